"""A Klartext plate entered with APPR LCT and left with DEP LCT (issue 32's
acceptance): it compensates, verifies, is timed, and exports to G-code and
PMAC programs that read back to the same motion; its CYCL DEF 32 tolerance
is reported."""
from __future__ import annotations

import json

import pytest

import ccopt
from ccopt.program import read_program
from ccopt.toolpath import Role
from cli_run import run_cli

PLATE = """0 BEGIN PGM PLATE MM
1 BLK FORM 0.1 Z X+0 Y+0 Z-10
2 BLK FORM 0.2 X+100 Y+80 Z+0
3 TOOL DEF 1 L+0 R+5
4 TOOL CALL 1 Z S3000
5 CYCL DEF 32.0 TOLERANCE
6 CYCL DEF 32.1 T0.01
7 L Z+50 R0 FMAX
8 L X-30 Y-30 R0 FMAX M3
9 L Z-5 R0 F1000
10 APPR LCT X+50 Y+0 R8 RR F500
11 L X+100 Y+0
12 RND R10
13 L X+100 Y+80
14 CHF 5
15 L X+40 Y+80
16 CR X+0 Y+40 R+40 DR+
17 L X+0 Y+0
18 L X+50 Y+0
19 DEP LCT X+80 Y-30 R8 F800
20 L Z+50 R0 FMAX
21 M30
22 END PGM PLATE MM
"""


@pytest.fixture()
def plate(tmp_path):
    p = tmp_path / "plate.h"
    p.write_text(PLATE)
    return p


def test_plate_compensates_verifies_and_is_timed(plate):
    prog = read_program(plate)
    path = ccopt.compensate(prog, style="heidenhain")
    limits = ccopt.AxisLimits(v=[100, 100, 50], a=[1000, 1000, 500])
    prof = ccopt.plan_feed(path, limits)
    cert = ccopt.verify(path, prog, profile=prof)
    assert cert.ok and prof.duration > 0
    # the approach arc ends on the offset of the first element at (50, -5),
    # the departure arc leaves from there too: radius 8 both
    arcs = [s.geom for s in path.segments if s.role is Role.COMPENSATED
            and hasattr(s.geom, "radius") and s.geom.radius == pytest.approx(8.0)]
    assert len(arcs) == 2
    assert arcs[0].end == pytest.approx((50.0, -5.0)) and arcs[1].start == pytest.approx((50.0, -5.0))


@pytest.mark.parametrize("suffix, dialect", [(".nc", "gcode"), (".pmc", "pmac")])
def test_plate_exports_and_reads_back(plate, tmp_path, capsys, suffix, dialect):
    out = tmp_path / f"plate-comp{suffix}"
    code, stdout, err = run_cli(capsys, "export", str(plate), "-o", str(out), "--json")
    assert code == 0, err
    doc = json.loads(stdout)
    assert doc["verified"] and doc["roundtrip_error"] <= doc["tolerance"]
    back = read_program(out)
    assert back.dialect == dialect
    path = ccopt.compensate(read_program(plate), style="heidenhain")
    # the exported program runs the tool-centre path uncompensated: same length
    moved = ccopt.toolpath.programmed_path(back)
    assert moved.length == pytest.approx(path.length, rel=1e-6)


def test_show_reports_the_cycle_32_tolerance(plate, capsys):
    code, stdout, _ = run_cli(capsys, "show", str(plate))
    assert code == 0 and "CYCL DEF 32 tolerance 0.01 mm (line 7)" in stdout
    code, stdout, _ = run_cli(capsys, "compensate", str(plate), "--json")
    assert json.loads(stdout)["cycle32_tolerance"] == [{"line": 7, "tolerance": 0.01}]
