"""The ``heidenhain`` style: corners, switching on and off, M97/M98 and the
APPR/DEP paths, each figure worked out here by hand from the rules of
docs/compensation.md section 10 (never the implementation's output pasted
back). The manual examples are those of the TNC User's Manual, "Approaching
and departing a contour" (APPR LT, LN, CT, LCT, with their printed points)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt import verify
from ccopt.compensate import compensate
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line
from ccopt.program import read_text
from ccopt.toolpath import Role

TOL = 1e-9


def prog(body: str, radius: float = 2.0):
    text = (f"0 BEGIN PGM T MM\n1 TOOL DEF 1 L+0 R+{radius}\n2 TOOL CALL 1 Z S1000\n"
            + body + "\n99 END PGM T MM\n")
    return read_text(text, "t.h", "heidenhain")


def path(body: str, radius: float = 2.0, style: str = "heidenhain"):
    p = prog(body, radius)
    return p, compensate(p, style=style)


def segs(tp, role=None):
    return [s for s in tp.segments if role is None or s.role is role]


def near(a, b, tol=1e-9):
    return float(np.hypot(*(np.asarray(a, float)[:2] - np.asarray(b, float)[:2]))) <= tol


# -- corners -----------------------------------------------------------------------
SQUARE = ("3 L X-10 Y-10 R0 F100\n4 L X+0 Y+0 RL\n5 L X+0 Y+20\n6 L X+20 Y+20\n"
          "7 L X+20 Y+0\n8 L X+0 Y+0\n9 L X-10 Y-10 R0")


def test_outside_corners_on_transition_arcs_about_the_corner():
    p, tp = path(SQUARE)
    arcs = [s for s in segs(tp, Role.CORNER)]
    # clockwise square, tool left (outside): three full corners, r = 2 about them
    assert len(arcs) == 3
    for s, corner in zip(arcs, [(0, 20), (20, 20), (20, 0)]):
        assert isinstance(s.geom, Arc) and near(s.geom.center, corner)
        assert s.geom.radius == pytest.approx(2.0)
    assert verify(tp, p).ok


def test_no_break_angle_even_a_slight_outside_corner_gets_its_arc():
    # a 1 degree outside turn: PMAC (Isx99 0.9998) extends to the intersection,
    # the TNC rounds it (HEIDENHAIN rule 2)
    a = math.radians(1.0)
    x2, y2 = 20 + 20 * math.cos(-a), 20 * math.sin(-a)
    body = f"3 L X-5 Y-5 R0 F100\n4 L X+0 Y+0 RL\n5 L X+20 Y+0\n6 L X{x2:+.12f} Y{y2:+.12f}\n7 L X+45 Y-20 R0"
    _, tp = path(body)
    corner = segs(tp, Role.CORNER)
    assert len(corner) == 1 and near(corner[0].geom.center, (20, 0))
    _, pm = path(body, style="pmac")
    assert not any(near(s.geom.center, (20, 0)) for s in segs(pm, Role.CORNER))


def test_inside_corner_at_the_intersection():
    # a left turn with RL: the tool inside, at (r, r) from the corner
    body = ("3 L X+10 Y+10 R0 F100\n4 L X+10 Y+0 RL\n5 L X+20 Y+0\n6 L X+20 Y+20\n"
            "7 L X+10 Y+20 R0")
    _, tp = path(body)
    comp = segs(tp, Role.COMPENSATED)
    assert near(comp[0].geom.end, (18, 2)) and near(comp[1].geom.start, (18, 2))
    assert not segs(tp, Role.CORNER)


def test_switching_on_and_off_perpendicular_to_the_contour():
    # lead-in (R0 -> RL at (0,0)), first element along +Y: the tool ends at
    # P + r*o(t_next) = (-2, 0) whatever the corner (PMAC adds an arc here)
    body = "3 L X+10 Y-10 R0 F100\n4 L X+0 Y+0 RL\n5 L X+0 Y+20\n6 L X+10 Y+30 R0"
    _, tp = path(body)
    lead_in = segs(tp, Role.LEAD_IN)[0]
    assert near(lead_in.geom.end, (-2, 0))
    comp = segs(tp, Role.COMPENSATED)[0]
    assert near(comp.geom.start, (-2, 0)) and near(comp.geom.end, (-2, 20))
    lead_out = segs(tp, Role.LEAD_OUT)[0]
    assert near(lead_out.geom.start, (-2, 20)) and near(lead_out.geom.end, (10, 30))
    assert not segs(tp, Role.CORNER)


def test_rl_to_rr_without_r0_is_refused_where_it_happens():
    with pytest.raises(CompensationError) as info:
        path("3 L X-5 Y+0 R0 F100\n4 L X+0 Y+0 RL\n5 L X+10 Y+0\n6 L X+20 Y+0 RR\n"
             "7 L X+30 Y+0 R0")
    assert info.value.line == 7 and "R0" in info.value.message


def test_m97_cuts_a_small_outside_step_at_the_intersection():
    # steps of 0.5 with a tool of radius 2 (the manual's M97 example, scaled):
    # tool left, path along +X, then down 0.5 (an outside corner), then on along +X
    body = ("3 L X-10 Y+5 R0 F100\n4 L X+0 Y+0 RL\n5 L X+10 Y+0 M97\n6 L X+10 Y-0.5\n"
            "7 L X+20 Y-0.5\n8 L X+30 Y+10 R0")
    _, tp = path(body)
    comp = segs(tp, Role.COMPENSATED)
    # no arc at the M97 corner (10, 0); the offsets y = 2 and x = 12 meet at (12, 2)
    assert near(comp[0].geom.end, (12, 2))
    assert not any(near(s.geom.center, (10, 0)) for s in segs(tp, Role.CORNER))
    _, plain = path(body.replace(" M97", ""))
    assert any(near(s.geom.center, (10, 0)) for s in segs(plain, Role.CORNER))


def test_m98_leaves_an_open_inside_corner():
    body = ("3 L X+10 Y+10 R0 F100\n4 L X+10 Y+0 RL\n5 L X+20 Y+0 M98\n6 L X+20 Y+20\n"
            "7 L X+10 Y+20 R0")
    _, tp = path(body)
    comp = segs(tp, Role.COMPENSATED)
    # past the intersection (18, 2) to the end of the first offset, (20, 2); the
    # next block runs from there to its own offset end (18, 20)
    assert near(comp[0].geom.end, (20, 2)) and near(comp[1].geom.start, (20, 2))
    assert near(comp[1].geom.end, (18, 20)) and not segs(tp, Role.CORNER)
    _, plain = path(body.replace(" M98", ""))
    assert near(segs(plain, Role.COMPENSATED)[0].geom.end, (18, 2))


# -- approach and departure --------------------------------------------------------
def _appr(words: str, r: float = 2.0, side: str = "RL", first: str = "L X+30 Y+0"):
    body = (f"3 L X-20 Y+20 R0 F100\n4 APPR {words} {side}\n5 {first}\n"
            "6 DEP LT LEN5\n7 L Z+10 R0 FMAX")
    return path(body, r)


def test_appr_lt_tangent_line_of_length_len():
    # PA (10,0), first element along +X, RL: PA_t = (10, 2), PH_t = (5, 2)
    _, tp = _appr("LT X+10 Y+0 LEN5")
    lead_in = segs(tp, Role.LEAD_IN)[0]
    assert near(lead_in.geom.start, (-20, 20)) and near(lead_in.geom.end, (5, 2))
    first = segs(tp, Role.COMPENSATED)[0]
    assert near(first.geom.start, (5, 2)) and near(first.geom.end, (10, 2))


def test_appr_ln_perpendicular_at_len_plus_radius():
    # PH is LEN plus the tool radius from PA: (10, 5 + 2)
    _, tp = _appr("LN X+10 Y+0 LEN5")
    first = segs(tp, Role.COMPENSATED)[0]
    assert near(first.geom.start, (10, 7)) and near(first.geom.end, (10, 2))


def test_appr_ct_end_point_and_centre_by_hand():
    # R+5 with RL: the arc comes from the tool side, centre PA_t + 5*(0,1) =
    # (10, 7); CCA 90 counter-clockwise ending at (10, 2): PH_t = (5, 7)
    _, tp = _appr("CT X+10 Y+0 CCA90 R+5")
    arc = segs(tp, Role.COMPENSATED)[0].geom
    assert isinstance(arc, Arc) and near(arc.center, (10, 7)) and arc.radius == pytest.approx(5)
    assert arc.sweep == pytest.approx(math.pi / 2) and near(arc.start, (5, 7))
    assert near(arc.end, (10, 2))
    # from the material side, centre (10, -3), clockwise: PH_t = (5, -3)
    _, tp = _appr("CT X+10 Y+0 CCA90 R-5")
    arc = segs(tp, Role.COMPENSATED)[0].geom
    assert near(arc.center, (10, -3)) and near(arc.start, (5, -3))
    assert arc.sweep == pytest.approx(-math.pi / 2)


def test_appr_lct_tangent_to_the_line_from_ps_and_to_the_contour():
    _, tp = _appr("LCT X+10 Y+0 R6")
    lead_in, arc = segs(tp, Role.LEAD_IN)[0].geom, segs(tp, Role.COMPENSATED)[0].geom
    c = np.array([10.0, 8.0])                 # PA_t (10, 2) + 6 along the tool-side normal
    T = np.asarray(lead_in.end)
    assert near(arc.center, c) and arc.radius == pytest.approx(6)
    assert abs(np.hypot(*(T - c)) - 6) < TOL
    assert abs(np.dot(T - np.array([-20.0, 20.0]), T - c)) < 1e-7      # tangent at T
    assert near(arc.end, (10, 2)) and arc.sweep > 0


def test_manual_example_appr_lct():
    """TNC manual: ``7 L X+40 Y+10 R0 FMAX M3``, ``8 APPR LCT X+10 Y+20 Z-10
    R10 RR F100``, ``9 L X+20 Y+35``: the arc of radius 10 touches the line
    from PS (40, 10) and ends on the first element's offset at PA."""
    r = 3.0
    p, tp = path("7 L X+40 Y+10 R0 FMAX M3\n8 APPR LCT X+10 Y+20 Z-10 R10 RR F100\n"
                 "9 L X+20 Y+35\n10 L X+40 Y+35\n11 DEP LT LEN10\n12 L Z+50 R0 FMAX", r)
    t1 = np.array([10.0, 15.0]) / math.hypot(10, 15)
    n = np.array([t1[1], -t1[0]])              # RR: to the right of travel
    pa_t = np.array([10.0, 20.0]) + r * n
    c = pa_t + 10 * n
    lead_in = segs(tp, Role.LEAD_IN)
    arc = [s.geom for s in segs(tp, Role.COMPENSATED) if isinstance(s.geom, Arc)][0]
    T = np.asarray(lead_in[0].geom.end)
    assert near(lead_in[0].geom.start, (40, 10)) and near(arc.center, c)
    assert abs(np.dot(T - np.array([40.0, 10.0]), T - c)) < 1e-7
    assert near(arc.end, pa_t) and arc.sweep < 0            # clockwise with RR
    # the infeed Z-10 happens at PH, before the arc
    assert lead_in[0].w1 == pytest.approx(0.0) and arc.radius == pytest.approx(10)
    assert verify(tp, p).ok


