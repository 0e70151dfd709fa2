"""``opt-cvxpy``: the G2 lead blend as a sequence of convex problems, solved with Clarabel.

Same curve as ``opt-casadi`` (:mod:`ccopt_formulations.lead_setup`: a Bezier ``r(t)``
of degree ``n`` from the approach point ``A`` matching the host's position,
tangent and curvature at the join, decision vector ``x = [P1 .. P(n-3), a, e,
sigma]``), but every subproblem is convex. At iterate ``x_k``, with the step
``x = x_k + L0 d`` (:mod:`ccopt_formulations.cvxpy_lead_model` builds it):

    minimise   len(x)/L0 + lam E2(x)/E2_0 + mu E3(x)/E3_0 + M sum(slack) + M_K sum(bslack)
    subject to G_ie . p_i(x) >= h_ie - slack_i   (clearance from element e, the row of
                 the case of sample i at x_k: exact alongside a line, the tangent
                 half-plane alongside a convex arc or beyond an end: safe),
               |p_i(x) - c_e| <= R_e - r + slack_i   (alongside a concave arc: a cone),
               ||p_i(x) - w_i|| <= W                            (tolerance band, SOC)
               ubar_i . r'(t_i; x) >= v_min                    (regular curve)
               the curvature bound at t_i (below)               (bslack_i >= 0)
               ||P_j(x) - P_j(x_k)|| <= Delta, |a - a_k|, |e - e_k|, |sigma - sigma_k| <= Delta

where ``p_i(x)`` are points of the curve at the samples ``t_i`` (equally spaced,
plus a few next to either end: :func:`ccopt_formulations.cvxpy_lead_model.sample_t`),
``len`` the length of the polyline through them (a sum of norms), ``E2 =
integral |r''|^2 dt`` and ``E3 = integral |r'''|^2 dt`` (convex quadratics), the
clearance rows those of :mod:`ccopt_formulations.clearance` (every half-plane
lies inside the true feasible set), ``w_i`` the point of the reference lead
nearest ``p_i(x_k)`` and ``ubar_i`` the unit tangent at the iterate. For a line
host the control points are affine in ``x``; for an arc host they are
linearised at ``x_k`` (the curve itself is always built exactly, so G2 at the
join holds whatever the iterate).

The curvature bound (issue 18 item 6): ``kappa = |r' x r''| / |r'|^3 <= K`` with
``K = CURVATURE_MODEL_SHARE * kappa_max``
(:func:`ccopt_formulations.lead_setup.curvature_bound`, ``a / v^2``),
i.e. ``+-q(x) <= K |r'(x)|^3`` with ``q = r' x r''``. Neither side is concave,
so each row is replaced by a convex *restriction* that is exact at ``x_k``
(the convex-concave procedure; every point the subproblem admits with
``bslack = 0`` keeps ``kappa(t_i) <= K``, so no iterate can grow a hook at a
sample, and a fixed point is a stationary point of the sampled problem):

- ``q`` is bilinear in ``d`` (``r'`` and ``r''`` are affine in it):
  ``q(d) = q_k + g . d + d' M d`` with ``M`` symmetric, of rank at most four and
  at most two positive eigenvalues (``u1 v2 - u2 v1`` has signature (2, 2)).
  With ``M+`` its positive part (eigen-decomposition, two rank-one terms),
  ``+-q(d) <= +-q_k +- g . d + d' (+-M)+ d``: a convex majorant, equal at ``d = 0``;
- ``|v|^3`` is convex, so it lies above its tangent at any ``v0 = s0 u``
  (``u`` the iterate's unit tangent): ``|r'|^3 >= 3 s0^2 u . r' - 2 s0^3``, an
  affine minorant, equal at ``d = 0`` when ``s0 = |r'_k|``.

The row ``+-q_k +- g . d + |(+-M)+^(1/2) d|^2 <= K (3 s0^2 u . r' - 2 s0^3) + K s^3 bslack``
is one second-order cone per sample and sign. ``s0 = rho |r'_k|`` with
``3 rho^2 - 2 rho^3 = phi``: ``phi = 1`` (tight) where the iterate turns at
``1/CURVATURE_GROWTH`` of the bound or more, less (down to ``PHI_MIN``)
elsewhere, where a tight minorant would only keep the speed from falling
(``|r'| >= 2 s0 / 3`` is implied). No row at ``t = 1``: the join has the host's
curvature by construction. The curve between samples is checked densely by
:func:`ccopt_formulations.lead_setup.too_tight` (the full bound) before a blend is
taken; the samples next to the ends see the curvature a short end leg packs
into a sliver of ``t``.

:func:`scp` iterates to a fixed point for one ``lam``; :func:`solve_lead`
tries :data:`LAMBDAS` (how much curvature costs against length) and keeps the
curve with the shortest traversal time (:func:`ccopt.geometry.bezier.speed_profile_time`,
the same time model as the CasADi NLP). The model of a lead's shape is
compiled once per process and reused (every number a CVXPY parameter).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ccopt.compare.contract import BlendProblem
from ccopt.stand_ins import import_cvxpy
from ccopt_formulations.cvxpy_lead_model import (  # noqa: F401  (re-exported)
    M_SAMPLES, ConvexLeadModel, control_jacobian, solve_subproblem)
from ccopt_formulations.lead_setup import (LeadSetup, blend_geometry, near_cusp, run_leads,
                                           too_tight)

#: Curvature weights (relative to length) tried; the first weight's curve, when it is
#: taken, is where the others start (they then need 2 to 4 subproblems, not 3 to 8).
LAMBDAS = (0.03, 3.0)
#: Cuts of the time model when choosing among the candidates.
SELECT_SAMPLES = 201
MAX_ITER = 12
#: Sample multipliers tried when the verifier refuses a blend: one, since this
#: model's samples do not scale with it (a second attempt solved the same
#: problems again and got the same curve).
ATTEMPTS = (1,)

# Lengths below relative to ``L0`` (the lead's approach distance + host reach + r).
#: The first trust radius (share of ``L0``); it halves on every refused step and
#: doubles, up to TRUST_MAX, on a step that reached half of it.
TRUST_START = 0.1
TRUST_MAX = 1.0
#: A trust radius below this gives up the iteration: no step can help any more.
TRUST_MIN = 1e-9
#: Slack (clearance violation) that counts as none while iterating: rounding.
SLACK_EPS = 1e-9
#: A step at most this is a fixed point.
STEP_EPS = 1e-5
#: A subproblem whose optimum improves on the last one's by at most this share has
#: converged for practical purposes (the tail of the iteration creeps towards the
#: curvature bound: on leadin-inside-line it changes the lead's time by 1e-4).
OBJ_RTOL = 1e-3
#: An iteration whose clearance slack stayed above STALL_SHARE of what it was STALL
#: subproblems before gives up (on the Fagor cases' open-end episodes the slack stays
#: at the clearance itself, 2 mm, for all MAX_ITER subproblems of both weights).
STALL = 3
STALL_SHARE = 0.9
#: Slack and exact clearance violation the final iterate may have and still be
#: feasible (looser than SLACK_EPS: the last solve may be "optimal_inaccurate").
FEASIBLE_EPS = 1e-7
#: Relative excess over the curvature-bound rows that counts as none (solver accuracy).
BOUND_EPS = 1e-6


def lead_model(setup: LeadSetup, problem: BlendProblem, lam: float) -> ConvexLeadModel:
    """The convex model of one lead, linearised nowhere yet (:meth:`ConvexLeadModel.update`)."""
    return ConvexLeadModel(setup, problem, lam)


def scp(setup: LeadSetup, problem: BlendProblem, lam: float, solver: str = "CLARABEL",
        model: ConvexLeadModel | None = None, x0=None):
    """Iterate the convex model from ``x0`` (default the first guess) to a fixed point:
    ``(x, info)``. ``model``: a :func:`lead_model` of this setup to reuse (its weight
    is set here).

    Stopping rule: no slack and a step of at most :data:`STEP_EPS` ``L0`` or an
    optimum within :data:`OBJ_RTOL` of the last, or :data:`MAX_ITER` subproblems,
    or a trust radius below :data:`TRUST_MIN` ``L0``, or a clearance slack that
    does not fall (:data:`STALL`)."""
    xk = setup.initial() if x0 is None else np.asarray(x0, float)
    if model is None:
        model = lead_model(setup, problem, lam)
    model.set_weight(lam)
    L0 = setup.L0
    delta = TRUST_START * L0
    status, it, slack_max, bound_max, last = None, 0, math.inf, math.inf, math.inf
    stuck = []      # clearance slack of the iterations so far
    for it in range(1, MAX_ITER + 1):
        model.update(xk, delta)
        status = model.solve(solver)
        xn = model.step()
        if xn is None or status not in ("optimal", "optimal_inaccurate"):
            delta *= 0.5
            if delta < TRUST_MIN * L0:
                break
            continue
        slack_max, bound_max = model.slack_max(), model.bound_slack_max()
        stuck.append(slack_max)
        if len(stuck) > STALL and min(stuck[-STALL:]) > STALL_SHARE * stuck[-STALL - 1] and \
                min(stuck[-STALL:]) > FEASIBLE_EPS * L0:
            break       # the clearance cannot be met from here: no use iterating on
        step = float(np.max(np.abs(xn - xk)))
        # the linearised rows are safe, but cases may change over a step: check exactly
        if slack_max <= SLACK_EPS * L0 and \
                setup.clearance_violation(xn, m=len(model.t)) > SLACK_EPS * L0:
            delta *= 0.5
            continue
        xk = xn
        if step >= 0.5 * delta:
            delta = min(2.0 * delta, TRUST_MAX * L0)
        value = model.value()
        clean = slack_max <= SLACK_EPS * L0 and bound_max <= BOUND_EPS
        if clean and (step <= STEP_EPS * L0 or last - value <= OBJ_RTOL * abs(value)):
            break
        last = value if clean else math.inf
    ok = slack_max <= FEASIBLE_EPS * L0 and bound_max <= BOUND_EPS and \
        setup.clearance_violation(xk, m=len(model.t)) <= FEASIBLE_EPS * L0
    return xk, {"status": status, "iterations": it, "feasible": bool(ok), "lambda": lam}


def solve_lead(setup: LeadSetup, problem: BlendProblem | None = None, solver: str = "CLARABEL"):
    """Run :func:`scp` for each weight of :data:`LAMBDAS`; keep the regular curve within
    the curvature bound (:func:`~ccopt_formulations.lead_setup.too_tight`,
    :func:`~ccopt_formulations.lead_setup.near_cusp`) with the shortest traversal
    time (the time model on :data:`SELECT_SAMPLES` cuts)."""
    t0 = time.perf_counter()
    best = None
    tried = []
    model = lead_model(setup, problem, LAMBDAS[0])   # one model, every weight
    x0 = None
    for lam in LAMBDAS:
        x, info = scp(setup, problem, lam, solver, model, x0)
        if not info["feasible"]:
            # the weight changes the objective, not the constraints: the next fails too
            tried.append((lam, None))
            break
        geom = blend_geometry(setup, x)
        if near_cusp(setup, geom) or too_tight(setup, geom):
            tried.append((lam, None))
            continue
        x0 = x if x0 is None else x0     # the next weights start from the first's curve
        T = setup.objective(x, m=SELECT_SAMPLES)
        tried.append((lam, T))
        if best is None or T < best[0]:
            best = (T, x, info)
    if best is None:
        raise RuntimeError("no feasible convex iterate for any curvature weight")
    _, x, info = best
    info = dict(info, solver=solver, tried=[list(t) for t in tried],
                solve_time=time.perf_counter() - t0)
    return x, info


def opt_cvxpy(problem: BlendProblem):
    """Entry point ``opt-cvxpy`` (group ``ccopt.blends``). Option ``conic_solver``:
    the CVXPY solver name (default ``"CLARABEL"``)."""
    solver = str(problem.options.get("conic_solver", "CLARABEL"))
    return run_leads(problem, lambda setup: solve_lead(setup, problem, solver), "opt-cvxpy",
                     attempts=ATTEMPTS)


#: what the blend imports only when it runs (:data:`ccopt.compare.contract.Blend`)
opt_cvxpy.imports = import_cvxpy
