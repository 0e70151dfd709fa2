"""G7 (lathe diameter mode) and G8 (radius mode), as LinuxCNC's interpreter
applies them: ``read_x`` halves every X word read while diameter mode is on,
and ``convert_lathe_diameter_mode`` halves (G7) or doubles back (G8) the X
of the line that switches; I, K and R are never scaled (interp_read.cc,
interp_convert.cc). Blocks hold radii (machine X), so a G7 program equals
the G8 program whose X words are half as large."""
from __future__ import annotations

import math

import pytest

from ccopt.compensate import compensate
from ccopt.export import export
from ccopt.program.gcode import read_gcode


def ends(text: str) -> list[tuple[float, float, float]]:
    return [b.end for b in read_gcode("G18 G21 F600\n" + text).blocks]


def test_x_words_are_diameters_in_g7_and_radii_after_g8():
    # X20 in G7 is radius 10; the G8 on the third line applies to its own X
    assert ends("G7 G1 X20 Z-1\nG1 X30\nG8 G1 X30\nG1 X8\n") == [
        (10.0, 0.0, -1.0), (15.0, 0.0, -1.0), (30.0, 0.0, -1.0), (8.0, 0.0, -1.0)]


def test_g7_on_a_line_halves_that_lines_x():
    assert ends("G1 X4 Z0\nG1 G7 X4\n") == [(4.0, 0.0, 0.0), (2.0, 0.0, 0.0)]


def test_incremental_x_is_a_diameter_change_too():
    # from radius 10, G91 X4 in G7 moves the radius by 2
    assert ends("G7 G1 X20 Z0\nG91 G1 X4\n") == [(10.0, 0.0, 0.0), (12.0, 0.0, 0.0)]


def test_arc_offsets_stay_radii():
    # start radius 10 on Z0; centre offset I-10 (not halved) puts the centre on
    # the axis, so the end X0 Z10 is at distance 10 from it as well: a valid
    # quarter arc. Halving I would put the centre at X5 and make the ends'
    # distances 5 and sqrt(125): LinuxCNC would refuse it.
    prog = read_gcode("G18 G21 F600\nG7 G0 X20 Z0\nG2 X0 Z10 I-10 K0\n")
    arc = prog.blocks[-1]
    assert arc.center[0] == pytest.approx(0.0) and arc.center[2] == pytest.approx(0.0)
    assert math.dist((arc.end[0], arc.end[2]), (0.0, 0.0)) == pytest.approx(10.0)


def test_offsets_and_g92_values_are_diameters():
    # G10 L2 P1 X20 sets the G54 X origin at radius 10; G92 X4 in G7 makes the
    # current radius (machine 10 + 0) read as 2: the axis offset is 8
    assert ends("G7\nG10 L2 P1 X20\nG0 X0 Z0\n") == [(10.0, 0.0, 0.0)]
    assert ends("G7 G0 X20 Z0\nG92 X4\nG1 X8\n") == [(10.0, 0.0, 0.0), (12.0, 0.0, 0.0)]


def test_a_compensated_g7_program_is_its_g8_program():
    # the same turning pass written in diameters (G7) and in radii (G8): the
    # compensated paths coincide segment by segment, the cutter radius (D) is
    # never halved
    diam = ("G18 G21 F600\nG7\nG0 X40 Z5\nG42.1 D2 G1 X40 Z0\nG1 Z-20\nG1 X60 Z-30\n"
            "G2 X80 Z-40 I0 K-10\nG40 G1 X90\n")
    rad = ("G18 G21 F600\nG8\nG0 X20 Z5\nG42.1 D2 G1 X20 Z0\nG1 Z-20\nG1 X30 Z-30\n"
           "G2 X40 Z-40 I0 K-10\nG40 G1 X45\n")
    a = compensate(read_gcode(diam), style="linuxcnc")
    b = compensate(read_gcode(rad), style="linuxcnc")
    assert len(a.segments) == len(b.segments)
    for sa, sb in zip(a.segments, b.segments):
        assert sa.geom.start == pytest.approx(sb.geom.start)
        assert sa.geom.end == pytest.approx(sb.geom.end)
    assert a.radius == pytest.approx(1.0)


def test_export_of_a_g7_program_says_g8(tmp_path):
    # the exported X words are radii; G8 on the mode line makes a lathe read
    # them as such (the read-back reads the file as written)
    text = ("G18 G21 F600\nG7\nG0 X40 Z5\nG42.1 D2 G1 X40 Z0\nG1 Z-20\nG40 G1 X50\n")
    prog = read_gcode(text)
    path = compensate(prog, style="linuxcnc")
    res = export(path, tmp_path / "turn.nc", program=prog)
    written = (tmp_path / "turn.nc").read_text().splitlines()
    assert "G21 G18 G90 G94 G8" in written
    assert res.verified
    # the face pass at radius 20 (X40 in G7) plus the cutter radius 1 on the
    # right of travel -Z in G18 (outside): X21 in radius
    assert any(line.startswith("G1") and "X21 " in line + " " for line in written)
