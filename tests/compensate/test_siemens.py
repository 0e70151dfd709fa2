"""The ``siemens`` style: corners, NORM/KONT, smooth approach and retraction.

Every expected figure is worked out by hand here (G41: ``o(t) = (-t_y, t_x)``,
the side ``s`` of an approach arc, its centre ``Q + DISR*s*perp(t)``), never
copied from ccopt's output.
"""
from __future__ import annotations

import math

import pytest

from ccopt import AxisLimits, cli, export, plan_feed, read_program, verify
from ccopt.cases import find_case
from ccopt.compensate import STYLES, compensate
from ccopt.errors import CompensationError
from ccopt.program.gcode import read_gcode
from ccopt.program.sinumerik import read_sinumerik
from segment_expect import A, L
from segment_expect import check as check_all

PI = math.pi
R = 2.0
S2 = math.sqrt(2.0)


def check(path, expected):
    """The segments after the first move to the start point (uncompensated)."""
    check_all(path, expected, skip_roles=("rapid", "uncompensated"))


def prog(text: str):
    return read_sinumerik(text, "s.mpf")


def comp(text: str, **kw):
    kw.setdefault("radius", R)
    return compensate(prog(text), style="siemens", **kw)


def test_registered_and_default_for_sinumerik(tmp_path, capsys):
    assert "siemens" in STYLES
    f = tmp_path / "p.mpf"
    f.write_text("G1 F600 X-10 Y0\nG41 X0 Y0\nX10\nG40 X10 Y-10\n")
    assert cli.main(["compensate", str(f), "--radius", "1", "--json"]) == 0
    assert '"style":"siemens"' in capsys.readouterr().out.replace(" ", "")


# Contour start (0,0), first element along +X, G41, r = 2: Q = (0,2).
HEAD = "G1 F600 X-10 Y-10\n"


def test_norm_goes_straight_to_the_perpendicular_point():
    check(comp(HEAD + "G41 NORM X0 Y0\nX20\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, -10), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (30, -10)),
    ])


def test_kont_behind_the_contour_goes_round_the_start_point_g450():
    # lead direction (1,1)/sqrt2, then +X: a right turn, outside for G41 ("behind").
    # The lead ends at P + r*o(t_lead) = 2*(-1,1)/sqrt2, the G450 circle about
    # P = (0,0) turns by -45 degrees to (0,2). Leaving: +X then (1,-1)/sqrt2, a
    # right turn: the last move ends at (20,2), the circle about (20,0) to
    # (20,0) + 2*(1,1)/sqrt2, then straight to (30,-10).
    check(comp(HEAD + "G41 KONT G450 X0 Y0\nX20\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, -10), (-S2, S2)),
        A("corner", (0, 0), (-S2, S2), (0, 2), -PI / 4),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (20 + S2, S2), -PI / 4),
        L("lead-out", (20 + S2, S2), (30, -10)),
    ])


def test_kont_g451_meets_the_offsets():
    # the lead's offset line through (-sqrt2, sqrt2) along (1,1) meets y = 2 at
    # x = 2 - 2 sqrt2; leaving, y = 2 meets the G40 move's offset line through
    # (20 + sqrt2, sqrt2) along (1,-1) at x = 20 + 2 sqrt2 - 2
    check(comp(HEAD + "G41 KONT G451 X0 Y0\nX20\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, -10), (2 - 2 * S2, 2)),
        L("compensated", (2 - 2 * S2, 2), (20 + 2 * S2 - 2, 2)),
        L("lead-out", (20 + 2 * S2 - 2, 2), (30, -10)),
    ])


def test_kont_in_front_of_the_contour_is_norm():
    # from (-10, 10): lead direction (1,-1)/sqrt2 then +X turns left: inside,
    # as NORM; KONT is modal: the G40 move's right turn goes round (20,0)
    check(comp("G1 F600 X-10 Y10\nG41 KONT X0 Y0\nX20\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, 10), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (20 + S2, S2), -PI / 4),
        L("lead-out", (20 + S2, S2), (30, -10)),
    ])
    # NORM on the G40 block: straight from (20,2)
    check(comp("G1 F600 X-10 Y10\nG41 KONT X0 Y0\nX20\nG40 NORM X30 Y-10\n"), [
        L("lead-in", (-10, 10), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (30, -10)),
    ])


BOX = "G1 F600 X-10 Y0\nG41 X0 Y0\nX20\n"


