"""The smoother: G2 blends at every corner and curvature jump, within a tolerance band.

``smooth(problem)`` takes PMAC's compensated path (the reference) and
replaces, at every join of two feed segments that is not curvature
continuous (a tangent break: inside corners of the tool path, lead-in and
lead-out joins; or a curvature jump: line into arc, arc into corner arc),
the last ``l_in`` of the incoming segment and the first ``l_out`` of the
outgoing one by a Bezier curve of degree 7 that matches position, tangent
and curvature of both at its ends (G2), and that stays in the band:

- never closer than ``r`` to the contour (no gouge), and
- never more than ``delta`` from the reference path, both ways (the blend's
  points are within ``delta`` of the reference, and the reference point it
  cuts off, the corner or the old join, is within ``delta`` of the blend: the
  material a blend leaves in a corner is at most ``delta``).

Each blend is a small convex problem (:class:`CornerModel`, CVXPY with
parameters, compiled once and solved with Clarabel; :func:`solve_model` is
the solver call). In coordinates centred on the join and scaled by the blend
size, with ``x = [a0, e0, a1, e1, P3, P4]`` (the legs and offsets of the
G2 end conditions, :func:`ccopt.geometry.bezier.g2_start` / ``g2_end``, and the
two free control points):

    minimise   integral |r'''|^2 dt + lam * integral |r''|^2 dt
    subject to clearance rows at m samples p_i, one per nearby contour element:
                 line element, foot inside:   n . p_i >= n . A + r   (exact)
                 arc element, tool inside:    |p_i - c| <= R - r      (SOC, exact)
                 arc element, tool outside:   u . (p_i - c) >= R + r  (safe half-plane)
                 foot beyond an end E:        u . (p_i - E) >= r      (safe half-plane)
               |p_i - w_i| <= delta'          (band: w_i the nearest reference point; SOC)
               |p_k - V| <= delta'            (the cut-off reference point V is covered)
               ubar_i . r'(t_i) >= v_min      (a regular curve)
               |a - a_k| <= Delta             (trust region: the curvature terms of the
                                               G2 conditions are linearised in a)

``delta' = BAND_FRACTION * delta`` leaves room for what happens between samples.
The clearance rows are elastic (a slack per sample, priced at
:data:`SLACK_PENALTY`), so a first guess on the wrong side can move; the exact
checks afterwards accept only curves that keep the clearance. The model is
re-linearised a few times (:data:`SCP_ITERATIONS`), and the blend
size is searched: the largest ``l`` (halving from what the neighbouring joins
leave, then bisecting) for which the exact curve passes the exact checks
(distance to every nearby element at dense samples, deviation both ways). The
whole smoothed path then goes to the verifier; a blend that the verifier
faults is solved again smaller, and if that fails the join is left as it was
(reported).
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.figures import joins as path_joins, max_deviation
from ccopt.geometry import BezierCurve
from ccopt.geometry.bezier import DIVISION_FLOOR, energy_root, g2_end, g2_start
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt.toolpath import PathSegment, Role, ToolPath
from ccopt_formulations.clearance import (
    Element, checked_distance, contour_elements, linear_rows, near,
)

DEGREE = 7
#: Samples of the blend constrained in each model.
M_SAMPLES = 25
#: Nearby contour elements per blend (padded), of which concave arcs (SOC rows).
E_MAX = 6
C_MAX = 2
#: Share of ``delta`` the model may use at its samples.
BAND_FRACTION = 0.85
#: Curvature-energy weight against the jerk energy.
LAM = 0.1
SCP_ITERATIONS = 4
#: Price of a unit of clearance slack in the scaled model (the energies are O(1..100)).
SLACK_PENALTY = 1e6
#: Share of a segment a blend may take when another blend uses its other end.
SHARED = 0.45
ALONE = 0.9
#: Blend size search: at most this many shrinking steps (by SHRINK), growing
#: steps (by GROW) and then bisection steps.
SHRINKS = 12
SHRINK = 0.5
GROWS = 3
GROW = 1.6
BISECTIONS = 3
#: Distance below the clearance the exact acceptance checks forgive: rounding
#: only (program units). A blend accepted inside the clearance would use up
#: the verifier's tolerance and leave nothing for its export's arc fit.
CHECK_TOL = 1e-12
#: Shares of the blend size on the incoming and outgoing side, tried in turn.
SHARES = ((1.0, 1.0), (1.0, 0.0), (0.0, 1.0))
#: Dense samples for the exact acceptance checks of one blend.
CHECK_SAMPLES = 801
#: Central-difference step (in the scaled decision variables, O(1)) of the map
#: x -> control points: it is smooth, so this balances truncation and rounding.
JACOBIAN_STEP = 1e-6
#: A linearisation has converged once its clearance slack is at most this
#: (scaled: rounding) and its step at most CONVERGED_STEP (scaled).
CONVERGED_SLACK = 1e-12
CONVERGED_STEP = 1e-6
#: Smallest turn (rad) and curvature jump (1/program units) the first blend size
#: divides by: a join barely broken gets the largest size its segments allow.
MIN_TURN = 1e-3
MIN_JUMP = 1e-9
#: A segment trimmed to at most this length (program units) by the blends at both
#: its ends is gone: the two blends meet.
TRIMMED_AWAY = 1e-12


# --------------------------------------------------------------------------- joins


@dataclass
class Join:
    """A non-G2 join at segment boundary ``index`` (between ``index - 1`` and ``index``)."""

    index: int
    kind: str              # "tangent-break" | "curvature-jump"
    angle: float
    jump: float
    lim_in: float = 0.0
    lim_out: float = 0.0
    l_in: float = 0.0
    l_out: float = 0.0
    curve: BezierCurve | None = None
    status: str = "pending"
    info: dict = field(default_factory=dict)


def find_joins(path: ToolPath) -> list[Join]:
    """Every join of feed segments that is G0 or G1 (``gap`` joins are left alone)."""
    out = []
    for i, cls, _gap, ang, jump in path_joins(path):
        if cls in ("G0", "G1"):
            out.append(Join(i, "tangent-break" if cls == "G0" else "curvature-jump", ang, jump))
    idx = {j.index for j in out}
    segs = path.segments
    for j in out:
        L_in, L_out = segs[j.index - 1].length, segs[j.index].length
        j.lim_in = (SHARED if (j.index - 1) in idx else ALONE) * L_in
        j.lim_out = (SHARED if (j.index + 1) in idx else ALONE) * L_out
    return out


# --------------------------------------------------------------------------- geometry


def _end_data(geom, s):
    p = np.asarray(geom.point(float(s)), float)
    t = np.asarray(geom.tangent(float(s)), float)
    k = float(geom.curvature(float(s)))
    return p, t / np.linalg.norm(t), k


@dataclass
class BlendFrame:
    """One blend's fixed data in world coordinates, and the scaling used by the model."""

    P0: np.ndarray
    t0: np.ndarray
    k0: float
    P7: np.ndarray
    t1: np.ndarray
    k1: float
    V: np.ndarray           # the reference point the blend cuts off (the join point)
    S: float                # scale (l_in + l_out)
    ref_pts: np.ndarray     # dense reference points near the join (world)

    def controls(self, x) -> np.ndarray:
        """World control points of ``x = [a0, e0, a1, e1, P3x, P3y, P4x, P4y]`` (lengths
        in units of ``S``, points relative to ``V`` in units of ``S``)."""
        x = np.asarray(x, float)
        S = self.S
        start = g2_start(self.P0, self.t0, self.k0, x[0] * S, x[1] * S, DEGREE)
        end = g2_end(self.P7, self.t1, self.k1, x[2] * S, x[3] * S, DEGREE)
        mid = self.V + S * x[4:8].reshape(2, 2)
        return np.vstack([start, mid, end])