def test_manual_examples_appr_lt_and_ln():
    r = 2.0
    t1 = np.array([15.0, 15.0]) / math.hypot(15, 15)
    n = np.array([t1[1], -t1[0]])
    _, tp = path("11 L X+40 Y+10 R0 F300 M3\n12 APPR LT X+20 Y+20 Z-10 LEN15 RR F100\n"
                 "13 L X+35 Y+35\n14 L X+50 Y+35\n15 DEP LT LEN5", r)
    pa_t = np.array([20.0, 20.0]) + r * n
    assert near(segs(tp, Role.LEAD_IN)[0].geom.end, pa_t - 15 * t1)
    t1 = np.array([10.0, 15.0]) / math.hypot(10, 15)
    n = np.array([t1[1], -t1[0]])
    _, tp = path("11 L X+40 Y+10 R0 F300 M3\n12 APPR LN X+10 Y+20 Z-10 LEN+15 RR F100\n"
                 "13 L X+20 Y+35\n14 L X+50 Y+35\n15 DEP LT LEN5", r)
    pa_t = np.array([10.0, 20.0]) + r * n
    assert near(segs(tp, Role.LEAD_IN)[0].geom.end, pa_t + 15 * n)


def _dep(words: str, r: float = 2.0):
    body = (f"3 L X-20 Y+20 R0 F100\n4 APPR LT X+0 Y+0 LEN5 RL\n5 L X+10 Y+0\n"
            f"6 DEP {words}\n7 L Z+10 R0 FMAX\n8 L X+50 Y+50 R0 FMAX")
    return path(body, r)


