"""``opt-cvxpy``: the G2 lead blend as a sequence of convex problems, solved with Clarabel.

Same curve as ``opt-casadi`` (:mod:`ccopt_formulations.lead_setup`: a Bezier from
the approach point ``A`` matching the host's position, tangent and curvature
at the join, decision vector ``x = [P1 .. P(n-3), a, e, sigma]``), but every
subproblem is convex. At iterate ``x_k`` (:class:`ConvexLeadModel`, the model):

    minimise   len(x)/len0 + lam * E2(x)/E2_0 + mu * E3(x)/E3_0 + M * sum(slack)
    subject to G_ie . p_i(x) >= h_ie - slack_i   (clearance from element e, the row of
                 the case of sample i at x_k: exact alongside a line, the tangent
                 half-plane alongside a convex arc or beyond an end: safe),
               |p_i(x) - c_e| <= R_e - r + slack_i   (alongside a concave arc: a cone),
               ||p_i(x) - w_i|| <= W                            (tolerance band, SOC)
               ubar_i . r'(t_i; x) >= v_min                   (regular curve)
               |nbar_i . r''(t_i; x)| <= kappa_cap |r'(t_i; x_k)|^2 + s_i  (curvature cap,
                 soft, in the iterate's frame: kappa_cap lets the curve run at a share
                 cap_speed of the feed under the axis acceleration)
               ||P_k(x) - P_k(x_k)|| <= Delta, |a - a_k|, |e - e_k|, |sigma - sigma_k| <= Delta

where ``p_i(x)`` are points of the curve at ``m`` samples of ``t``,
``len`` the length of the polyline through them (a sum of norms), ``E2 =
integral |r''|^2 dt`` and ``E3 = integral |r'''|^2 dt`` (convex quadratics),
the clearance rows those of :mod:`ccopt_formulations.clearance` (every half-plane
lies inside the true feasible set, so an iterate with zero slack keeps its
clearance at the samples), ``w_i`` the point of the reference lead
nearest ``p_i(x_k)`` (``|p - w_i| <= W`` implies distance to the reference
``<= W``) and ``ubar_i`` the unit tangent at the iterate (``|r'| >= ubar . r'``).
For a line host the control points are affine in ``x``; for an arc host
they are linearised at ``x_k`` (the curve itself is always built exactly, so
G2 at the join holds whatever the iterate).

:func:`scp` iterates to a fixed point for one ``lam``; :func:`solve_lead`
tries a few ``lam`` (how much curvature costs against length) and curvature
caps, and keeps the curve with the shortest traversal time
(:func:`ccopt.geometry.bezier.speed_profile_time`, the same time model as the
CasADi NLP). :func:`solve_subproblem` is the solver call: the same model
goes to Clarabel (default), ECOS or SCS.
"""
from __future__ import annotations

import math
import time
import warnings

import numpy as np

from ccopt.compare.contract import BlendProblem
from ccopt.geometry.bezier import DIVISION_FLOOR, bezier_energy, energy_root
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt_formulations.clearance import linear_rows
from ccopt_formulations.lead_setup import V_MIN_FRACTION, LeadSetup, run_leads

#: (curvature weight relative to length, curvature cap as a share of the feed) tried.
CANDIDATES = ((0.03, 0.3), (3.0, 0.6))
#: Cuts of the time model when choosing among the candidates.
SELECT_SAMPLES = 801
#: Jerk weight (relative).
MU = 1e-3
#: Slack penalty per unit of violated clearance (relative to the length term).
SLACK_PENALTY = 1e4
MAX_ITER = 12
M_SAMPLES = 31
#: Curvature cap (soft): the curve should allow a share ``cap_speed`` of the feed under the
#: smaller axis acceleration, ``kappa <= a / (cap_speed F)^2``; priced per unit of excess
#: |r''| (t-parametrisation; relative to the length term).
CURVATURE_PENALTY = 10.0
#: Sample multipliers tried when the verifier refuses a blend: one, since this
#: model's samples do not scale with it (a second attempt solved the same
#: problems again and got the same curve).
ATTEMPTS = (1,)
#: Concave arcs (cones) per subproblem; a void row or cone never binds (VOID).
C_MAX = 3
VOID = 1e3