def test_g450_outside_corner_circle_and_inside_intersection():
    # +X then -Y (right turn, outside): circle about (20,0) from (20,2) to (22,0);
    # -Y then -X (right, outside): circle about (20,-10) from (22,-10) to (20,-12);
    # -X then +Y at (10,-10) (right turn? (-1,0) x (0,1) = -1: right, outside)...
    # use a left turn instead: -X then -Y at (10,-10): (-1,0)x(0,-1) = 1: inside,
    # offsets y = -12 and x = 10 + 2 meet at (12,-12).
    check(comp(BOX + "G450 Y-10\nX10\nY-20\nG40 X0 Y-20\n"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (22, 0), -PI / 2),
        L("compensated", (22, 0), (22, -10)),
        A("corner", (20, -10), (22, -10), (20, -12), -PI / 2),
        L("compensated", (20, -12), (12, -12)),
        L("compensated", (12, -12), (12, -20)),
        L("lead-out", (12, -20), (0, -20)),
    ])


def test_g451_intersection_below_the_corner_limit_circle_beyond():
    # 90 degrees (< 100): the offsets y = 2 and x = 22 meet at (22,2)
    check(comp(BOX + "G451 Y-10\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (22, 2)),
        L("compensated", (22, 2), (22, -10)),
        L("lead-out", (22, -10), (30, -10)),
    ])
    # 120 degrees (>= 100): G450's circle. t_out = (-1/2, -sqrt3/2); the
    # circle about (20,0) from (20,2) to (20,0) + 2*(-sqrt3/2, 1/2)... o(t_out)
    # for G41 = (sqrt3/2, -1/2): to (20 + sqrt3, -1), sweep -120 degrees.
    h = math.sqrt(3) / 2
    end = (20 - 5, -10 * h)
    path = comp(BOX + f"G451 X{end[0]} Y{end[1]!r}\nG40 X0 Y-20\n")
    arc = [s for s in path.segments if s.role.value == "corner"]
    assert len(arc) == 1
    d = arc[0].to_json()
    assert d["center"] == pytest.approx([20, 0]) and d["sweep"] == pytest.approx(-2 * PI / 3)
    assert d["end"] == pytest.approx([20 + 2 * h, -1.0])
    # the corner limit is an option: at 130 degrees the 120-degree corner meets
    path = comp(BOX + f"G451 X{end[0]} Y{end[1]!r}\nG40 X0 Y-20\n", corner_limit=130)
    assert not [s for s in path.segments if s.role.value == "corner"]


def test_disc_100_is_the_intersection_and_between_is_refused():
    check(comp(BOX + "G450 DISC=100 Y-10\nG40 X30 Y-10\n"), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (22, 2)),
        L("compensated", (22, 2), (22, -10)),
        L("lead-out", (22, -10), (30, -10)),
    ])
    with pytest.raises(CompensationError) as info:
        comp(BOX + "G450 DISC=50 Y-10\nG40 X30 Y-10\n")
    assert info.value.line == 4 and "DISC=50" in str(info.value)


def test_kontt_is_refused_where_it_is_met():
    with pytest.raises(CompensationError) as info:
        comp("G1 F600 X-10 Y-10\nG41 KONTT X0 Y0\nX20\nG40 X30 Y-10\n")
    assert info.value.line == 2 and "KONTT" in str(info.value)


# SAR: contour start (0,0), first element +X, G41, r = 2: Q = (0,2), G140: s = +1.
SAR = "G1 F600 X-20 Y-20\nG41 {kind} DISR=5 X0 Y0\nX20\nG40 X20 Y-20\n"


def test_g147_straight_line_of_disr_plus_radius():
    # P3 = Q - (DISR + r) * t = (-7, 2)
    check(comp(SAR.format(kind="G147")), [
        L("lead-in", (-20, -20), (-7, 2)),
        L("lead-in", (-7, 2), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (20, -20)),
    ])


def test_g247_quadrant_centre_and_start_from_disr():
    # C = Q + 5*(0,1) = (0,7); the quadrant ends at (0,2) (angle -90) turning
    # counter-clockwise, so it starts at angle 180: (-5,7)
    check(comp(SAR.format(kind="G247")), [
        L("lead-in", (-20, -20), (-5, 7)),
        A("lead-in", (0, 7), (-5, 7), (0, 2), PI / 2),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (20, -20)),
    ])


