"""``opt-casadi``: a G2 quintic Bezier lead-in/lead-out solved with IPOPT through CasADi.

The model (:func:`lead_model`) and the solve (:func:`solve_lead_model`) are
separate, so the same NLP can go to another CasADi solver (``sqpmethod``,
``bonmin`` ...). The numbers come from :mod:`ccopt_formulations.lead_setup`:

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
                 an arc, |p - E|^2 >= r^2 beyond an end E (beyond a line's open
                 end too, and u . p >= u . E, u its direction out of E),
               |r'(t_i)| >= v_min (a regular curve),

so the path and its speed are optimised together (a small time-optimal
parametrisation inside the NLP, with the machine's own axis limits; TOPPRA
on the exact path gives the reported cycle time). The clearance cases are
taken at the first guess and re-taken at each solution until they no longer
change (at most :data:`MAX_ROUNDS` rounds).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ccopt.compare.contract import BlendProblem
from ccopt.geometry.bezier import DIVISION_FLOOR, curve_samples, end_acceleration, jerk_gram
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt_formulations.clearance import CONCAVE, CONVEX, END, EXEMPT, LINE, classify
from ccopt_formulations.lead_setup import V_MIN_FRACTION, LeadSetup, run_leads

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


def classes_at(setup: LeadSetup, x, m_clear: int):
    """Clearance cases (:func:`ccopt_formulations.clearance.classify`) of every element at the
    curve samples of ``x`` (ends excluded)."""
    pts = bernstein(np.linspace(0.0, 1.0, m_clear)[1:-1], setup.degree) @ setup.controls(x)
    return [classify(el, pts) for el in setup.elements]


def _join_controls(setup: LeadSetup, x):
    """The control points (``(n+1) x 2``, CasADi) of the decision vector ``x``: ``A``,
    the free points, and the G2 end at the host point ``J(sigma)`` (as
    :func:`ccopt.geometry.bezier.g2_end`, with ``J``, its tangent and curvature
    symbolic in ``sigma`` on an arc host)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n = setup.degree
    free = [x[2 * i: 2 * i + 2] for i in range(setup.n_free)]
    a, e, sg = x[-3], x[-2], x[-1]
    if setup.host_kind == "line":
        J = ca.DM(setup.H0) + sg * ca.DM(setup.t0)
        t = ca.DM(setup.t0)
        kappa = 0.0
    else:
        phi = setup.theta0 + setup.sweep_sign * sg / setup.rho
        J = ca.DM(setup.center) + setup.rho * ca.vertcat(ca.cos(phi), ca.sin(phi))
        t = setup.sweep_sign * ca.vertcat(-ca.sin(phi), ca.cos(phi))
        kappa = setup.sweep_sign / setup.rho
    nl = ca.vertcat(-t[1], t[0])
    c = n * kappa * a * a / (n - 1)
    Pm2 = J + (e - 2.0 * a) * t + c * nl
    Pm1 = J - a * t
    return ca.horzcat(ca.DM(setup.A), *free, Pm2, Pm1, J).T


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


