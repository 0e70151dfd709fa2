"""The objective of the optimised leads is the planned cycle time (issue 30
item 1): a blend is judged by the time of a window around it
(:mod:`ccopt_formulations.lead_timing`), planned by the planner that times the
variants. Checked here:

- the settle distance of a profile from rest, against a jerk-limited S-curve
  integrated step by step (and ``v^2 / 2a`` without jerk);
- window times order blends as the whole path's cycle times do: on the
  stadium (PMAC CC1, r 2, perpendicular lead from outside, 200 mm/s and
  2000 mm/s^2, with and without 20000 mm/s^3), blends of the lead-in around
  the model's solution, each planned whole and in its window: the differences
  between blends agree (with the jerk planner, within its duration tolerance).
"""
from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import ccopt
from ccopt.compare.contract import BlendProblem
from ccopt.feed import AxisLimits, certified_planner, plan_feed
from ccopt.feed.jerk.windows import DURATION_TOL
from ccopt.feed.path import ExactPath
from ccopt.program import read_text
from ccopt_formulations.blend_casadi import solve_lead
from ccopt_formulations.lead_setup import _is_blend, blend_geometry, lead_setup
from ccopt_formulations.lead_timing import LeadTimer, settle_distance

from cam_programs import STADIUM



def _s_curve_distance(v, a, j, dt=1e-6):
    """Distance to reach ``v`` from rest: jerk ``j`` up to ``a`` (or less), hold,
    jerk ``-j`` down, the phases worked out from ``v`` and integrated in steps."""
    if v >= a * a / j:
        t1, t2 = a / j, v / a - a / j        # ramp time, hold time
    else:
        t1, t2 = math.sqrt(v / j), 0.0
    x = s = acc = 0.0
    for jerk, dur in ((j, t1), (0.0, t2), (-j, t1)):
        for _ in range(int(round(dur / dt))):
            x += s * dt + 0.5 * acc * dt * dt + jerk * dt ** 3 / 6
            s += acc * dt + 0.5 * jerk * dt * dt
            acc += jerk * dt
    assert s == pytest.approx(v, rel=1e-4)
    return x


@pytest.mark.parametrize("v,a,j", [(100.0, 2000.0, 20000.0), (100.0, 2000.0, 1e6),
                                   (10.0, 2000.0, 20000.0), (50.0, 500.0, 5000.0)])
def test_settle_distance_is_the_s_curve_distance(v, a, j):
    assert settle_distance(v, a, j) == pytest.approx(_s_curve_distance(v, a, j), rel=1e-4)
    assert settle_distance(v, a, None) == pytest.approx(v * v / (2 * a), rel=1e-15)


def _setup(limits):
    prog = read_text(STADIUM, dialect="pmac")
    ref = ccopt.compensate(prog, "pmac")
    problem = BlendProblem(prog, ref, limits)
    lead = problem.leads()[0]
    assert lead.kind == "in"
    setup = lead_setup(problem, lead)
    x, _ = solve_lead(setup, "ipopt")
    return problem, ref, lead, setup, x


@pytest.mark.parametrize("jerk", [None, (20000.0, 20000.0, 5000.0)])
def test_window_times_order_blends_as_cycle_times_do(jerk):
    limits = AxisLimits((200.0, 200.0, 50.0), (2000.0, 2000.0, 500.0), j=jerk)
    problem, ref, lead, setup, x = _setup(limits)
    timer = LeadTimer(problem, ref, lead, "opt")
    rng = np.random.default_rng(7)
    d = float(np.linalg.norm(setup.H0 - setup.A))
    blends = [x]
    while len(blends) < 5:
        y = x.copy()
        y[:-1] += rng.normal(scale=0.05 * d, size=len(x) - 1) * (np.arange(len(x) - 1) != len(x) - 3)
        if _is_blend(setup, y, True):
            blends.append(y)
    window, whole = [], []
    for y in blends:
        cand = timer.candidate(blend_geometry(setup, y), float(y[-1]))
        window.append(timer.time(cand))
        prof = plan_feed(ExactPath(cand), limits, planner=certified_planner(limits))
        whole.append(prof.duration)
    # the window is a short piece of the path: most of the cycle is outside it
    assert timer.reach < 0.2 * ref.length
    spread = max(whole) - min(whole)
    assert spread > 1e-3                      # the blends differ in time
    for i, k in itertools.combinations(range(len(blends)), 2):
        dw, dp = window[i] - window[k], whole[i] - whole[k]
        # TOPPRA is exact up to its grid; the jerk planner stops its rounds when a
        # window's duration settles within DURATION_TOL, in both plans
        tol = 1e-3 * spread if jerk is None else 2 * DURATION_TOL * (window[i] + window[k])
        assert dw == pytest.approx(dp, abs=tol), (i, k, dw, dp)
