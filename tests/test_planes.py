"""Programs that compensate in G17 and then, after G40, in G18 (issue 15, item 1).

Every tool-path segment carries its plane; the JSON gives it with the
machine-coordinate ends; feed holds each section to the limits of the axes
it moves; verify checks each plane against its own contour; export writes the
plane words. A plane change while compensation is on is refused where the
plane word stands, as LinuxCNC's ``convert_set_plane`` refuses it.

The expected figures are worked out here from the geometry: in G18 the
in-plane coordinates are ``(u, v) = (Z, X)`` and the normal is ``w = Y``
(docs/compensation.md 1.2), so "left" of a move along ``+u`` is ``+v``.
"""
from __future__ import annotations

import json
import math

import pytest

from ccopt.cli import main
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program.gcode import read_gcode
from ccopt.toolpath import machine_point
from ccopt.toolpath_json import toolpath_from_json
from linuxcnc_data import CONFORMANCE

R = 2.0  # G41.1 D4

# The same outline twice: in G17 (u, v) = (X, Y) at Z0, then after G40 in
# G18 (u, v) = (Z, X) at Y50. Each: from (u, v) = (0, -20) up to (0, 0)
# (lead-in), along +u to (20, 0) with the tool on the left (+v), off, and
# on to (20, 10) (lead-out). The part lies on the -v side of the u axis.
TWO_PLANES = """G21 G17 G90 G94 F1200
G0 X0 Y-20 Z0
G41.1 D4
G1 X0 Y0
G1 X20 Y0
G40
G1 X20 Y10
G18
G0 Z0 X-20 Y50
G41.1 D4
G1 Z0 X0
G1 Z20 X0
G40
G1 Z20 X10
M2
"""
STYLES = ("pmac", "linuxcnc", "fagor")


@pytest.fixture()
def part(tmp_path):
    f = tmp_path / "two-planes.ngc"
    f.write_text(TWO_PLANES)
    return f


