#!/bin/bash -e
rs274 -g test-named.ngc
rs274 -g test-numbered.ngc
