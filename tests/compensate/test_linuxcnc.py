"""The ``linuxcnc`` style on hand-worked programs.

Every expected figure is derived here from the program's geometry with the
rules of LinuxCNC's interpreter (spec "LinuxCNC style"): ``o(t) = k*(-t_y, t_x)``
(``k = +1`` for G41, left), ``G41.1 D`` is the tool DIAMETER, entry to
``P + r*n`` with ``n`` perpendicular to ``P - S``, corner arcs about the
programmed corner for outside corners, the previous end pulled back to the
offsets' intersection for inside corners. Never copied from ccopt's output.
"""
from __future__ import annotations

import math

import pytest

from ccopt.compensate import STYLES, compensate
from ccopt.compensate.linuxcnc import CONCAVE_TOLERANCE, find_turn
from ccopt.program.gcode import read_gcode
from segment_expect import L, A, check

TOL = 1e-9
PI = math.pi


def comp(text: str, **kw):
    return compensate(read_gcode(text, "t.ngc"), style="linuxcnc", **kw)


def test_registered():
    assert "linuxcnc" in STYLES


def test_find_turn_conventions():
    c = (0.0, 0.0)
    assert find_turn((1, 0), c, 1, (0, 1)) == pytest.approx(PI / 2)
    assert find_turn((1, 0), c, -1, (0, 1)) == pytest.approx(-3 * PI / 2)
    assert find_turn((1, 0), c, 1, (1, 0)) == pytest.approx(2 * PI)    # same point: a full turn
    assert find_turn((1, 0), c, -2, (1, 0)) == pytest.approx(-4 * PI)
    assert find_turn((1, 0), c, 0, (0, 1)) == 0.0


PROLOGUE = "G21 G17 F60\nG0 X0 Y-10\nG41.1 D2\n"   # r = 1, left


def test_entry_outside_corner_and_exit():
    # Entry S=(0,-10) -> P=(0,0): n = left of +Y = (-1,0), ends at (-1,0).
    # +Y then +X turns right: outside for the left side: a clockwise arc about
    # P to P + r*o(+X) = (0,1). Exit after G40 from the offset end (10,1)
    # straight to the programmed (10,-10).
    path = comp(PROLOGUE + "G1 X0 Y0\nG1 X10 Y0\nG40\nG1 X10 Y-10\n")
    check(path, [
        L("lead-in", (0, -10), (-1, 0)),
        A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
        L("compensated", (0, 1), (10, 1)),
        L("lead-out", (10, 1), (10, -10)),
    ])


def test_entry_pulled_back_by_inside_corner():
    # +Y then -X turns left: inside. The entry's offset is the line through its
    # end point parallel to P - S (x = -1); the next offset is y = -1: the entry
    # ends at (-1,-1), and the next move starts there.
    path = comp(PROLOGUE + "G1 X0 Y0\nG1 X-10 Y0\nG40\nG1 X-10 Y-10\n")
    check(path, [
        L("lead-in", (0, -10), (-1, -1)),
        L("compensated", (-1, -1), (-10, -1)),
        L("lead-out", (-10, -1), (-10, -10)),
    ])


def test_entry_not_perpendicular_to_the_contour():
    # Entry from (-10,-10) to (0,0): n = left of (1,1)/sqrt2 = (-1,1)/sqrt2.
    # Then +X: the turn from 45 deg to 0 is to the right: outside, an arc about
    # (0,0) from P + r*n to (0,1), clockwise by 45 degrees.
    h = 1 / math.sqrt(2)
    path = comp("G21 F60\nG0 X-10 Y-10\nG41.1 D2\nG1 X0 Y0\nG1 X10 Y0\nG40\nG1 X10 Y-5\n")
    check(path, [
        L("lead-in", (-10, -10), (-h, h)),
        A("corner", (0, 0), (-h, h), (0, 1), -PI / 4),
        L("compensated", (0, 1), (10, 1)),
        L("lead-out", (10, 1), (10, -5)),
    ])


