"""PMAC reference compensation on the bundled cases.

Every expected figure is derived here from the case's geometry with the
spec's formulas (``o(t) = k*(-t_y, t_x)``, offset arc radius ``R -/+ r``, line
and circle intersections worked out by hand), never copied from ccopt's output.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import bundled_cases_dir, load_case
from ccopt.compensate import compensate
from segment_expect import L, A, SP, check

TOL = 1e-9
S2 = math.sqrt(2.0)
H = 1.0 / S2  # cos 45


def run_case(name: str):
    case = load_case(bundled_cases_dir() / name)
    prog = ccopt.read_program(case.program)
    return compensate(prog, style="pmac", radius=case.radius)


def angle(c, p):
    return math.atan2(p[1] - c[1], p[0] - c[0])


def test_leadin_inside_line():
    # Lead-in (0,-20)->(0,0) then -X, CC1 r=2: left turn = inside, the lead-in
    # ends at P + r*o(t_next) = (0,0) + 2*(0,-1).
    check(run_case("leadin-inside-line"), [
        L("lead-in", (0, -20), (0, -2)),
        # (0,0)->(-20,0) then +Y is a right turn: outside, d = 0 < break: arc.
        L("compensated", (0, -2), (-20, -2)),
        A("corner", (-20, 0), (-20, -2), (-22, 0), -math.pi / 2),
        # lead-out to (-40,20) turns left: inside, ends at P + r*o(t_last).
        L("compensated", (-22, 0), (-22, 20)),
        L("lead-out", (-22, 20), (-40, 20)),
    ])


def test_leadin_outside_line():
    # +Y then +X is a right turn for CC1: outside. Lead-in ends perpendicular
    # to its own path at P: (0,0) + 2*(-1,0); arc about P to (0,2).
    check(run_case("leadin-outside-line"), [
        L("lead-in", (0, -20), (-2, 0)),
        A("corner", (0, 0), (-2, 0), (0, 2), -math.pi / 2),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (20, 10)),
    ])


def test_leadin_inside_arc_is_a_spiral():
    # CIRCLE2 about (0,0) from (10,0) to (0,10); next move along u=(-1,-1)/sqrt2
    # (left turn, inside). End = (0,10) + 2*(-u_y, u_x) = (sqrt2, 10 - sqrt2).
    e = (S2, 10 - S2)
    e2 = (-10 + S2, -S2)  # lead-out corner (-10,0): inside, P + 2*(H, -H)
    check(run_case("leadin-inside-arc"), [
        # programmed sweep pi/2 from angle 0, end angle moved to atan2(e)
        SP("lead-in", (0, 0), (10, 0), e, math.atan2(e[1], e[0])),
        L("compensated", e, e2),
        L("lead-out", e2, (-10, -10)),
    ])
    seg = run_case("leadin-inside-arc").segments[1]
    assert seg.geom.rho0 == pytest.approx(10, abs=TOL)
    assert seg.geom.rho1 == pytest.approx(math.hypot(*e), abs=TOL)


def test_leadin_outside_arc():
    # CIRCLE1 about (0,0) from (-10,0) to (0,10) (sweep -pi/2), CC1 r=1.5.
    # Next move -Y: right turn, outside. Lead-in ends at (0,10) + 1.5*(0,1).
    check(run_case("leadin-outside-arc"), [
        SP("lead-in", (0, 0), (-10, 0), (0, 11.5), -math.pi / 2),
        A("corner", (0, 10), (0, 11.5), (1.5, 10), -math.pi / 2),
        L("compensated", (1.5, 10), (1.5, -5)),
        L("lead-out", (1.5, -5), (10, -5)),
    ])


def test_leadout_inside_line_line():
    # CC2 r=2; lead-in collinear: ends at (0,0) + 2*o((1,0)) = (0,-2).
    check(run_case("leadout-inside-line-line"), [
        L("lead-in", (-10, 0), (0, -2)),
        L("compensated", (0, -2), (20, -2)),
        L("lead-out", (20, -2), (30, -10)),
    ])


def test_leadout_inside_line_arc():
    # Lead-out arc about (15,-5) from (20,-2) (rho sqrt34) to (20,-10) (rho
    # sqrt50); programmed sweep -pi/2 from angle pi/4; start angle atan2(3,5).
    sweep = -math.pi / 2 - (math.atan2(3, 5) - math.pi / 4)
    path = run_case("leadout-inside-line-arc")
    check(path, [
        L("lead-in", (-10, 0), (0, -2)),
        L("compensated", (0, -2), (20, -2)),
        SP("lead-out", (15, -5), (20, -2), (20, -10), sweep),
    ])
    sp = path.segments[-1].geom
    assert (sp.rho0, sp.rho1) == pytest.approx((math.sqrt(34), math.sqrt(50)), abs=TOL)


def test_leadout_inside_arc_arc():
    # Compensated CIRCLE1 about (0,-10), R10, CC2: tool toward the centre, R 8.
    # Ends at (10,-10) + 2*o((0,-1)) = (8,-10). Lead-out about (5,-5): from
    # angle atan2(-5,3) (rho sqrt34) to the programmed end (0,-10), angle -3pi/4.
    sweep = -math.pi / 2 - (math.atan2(-5, 3) - (-math.pi / 4))
    check(run_case("leadout-inside-arc-arc"), [
        L("lead-in", (-10, 0), (0, -2)),
        A("compensated", (0, -10), (0, -2), (8, -10), -math.pi / 2),
        SP("lead-out", (5, -5), (8, -10), (0, -10), sweep),
    ])


def test_leadout_inside_arc_line():
    check(run_case("leadout-inside-arc-line"), [
        L("lead-in", (-10, 0), (0, -2)),
        A("compensated", (0, -10), (0, -2), (8, -10), -math.pi / 2),
        L("lead-out", (8, -10), (0, -20)),
    ])


def test_leadout_outside_line_line():
    # +X then (1,1)/sqrt2 is a left turn: outside for CC2. Arc about (20,0)
    # from (20,-2) by +45 degrees to (20,0) + 2*(H,-H).
    check(run_case("leadout-outside-line-line"), [
        L("lead-in", (-10, 0), (0, -2)),
        L("compensated", (0, -2), (20, -2)),
        A("corner", (20, 0), (20, -2), (20 + S2, -S2), math.pi / 4),
        L("lead-out", (20 + S2, -S2), (30, 10)),
    ])


def test_side_change_through_a_line():
    # Left offset y=+2 and right offset y=-2 are parallel: no intersection, the
    # change runs over the next move as a diagonal.
    check(run_case("sidechange-through-line"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        L("compensated", (20, 2), (40, -2)),
        L("lead-out", (40, -2), (50, 0)),
    ])


def test_side_change_through_an_arc():
    # Old side: line y=2. New side (right) of the clockwise arc about (20,-10):
    # radius 10 - 2 = 8, which y=2 misses (distance 12). Spiral about (20,-10)
    # from (20,2) (rho 12, angle pi/2) to (28,-10) (rho 8), sweep -pi/2.
    path = run_case("sidechange-through-arc")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        SP("compensated", (20, -10), (20, 2), (28, -10), -math.pi / 2),
        L("lead-out", (28, -10), (20, -20)),
    ])
    sp = [s for s in path.segments if s.kind == "spiral"][0].geom
    assert (sp.rho0, sp.rho1) == pytest.approx((12, 8), abs=TOL)


def test_side_change_in_reversal():
    # Decision: 180-degree arc on the old (left) side about (20,0), passing
    # ahead of the corner (22,0), then the change over the next move.
    path = run_case("sidechange-reversal")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (20, -2), -math.pi),
        L("compensated", (20, -2), (10, 2)),
        L("lead-out", (10, 2), (0, 10)),
    ])
    arc = [s for s in path.segments if s.role.value == "corner"][0].geom
    assert np.allclose(arc.point(arc.length / 2), (22, 0), atol=1e-9)


def test_outside_corner_break_angle():
    r = 2.0
    c2, s2 = math.cos(math.radians(2)), math.sin(math.radians(2))
    c25, s25 = math.cos(math.radians(2.5)), math.sin(math.radians(2.5))
    q2 = np.array([20 + 20 * c2, -20 * s2])
    q3 = q2 + 20 * np.array([c25, -s25])
    n2 = np.array([s2, c2])      # left normal of (c2, -s2)
    n3 = np.array([s25, c25])
    # 2 degrees: cos 2 < 0.9998: sharp, arc about (20,0) from 90 deg by -2 deg.
    a_end = (20 + r * math.cos(math.radians(88)), r * math.sin(math.radians(88)))
    # 0.5 degrees: shallow, the offsets meet at the miter point
    # X = Q + r*(n2 + n3)/(1 + n2.n3).
    x = q2 + r * (n2 + n3) / (1 + n2 @ n3)
    e3 = q3 + r * n3
    check(run_case("outside-break"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), a_end, -math.radians(2)),
        L("compensated", a_end, tuple(x)),
        L("compensated", tuple(x), tuple(e3)),
        # lead-out -Y: right turn by 87.5 deg, outside: arc to Q3 + (2, 0)
        A("corner", tuple(q3), tuple(e3), tuple(q3 + [2, 0]), -math.radians(87.5)),
        L("lead-out", tuple(q3 + [2, 0]), tuple(q3 + [0, -10])),
    ])


def test_outside_corner_break_angle_is_isx99():
    # With Isx99 = 0.99999 the 0.5-degree corner is sharp too: two corner arcs.
    case = load_case(bundled_cases_dir() / "outside-break")
    path = compensate(ccopt.read_program(case.program), "pmac", break_cos=0.99999)
    assert sum(s.role.value == "corner" for s in path.segments) == 3
    path = compensate(ccopt.read_program(case.program), "pmac", break_cos=0.999)
    # cos 2 = 0.99939 >= 0.999: both shallow, only the lead-out arc remains
    assert sum(s.role.value == "corner" for s in path.segments) == 1


def test_radius_change_is_introduced_over_the_next_move():
    check(run_case("radius-change"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        # r 2 -> 3 over (20,0)->(40,0): from (20,2) to the r=3 inside corner
        # x = 40 - 3, y = 3.
        L("compensated", (20, 2), (37, 3)),
        L("compensated", (37, 3), (37, 17)),
        # r 3 -> 0 over (40,20)->(20,20): from the r=3 corner to the programmed point
        L("compensated", (37, 17), (20, 20)),
        L("compensated", (20, 20), (0, 20)),
        L("lead-out", (0, 20), (-10, 20)),
    ])


def test_short_move_runs_backwards_and_overcuts():
    path = run_case("short-move-overcut")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (18, 2)),          # inside corner: y=2 meets x=18
        L("compensated", (18, 2), (18, 1)),         # the 1 mm step runs backwards
        A("corner", (20, 1), (18, 1), (20, 3), -math.pi / 2),
        L("compensated", (20, 3), (40, 3)),
        L("lead-out", (40, 3), (50, 1)),
    ])
    # The tool centre reaches (18,1): 1 from the first programmed move (y=0),
    # so PMAC overcuts by r - 1 = 1 there; the verifier reports it.
    back = path.segments[3]
    assert back.geom.end[1] - 0.0 == pytest.approx(1.0, abs=TOL)


def test_concave_arc_smaller_than_cutter_is_an_error():
    case = load_case(bundled_cases_dir() / "concave-arc-too-small")
    prog = ccopt.read_program(case.program)
    with pytest.raises(ccopt.ProgramError) as err:
        compensate(prog, "pmac")
    assert err.value.line == 8  # the CIRCLE2 move: "X10 Y2 I0 J1"
    assert "radius 1" in str(err.value) and "cutter radius 2" in str(err.value)


def test_z_plunges_run_at_the_compensated_corner_point():
    path = run_case("z-plunges")
    segs = [s for s in path.segments if s.role.value != "rapid"]
    pts = [(s.kind, s.start, s.end, s.w0, s.w1) for s in segs]
    expected = [
        ("line", (-10, 0), (0, 2), 5, 5),        # lead-in (tangent: P + r*o(t_next))
        ("line", (0, 2), (0, 2), 5, -2),         # plunge at the lead-in's end
        ("line", (0, 2), (18, 2), -2, -2),       # inside corner at (18,2)
        ("line", (18, 2), (18, 2), -2, -4),      # Z-4 at the intersection point
        ("line", (18, 2), (18, 20), -4, -4),
        ("arc", (18, 20), (20, 22), -4, -4),     # outside corner arc first ...
        ("line", (20, 22), (20, 22), -4, -6),    # ... then Z-6
        ("line", (20, 22), (40, 22), -6, -6),
        ("line", (40, 22), (50, 20), -6, -6),    # lead-out
        ("line", (50, 20), (50, 20), -6, 5),     # Z5 after CC0, at the programmed point
    ]
    assert len(pts) == len(expected)
    for (k, s, e, w0, w1), (k2, s2_, e2, v0, v1) in zip(pts, expected):
        assert k == k2
        assert np.allclose(s, s2_, atol=TOL) and np.allclose(e, e2, atol=TOL)
        assert (w0, w1) == pytest.approx((v0, v1), abs=TOL)
    assert len(path.dwells) == 1 and path.dwells[0][1] == pytest.approx(0.1)
    # the dwell happens right after the plunge
    idx = path.dwells[0][0]
    assert path.segments[idx - 1].w1 == pytest.approx(-2)
    # the outside corner arc: about the programmed corner P = (20,20), radius
    # r = 2, from P + r*o(t_in) (t_in = +Y: (18,20)) to P + r*o(t_out)
    # (t_out = +X: (20,22)), turning right with the path: -90 degrees
    arc = [s for s in segs if s.kind == "arc"][0]
    assert arc.geom.center == pytest.approx((20.0, 20.0), abs=TOL)
    assert arc.geom.radius == pytest.approx(2.0, abs=TOL)
    assert arc.geom.sweep == pytest.approx(-math.pi / 2, abs=TOL)


def test_inside_corners_line_arc_arc_line():
    r = 1.0
    Rp = math.sqrt(50) + r          # clockwise arcs with CC1: tool outside
    Rp2 = Rp * Rp
    c1, c2 = (15, -5), (25, -5)
    x1 = (15 - math.sqrt(Rp2 - 36), 1)              # y = 1 meets circle 1 (nearest root)
    x2 = (20, -5 + math.sqrt(Rp2 - 25))             # circles meet on x = 20 (upper root)
    x3 = (29, -5 + math.sqrt(Rp2 - 16))             # x = 29 meets circle 2 (upper root)

    def sweep(c, s, e, th_s, prog_sweep):
        def wrap(a):
            return (a + math.pi) % (2 * math.pi) - math.pi
        return prog_sweep + wrap(angle(c, e) - (th_s + prog_sweep)) - wrap(angle(c, s) - th_s)

    check(run_case("inside-corners"), [
        L("lead-in", (-10, 0), (0, 1)),
        L("compensated", (0, 1), x1),
        A("compensated", c1, x1, x2, sweep(c1, x1, x2, 3 * math.pi / 4, -math.pi / 2)),
        A("compensated", c2, x2, x3, sweep(c2, x2, x3, 3 * math.pi / 4, -math.pi / 2)),
        L("compensated", x3, (29, 9)),
        L("compensated", (29, 9), (10, 9)),
        A("corner", (10, 10), (10, 9), (9, 10), -math.pi / 2),
        L("lead-out", (9, 10), (10, 20)),
    ])


def test_pocket_every_segment():
    # CC1 (tool inside, counter-clockwise), r = 3. Concave R6 corners give tool
    # arcs of radius 3; the lines' offsets are x=3, y=3, x=57, y=37; the boss
    # (25..35 x 0..8) gives inside corners (22,3), (38,3) and outside arcs about
    # (25,8) and (35,8); the clockwise R10 bulge about (30,40) gives a tool arc
    # of radius 13 meeting y = 37 at x = 30 +- sqrt(13^2 - 3^2).
    q = math.sqrt(13 ** 2 - 3 ** 2)
    bulge_sweep = -math.pi + 2 * math.atan2(3, q)
    P = math.pi
    check(run_case("pocket"), [
        L("uncompensated", (20, 20), (20, 20)),           # Z-2 plunge
        L("lead-in", (20, 20), (3, 20)),                  # inside: P + 3*o(-Y)
        L("compensated", (3, 20), (3, 6)),
        A("compensated", (6, 6), (3, 6), (6, 3), P / 2),
        L("compensated", (6, 3), (22, 3)),
        L("compensated", (22, 3), (22, 8)),
        A("corner", (25, 8), (22, 8), (25, 11), -P / 2),
        L("compensated", (25, 11), (35, 11)),
        A("corner", (35, 8), (35, 11), (38, 8), -P / 2),
        L("compensated", (38, 8), (38, 3)),
        L("compensated", (38, 3), (54, 3)),
        A("compensated", (54, 6), (54, 3), (57, 6), P / 2),
        L("compensated", (57, 6), (57, 34)),
        A("compensated", (54, 34), (57, 34), (54, 37), P / 2),
        L("compensated", (54, 37), (30 + q, 37)),
        A("compensated", (30, 40), (30 + q, 37), (30 - q, 37), bulge_sweep),
        L("compensated", (30 - q, 37), (6, 37)),
        A("compensated", (6, 34), (6, 37), (3, 34), P / 2),
        L("compensated", (3, 34), (3, 20)),
        L("lead-out", (3, 20), (20, 20)),                 # inside lead-out
        L("uncompensated", (20, 20), (20, 20)),           # Z5 retract
    ])
    bulge = next(s for s in run_case("pocket").segments
                 if s.kind == "arc" and np.allclose(s.geom.center, (30, 40)))
    assert bulge.geom.radius == pytest.approx(13, abs=TOL)


def test_profile_every_segment():
    # CC1 (tool outside, clockwise), r = 3. Tangent CIRCLE lead-in about
    # (-10,15): spiral from rho 10 to rho 10 - 3 = 7 (counter-clockwise with CC1
    # is toward the centre); convex R5 corners give tool arcs of radius 8; the
    # V-notch gives outside arcs about (15,30) and (25,30) (45 degrees) and the
    # inside corner (20, 25 + 3*sqrt2); the sharp corner (0,0) an arc to (-3,0).
    P = math.pi
    h = 3 * H
    check(run_case("profile"), [
        L("uncompensated", (-10, 5), (-10, 5)),           # Z-3 plunge
        SP("lead-in", (-10, 15), (-10, 5), (-3, 15), P / 2),
        L("compensated", (-3, 15), (-3, 25)),
        A("compensated", (5, 25), (-3, 25), (5, 33), -P / 2),
        L("compensated", (5, 33), (15, 33)),
        A("corner", (15, 30), (15, 33), (15 + h, 30 + h), -P / 4),
        L("compensated", (15 + h, 30 + h), (20, 25 + 3 * S2)),
        L("compensated", (20, 25 + 3 * S2), (25 - h, 30 + h)),
        A("corner", (25, 30), (25 - h, 30 + h), (25, 33), -P / 4),
        L("compensated", (25, 33), (35, 33)),
        A("compensated", (35, 25), (35, 33), (43, 25), -P / 2),
        L("compensated", (43, 25), (43, 5)),
        A("compensated", (35, 5), (43, 5), (35, -3), -P / 2),
        L("compensated", (35, -3), (0, -3)),
        A("corner", (0, 0), (0, -3), (-3, 0), -P / 2),
        L("compensated", (-3, 0), (-3, 15)),
        SP("lead-out", (-10, 15), (-3, 15), (-10, 25), P / 2),
        L("uncompensated", (-10, 25), (-10, 25)),         # Z5 retract
    ])
    segs = run_case("profile").segments
    spirals = [s.geom for s in segs if s.kind == "spiral"]
    assert [(g.rho0, g.rho1) for g in spirals] == [pytest.approx((10, 7)), pytest.approx((7, 10))]
    for c in [(5, 25), (35, 25), (35, 5)]:
        arc = next(s for s in segs if s.kind == "arc" and np.allclose(s.geom.center, c))
        assert arc.geom.radius == pytest.approx(8, abs=TOL)


def test_gcode_twin_of_the_pocket_gives_the_same_path():
    # G41.1 D6 (diameter) read through the G-code reader and compensated PMAC
    # style is the same tool path as the PMAC program with CC1 CCR3.
    folder = bundled_cases_dir() / "pocket"
    pmc = compensate(ccopt.read_program(folder / "pocket.pmc"), "pmac")
    nc = compensate(ccopt.read_program(folder / "pocket.nc"), "pmac")
    a = [s for s in pmc.segments if s.role.value != "rapid"]
    b = [s for s in nc.segments if s.role.value != "rapid"]
    assert [(s.kind, s.role) for s in a] == [(s.kind, s.role) for s in b]
    for x, y in zip(a, b):
        assert np.allclose(x.start, y.start, atol=TOL) and np.allclose(x.end, y.end, atol=TOL)
        assert x.feed == pytest.approx(y.feed)   # F1800 per minute = 30 per second


def test_isx99_written_in_the_pmac_file_is_used(tmp_path):
    # Turbo PMAC: coordinate system 1's Isx99 is I5199. 0.99999 makes the 0.5-degree
    # corner of outside-break sharp (three corner arcs instead of two).
    src = (bundled_cases_dir() / "outside-break" / "part.pmc").read_text()
    prog_file = tmp_path / "break.pmc"
    prog_file.write_text("I5199=0.99999\n" + src)
    path = compensate(ccopt.read_program(prog_file), "pmac")
    assert sum(s.role.value == "corner" for s in path.segments) == 3
    # an explicit option wins over the file
    path = compensate(ccopt.read_program(prog_file), "pmac", break_cos=0.9998)
    assert sum(s.role.value == "corner" for s in path.segments) == 2


def test_radius_zero_runs_on_the_programmed_path(tmp_path):
    # CCR0 with CC1 on: every corner point is the programmed point, including
    # the outside corner at (10,-10) (no zero-radius arc).
    f = tmp_path / "r0.pmc"
    f.write_text("LINEAR ABS F10\nCCR0 CC1\nX10 Y0\nX10 Y-10\nX20 Y-10\nCC0\nX30 Y-10\n")
    check(compensate(ccopt.read_program(f), "pmac"), [
        L("lead-in", (0, 0), (10, 0)),
        L("compensated", (10, 0), (10, -10)),
        L("compensated", (10, -10), (20, -10)),
        L("lead-out", (20, -10), (30, -10)),
    ])


def test_radius_change_from_zero_after_the_lead_in(tmp_path):
    # CCR0 CC1: the lead-in (0,0)->(10,0) runs at r = 0, on the programmed
    # point. CCR2 before "X20 Y0" is a change 0 -> 2 introduced over that move
    # (spec rule 4): it starts at r = 0 on P = (10,0) and ends at the r = 2
    # inside corner with "X20 Y10" (left turn, CC1): y = 2 meets x = 20 - 2.
    # The outside corner at (20,10) with the lead-out gets the arc of r = 2.
    f = tmp_path / "from0.pmc"
    f.write_text("LINEAR ABS F10\nCCR0 CC1\nX10 Y0\nCCR2\nX20 Y0\nX20 Y10\nCC0\nX30 Y10\n")
    check(compensate(ccopt.read_program(f), "pmac"), [
        L("lead-in", (0, 0), (10, 0)),
        L("compensated", (10, 0), (18, 2)),
        L("compensated", (18, 2), (18, 10)),
        A("corner", (20, 10), (18, 10), (20, 12), -math.pi / 2),
        L("lead-out", (20, 12), (30, 10)),
    ])


def test_radius_change_to_zero_after_the_lead_in(tmp_path):
    # The other way: the lead-in at r = 2 (inside corner with "X20 Y0", which
    # goes on straight: it ends at P + r*o(t_next) = (10,2)), then CCR0: the
    # change 2 -> 0 runs over "X20 Y0" to the programmed point (20,0).
    f = tmp_path / "to0.pmc"
    f.write_text("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nCCR0\nX20 Y0\nX20 Y10\nCC0\nX30 Y10\n")
    check(compensate(ccopt.read_program(f), "pmac"), [
        L("lead-in", (0, 0), (10, 2)),
        L("compensated", (10, 2), (20, 0)),
        L("compensated", (20, 0), (20, 10)),
        L("lead-out", (20, 10), (30, 10)),
    ])
