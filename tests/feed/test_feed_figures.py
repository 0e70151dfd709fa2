"""FeedProfile figures: maxima to a stated bound without a dt grid (ccopt.feed.figures)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed.figures import FIGURE_TOL, derivative_bounds
from ccopt.feed.profile import FeedProfile
from ccopt.geometry import Arc, Line, Spiral
from ccopt.toolpath import PathSegment, Role, ToolPath


def seg(geom, feed=50.0):
    return PathSegment(geom, Role.COMPENSATED, None, 0.0, 0.0, feed)


def steady(geom, speed: float, limits: AxisLimits) -> FeedProfile:
    """One piece at constant path speed over the whole segment."""
    path = ExactPath(ToolPath((seg(geom),)))
    L = path.length
    return FeedProfile.from_knots(path, limits, "test", [L / speed], [0.0, L], [speed, speed],
                                  [0.0], [0])


def test_arc_maxima_inside_the_piece_found_to_the_bound():
    # CCW arc R = 10 from theta 0.3 to 2.0 at 50 units/s: the X velocity -F sin(theta)
    # peaks at theta = pi/2, inside the piece (|vx| = F = 50); the Y acceleration
    # -F^2/R sin(theta) likewise (250). At the piece's ends they are only
    # F sin(2.0) = 45.5 and 227: the knots alone would miss both.
    limits = AxisLimits((100.0, 100.0), (1000.0, 1000.0))
    prof = steady(Arc((0.0, 0.0), 10.0, 0.3, 1.7), 50.0, limits)
    out = prof.summary(1e-3)
    assert 0.5 - FIGURE_TOL <= out["max_axis_vel_ratio"] <= 0.5 + 1e-12
    assert 0.25 - FIGURE_TOL <= out["max_axis_acc_ratio"] <= 0.25 + 1e-12
    assert out["max_feed_ratio"] == pytest.approx(1.0, abs=1e-12)
    # far fewer evaluations than the 1 ms grid would take (341 samples)
    smp, share = prof.figure_samples(1e-3)
    assert len(smp) < 100 and share.sum() == pytest.approx(prof.duration, rel=1e-12)


def test_line_needs_its_piece_ends_only():
    limits = AxisLimits((100.0, 50.0), (1000.0, 400.0))
    tp = ToolPath((seg(Line((0, 0), (60, 80)), feed=None),))
    prof = plan_feed(tp, limits)
    smp, _ = prof.figure_samples(1e-3)
    assert len(smp) == 2 * prof.sdd.size
    out = prof.summary()
    # direction (0.6, 0.8): Y binds, 62.5 units/s and 500 units/s^2 on the path
    assert out["max_axis_vel_ratio"] == pytest.approx(1.0, abs=1e-6)
    assert out["max_axis_acc_ratio"] == pytest.approx(1.0, abs=1e-6)


def test_spiral_figures_agree_with_a_dense_grid():
    # a genuine spiral (radius 2 -> 6 over 1.5 turns) at 40 units/s
    limits = AxisLimits((100.0, 100.0), (1000.0, 1000.0))
    prof = steady(Spiral((0.0, 0.0), 2.0, 6.0, 0.0, 3.0 * math.pi), 40.0, limits)
    fig = prof.summary(1e-3)
    dense = prof.at(np.linspace(0.0, prof.duration, 200_001))
    v_dense = float(dense.axis_velocity_ratio.max())
    a_dense = float(dense.axis_acceleration_ratio.max())
    # the figure is a genuine value (<= the true maximum, which a dense grid
    # approaches from below) and within the stated bound of it
    assert abs(fig["max_axis_vel_ratio"] - v_dense) <= FIGURE_TOL
    assert abs(fig["max_axis_acc_ratio"] - a_dense) <= FIGURE_TOL


def test_spiral_derivative_bounds_hold_against_finite_differences():
    """|q''|, |q'''|, |kappa'| of a spiral measured from its points (polar formula
    worked here, derivatives by differences in arc length) stay under the bounds."""
    rho0, rho1, sweep = 1.0, 4.0, 2.0 * math.pi
    b = (rho1 - rho0) / sweep
    phi = np.linspace(0.0, sweep, 400_001)
    rho = rho0 + b * phi
    pts = np.c_[rho * np.cos(phi), rho * np.sin(phi)]
    step = np.hypot(*np.diff(pts, axis=0).T)
    s = np.r_[0.0, np.cumsum(step)]
    d1 = np.gradient(pts, s, axis=0)
    d2 = np.gradient(d1, s, axis=0)
    d3 = np.gradient(d2, s, axis=0)
    kappa = np.hypot(*d2.T)
    dkappa = np.gradient(kappa, s)
    inner = slice(10, -10)
    K2, K3, _, k1, _, _ = derivative_bounds([Spiral((0.0, 0.0), rho0, rho1, 0.0, sweep)])[0]
    assert kappa[inner].max() <= K2 * (1 + 1e-6)
    assert np.hypot(*d3[inner].T).max() <= K3 * (1 + 1e-6)
    assert np.abs(dkappa[inner]).max() <= k1 * (1 + 1e-6)
    # an arc: exactly 1/R, 1/R^2, 1/R^3; a line: nothing
    assert derivative_bounds([Arc((0, 0), 4.0, 0.0, 1.0)])[0, :3] == pytest.approx([0.25, 1 / 16,
                                                                                     1 / 64])
    assert not derivative_bounds([Line((0, 0), (1, 0))]).any()
