"""``opt-casadi``: a G2 quintic Bezier lead-in/lead-out solved with IPOPT through CasADi.

The model is built and compiled once per :class:`ModelShape` (host kind,
degree, number of contour elements and samples, solver) with every number of
a lead as a CasADi parameter (:func:`lead_solver`), and reused for every
round and every lead of that shape (:func:`solve_round`: parameters, bounds,
warm start); the solver is a CasADi NLP plug-in (``ipopt`` by default,
``sqpmethod``, ``bonmin`` ...). The numbers come from :mod:`ccopt_formulations.lead_setup`:

    minimise   sum_i 2 ds_i / (v_i + v_i+1) + (F - v_end)^2 / (2 a F)
               + (L_host - sigma)/F + mu * integral |r'''(t)|^2 dt
    over       x = [P1, P2, a, e, sigma]        (P0 = A; P3, P4, P5: G2 at the join)
               and b_i = v_i^2 at m_time cuts of t (the speed along the blend)
    subject to b_0 = 0 (the approach point is a stop), b_i <= F^2,
               |q'_k u_i + q''_k b_i| <= a_k for each axis k at both ends of every
               piece, u_i = (b_i+1 - b_i) / (2 ds_i) (TOPP's discrete model),
               clearance from every element within reach at m_clear samples,
                 by the case of each (ccopt_formulations.clearance): n . p >= n . A + r
                 alongside a line, |p - c|^2 <= (R - r)^2 or >= (R + r)^2 alongside
                 an arc, |p - E|^2 >= r^2 beyond an end E (beyond an open end
                 too, and u . p >= u . E, u the element's direction out of E),
               |r'(t_i)| >= v_min (a regular curve),
               |r'(t_i) x r''(t_i)| <= 0.8 kappa_max |r'(t_i)|^3 (the curvature bound,
                 :func:`ccopt_formulations.lead_setup.curvature_bound`),

so the path and its speed are optimised together (a small time-optimal
parametrisation inside the NLP, with the machine's own axis limits; TOPPRA
on the exact path gives the reported cycle time). The clearance cases are
taken at the first guess (:func:`ccopt_formulations.lead_setup.first_guess`: one
that keeps these rows) and re-taken at each solution until they no longer
change (at most :data:`MAX_ROUNDS` rounds, each after the first warm-started
from the previous one's multipliers).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ccopt.compare.contract import BlendProblem
from ccopt.geometry.bezier import DIVISION_FLOOR, curve_samples, end_acceleration, jerk_gram
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt_formulations.clearance import (CONCAVE, CONVEX, END, EXEMPT, LINE, classify,
                                          exempt_ends)
from ccopt_formulations.lead_setup import (CURVATURE_MODEL_SHARE, V_MIN_FRACTION, LeadSetup,
                                           first_guess, run_leads)

#: Rounds of "solve, re-classify the clearance cases at the solution".
MAX_ROUNDS = 4

#: Cuts of ``t`` where the NLP's speed profile lives (TOPP's discrete model).
M_TIME = 41
#: Curve samples constrained for clearance (times the setup's refine factor).
M_CLEAR = 61

# Smoothing terms under square roots: they keep the NLP differentiable where a
# speed or a piece length is zero, and are far below anything that matters.
#: ... of ``|r'(t)|``, times ``L0^2``;
SPEED_SMOOTHING = 1e-12
#: ... of a piece's chord length, times ``L0^2``;
PIECE_SMOOTHING = 1e-14
#: ... of the speed ``v = sqrt(b)`` (the approach point is a stop, ``b = 0``), times ``F^2``.
SPEED_SQUARE_SMOOTHING = 1e-10

#: IPOPT's convergence and constraint tolerances (the verifier judges the result).
IPOPT_TOL = 1e-9
#: IPOPT's iteration limit: the solves that succeed on the bundled cases take 25 to
#: 240 iterations (with the curvature rows; z-plunges and the sidechange cases
#: 220-240); a lead still unsolved after this many keeps PMAC's (with 1000, two
#: such leads took 3/4 of opt-casadi's time on fagor-g136-g138).
IPOPT_MAX_ITER = 500
#: IPOPT's first barrier parameter (its default is 0.1). The model has about a
#: thousand inequality rows and an objective of a few seconds: at 0.1 the first
#: barrier problems are all barrier, whose centre lies where the rows are slack,
#: far out (|p - E| >= r has no upper side): IPOPT took Newton steps of 1e5 mm
#: cut to a thousandth, 500 iterations without converging on
#: fagor-seed-line-cancel, and 200-240 on the z-plunge and sidechange lead-ins.
#: At 1e-3 every bundled lead solves in 22 to 82 iterations (3,322 in all against
#: 7,651), to the same or a lower objective but for two leads (+0.04 % and +0.1 %).
IPOPT_MU_INIT = 1e-3
#: IPOPT's options for a round warm-started from the previous round's solution
#: and multipliers (the rows are the same, only the clearance cases of a few
#: samples change): a small barrier parameter and small pushes off the bounds, so
#: that IPOPT stays where it is instead of re-centring (a round started from
#: its own converged point took 187 iterations on fagor-g136-g138 without them).
IPOPT_WARM = {"ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6,
              "ipopt.warm_start_bound_push": 1e-9, "ipopt.warm_start_slack_bound_push": 1e-9,
              "ipopt.warm_start_mult_bound_push": 1e-9}


def classes_at(setup: LeadSetup, x, m_clear: int):
    """Clearance cases (:func:`ccopt_formulations.clearance.classify`) of every element at the
    curve samples of ``x`` (ends excluded)."""
    pts = bernstein(np.linspace(0.0, 1.0, m_clear)[1:-1], setup.degree) @ setup.controls(x)
    return [classify(el, pts) for el in setup.elements]


@dataclass(frozen=True)
class ModelShape:
    """What the structure of a lead's NLP depends on; every lead of one shape shares one
    compiled solver (:func:`lead_solver`), its numbers passed as parameters."""

    host_kind: str      # "line" | "arc"
    degree: int
    n_free: int         # free control points (LeadSetup.n_free)
    nx: int             # length of the decision vector (LeadSetup.nx)
    elements: int       # contour elements constrained
    m_clear: int
    m_time: int
    solver: str

    @classmethod
    def of(cls, setup: LeadSetup, m_clear: int, m_time: int, solver: str) -> "ModelShape":
        """The shape of ``setup``'s NLP (its sizes as :class:`LeadSetup` defines them)."""
        return cls(setup.host_kind, setup.degree, setup.n_free, setup.nx,
                   len(setup.elements), m_clear, m_time, solver)


