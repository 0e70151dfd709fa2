"""The jerk planner's windows solved in worker processes give the profile
solved in this one, and keep the limits.

A square of side 20 mm run counter-clockwise stops at its four corners, so
its four sides are four independent chains of windows; in two processes
(forced on this small path) every gridpoint's speed is the one planned here.
Each side is a rest-to-rest straight move of 20 mm along one axis, so its
time is the closed form L / v + v / a + a / j (v j >= a^2 and room to cruise),
four times over.
"""
from __future__ import annotations

import numpy as np
import pytest

from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed import jerk_windows
from ccopt.feed.jerk_bound import StretchBound
from ccopt.geometry import Line
from ccopt.toolpath import PathSegment, Role, ToolPath


def square():
    pts = [(0, 0), (20, 0), (20, 20), (0, 20), (0, 0)]
    return ToolPath(tuple(PathSegment(Line(p, q), Role.COMPENSATED, None, 0.0, 0.0, 1000.0)
                          for p, q in zip(pts[:-1], pts[1:])))


@pytest.mark.slow
def test_windows_in_two_processes_match_one(monkeypatch):
    lim = AxisLimits((100, 100), (1000, 1000), j=(20000, 20000))
    monkeypatch.setattr(jerk_windows, "BATCH_POINTS", 1)      # one window per side
    here = plan_feed(square(), lim, planner="jerk")
    monkeypatch.setattr(jerk_windows, "PARALLEL_MIN_POINTS", 0)
    monkeypatch.setattr(jerk_windows, "WORKERS", 2)
    monkeypatch.setattr(jerk_windows, "TASK_POINTS", 1)       # a task per side
    apart = plan_feed(square(), lim, planner="jerk")
    assert here.info["workers"] == 1 and apart.info["workers"] == 2
    assert apart.info["windows"] == 4
    np.testing.assert_array_equal(apart.s, here.s)
    np.testing.assert_array_equal(apart.sd, here.sd)
    closed = 4 * (20 / 100 + 100 / 1000 + 1000 / 20000)
    assert apart.duration == pytest.approx(closed, rel=5e-3)
    smp = apart.sample(1e-4)
    assert max(smp.axis_velocity_ratio.max(), smp.axis_acceleration_ratio.max(),
               smp.axis_jerk_ratio.max()) <= 1.005


def test_stretch_bound_is_toppra_rest_to_rest_on_its_side():
    """The speed bound a task computes on its own stretch (the square's second
    side, from the stop at (20, 0) to the one at (20, 20)): a straight move of
    20 mm from rest to rest under v = 100, a = 1000 alone, whose time-optimal
    squared speed is min(v^2, 2 a d, 2 a (L - d)) at distance d along it."""
    lim = AxisLimits((100, 100), (1000, 1000), j=(20000, 20000))
    path = ExactPath(square())
    bound = StretchBound.of(path, lim, None, 20.0, 40.0)
    assert len(bound.toolpath.segments) == 1 and bound.origin == 20.0
    s = np.linspace(20.0, 40.0, 41)
    stop = (s == 20.0) | (s == 40.0)
    b = bound(s, stop, np.full(s.size, np.inf))
    d = s - 20.0
    np.testing.assert_allclose(b, np.minimum(100.0 ** 2, 2000.0 * np.minimum(d, 20.0 - d)),
                               rtol=1e-9, atol=1e-9)


def test_split_program_plans_the_closed_form(monkeypatch):
    """Planned as a long program (each task with its own stretch's bound, here
    in this process), the square takes the closed form of its four sides."""
    lim = AxisLimits((100, 100), (1000, 1000), j=(20000, 20000))
    monkeypatch.setattr(jerk_windows, "SPLIT_BOUND_POINTS", 0)
    monkeypatch.setattr(jerk_windows, "BATCH_POINTS", 1)
    monkeypatch.setattr(jerk_windows, "TASK_POINTS", 1)
    prof = plan_feed(square(), lim, planner="jerk")
    assert prof.info["workers"] == 1
    closed = 4 * (20 / 100 + 100 / 1000 + 1000 / 20000)
    assert prof.duration == pytest.approx(closed, rel=5e-3)