def test_right_side_and_negative_diameter_flip():
    # G42.1 D2 and G41.1 D-2 are both right, r = 1: o(+Y) = (1,0); +Y then +X
    # turns right: inside for the right side: x = 1 and y = -1 meet at (1,-1).
    want = [
        L("lead-in", (0, -10), (1, -1)),
        L("compensated", (1, -1), (10, -1)),
        L("lead-out", (10, -1), (10, -10)),
    ]
    for on in ("G42.1 D2", "G41.1 D-2"):
        check(comp(f"G21 F60\nG0 X0 Y-10\n{on}\nG1 X0 Y0\nG1 X10 Y0\nG40\nG1 X10 Y-10\n"), want)


def test_g0_outside_corner_is_a_straight_traverse():
    # LinuxCNC has no arc traverse: at an outside corner of a G0 the tool goes
    # straight (a traverse) to the arc's end point; the G0 itself stays a
    # traverse (feed None). The G1 that follows gets a real corner arc.
    # Entry (-1,0); +Y then +X (G0): right turn, outside: traverse (-1,0) ->
    # (0,1), traverse to (10,1); +X then -Y (G1): right turn, outside: arc
    # about (10,0) to (11,0), feed to (11,-5); exit to (20,-5).
    path = comp(PROLOGUE + "G1 X0 Y0\nG0 X10 Y0\nG1 X10 Y-5\nG40\nG1 X20 Y-5\n")
    check(path, [
        L("lead-in", (0, -10), (-1, 0)),
        L("corner", (-1, 0), (0, 1)),
        L("compensated", (0, 1), (10, 1)),
        A("corner", (10, 0), (10, 1), (11, 0), -PI / 2),
        L("compensated", (11, 0), (11, -5)),
        L("lead-out", (11, -5), (20, -5)),
    ])
    segs = [s for s in path.segments if s.role.value != "rapid"]
    assert [s.feed is None for s in segs] == [False, True, True, False, False, False]


def test_arc_entry_inside_and_outside():
    # G3 from S=(0,0) about (5,0) to E=(10,0), tool left = inside the arc:
    # end point E + r*(C - E)/|C - E| = (9,0). The entry runs on the circle
    # through S and (9,0) whose centre lies on the line (9,0) -> C, i.e. the
    # X axis: centre (4.5,0), radius 4.5, counter-clockwise by pi.
    # Then +Y continues tangentially (beta = 0): no corner.
    check(comp("G21 F60\nG0 X0 Y0\nG41.1 D2\nG3 X10 Y0 I5 J0\nG1 X10 Y10\nG40\nG1 X20 Y10\n"), [
        A("lead-in", (4.5, 0), (0, 0), (9, 0), PI),
        L("compensated", (9, 0), (9, 10)),
        L("lead-out", (9, 10), (20, 10)),
    ])
    # G2 over the top, tool left = outside: end (11,0), centre (5.5,0), sweep -pi.
    # Then -Y continues tangentially.
    check(comp("G21 F60\nG0 X0 Y0\nG41.1 D2\nG2 X10 Y0 I5 J0\nG1 X10 Y-10\nG40\nG1 X20 Y-10\n"), [
        A("lead-in", (5.5, 0), (0, 0), (11, 0), -PI),
        L("compensated", (11, 0), (11, -10)),
        L("lead-out", (11, -10), (20, -10)),
    ])


def test_line_to_arc_outside_then_arc_to_line_inside():
    # Entry to (0,0) ends (-1,0). The G3 about (0,5) starts heading +X: a right
    # turn, outside: corner arc to (0,1); the arc runs inside (radius 4) to
    # its offset end (4,5)... but the next line (-X, a left turn: inside) pulls
    # that end back to where the tool circle (centre (0,5), radius 4) meets the
    # line's offset y = 4: x = +-sqrt(15); LinuxCNC takes the root behind the
    # centre's foot along the new direction (-X) when the tool is inside the
    # arc, i.e. x = +sqrt(15).
    s15 = math.sqrt(15)
    sweep = math.atan2(4 - 5, s15) - (-PI / 2)   # from the arc's start angle -90 deg
    check(comp(PROLOGUE + "G1 X0 Y0\nG3 X5 Y5 I0 J5\nG1 X-5 Y5\nG40\nG1 X-5 Y-5\n"), [
        L("lead-in", (0, -10), (-1, 0)),
        A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
        A("compensated", (0, 5), (0, 1), (s15, 4), sweep),
        L("compensated", (s15, 4), (-5, 4)),
        L("lead-out", (-5, 4), (-5, -5)),
    ])