class _Symbols:
    """A lead's numbers (:class:`LeadSetup`) as CasADi parameters: the points ``A``,
    ``H0``, ``t0``, ``center`` and the scalars of :data:`SCALARS`
    (:meth:`values` gives them for one setup)."""

    POINTS = ("A", "H0", "t0", "center")
    SCALARS = ("rho", "theta0", "sweep_sign", "L0", "feed", "a_end", "host_length",
               "jerk_weight", "kappa_cap", "vmin")

    def __init__(self, shape: ModelShape):
        import casadi as ca  # deferred: heavy, and only this blend needs it

        for k in self.POINTS:
            setattr(self, k, ca.SX.sym(k, 2))
        for k in self.SCALARS:
            setattr(self, k, ca.SX.sym(k))
        self.shape = shape

    def vector(self):
        import casadi as ca  # deferred: heavy, and only this blend needs it

        return ca.vertcat(*[getattr(self, k) for k in self.POINTS + self.SCALARS])

    @staticmethod
    def values(setup: LeadSetup) -> np.ndarray:
        a_end = end_acceleration(setup.t0, setup.acc) \
            if setup.host_kind == "line" else float(np.min(setup.acc))
        cap = CURVATURE_MODEL_SHARE * setup.kappa_max if np.isfinite(setup.kappa_max) else 0.0
        center = setup.center if setup.center is not None else np.zeros(2)
        return np.r_[setup.A, setup.H0, setup.t0, center, setup.rho, setup.theta0,
                     setup.sweep_sign, setup.L0, setup.feed, a_end, setup.lg.host_length,
                     setup.jerk_weight, cap, V_MIN_FRACTION * setup.L0]