def test_dep_lt_ln_ct_by_hand():
    # last element along +X to PE (10,0), RL: PE_t = (10, 2)
    _, tp = _dep("LT LEN5")
    last = segs(tp, Role.COMPENSATED)[-1].geom
    assert near(last.start, (10, 2)) and near(last.end, (15, 2))
    _, tp = _dep("LN LEN5")
    last = segs(tp, Role.COMPENSATED)[-1].geom
    assert near(last.end, (10, 7))
    _, tp = _dep("CT CCA90 R+4")
    arc = segs(tp, Role.COMPENSATED)[-1].geom
    assert near(arc.center, (10, 6)) and near(arc.end, (14, 6))
    assert arc.sweep == pytest.approx(math.pi / 2)
    # after DEP the tool goes on from where DEP left it, uncompensated
    after = [s for s in tp.segments if s.block.source.line == 9 and s.geom.length > 0][0]
    assert near(after.geom.start, (14, 6)) and near(after.geom.end, (50, 50))


def test_dep_lct_arc_then_tangent_line_to_pn():
    _, tp = _dep("LCT X+30 Y+30 R5")
    arc, line = [s.geom for s in segs(tp, Role.COMPENSATED)][-2:]
    c = np.array([10.0, 7.0])
    T = np.asarray(arc.end)
    assert near(arc.start, (10, 2)) and near(arc.center, c) and arc.sweep > 0
    assert near(line.start, T) and near(line.end, (30, 30))
    assert abs(np.dot(np.array([30.0, 30.0]) - T, T - c)) < 1e-7


