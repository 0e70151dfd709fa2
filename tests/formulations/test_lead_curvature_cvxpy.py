"""Optimised leads without hooks (issue 18 item 6), opt-cvxpy: its leads turn no
tighter than the stated bound, 4 max(1/r, kappa_ref), on every bundled case.

As for opt-casadi (test_lead_curvature.py), the bound is worked out here from
the geometry: ``r`` the cutter radius of PMAC's path, ``kappa_ref`` the largest
curvature of its feed segments (lines 0, arcs 1/R, other curves sampled from
their own derivatives); checked are the comparison table's ``max_curv`` of the
variant and each Bezier lead's own curvature at 20,001 parameter values
(derivatives by the hodograph, written out here).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import bundled_cases, resolve_input
from ccopt.compare import compare
from ccopt.compare.contract import BlendProblem
from ccopt.compare.registry import load
from ccopt.geometry import Arc, BezierCurve, Line
from ccopt.toolpath import Role

FEED = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)


def _curvature(g) -> float:
    if isinstance(g, Line):
        return 0.0
    if isinstance(g, Arc):
        return 1.0 / g.radius
    s = np.linspace(0.0, g.length, 4001)
    return float(np.max(np.abs(g.curvature(s))))


def _basis(t, n):
    """Bernstein basis of degree ``n`` at ``t`` (rows)."""
    k = np.arange(n + 1)
    return np.array([math.comb(n, i) for i in k]) * t[:, None] ** k * (1 - t[:, None]) ** (n - k)


def _bezier_curvature(g: BezierCurve) -> float:
    """Largest |r' x r''| / |r'|^3 of the curve at 20,001 values of its parameter."""
    P = np.asarray(g.control_points, float)
    n = len(P) - 1
    t = np.linspace(0.0, 1.0, 20001)
    d1 = _basis(t, n - 1) @ (n * np.diff(P, axis=0))
    d2 = _basis(t, n - 2) @ (n * (n - 1) * np.diff(P, 2, axis=0))
    return float(np.max(np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
                        / np.hypot(d1[:, 0], d1[:, 1]) ** 3))


def _bound(ref) -> float:
    kref = max((_curvature(s.geom) for s in ref.segments if s.role in FEED and s.length > 0),
               default=0.0)
    return 4.0 * max(1.0 / ref.radius, kref)


@pytest.mark.parametrize("case", ["leadin-inside-line", "leadin-outside-line",
                                  "leadout-inside-arc-arc"])
def test_opt_cvxpy_blends_within_the_curvature_bound(case):
    # the blend alone (no cycle times): every lead it makes, on cases where the
    # convex model's leads used to turn at 3.4 /mm (leadin-inside-line's lead-in),
    # 4.3 /mm and 146 /mm (leadin-outside-line's lead-out, just after the join)
    job = resolve_input(case)
    prog = job.read()
    ref = ccopt.compensate(prog, "pmac", radius=job.radius, side=job.side)
    bound = _bound(ref)
    out = load("opt-cvxpy")(BlendProblem(prog, ref, job.limits(), None, {}, job.radius,
                                         job.side))
    curves = [s.geom for s in out.toolpath.segments if isinstance(s.geom, BezierCurve)]
    assert len(curves) == 2, out.info["leads"]       # both leads replaced
    for g in curves:
        assert _bezier_curvature(g) <= bound * (1 + 1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("case", [c.name for c in bundled_cases()])
def test_opt_cvxpy_leads_within_the_curvature_bound(case):
    job = resolve_input(case)
    prog = job.read()
    try:
        ref = ccopt.compensate(prog, "pmac", radius=job.radius, side=job.side)
    except ccopt.CcoptError:
        # no reference path, so no lead to replace: listed as failed, with no curve
        row = compare(prog, ["opt-cvxpy"], limits=job.limits(), radius=job.radius)["opt-cvxpy"]
        assert row.status == "failed" and row.toolpath is None
        return
    bound = _bound(ref)
    cmp = compare(prog, ["opt-cvxpy"], limits=job.limits(), radius=job.radius, side=job.side)
    row = cmp["opt-cvxpy"]
    if row.status != "ok":
        assert row.status == "rejected", row.message
        return
    assert row.figures["max_curvature"] <= bound
    curves = [s.geom for s in row.toolpath.segments if isinstance(s.geom, BezierCurve)]
    for g in curves:
        assert _bezier_curvature(g) <= bound * (1 + 1e-9)
