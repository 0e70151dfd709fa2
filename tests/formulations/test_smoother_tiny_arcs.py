"""The smoother at the tiny corner arcs CAM fillets leave beside lines.

A CAM program writes a fillet tangent to its lines with a few decimals, so the
line meets the fillet with a turn of a few microradians; on the convex side the
controller adds a corner arc of the cutter radius ``r`` there, a tenth of a
micrometre long. A G2 blend that ends on that arc with its curvature ``1/r``
bends toward the part alongside the line by ``x^2 / (2 r)`` at ``x`` before the
join (the line lies at exactly ``r`` from its edge), so none passes the checks;
the smoother ends the line at the arc's far end instead and blends the line
into the fillet. Checked here with figures measured in the test: the
controller's path has such arcs (found here by their length and neighbours),
the smoothed path has no join left without curvature continuity near them, it
stays within the band of the path it smooths (dense samples of both), is
certified, and is faster under jerk limits; over generated plates (slow tier)
the comparison's smoother row is certified and never slower than the fastest
controller variant it starts from, and leaves no join at such an arc (beside a
curve, or between two lines turning too little to intersect).
"""
from __future__ import annotations

import numpy as np
import pytest

import ccopt
from ccopt.compare import BlendProblem, compare
from ccopt.compare.contract import CONTROLLER_NAMES
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role
from ccopt_formulations.smoother import smooth

from smoother_checks import LIMITS, program, smooth_row, unsmooth_joins_near, within_band

#: A corner arc this many times shorter than the cutter radius is "tiny" here
#: (a rounding's turn of 1e-4 rad at most; the arcs of the plates below are
#: 1e-7 long on radii 0.4-5).
TINY = 1e-4


def _turn(a, b) -> float:
    """The angle (rad) between the end tangent of segment ``a`` and the start
    tangent of ``b``."""
    t0 = np.asarray(a.geom.tangent(a.length), float)
    t1 = np.asarray(b.geom.tangent(0.0), float)
    return float(np.arctan2(abs(t0[0] * t1[1] - t0[1] * t1[0]), float(t0 @ t1)))


def _tiny_corner_arcs(path, lines: int = 1) -> list[tuple[float, float]]:
    """The start points of the corner arcs of ``path`` shorter than ``TINY * r``,
    tangent to both neighbours, ``lines`` of which are lines (1: beside a
    curve; found from the segments, not from the smoother)."""
    segs = path.segments
    out = []
    for i in range(1, len(segs) - 1):
        s = segs[i]
        if s.role is not Role.CORNER or not isinstance(s.geom, Arc) \
                or not s.length < TINY * s.geom.radius:
            continue
        if max(_turn(segs[i - 1], s), _turn(s, segs[i + 1])) > 1e-6:      # G1 both ends
            continue
        if [isinstance(segs[k].geom, Line) for k in (i - 1, i + 1)].count(True) == lines:
            out.append(tuple(s.start))
    return out


def test_tiny_corner_arcs_beside_fillets_are_smoothed_through():
    # seed 400: a 9-gon with fillets, 6 decimals, r 0.449; Fagor's path (G138,
    # the program's own modes), the fastest controller's there, as compare starts from
    cp, prog = program(400)
    ref = ccopt.compensate(prog, "fagor", radius=cp.radius)
    tiny = _tiny_corner_arcs(ref)
    assert len(tiny) >= 4, cp.description                 # the premise
    delta = 0.01 * cp.radius
    path, info = smooth(BlendProblem(prog, ref, LIMITS), delta)
    assert all(j["status"] == "blended" for j in info["joins"]), info["joins"]
    assert unsmooth_joins_near(path, tiny) == []
    assert info["certificate"].ok
    # within the band of PMAC's path, both ways, on dense samples of both
    assert within_band(path, ref, delta)
    t_ref = ccopt.plan_feed(ref, LIMITS, planner="jerk").duration      # Fagor's
    t_smooth = ccopt.plan_feed(path, LIMITS, planner="jerk").duration
    assert t_smooth < t_ref


def _smooth_row_holds(seed: int) -> None:
    cp, cmp, row = smooth_row(seed)
    if row.info.get("optimised") is None:                 # the smoother's own path
        base = cmp[row.info.get("base", "pmac")].toolpath
        tiny = _tiny_corner_arcs(base) + _tiny_corner_arcs(base, lines=2)
        assert unsmooth_joins_near(row.toolpath, tiny) == [], \
            cp.description


@pytest.mark.parametrize("seed", [0, 14])
def test_generated_plates_smooth_row_quick(seed):
    _smooth_row_holds(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(500, 560))
def test_generated_plates_smooth_row(seed):
    _smooth_row_holds(seed)


def test_no_blend_shorter_than_a_micrometre_leaves_stops_the_planners_cannot_part():
    # seed 163 (a rectangle, 6 decimals, r 2.771): beside the lead-out a corner
    # arc 6e-8 long left room for a blend 2.7e-8 long between two stops, which
    # neither feed planner can plan (the row fell back to the controller's
    # path for want of a cycle time); such a join is now left as it is
    from ccopt.geometry import BezierCurve
    cp, prog = program(163)
    cmp = compare(prog, list(CONTROLLER_NAMES) + ["smooth"], limits=LIMITS, radius=cp.radius)
    row = cmp["smooth"]
    assert row.status == "ok" and row.certificate.ok and row.info.get("optimised") is None, \
        row.message
    curves = [s.length for s in row.toolpath.segments if isinstance(s.geom, BezierCurve)]
    assert curves and min(curves) >= 1e-6
    best = min(cmp[n].figures["duration"] for n in CONTROLLER_NAMES if cmp[n].status == "ok")
    assert row.figures["duration"] < best


def test_a_tiny_corner_arc_between_two_nearly_parallel_lines_is_smoothed_through():
    # seed 37 (an 8-gon, 6 decimals, r 0.639): a corner arc 6.7e-8 long between
    # two lines turning by 1e-7 rad, too nearly parallel to intersect, so the
    # line-line absorption left it; the first line now ends where the second
    # starts, and no join is left there
    cp, prog = program(37)
    ref = ccopt.compensate(prog, "fagor", radius=cp.radius)
    tiny = _tiny_corner_arcs(ref, lines=2)
    assert tiny, cp.description                                   # the premise
    delta = 0.01 * cp.radius
    path, info = smooth(BlendProblem(prog, ref, LIMITS), delta)
    assert unsmooth_joins_near(path, tiny) == []
    assert info["certificate"].ok
    assert within_band(path, ref, delta)