# Lengths below relative to ``L0`` (the lead's approach distance + host reach + r).
#: Central-difference step of the control-point Jacobian (the map is smooth;
#: this balances truncation against rounding).
JACOBIAN_STEP = 1e-6
#: The first trust radius (share of ``L0``); it halves on every refused step.
TRUST_START = 0.1
#: A trust radius below this gives up the iteration: no step can help any more.
TRUST_MIN = 1e-9
#: Slack (clearance violation) that counts as none while iterating: rounding.
SLACK_EPS = 1e-9
#: A step at most this is a fixed point.
STEP_EPS = 1e-5
#: Slack and exact clearance violation the final iterate may have and still be
#: feasible (looser than SLACK_EPS: the last solve may be "optimal_inaccurate").
FEASIBLE_EPS = 1e-7
#: Floor of the energy scales (E2_0, E3_0): a straight first guess has none.
ENERGY_FLOOR = 1e-12


def control_jacobian(setup: LeadSetup, x: np.ndarray, h: float | None = None):
    """``(P(x), dP/dx)`` with ``dP/dx`` of shape ``((n+1)*2, nx)`` (central differences;
    exact for line hosts, where ``P`` is affine in ``x``)."""
    P0 = setup.controls(x)
    h = h or JACOBIAN_STEP * setup.L0
    Jc = np.zeros((P0.size, x.size))
    for k in range(x.size):
        d = np.zeros_like(x)
        d[k] = h
        Jc[:, k] = (setup.controls(x + d) - setup.controls(x - d)).ravel() / (2 * h)
    return P0, Jc


def _reference_points(setup: LeadSetup, problem: BlendProblem) -> np.ndarray:
    """Dense points of the reference lead (PMAC's lead run and host), for the band."""
    ref = problem.reference
    ld = setup.lead
    idx = range(ld.first, ld.host + 1) if ld.kind == "in" else range(ld.host, ld.last + 1)
    pts = []
    for i in idx:
        g = ref.segments[i].geom
        n = max(2, int(math.ceil(g.length / (0.02 * setup.r))) + 1)
        pts.append(np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2))
    return np.vstack(pts)


