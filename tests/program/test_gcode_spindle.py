"""Feed per revolution (G95) and constant surface speed (G96/G97), as LinuxCNC
runs them (ccopt.program.gcode.spindle): feeds worked out by hand from
rpm = 1000 v / (2 pi r) (G21, v in m/min; 12 v / (2 pi r) under G20), capped
at D, and feed = F * rpm / 60 per second."""
from __future__ import annotations

import math

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode


def blocks(text: str):
    prog = read_gcode("G18 G21\n" + text, "s.ngc")
    return prog.blocks, prog.meta.get("notes", [])


def test_g95_with_a_constant_spindle_speed():
    b, notes = blocks("G97 S500 M3\nG95 F0.2\nG0 X10 Z0\nG1 Z-10\nM2\n")
    assert b[-1].feed == pytest.approx(0.2 * 500 / 60) and notes == []


def test_g96_turning_at_one_radius_is_exact():
    # v = 100 m/min at r = 20 mm: 1000 * 100 / (2 pi 20) = 795.8 rev/min (< D2000)
    b, notes = blocks("G96 S100 D2000 M3\nG95 F0.1\nG0 X20 Z0\nG1 Z-30\nM2\n")
    rpm = 1000 * 100 / (2 * math.pi * 20)
    assert b[-1].feed == pytest.approx(0.1 * rpm / 60) and notes == []


def test_g96_facing_takes_the_largest_radius_and_says_its_time_is_a_bound():
    # facing from r = 20 to r = 2: the slowest spindle speed is at r = 20
    b, notes = blocks("G96 S100 D2000 M3\nG95 F0.1\nG0 X20 Z0\nG1 X2\nG1 X0\nM2\n")
    assert b[-2].feed == pytest.approx(0.1 * 1000 * 100 / (2 * math.pi * 20) / 60)
    # from r = 2 to 0: 1000 * 100 / (2 pi 2) = 7958 rev/min, capped at D2000
    assert b[-1].feed == pytest.approx(0.1 * 2000 / 60)
    assert len(notes) == 1 and notes[0].startswith("s.ngc:5: G96 (constant surface speed)")


def test_g96_in_inches_and_g97_back_to_rpm():
    # G20: v = 300 ft/min at r = 1 in: 12 * 300 / (2 pi) = 573.0 rev/min
    b = read_gcode("G18 G20 G96 S300 M3\nG95 F0.01\nG0 X1 Z0\nG1 Z-1\nG97 S400\nG1 Z-2\nM2\n",
                   "s.ngc").blocks
    assert b[1].feed == pytest.approx(0.01 * 12 * 300 / (2 * math.pi) / 60)   # inch/s
    assert b[2].feed == pytest.approx(0.01 * 400 / 60)


def test_a_thread_under_g96_is_synchronised_at_its_radius():
    b, _ = blocks("G96 S100 D3000 M3\nG0 X10 Z2\nG33 Z-20 K1.5\nM2\n")
    assert b[-1].feed == pytest.approx(1.5 * 1000 * 100 / (2 * math.pi * 10) / 60)


@pytest.mark.parametrize("text, line, message", [
    ("G96 S100 M3\nG95 F0.1\nG0 X0 Z0\nG1 Z-5\n", 5, "G96 (constant surface speed) at X0 without D"),
    ("S500 M5\nG95 F0.1\nG0 X5 Z0\nG1 Z-5\n", 5, "feed per spindle revolution with the spindle "
                                                 "not turning"),
    ("G1 X1 D5 F60\n", 2, "D word with no G41"),
])
def test_refusals_are_located(text, line, message):
    with pytest.raises(ProgramError) as err:
        blocks(text)
    assert message in str(err.value) and err.value.line == line


def test_a_facing_move_across_the_axis_is_noted_as_a_bound():
    # X50 to X-50 passes radius 0: the speed varies along it (found by generation)
    _, notes = blocks("G96 S100 D2000 M3\nG95 F0.1\nG0 X50 Z0\nG1 X-50\nM2\n")
    assert len(notes) == 1 and notes[0].startswith("s.ngc:5: G96")
