"""LinuxCNC's polar coordinates ``@`` (radius) and ``^`` (angle, degrees)
(ccopt.program.gcode.polar): points worked out with cos and sin here, from
``find_ends`` and ``CYCLE_MACRO``'s rules."""
from __future__ import annotations

import math

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion


def ends(text: str):
    prog = read_gcode("G21 G17 F60\n" + text, "p.ngc")
    return [tuple(round(c, 9) for c in b.end[:2]) for b in prog.blocks]


def _at(r, deg):
    return (round(r * math.cos(math.radians(deg)), 9), round(r * math.sin(math.radians(deg)), 9))


def test_absolute_polar_points_and_a_word_left_out_keeps_the_current_one():
    # @2 ^30; then ^90 keeps radius 2; then @5 keeps the angle 90
    assert ends("G0 @2 ^30\nG1 ^90\nG1 @5\n") == [_at(2, 30), _at(2, 90), _at(5, 90)]


def test_incremental_polar_grows_the_radius_and_turns_about_the_origin():
    # from (3, 0): @1 -> radius 4 on the same ray; ^90 -> (0, 4)
    assert ends("G0 X3 Y0\nG91 G1 @1\nG1 ^90\n") == [(3.0, 0.0), (4.0, 0.0), _at(4, 90)]


def test_a_g91_cycle_turns_at_every_repeat_a_bolt_circle():
    # LinuxCNC's hole-circle.ngc: six holes on radius 1.5, 60 degrees apart
    prog = read_gcode("G20 G17 G90\nG0 X1.5 Y0 Z0\nG91 G81 R.1 Z-.5 ^60 L6 F10\nM2\n", "h.ngc")
    holes = [tuple(round(c, 9) for c in b.end[:2]) for b in prog.blocks
             if b.motion is Motion.LINE]
    assert holes == [_at(1.5, 60 * k) for k in range(1, 7)]


@pytest.mark.parametrize("text, col, message", [
    ("G0 @1 X2", 7, "Cannot specify X or Y words with polar coordinate"),
    ("G0 @1", 4, "Must specify angle in polar coordinate if at the origin"),
    ("G91 G0 ^10", 8, "G91 motion with polar coordinates is indeterminate when at the origin"),
    ("G53 G0 @1 ^2", 8, "Cannot use polar coordinates with G53"),
])
def test_refusals_are_linuxcncs_and_located(text, col, message):
    with pytest.raises(ProgramError) as err:
        read_gcode("G21 F60\n" + text + "\n", "p.ngc")
    assert message in str(err.value) and err.value.col == col
