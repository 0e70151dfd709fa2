"""Exports a machine can run (issue 31): a plate program with G55, T1 M6,
S8000 M3, coolant, a G42 contour, G81 drill patterns (G98, and G91 with L3)
and M30 reads, verifies, times and exports; the export keeps the machine's
words in order, G55, the work coordinates and M30, and reads back to the
same motion. Expected words and coordinates are written out by hand."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.program.model import PROGRAM_END, TRAILING_WORDS
from cli_run import run_cli

PLATE = """%
O1234
G21 G17 G90 G94
G55
T1 M6
S8000 M3
M8
G0 X-10 Y-10 Z5
G1 Z-2 F300
G42 D1 G1 X0 Y0 F600
G1 X80
G1 Y50
G1 X0
G1 Y0
G40 G1 X-10 Y-10
G0 Z5
G98 G81 X20 Y15 Z-8 R2 F200
X40
G80
G91 G99 G81 X10 Y10 Z-6 R-3 L3
G90 G80
G0 Z20
M9
M5
M30
%
"""
#: G55's origin in the parameter file: machine = work + (100, 50, -20).
VAR = "5241 100\n5242 50\n5243 -20\n5220 1\n"


@pytest.fixture
def plate(tmp_path):
    (tmp_path / "plate.ngc").write_text(PLATE)
    (tmp_path / "tools.tbl").write_text("T1 P1 D6 ;\n")
    (tmp_path / "p.var").write_text(VAR)
    return tmp_path


def _read(d, name="plate.ngc"):
    return ccopt.read_program(d / name, tool_table=d / "tools.tbl", var_file=d / "p.var")


def _words(prog):
    return [w for b in prog.blocks for w in b.words] + list(prog.meta[TRAILING_WORDS])


def test_the_reader_records_words_frames_and_the_end(plate):
    prog = _read(plate)
    assert _words(prog) == ["T1 M6", "S8000 M3", "M8", "M9", "M5"]
    assert prog.meta[PROGRAM_END] == "M30"
    assert {b.frame.system for b in prog.blocks} == {2}
    assert prog.blocks[0].end == (90.0, 40.0, -15.0)   # work (-10, -10, 5) in G55


def test_plate_verifies_times_and_exports_keeping_what_the_machine_needs(plate):
    prog = _read(plate)
    path = ccopt.compensate(prog, style="linuxcnc")
    cert = ccopt.verify(path, prog)
    assert cert.ok
    prof = ccopt.plan_feed(path, ccopt.AxisLimits(v=[100, 100, 50], a=[1000, 1000, 500]))
    assert prof.duration > 0
    res = ccopt.export(path, plate / "out.nc", program=prog)
    assert res.verified and res.roundtrip_error < 1e-5
    lines = [ln for ln in (plate / "out.nc").read_text().splitlines()
             if not ln.startswith("(")]
    assert lines[:7] == ["%", "O1234", "G21 G17 G90 G94", "T1 M6", "S8000 M3", "M8", "G55"]
    assert lines[-4:] == ["M9", "M5", "M30", "%"]
    assert "M2" not in lines
    # work coordinates as programmed: the first rapid, the first hole (R2, Z-8)
    assert lines[7] == "G0 X-10 Y-10 Z5"
    assert "G1 X20 Y15 Z-8 F200" in lines
    # the G91 L3 holes: R 3 below the initial level Z5, bottom 6 below R
    for k in (1, 2, 3):
        assert f"G1 X{40 + 10 * k} Y{15 + 10 * k} Z-4" in lines


def test_export_reads_back_to_the_same_moves_and_words_in_order(plate):
    prog = _read(plate)
    path = ccopt.compensate(prog, style="linuxcnc")
    ccopt.export(path, plate / "out.nc", program=prog)
    back = _read(plate, "out.nc")
    assert _words(back) == _words(prog)
    assert back.meta[PROGRAM_END] == "M30"
    assert back.meta.get("program_number") == 1234
    moves = [s for s in path.segments]
    got = [b for b in back.blocks if b.motion.is_move]
    assert len(got) == len(moves)
    for seg, b in zip(moves, got):
        assert math.dist(seg.end_xyz, b.end) < 1e-6
        assert (seg.feed is None) == (b.feed is None)
    assert {b.frame.system for b in back.blocks} == {2}


def test_offsets_the_program_sets_and_g53_are_written(tmp_path):
    # G10 L2 sets G54 to X5 (the parameters say 0); G92 makes the current
    # point X0 (offset X1 more); a G53 rapid stays in machine coordinates
    text = ("G21 F600\nG10 L2 P1 X5\nG0 X1 Y0 Z0\nG92 X0\nG1 X2\nG92.1\n"
            "G53 G0 X0 Y0 Z10\nM2\n")
    (tmp_path / "p.ngc").write_text(text)
    prog = ccopt.read_program(tmp_path / "p.ngc")
    path = ccopt.compensate(prog, style="linuxcnc")
    res = ccopt.export(path, tmp_path / "o.nc", program=prog)
    assert res.roundtrip_error < 1e-6
    body = [ln for ln in (tmp_path / "o.nc").read_text().splitlines()
            if not ln.startswith("(")]
    assert body[2:] == ["G10 L2 P1 X5 Y0 Z0", "G54", "G0 X1 Y0 Z0",
                        "G52 X1 Y0 Z0", "G1 X2 Y0 Z0 F600",
                        "G52 X0 Y0 Z0", "G53 G0 X0 Y0 Z10", "M2", "%"]
    back = ccopt.read_program(tmp_path / "o.nc")
    assert [b.end for b in back.blocks] == [b.end for b in prog.blocks]


def test_cli_export_with_var_file_writes_work_coordinates(plate, capsys):
    code, out, err = run_cli(capsys, "export", str(plate / "plate.ngc"), "--tool-table",
                             str(plate / "tools.tbl"), "--var-file", str(plate / "p.var"),
                             "-o", str(plate / "cli.nc"))
    assert code == 0, err
    text = (plate / "cli.nc").read_text()
    assert "G55\nG0 X-10 Y-10 Z5\n" in text and "X90" not in text


def test_a_rotated_system_is_written_with_its_rotation_and_reads_back(tmp_path):
    # G55 turned 30 deg about (30, 20): the export writes G10 L2 ... R30 and
    # the contour, its arc and its compensation in the turned work coordinates
    text = ("G21 G17 G90 G94\nG10 L2 P2 X30 Y20 Z0 R30\nG55\nG0 X-5 Y-5 Z5\nG1 Z-1 F300\n"
            "G42 D1 G1 X0 Y0\nG1 Y30\nG1 X40\nG2 X50 Y20 I0 J-10\nG1 Y0\nG1 X0\n"
            "G40 G1 X-5 Y-5\nG0 Z5\nM30\n")
    (tmp_path / "r.ngc").write_text(text)
    (tmp_path / "t.tbl").write_text("T1 P1 D6 ;\n")
    prog = ccopt.read_program(tmp_path / "r.ngc", tool_table=tmp_path / "t.tbl")
    path = ccopt.compensate(prog, style="linuxcnc")
    res = ccopt.export(path, tmp_path / "o.nc", program=prog)
    assert res.roundtrip_error < 1e-5
    body = [ln for ln in (tmp_path / "o.nc").read_text().splitlines()
            if not ln.startswith("(")]
    assert body[2:5] == ["G10 L2 P2 X30 Y20 Z0 R30", "G55", "G0 X-5 Y-5 Z5"]
    back = ccopt.read_program(tmp_path / "o.nc")
    got = [b for b in back.blocks if b.motion.is_move]
    assert len(got) == len(path.segments)
    for seg, b in zip(path.segments, got):
        assert math.dist(seg.end_xyz, b.end) < 1e-5