def _speed_model(setup: LeadSetup, P, m_time: int) -> SpeedModel:
    """The speed profile of the curve ``P`` and its time (see :class:`SpeedModel`)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n = setup.degree
    b = ca.SX.sym("b", m_time)
    tt = np.linspace(0.0, 1.0, m_time)
    pt = ca.mtimes(ca.DM(bernstein(tt, n)), P)
    d1 = ca.mtimes(ca.DM(bernstein(tt, n - 1) @ derivative_matrix(n, 1)), P)
    d2 = ca.mtimes(ca.DM(bernstein(tt, n - 2) @ derivative_matrix(n, 2)), P)
    sp2 = d1[:, 0] ** 2 + d1[:, 1] ** 2
    sp = ca.sqrt(sp2 + SPEED_SMOOTHING * setup.L0 ** 2)
    Tx, Ty = d1[:, 0] / sp, d1[:, 1] / sp
    dn = d2[:, 0] * Tx + d2[:, 1] * Ty
    Kx = (d2[:, 0] - dn * Tx) / sp2
    Ky = (d2[:, 1] - dn * Ty) / sp2
    dp = pt[1:, :] - pt[:-1, :]
    ds = ca.sqrt(dp[:, 0] ** 2 + dp[:, 1] ** 2 + PIECE_SMOOTHING * setup.L0 ** 2)
    u = (b[1:] - b[:-1]) / (2.0 * ds)
    v = ca.sqrt(b + SPEED_SQUARE_SMOOTHING * setup.feed ** 2)
    a_end = end_acceleration(setup.t0, setup.acc) \
        if setup.host_kind == "line" else float(np.min(setup.acc))
    T = ca.sum1(2.0 * ds / (v[:-1] + v[1:]))
    T += (setup.feed - v[-1]) ** 2 / (2.0 * a_end * setup.feed)
    return SpeedModel(b, sp2, Tx, Ty, Kx, Ky, u, T)


class _Rows:
    """Constraint rows ``lbg <= g <= ubg`` as they are added."""

    def __init__(self):
        self.g, self.lbg, self.ubg = [], [], []

    def add(self, expr, count: int, lo=0.0, hi=None):
        import casadi as ca  # deferred: heavy, and only this blend needs it

        self.g.append(expr)
        self.lbg += lo if isinstance(lo, list) else [lo] * count
        self.ubg += hi if isinstance(hi, list) else [ca.inf if hi is None else hi] * count


def _clearance_rows(rows: _Rows, setup: LeadSetup, classes, pts) -> None:
    """Clearance from every element within reach, by the case of each sample
    (:mod:`ccopt_formulations.clearance`; ``pts`` the curve samples, ends excluded)."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    for el, (kind, vec, scal) in zip(setup.elements, classes):
        for k in (LINE, CONCAVE, CONVEX, END, EXEMPT):
            if k == EXEMPT and el.kind != "line":
                continue                       # beyond an arc's open end: free
            idx = [int(i) for i in np.flatnonzero(kind == k)]
            if not idx:
                continue
            px, py = pts[idx, 0], pts[idx, 1]
            vx, vy, sc = ca.DM(vec[idx, 0]), ca.DM(vec[idx, 1]), ca.DM(scal[idx])
            if k == EXEMPT:
                # beyond a line's open end E: kept beyond it (u . p >= u . E), and r from
                # E. The verifier checks no point there, but one just inside the end
                # (between samples) it does; and a sample left free would drift into
                # the band along the line, where the next round, with its case re-taken,
                # could not move it out (the model fixes each sample's case for a round)
                d = np.subtract(el.geom.p1, el.geom.p0)
                at_start = vec[idx] @ d < 0.0
                E = np.where(at_start[:, None], el.geom.p0, el.geom.p1)
                rows.add(vx * px + vy * py - sc, len(idx))
                rows.add((px - ca.DM(E[:, 0])) ** 2 + (py - ca.DM(E[:, 1])) ** 2
                         - el.clearance ** 2, len(idx))
            elif k == LINE:
                rows.add(vx * px + vy * py - sc, len(idx))
            elif k == CONCAVE:
                rows.add(sc ** 2 - (px - vx) ** 2 - (py - vy) ** 2, len(idx))
            else:
                rows.add((px - vx) ** 2 + (py - vy) ** 2 - sc ** 2, len(idx))


