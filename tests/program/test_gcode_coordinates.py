"""Coordinate systems in the G-code reader, as LinuxCNC's interpreter applies
them (interp_convert.cc: convert_coordinate_system, convert_setup,
convert_axis_offsets; LinuxCNC's G-code reference for G10 L2/L20, G52, G53,
G54-G59.3, G92-G92.3): blocks hold machine coordinates,
machine = programmed + active origin + axis offset."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program import read_program
from ccopt.program.gcode import read_gcode
from ccopt.program.gcode.coordinates import read_var_file


def ends(text, **kw):
    return [b.end for b in read_gcode("G21 F600\n" + text, **kw).blocks]


def test_g92_example_of_the_interpreter():
    # "if the current point is at X=4 ... and the current X-axis offset is
    # zero, then G92 X7 causes the X-axis offset to be reset to -3": X7 is
    # then machine 4, and X10 is machine 7.
    assert ends("G0 X4\nG92 X7\nG1 X10\n") == [(4.0, 0.0, 0.0), (7.0, 0.0, 0.0)]


def test_g92_1_2_3():
    text = ("G0 X10 Y10\nG92 X0 Y0\nG1 X5\n"   # offset (10, 10): machine (15, 10)
            "G92.2\nG1 X5\n"                   # offset suspended: machine X5
            "G92.3\nG1 Y1\n"                   # restored from #5211/#5212: Y 1 + 10
            "G92.1\nG1 X1\nG92.3\nG1 X2\n")    # cleared with its parameters: stays 0
    assert ends(text) == [(10, 10, 0), (15, 10, 0), (5, 10, 0), (5, 11, 0), (1, 11, 0),
                          (2, 11, 0)]


def test_g92_writes_its_parameters():
    prog = read_gcode("G21 G0 X10 Y-2\nG92 X1 Y1\n#1 = #5211\n#2 = #5212\n#3 = #5210\n"
                      "G1 X[#1] Y[#2] Z[#3] F100\n")
    # offset = current - value: (9, -3); #5210 = 1 while applied
    assert prog.blocks[-1].end == pytest.approx((9 + 9, -3 - 3, 1))


def test_g52_is_a_local_origin():
    assert ends("G0 X3\nG52 X10\nG0 X1 Y1\nG52 X0\nG0 X1\n") == [
        (3, 0, 0), (11, 1, 0), (1, 1, 0)]


def test_g10_l2_and_g55():
    # G54 X1 Y2 leaves Z where it is: machine -2
    assert ends("G10 L2 P2 X100 Y50 Z-5\nG55 G0 X1 Y2 Z3\nG54 X1 Y2\n") == [
        (101, 52, -2), (1, 2, -2)]


def test_g10_l20_makes_the_current_point_the_given_value():
    # at machine (1, 2): G54's origin becomes (1 - 0.5, 2 + 1) so that the
    # point reads (0.5, -1); X1 Y1 is then machine (1.5, 4)
    assert ends("G0 X1 Y2\nG10 L20 P1 X0.5 Y-1\nG0 X1 Y1\n") == [(1, 2, 0), (1.5, 4, 0)]


def test_g10_p0_is_the_active_system_and_g53_is_machine():
    assert ends("G56\nG10 L2 P0 X7\nG0 X1\nG53 G0 X1\nG0 X2\n") == [
        (8, 0, 0), (1, 0, 0), (9, 0, 0)]


def test_absolute_arc_centre_is_in_work_coordinates():
    # G92 shifts X by 10: the arc from machine (10, 0) about work (5, 0),
    # machine (15, 0), to work (10, 0), machine (20, 0)
    prog = read_gcode("G21 F600 G0 X10\nG92 X0\nG90.1 G2 X10 Y0 I5 J0\n")
    arc = prog.blocks[-1]
    assert arc.end == (20, 0, 0) and arc.center[:2] == pytest.approx((15, 0))


def test_parameters_at_start_select_and_place_the_origins(tmp_path):
    var = tmp_path / "linuxcnc.var"
    var.write_text("5220\t2.000000\n5241\t7.000000\n5242\t-1.000000\n\n5211 0.5\n5210 1\n")
    params = read_var_file(var)
    assert params == {5220: 2.0, 5241: 7.0, 5242: -1.0, 5211: 0.5, 5210: 1.0}
    # G55 active at start (#5220 = 2) with origin (7, -1) and the G92 offset X 0.5
    assert ends("G0 X0 Y0\n", parameters=params) == [(7.5, -1, 0)]
    prog_file = tmp_path / "p.ngc"
    prog_file.write_text("G21 G0 X1 Y1\n")
    assert read_program(prog_file, var_file=var).blocks[0].end == (8.5, 0, 0)


@pytest.mark.parametrize("text, message", [
    ("G41.1 D2 G1 X1\nG55 X2\n", "cannot change coordinate systems with cutter radius"),
    ("G41.1 D2 G1 X1\nG92 X0\n", "cannot change axis offsets with cutter radius"),
    ("G41.1 D2 G1 X1\nG52 X0\n", "cannot change axis offsets with cutter radius"),
    ("G41.1 D2 G1 X1\nG10 L2 P1 X3\n", "cannot change the active coordinate system"),
    ("G41.1 D2 G1 X1\nG53 G1 X3\n", "G53 cannot be used with cutter radius compensation"),
    ("G10 L1 P1 R1\n", "Requested tool 1 not found in the tool table"),
    ("G10 L3 P1 X1\n", "ccopt reads G10 L1, L10 and L11"),
    ("G10 L2 X1\n", "needs P"),
    ("G10 L2 P10 X1\n", "P must be 0 to 9"),
    ("G10 L20 P1 R30 X1\n", "R not allowed in G10 L20"),
    ("G1 G92 X1\n", "both use the axis words"),
    ("G53 G2 X1 I1\n", "G53 needs G0 or G1"),
    ("G91 G53 G0 X1\n", "G53 is absolute"),
    ("G1 X1 L2\n", "L word with no G10"),
    ("G76 X1\n", "P word missing with G76"),
])
def test_refusals_are_located(text, message):
    with pytest.raises(ProgramError) as err:
        read_gcode("G21 F600\n" + text, "p.ngc")
    assert message in str(err.value)
    assert err.value.line == 1 + text.count("\n")


def test_g41_survives_an_offset_set_before_it():
    # offsets set with compensation off, then compensation in the new frame
    prog = read_gcode("G21 F600\nG0 X5 Y5\nG92 X0 Y0\nG41.1 D2 G1 X10\nG40 G1 X20\n")
    assert [b.end[:2] for b in prog.blocks] == [(5, 5), (15, 5), (25, 5)]
    assert prog.blocks[1].modal.side == 1


@pytest.mark.parametrize("line, where", [("5221 abc\n", 1), ("\n9999 1\n", 2)])
def test_var_file_errors_are_located(tmp_path, line, where):
    var = tmp_path / "bad.var"
    var.write_text(line)
    with pytest.raises(ProgramError) as err:
        read_var_file(var)
    assert err.value.line == where and err.value.file == str(var)


def test_var_file_on_the_command_line(tmp_path, capsys):
    from ccopt.cli import main
    (tmp_path / "p.ngc").write_text("G21 F600\nG0 X0 Y0\nG41.1 D2 G1 X10\nG40 G1 X20\n")
    (tmp_path / "linuxcnc.var").write_text("5220 2\n5241 10\n")   # G55 at X 10
    code = main(["show", str(tmp_path / "p.ngc"), "--var-file", str(tmp_path / "linuxcnc.var"),
                 "--json"])
    import json
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    assert [s["end"] for s in doc["segments"]] == [[10, 0], [20, 0], [30, 0]]
    assert main(["show", str(tmp_path / "p.ngc"), "--var-file", str(tmp_path / "no.var")]) == 2
    assert capsys.readouterr().err.startswith(f"{tmp_path / 'no.var'}: cannot read")