def _frame(seg_in: PathSegment, seg_out: PathSegment, l_in: float, l_out: float) -> BlendFrame:
    L_in = seg_in.length
    P0, t0, k0 = _end_data(seg_in.geom, L_in - l_in)
    P7, t1, k1 = _end_data(seg_out.geom, l_out)
    V = np.asarray(seg_out.start, float)
    S = l_in + l_out
    h = S / 400.0
    a = seg_in.geom.point(np.linspace(max(0.0, L_in - 2.0 * l_in), L_in,
                                      max(2, int(2 * l_in / h) + 1)))
    b = seg_out.geom.point(np.linspace(0.0, min(seg_out.length, 2.0 * l_out),
                                       max(2, int(2 * l_out / h) + 1)))
    return BlendFrame(P0, t0, k0, P7, t1, k1, V, S, np.vstack([a, b]))


def _initial(fr: BlendFrame) -> np.ndarray:
    a0 = max(np.linalg.norm(fr.V - fr.P0) / (DEGREE / 2.0) / fr.S, 0.05)
    a1 = max(np.linalg.norm(fr.P7 - fr.V) / (DEGREE / 2.0) / fr.S, 0.05)
    P3 = (fr.P0 + 3.0 * a0 * fr.S * fr.t0 - fr.V) / fr.S
    P4 = (fr.P7 - 3.0 * a1 * fr.S * fr.t1 - fr.V) / fr.S
    return np.r_[a0, 0.0, a1, 0.0, P3, P4]


