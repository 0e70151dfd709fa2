#!/bin/bash -e
rs274 -g test.ngc
