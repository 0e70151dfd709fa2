"""TOPPRA keeps the axis limits between its gridpoints (issue 16, build item 3).

Between gridpoints TOPPRA's profile has a constant ``u = s''`` and a squared
speed ``x = s'^2`` linear in ``s``; an axis acceleration
``a_j = q_j' u + q_j'' x`` then follows the path's geometry, and on a curve
it bulges above the values checked at the interval's ends. With checks at the
ends only, a profile sampled at 1 kHz on ``pocket`` (cutter radius 1,
limits 50/500) rode 1.0003 times its acceleration limit: on an arc of radius
``R`` turning ``theta = 0.05`` rad per interval at constant speed,
``a_j = (v^2/R) cos(phi)`` peaks between two gridpoints where it is
``cos(theta/2)`` of its peak, ``1 - cos(0.025) = 3.1e-4`` below it.

The planner now checks three interior points of each interval and shrinks the
limits on curved intervals by the residual defect between checks
(:func:`ccopt.feed.grid.residual_margins`): the profile, sampled ten times
finer than the verifier does, stays within its limits up to toppra's own
rounding, and the limits still bind.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed.grid import RESIDUAL_SAFETY, interval_samples, residual_margins
from ccopt.geometry import Arc, Line
from ccopt.toolpath import PathSegment, Role, ToolPath

#: toppra's seidel solver holds its constraints to about 1e-9 (feasibility
#: tolerance 1e-8 on squared speeds of order 1): the ratio may exceed 1 by this.
ROUNDING = 1e-8
#: the verifier samples at 1 kHz; ten times finer here
DT = 1e-4


def ratios(toolpath, limits):
    smp = plan_feed(toolpath, limits).sample(DT)
    return smp.axis_acceleration_ratio.max(), smp.axis_velocity_ratio.max()


@pytest.mark.parametrize("name", ["pocket", "pocket-chords", "profile"])
def test_bundled_arcs_at_the_limits_that_overshot(name):
    """The three bundled paths that rode 1.0003 times the acceleration limit at r = 1, 50/500."""
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    path = ccopt.compensate(prog, case.style, radius=1.0)
    acc, vel = ratios(path, AxisLimits((50.0,) * 3, (500.0,) * 3))
    assert acc <= 1.0 + ROUNDING and vel <= 1.0 + ROUNDING
    assert acc > 1.0 - 1e-6          # on the lines the limit binds exactly


def test_circle_under_unequal_axis_limits():
    """A fast full circle, limited by its axis accelerations all the way round:
    the limits hold everywhere and still bind (within the residual margin)."""
    tp = ToolPath((PathSegment(Arc((0.0, 0.0), 5.0, 0.3, 2 * math.pi), Role.COMPENSATED, None,
                               0.0, 0.0, 500.0),))
    acc, vel = ratios(tp, AxisLimits((200.0, 150.0), (2000.0, 900.0)))
    assert acc <= 1.0 + ROUNDING and vel <= 1.0 + ROUNDING
    assert acc > 1.0 - 5e-4


def margins_of(geom, a_axis, gridpoints):
    tp = ToolPath((PathSegment(geom, Role.COMPENSATED, None, 0.0, 0.0, 1e3),))
    path = ExactPath(tp)
    smp = interval_samples(path, np.asarray(gridpoints, float))
    return residual_margins(smp, a_axis, np.full(len(gridpoints), np.inf))


def test_no_margin_on_a_line():
    """On a line ``q'`` is constant and ``q'' = 0``: ``a_j = q_j' u`` is constant
    over the interval, the checks at its ends are exact, the margin is 0."""
    m = margins_of(Line((0.0, 0.0), (3.0, 4.0)), np.array([100.0, 400.0]), [0.0, 1.0, 2.5, 5.0])
    assert np.all(m == 0.0)


@pytest.mark.parametrize("theta", [0.05, 0.2])
def test_margin_on_an_arc_is_the_derived_second_order_figure(theta):
    """On an arc of radius ``R``: ``q''' = -t/R^2``, ``q'''' = -n/R^3``, so
    ``a'' = 5 q''' u + q'''' x`` has length ``sqrt(25 u^2 + (x/R)^2) / R^2 <=
    5 |A|_2 / R^2`` (``(u, x/R)`` is the acceleration in the tangent/normal
    frame, at most the norm of the axis limits). Between checks a quarter of an
    interval apart, ``h = R theta / 4``, an axis exceeds the chord of its
    checked values by at most ``h^2 / 8 * 5 |A|_2 / R^2 = (5/128) theta^2 |A|_2``;
    the margin (the defect measured mid-stretch, times RESIDUAL_SAFETY) is at
    most that relative to the axis's limit, times the safety, and at least the
    purely centripetal part ``(x/R) (1 - cos(theta/8))``, relative."""
    R = 2.0
    a = np.array([1000.0, 1000.0])
    norm = float(np.linalg.norm(a))
    arc = Arc((0.0, 0.0), R, 0.1, 8 * theta)
    m = margins_of(arc, a, R * theta * np.arange(9))
    upper = RESIDUAL_SAFETY * 5.0 / 128.0 * theta ** 2 * norm / a
    assert np.all(m <= upper * (1.0 + theta ** 2))
    lower = (1.0 - math.cos(theta / 8.0)) * norm / a.max()
    assert np.all(m.max(axis=1) >= lower)
    # and of that order (the bound is reached where u and the axis align)
    assert m.max() == pytest.approx(upper.max(), rel=0.5)


def test_circle_at_its_axis_velocity_limits():
    """A circle whose speed the axis velocities limit (accelerations far away):
    ``v_j = s' |t_j|`` peaks where the tangent is along axis ``j``, which a
    gridpoint seldom hits; ``x`` is linear between gridpoints, so holding it at
    ``V_j^2 / max |t_j|^2`` over each interval keeps ``v_j <= V_j`` all along,
    and at the axis directions the speed is then ``V_j`` within the interval's
    turning: ``cos(theta/2)`` at worst, ``theta = 0.05``."""
    tp = ToolPath((PathSegment(Arc((0.0, 0.0), 5.0, 0.3, 2 * math.pi), Role.COMPENSATED, None,
                               0.0, 0.0, 500.0),))
    acc, vel = ratios(tp, AxisLimits((100.0, 100.0), (1e6, 1e6)))
    assert vel <= 1.0 + ROUNDING and acc <= 1.0 + ROUNDING
    assert vel >= math.cos(0.025) ** 2 - 1e-9
