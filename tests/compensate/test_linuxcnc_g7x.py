"""LinuxCNC's own lathe-cycle tests (``tests/interp/g71-*`` and ``g72-*``, kept
in tests/conformance/linuxcnc/g7x with their licence): each program read as
its ``test.sh`` runs ``rs274 -g`` and compensated in the ``linuxcnc`` style
gives the STRAIGHT_TRAVERSE, STRAIGHT_FEED and ARC_FEED calls of LinuxCNC's
``expected`` canon, move for move within 5e-5, in well under LinuxCNC's 10 s
timeout (these tests once looped for ever in LinuxCNC).

Two of them set feed per revolution with constant surface speed (``G95``,
``G96 S D``: the feed does not change the moves), and one of those
compensates with ``G42`` and no tool loaded (LinuxCNC's tool 0, diameter 0).
"""
from __future__ import annotations

import re
import time

import pytest

from ccopt.compensate import compensate
from ccopt.program.gcode import read_gcode
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

G7X = CONFORMANCE / "g7x"
AS_IS = ["g71-endless-loop", "g71-with-g70", "g72-facing", "g72-missing-iteration",
         "g71-endless-loop2", "g71-endless-loop_2"]


def _program(test: str):
    folder = G7X / test
    script = (folder / "test.sh").read_text()
    path = folder / re.search(r"-g\s+(\S+\.ngc)", script).group(1)
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    return path


def _check(text: str, path, test: str) -> None:
    started = time.perf_counter()
    got = canonical_moves(compensate(read_gcode(text, str(path)), style="linuxcnc"))
    assert time.perf_counter() - started < 2.0
    want = expected_moves(f"g7x/{test}")
    assert [k for k, _ in got] == [k for k, _ in want]
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        fields = (0, 1, 2, 3, 5) if kind == "ARC_FEED" else range(3)
        assert all(abs(a[q] - b[q]) <= TOL for q in fields), (i, kind, a, b)
        if kind == "ARC_FEED":
            assert int(a[4]) == int(b[4]), (i, a, b)


@pytest.mark.parametrize("test", AS_IS)
def test_lathe_cycle_program_matches_linuxcnc_move_for_move(test):
    path = _program(test)
    _check(path.read_text(), path, test)