def test_line_to_arc_and_arc_to_arc_inside():
    # +X line (offset y = 1), then G3 about (0,0), R 10, starting heading +Y:
    # a left turn, inside. Tool circle radius 9: y = 1 meets it at
    # x = +-sqrt(80); tool inside the arc: the root ahead of the centre along
    # +X, x = +sqrt(80).
    # Then G3 about (5,10), R 5, starting heading -Y (the first arc ends
    # heading -X): a left turn, inside. Circles (0,0) r 9 and (5,10) r 4 meet
    # at angle atan2(10,5) +- acos((81 + 125 - 16) / (2*9*sqrt(125))) about
    # (0,0); tool inside the first arc and the new arc counter-clockwise: the
    # one left of (0,0) -> (5,10), i.e. "+".
    s80 = math.sqrt(80)
    ang = math.atan2(10, 5) + math.acos((81 + 125 - 16) / (2 * 9 * math.sqrt(125)))
    X = (9 * math.cos(ang), 9 * math.sin(ang))
    a1 = math.atan2(1, s80)
    a2 = math.atan2(X[1] - 10, X[0] - 5)
    check(comp(PROLOGUE + "G1 X0 Y0\nG1 X10 Y0\nG3 X0 Y10 I-10 J0\nG3 X10 Y10 I5 J0\n"
               "G40\nG1 X20 Y20\n"), [
        L("lead-in", (0, -10), (-1, 0)),
        A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
        L("compensated", (0, 1), (s80, 1)),
        A("compensated", (0, 0), (s80, 1), X, ang - a1),
        # ends at E + r*(C - E)/R = (10,10) + (-1,0); runs CCW from a2 to 0
        A("compensated", (5, 10), X, (9, 10), (0 - a2) % (2 * PI)),
        L("lead-out", (9, 10), (20, 20)),
    ])


@pytest.mark.parametrize("deg", [2.0, -2.0])
def test_turn_within_the_concave_tolerance_is_straight_on(deg):
    # A turn of 2 degrees (0.035 rad < 0.05) either way: no corner arc and no
    # pull-back: the +X line keeps its offset end (10,1) and the next line
    # runs from there to its own offset end.
    a = math.radians(deg)
    assert abs(a) < CONCAVE_TOLERANCE
    q = (10 + 10 * math.cos(a), 10 * math.sin(a))
    o = (-math.sin(a), math.cos(a))
    check(comp(PROLOGUE + f"G1 X0 Y0\nG1 X10 Y0\nG1 X{q[0]:.12f} Y{q[1]:.12f}\nG40\nG1 X30 Y10\n"), [
        L("lead-in", (0, -10), (-1, 0)),
        A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
        L("compensated", (0, 1), (10, 1)),
        L("compensated", (10, 1), (q[0] + o[0], q[1] + o[1])),
        L("lead-out", (q[0] + o[0], q[1] + o[1]), (30, 10)),
    ])


def test_turn_just_beyond_the_tolerance_gets_an_arc():
    a = -0.06   # turning right by 0.06 rad > 0.05: outside corner with an arc
    q = (10 + 10 * math.cos(a), 10 * math.sin(a))
    path = comp(PROLOGUE + f"G1 X0 Y0\nG1 X10 Y0\nG1 X{q[0]:.12f} Y{q[1]:.12f}\nG40\nG1 X30 Y10\n")
    corners = [s.to_json() for s in path.segments if s.role.value == "corner"]
    assert len(corners) == 2
    assert corners[1]["center"] == pytest.approx([10, 0])
    assert corners[1]["sweep"] == pytest.approx(a, abs=1e-6)


