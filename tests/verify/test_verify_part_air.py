"""Part surface and air (issue 16): a CAM-style profile with tangent arcs in
and out, the user's word (--part-lines, comment markers), and the sound
contact and open-end checks.

The CAM program: the outside profile of the plate 0 <= x <= 40, 0 <= y <= 30,
cut clockwise with G41 (tool outside, left of the travel), cutter radius
r = 3, starting mid-edge at P0 = (20, 0) going -X. In: the line (25,-15) ->
(25,-5) with G41 on it, then the tangent arc G3 about C = (20,-5), R = 5, from
(25,-5) to P0 (at P0 it runs -X, like the contour). Out: G3 about the same C
from P0 to (15,-5), then the line to (15,-15) with G40. The tool runs on the
centre's side of both arcs (left of a counter-clockwise arc), on radius
R - r = 2 about C, and at y = -3 along the bottom edge. That tool line meets
the arcs' circle |q - C| = 5 where (x - 20)^2 + 2^2 = 25, x = 20 +- sqrt(21),
at polar angles inside the arcs' quarters: if the arcs were part surface the
tool would touch them there, a "gouge" of the whole radius 3, in air.
"""
from __future__ import annotations

import json
import math
from dataclasses import replace

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.cli import main
from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role
from ccopt.verify import decisions, verify

EPS = 1e-6
R_CUT = 3.0

GCODE = """(CAM-style outside profile of a 40 x 30 plate, cutter diameter 6)
G21 G17 G90 G94
G0 X25 Y-15
G41.1 D6 G1 X25 Y-5 F600
G3 X20 Y0 I-5 J0
G1 X0 Y0
G1 X0 Y30
G1 X40 Y30
G1 X40 Y0
G1 X20 Y0
G3 X15 Y-5 I0 J-5
G40 G1 X15 Y-15
M30
"""
#: program lines: the arc in, the contour, the arc out, the lead lines
G_ARC_IN, G_CONTOUR, G_ARC_OUT, G_LINE_IN, G_LINE_OUT = 5, (6, 10), 11, 4, 12

PMAC = """; CAM-style outside profile of a 40 x 30 plate, cutter radius 3
OPEN PROG 1 CLEAR
RAPID X25 Y-15
LINEAR ABS F10
CCR3 CC1
X25 Y-5
CIRCLE2 X20 Y0 I-5 J0
LINEAR X0 Y0
X0 Y30
X40 Y30
X40 Y0
X20 Y0
CIRCLE2 X15 Y-5 I0 J-5
CC0
LINEAR X15 Y-15
CLOSE
"""
P_ARC_IN, P_CONTOUR, P_ARC_OUT, P_LINE_IN, P_LINE_OUT = 7, (8, 12), 13, 6, 15

PROGRAMS = {
    "gcode": (GCODE, "cam.nc", G_ARC_IN, G_CONTOUR, G_ARC_OUT, G_LINE_IN, G_LINE_OUT,
              ("G1 X0 Y30", "G1 X40 Y30"), ("G1 X0 Y29.99", "G1 X40 Y29.99")),
    "pmac": (PMAC, "cam.pmc", P_ARC_IN, P_CONTOUR, P_ARC_OUT, P_LINE_IN, P_LINE_OUT,
             ("X0 Y30", "X40 Y30"), ("X0 Y29.99", "X40 Y29.99")),
}