def test_appr_lct_start_inside_its_circle_is_refused_located():
    with pytest.raises(CompensationError) as info:
        # PS (10, 13.5) is 7.5 from the arc's centre (10, 6) at radius 0 but
        # 5.5 from (10, 8) with the tool's radius 2: no tangent from it
        path("3 L X+10 Y+13.5 R0 F100\n4 APPR LCT X+10 Y+0 R6 RL\n5 L X+30 Y+0\n"
             "6 DEP LT LEN5", 2.0)
    assert info.value.line == 5 and "inside the circle" in info.value.message


# -- any program ---------------------------------------------------------------------
def test_a_gcode_program_compensated_as_a_tnc_would():
    text = ("G90 G17 F600\nG0 X-10 Y-10\nG41 G1 X0 Y0 D1\nY20\nX20\nY0\nX0\n"
            "G40 X-10 Y-10\nM2\n")
    p = read_text(text, "sq.ngc", "gcode", tool_table={1: 4.0})
    tp = compensate(p, style="heidenhain")
    assert len(segs(tp, Role.CORNER)) == 3 and verify(tp, p).ok


def test_manual_example_appr_ct():
    """``7 L X+40 Y+10 R0 FMAX M3``, ``8 APPR CT X+10 Y+20 Z-10 CCA180 R+10 RR
    F100``, ``9 L X+20 Y+35``: a half circle of radius 10 ending at PA_t,
    its centre 10 to the right of the first element (RR), clockwise."""
    r = 2.5
    _, tp = path("7 L X+40 Y+10 R0 FMAX M3\n8 APPR CT X+10 Y+20 Z-10 CCA180 R+10 RR F100\n"
                 "9 L X+20 Y+35\n10 L X+40 Y+35\n11 DEP LT LEN5", r)
    t1 = np.array([10.0, 15.0]) / math.hypot(10, 15)
    n = np.array([t1[1], -t1[0]])
    pa_t = np.array([10.0, 20.0]) + r * n
    arc = [s.geom for s in segs(tp, Role.COMPENSATED) if isinstance(s.geom, Arc)][0]
    assert near(arc.center, pa_t + 10 * n) and near(arc.start, pa_t + 20 * n)
    assert near(arc.end, pa_t) and arc.sweep == pytest.approx(-math.pi)
    assert near(segs(tp, Role.LEAD_IN)[0].geom.end, pa_t + 20 * n)