# --------------------------------------------------------------------------- elements


def near_elements(problem: BlendProblem, V, reach: float) -> list[Element]:
    """Contour elements within ``clearance + reach`` of ``V`` (nearest first, at most
    :data:`E_MAX`)."""
    return near(contour_elements(problem.contour), np.asarray(V, float)[None, :], reach,
                limit=E_MAX)


# --------------------------------------------------------------------------- the model


class CornerModel:
    """The convex model of one blend (see the module docstring), compiled once
    with parameters and reused for every join and every linearisation."""

    NX = 8

    def __init__(self, lam: float = LAM):
        import cvxpy as cp  # deferred: heavy, and only this blend needs it

        n, m, nx = DEGREE, M_SAMPLES, self.NX
        self.t = np.linspace(0.0, 1.0, m)
        self.B = bernstein(self.t, n)
        self.D1 = bernstein(self.t, n - 1) @ derivative_matrix(n, 1)
        x = cp.Variable(nx)
        self.x = x
        Par = cp.Parameter
        # control points (scaled, relative to V) = M x + c, per coordinate
        self.Mx, self.My = Par((n + 1, nx)), Par((n + 1, nx))
        self.cx, self.cy = Par(n + 1), Par(n + 1)
        Px, Py = self.Mx @ x + self.cx, self.My @ x + self.cy
        px, py = self.B @ Px, self.B @ Py
        R3 = energy_root(n, 3)
        R2 = energy_root(n, 2)
        obj = cp.sum_squares(R3 @ Px) + cp.sum_squares(R3 @ Py) \
            + lam * (cp.sum_squares(R2 @ Px) + cp.sum_squares(R2 @ Py))
        inner = slice(1, m - 1)
        rows = (m - 2) * E_MAX
        self.G, self.h = Par((rows, nx)), Par(rows)
        # elastic clearance: a linearisation may start infeasible (a corner cut the wrong
        # way); the slack is paid dearly and must be zero in the end (exact checks)
        self.slack = cp.Variable(m - 2, nonneg=True)
        S = np.kron(np.ones((E_MAX, 1)), np.eye(m - 2))
        cons = [self.G @ x >= self.h - S @ self.slack]
        obj += SLACK_PENALTY * cp.sum(self.slack)
        self.cc = [Par(2) for _ in range(C_MAX)]
        self.crho = [Par(m - 2) for _ in range(C_MAX)]     # radius per sample (huge = void)
        for c, rho in zip(self.cc, self.crho):
            cons.append(cp.norm(cp.vstack([px[inner] - c[0], py[inner] - c[1]]), 2, axis=0)
                        <= rho + self.slack)
        self.w0, self.w1 = Par(m), Par(m)
        self.band = Par(nonneg=True)
        cons.append(cp.norm(cp.vstack([px - self.w0, py - self.w1]), 2, axis=0) <= self.band)
        self.vrow_x, self.vrow_y = Par(nx), Par(nx)
        self.vc = Par(2)
        cons.append(cp.norm(cp.hstack([self.vrow_x @ x + self.vc[0], self.vrow_y @ x + self.vc[1]]),
                            2) <= self.band)
        self.Ar, self.br = Par((m, nx)), Par(m)
        cons.append(self.Ar @ x >= self.br)
        self.ak = Par(2)
        self.trust = Par(nonneg=True)
        cons += [cp.abs(x[[0, 2]] - self.ak) <= self.trust, x[[0, 2]] >= 1e-3]
        self.problem = cp.Problem(cp.Minimize(obj), cons)

    def update(self, fr: BlendFrame, xk: np.ndarray, elements: list[Element], band: float,
               trust: float) -> None:
        n, m = DEGREE, M_SAMPLES
        S, V = fr.S, fr.V
        # affine map x -> scaled control points (exact but for the a^2 curvature terms)
        P0 = (fr.controls(xk) - V) / S
        h = JACOBIAN_STEP
        M = np.zeros(((n + 1) * 2, self.NX))
        for k in range(self.NX):
            d = np.zeros(self.NX)
            d[k] = h
            M[:, k] = (((fr.controls(xk + d) - V) / S) - ((fr.controls(xk - d) - V) / S)).ravel() \
                / (2 * h)
        Mx, My = M[0::2], M[1::2]
        self.Mx.value, self.My.value = Mx, My
        self.cx.value, self.cy.value = P0[:, 0] - Mx @ xk, P0[:, 1] - My @ xk
        pk = self.B @ P0                                   # scaled samples at xk
        world = V + S * pk
        BMx, BMy = self.B @ Mx, self.B @ My
        G = np.zeros(((m - 2) * E_MAX, self.NX))
        hh = np.full((m - 2) * E_MAX, -10.0)
        conc = []
        inner = slice(1, m - 1)
        for e, el in enumerate(elements[:E_MAX]):
            g2, h2, soc, vec, scal = linear_rows(el, world[inner])
            # world rows g . p >= h  ->  scaled: g . (V + S p~) >= h
            live = np.isfinite(h2)
            h2 = np.where(live, h2, 0.0)
            rows = slice(e * (m - 2), (e + 1) * (m - 2))
            Gs = g2[:, 0:1] * BMx[inner] + g2[:, 1:2] * BMy[inner]
            base = g2[:, 0] * (pk[inner, 0] - BMx[inner] @ xk) + g2[:, 1] * (pk[inner, 1]
                                                                            - BMy[inner] @ xk)
            hs = (h2 - g2 @ V) / S - base
            G[rows] = np.where(live[:, None], Gs, 0.0)
            hh[rows] = np.where(live, hs, -10.0)
            if soc.any() and len(conc) < C_MAX:
                c = (vec[soc][0] - V) / S
                rad = np.where(soc, scal / S, 10.0 + float(np.max(np.hypot(*(pk[inner] - c).T))))
                conc.append((c, rad))
        self.G.value, self.h.value = G, hh
        for i in range(C_MAX):
            c, rad = conc[i] if i < len(conc) else (np.zeros(2), np.full(m - 2, 10.0))
            self.cc[i].value, self.crho[i].value = c, rad
        # band about the reference, and the cut-off point V covered
        d = np.hypot(world[:, None, 0] - fr.ref_pts[None, :, 0],
                     world[:, None, 1] - fr.ref_pts[None, :, 1])
        w = (fr.ref_pts[np.argmin(d, axis=1)] - V) / S
        self.w0.value, self.w1.value = w[:, 0], w[:, 1]
        self.band.value = band / S
        i_star = int(np.argmin(np.hypot(pk[:, 0], pk[:, 1])))
        self.vrow_x.value, self.vrow_y.value = BMx[i_star], BMy[i_star]
        self.vc.value = np.array([pk[i_star, 0] - BMx[i_star] @ xk, pk[i_star, 1] - BMy[i_star] @ xk])
        # regular curve
        D1 = self.D1
        d1 = D1 @ P0
        sp = np.hypot(d1[:, 0], d1[:, 1])
        ub = d1 / np.maximum(sp, DIVISION_FLOOR)[:, None]
        A = ub[:, 0:1] * (D1 @ Mx) + ub[:, 1:2] * (D1 @ My)
        self.Ar.value = A
        self.br.value = 0.05 - (np.einsum("ij,ij->i", ub, d1) - A @ xk)
        self.ak.value = xk[[0, 2]]
        self.trust.value = trust