def read(tmp_path, text, name):
    f = tmp_path / name
    f.write_text(text)
    return ccopt.read_program(f)


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_cam_profile_verifies_ok_with_its_leads_in_air(tmp_path, dialect):
    text, name, arc_in, (c0, c1), arc_out, line_in, line_out, _, _ = PROGRAMS[dialect]
    prog = read(tmp_path, text, name)
    path = compensate(prog, "pmac")
    cert = verify(path, prog, eps=EPS)
    assert cert.ok, cert.summary()
    assert cert.violations == ()
    # the tool touches the plate all round, at r: the arcs in air do not count
    assert cert.min_clearance == pytest.approx(R_CUT, abs=1e-12)
    s = cert.to_json()["surface"]
    assert s["rule"] == "closed-loop"
    assert s["part_lines"] == [[c0, c1]]
    assert s["air_lines"] == [[line_in, line_in], [arc_in, arc_in], [arc_out, arc_out],
                              [line_out, line_out]]
    why = {r["lines"][0]: r["why"] for r in s["moves"]}
    assert why[arc_in] == "lead before the closed loop"
    assert why[arc_out] == "lead after the closed loop"
    assert why[c0] == "closed loop"
    text_out = cert.summary()
    assert "part and air by rule closed-loop:" in text_out
    assert f"part surface: lines {c0}-{c1} (closed loop)" in text_out
    assert f"air: lines {arc_in} (lead before the closed loop)" in text_out


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_cam_profile_with_a_contour_move_pushed_inside_fails(tmp_path, dialect):
    # the top edge y = 30 written 0.01 lower: its tool line runs at y = 32.99,
    # 2.99 from the real edge, and the corner arcs about (0, 29.99) and
    # (40, 29.99) reach y = 32.99 too: a gouge of 0.01
    text, name, _, _, _, _, _, old, new = PROGRAMS[dialect]
    prog = read(tmp_path, text, name)
    pushed = text
    for a, b in zip(old, new):
        assert pushed.count(a + "\n") == 1
        pushed = pushed.replace(a + "\n", b + "\n")
    bad = compensate(read(tmp_path, pushed, "pushed" + name[3:]), "pmac")
    cert = verify(bad, prog, eps=EPS)
    assert not cert.ok
    g = cert.violations_of("gouge")
    assert g
    assert max(v.depth for v in g) == pytest.approx(0.01, abs=1e-9)
    top = [v for v in g if v.tool_role == "compensated"]
    assert top and all(v.witness_tool[1] == pytest.approx(32.99, abs=1e-9) for v in top)


def test_every_compensated_move_as_part_gives_the_false_alarm_in_air(tmp_path, monkeypatch):
    # the alternative of CLOSED_LOOP_IS_THE_PART: the arcs in and out are part
    # surface, and the bottom tool line y = -3 crosses their circle (module
    # docstring): depth r at x = 20 + sqrt(21) and x = 20 - sqrt(21)
    prog = read(tmp_path, GCODE, "cam.nc")
    path = compensate(prog, "pmac")
    monkeypatch.setattr(decisions, "CLOSED_LOOP_IS_THE_PART", False)
    cert = verify(path, prog, eps=EPS)
    assert not cert.ok
    assert cert.to_json()["surface"]["air_lines"] == [[G_LINE_IN, G_LINE_IN],
                                                      [G_LINE_OUT, G_LINE_OUT]]
    deep = [v for v in cert.violations_of("gouge") if v.element_block in (G_ARC_IN, G_ARC_OUT)]
    assert deep
    assert max(v.depth for v in deep) == pytest.approx(R_CUT, abs=1e-9)
    xs = sorted(round(v.witness_tool[0], 9) for v in deep if v.depth > R_CUT - 1e-9)
    assert xs[0] == pytest.approx(20 - math.sqrt(21), abs=1e-9)
    assert xs[-1] == pytest.approx(20 + math.sqrt(21), abs=1e-9)