def _join_controls(sym: _Symbols, x):
    """The control points (``(n+1) x 2``, CasADi) of the decision vector ``x``: ``A``,
    the free points, and the G2 end at the host point ``J(sigma)`` (as
    :func:`ccopt.geometry.bezier.g2_end`, with ``J``, its tangent and curvature
    symbolic in ``sigma`` on an arc host)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n = sym.shape.degree
    free = [x[2 * i: 2 * i + 2] for i in range(sym.shape.n_free)]
    a, e, sg = x[-3], x[-2], x[-1]
    if sym.shape.host_kind == "line":
        J = sym.H0 + sg * sym.t0
        t = sym.t0
        kappa = 0.0
    else:
        phi = sym.theta0 + sym.sweep_sign * sg / sym.rho
        J = sym.center + sym.rho * ca.vertcat(ca.cos(phi), ca.sin(phi))
        t = sym.sweep_sign * ca.vertcat(-ca.sin(phi), ca.cos(phi))
        kappa = sym.sweep_sign / sym.rho
    nl = ca.vertcat(-t[1], t[0])
    c = n * kappa * a * a / (n - 1)
    Pm2 = J + (e - 2.0 * a) * t + c * nl
    Pm1 = J - a * t
    return ca.horzcat(sym.A, *free, Pm2, Pm1, J).T


@dataclass
class SpeedModel:
    """The speed profile inside the NLP: ``b_i = v_i^2`` at ``m_time`` cuts of ``t``
    (TOPP's discrete model), as CasADi expressions of the control points ``P``.

    ``Tx, Ty``: unit tangent ``q'``; ``Kx, Ky``: ``q'' = kappa * normal``
    (1/program units); ``sp2``: ``|r'(t)|^2``; ``u``: the path acceleration
    ``s''`` on each piece; ``time``: the seconds to run the blend and regain
    the feed after it."""

    b: object
    sp2: object
    Tx: object
    Ty: object
    Kx: object
    Ky: object
    u: object
    time: object


def _speed_model(sym: _Symbols, P, m_time: int) -> SpeedModel:
    """The speed profile of the curve ``P`` and its time (see :class:`SpeedModel`)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n = sym.shape.degree
    b = ca.SX.sym("b", m_time)
    tt = np.linspace(0.0, 1.0, m_time)
    pt = ca.mtimes(ca.DM(bernstein(tt, n)), P)
    d1 = ca.mtimes(ca.DM(bernstein(tt, n - 1) @ derivative_matrix(n, 1)), P)
    d2 = ca.mtimes(ca.DM(bernstein(tt, n - 2) @ derivative_matrix(n, 2)), P)
    sp2 = d1[:, 0] ** 2 + d1[:, 1] ** 2
    sp = ca.sqrt(sp2 + SPEED_SMOOTHING * sym.L0 ** 2)
    Tx, Ty = d1[:, 0] / sp, d1[:, 1] / sp
    dn = d2[:, 0] * Tx + d2[:, 1] * Ty
    Kx = (d2[:, 0] - dn * Tx) / sp2
    Ky = (d2[:, 1] - dn * Ty) / sp2
    dp = pt[1:, :] - pt[:-1, :]
    ds = ca.sqrt(dp[:, 0] ** 2 + dp[:, 1] ** 2 + PIECE_SMOOTHING * sym.L0 ** 2)
    u = (b[1:] - b[:-1]) / (2.0 * ds)
    v = ca.sqrt(b + SPEED_SQUARE_SMOOTHING * sym.feed ** 2)
    T = ca.sum1(2.0 * ds / (v[:-1] + v[1:]))
    T += (sym.feed - v[-1]) ** 2 / (2.0 * sym.a_end * sym.feed)
    return SpeedModel(b, sp2, Tx, Ty, Kx, Ky, u, T)


#: Columns of the clearance parameters of each (element, inner sample):
#: row 1 ``vx px + vy py + q |p - c|^2 - k0 >= 0``, row 2 ``q2 |p - c2|^2 - k2 >= 0``.
ROW1, ROW2 = 6, 4


def clearance_numbers(setup: LeadSetup, classes):
    """The clearance parameters ``(C1, C2)`` and lower bounds of both rows for the cases
    ``classes`` (:func:`classes_at`), element by element (see :data:`ROW1`):

    alongside a line ``n . p >= n . A + r``; alongside a concave arc
    ``-|p - c|^2 >= -(R - r)^2``; a convex one ``|p - c|^2 >= (R + r)^2``;
    beyond an end ``E`` ``|p - E|^2 >= r^2``; beyond an *open* end ``E`` of a
    line or an arc ``u . p >= u . E`` and ``|p - E|^2 >= r^2`` (the verifier
    checks no point there, but one just inside the end it does, and a sample
    left free would drift into the band along the element, where the next
    round, with its case re-taken, could not move it out: beyond an arc's open
    end, left free, samples crossed its end radius inside the band between two
    samples on fagor-g136-g138, round after round); beyond an open end of
    another kind: free (both rows void, lower bound ``-inf``).
    """
    rows1, rows2, lo1, lo2 = [], [], [], []
    for el, (kind, vec, scal) in zip(setup.elements, classes):
        m = len(kind)
        C1 = np.zeros((m, ROW1))
        C2 = np.zeros((m, ROW2))
        l1 = np.zeros(m)
        l2 = np.full(m, -np.inf)
        k = kind == LINE
        C1[k, 0:2], C1[k, 5] = vec[k], scal[k]
        for case, sign in ((CONCAVE, -1.0), (CONVEX, 1.0), (END, 1.0)):
            k = kind == case
            C1[k, 2], C1[k, 3:5], C1[k, 5] = sign, vec[k], sign * scal[k] ** 2
        k = kind == EXEMPT
        if el.kind in ("line", "arc") and k.any():
            C1[k, 0:2], C1[k, 5] = vec[k], scal[k]
            C2[k, 0] = 1.0
            C2[k, 1:3] = exempt_ends(el, vec[k])
            C2[k, 3] = el.clearance ** 2
            l2[k] = 0.0
        else:
            l1[k] = -np.inf
        rows1.append(C1)
        rows2.append(C2)
        lo1.append(l1)
        lo2.append(l2)
    if not rows1:        # no element within reach: no clearance rows
        return np.zeros((0, ROW1)), np.zeros((0, ROW2)), np.zeros(0), np.zeros(0)
    return np.vstack(rows1), np.vstack(rows2), np.concatenate(lo1), np.concatenate(lo2)


@dataclass
class LeadSolver:
    """One compiled NLP per :class:`ModelShape` (:func:`lead_solver`): ``solve`` takes a
    lead's parameters, bounds and first guess. Rows, in order: clearance row 1 and
    row 2 of every (element, inner sample), ``|r'|^2 >= v_min^2`` at the speed cuts and
    at the clearance samples, the curvature bound ``cap |r'|^3 -+ r' x r'' >= 0`` at
    the clearance samples, and the axis accelerations at both ends of every piece."""

    shape: ModelShape
    function: object

    def bounds_g(self, setup: LeadSetup, lo1, lo2, m_time: int):
        """``(lbg, ubg)`` of every row."""
        sh = self.shape
        ax, ay = float(setup.acc[0]), float(setup.acc[1])
        curv = 0.0 if np.isfinite(setup.kappa_max) else -np.inf
        lbg = np.r_[lo1, lo2, np.zeros(m_time + sh.m_clear), np.full(2 * sh.m_clear, curv),
                    np.tile(np.r_[np.full(m_time - 1, -ax), np.full(m_time - 1, -ay)], 2)]
        ubg = np.r_[np.full(len(lbg) - 4 * (m_time - 1), np.inf),
                    np.tile(np.r_[np.full(m_time - 1, ax), np.full(m_time - 1, ay)], 2)]
        return lbg, ubg


def _lead_nlp(shape: ModelShape):
    """The NLP of a lead of ``shape``: ``(nlp dict, parameter symbols)``."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n, E, mc, mt = shape.degree, shape.elements, shape.m_clear, shape.m_time
    sym = _Symbols(shape)
    x = ca.SX.sym("x", shape.nx)
    C1 = ca.SX.sym("C1", E * (mc - 2), ROW1)
    C2 = ca.SX.sym("C2", E * (mc - 2), ROW2)
    P = _join_controls(sym, x)                                    # (n + 1) x 2
    spd = _speed_model(sym, P, mt)
    G = ca.DM(jerk_gram(n))
    jerk = ca.dot(P[:, 0], ca.mtimes(G, P[:, 0])) + ca.dot(P[:, 1], ca.mtimes(G, P[:, 1]))
    obj = spd.time + (sym.host_length - x[-1]) / sym.feed + sym.jerk_weight * jerk
    tc = np.linspace(0.0, 1.0, mc)
    pts = ca.mtimes(ca.DM(bernstein(tc, n)), P)
    inner = ca.repmat(pts[1:-1, :], E, 1)
    px, py = inner[:, 0], inner[:, 1]
    g = [C1[:, 0] * px + C1[:, 1] * py
         + C1[:, 2] * ((px - C1[:, 3]) ** 2 + (py - C1[:, 4]) ** 2) - C1[:, 5],
         C2[:, 0] * ((px - C2[:, 1]) ** 2 + (py - C2[:, 2]) ** 2) - C2[:, 3]]
    # regular curve, at the speed cuts and at the (refined) clearance samples
    dc = ca.mtimes(ca.DM(bernstein(tc, n - 1) @ derivative_matrix(n, 1)), P)
    sp2c = dc[:, 0] ** 2 + dc[:, 1] ** 2
    g += [spd.sp2[:] - sym.vmin ** 2, sp2c - sym.vmin ** 2]
    # curvature bound: |r' x r''| <= cap |r'|^3 at the clearance samples
    d2c = ca.mtimes(ca.DM(bernstein(tc, n - 2) @ derivative_matrix(n, 2)), P)
    cross = dc[:, 0] * d2c[:, 1] - dc[:, 1] * d2c[:, 0]
    cap = sym.kappa_cap * sp2c ** 1.5
    g += [cap - cross, cap + cross]
    # axis accelerations q' s'' + q'' s'^2 within the limits, at both ends of every piece
    for end in (slice(0, mt - 1), slice(1, mt)):
        g += [spd.Tx[end] * spd.u + spd.Kx[end] * spd.b[end],
              spd.Ty[end] * spd.u + spd.Ky[end] * spd.b[end]]
    p = ca.vertcat(sym.vector(), ca.vec(C1), ca.vec(C2))
    return {"x": ca.vertcat(x, spd.b), "p": p, "f": obj, "g": ca.vertcat(*g)}


#: Compiled solvers by shape (per process; a handful per comparison).
_SOLVERS: dict = {}


def lead_solver(shape: ModelShape, options: dict | None = None) -> LeadSolver:
    """The compiled solver of ``shape`` (built on first use, then reused)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    key = (shape, tuple(sorted((options or {}).items())))
    if key not in _SOLVERS:
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                "ipopt.tol": IPOPT_TOL, "ipopt.constr_viol_tol": IPOPT_TOL,
                "ipopt.max_iter": IPOPT_MAX_ITER, "ipopt.mu_init": IPOPT_MU_INIT} \
            if shape.solver == "ipopt" else {}
        opts.update(options or {})
        _SOLVERS[key] = LeadSolver(shape, ca.nlpsol("lead", shape.solver, _lead_nlp(shape),
                                                    opts))
    return _SOLVERS[key]