def solve_model(model: CornerModel, solver: str = "CLARABEL", **options):
    """The solver call: ``(x or None, status)``."""
    try:
        with warnings.catch_warnings():
            # "solution may be inaccurate": the exact checks after the solve judge it
            warnings.simplefilter("ignore", UserWarning)
            model.problem.solve(solver=solver, **options)
    except Exception as exc:  # solver failure on a bad linearisation: try smaller
        return None, f"solver error: {exc}"
    st = model.problem.status
    if st not in ("optimal", "optimal_inaccurate") or model.x.value is None:
        return None, st
    return np.asarray(model.x.value, float), st


# --------------------------------------------------------------------------- one join


def _exact_ok(curve_pts: np.ndarray, elements, fr: BlendFrame, delta: float, tol: float):
    """Exact checks at dense samples: clearance to every nearby element (ends of the
    blend excluded, they are the reference's own points) and deviation both ways."""
    inner = curve_pts[1:-1]
    for el in elements:
        if np.min(checked_distance(el, inner)) < el.clearance - tol:
            return False, "clearance"
    d = np.hypot(curve_pts[:, None, 0] - fr.ref_pts[None, :, 0],
                 curve_pts[:, None, 1] - fr.ref_pts[None, :, 1])
    if np.max(np.min(d, axis=1)) > delta:
        return False, "band"
    if np.min(np.hypot(*(curve_pts - fr.V).T)) > delta:
        return False, "corner"
    return True, "ok"


