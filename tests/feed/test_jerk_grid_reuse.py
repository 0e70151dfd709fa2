"""A refinement pass of the jerk planner builds its finer grid from the last
one's (``build_grid(..., previous=)``, issue 34): the derivatives at the
gridpoints it had, and inside its intervals that are still intervals, are
copied instead of evaluated again. The grid must be the one built from
scratch, every array bit for bit (each derivative is evaluated at its own
position alone, so copying it changes nothing).

Over the refinement passes of generated pockets (small corner arcs: the
passes split intervals there), a CAM chord program and a smoothed path
(blend curves), each pass's grid against the grid built from scratch.
"""
from __future__ import annotations

import dataclasses
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed.jerk import planner as P

# bench/feed.py's generated programs (loaded by path: "feed" is also a test folder)
_spec = importlib.util.spec_from_file_location(
    "bench_feed_grid", Path(__file__).resolve().parents[2] / "bench" / "feed.py")
bench_feed = importlib.util.module_from_spec(_spec)
sys.modules["bench_feed_grid"] = bench_feed
_spec.loader.exec_module(bench_feed)


def _passes_checked(tp: ExactPath, limits: AxisLimits, monkeypatch) -> int:
    """Plan ``tp``; every grid built from a previous one is checked against
    the grid built from scratch. Returns how many were."""
    checked = []
    original = P.build_grid

    def build(path, lim, ts, grid=None, extra=None, previous=None):
        got = original(path, lim, ts, grid, extra, previous)
        if previous is not None:
            fresh = original(path, lim, ts, grid, extra)
            for f in dataclasses.fields(got):
                a, b = getattr(got, f.name), getattr(fresh, f.name)
                if isinstance(a, np.ndarray):
                    np.testing.assert_array_equal(a, b, err_msg=f.name, strict=True)
                else:
                    assert a == b, f.name
            checked.append(got.s.size - previous.s.size)
        return got

    monkeypatch.setattr(P, "build_grid", build)
    monkeypatch.setattr("ccopt.feed.jerk.windows.WORKERS", 1)
    prof = plan_feed(tp, limits, planner="jerk")
    assert len(checked) == prof.info["refine_passes"]
    return len(checked)


LIMITS = AxisLimits(bench_feed.LIMITS.v, bench_feed.LIMITS.a, j=bench_feed.JERK)


@pytest.mark.parametrize("n", (60, 150))
def test_pocket_passes(n, monkeypatch):
    tp = ExactPath(compensate(bench_feed.pocket_program(n, seed=n), "pmac"))
    assert _passes_checked(tp, LIMITS, monkeypatch) > 0


def test_cam_chord_passes(monkeypatch):
    tp = ExactPath(compensate(bench_feed.cam_program(400), "pmac"))
    _passes_checked(tp, LIMITS, monkeypatch)


def test_smoothed_path_passes(monkeypatch):
    from ccopt.cases import make_job
    from ccopt.pipeline import pipeline
    out = pipeline(make_job("pocket-chords", variants=("pmac", "smooth")), compare=True)
    row = next(v for v in out.comparison if v.name == "smooth")
    lim = AxisLimits(out.limits.v, out.limits.a, j=(20000.0, 20000.0, 5000.0))
    _passes_checked(ExactPath(row.toolpath), lim, monkeypatch)
