"""Lathe cycles G70-G72 (ccopt.program.gcode.lathe_cycles): the moves of a
shoulder turned from stock, worked out by hand from what the cycles do (not
taken from ccopt's output), and the located refusals.

The contour ``o100`` is a shoulder: from the start point straight in to X4,
along Z to Z-10, up the face to X10 (radius, mm). Roughing from X10 Z1 with
depth of cut I2 cuts along Z at X10, 8 and 6 (LinuxCNC starts at the stock's
own X), each feed ending on the face at Z-10, then retracts by R0.5 along both
axes, rapids back to Z1 - 0.5 and onto the start of the pass; the last pass
follows the contour at X4 and up the face. Moves are ``(kind, x, z)`` with
kind ``R`` rapid, ``F`` feed.
"""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion

SHOULDER = "o100 sub\nG1 X4\nZ-10\nX10\no100 endsub\n"
_KIND = {Motion.RAPID: "R", Motion.LINE: "F"}


def read(text: str):
    return read_gcode("G18 G21 F100\n" + text, "p.ngc")


def moves(text: str) -> list[tuple]:
    """The cycle's blocks (after the program's first rapid) as (kind, x, z)."""
    prog = read(text)
    return [(_KIND[b.motion], round(b.end[0], 9), round(b.end[2], 9)) for b in prog.blocks[1:]]


def _pass(x: float, z0: float, z1: float, r: float = 0.5) -> list[tuple]:
    """One roughing pass at X ``x`` from Z ``z0`` to the face at ``z1``."""
    return [("R", x, z0), ("F", x, z1), ("R", x + r, z1 + r), ("R", x + r, z0 - r),
            ("R", x, z0)]


def test_g71_roughs_a_shoulder_in_passes_of_i():
    got = moves("G0 X20 Z5\n" + SHOULDER + "G71 Q100 X10 Z1 I2 R0.5\n")
    want = [("R", 10, 1), ("R", 10, 1)]           # to X Z, then to the contour's start
    for x in (10, 8, 6):
        want += _pass(x, 1, -10)
    want += [("R", 4, 1), ("F", 4, -10), ("F", 10, -10)]
    assert got == want


def test_g71_u_w_shift_the_contour_and_its_start():
    got = moves("G0 X20 Z5\n" + SHOULDER + "G71 Q100 X10 Z1 I2 R0.5 U0.5 W0.2\n")
    want = [("R", 10, 1), ("R", 10.5, 1.2)]
    for x in (10.5, 8.5, 6.5):
        want += _pass(x, 1.2, -9.8)
    want += [("R", 4.5, 1.2), ("F", 4.5, -9.8), ("F", 10.5, -9.8)]
    assert got == want


def test_g71_in_diameter_mode_halves_x_of_the_line_and_the_contour():
    text = "G7 G0 X40 Z5\no100 sub\nG1 X8\nZ-10\nX20\no100 endsub\nG71 Q100 X20 Z1 I2 R0.5\n"
    assert moves(text) == moves("G0 X20 Z5\n" + SHOULDER + "G71 Q100 X10 Z1 I2 R0.5\n")


def test_g70_passes_from_d_to_e_off_the_contour():
    # P2 D1 E0: a pass 0.5 off (X4.5, face at Z-9.5), then one on the contour;
    # each starts with a rapid to X Z and one to the contour's first point
    got = moves("G0 X20 Z5\n" + SHOULDER + "G70 Q100 X10 Z1 P2 D1\n")
    assert got == [("R", 10, 1),
                   ("R", 10, 1), ("R", 4.5, 1), ("F", 4.5, -9.5), ("F", 10, -9.5),
                   ("R", 10, 1), ("R", 4, 1), ("F", 4, -10), ("F", 10, -10)]


def test_the_cycles_moves_are_marked_and_leave_the_last_moves_mode():
    prog = read("G0 X20 Z5\n" + SHOULDER + "G71.1 Q100 X10 Z1 I2 M8\nX12\n")
    cycle = [b for b in prog.blocks if b.cycle is not None]
    assert {b.cycle for b in cycle} == {"G71.1"}
    assert {b.source.line for b in cycle} == {8}
    assert cycle[0].mcodes == (8,) and all(b.mcodes == () for b in cycle[1:])
    last = prog.blocks[-1]          # X12: a G1 (the cycle's last move), not a G71
    assert (last.cycle, last.motion, last.end[0], last.end[2]) == (None, Motion.LINE, 12, -10)