def solve_blend(model: CornerModel, fr: BlendFrame, elements, delta: float,
                band_fraction: float = BAND_FRACTION, solver: str = "CLARABEL"):
    """The blend of the frame ``fr``: the model re-linearised and solved up to
    :data:`SCP_ITERATIONS` times (trust region shrinking), then the exact checks
    (:func:`_exact_ok`) on the exact curve. The curve, or ``None`` when there is
    no solution or it fails a check."""
    x = _initial(fr)
    trust = 0.5 * max(x[0], x[2])
    sol = None
    for it in range(SCP_ITERATIONS):
        model.update(fr, x, elements, band_fraction * delta, trust)
        xn, _ = solve_model(model, solver)
        if xn is None:
            break
        step = float(np.max(np.abs(xn - x)))
        x, sol = xn, xn
        if it >= 1 and float(np.max(model.slack.value)) <= CONVERGED_SLACK \
                and step <= CONVERGED_STEP:
            break
        trust *= 0.7
    if sol is None:
        return None
    P = fr.controls(sol)
    pts = bernstein(np.linspace(0.0, 1.0, CHECK_SAMPLES), DEGREE) @ P
    ok, _ = _exact_ok(pts, elements, fr, delta, CHECK_TOL)
    if not ok:
        return None
    try:
        return BezierCurve(P)
    except ValueError:
        return None


