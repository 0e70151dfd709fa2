"""The jerk planner's graded grid (``ccopt.feed.jerk.planner.GRADED``) against
its even grid, on generated CAM programs (tests/cam_programs.py, PMAC style,
limits drawn from the seed as in test_jerk_generated.py).

Grading keeps the even grid's spacing within the ramp zones of lines and
arcs, where the speed can change, and coarsens it only where the speed is at
its cap, so the two plans agree to the planner's own tolerance: its rounds
stop when a window's duration settles within
:data:`~ccopt.feed.jerk.windows.DURATION_TOL` (relative). Measured on seeds
100-129: within 7.1e-5, the graded one planned in a third of the CPU time
(median).
"""
from __future__ import annotations

import numpy as np
import pytest

import ccopt.feed.jerk.planner as jerk_planner
from ccopt.feed import plan_feed
from ccopt.feed.jerk.windows import DURATION_TOL
from ccopt.verify.limits import LIMITS_TOL
from feed.test_jerk_generated import _path_and_limits


def _both(seed: int, monkeypatch) -> tuple[float, float, int, int]:
    _, path, lim = _path_and_limits(seed)
    out = []
    for graded in (False, True):
        monkeypatch.setattr(jerk_planner, "GRADED", graded)
        prof = plan_feed(path, lim, planner="jerk")
        out.append((prof.duration, prof.info["gridpoints"]))
    return out[0][0], out[1][0], out[0][1], out[1][1]


def _check(seed, monkeypatch):
    even, graded, n_even, n_graded = _both(seed, monkeypatch)
    assert abs(graded - even) <= DURATION_TOL * even, (seed, even, graded)
    assert n_graded < n_even, seed          # F600 plates: the feed is the cap on most of them


@pytest.mark.parametrize("seed", [4, 127])
def test_graded_grid_plans_as_the_even_one_quick(seed, monkeypatch):
    _check(seed, monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 140))
def test_graded_grid_plans_as_the_even_one(seed, monkeypatch):
    _check(seed, monkeypatch)


def test_no_gridpoint_closer_than_min_spacing_to_a_stop():
    # seed 104: a corner arc of sweep 6.5e-8 rad (6e-8 mm) next to a stop gave
    # gridpoints 3.8e-9 mm apart there, and the LP a squared speed of 0 at one
    # of them (the planner stalled on a coarser grid)
    _, path, lim = _path_and_limits(104)
    g = jerk_planner.build_grid(path, lim, 1e-3)
    stops = g.s[g.stop]
    moving = g.s[~g.stop]
    nearest = np.min(np.abs(moving[:, None] - stops[None, :]), axis=1)
    assert nearest.min() >= jerk_planner.JERK_GRID.min_spacing
    tiny = [k for k, sg in enumerate(path.segments) if sg.length < 1e-7]
    assert tiny, "the program no longer has the degenerate arc this test is about"


@pytest.mark.parametrize("feed", [10.0, 60.0])
@pytest.mark.parametrize("shape", ["tight-bezier", "spiral"])
def test_graded_curves_plan_as_the_even_ones(shape, feed, monkeypatch):
    # curves are graded around their critical samples (grading.curve_braking):
    # the tight quintic's curvature changes fast enough near its middle that
    # |q'''| f^3 there passes the jerk limit at F600
    from feed.test_feed_grid import spiral_path, tight_bezier_path
    from ccopt.feed import AxisLimits, ExactPath
    tp = tight_bezier_path(feed) if shape == "tight-bezier" else spiral_path(feed)
    path = ExactPath(tp)
    lim = AxisLimits((100.0, 100.0), (1000.0, 1000.0), j=(10_000.0, 10_000.0))
    out = []
    for graded in (False, True):
        monkeypatch.setattr(jerk_planner, "GRADED", graded)
        prof = plan_feed(path, lim, planner="jerk")
        assert prof.sample(1e-4).axis_jerk_ratio.max() <= 1 + LIMITS_TOL
        out.append((prof.duration, prof.info["gridpoints"]))
    (even, n_even), (graded, n_graded) = out
    assert abs(graded - even) <= DURATION_TOL * even, (even, graded)
    assert n_graded <= n_even
