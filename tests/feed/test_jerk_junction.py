"""The junction baseline under jerk limits, against closed-form figures.

Derived here: a change of speed by dv with the acceleration 0 at both ends,
under path limits a and j, takes T = dv / a + a / j when dv >= a^2 / j, else
T = 2 sqrt(dv / j); the acceleration pulse is symmetric, so it covers the
mean speed times T.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.feed import AxisLimits, plan_feed
from ccopt.geometry import Arc, Line
from ccopt.toolpath import PathSegment, Role, ToolPath

V, A, J = 100.0, 1000.0, 20000.0
LIM = AxisLimits((V, V), (A, A), j=(J, J))


def seg(geom, feed=1000.0):
    return PathSegment(geom, Role.COMPENSATED, None, 0.0, 0.0, feed)


def change_time(dv):
    return dv / A + A / J if dv >= A * A / J else 2.0 * math.sqrt(dv / J)


def within_limits(prof):
    smp = prof.sample(1e-4)
    return max(smp.axis_velocity_ratio.max(), smp.axis_acceleration_ratio.max(),
               smp.axis_jerk_ratio.max()) <= 1 + 1e-9


def test_collinear_blocks_run_through():
    """40 + 60 mm along X, tangent and straight: no slowing at the join, one
    S-curve over 100 mm: T = L / v + v / a + a / j (v j >= a^2, room to cruise)."""
    tp = ToolPath((seg(Line((0, 0), (40, 0))), seg(Line((40, 0), (100, 0)))))
    prof = plan_feed(tp, LIM, planner="junction")
    assert prof.duration == pytest.approx(100 / V + V / A + A / J, rel=1e-9)
    assert np.interp(40.0, prof.s, prof.sd) == pytest.approx(V, rel=1e-9)
    assert within_limits(prof)


def test_short_first_block_limits_the_junction_speed():
    """1 mm then 99 mm along X. Over 1 mm from rest, ending with acceleration
    0: v1 sqrt(v1 / j) = 1 (below a^2 / j = 50), so v1 = j^(1/3) = 27.14 mm/s;
    then from v1 up to v, a cruise, and down to rest in the 99 mm."""
    tp = ToolPath((seg(Line((0, 0), (1, 0))), seg(Line((1, 0), (100, 0)))))
    prof = plan_feed(tp, LIM, planner="junction")
    v1 = J ** (1 / 3)
    assert v1 < A * A / J
    up, down = change_time(V - v1), change_time(V)
    cruise = (99.0 - 0.5 * (v1 + V) * up - 0.5 * V * down) / V
    closed = 2.0 * math.sqrt(v1 / J) + up + cruise + down
    assert np.interp(1.0, prof.s, prof.sd) == pytest.approx(v1, rel=1e-9)
    assert prof.duration == pytest.approx(closed, rel=1e-9)
    assert within_limits(prof)
    # the jerk-limited stop baseline stops at the join: slower
    assert plan_feed(tp, LIM, planner="stop").duration > prof.duration


def test_curvature_break_speed_is_capped_by_jmax_ts():
    """Line, tangent quarter arc of radius 2, line: at each join the axis
    acceleration steps by v^2 / R, at most J Ts, so the junction speed is
    sqrt(J Ts R) = 4.47 mm/s (Ts = 1 ms), as in the jerk planner."""
    R = 2.0
    tp = ToolPath((seg(Line((0, -20), (0, 0)), 200.0), seg(Arc((-R, 0), R, 0.0, math.pi / 2), 200.0),
                   seg(Line((-R, R), (-R - 20, R)), 200.0)))
    prof = plan_feed(tp, LIM, planner="junction")
    joins = [20.0, 20.0 + math.pi * R / 2]
    assert np.interp(joins, prof.s, prof.sd) == pytest.approx([math.sqrt(J * 1e-3 * R)] * 2,
                                                             rel=1e-9)
    assert within_limits(prof)
    jerk = plan_feed(tp, LIM, planner="jerk")
    assert jerk.duration <= prof.duration