def largest_feasible(attempt, start: float, lmax: float):
    """The blend size search: from ``start``, shrink by :data:`SHRINK` until
    ``attempt(l)`` succeeds (at most :data:`SHRINKS` tries); if the first try
    succeeded, grow by :data:`GROW` up to ``lmax`` until one fails; then bisect
    between the largest success and the smallest failure. Returns what
    ``attempt`` gave for the largest size that succeeded, or ``None``."""
    best, bad = None, None
    l = start
    for _ in range(SHRINKS):
        res = attempt(l)
        if res is not None:
            best = (l, res)
            break
        bad = l
        l *= SHRINK
    if best is None:
        return None
    good = best[0]
    if bad is None:
        for _ in range(GROWS):
            if good >= lmax:
                break
            nxt = min(lmax, good * GROW)
            res = attempt(nxt)
            if res is None:
                bad = nxt
                break
            good, best = nxt, (nxt, res)
    if bad is not None:
        for _ in range(BISECTIONS):
            mid = 0.5 * (good + bad)
            res = attempt(mid)
            if res is None:
                bad = mid
            else:
                good, best = mid, (mid, res)
    return best[1]


def solve_join(model: CornerModel, problem: BlendProblem, path: ToolPath, jn: Join, delta: float,
               band_fraction: float = BAND_FRACTION, solver: str = "CLARABEL"):
    """The largest feasible blend at ``jn`` (sets ``jn.curve``, ``l_in``, ``l_out``)."""
    seg_in, seg_out = path.segments[jn.index - 1], path.segments[jn.index]
    lmax = min(jn.lim_in, jn.lim_out)
    if lmax <= 0:
        jn.status = "no room"
        return jn
    V = np.asarray(seg_out.start, float)
    elements = near_elements(problem, V, 2.0 * lmax + delta)

    def attempt(l: float, share):
        l_in = min(l, jn.lim_in) * share[0]
        l_out = min(l, jn.lim_out) * share[1]
        fr = _frame(seg_in, seg_out, l_in, l_out)
        curve = solve_blend(model, fr, elements, delta, band_fraction, solver)
        return None if curve is None else (curve, l_in, l_out)

    # symmetric first; then one-sided (a blend that ends exactly at the join point, as
    # at an open end of the contour, where the other side has no room inside the band)
    for share in SHARES:
        res = largest_feasible(lambda l, share=share: attempt(l, share),
                               min(lmax, size_estimate(jn, delta)), lmax)
        if res is not None:
            jn.curve, jn.l_in, jn.l_out = res
            jn.status = "blended"
            jn.info["share"] = list(share)
            return jn
    jn.status = "no feasible blend"
    return jn


def size_estimate(jn: Join, delta: float) -> float:
    """A first blend size: a G2 blend of legs ``l`` cuts a corner turning by ``theta``
    by about ``l * theta / 6``, and shifts a transition into curvature ``kappa``
    by about ``l^2 * kappa / 3``, so try ``l`` with that equal to ``delta``."""
    if jn.kind == "tangent-break":
        return 6.0 * delta / max(jn.angle, MIN_TURN)
    return math.sqrt(3.0 * delta / max(jn.jump, MIN_JUMP))


# --------------------------------------------------------------------------- the path


