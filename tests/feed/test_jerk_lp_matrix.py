"""The jerk planner's window LP hands HiGHS its matrix as compressed columns
built directly (:func:`ccopt.feed.jerk.columns.compressed_columns`, issue 34: scipy.sparse's
per-matrix overhead was most of a window's set-up). They must be exactly the
arrays scipy.sparse gives for the same entries: duplicates summed, columns
scaled, zeros left out, and the row indices in the order scipy's product
leaves them (descending in each column), so HiGHS gets the LP it got
before, in the same order, and every plan comes out bit for bit as before.

Over every window the planner builds (its rounds and its local re-plans) on
generated pockets, a CAM chord program and a smoothed path (blend curves:
rows inside intervals), the arrays against scipy's, and on hand-made
entries the sums, the scaling and the zeros.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed.jerk import lp as L
from ccopt.feed.jerk.columns import compressed_columns

# bench/feed.py's generated programs (loaded by path: "feed" is also a test folder)
_spec = importlib.util.spec_from_file_location(
    "bench_feed", Path(__file__).resolve().parents[2] / "bench" / "feed.py")
bench_feed = importlib.util.module_from_spec(_spec)
sys.modules["bench_feed"] = bench_feed
_spec.loader.exec_module(bench_feed)


def _scipy(rows, cols, vals, shape, scale):
    A = sp.csc_matrix((vals, (rows, cols)), shape=shape) @ sp.diags(scale, format="csc")
    return A.indptr, A.indices, A.data


def _same(rows, cols, vals, shape, scale, csc=compressed_columns):
    got = csc(rows, cols, vals, shape[1], scale)
    want = _scipy(rows, cols, vals, shape, scale)
    for a, b in zip(got, want):
        np.testing.assert_array_equal(a, b, strict=False)
        assert a.dtype.kind == b.dtype.kind
    assert got[2].dtype == want[2].dtype


def test_hand_made_entries():
    rows = np.array([0, 2, 0, 1, 2, 1, 0])
    cols = np.array([1, 0, 1, 2, 2, 2, 0])
    vals = np.array([0.1, 2.0, 0.2, 5.0, 1e-3, -5.0, 7.0])
    start, index, value = compressed_columns(rows, cols, vals, 3, np.array([3.0, 0.5, 2.0]))
    # column 0: rows 2 (2 * 3), 0 (7 * 3); column 1: row 0 ((0.1 + 0.2) * 0.5);
    # column 2: row 2 (1e-3 * 2), row 1 (5 - 5 = 0, left out)
    assert start.tolist() == [0, 2, 3, 4]
    assert index.tolist() == [2, 0, 0, 2]
    assert value.tolist() == [6.0, 21.0, (0.1 + 0.2) * 0.5, 2e-3]
    _same(rows, cols, vals, (3, 3), np.array([3.0, 0.5, 2.0]))


def _windows_of(tp: ExactPath, limits: AxisLimits, monkeypatch) -> int:
    """Plan ``tp`` with every window's entries checked against scipy's; returns
    how many windows were built."""
    seen = []
    original = L.compressed_columns

    def checked(rows, cols, vals, n_cols, scale):
        _same(rows, cols, vals, (int(rows.max(initial=-1)) + 1, n_cols), scale, original)
        seen.append(rows.size)
        return original(rows, cols, vals, n_cols, scale)

    monkeypatch.setattr(L, "compressed_columns", checked)
    monkeypatch.setattr("ccopt.feed.jerk.windows.WORKERS", 1)
    plan_feed(tp, limits, planner="jerk")
    return len(seen)


@pytest.mark.parametrize("n", (40, 120))
def test_pocket_windows(n, monkeypatch):
    tp = ExactPath(compensate(bench_feed.pocket_program(n, seed=n), "pmac"))
    lim = AxisLimits(bench_feed.LIMITS.v, bench_feed.LIMITS.a, j=bench_feed.JERK)
    assert _windows_of(tp, lim, monkeypatch) > 5


def test_cam_chord_windows(monkeypatch):
    tp = ExactPath(compensate(bench_feed.cam_program(300), "pmac"))
    lim = AxisLimits(bench_feed.LIMITS.v, bench_feed.LIMITS.a, j=bench_feed.JERK)
    assert _windows_of(tp, lim, monkeypatch) > 0


def test_smoothed_path_windows(monkeypatch):
    from ccopt.cases import make_job
    from ccopt.pipeline import pipeline
    out = pipeline(make_job("pocket-chords", variants=("pmac", "smooth")), compare=True)
    row = next(v for v in out.comparison if v.name == "smooth")
    lim = AxisLimits(out.limits.v, out.limits.a, j=(20000.0, 20000.0, 5000.0))
    assert _windows_of(ExactPath(row.toolpath), lim, monkeypatch) > 0