def speed_squares(setup: LeadSetup, x, m: int) -> np.ndarray:
    """``v^2`` at ``m`` cuts of the blend ``x`` by the forward/backward passes (a first guess)."""
    P = setup.controls(x)
    pts, _, k = curve_samples(P, np.linspace(0.0, 1.0, m))
    ds = np.hypot(*np.diff(pts, axis=0).T)
    a = float(np.min(setup.acc))
    b = np.minimum(setup.feed ** 2, a / np.maximum(np.abs(k), DIVISION_FLOOR))
    b[0] = 0.0
    for i in range(m - 1):
        b[i + 1] = min(b[i + 1], b[i] + 2.0 * a * ds[i])
    for i in range(m - 2, -1, -1):
        b[i] = min(b[i], b[i + 1] + 2.0 * a * ds[i])
    return b


def solve_round(setup: LeadSetup, classes, m_clear: int, solver: str = "ipopt",
                options: dict | None = None, x0=None, m_time: int = M_TIME, duals=None):
    """One solve of the lead's NLP with the clearance cases ``classes``: ``(X, stats,
    duals)`` (``X``: the decision vector and the squared speeds; ``duals``: the
    multipliers of the bounds and of the rows). Given the ``duals`` of an earlier
    round of the same shape (and IPOPT), the solve is warm-started from them
    (:data:`IPOPT_WARM`)."""
    shape = ModelShape.of(setup, m_clear, m_time, solver)
    warm = duals is not None and solver == "ipopt"
    ls = lead_solver(shape, {**IPOPT_WARM, **(options or {})} if warm else options)
    C1, C2, lo1, lo2 = clearance_numbers(setup, classes)
    p = np.r_[_Symbols.values(setup), C1.ravel(order="F"), C2.ravel(order="F")]
    lbg, ubg = ls.bounds_g(setup, lo1, lo2, m_time)
    lo, hi = setup.bounds()
    bhi = np.full(m_time, setup.feed ** 2)
    bhi[0] = 0.0                       # the approach point is a stop
    if x0 is None:
        xi = setup.initial()
        x0 = np.r_[xi, speed_squares(setup, xi, m_time)]
    S = ls.function
    extra = {"lam_x0": duals[0], "lam_g0": duals[1]} if warm else {}
    res = S(x0=x0, p=p, lbx=np.r_[lo, np.zeros(m_time)], ubx=np.r_[hi, bhi], lbg=lbg, ubg=ubg,
            **extra)
    st = S.stats()
    return np.asarray(res["x"]).ravel(), {"solver": solver, "status": st.get("return_status"),
                                          "success": bool(st.get("success")),
                                          "iterations": int(st.get("iter_count", -1)),
                                          "objective": float(res["f"])}, \
        (np.asarray(res["lam_x"]).ravel(), np.asarray(res["lam_g"]).ravel())