def test_o_word_keywords_may_hold_blanks():
    text = "G0 X20 Z5\n" + SHOULDER.replace("endsub", "end sub") + "G71 Q100 X10 Z1 I2\n"
    assert moves(text) == moves("G0 X20 Z5\n" + SHOULDER + "G71 Q100 X10 Z1 I2\n")


ERRORS = [
    # (program after "G18 G21 F100", line, column, words of the message)
    ("G71 X10 Z1\n", 2, 1, "G71 requires a Q word"),
    ("G0 X20 Z5\nG71 Q5 X10 Z1\n", 3, 5, "G71 Q5: o5 call: no subroutine o5"),
    ("G17\n" + SHOULDER + "G71 Q100 X10 Z1\n", 8, 1, "can only be used in XZ plane (G18)"),
    ("G41.1 D1\n" + SHOULDER + "G72 Q100 X10 Z1\n", 8, 1,
     "G72 cannot be used with cutter compensation enabled"),
    (SHOULDER + "G71 Q100 X10 Z1 P2\n", 7, 17, "P word with no"),
    (SHOULDER + "G70 Q100 X10 Z1 I1\n", 7, 17, "I word with no"),
    (SHOULDER + "G71 Q100 X10 Z1 K1\n", 7, 17, "K word with no"),
    (SHOULDER + "G71 Q100 X10 Y1 Z1\n", 7, 14, "Y word with G71"),
    (SHOULDER + "G71 Q100 X10 Z1 I0\n", 7, 17, "I must be greater than zero"),
    (SHOULDER + "G70 Q100 X10 Z1 P0\n", 7, 17, "P is the number of finishing passes"),
    (SHOULDER + "G71 Q1.5 X10 Z1\n", 7, 5, "Q is the number of the contour's subroutine"),
    ("o100 sub\nG1 X4 U1\nZ-10\no100 endsub\nG71 Q100 X10 Z1\n", 3, 7,
     "Cannot use U and X in the same block (in subroutine o100 called from line 6)"),
    ("o100 sub\nG2 X4 Z-2\no100 endsub\nG71 Q100 X10 Z1\n", 3, 1,
     "either I or K must be present for arc"),
    ("o100 sub\nG1 X4\nG92 Z-10\no100 endsub\nG71 Q100 X10 Z1\n", 4, 1,
     "G92 in a lathe cycle's contour"),
    ("o100 sub\nG1 X4\nZ-10\nZ-5\nX10\no100 endsub\nG71 Q100 X10 Z1\n", 8, 1,
     "G7X error: Not monotonic"),
    ("G93\n" + SHOULDER + "G71 Q100 X10 Z1 F1\n", 8, 1, "inverse time feed (G93)"),
]


@pytest.mark.parametrize("text, line, col, words", ERRORS,
                         ids=[f"{e[3]}@{i}" for i, e in enumerate(ERRORS)])
def test_error_is_located(text, line, col, words):
    with pytest.raises(ProgramError) as info:
        read(text)
    assert words in info.value.message
    assert (info.value.line, info.value.col) == (line, col)


def test_a_contour_that_loops_for_ever_stops_at_the_loop_guard():
    text = ("o100 sub\nG1 X4\no101 while [1]\no101 endwhile\no100 endsub\n"
            "G71 Q100 X10 Z1\n")
    with pytest.raises(ProgramError, match="loop"):
        read(text)


def test_a_cycle_of_too_many_moves_is_refused(monkeypatch):
    import ccopt.program.gcode.lathe_cycles as lathe_cycles
    monkeypatch.setattr(lathe_cycles, "MAX_CYCLE_MOVES", 50)
    with pytest.raises(ProgramError, match="G71 makes more than 50 moves") as info:
        read("G0 X20 Z5\n" + SHOULDER + "G71 Q100 X10 Z1 I0.1\n")
    assert (info.value.line, info.value.col) == (8, 1)


def test_g91_contour_moves_are_increments():
    contour = "o100 sub\nG1 X-6\nZ-11\nX6\no100 endsub\n"
    text = "G0 X20 Z5\n" + contour + "G0 X10 Z1\nG91 G71 Q100 I2 R0.5\n"
    absolute = moves("G0 X20 Z5\n" + SHOULDER + "G0 X10 Z1\nG71 Q100 I2 R0.5\n")
    assert moves(text) == absolute


def test_g91_x_on_the_cycles_line_is_refused():
    with pytest.raises(ProgramError, match="under G91") as info:
        read(SHOULDER + "G91 G71 Q100 X-2 Z0\n")
    assert (info.value.line, info.value.col) == (7, 14)