@pytest.mark.parametrize("dep, check", [
    ("DEP LT LEN12.5 F100", "lt"), ("DEP LN LEN+20 F100", "ln"),
    ("DEP CT CCA 180 R+8 F100", "ct"), ("DEP LCT X+10 Y+12 R+8 F100", "lct")])
def test_manual_examples_dep(dep, check):
    """The manuals' departures after ``23 L Y+20 RR F100`` (here from (30, 0)
    up to (30, 20)): last element along +Y, RR: n = (1, 0), PE_t = (30 + r, 20)."""
    r = 2.0
    _, tp = path(f"3 L X+30 Y-20 R0 FMAX\n4 APPR LT X+30 Y+0 LEN5 RR F100\n"
                 f"23 L Y+20 RR F100\n24 {dep}\n25 L Z+100 R0 FMAX M2", r)
    pe_t = np.array([30.0 + r, 20.0])
    last = [s.geom for s in segs(tp, Role.COMPENSATED)]
    if check == "lt":
        assert near(last[-1].start, pe_t) and near(last[-1].end, pe_t + [0, 12.5])
    elif check == "ln":
        # PN is LEN plus the tool radius from PE
        assert near(last[-1].end, (30 + 20 + r, 20))
    elif check == "ct":
        assert near(last[-1].center, pe_t + [8, 0]) and near(last[-1].end, pe_t + [16, 0])
        assert last[-1].sweep == pytest.approx(-math.pi)
    else:
        arc, line = last[-2], last[-1]
        c = pe_t + [8, 0]
        T = np.asarray(arc.end)
        assert near(arc.start, pe_t) and near(arc.center, c) and arc.sweep < 0
        assert near(line.end, (10, 12)) and abs(np.dot(np.array([10.0, 12.0]) - T, T - c)) < 1e-7


def test_manual_example_m98():
    """TNC7 "Machining open contour corners with M98": ``11 L X+0 Y+50 RL
    F1000``, ``12 L X+30``, ``13 L Y+0 M98``, ``14 L X+100``, ``15 L Y+50``.
    With r = 5: block 13 runs down x = 35 (after the arc about (30, 50)) past
    the intersection (35, 5) to the end of its offset (35, 0); block 14 runs
    from there to the inside corner at (100, 0), the intersection (95, 5)
    (HEIDENHAIN_M98_OPEN_CORNER)."""
    _, tp = path("10 L X-10 Y+60 R0 F1000\n11 L X+0 Y+50 RL F1000\n12 L X+30\n13 L Y+0 M98\n"
                 "14 L X+100\n15 L Y+50\n16 L X+110 Y+60 R0", 5.0)
    by_line = {}
    for s in segs(tp, Role.COMPENSATED):
        by_line.setdefault(s.block.source.line, s.geom)
    assert near(by_line[7].start, (35, 50)) and near(by_line[7].end, (35, 0))
    assert near(by_line[8].start, (35, 0)) and near(by_line[8].end, (95, 5))
    assert near(by_line[9].start, (95, 5)) and near(by_line[9].end, (95, 50))