def solve_lead(setup: LeadSetup, solver: str = "ipopt"):
    """Solve one lead; re-classify the clearance cases at the solution and solve
    again, warm-started, until they no longer change (at most :data:`MAX_ROUNDS`
    rounds). Every round runs the same compiled solver (:func:`lead_solver`).

    A later round can fail where an earlier one succeeded: re-classified at
    the earlier solution, a sample that was beyond an open end of the contour
    (exempt) and now has its foot on an element must get out of that
    element's band on its own side, which from there may be locally
    infeasible. The earlier solution is then returned (``stats["note"]``
    says so): like every blend it is taken only if the verifier certifies it,
    between samples too (:func:`ccopt_formulations.lead_setup.run_leads`).
    """
    t0 = time.perf_counter()
    m_clear = M_CLEAR * setup.refine
    x = first_guess(setup)
    classes = classes_at(setup, x, m_clear)
    X, stats, rounds, duals = None, {}, 0, None
    for rounds in range(1, MAX_ROUNDS + 1):
        x0 = X if X is not None else np.r_[x, speed_squares(setup, x, M_TIME)]
        X_new, st, duals_new = solve_round(setup, classes, m_clear, solver, x0=x0, duals=duals)
        if not st["success"]:
            if X is None:
                raise RuntimeError(f"IPOPT: {st['status']}")
            stats["note"] = (f"round {rounds} (re-classified clearance cases): IPOPT "
                             f"{st['status']}; round {rounds - 1}'s solution kept")
            rounds -= 1
            break
        X, stats, duals = X_new, st, duals_new
        x = X[:setup.nx]
        new = classes_at(setup, x, m_clear)
        if all(np.array_equal(a[0], b[0]) for a, b in zip(new, classes)):
            break
        classes = new
    stats.update(rounds=rounds, solve_time=time.perf_counter() - t0)
    return x, stats


def opt_casadi(problem: BlendProblem):
    """Entry point ``opt-casadi`` (group ``ccopt.blends``). Option ``nlp_solver``:
    the CasADi NLP plug-in (default ``"ipopt"``)."""
    solver = str(problem.options.get("nlp_solver", "ipopt"))
    return run_leads(problem, lambda setup: solve_lead(setup, solver), "opt-casadi")
