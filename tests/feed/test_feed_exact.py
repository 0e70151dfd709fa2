"""Exact answers: TOPPRA's duration against figures derived by hand.

Each expected duration is derived here from the limits:

* a straight move of length ``L`` in direction ``t`` under per-axis limits
  moves at most at ``v = min(F, min_i vmax_i / |t_i|)`` and speeds up and
  slows down at ``a = min_i amax_i / |t_i|``: rest to rest it takes
  ``T = L/v + v/a`` when ``L >= v^2/a`` (it reaches ``v``), else ``2 sqrt(L/a)``;
* a half circle of radius ``R`` with a tangential limit ``a_t`` and a
  centripetal limit ``a_n`` (axis limits out of the way) cruises at
  ``v = min(F, sqrt(a_n R))``: ``T = pi R / v + v / a_t``;
* an L-shaped corner stops at the corner: the sum of the two trapezoids.

TOPPRA's duration must be within 0.1% of the figure and never below it
(beyond rounding, 1e-12 relative).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.feed import AxisLimits, GridOptions, plan_feed
from ccopt.geometry import Arc, Line
from ccopt.toolpath import PathSegment, Role, ToolPath

REL = 1e-3          # the acceptance bound
ROUNDING = 1e-12    # "never below" up to rounding


def toolpath(*pieces, plane="XY"):
    segs = []
    for geom, feed, *w in pieces:
        w0, w1 = w if w else (0.0, 0.0)
        role = Role.RAPID if feed is None else Role.COMPENSATED
        segs.append(PathSegment(geom, role, None, w0, w1, feed))
    return ToolPath(tuple(segs), plane=plane)


def trapezoid_time(L, v, a):
    return L / v + v / a if L >= v * v / a else 2.0 * math.sqrt(L / a)


def effective(direction, vmax, amax, feed=math.inf):
    t = np.abs(np.asarray(direction, float))
    t /= np.linalg.norm(t)
    with np.errstate(divide="ignore"):
        v = min(feed, float(np.min(np.where(t > 0, np.asarray(vmax) / np.where(t > 0, t, 1), np.inf))))
        a = float(np.min(np.where(t > 0, np.asarray(amax) / np.where(t > 0, t, 1), np.inf)))
    return v, a


def assert_exact(T, expected):
    assert T >= expected * (1 - ROUNDING), f"{T} below the exact {expected}"
    assert T <= expected * (1 + REL), f"{T} more than 0.1% above {expected}"


GRIDS = [GridOptions(), GridOptions(baseline_knots=False)]


@pytest.mark.parametrize("grid", GRIDS, ids=["default", "no-baseline-knots"])
@pytest.mark.parametrize("angle_deg,length,feed", [
    (0.0, 100.0, math.inf),      # along X: X limits
    (53.13010235415598, 100.0, math.inf),   # (0.6, 0.8): Y velocity limit binds
    (30.0, 100.0, 40.0),         # the feed binds
    (120.0, 2.0, math.inf),      # too short to reach v: 2 sqrt(L/a)
    (90.0, 0.5, 20.0),
])
def test_straight_line(angle_deg, length, feed, grid):
    vmax, amax = (100.0, 50.0), (1000.0, 400.0)
    th = math.radians(angle_deg)
    d = (math.cos(th), math.sin(th))
    line = Line((1.0, 2.0), (1.0 + length * d[0], 2.0 + length * d[1]))
    F = None if math.isinf(feed) else feed
    tp = toolpath((line, F))
    v, a = effective(d, vmax, amax, feed)
    expected = trapezoid_time(length, v, a)
    prof = plan_feed(tp, AxisLimits(vmax, amax), grid=grid)
    assert_exact(prof.duration, expected)


@pytest.mark.parametrize("grid", GRIDS, ids=["default", "no-baseline-knots"])
def test_straight_line_with_z(grid):
    """A 3-D move (ramp down in Z): the Z limits join in through the direction."""
    vmax, amax = (100.0, 100.0, 20.0), (1000.0, 1000.0, 150.0)
    line = Line((0.0, 0.0), (30.0, 0.0))
    tp = toolpath((line, 80.0, 0.0, -10.0))
    L = math.hypot(30.0, 10.0)
    v, a = effective((30.0, 0.0, -10.0), vmax, amax, 80.0)
    assert (v, a) == pytest.approx((20.0 * L / 10.0, 150.0 * L / 10.0))
    assert_exact(plan_feed(tp, AxisLimits(vmax, amax), grid=grid).duration,
                 trapezoid_time(L, v, a))


@pytest.mark.parametrize("grid", GRIDS, ids=["default", "no-baseline-knots"])
def test_z_plunge_alone(grid):
    """A move with no in-plane component is parameterised by its Z length."""
    tp = toolpath((Line((3.0, 4.0), (3.0, 4.0)), 30.0, 5.0, -2.0))
    lim = AxisLimits((100.0, 100.0, 20.0), (1000.0, 1000.0, 200.0))
    assert_exact(plan_feed(tp, lim, grid=grid).duration, trapezoid_time(7.0, 20.0, 200.0))


@pytest.mark.parametrize("grid", GRIDS, ids=["default", "no-baseline-knots"])
@pytest.mark.parametrize("R,F,a_t,a_n", [
    (10.0, 50.0, 200.0, 100.0),    # centripetal limit binds: v = sqrt(1000) = 31.6
    (10.0, 20.0, 200.0, 100.0),    # the feed binds
    (4.0, 80.0, 1000.0, 2500.0),   # sqrt(a_n R) = 100 > F = 80: the feed binds
])
def test_half_circle(R, F, a_t, a_n, grid):
    arc = Arc((0.0, 0.0), R, 0.0, math.pi)
    tp = toolpath((arc, F))
    lim = AxisLimits((1e4, 1e4), (1e6, 1e6), tangential_acc=a_t, centripetal_acc=a_n)
    v = min(F, math.sqrt(a_n * R))
    L = math.pi * R
    assert L >= v * v / a_t
    expected = L / v + v / a_t
    prof = plan_feed(tp, lim, grid=grid)
    assert_exact(prof.duration, expected)


@pytest.mark.parametrize("grid", GRIDS, ids=["default", "no-baseline-knots"])
def test_l_corner_is_the_sum_of_two_trapezoids(grid):
    vmax, amax = (100.0, 60.0), (500.0, 300.0)
    first = Line((0.0, 0.0), (50.0, 0.0))       # along X, feed 40: v = 40, a = 500
    second = Line((50.0, 0.0), (50.0, 30.0))    # along Y, feed 80: v = 60, a = 300
    tp = toolpath((first, 40.0), (second, 80.0))
    expected = trapezoid_time(50.0, 40.0, 500.0) + trapezoid_time(30.0, 60.0, 300.0)
    prof = plan_feed(tp, AxisLimits(vmax, amax), grid=grid)
    assert_exact(prof.duration, expected)
    assert prof.speed_at([50.0])[0] == 0.0


def test_diagonal_corner_short_legs():
    """Two short diagonal legs (neither reaches its speed), a 90 degree turn."""
    vmax, amax = (100.0, 100.0), (800.0, 200.0)
    a1 = effective((1, 1), vmax, amax)[1]
    a2 = effective((1, -1), vmax, amax)[1]
    tp = toolpath((Line((0, 0), (1, 1)), 500.0), (Line((1, 1), (2, 0)), 500.0))
    L = math.sqrt(2)
    expected = 2 * math.sqrt(L / a1) + 2 * math.sqrt(L / a2)
    assert_exact(plan_feed(tp, AxisLimits(vmax, amax)).duration, expected)


@pytest.mark.parametrize("planner", ["stop", "junction"])
def test_baselines_are_exact_on_straight_moves(planner):
    vmax, amax = (100.0, 60.0), (500.0, 300.0)
    tp = toolpath((Line((0, 0), (50, 0)), 40.0), (Line((50, 0), (50, 30)), 80.0))
    expected = trapezoid_time(50.0, 40.0, 500.0) + trapezoid_time(30.0, 60.0, 300.0)
    assert plan_feed(tp, AxisLimits(vmax, amax), planner=planner).duration == \
        pytest.approx(expected, rel=1e-12)


def test_collinear_blocks_do_not_stop_but_feed_changes_hold():
    """Two collinear blocks with feeds 40 then 20: no stop at the join, the
    speed there is at most 20, and the time is that of the exact profile:
    accelerate to 40, brake to 20 just before the join, cruise, brake to 0."""
    a = 500.0
    tp = toolpath((Line((0, 0), (50, 0)), 40.0), (Line((50, 0), (100, 0)), 20.0))
    prof = plan_feed(tp, AxisLimits((100.0, 100.0), (a, a)))
    T1 = 40 / a + (50 - 40 ** 2 / (2 * a) - (40 ** 2 - 20 ** 2) / (2 * a)) / 40 + (40 - 20) / a
    T2 = (50 - 20 ** 2 / (2 * a)) / 20 + 20 / a
    assert_exact(prof.duration, T1 + T2)
    assert prof.speed_at([50.0])[0] == pytest.approx(20.0, rel=1e-6)
