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

Each blend is first the closed form of :mod:`ccopt_formulations.smoother_joins`
(sized in closed form and checked, no solver; steps below). Where none passes,
it is a small convex problem (:class:`CornerModel`, CVXPY with parameters,
compiled on first need and solved with Clarabel; :func:`solve_model` is the
solver call). In coordinates centred on the join and scaled by the blend
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
checks afterwards accept only curves that keep the clearance.

How a join is blended (:func:`solve_join`), cheapest first:

1. Before any blend, :func:`ccopt_formulations.smoother_chain.chain_path`
   absorbs PMAC's short corner arcs between chords, so a chorded program is a
   chain of line-line corners (the convex ones blended by an outward closed
   form that keeps outside both lines), and the tiny corner arcs a rounded
   fillet leaves beside a line, whose line then ends at the fillet (no blend
   ending on such an arc can keep the clearance).
2. The closed-form blend (:func:`ccopt_formulations.smoother_joins.initial`):
   at a line-line corner its size is the one whose cut uses the band
   (``(5/16) l sin(theta/2) = delta'``, capped by what the segments leave), and
   it is only checked (clearance, band, cover, curvature bound:
   :func:`ccopt_formulations.smoother_joins.exact_ok`); at other joins the size
   is searched by shrinking and growing, each try one closed form and one check
   (at a curvature jump with its middle points lifted towards the arc's centre
   by a few fixed shares of its size, in turn: into a concave arc of the tool
   path it must turn more sharply than the arc); then the same one-sided (the
   blend ends at the join point).
3. Only where no closed form passes (none of the bundled cases today), the
   convex model above,
   re-linearised up to :data:`SCP_ITERATIONS` times, at sizes halving from the
   estimate and then bisected (:func:`largest_feasible`).
4. Where that fails too at a tiny kink, the closed form once more, allowed to
   come a thousandth of the gouge tolerance nearer the part
   (:meth:`Smoother._kink_tol`).

Every accepted blend keeps its curvature within the bound of
:mod:`ccopt_formulations.smoother_joins` (:data:`~ccopt_formulations.smoother_joins.CURVATURE_FACTOR`
times its turn over its length plus its end curvatures): no hooks. The whole
smoothed path then goes to the verifier once; a blend that the verifier
faults is solved again smaller, and if that fails the join is left as it was
(reported).
"""
from __future__ import annotations

import math
import time
import warnings

import numpy as np

from ccopt.compare.contract import BlendProblem, BlendRejected
from ccopt.geometry import BezierCurve, Line
from ccopt.geometry.bezier import DIVISION_FLOOR, energy_root
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt.stand_ins import import_cvxpy
from ccopt.tolerances import VERIFY_EPS
from ccopt.toolpath import Role, ToolPath
from ccopt.verify.tolerance import resolve_tolerance
from ccopt_formulations.clearance import Element, linear_rows, near
from ccopt_formulations.smoother_chain import APPROACH_SHARE, chain_path
from ccopt_formulations.smoother_deviation import windowed_deviation
from ccopt_formulations.smoother_joins import (  # noqa: F401  (the smoother's vocabulary)
    CHECK_SAMPLES, DEGREE, LIFTS, BlendFrame, ElementIndex, Join, assemble, closed_blend, exact_ok,
    closed_search, contour_inside, find_joins, frame, initial, kink_size, largest_closed,
    grow_one_leg, lasting_gouge, size_estimate,
)

#: Samples of the blend constrained in each model.
M_SAMPLES = 25
#: Nearby contour elements per blend (padded), of which concave arcs (SOC rows).
E_MAX = 6
C_MAX = 2
#: Share of ``delta`` the model may use at its samples, and the closed form's target.
BAND_FRACTION = 0.85
#: Curvature-energy weight against the jerk energy.
LAM = 0.1
SCP_ITERATIONS = 4
#: Price of a unit of clearance slack in the scaled model (the energies are O(1..100)).
SLACK_PENALTY = 1e6
#: The convex model's size search: at most this many shrinking steps (by SHRINK),
#: growing steps (by GROW) and then bisection steps.
SHRINKS = 6
SHRINK = 0.5
GROWS = 3
GROW = 1.6
BISECTIONS = 2
#: Distance below the clearance the exact acceptance checks forgive: rounding
#: only (program units). A blend accepted inside the clearance would use up
#: the verifier's tolerance and leave nothing for its export's arc fit.
CHECK_TOL = 1e-12
#: The shortest blend taken (program units): the verifier's point tolerance
#: (:data:`ccopt.tolerances.VERIFY_EPS`), below which two points are one.
MIN_BLEND = VERIFY_EPS
#: Shares of the blend size on the incoming and outgoing side, tried in turn.
SHARES = ((1.0, 1.0), (1.0, 0.0), (0.0, 1.0))
#: Central-difference step (in the scaled decision variables, O(1)) of the map
#: x -> control points: it is smooth, so this balances truncation and rounding.
JACOBIAN_STEP = 1e-6
#: A linearisation has converged once its clearance slack is at most this
#: (scaled: rounding) and its step at most CONVERGED_STEP (scaled).
CONVERGED_SLACK = 1e-12
CONVERGED_STEP = 1e-6


# --------------------------------------------------------------------------- the model


class CornerModel:
    """The convex model of one blend (see the module docstring), compiled once
    with parameters and reused for every join and every linearisation."""

    NX = 8

    def __init__(self, lam: float = LAM):
        cp = import_cvxpy()  # on first use: heavy, and only this blend needs it

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


def solve_blend(model: CornerModel, fr: BlendFrame, elements, delta: float,
                band_fraction: float = BAND_FRACTION, solver: str = "CLARABEL"):
    """The blend of the frame ``fr`` by the convex model: re-linearised and solved up
    to :data:`SCP_ITERATIONS` times (trust region shrinking) from the closed form,
    then the exact checks (:func:`exact_ok`) on the exact curve. The curve, or
    ``None`` when there is no solution or it fails a check."""
    x = initial(fr)
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
    if not exact_ok(P, elements, fr, delta, CHECK_TOL)[0]:
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



class Smoother:
    """What the joins of one path share: the problem, the path being blended (PMAC's
    with chords chained, :func:`chain_path`), PMAC's path near each join, the
    contour's element index, and the convex model (built on first need)."""

    def __init__(self, problem: BlendProblem, delta: float, solver: str = "CLARABEL"):
        self.problem, self.delta, self.solver = problem, delta, solver
        self.ref = problem.reference
        gouge = resolve_tolerance(problem.tolerance, self.ref.units)
        #: how much closer to the part than the controller's path a change may come where
        #: none keeps away: a tiny corner arc's line, a blend at a tiny kink (:meth:`_kink_tol`)
        self.approach = APPROACH_SHARE * gouge
        self.chain = chain_path(self.ref, BAND_FRACTION * delta, self.approach)
        self.path = self.chain.path
        self.index = ElementIndex(problem.contour)
        self._model = None
        self._elements = None

    @property
    def model(self) -> CornerModel:
        if self._model is None:
            self._model = CornerModel()
        return self._model

    def context(self, k: int):
        """``(ref_geoms, cover)`` of the join before segment ``k`` of the chained
        path: PMAC's feed segments from the one before the incoming segment's origin
        to the one after the outgoing one's, and the points it cuts off (the join
        point; an absorbed corner arc's ends and middle)."""
        segs = self.ref.segments
        lo, hi = self.chain.origin[k - 1], self.chain.origin[k]
        geoms = [segs[i].geom for i in range(max(0, lo - 1), min(len(segs), hi + 2))
                 if segs[i].role in (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)
                 and segs[i].length > 0]
        if hi == lo + 1:
            return geoms, np.asarray(segs[hi].start, float)[None, :], False
        arc = segs[lo + 1].geom
        return (geoms, np.asarray(arc.point(np.linspace(0.0, arc.length, 5)), float),
                lo + 1 not in self.chain.beside_curve)

    def solve_join(self, jn: Join, delta: float) -> Join:
        """The largest blend at ``jn`` that passes the checks: the closed form, else
        the convex model (module docstring). Sets ``jn.curve``, ``l_in``, ``l_out``;
        a blend shorter than :data:`MIN_BLEND` is not taken (status ``"too
        small"``): the verifier cannot tell its ends apart, and it would leave
        the joins beside it a few hundredths of a micrometre apart, where the
        feed planners find no room between two stops (a generated plate's
        lead-out, next to a corner arc 6e-8 long)."""
        self._solve_join(jn, delta)
        if jn.status == "blended" and not jn.curve.length >= MIN_BLEND:
            jn.info["too_small"] = jn.curve.length
            jn.curve, jn.l_in, jn.l_out, jn.status = None, 0.0, 0.0, "too small"
        return jn

    def _solve_join(self, jn: Join, delta: float) -> Join:
        """:meth:`solve_join` before the size rule."""
        path = self.path
        seg_in, seg_out = path.segments[jn.index - 1], path.segments[jn.index]
        lmax = min(jn.lim_in, jn.lim_out)
        if lmax <= 0:
            jn.status = "no room"
            return jn
        V = np.asarray(seg_out.start, float)
        reach = 2.0 * max(jn.lim_in, jn.lim_out) + delta
        elements = self.index.near(V, reach)
        ctx = self.context(jn.index)
        if not ctx[2] and isinstance(seg_in.geom, Line) and isinstance(seg_out.geom, Line) \
                and contour_inside(V, seg_in.geom.tangent(0.0), seg_out.geom.tangent(0.0),
                                   elements):
            ctx = (ctx[0], ctx[1], True)        # a shallow outside corner: outward too
        target = BAND_FRACTION * delta

        def at_legs(l_in: float, l_out: float, tol: float):
            fr = frame(seg_in, seg_out, l_in, l_out, ctx)
            P = closed_blend(fr, elements, delta, tol,
                             LIFTS if jn.kind == "curvature-jump" else (0.0,))
            return None if P is None else (P, l_in, l_out)

        def closed(l: float, share, tol: float):
            l_in, l_out = min(l, jn.lim_in) * share[0], min(l, jn.lim_out) * share[1]
            if ctx[2]:
                # outward: symmetric legs (the closed form's proof is for those)
                l_in = l_out = min(l_in, l_out)
            return at_legs(l_in, l_out, tol)

        # outward: the blend does not cut the corner, so its size is what the chords leave
        start = math.inf if ctx[2] else size_estimate(jn, target)
        # at a line-line corner the closed-form size is exact (a guess elsewhere)
        exact = isinstance(seg_in.geom, Line) and isinstance(seg_out.geom, Line)
        shares = SHARES[:1] if ctx[2] else SHARES
        if closed_search(jn, closed, shares, start, exact, CHECK_TOL):
            if jn.kind == "tangent-break" and not ctx[2]:
                grow_one_leg(jn, at_legs, CHECK_TOL)
            return jn
        self._convex(jn, delta, seg_in, seg_out, min(jn.lim_in, jn.lim_out), ctx)
        kink = self._kink_tol(jn)
        if jn.status != "blended" and kink is not None and \
                closed_search(jn, closed, shares, kink_size(jn, min(target, kink)),
                                    exact, kink):
            jn.info["method"] = "closed form at a tiny kink"
            jn.info["clearance_allowance"] = kink
        return jn

    def _kink_tol(self, jn: Join) -> float | None:
        """The clearance a blend at ``jn`` may give up when ``jn`` is a tiny
        kink (:attr:`approach`), else None.

        A CAM program writes a fillet tangent to its line with a few decimals,
        so the line can meet it with a turn of a few microradians. Where that
        corner is concave the tool path has a kink, and every blend of it cuts
        towards the part: by ``(5/16) l sin(theta/2)`` at legs ``l``, so with
        :data:`CHECK_TOL` alone none is longer than a few nanometres and the
        planners stop there. A kink counts as tiny when a corner arc of the
        cutter radius ``r`` over its turn, ``r (1 - cos theta)``, stays within
        :attr:`approach`, the same share of the gouge tolerance a tiny corner
        arc's line may use (:func:`chain_path`): there blends of about the
        cutter's size give up no more than that."""
        r = self.problem.cutter_radius
        if jn.kind != "tangent-break" or not r > 0.0:
            return None
        return self.approach if r * (1.0 - math.cos(jn.angle)) <= self.approach else None

    def _convex(self, jn, delta, seg_in, seg_out, lmax, ctx) -> Join:
        V = np.asarray(seg_out.start, float)
        elements = near(self.index.near(V, 2.0 * lmax + delta), V[None, :], 2.0 * lmax + delta,
                        limit=E_MAX)

        def attempt(l: float, share):
            l_in = min(l, jn.lim_in) * share[0]
            l_out = min(l, jn.lim_out) * share[1]
            fr = frame(seg_in, seg_out, l_in, l_out, ctx, dense=True)
            curve = solve_blend(self.model, fr, elements, delta, BAND_FRACTION, self.solver)
            return None if curve is None else (curve, l_in, l_out)

        # symmetric first; then one-sided (a blend that ends exactly at the join point, as
        # at an open end of the contour, where the other side has no room inside the band)
        for share in SHARES:
            res = largest_feasible(lambda l, share=share: attempt(l, share),
                                   min(lmax, size_estimate(jn, delta)), lmax)
            if res is not None:
                jn.curve, jn.l_in, jn.l_out = res
                jn.status = "blended"
                jn.info.update(share=list(share), method="convex model")
                return jn
        jn.status = "no feasible blend"
        return jn


def smooth(problem: BlendProblem, delta: float | None = None, solver: str = "CLARABEL",
           deviation: bool = True, certifiable: bool = False):
    """Smooth ``problem.reference`` within ``delta`` (default :attr:`BlendProblem.band`).

    Returns ``(toolpath, info)``; ``info["joins"]`` says what became of each join
    (``segment``: the index in PMAC's path of the segment that starts at the join,
    or of the corner arc an absorbed corner replaced). ``deviation``: also measure
    the Hausdorff distance to PMAC's path (``info["max_deviation"]`` and its bound;
    :func:`~ccopt_formulations.smoother_variant.smooth_variant` leaves it to
    :func:`ccopt.compare.variant.measure`, which measures every variant so). ``certifiable``: raise :class:`BlendRejected`
    before any join is solved when the reference gouges where no blend reaches
    (:func:`~ccopt_formulations.smoother_joins.lasting_gouge`): the result
    could not be certified.
    """
    t0 = time.perf_counter()
    delta = float(problem.band if delta is None else delta)
    if not delta > 0:
        why = (" (the default band is 1 % of the cutter radius, and the radius is 0: give "
               "--delta)" if problem.delta is None else "")
        raise BlendRejected(f"delta must be > 0, got {delta!r}{why}")
    sm = Smoother(problem, delta, solver)
    joins = find_joins(sm.path)
    if certifiable:
        lasting = lasting_gouge(problem, sm.path, sm.ref, sm.chain.origin, joins)
        if lasting is not None:
            raise BlendRejected(lasting)
    for jn in joins:
        sm.solve_join(jn, delta)
    out_origin: list = []
    path = assemble(sm.path, joins, origin=out_origin)
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
                sm.solve_join(jn, 0.5 * delta)
                jn.info["verifier_retries"] = round_ + 1
            else:
                jn.status, jn.curve = "faulted by the verifier", None
        out_origin = []
        path = assemble(sm.path, joins, origin=out_origin)
    origin = sm.chain.origin
    dev = dev_bound = None
    if deviation:
        dev, dev_bound = windowed_deviation(path, sm.ref, [origin[i] for i in out_origin])
    info = {
        "delta": delta,
        "joins_found": len(joins),
        "joins_blended": sum(1 for j in joins if j.status == "blended"),
        "joins": [{"segment": _origin_of(origin, j.index), "kind": j.kind, "angle": j.angle,
                   "curvature_jump": j.jump, "status": j.status, "l_in": j.l_in,
                   "l_out": j.l_out, **j.info}
                  for j in joins],
        "corners_absorbed": len(sm.chain.absorbed),
        "max_deviation": dev,
        "max_deviation_bound": dev_bound,
        "solve_time": time.perf_counter() - t0,
        "certificate": cert,
    }
    return path, info


def _origin_of(origin: list, k: int) -> int:
    """PMAC's segment index for the join before chained segment ``k``: the segment
    that starts there, or the absorbed corner arc just before it."""
    o = origin[k]
    return o - 1 if k >= 1 and origin[k - 1] == o - 2 else o


def _segment_of(path: ToolPath, curve) -> int | None:
    for i, s in enumerate(path.segments):
        if s.geom is curve:
            return i
    return None
