"""No window LP of the jerk planner fails on the 1,000-block pocket of bench/feed.py.

A window whose LP HiGHS cannot solve falls back to an S-curve per stretch
(:mod:`ccopt.feed.jerk.windows`): exact, but slower. Under HiGHS's default
scaling (equilibration) one window of this pocket failed and its six
stretches fell back (157.806 s against 155.014 s planned with no failure);
ccopt scales its LPs by their largest entries instead
(:data:`ccopt.feed.jerk.lp.SIMPLEX_SCALE`). The property asserted is the
planner's own count of failed windows, and that every stretch timed by an
S-curve is a lone straight line (exact by the S-curve, no LP at all).
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, plan_feed

# loaded from its file: bench/ on sys.path would make its feed.py shadow tests/feed
_spec = importlib.util.spec_from_file_location(
    "bench_feed", Path(__file__).resolve().parents[2] / "bench" / "feed.py")
_bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_bench)


@pytest.mark.slow
def test_no_window_lp_fails_on_the_1000_block_pocket():
    path = compensate(_bench.pocket_program(1000), "pmac")
    limits = AxisLimits(v=(200.0, 200.0, 50.0), a=(2000.0, 2000.0, 500.0), j=_bench.JERK)
    prof = plan_feed(path, limits, planner="jerk")
    assert prof.info["lp_failed_windows"] == 0
    assert prof.info["scurve_stretches"] == prof.info["lone_lines"]
