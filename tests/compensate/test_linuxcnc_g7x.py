"""LinuxCNC's own lathe-cycle tests (``tests/interp/g71-*`` and ``g72-*``, kept
in tests/conformance/linuxcnc/g7x with their licence): each program read as
its ``test.sh`` runs ``rs274 -g`` and compensated in the ``linuxcnc`` style
gives the STRAIGHT_TRAVERSE, STRAIGHT_FEED and ARC_FEED calls of LinuxCNC's
``expected`` canon, move for move within 5e-5, in well under LinuxCNC's 10 s
timeout (these tests once looped for ever in LinuxCNC).

Two of them set feed per revolution with constant surface speed (``G95``,
``G96 S D``), which ccopt does not read: their originals are refused at that
line, and their cycles are checked with those lines written as feed per
minute (the cycles' geometry does not depend on the feed mode). One of
those also compensates with ``G42`` and no tool loaded, LinuxCNC's tool 0 of
diameter 0; it is written ``G42.1 D0`` (the same zero radius).
"""
from __future__ import annotations

import re
import time

import pytest

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

G7X = CONFORMANCE / "g7x"
AS_IS = ["g71-endless-loop", "g71-with-g70", "g72-facing", "g72-missing-iteration"]
#: test -> (the line ccopt refuses, its column, [(original text, rewritten)]).
REWRITTEN = {
    "g71-endless-loop2": (1, 4, [("G18G95", "G18G94"), ("G96 M3 S250 D700", "M3 S250"),
                                 ("F.24", "F240")]),
    "g71-endless-loop_2": (27, 4, [("M3 G96 S200 d1400", "M3 S200"),
                                   ("G95 F0.12", "G94 F120"), ("\ng42\n", "\ng42.1 D0\n")]),
}


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


@pytest.mark.parametrize("test", sorted(REWRITTEN))
def test_feed_per_revolution_program_is_refused_where_it_sets_it(test):
    path = _program(test)
    line, col, _ = REWRITTEN[test]
    with pytest.raises(ProgramError) as info:
        read_gcode(path.read_text(), str(path))
    assert (info.value.line, info.value.col) == (line, col)
    assert re.search(r"G9[56]", info.value.message)


@pytest.mark.parametrize("test", sorted(REWRITTEN))
def test_feed_per_revolution_program_cycles_match_with_feed_per_minute(test):
    path = _program(test)
    text = path.read_text()
    for old, new in REWRITTEN[test][2]:
        assert old in text
        text = text.replace(old, new)
    _check(text, path, test)
