"""The one-dimensional time bounds bench/blend_gains.py builds its window
bound from: closed forms where they exist, and never above the time of a
motion that keeps the limits (an S-curve written out here)."""
from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

# loaded from its file: bench/ on sys.path would make its feed.py shadow tests/feed
_spec = importlib.util.spec_from_file_location(
    "blend_gains", Path(__file__).resolve().parents[2] / "bench" / "blend_gains.py")
_bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_bench)
rapid_to_feed, travel_from_rest = _bench.rapid_to_feed, _bench.travel_from_rest


def test_travel_from_rest_closed_forms():
    # inside the first jerk phase: L = j t^3 / 6
    assert travel_from_rest(1e-6, 10.0, 2000.0, 20000.0) == pytest.approx(
        (6e-6 / 20000.0) ** (1 / 3), rel=1e-12)
    # v = 10 < a^2/j = 200: two jerk phases of sqrt(v/j) to reach v, covering v sqrt(v/j)
    t = 2.0 * math.sqrt(10.0 / 20000.0)
    assert travel_from_rest(100.0, 10.0, 2000.0, 20000.0) == pytest.approx(
        t + (100.0 - 10.0 * t / 2.0) / 10.0, rel=1e-12)


def _s_curve_time(L, v, a, j, f):
    """A feasible motion from rest over ``L`` arriving at ``f``: jerk-limited up to
    a peak speed and down to ``f`` (acceleration 0 at both ends), the peak the
    largest that fits ``L`` (bisection); its duration."""
    def ramp(dv):                           # time and its average speed factor
        tj = min(a / j, math.sqrt(dv / j))
        return 2.0 * tj + max(dv / a - a / j, 0.0)

    def dist(vp):
        t_up, t_down = ramp(vp), ramp(vp - f)
        return vp * t_up / 2.0 + (vp + f) * t_down / 2.0, t_up + t_down

    lo, hi = f, v
    if dist(v)[0] <= L:
        d, t = dist(v)
        return t + (L - d) / v
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if dist(mid)[0] < L else (lo, mid)
    return dist(lo)[1] + (L - dist(lo)[0]) / lo


@pytest.mark.parametrize("seed", range(20))
def test_rapid_to_feed_is_below_a_feasible_motion(seed):
    rng = np.random.default_rng(seed)
    v, a = rng.uniform(50, 300), rng.uniform(500, 5000)
    j = a * rng.uniform(2, 50)
    f = rng.uniform(1, 0.5 * v)
    L = rng.uniform(0.5, 100)
    bound = rapid_to_feed(L, v, a, j, f)
    assert 0.0 < bound <= _s_curve_time(L, v, a, j, f) + 1e-12
    # and never below the bound that ignores the arrival speed
    assert bound >= L / v


def test_rapid_to_feed_without_jerk_is_bang_bang():
    # j -> infinity, f = 0: up at a to v, cruise, down at a: 0.1 + 0.4 + 0.1 s
    assert rapid_to_feed(100.0, 200.0, 2000.0, 1e12, 0.0) == pytest.approx(0.6, abs=1e-3)
    assert rapid_to_feed(100.0, 200.0, 2000.0, 1e12, 0.0) <= 0.6