def test_part_lines_and_markers_say_which_moves_are_part(tmp_path):
    prog = read(tmp_path, GCODE, "cam.nc")
    path = compensate(prog, "pmac")
    # the user's word: the same part as the closed loop ...
    same = verify(path, prog, eps=EPS, part_lines="6-10")
    assert same.ok and same.surface["rule"] == "part-lines"
    assert same.surface["part_lines"] == [[6, 10]]
    # ... or the arcs as part too: the alarm of depth r comes back
    arcs = verify(path, prog, eps=EPS, part_lines=[(5, 11)])
    assert not arcs.ok
    assert max(v.depth for v in arcs.violations_of("gouge")) == pytest.approx(R_CUT, abs=1e-9)
    # a marker on the arc in makes it part; the arc out stays a lead
    marked = read(tmp_path, GCODE.replace("G3 X20 Y0 I-5 J0", "G3 X20 Y0 I-5 J0 (ccopt: part)"),
                  "marked.nc")
    cert = verify(compensate(marked, "pmac"), marked, eps=EPS)
    assert not cert.ok
    assert {v.element_block for v in cert.violations_of("gouge")} == {G_ARC_IN}
    runs = {r["lines"][0]: r for r in cert.surface["moves"]}
    assert runs[G_ARC_IN]["surface"] == "part" and runs[G_ARC_IN]["why"] == "marked (ccopt: part)"
    assert runs[G_ARC_OUT]["surface"] == "air"
    with pytest.raises(ProgramError, match="part lines"):
        verify(path, prog, part_lines="6-x")
    # lines with no compensated move on them would leave no part at all
    with pytest.raises(ProgramError, match=r"part lines 1-3,12 hold no fully compensated move "
                                           r"\(those are on lines 5-11\)"):
        verify(path, prog, part_lines="1-3,12")


def test_pmac_air_marker_on_an_open_profile(tmp_path):
    # No closed loop: the contour stops at (21, 0), 1 short of P0, and leaves
    # straight down with CC0; every compensated move is part, the arc in (7)
    # too. The tool line y = -3 back along the bottom edge crosses that arc's
    # circle at x = 20 + sqrt(21) (module docstring): a gouge of r there.
    # Marked air (; ccopt: air), the arc in is no longer checked against.
    text = PMAC.replace("X20 Y0\nCIRCLE2 X15 Y-5 I0 J-5\nCC0\nLINEAR X15 Y-15",
                        "X21 Y0\nCC0\nLINEAR X21 Y-15")
    assert "X21 Y0" in text
    open_prog = read(tmp_path, text, "open.pmc")
    cert = verify(compensate(open_prog, "pmac"), open_prog, eps=EPS)
    assert cert.surface["rule"] == "closed-loop"
    assert cert.surface["moves"][1]["why"].startswith("no closed loop")
    g = cert.violations_of("gouge")
    assert not cert.ok and {v.element_block for v in g} == {P_ARC_IN}
    v = max(g, key=lambda v: v.depth)
    assert v.depth == pytest.approx(R_CUT, abs=1e-9)
    assert v.witness_tool == pytest.approx((20 + math.sqrt(21), -3.0), abs=1e-9)
    marked = read(tmp_path, text.replace("CIRCLE2 X20 Y0 I-5 J0", "CIRCLE2 X20 Y0 I-5 J0 ; ccopt: air"),
                  "marked.pmc")
    cert = verify(compensate(marked, "pmac"), marked, eps=EPS)
    assert cert.ok, cert.summary()
    assert cert.surface["rule"] == "closed-loop+markers"
    runs = {r["lines"][0]: r for r in cert.surface["moves"]}
    assert runs[P_ARC_IN]["surface"] == "air" and runs[P_ARC_IN]["why"] == "marked (ccopt: air)"