def test_g347_semicircle_and_g143_side():
    # semicircle about (0,7) from angle 90, (0,12), to (0,2)
    check(comp(SAR.format(kind="G347")), [
        L("lead-in", (-20, -20), (0, 12)),
        A("lead-in", (0, 7), (0, 12), (0, 2), PI),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (20, -20)),
    ])
    # G143: the start (-20,-20) lies right of +X: s = -1, C = (0,2) - 5*(0,1) =
    # (0,-3), clockwise from angle 180, (-5,-3), to (0,2)
    check(comp(SAR.format(kind="G247 G143")), [
        L("lead-in", (-20, -20), (-5, -3)),
        A("lead-in", (0, -3), (-5, -3), (0, 2), -PI / 2),
        L("compensated", (0, 2), (20, 2)),
        L("lead-out", (20, 2), (20, -20)),
    ])


def test_g248_retraction_quadrant():
    # the contour ends at (20,0) along +X: A = (20,2); C = (20,7); the quadrant
    # leaves counter-clockwise from angle -90 to 0: (25,7); then to P0 (20,-20)
    text = "G1 F600 X-10 Y0\nG41 X0 Y0\nX20\nG40 G248 DISR=5 X20 Y-20\n"
    check(comp(text), [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("lead-out", (20, 7), (20, 2), (25, 7), PI / 2),
        L("lead-out", (25, 7), (20, -20)),
    ])


def test_manual_example_g147_discl():
    # Programming Manual 2.10.4, "Programming of end point P4 for approach":
    # $TC_DP6[1,1]=7, N10 G90 G0 X0 Y0 Z30 D1 T1, N20 X10,
    # N30 G41 G147 DISCL=3 DISR=13 X40 Y-10 Z0 F1000, N50 G1 X50 (G340, G140).
    # Q = (40,-10) + 7*(0,1) = (40,-3); P3 = Q - (13 + 7)*(1,0) = (20,-3);
    # P0 (10,0,30) -> P1 (20,-3,30) -> P3 (20,-3,3) in rapid (G0 in force),
    # then the line to Q from Z3 down to Z0 at F1000.
    text = ("$TC_DP1[1,1]=120\n$TC_DP6[1,1]=7\nN10 G90 G0 X0 Y0 Z30 D1 T1\nN20 X10\n"
            "N30 G41 G147 DISCL=3 DISR=13 X40 Y-10 Z0 F1000\nN50 G1 X50\nN60 G40 X60 Y-30\n")
    path = compensate(prog(text), style="siemens")
    segs = [(s.kind, s.role.value, s.start, s.end, round(s.w0, 9), round(s.w1, 9), s.feed)
            for s in path.segments if s.block.source.line == 5]
    assert segs == [
        ("line", "rapid", (10.0, 0.0), (20.0, -3.0), 30.0, 30.0, None),
        ("line", "rapid", (20.0, -3.0), (20.0, -3.0), 30.0, 3.0, None),
        ("line", "lead-in", (20.0, -3.0), (40.0, -3.0), 3.0, 0.0, pytest.approx(1000 / 60)),
    ]


def test_manual_example_end_point_in_the_next_block():
    # the manual's first form: N30 G41 G147 DISCL=3 DISR=13 Z=0 F1000, N40 G1 X40 Y-10
    # (and its third: the Z in N40 too): the same sub-moves as the one-block form
    one = ("$TC_DP6[1,1]=7\nN10 G90 G0 X0 Y0 Z30 D1 T1\nN20 X10\n"
           "N30 G41 G147 DISCL=3 DISR=13 X40 Y-10 Z0 F1000\nN50 G1 X50\nN60 G40 X60 Y-30\n")
    two = ("$TC_DP6[1,1]=7\nN10 G90 G0 X0 Y0 Z30 D1 T1\nN20 X10\n"
           "N30 G41 G147 DISCL=3 DISR=13 Z=0 F1000\nN40 G1 X40 Y-10\nN50 G1 X50\n"
           "N60 G40 X60 Y-30\n")
    three = two.replace("Z=0 F1000\nN40 G1 X40 Y-10", "F1000\nN40 G1 X40 Y-10 Z0")

    def moves(text):
        return [(s.kind, s.role.value, s.start, s.end, round(s.w0, 9), round(s.w1, 9), s.feed)
                for s in compensate(prog(text), style="siemens").segments]
    assert moves(two) == moves(one) and moves(three) == moves(one)
    with pytest.raises(Exception) as info:
        prog("G41 G147 DISR=2 F100 Z0\nG1 Z5\nX5\n")
    assert "nothing may move" in str(info.value)