class ConvexLeadModel:
    """The convex model of one lead for one curvature weight ``lam`` (see the
    module docstring), compiled once with CVXPY parameters (DPP): :meth:`update`
    sets the linearisation at an iterate, :attr:`problem` is what a solver gets.

    Clearance rows: for every element within reach and every inner curve
    sample, the row of its case at the iterate (:func:`ccopt_formulations.clearance.linear_rows`;
    concave arcs as cones), with one slack per curve sample; a step over which
    the exact clearance fails is refused by :func:`scp`, which then shrinks the
    trust region.
    """

    def __init__(self, setup: LeadSetup, lam: float, ref_pts: np.ndarray, band: float,
                 scales: dict, cap_speed: float = 0.5):
        import cvxpy as cp  # deferred: heavy, and only this blend needs it

        self.setup = setup
        self.ref_pts = ref_pts
        self.cap_speed = cap_speed
        # a parameter: one compiled model serves every curvature weight (set_weights)
        self.lam = cp.Parameter(nonneg=True, name="lam", value=float(lam))
        n = setup.degree
        m = M_SAMPLES
        nx = setup.nx
        self.t = np.linspace(0.0, 1.0, m)
        self.B = bernstein(self.t, n)
        self.D1 = bernstein(self.t, n - 1) @ derivative_matrix(n, 1)
        self.D2 = bernstein(self.t, n - 2) @ derivative_matrix(n, 2)
        E = len(setup.elements)
        self.E = E
        x = cp.Variable(nx)
        self.x = x
        P = lambda name, shape: cp.Parameter(shape, name=name)  # noqa: E731
        self.Jx, self.Jy = P("Jx", (n + 1, nx)), P("Jy", (n + 1, nx))
        self.cx, self.cy = P("cx", n + 1), P("cy", n + 1)
        self.xk = P("xk", nx)
        self.delta = cp.Parameter(nonneg=True, name="delta")
        Px = self.Jx @ x + self.cx
        Py = self.Jy @ x + self.cy
        px, py = self.B @ Px, self.B @ Py
        Dm = np.diff(np.eye(m), axis=0)
        obj = cp.sum(cp.norm(cp.vstack([Dm @ px, Dm @ py]), 2, axis=0)) / scales["len"]
        R2 = energy_root(n, 2)
        R3 = energy_root(n, 3)
        obj += self.lam * (cp.sum_squares(R2 @ Px) + cp.sum_squares(R2 @ Py)) / scales["e2"]
        obj += MU * (cp.sum_squares(R3 @ Px) + cp.sum_squares(R3 @ Py)) / scales["e3"]
        cons = []
        self.slack = None
        inner = slice(1, m - 1)
        if E:
            # one row per (element, inner sample); one slack per inner sample
            rows = (m - 2) * E
            self.Ac, self.bc = P("Ac", (rows, nx)), P("bc", rows)
            self.slack = cp.Variable(m - 2, nonneg=True)
            S = np.kron(np.ones((E, 1)), np.eye(m - 2))
            cons.append(self.Ac @ x >= self.bc - S @ self.slack)
            obj += SLACK_PENALTY * cp.sum(self.slack) / scales["len"]
            # concave arcs: cones |p - c| <= R - r (+ slack), void where not alongside
            self.cc = [P(f"cc{i}", 2) for i in range(C_MAX)]
            self.crho = [P(f"crho{i}", m - 2) for i in range(C_MAX)]
            for c, rho in zip(self.cc, self.crho):
                cons.append(cp.norm(cp.vstack([px[inner] - c[0], py[inner] - c[1]]), 2, axis=0)
                            <= rho + self.slack)
        self.w0, self.w1 = P("w0", m), P("w1", m)
        cons.append(cp.norm(cp.vstack([px - self.w0, py - self.w1]), 2, axis=0) <= band)
        self.Ar, self.br = P("Ar", (m, nx)), P("br", m)
        cons.append(self.Ar @ x >= self.br)
        # curvature cap (soft): |nbar . r''| <= kappa_cap |r'|^2 at the iterate's frame
        self.Ak, self.bk = P("Ak", (m, nx)), P("bk", m)
        self.kslack = cp.Variable(m, nonneg=True)
        cons += [self.Ak @ x <= self.bk + self.kslack, -(self.Ak @ x) <= self.bk + self.kslack]
        obj += CURVATURE_PENALTY * cp.sum(self.kslack) / scales["len"]
        for j in range(setup.n_free):
            cons.append(cp.norm(x[2 * j:2 * j + 2] - self.xk[2 * j:2 * j + 2], 2) <= self.delta)
        cons.append(cp.abs(x[-3:] - self.xk[-3:]) <= self.delta)
        lo, hi = setup.bounds()
        cons += [x >= lo, x <= hi]
        self.problem = cp.Problem(cp.Minimize(obj), cons)

    def set_weights(self, lam: float, cap_speed: float) -> None:
        """Another candidate of :data:`CANDIDATES` on the same compiled model."""
        self.lam.value = float(lam)
        self.cap_speed = cap_speed

    def update(self, xk: np.ndarray, delta: float) -> None:
        """Linearise at ``xk`` with trust radius ``delta``."""
        su = self.setup
        Pk, Jc = control_jacobian(su, xk)
        Jx, Jy = Jc[0::2], Jc[1::2]
        self.Jx.value, self.Jy.value = Jx, Jy
        self.cx.value, self.cy.value = Pk[:, 0] - Jx @ xk, Pk[:, 1] - Jy @ xk
        self.xk.value = xk
        self.delta.value = delta
        B = self.B
        pk = B @ Pk
        BJx, BJy = B @ Jx, B @ Jy
        if self.E:
            m = len(pk)
            inner = slice(1, m - 1)
            A_all, b_all, conc = [], [], []
            for el in su.elements:
                G, h, soc, vec, scal = linear_rows(el, pk[inner])
                # G . p(x) = G . (pk + BJ (x - xk)) >= h
                A = G[:, 0:1] * BJx[inner] + G[:, 1:2] * BJy[inner]
                b = h - (np.einsum("ij,ij->i", G, pk[inner]) - A @ xk)
                live = np.isfinite(h)
                A_all.append(np.where(live[:, None], A, 0.0))
                b_all.append(np.where(live, b, -VOID))
                if soc.any() and len(conc) < C_MAX:
                    c = vec[soc][0]
                    conc.append((c, np.where(soc, scal, VOID + float(np.max(
                        np.hypot(*(pk[inner] - c).T))))))
            self.Ac.value = np.vstack(A_all)
            self.bc.value = np.concatenate(b_all)
            for i in range(C_MAX):
                c, rad = conc[i] if i < len(conc) else (np.zeros(2), np.full(m - 2, VOID + float(
                    np.max(np.hypot(*pk[inner].T)))))
                self.cc[i].value, self.crho[i].value = c, rad
        dref = np.hypot(pk[:, None, 0] - self.ref_pts[None, :, 0],
                        pk[:, None, 1] - self.ref_pts[None, :, 1])
        w = self.ref_pts[np.argmin(dref, axis=1)]
        self.w0.value, self.w1.value = w[:, 0], w[:, 1]
        d1k = self.D1 @ Pk
        ub = d1k / np.maximum(np.hypot(d1k[:, 0], d1k[:, 1]), DIVISION_FLOOR)[:, None]
        A = ub[:, 0:1] * (self.D1 @ Jx) + ub[:, 1:2] * (self.D1 @ Jy)
        self.Ar.value = A
        self.br.value = V_MIN_FRACTION * su.L0 - (np.einsum("ij,ij->i", ub, d1k) - A @ xk)
        # normal component of r'' over |r'|^2 is the curvature: cap it where the iterate is
        nb = np.c_[-ub[:, 1], ub[:, 0]]
        D2 = self.D2
        Ak = nb[:, 0:1] * (D2 @ Jx) + nb[:, 1:2] * (D2 @ Jy)
        sp2 = np.einsum("ij,ij->i", d1k, d1k)
        cap = float(np.min(su.acc)) / (self.cap_speed * su.feed) ** 2
        self.Ak.value = Ak
        self.bk.value = cap * sp2 - (np.einsum("ij,ij->i", nb, D2 @ Pk) - Ak @ xk)

    def slack_max(self) -> float:
        return float(np.max(self.slack.value)) if self.slack is not None else 0.0