def lead_model(setup: LeadSetup, classes, m_time: int = M_TIME, m_clear: int = M_CLEAR) -> dict:
    """The NLP of one lead as a CasADi dict: ``nlp`` (``x``, ``f``, ``g``),
    bounds ``lbx, ubx, lbg, ubg``, first guess ``x0``."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    n = setup.degree
    x = ca.SX.sym("x", setup.nx)
    P = _join_controls(setup, x)                                  # (n + 1) x 2
    spd = _speed_model(setup, P, m_time)
    G = ca.DM(jerk_gram(n))
    jerk = ca.dot(P[:, 0], ca.mtimes(G, P[:, 0])) + ca.dot(P[:, 1], ca.mtimes(G, P[:, 1]))
    obj = spd.time + (setup.lg.host_length - x[-1]) / setup.feed + setup.jerk_weight * jerk

    rows = _Rows()
    tc = np.linspace(0.0, 1.0, m_clear)
    pts = ca.mtimes(ca.DM(bernstein(tc, n)), P)
    _clearance_rows(rows, setup, classes, pts[1:-1, :])
    # regular curve, at the speed cuts and at the (refined) clearance samples
    vmin = V_MIN_FRACTION * setup.L0
    rows.add(spd.sp2[:] - vmin ** 2, m_time)
    dc = ca.mtimes(ca.DM(bernstein(tc, n - 1) @ derivative_matrix(n, 1)), P)
    rows.add(dc[:, 0] ** 2 + dc[:, 1] ** 2 - vmin ** 2, m_clear)
    # axis accelerations q' s'' + q'' s'^2 within the limits, at both ends of every piece
    ax, ay = float(setup.acc[0]), float(setup.acc[1])
    for end in (slice(0, m_time - 1), slice(1, m_time)):
        rows.add(spd.Tx[end] * spd.u + spd.Kx[end] * spd.b[end], m_time - 1, -ax, ax)
        rows.add(spd.Ty[end] * spd.u + spd.Ky[end] * spd.b[end], m_time - 1, -ay, ay)
    lo, hi = setup.bounds()
    blo = np.zeros(m_time)
    bhi = np.full(m_time, setup.feed ** 2)
    bhi[0] = 0.0                       # the approach point is a stop
    x0 = setup.initial()
    return {"nlp": {"x": ca.vertcat(x, spd.b), "f": obj, "g": ca.vertcat(*rows.g)},
            "lbx": np.r_[lo, blo], "ubx": np.r_[hi, bhi],
            "lbg": np.asarray(rows.lbg, float), "ubg": np.asarray(rows.ubg, float),
            "x0": np.r_[x0, speed_squares(setup, x0, m_time)], "m_time": m_time}


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


def solve_lead_model(model: dict, solver: str = "ipopt", options: dict | None = None, x0=None):
    """Solve a :func:`lead_model` with a CasADi NLP solver: ``(x, stats)``."""
    import casadi as ca  # deferred: heavy, and only this blend needs it

    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
            "ipopt.tol": IPOPT_TOL, "ipopt.constr_viol_tol": IPOPT_TOL,
            "ipopt.max_iter": 1000} \
        if solver == "ipopt" else {}
    opts.update(options or {})
    S = ca.nlpsol("lead", solver, model["nlp"], opts)
    res = S(x0=model["x0"] if x0 is None else x0, lbx=model["lbx"], ubx=model["ubx"],
            lbg=model["lbg"], ubg=model["ubg"])
    st = S.stats()
    return np.asarray(res["x"]).ravel(), {"solver": solver, "status": st.get("return_status"),
                                          "success": bool(st.get("success")),
                                          "iterations": int(st.get("iter_count", -1)),
                                          "objective": float(res["f"])}


def solve_lead(setup: LeadSetup, solver: str = "ipopt"):
    """Solve one lead; re-classify the clearance cases at the solution and solve
    again until they no longer change (at most :data:`MAX_ROUNDS` rounds).

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
    x = setup.initial()
    classes = classes_at(setup, x, m_clear)
    X, stats, rounds = None, {}, 0
    for rounds in range(1, MAX_ROUNDS + 1):
        model = lead_model(setup, classes, m_clear=m_clear)
        X_new, st = solve_lead_model(model, solver, x0=X)
        if not st["success"]:
            if X is None:
                raise RuntimeError(f"IPOPT: {st['status']}")
            stats["note"] = (f"round {rounds} (re-classified clearance cases): IPOPT "
                             f"{st['status']}; round {rounds - 1}'s solution kept")
            rounds -= 1
            break
        X, stats = X_new, st
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