def _json(capsys, *argv):
    code = main([*argv, "--json"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out)


@pytest.mark.parametrize("style", STYLES)
def test_compensate_gives_each_segment_its_plane_and_machine_ends(capsys, part, style):
    """The compensated move of each plane runs on the +v offset, r = 2 from
    the contour u axis, from the end of the lead-in's outside corner
    (0, 2) to the offset end of the programmed corner (20, 2) (the lead-out
    turns left, inside: PMAC rule 5, LinuxCNC's G40 and Fagor alike end the
    last move at P + r*o(t)). In G17 that is X0..20 at Y2, Z0; in G18,
    (u, v) = (Z, X), so Z0..20 at X2 and Y50."""
    data = _json(capsys, "compensate", str(part), "--style", style)
    segs = data["segments"]
    assert data["plane"] == "XY"                 # the first segment's
    assert {s["plane"] for s in segs} == {"XY", "ZX"}
    comp = [s for s in segs if s["role"] == "compensated"]
    assert [(s["plane"], s["block"]) for s in comp] == [("XY", 5), ("ZX", 12)]
    xy, zx = comp
    assert xy["start"] == pytest.approx([0.0, R]) and xy["end"] == pytest.approx([20.0, R])
    assert xy["start_xyz"] == pytest.approx([0.0, R, 0.0])
    assert xy["end_xyz"] == pytest.approx([20.0, R, 0.0])
    assert zx["start"] == pytest.approx([0.0, R]) and zx["end"] == pytest.approx([20.0, R])
    assert zx["start_xyz"] == pytest.approx([R, 50.0, 0.0])
    assert zx["end_xyz"] == pytest.approx([R, 50.0, 20.0])
    # every segment: machine ends are the in-plane ends with w on the plane's axes
    for s in segs:
        w0, w1 = s.get("w", [0.0, 0.0])
        assert s["start_xyz"] == pytest.approx(list(machine_point(s["plane"], *s["start"], w0)))
        assert s["end_xyz"] == pytest.approx(list(machine_point(s["plane"], *s["end"], w1)))
    # the path is continuous in machine coordinates across the plane change
    for a, b in zip(segs, segs[1:]):
        assert math.dist(a["end_xyz"], b["start_xyz"]) < 1e-9


def test_machine_point_puts_u_v_w_on_each_planes_axes():
    # PLANE_AXES: XY (u, v, w) = (X, Y, Z); ZX = (Z, X, Y); YZ = (Y, Z, X)
    assert machine_point("XY", 1.0, 2.0, 3.0) == (1.0, 2.0, 3.0)
    assert machine_point("ZX", 1.0, 2.0, 3.0) == (2.0, 3.0, 1.0)
    assert machine_point("YZ", 1.0, 2.0, 3.0) == (3.0, 1.0, 2.0)


@pytest.mark.parametrize("style", STYLES)
def test_feed_verify_export_run_with_exit_0(capsys, tmp_path, part, style):
    args = [str(part), "--style", style]
    assert main(["feed", *args, "--vmax", "100,50,20", "--amax", "1000,500,200"]) == 0
    assert main(["verify", *args, "--feed", "--vmax", "100,50,20",
                 "--amax", "1000,500,200"]) == 0
    nc, pmc = tmp_path / "out.nc", tmp_path / "out.pmc"
    assert main(["export", *args, "-o", str(nc)]) == 0
    assert main(["export", *args, "-o", str(pmc)]) == 0
    assert main(["export", *args, "-o", str(tmp_path / "out.json")]) == 0
    capsys.readouterr()
    lines = nc.read_text().splitlines()
    first = next(i for i, ln in enumerate(lines) if ln.startswith("G21 "))
    assert lines[first] == "G21 G17 G90 G94"
    assert [ln for ln in lines[first + 1:] if ln in ("G17", "G18", "G19")] == ["G18"]
    normals = [ln for ln in pmc.read_text().splitlines() if ln.startswith("NORMAL")]
    assert normals == ["NORMAL K-1", "NORMAL J-1"]   # docs/pmac.md: XY, then ZX
    # the exported G-code, read back as a program, is the same tool path
    back = _json(capsys, "show", str(nc))
    ours = _json(capsys, "compensate", *args)
    moving = [s for s in ours["segments"] if math.dist(s["start_xyz"], s["end_xyz"]) > 1e-9]
    got = [s for s in back["segments"] if math.dist(s["start_xyz"], s["end_xyz"]) > 1e-9]
    assert [s["plane"] for s in got] == [s["plane"] for s in moving]
    for a, b in zip(got, moving):
        assert a["end_xyz"] == pytest.approx(b["end_xyz"], abs=1e-6)


def test_verify_checks_each_plane_against_its_own_contour(capsys, part):
    """Each plane's compensated move runs r from its own contour element: the
    smallest clearance is r. Checked together in one plane, the G18 pass (at
    u = Z 0..20, v = X 2) would sit on the G17 contour (X 0..20 at Y 0)."""
    cert = _json(capsys, "verify", str(part), "--style", "linuxcnc")
    assert cert["ok"] and cert["min_clearance"] == pytest.approx(R, abs=1e-9)
    gouge = next(c for c in cert["checks"] if c["name"] == "gouge")
    assert gouge["detail"]["elements"] == 2       # one contour element per plane
    assert any("plane by plane" in n for n in cert["notes"])


def test_toolpath_json_read_back_keeps_planes(capsys, tmp_path, part):
    data = _json(capsys, "compensate", str(part), "--style", "pmac")
    prog = read_gcode(TWO_PLANES, str(part))
    path = toolpath_from_json(data, prog, "path.json")
    assert [s.plane for s in path.segments] == [s["plane"] for s in data["segments"]]
    f = tmp_path / "path.json"
    f.write_text(json.dumps(data))
    assert main(["verify", str(part), "--toolpath", str(f)]) == 0
    # a segment said to lie in another plane than its block is refused
    bad = json.loads(json.dumps(data))
    k = next(i for i, s in enumerate(bad["segments"]) if s["plane"] == "ZX")
    bad["segments"][k]["plane"] = "XY"
    f.write_text(json.dumps(bad))
    assert main(["verify", str(part), "--toolpath", str(f)]) == 2
    assert f"segment {k}: 'plane' XY is not the plane of its block" in capsys.readouterr().err


def _trapezoid_time(length: float, v: float, a: float) -> float:
    """Rest to rest along a line at one axis's limits: accelerate at ``a`` to
    ``v``, cruise, brake (bang-bang ``2 sqrt(L / a)`` when ``v`` is not reached)."""
    if length >= v * v / a:
        return length / v + v / a
    return 2.0 * math.sqrt(length / a)


def test_each_section_is_planned_against_its_own_axes():
    """A G1 along X in G17 (100 mm), then in G18 a G1 along u = Z (50 mm) and
    one along v = X (30 mm), each from rest to rest (90-degree corners
    stop). X: 100 mm/s, 1000 mm/s^2; Y: 50, 500; Z: 20, 200. Each line is one
    axis's trapezoid: 100/100 + 100/1000 = 1.1 s; 50/20 + 20/200 = 2.6 s;
    30 mm at X reaches 100 mm/s only after 10 mm and brakes in 10: 0.3 +
    0.1 = 0.4 s. With the G18 lines held to X and Y (the first plane's u
    and v) the Z line would take 0.6 s."""
    prog = read_gcode("G21 G17 F60000\nG1 X100\nG18\nG1 Z50\nG1 X130\nM2\n", "lines.ngc")
    path = compensate(prog, style="pmac")
    assert [s.plane for s in path.segments] == ["XY", "ZX", "ZX"]
    lim = AxisLimits((100.0, 50.0, 20.0), (1000.0, 500.0, 200.0))
    want = (_trapezoid_time(100, 100, 1000) + _trapezoid_time(50, 20, 200)
            + _trapezoid_time(30, 100, 1000))
    assert want == pytest.approx(1.1 + 2.6 + 0.4)
    for planner in ("toppra", "stop"):
        prof = plan_feed(path, lim, planner=planner)
        assert prof.duration == pytest.approx(want, rel=1e-6), planner
        smp = prof.sample()
        assert smp.axes == ("X", "Y", "Z")
    # the same two G18 lines alone, one plane: the same times
    alone = compensate(read_gcode("G21 G18 F60000\nG0 X100\nG1 Z50\nG1 X130\nM2\n", "z.ngc"),
                       style="pmac")
    t_alone = plan_feed(alone, lim).duration - _trapezoid_time(100, 100, 1000)
    assert t_alone == pytest.approx(2.6 + 0.4, rel=1e-6)


def test_plane_change_while_compensation_is_on_is_refused_at_the_plane_word(capsys, tmp_path):
    """LinuxCNC runs the plane words before G40 in a block
    (interp_convert.cc, convert_g): G18 G40 on one line while on is refused."""
    for text, line, col in (
            ("G21 F600\nG0 X0 Y-20\nG41.1 D4\nG1 X0 Y0\nG1 X20 Y0\nG18\nG40\nG1 Z5\n", 6, 1),
            ("G21 F600\nG0 X0 Y-20\nG41.1 D4\nG1 X0 Y0\nG1 X20 Y0\nG40 G18\nG1 Z5\n", 6, 5)):
        f = tmp_path / "bad.ngc"
        f.write_text(text)
        for style in STYLES:
            assert main(["compensate", str(f), "--style", style]) == 2
            err = capsys.readouterr().err
            assert err.startswith(f"{f}:{line}:{col}: cannot change planes (XY to ZX)"), err
            assert len(err.strip().splitlines()) == 1


def test_g40_then_g18_then_g41_between_two_moves_is_a_new_entry(capsys, tmp_path):
    """Compensation off at the plane change and on again before the next
    move (legal in LinuxCNC): the first G18 move is an entry. It starts where
    the tool stands after the G17 pass, (X20, Y2, Z0); LinuxCNC takes its
    direction from the programmed point (X20, Y0, Z0), (u, v) = (0, 20) in
    G18, to the programmed end (Z10, X20), (u, v) = (10, 20): +u, so its end
    is offset r to the left, (10, 22), i.e. X22, Z10, at the programmed Y0
    (the normal is never offset)."""
    f = tmp_path / "again.ngc"
    f.write_text("G21 F600\nG0 X0 Y-20\nG41.1 D4\nG1 X0 Y0\nG1 X20 Y0\nG40\nG18\nG41.1 D4\n"
                 "G1 Z10 X20\nG1 Z20 X20\nG40\nG1 Z20 X30\nM2\n")
    data = _json(capsys, "compensate", str(f), "--style", "linuxcnc")
    entry = next(s for s in data["segments"] if s["plane"] == "ZX")
    assert entry["role"] == "lead-in" and entry["block"] == 9
    assert entry["start_xyz"] == pytest.approx([20.0, 2.0, 0.0])
    assert entry["end_xyz"] == pytest.approx([22.0, 0.0, 10.0])


def test_pmac_normal_change_after_the_lead_out_is_accepted(capsys, tmp_path):
    """PMAC: CC0, the lead-out in XY, then NORMAL J-1 and a pass in ZX; the
    ZX compensated move Z0 -> Z20 at X0 with CC1 runs at X = +r."""
    f = tmp_path / "two.pmc"
    f.write_text("OPEN PROG 1 CLEAR\nRAPID X0 Y-20\nLINEAR ABS F20\nCCR2 CC1\nX0 Y0\nX20 Y0\n"
                 "CC0\nX20 Y10\nNORMAL J-1\nRAPID Z0 X-20 Y50\nLINEAR\nCC1\nZ0 X0\nZ20 X0\n"
                 "CC0\nZ20 X10\nCLOSE\n")
    data = _json(capsys, "compensate", str(f))
    comp = [s for s in data["segments"] if s["role"] == "compensated"]
    assert [s["plane"] for s in comp] == ["XY", "ZX"]
    assert comp[1]["start_xyz"] == pytest.approx([R, 50.0, 0.0])
    assert comp[1]["end_xyz"] == pytest.approx([R, 50.0, 20.0])


@pytest.mark.parametrize("style", STYLES)
def test_linuxcnc_comp_ngc_is_no_longer_refused_at_its_g18(capsys, style):
    """LinuxCNC's nc_files/comp.ngc: G42 and G41 passes in G17, G40, then the
    same in G18 (its D1 names tool 1: its radius is given here)."""
    prog = CONFORMANCE / "nc_files" / "comp.ngc"
    data = _json(capsys, "compensate", str(prog), "--style", style, "--radius", "0.05")
    planes = [s["plane"] for s in data["segments"]]
    assert planes[0] == "XY" and planes[-1] == "ZX"
    assert sorted(set(planes)) == ["XY", "ZX"]
    g18_line = 30       # "g20 g64 g18": the first G18 move is line 31's G0
    first_zx = next(s for s in data["segments"] if s["plane"] == "ZX")
    assert first_zx["block"] == g18_line + 1
    # G0 X-.2 Z-.2 Y0: the rapid ends there, in (u, v, w) = (Z, X, Y)
    assert first_zx["end_xyz"] == pytest.approx([-0.2, 0.0, -0.2])
    assert first_zx["end"] == pytest.approx([-0.2, -0.2])


def test_a_gouge_in_the_g18_section_names_the_whole_paths_segment(capsys, tmp_path, part):
    """The G18 compensated move's end moved from (u, v) = (20, 2) to (20, 1),
    1 from its contour element's end (Z20, X0): a gouge of depth r - 1 = 1 at
    that segment (numbered in the whole path), witnessed at (20, 1) in the ZX
    plane, and a jump of 1 to the lead-out that still starts at (20, 2)."""
    data = _json(capsys, "compensate", str(part), "--style", "pmac")
    k = next(i for i, s in enumerate(data["segments"])
             if s["plane"] == "ZX" and s["role"] == "compensated")
    data["segments"][k]["end"] = [20.0, 1.0]
    f = tmp_path / "moved.json"
    f.write_text(json.dumps(data))
    code = main(["verify", str(part), "--toolpath", str(f), "--json"])
    cert = json.loads(capsys.readouterr().out)
    assert code == 1 and not cert["ok"]
    gouge = [v for v in cert["violations"] if v["kind"] == "gouge"]
    assert gouge and gouge[0]["tool_segment"] == k and gouge[0]["plane"] == "ZX"
    assert gouge[0]["depth"] == pytest.approx(1.0, abs=1e-12)
    assert gouge[0]["witness_tool"] == pytest.approx([20.0, 1.0])
    assert gouge[0]["element"] == 1          # the G17 run's element is 0
    gap = [v for v in cert["violations"] if v["kind"] == "gap"]
    assert [(v["tool_segment"], v["plane"]) for v in gap] == [(k + 1, "ZX")]
    assert gap[0]["depth"] == pytest.approx(1.0, abs=1e-12)