def solve_subproblem(problem, solver: str = "CLARABEL", **options):
    """The solver call, kept apart from the model: ``problem.solve`` with ``solver``."""
    with warnings.catch_warnings():
        # "solution may be inaccurate": the exact clearance check after the solve judges it
        warnings.simplefilter("ignore", UserWarning)
        try:
            problem.solve(solver=solver, **options)
        except Exception:  # a solver failure on a bad linearisation: the caller shrinks
            return "solver_error"
    return problem.status


def lead_model(setup: LeadSetup, problem: BlendProblem, lam: float,
               cap_speed: float = 0.5) -> ConvexLeadModel:
    """The convex model of one lead, linearised nowhere yet (:meth:`ConvexLeadModel.update`)."""
    xk = setup.initial()
    ref_pts = _reference_points(setup, problem)
    Pk = setup.controls(xk)
    dref = np.hypot(*(Pk[:, None, :] - ref_pts[None]).transpose(2, 0, 1))
    band = float(problem.options.get("band_width", 2.0 * setup.r)) + float(
        np.max(np.min(dref, axis=1)))
    scales = {"len": setup.L0, "e2": max(bezier_energy(Pk, 2), ENERGY_FLOOR),
              "e3": max(bezier_energy(Pk, 3), ENERGY_FLOOR)}
    return ConvexLeadModel(setup, lam, ref_pts, band, scales, cap_speed)