def test_manual_example_w1_quadrant_with_offn():
    # Function Manual Basic Functions W1 (6FC5397-0BP10-2BA0, 11/2006), 2.4,
    # "Contour example 2" (Figure 2-26), the program as printed there. The
    # manual's note: radius 10 + OFFN 5 = 15 effective, so the tool centre
    # path's radius is DISR = 10 in the approach and 5 in the retraction.
    # By hand: P4 = (30,-10) from N30, the contour leaves along +X, G41 puts
    # the tool left, Q = P4 + 15*(0,1) = (30,5); the G247 quadrant ends at Q
    # along +X: centre Q + 10*(0,1) = (30,15), start P3 = (20,15). G341: P0
    # (0,0,20) -> (20,15,20) -> DISCL=AC(7) -> Z0 at FAD 200/min, rapids
    # before (G0 in force), the quadrant at F1500. Retraction G248 G340 from
    # Q' = (50,-10) + 15*(0,1) = (50,5): quadrant about (50,10) to (55,10),
    # a helix up to DISCL=6 above the contour's Z2, then up to P0's Z20 and
    # across to P0 = (70,0).
    text = ("$TC_DP1[1,1]=120\n$TC_DP6[1,1]=10\nN10 G0 X0 Y0 Z20 G64 D1 T1 OFFN = 5\n"
            "N20 G41 G247 G341 Z0 DISCL = AC(7) DISR = 10 F1500 FAD=200\n"
            "N30 G1 X30 Y-10\nN40 X40 Z2\nN50 X50\n"
            "N60 G248 G340 X70 Y0 Z20 DISCL = 6 DISR = 5 G40 F10000\nN70 X80 Y0\nN80 M 30\n")
    segs = compensate(prog(text), style="siemens").segments
    ap = [s for s in segs if s.block.source.line == 5]
    assert [(s.kind, s.start, s.end, s.w0, s.w1) for s in ap] == [
        ("line", (0, 0), pytest.approx((20, 15)), 20, 20),
        ("line", pytest.approx((20, 15)), pytest.approx((20, 15)), 20, 7),
        ("line", pytest.approx((20, 15)), pytest.approx((20, 15)), 7, 0),
        ("arc", pytest.approx((20, 15)), pytest.approx((30, 5)), 0, 0)]
    assert [s.feed for s in ap] == [None, None, pytest.approx(200 / 60), pytest.approx(25.0)]
    assert ap[3].geom.radius == pytest.approx(10.0)
    assert ap[3].geom.center == pytest.approx((30, 15))
    contour = [(s.start, s.end, s.w1) for s in segs if s.block.source.line in (6, 7)]
    assert contour == [((30, 5), (40, 5), 2), ((40, 5), (50, 5), 2)]
    ret = [s for s in segs if s.block.source.line == 8]
    assert [(s.kind, s.start, s.end, s.w0, s.w1) for s in ret] == [
        ("arc", pytest.approx((50, 5)), pytest.approx((55, 10)), 2, pytest.approx(8)),
        ("line", pytest.approx((55, 10)), pytest.approx((55, 10)), pytest.approx(8), 20),
        ("line", pytest.approx((55, 10)), pytest.approx((70, 0)), 20, 20)]
    assert ret[0].geom.radius == pytest.approx(5.0)
    assert ret[0].geom.center == pytest.approx((50, 10))
    assert ret[0].feed == pytest.approx(10000 / 60)


def test_g341_infeed_at_fad_then_the_curve_in_the_plane():
    # P0 at Z10: P1 above P3 at Z10, P2 at DISCL=3, P3 at Z0 at FAD (300/min =
    # 5/s), then the quadrant in the plane
    text = ("G1 F600 X-20 Y-20 Z10\nG41 G247 G341 DISR=5 DISCL=3 FAD=300 X0 Y0 Z0\nX20\n"
            "G40 X20 Y-20\n")
    segs = [(s.kind, s.start, s.end, s.w0, s.w1, s.feed)
            for s in comp(text).segments if s.block.source.line == 2]
    assert segs == [
        ("line", (-20.0, -20.0), pytest.approx((-5.0, 7.0)), 10.0, 10.0, 10.0),
        ("line", pytest.approx((-5.0, 7.0)), pytest.approx((-5.0, 7.0)), 10.0, 3.0, 10.0),
        ("line", pytest.approx((-5.0, 7.0)), pytest.approx((-5.0, 7.0)), 3.0, 0.0, 5.0),
        ("arc", pytest.approx((-5.0, 7.0)), pytest.approx((0.0, 2.0)), 0.0, 0.0, 10.0),
    ]


