"""Optimised leads without hooks (issue 18 item 6, issue 30 item 3), opt-cvxpy,
quick: the blend alone on three cases where the convex model's leads used to
turn far tighter than their bound, now ``a / v^2`` from the limits and the
lead's feed (worked out by :func:`blend_checks.lead_curvature_bound`). Every
bundled case and generated plates are test_lead_curvature.py's (slow).
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.cases import resolve_input
from ccopt.compare.contract import BlendProblem
from ccopt.compare.registry import load

import blend_checks as bc


@pytest.mark.parametrize("case", ["leadin-inside-line", "leadin-outside-line",
                                  "leadout-inside-arc-arc"])
def test_opt_cvxpy_blends_within_the_curvature_bound(case):
    # the blend alone (no cycle times): every lead it makes, on cases where the
    # convex model's leads used to turn at 3.4 /mm (leadin-inside-line's lead-in),
    # 4.3 /mm and 146 /mm (leadin-outside-line's lead-out, just after the join)
    job = resolve_input(case)
    prog = job.read()
    ref = ccopt.compensate(prog, "pmac", radius=job.radius, side=job.side)
    out = load("opt-cvxpy")(BlendProblem(prog, ref, job.limits(), None, {}, job.radius,
                                         job.side))
    curves = bc.lead_curves(out.toolpath)
    assert len(curves) == 2, out.info["leads"]       # both leads replaced
    for seg, g in curves:
        bound = bc.lead_curvature_bound(seg, job.limits(), ref)
        assert bc.bezier_max_curvature(g) <= bound * (1 + 1e-9)
