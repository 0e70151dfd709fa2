"""Units that change in the middle of a program: every length converted to one
output unit (the first G20/G21, or ``units=``), as LinuxCNC rescales its state
in ``convert_length_units``; tool tables in their own units. 1 in = 25.4 mm."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode

IN = 25.4


def test_mixed_units_in_the_first_unit():
    prog = read_gcode("G21 F600\nG1 X10\nG20\nG1 X1 F60\nG2 X2 I0.5\nG41.1 D0.1 G1 Y1\n"
                      "G40 G21 G1 X0\n")
    assert prog.units == "mm"
    b = prog.blocks
    assert b[0].end == (10, 0, 0) and b[0].feed == pytest.approx(600 / 60)
    # F60 in/min = 25.4 mm/s; X1 in = 25.4 mm
    assert b[1].end == pytest.approx((IN, 0, 0)) and b[1].feed == pytest.approx(IN)
    # arc about X 1.5 in to X 2 in
    assert b[2].end == pytest.approx((2 * IN, 0, 0))
    assert b[2].center == pytest.approx((1.5 * IN, 0, 0))
    # G41.1 D0.1 in: radius 0.05 in
    assert b[3].modal.radius == pytest.approx(0.05 * IN)
    # back in mm: X0 is 0 mm, Y stays at 1 in
    assert b[4].end == pytest.approx((0, IN, 0))
    assert all(m.modal.units == "mm" for m in b)


def test_output_unit_chosen_by_the_caller():
    prog = read_gcode("G20 F60\nG1 X1 Y-0.5\n", units="mm")
    assert prog.units == "mm"
    assert prog.blocks[0].end == pytest.approx((IN, -IN / 2, 0))
    assert prog.blocks[0].feed == pytest.approx(IN)   # 60 in/min
    prog = read_gcode("G21 F600\nG1 X25.4\n", units="inch")
    assert prog.units == "inch" and prog.blocks[0].end == pytest.approx((1, 0, 0))
    assert prog.blocks[0].feed == pytest.approx(10 / IN)


def test_feed_set_on_the_line_of_a_later_change_keeps_its_speed():
    # RS274NGC sets F before the units (LinuxCNC keeps the canonical feed's
    # speed across the change): F60 here is still mm/min, 1 mm/s
    prog = read_gcode("G21 F600\nG1 X1\nG20 F60 X1\n")
    assert prog.blocks[1].end == pytest.approx((IN, 0, 0))
    assert prog.blocks[1].feed == pytest.approx(1.0)


def test_offsets_and_tool_tables_in_their_units():
    # G92 in inches, then millimetres: the offset is one physical length
    prog = read_gcode("G20 G0 X1\nG92 X0\nG21 G0 X10\n")
    assert prog.blocks[-1].end == pytest.approx((1 + 10 / IN, 0, 0))
    # a table of inches read for a mm program: D0.25 in is r 3.175 mm
    prog = read_gcode("G21 F600\nG41 D1 G1 X10\n", tool_table={1: 0.25}, table_units="inch")
    assert prog.blocks[0].modal.radius == pytest.approx(0.125 * IN)
    # by default the table is in the program's unit
    prog = read_gcode("G21 F600\nG41 D1 G1 X10\n", tool_table={1: 0.25})
    assert prog.blocks[0].modal.radius == pytest.approx(0.125)


def test_bad_unit_names_are_refused():
    with pytest.raises(ProgramError, match="units must be one of mm, inch"):
        read_gcode("G1 X1 F1", units="cm")