def test_z_moves_and_dwells_run_at_the_pulled_back_end_before_corners():
    text = ("G21 F60\nG0 X-10 Y0\nG41.1 D2\nG1 X0 Y0\nG1 X10 Y0\nG1 Z-1\nG4 P0.5\n"
            "G1 X10 Y{y}\nG40\nG1 X0 Y{y}\n")
    # Inside (+X then +Y, left side): the line and the Z move both end at the
    # offsets' intersection (9,1); the dwell happens there.
    path = comp(text.format(y=10))
    segs = [s for s in path.segments if s.role.value != "rapid"]
    ends = [(round(s.end[0], 9), round(s.end[1], 9), s.w1) for s in segs]
    assert ends == [(0, 1, 0), (9, 1, 0), (9, 1, -1), (9, 10, -1), (0, 10, -1)]
    assert [(i, t) for i, t, _ in path.dwells] == [(path.segments.index(segs[2]) + 1, 0.5)]
    # Outside (+X then -Y): the line and the Z move keep (10,1), the dwell
    # happens there, and only then the corner arc about (10,0) to (11,0).
    path = comp(text.format(y=-10))
    segs = [s for s in path.segments if s.role.value != "rapid"]
    assert [(s.kind, s.role.value) for s in segs] == [
        ("line", "lead-in"), ("line", "compensated"), ("line", "compensated"),
        ("arc", "corner"), ("line", "compensated"), ("line", "lead-out")]
    assert segs[2].start == pytest.approx((10, 1)) and segs[2].end == pytest.approx((10, 1))
    assert (segs[2].w0, segs[2].w1) == (0, -1)
    assert path.dwells[0][0] == path.segments.index(segs[3])
    assert segs[3].end == pytest.approx((11, 0))


def test_full_circle_and_extra_turns_keep_their_sweep():
    # Entry heading +Y, then a full G3 circle about (0,5) starting heading +X:
    # outside corner arc to (0,1), then the circle inside at radius 4 all the way
    # round (P2: twice). The exit leaves from (0,1).
    for p, sweep in (("", 2 * PI), (" P2", 4 * PI)):
        check(comp(PROLOGUE + f"G1 X0 Y0\nG3 I0 J5{p}\nG40\nG1 X-10 Y0\n"), [
            L("lead-in", (0, -10), (-1, 0)),
            A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
            A("compensated", (0, 5), (0, 1), (0, 1), sweep),
            L("lead-out", (0, 1), (-10, 0)),
        ])


def test_program_end_while_on_stays_at_the_offset():
    # No G40: LinuxCNC sends the queued move as it is; there is no return move.
    check(comp(PROLOGUE + "G1 X0 Y0\nG1 X10 Y0\n"), [
        L("lead-in", (0, -10), (-1, 0)),
        A("corner", (0, 0), (-1, 0), (0, 1), -PI / 2),
        L("compensated", (0, 1), (10, 1)),
    ])


def test_radius_and_side_overrides():
    # --radius 2 --side right: o(+Y) = (2,0) ... +Y then +X is inside for the
    # right side: x = 2 and y = -2 meet at (2,-2).
    path = comp(PROLOGUE + "G1 X0 Y0\nG1 X10 Y0\nG40\nG1 X10 Y-10\n", radius=2.0, side="right")
    check(path, [
        L("lead-in", (0, -10), (2, -2)),
        L("compensated", (2, -2), (10, -2)),
        L("lead-out", (10, -2), (10, -10)),
    ])
    assert path.radius == 2.0 and path.style == "linuxcnc"


def test_d0_is_no_compensation():
    path = comp("G21 F60\nG0 X0 Y-10\nG41.1 D0\nG1 X0 Y0\nG1 X10 Y0\nG40\nG1 X10 Y-10\n")
    assert [s.end for s in path.segments] == [(0, -10), (0, 0), (10, 0), (10, -10)]


def test_xz_plane_is_the_xy_rule_in_z_x_coordinates():
    # G18: in-plane (u, v) = (Z, X). The same program written with X -> Z and
    # Y -> X gives the same tool path in (u, v).
    xy = comp(PROLOGUE + "G1 X0 Y0\nG1 X10 Y0\nG3 X0 Y10 I-10 J0\nG40\nG1 X-10 Y10\n")
    xz = comp("G21 G18 F60\nG0 Z0 X-10\nG41.1 D2\nG1 Z0 X0\nG1 Z10 X0\nG3 Z0 X10 K-10 I0\n"
              "G40\nG1 Z-10 X10\n")
    assert xz.plane == "ZX"
    assert len(xy.segments) == len(xz.segments)
    for a, b in zip(xy.segments, xz.segments):
        assert (a.kind, a.role) == (b.kind, b.role)
        assert a.start == pytest.approx(b.start, abs=TOL) and a.end == pytest.approx(b.end, abs=TOL)
