"""The LinuxCNC interpreter-test harness (bench/linuxcnc_interp.py) reads the
shell idioms of LinuxCNC's ``tests/interp/*/test.sh`` scripts as rs274 would
run them. The scripts below are LinuxCNC's (commit 5c41560ebb, GPL-2.0, as
tests/conformance/linuxcnc/README.md says), shortened."""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

from linuxcnc_interp import Run, _segments, _text_lines, plain_runs  # noqa: E402

TIMEOUT = """#!/bin/bash
rs274 -g g72-iterations-present.ngc | awk '{$1=""; print}' > result &
pid=$!

# Give it 10 seconds to complete
count=10
while [ 0 -lt $count ] && kill -0 $pid > /dev/null 2>&1 ; do
    sleep 1
    count=$((count - 1))
done

if kill -0 $pid > /dev/null 2>&1; then
    kill -9 $pid
    echo "E: g71-iterations-present.ngc program seem to be stuck, killing"
    exit 1
fi

exit 0
"""

FANUC = """#!/bin/bash

trim() { sed 's/^ *[0-9][0-9]* //'; }

echo "program: fanuc; INI: fanuc"
rs274 -g -i test-fanuc.ini test-fanuc.ngc 2>&1 | trim
echo "program: fanuc; INI: NO fanuc"
{ ! rs274 -g -i test-no-fanuc.ini test-fanuc.ngc 2>&1; } | trim || exit 1
"""

COPY = """cp g92_offsets.var.template g92_offsets.var
rs274 -g -v g92_offsets.var -i persistent_g92_offset_true.ini \\
    g92_offsets.ngc
rm -f g92_offsets.var g92_offsets.var.bak
"""

LOOP = """for t in $LEGAL_TESTS; do
    rs274 -g "test-legal-${t}.ngc" | awk '{$1=""; print}'
done
"""


def test_a_run_under_a_timeout_is_one_plain_run():
    assert plain_runs(TIMEOUT) == [Run("g72-iterations-present.ngc",
                                       first_field_dropped=True)]


def test_runs_that_must_fail_and_runs_that_must_not():
    assert plain_runs(FANUC) == [
        Run("test-fanuc.ngc", ini="test-fanuc.ini", errors_shown=True),
        Run("test-fanuc.ngc", ini="test-no-fanuc.ini", fails=True, errors_shown=True)]


def test_a_copied_file_is_read_under_its_first_name():
    assert plain_runs(COPY) == [Run("g92_offsets.ngc", ini="persistent_g92_offset_true.ini",
                                    var="g92_offsets.var.template")]


def test_loops_and_plug_ins_are_not_plain():
    assert plain_runs(LOOP) is None
    assert plain_runs("rs274 -p plug.py -g test.ngc\n") is None


def test_outputs_are_cut_per_run_and_printed_lines_kept():
    expected = ("program: a\nexecuting\nN..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n"
                "N..... STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                "G92 flag:  param 5210 == 2.000000\n"
                "N1234 SET_SPINDLE_SPEED(0, 600.0000)\n"
                "program: b\nexecuting\nN..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n"
                "DISABLE_FANUC_STYLE_SUB set in INI file, but found m98\nM98 P1 L3\n")
    first, second = _segments(expected, 2)
    assert "STRAIGHT_TRAVERSE" in first and "STRAIGHT_TRAVERSE" not in second
    echoes = {"program: a", "program: b"}
    assert _text_lines(first, echoes) == ["G92 flag:  param 5210 == 2.000000"]
    assert _text_lines(second, echoes) == [
        "DISABLE_FANUC_STYLE_SUB set in INI file, but found m98", "M98 P1 L3"]
    assert _segments(expected, 3) is None