def assemble(path: ToolPath, joins: list[Join], style: str = "smooth") -> ToolPath:
    """``path`` with every blended join's curve put in; ``meta["joins"]`` lists
    every feed join of the result (the smoother answers for all of them)."""
    segs = path.segments
    by_index = {j.index: j for j in joins if j.status == "blended"}
    out: list[PathSegment] = []
    new_index = {}
    for i, seg in enumerate(segs):
        j_start = by_index.get(i)
        j_end = by_index.get(i + 1)
        if j_start is not None:
            jb = j_start
            src_in = segs[i - 1]
            feed = min((f for f in (src_in.feed, seg.feed) if f is not None), default=None)
            w = src_in.w1
            out.append(PathSegment(jb.curve, Role.CORNER, src_in.block, w, w, feed))
        s0 = j_start.l_out if j_start is not None else 0.0
        s1 = seg.length - (j_end.l_in if j_end is not None else 0.0)
        g = seg.geom
        if s0 > 0.0 or s1 < seg.length:
            if s1 - s0 <= TRIMMED_AWAY:
                g = None
            else:
                if s1 < seg.length:
                    g = g.split(s1)[0]
                if s0 > 0.0:
                    g = g.split(s0)[1]
        if g is not None:
            L = seg.length
            w0 = seg.w0 + (seg.w1 - seg.w0) * (s0 / L if L else 0.0)
            w1 = seg.w0 + (seg.w1 - seg.w0) * (s1 / L if L else 1.0)
            new_index[i] = len(out)
            out.append(PathSegment(g, seg.role, seg.block, w0, w1, seg.feed))
    dwells = []
    for d, sec, blk in path.dwells:
        k = min((new_index[i] for i in new_index if i >= d), default=len(out))
        dwells.append((k, sec, blk))
    res = ToolPath(tuple(out), plane=path.plane, style=style, radius=path.radius,
                   dwells=tuple(dwells), units=path.units, meta=dict(path.meta))
    res.meta["joins"] = [j[0] for j in path_joins(res)]
    return res


def smooth(problem: BlendProblem, delta: float | None = None, solver: str = "CLARABEL"):
    """Smooth ``problem.reference`` within ``delta`` (default :attr:`BlendProblem.band`).

    Returns ``(toolpath, info)``; ``info["joins"]`` says what became of each join.
    """
    t0 = time.perf_counter()
    delta = float(problem.band if delta is None else delta)
    if not delta > 0:
        raise BlendRejected(f"delta must be > 0, got {delta!r}")
    ref = problem.reference
    joins = find_joins(ref)
    model = CornerModel()
    for jn in joins:
        solve_join(model, problem, ref, jn, delta, solver=solver)
    path = assemble(ref, joins)
    # the verifier has the last word: faulted blends are solved again smaller, then dropped
    for round_ in range(3):
        cert = problem.certify(path)
        bad_segments = {v.tool_segment for v in cert.violations
                        if v.kind in ("gouge", "gap", "side")}
        faulted = [jn for jn in joins if jn.status == "blended"
                   and _segment_of(path, jn.curve) in bad_segments]
        if not faulted:
            break
        for jn in faulted:
            if round_ < 2:
                jn.lim_in *= 0.5
                jn.lim_out *= 0.5
                solve_join(model, problem, ref, jn, 0.5 * delta, solver=solver)
                jn.info["verifier_retries"] = round_ + 1
            else:
                jn.status, jn.curve = "faulted by the verifier", None
        path = assemble(ref, joins)
    dev, dev_bound = max_deviation(path, ref)
    info = {
        "delta": delta,
        "joins_found": len(joins),
        "joins_blended": sum(1 for j in joins if j.status == "blended"),
        "joins": [{"segment": j.index, "kind": j.kind, "angle": j.angle, "curvature_jump": j.jump,
                   "status": j.status, "l_in": j.l_in, "l_out": j.l_out, **j.info}
                  for j in joins],
        "max_deviation": dev,
        "max_deviation_bound": dev_bound,
        "solve_time": time.perf_counter() - t0,
        "certificate": cert,
    }
    return path, info


def _segment_of(path: ToolPath, curve) -> int | None:
    for i, s in enumerate(path.segments):
        if s.geom is curve:
            return i
    return None


def smooth_variant(problem: BlendProblem) -> BlendOutcome:
    """Entry point ``smooth`` (group ``ccopt.blends``): the smoother at ``problem.band``.
    Option ``conic_solver``: the CVXPY solver name (default ``"CLARABEL"``)."""
    path, info = smooth(problem, solver=str(problem.options.get("conic_solver", "CLARABEL")))
    if info["joins_found"] and not info["joins_blended"]:
        raise BlendRejected("no join could be blended within the band")
    return BlendOutcome(path, info)