def test_cli_part_lines(tmp_path, capsys):
    f = tmp_path / "cam.nc"
    f.write_text(GCODE)
    assert main(["verify", str(f), "--part-lines", "6-10", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["surface"]["part_lines"] == [[6, 10]]
    assert [5, 5] in doc["surface"]["air_lines"] and [11, 11] in doc["surface"]["air_lines"]
    assert main(["verify", str(f), "--part-lines", "5-11"]) == 1
    with pytest.raises(SystemExit) as exc:
        main(["verify", str(f), "--part-lines", "10-6"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--part-lines" in err and len(err.strip().splitlines()) == 1


# --------------------------------------------------------------------------- sound checks


@pytest.mark.parametrize("name", ["fagor-seed-arc-cancel", "leadout-inside-arc-arc",
                                  "leadout-inside-arc-line"])
def test_an_arc_swept_the_long_way_fails_contact(name):
    # the finding: the compensated arc swept 270 degrees the other way
    # round (same ends, same centre) passed; it never runs alongside its element
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    path = compensate(prog, case.style, radius=case.radius)
    i = next(k for k, s in enumerate(path.segments)
             if s.role is Role.COMPENSATED and isinstance(s.geom, Arc))
    g = path.segments[i].geom
    assert abs(g.sweep) == pytest.approx(math.pi / 2, abs=1e-12)
    flip = Arc(g.center, g.radius, g.theta0, g.sweep - math.copysign(2 * math.pi, g.sweep))
    assert abs(flip.sweep) == pytest.approx(1.5 * math.pi, abs=1e-12)
    segs = list(path.segments)
    segs[i] = replace(segs[i], geom=flip)
    cert = verify(replace(path, segments=tuple(segs)), prog, radius=case.radius, eps=EPS)
    assert not cert.ok
    c = [v for v in cert.violations_of("contact") if v.tool_segment == i]
    assert len(c) == 1 and c[0].depth == math.inf
    assert "never runs alongside" in c[0].detail["reason"]


def test_a_point_just_past_an_open_end_keeps_the_clearance():
    # leadin-inside-line: CC1, r = 2; first element (0,0) -> (-20,0), open at
    # P = (0,0); the lead-in runs up x = 0 to Q = (0,-2). Bent through
    # Q' = (s, -(2 - d)) just past the end (s > 0 is beyond it): the old
    # exemption dropped it; now it counts by |Q' - P| + s against r = 2.
    case = find_case("leadin-inside-line")
    prog = ccopt.read_program(case.program)
    path = compensate(prog, case.style)
    k = next(i for i, s in enumerate(path.segments) if s.role is Role.LEAD_IN)
    seg = path.segments[k]
    assert seg.geom.end == pytest.approx((0.0, -2.0), abs=1e-12)
    d, s = 0.1, 0.01
    Qn = (s, -(2.0 - d))
    bent = [replace(seg, geom=Line(seg.geom.p0, Qn)), replace(seg, geom=Line(Qn, (0.0, -2.0)))]
    segs = list(path.segments)
    segs[k:k + 1] = bent
    cert = verify(replace(path, segments=tuple(segs)), prog, eps=EPS)
    assert not cert.ok
    v = max(cert.violations_of("gouge"), key=lambda v: v.depth)
    # the deepest point: Q' itself (both lines run from it away from P and
    # further past the end), depth r - (|Q' - P| + s)
    expect = 2.0 - (math.hypot(s, 2.0 - d) + s)
    assert v.depth == pytest.approx(expect, abs=1e-12)
    assert v.witness_tool == pytest.approx(Qn, abs=1e-12)
    assert v.detail["past_open_end"] is True
    # the controller's own lead along the end's normal still passes
    assert verify(path, prog, eps=EPS).ok


def test_readers_keep_the_marker_on_the_block(tmp_path, capsys):
    g = read(tmp_path, "G21 G90 F600\nG1 X10 (ccopt: air)\nG1 Y10 (CCOPT: Part)\nG1 X0\n"
             "G1 Y0 ; ccopt: air\n", "m.nc")
    assert [b.surface for b in g.blocks] == ["air", "part", None, "air"]
    p = read(tmp_path, "LINEAR F10\nX10 ; ccopt: air\nY10 ; tool side ccopt: part\nX0 Y0\n",
             "m.pmc")
    assert [b.surface for b in p.blocks] == ["air", "part", None]
    # two markers on one line: bad input, located
    f = tmp_path / "both.nc"
    f.write_text("G21 G90 F600\nG1 X10 (ccopt: air) (ccopt: part)\n")
    assert main(["show", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"{f}:2:") and len(err.splitlines()) == 1