def test_sar_option_puts_a_lead_on_a_gcode_program_and_verifies():
    gcode = read_gcode("G90 F600\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nX20\nY-20\nX0\nY0\n"
                       "G40 G1 X-10 Y0\n", "g.nc")
    for kind, disr in (("G147", 3.0), ("G247", 3.0), ("G347", 3.0)):
        path = compensate(gcode, style="siemens", radius=1.0, sar=kind, disr=disr)
        roles = [s.role.value for s in path.segments]
        assert roles.count("lead-in") >= 2 and roles.count("lead-out") >= 2, (kind, roles)
        assert verify(path, gcode).ok, kind


def test_other_styles_compensate_a_sinumerik_program():
    text = ("T1 D1\n$TC_DP6[1,1]=1\nG0 X-20 Y-20\nG1 F600 G41 G247 DISR=4 X0 Y0\nX30\n"
            "G3 X30 Y20 CR=10\nG1 X0\nY0\nG40 G248 DISR=4 X-20 Y-20\n")
    p = prog(text)
    for style in ("pmac", "fagor", "linuxcnc", "siemens"):
        path = compensate(p, style=style)
        assert path.segments, style


def test_options_are_checked():
    for bad in ({"corner": "G452"}, {"approach": "KONTC"}, {"sar": "G147"},
                {"sar": "G247", "disr": 0.0}, {"corner_limit": 0.0}):
        with pytest.raises(Exception):
            compensate(prog(BOX + "G40 X30 Y0\n"), style="siemens", radius=1.0, **bad)


def test_manual_example_kont_g450_outside_corners():
    # Programming Manual 2.10.3, example: N10 G17 T1 G0 X35 Y0 Z0 F500, N20 G1 Z-5,
    # N30 G41 KONT G450 X10 Y10, N40 Y60, N50 X50 Y30, N60 X10 Y10 (no G40: the
    # program ends while on). Radius 5 given (the manual names no radius).
    text = ("N10 G17 T1 G0 X35 Y0 Z0 F500\nN20 G1 Z-5\nN30 G41 KONT G450 X10 Y10\nN40 Y60\n"
            "N50 X50 Y30\nN60 X10 Y10\n")
    r = 5.0
    n = math.sqrt(725.0)
    t_lead = (-25 / n, 10 / n)                 # (35,0) -> (10,10)
    A0 = (10 + r * -t_lead[1], 10 + r * t_lead[0])   # P + r*o(t_lead), o(t) = (-t_y, t_x)
    # behind the contour: the lead turns right into +Y (outside for G41)
    s5 = math.sqrt(5.0)
    expected = [
        L("lead-in", (35, 0), A0),
        A("corner", (10, 10), A0, (5, 10), math.atan2(-25, 10)),
        L("compensated", (5, 10), (5, 60)),
        # +Y then (0.8,-0.6): right turn, the circle about (10,60) to (10,60) + 5*(0.6,0.8)
        A("corner", (10, 60), (5, 60), (13, 64), math.atan2(-0.8, -0.6)),
        L("compensated", (13, 64), (53, 34)),
        # (0.8,-0.6) then (-2,-1)/sqrt5: right turn, about (50,30) to (50,30) + 5*(1,-2)/sqrt5
        A("corner", (50, 30), (53, 34), (50 + s5, 30 - 2 * s5), math.atan2(-2, -1)),
        L("compensated", (50 + s5, 30 - 2 * s5), (10 + s5, 10 - 2 * s5)),
        # the program ends while on: cancelled in place, back to the programmed end
        L("lead-out", (10 + s5, 10 - 2 * s5), (10, 10)),
    ]
    check(compensate(prog(text), style="siemens", radius=r), expected)


def test_transition_circle_belongs_to_the_next_block():
    # +X at F600 (10/s), then -Y at F1200 (20/s): the circle runs at 20/s, carried
    # by the -Y block (line 4)
    path = comp(BOX + "G450 Y-10 F1200\nG40 X30 Y-10\n")
    arc = [s for s in path.segments if s.role.value == "corner"][0]
    assert arc.feed == pytest.approx(20.0) and arc.block.source.line == 4


def test_sar_plate_compensates_verifies_times_and_exports(tmp_path):
    case = find_case("sinumerik-sar-plate")
    p = read_program(case.program)
    path = compensate(p, style="siemens")
    assert verify(path, p).ok
    prof = plan_feed(path, AxisLimits(case.vmax, case.amax))
    assert prof.duration > 0
    for suffix in (".nc", ".pmc"):
        res = export(path, tmp_path / f"plate{suffix}", program=p)
        assert res.verified and res.roundtrip_error < 1e-6, (suffix, res.to_json())