def scp(setup: LeadSetup, problem: BlendProblem, lam: float, solver: str = "CLARABEL",
        cap_speed: float = 0.5, model: ConvexLeadModel | None = None):
    """Iterate the convex model from the first guess to a fixed point: ``(x, info)``.
    ``model``: a :func:`lead_model` of this setup to reuse (its weights are set here).

    Stopping rule: a step of at most :data:`STEP_EPS` ``L0`` with no clearance slack
    (a fixed point), or :data:`MAX_ITER` subproblems, or a trust radius below
    :data:`TRUST_MIN` ``L0``."""
    xk = setup.initial()
    if model is None:
        model = lead_model(setup, problem, lam, cap_speed)
    model.set_weights(lam, cap_speed)
    delta = TRUST_START * setup.L0
    status, it, slack_max = None, 0, math.inf
    for it in range(1, MAX_ITER + 1):
        model.update(xk, delta)
        status = solve_subproblem(model.problem, solver)
        if model.x.value is None or status not in ("optimal", "optimal_inaccurate"):
            delta *= 0.5
            if delta < TRUST_MIN * setup.L0:
                break
            continue
        xn = np.asarray(model.x.value, float)
        slack_max = model.slack_max()
        step = float(np.max(np.abs(xn - xk)))
        # the linearised rows are safe, but cases may change over a step: check exactly
        if slack_max <= SLACK_EPS * setup.L0 and \
                setup.clearance_violation(xn, m=len(model.t)) > SLACK_EPS * setup.L0:
            delta *= 0.5
            continue
        xk = xn
        if step <= STEP_EPS * setup.L0 and slack_max <= SLACK_EPS * setup.L0:
            break
    ok = slack_max <= FEASIBLE_EPS * setup.L0 and \
        setup.clearance_violation(xk, m=len(model.t)) <= FEASIBLE_EPS * setup.L0
    return xk, {"status": status, "iterations": it, "feasible": bool(ok), "lambda": lam,
                "cap_speed": cap_speed}


def solve_lead(setup: LeadSetup, problem: BlendProblem | None = None, solver: str = "CLARABEL"):
    """Run :func:`scp` for each ``(lam, cap_speed)`` of :data:`CANDIDATES`; keep the
    curve with the shortest traversal time (the time model on :data:`SELECT_SAMPLES`
    cuts, fine enough to see a tight turn)."""
    t0 = time.perf_counter()
    best = None
    tried = []
    model = lead_model(setup, problem, *CANDIDATES[0])   # compiled once, for every candidate
    for lam, cap in CANDIDATES:
        x, info = scp(setup, problem, lam, solver, cap, model)
        if not info["feasible"]:
            tried.append((lam, cap, None))
            continue
        T = setup.objective(x, m=SELECT_SAMPLES)
        tried.append((lam, cap, T))
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
    # the curvature bound is not imposed on this model yet: imposed (as a soft cap at
    # 0.8 of the bound, priced 1e4), its iteration ends in hairpins of curvature 6 to
    # 600 /mm on leadin-inside-line and profile, where opt-casadi finds bounded curves
    return run_leads(problem, lambda setup: solve_lead(setup, problem, solver), "opt-cvxpy",
                     attempts=ATTEMPTS, curvature_bounded=False)
