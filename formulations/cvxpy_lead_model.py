"""The convex subproblem of ``opt-cvxpy``, compiled once per shape and solved repeatedly.

:mod:`ccopt_formulations.blend_cvxpy` states the model and the curvature
restriction; this module builds it. The CVXPY problem depends only on a
:class:`ModelShape` (Bezier degree, curve samples, contour elements
constrained): every number of a lead and of an iterate is a CVXPY
``Parameter`` and the problem is DPP, so CVXPY canonicalises it once per
shape and per process (:func:`compiled`) and each later solve only maps the
parameter values to the conic data (no re-canonicalisation).

The variable is the step ``d`` from the iterate, in units of the lead's
``L0``: ``x = x_k + L0 d``; lengths in the model are in ``L0`` too, so the
numbers the solver sees are of order one on every case.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ccopt.geometry.bezier import DIVISION_FLOOR, bezier_energy, energy_root
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt.stand_ins import import_cvxpy
from ccopt_formulations.clearance import linear_rows
from ccopt_formulations.lead_setup import CURVATURE_MODEL_SHARE, V_MIN_FRACTION, LeadSetup

#: Curve samples equally spaced in ``t`` (ends included); :data:`END_SAMPLES` are added.
M_SAMPLES = 31
#: Jerk weight (relative to the length term).
MU = 1e-3
#: Slack penalty per unit of violated clearance (in ``L0``, relative to the length term).
SLACK_PENALTY = 1e4
#: Price of exceeding the curvature bound, per unit of the bound rows' relative excess
#: (an exact penalty: any feasible point of the true rows is preferred).
BOUND_PENALTY = 1e3
#: The curvature rows' minorant of ``|r'|^3`` (see blend_cvxpy) is tight where the iterate
#: turns at ``1/CURVATURE_GROWTH`` of the bound or more, and at least PHI_MIN of tight elsewhere.
CURVATURE_GROWTH = 3.0
PHI_MIN = 0.25
#: Extra samples at these distances (in ``t``) from either end (see :func:`sample_t`).
END_SAMPLES = (0.001, 0.002, 0.004, 0.008, 0.016)
#: Concave arcs (cones) per subproblem; a void row or cone never binds (VOID, in ``L0``).
C_MAX = 3
VOID = 1e3
#: Central-difference step of the control-point Jacobian (the map is smooth;
#: this balances truncation against rounding), times ``L0``.
JACOBIAN_STEP = 1e-6
#: Floor of the energy scales (E2_0, E3_0): a straight first guess has none.
ENERGY_FLOOR = 1e-12


@dataclass(frozen=True)
class ModelShape:
    """What the CVXPY problem's structure depends on; leads of one shape share it."""

    degree: int
    m: int          # curve samples
    elements: int   # contour elements constrained
    cones: int      # concave-arc cones (arc elements among them, at most C_MAX)
    free_join: bool  # the join's arc length sigma is a variable (else fixed)

    @property
    def nx(self) -> int:
        return 2 * (self.degree - 3) + 3


class CompiledModel:
    """The DPP problem of one :class:`ModelShape`: variables ``d`` (step), ``slack``
    (clearance, per inner sample), ``bslack`` (curvature bound, per sample); every
    coefficient a parameter (:attr:`par`, by name). The curvature rows are written
    with ``square`` (with one norm cone per row instead, Clarabel took twice the
    iterations on leadin-inside-line: 57 against 28)."""

    def __init__(self, shape: ModelShape):
        cp = import_cvxpy()  # on first use: heavy, and only this blend needs it

        self.shape = shape
        n, m, E, nx = shape.degree, shape.m, shape.elements, shape.nx
        par = {}

        def P(name, dims=(), **kw):
            par[name] = cp.Parameter(dims, name=name, **kw)
            return par[name]

        d = cp.Variable(nx, name="d")
        self.d = d
        nq = 2 * ((n - 1) + (n - 2))     # energy rows: R2 and R3 for x and y
        obj = cp.sum(cp.norm(cp.vstack([P("LJx", (m - 1, nx)) @ d + P("lx", m - 1),
                                        P("LJy", (m - 1, nx)) @ d + P("ly", m - 1)]), 2, axis=0))
        obj += cp.sum_squares(P("Q", (nq, nx)) @ d + P("q", nq))
        px = P("BJx", (m, nx)) @ d
        py = P("BJy", (m, nx)) @ d
        cons = []
        self.slack = None
        if E:
            rows = (m - 2) * E
            self.slack = cp.Variable(m - 2, nonneg=True, name="slack")
            S = np.kron(np.ones((E, 1)), np.eye(m - 2))
            cons.append(P("Ac", (rows, nx)) @ d >= P("bc", rows) - S @ self.slack)
            obj += SLACK_PENALTY * cp.sum(self.slack)
            for i in range(shape.cones):
                cons.append(cp.norm(cp.vstack([px[1:m - 1] + P(f"cx{i}", m - 2),
                                               py[1:m - 1] + P(f"cy{i}", m - 2)]), 2, axis=0)
                            <= P(f"crho{i}", m - 2) + self.slack)
        cons.append(cp.norm(cp.vstack([px + P("wx", m), py + P("wy", m)]), 2, axis=0)
                    <= P("band", nonneg=True))
        cons.append(P("Ar", (m, nx)) @ d >= P("br", m))
        # curvature bound, both signs of r' x r'' (blend_cvxpy: the convex restriction)
        self.bslack = cp.Variable(m, nonneg=True, name="bslack")
        for s in ("p", "n"):
            cons.append(cp.square(P(f"U{s}x", (m, nx)) @ d) + cp.square(P(f"U{s}y", (m, nx)) @ d)
                        + P(f"L{s}", (m, nx)) @ d + P(f"l{s}", m) <= self.bslack)
        obj += BOUND_PENALTY * cp.sum(self.bslack)
        delta = P("delta", nonneg=True)
        for j in range(shape.degree - 3):
            cons.append(cp.norm(d[2 * j:2 * j + 2], 2) <= delta)
        cons.append(cp.abs(d[-3:]) <= delta)
        cons += [d[:-1] >= P("lo", nx - 1), d[:-1] <= P("hi", nx - 1)]
        # the join: on the host between bounds, or fixed (an equality, not two inequalities)
        cons += [d[-1] >= P("slo"), d[-1] <= P("shi")] if shape.free_join else [d[-1] == 0]
        self.par = par
        self.problem = cp.Problem(cp.Minimize(obj), cons)
        if not self.problem.is_dpp():   # it would be canonicalised again at every solve
            raise RuntimeError("the opt-cvxpy lead model is not DPP")

    def set(self, **values) -> None:
        for k, v in values.items():
            self.par[k].value = v


_COMPILED: dict[ModelShape, CompiledModel] = {}


def compiled(shape: ModelShape) -> CompiledModel:
    """The one :class:`CompiledModel` of ``shape`` in this process (built on first use)."""
    if shape not in _COMPILED:
        _COMPILED[shape] = CompiledModel(shape)
    return _COMPILED[shape]


def sample_t(m: int) -> np.ndarray:
    """The model's sample parameters: ``m`` equally spaced, and :data:`END_SAMPLES` from
    either end, where a short end leg (``|r'|`` small at ``t = 0`` or ``1``) packs a
    turn into a sliver of ``t``: near a G2 join on a line, with ``a`` the last leg and
    ``e`` the second, the curvature peaks at ``1 - t ~ a / (4 |e|)`` (quintic), which
    these samples, doubling in distance, see to within 11 % of its height."""
    ends = np.asarray(END_SAMPLES, float)
    return np.unique(np.concatenate([np.linspace(0.0, 1.0, m), ends, 1.0 - ends]))


def control_jacobian(setup: LeadSetup, x: np.ndarray, h: float | None = None):
    """``(P(x), dP/dx)`` with ``dP/dx`` of shape ``((n+1)*2, nx)`` (central differences;
    exact for line hosts, where ``P`` is affine in ``x``)."""
    P0 = setup.controls(x)
    h = h or JACOBIAN_STEP * setup.L0
    Jc = np.zeros((P0.size, x.size))
    for k in range(x.size):
        dx = np.zeros_like(x)
        dx[k] = h
        Jc[:, k] = (setup.controls(x + dx) - setup.controls(x - dx)).ravel() / (2 * h)
    return P0, Jc


def reference_points(setup: LeadSetup, problem) -> np.ndarray:
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


def curvature_rows(r1, r2, F, H, K: float, v_floor: float) -> dict:
    """Parameter values of the curvature-bound rows at the iterate (``L0`` units).

    ``r1, r2``: ``r'``, ``r''`` of the iterate at the samples (``(m, 2)``); ``F, H``:
    their derivatives by ``d`` (``(2, m, nx)``, x then y); ``K``: the bound imposed
    (``1/L0``); ``v_floor``: least speed ``|r'|^3`` is linearised at. For each sign
    (``p``: ``+q``, ``n``: ``-q``, ``q = r' x r''``) the rows are
    ``|U_x d|^2 + |U_y d|^2 + L d + l <= bslack``, each divided by ``K s^3`` (see
    :mod:`ccopt_formulations.blend_cvxpy` for the majorant and minorant)."""
    s_true = np.hypot(r1[:, 0], r1[:, 1])
    s = np.maximum(s_true, v_floor)
    u = r1 / np.maximum(s_true, DIVISION_FLOOR)[:, None]
    Fx, Fy, Hx, Hy = F[0], F[1], H[0], H[1]
    q0 = r1[:, 0] * r2[:, 1] - r1[:, 1] * r2[:, 0]
    grad = (r1[:, 0:1] * Hy + r2[:, 1:2] * Fx - r1[:, 1:2] * Hx - r2[:, 0:1] * Fy)
    outer = np.einsum("ij,ik->ijk", Fx, Hy) - np.einsum("ij,ik->ijk", Fy, Hx)
    w, V = np.linalg.eigh(0.5 * (outer + outer.transpose(0, 2, 1)))   # ascending
    # K |r'|^3 >= K (3 s0^2 u.r' - 2 s0^3) for any s0 = rho s: tight (rho = 1) where the
    # iterate turns at a share 1/CURVATURE_GROWTH of the bound or more, looser elsewhere
    phi = np.clip(CURVATURE_GROWTH * np.abs(q0) / (K * s ** 3), PHI_MIN, 1.0)
    s0 = s * (0.5 - np.sin(np.arcsin(1.0 - 2.0 * phi) / 3.0))    # 3 rho^2 - 2 rho^3 = phi
    rhs0 = K * (3 * s0 * s0 * np.einsum("ij,ij->i", u, r1) - 2 * s0 ** 3)
    rhs_d = (3 * K * s0 * s0)[:, None] * (u[:, 0:1] * Fx + u[:, 1:2] * Fy)
    out = {}
    for name, sg, cols in (("p", 1.0, (-1, -2)), ("n", -1.0, (0, 1))):
        L = sg * grad - rhs_d
        # each row divided by the larger of K s^3 and its gradient's norm: coefficients
        # of order one (a slow sample near an end has K s^3 small) for the solver
        scale = np.maximum(K * s ** 3, np.sqrt(np.einsum("ij,ij->i", L, L)))
        # the positive part of the form sg * M: at most two eigenvalues (see the model)
        rows = [np.sqrt(np.maximum(sg * w[:, k], 0.0) / scale)[:, None] * V[:, :, k]
                for k in cols]
        L, l = L / scale[:, None], (sg * q0 - rhs0) / scale
        # the join (t = 1) has the host's curvature by construction (G2): no row there,
        # which would only keep the speed from falling (by the minorant) and help nothing
        rows[0][-1], rows[1][-1], L[-1], l[-1] = 0.0, 0.0, 0.0, -1.0
        out.update({f"U{name}x": rows[0], f"U{name}y": rows[1], f"L{name}": L, f"l{name}": l})
    return out


class ConvexLeadModel:
    """The convex model of one lead (see :mod:`ccopt_formulations.blend_cvxpy`) on the
    :class:`CompiledModel` of its shape: :meth:`update` linearises at an iterate,
    :meth:`solve` solves, :meth:`step` is the new ``x``.

    Clearance rows: for every element within reach and every inner curve sample,
    the row of its case at the iterate (:func:`ccopt_formulations.clearance.linear_rows`;
    concave arcs as cones), with one slack per curve sample.
    """

    def __init__(self, setup: LeadSetup, problem, lam: float, m: int = M_SAMPLES):
        self.setup = setup
        arcs = sum(el.kind == "arc" for el in setup.elements)
        self.shape = ModelShape(setup.degree, len(sample_t(m)), len(setup.elements),
                                min(arcs, C_MAX), setup.sigma_hi > setup.sigma_lo)
        self.model = compiled(self.shape)
        self.ref_pts = reference_points(setup, problem)
        xk = setup.initial()
        Pk = setup.controls(xk)
        self.band = float(problem.options.get("band_width", 2.0 * setup.r)) + float(
            np.max(np.min(self._ref_distance(Pk), axis=1)))
        self.e2 = max(bezier_energy(Pk, 2), ENERGY_FLOOR)
        self.e3 = max(bezier_energy(Pk, 3), ENERGY_FLOOR)
        n = setup.degree
        self.Dk = (derivative_matrix(n, 1), derivative_matrix(n, 2))
        self._sample_at(sample_t(m))
        self.R2, self.R3 = energy_root(n, 2), energy_root(n, 3)
        self.lam = float(lam)
        self.xk = xk

    def _sample_at(self, t: np.ndarray) -> None:
        n = self.setup.degree
        self.t = t
        self.B = bernstein(t, n)
        self.D1 = bernstein(t, n - 1) @ self.Dk[0]
        self.D2 = bernstein(t, n - 2) @ self.Dk[1]

    def _ref_distance(self, pts: np.ndarray) -> np.ndarray:
        return np.hypot(pts[:, None, 0] - self.ref_pts[None, :, 0],
                        pts[:, None, 1] - self.ref_pts[None, :, 1])

    def set_weight(self, lam: float) -> None:
        """Another curvature weight on the same model."""
        self.lam = float(lam)

    def update(self, xk: np.ndarray, delta: float) -> None:
        """Linearise at ``xk`` with trust radius ``delta`` (program units)."""
        su = self.setup
        L0 = su.L0
        self.xk = np.asarray(xk, float)
        Pk, Jc = control_jacobian(su, self.xk)
        Jx, Jy = Jc[0::2], Jc[1::2]            # dP/dx; dP/dd = L0 J, in L0 units: J
        Ph = Pk / L0
        B = self.B
        pk = B @ Pk
        BJx, BJy = B @ Jx, B @ Jy
        Dm = np.diff(np.eye(len(self.t)), axis=0)
        mdl = self.model
        wq2 = math.sqrt(self.lam * L0 * L0 / self.e2)
        wq3 = math.sqrt(MU * L0 * L0 / self.e3)
        R2, R3 = self.R2, self.R3
        mdl.set(LJx=Dm @ BJx, lx=Dm @ pk[:, 0] / L0, LJy=Dm @ BJy, ly=Dm @ pk[:, 1] / L0,
                Q=np.vstack([wq2 * R2 @ Jx, wq2 * R2 @ Jy, wq3 * R3 @ Jx, wq3 * R3 @ Jy]),
                q=np.concatenate([wq2 * R2 @ Ph[:, 0], wq2 * R2 @ Ph[:, 1],
                                  wq3 * R3 @ Ph[:, 0], wq3 * R3 @ Ph[:, 1]]),
                BJx=BJx, BJy=BJy)
        if self.shape.elements:
            self._clearance(pk, BJx, BJy)
        w = self.ref_pts[np.argmin(self._ref_distance(pk), axis=1)]
        mdl.set(wx=(pk[:, 0] - w[:, 0]) / L0, wy=(pk[:, 1] - w[:, 1]) / L0, band=self.band / L0)
        self._frame_rows(Ph, Jx, Jy)
        lo, hi = su.bounds()
        lo, hi = (lo - self.xk) / L0, (hi - self.xk) / L0
        mdl.set(delta=delta / L0, lo=lo[:-1], hi=hi[:-1])
        if self.shape.free_join:
            mdl.set(slo=lo[-1], shi=hi[-1])

    def _clearance(self, pk, BJx, BJy) -> None:
        """Clearance rows and cones at the iterate's samples ``pk`` (see the class)."""
        L0 = self.setup.L0
        inner = slice(1, len(pk) - 1)
        A_all, b_all, conc = [], [], []
        for el in self.setup.elements:
            G, h, soc, vec, scal = linear_rows(el, pk[inner])
            # G . p >= h with p = pk + L0 BJ d:  (G . BJ) d >= (h - G . pk) / L0
            A = G[:, 0:1] * BJx[inner] + G[:, 1:2] * BJy[inner]
            b = (h - np.einsum("ij,ij->i", G, pk[inner])) / L0
            live = np.isfinite(h)
            A_all.append(np.where(live[:, None], A, 0.0))
            b_all.append(np.where(live, b, -VOID))
            if soc.any() and len(conc) < self.shape.cones:
                conc.append((vec[soc][0], np.where(soc, scal / L0, VOID)))
        mdl = self.model
        mdl.set(Ac=np.vstack(A_all), bc=np.concatenate(b_all))
        for i in range(self.shape.cones):
            c, rho = conc[i] if i < len(conc) else (pk[inner].mean(axis=0),
                                                    np.full(len(pk) - 2, VOID))
            mdl.set(**{f"cx{i}": (pk[inner, 0] - c[0]) / L0, f"cy{i}": (pk[inner, 1] - c[1]) / L0,
                       f"crho{i}": rho})

    def _frame_rows(self, Ph, Jx, Jy) -> None:
        """Regularity and the curvature bound at the iterate (``L0`` units)."""
        su, mdl = self.setup, self.model
        D1, D2 = self.D1, self.D2
        r1, r2 = D1 @ Ph, D2 @ Ph
        F = np.stack([D1 @ Jx, D1 @ Jy])
        H = np.stack([D2 @ Jx, D2 @ Jy])
        sp = np.hypot(r1[:, 0], r1[:, 1])
        ub = r1 / np.maximum(sp, DIVISION_FLOOR)[:, None]
        Ar = ub[:, 0:1] * F[0] + ub[:, 1:2] * F[1]
        mdl.set(Ar=Ar, br=V_MIN_FRACTION - sp)
        K = CURVATURE_MODEL_SHARE * su.kappa_max * su.L0
        if not np.isfinite(K):
            K = VOID
        mdl.set(**curvature_rows(r1, r2, F, H, K, V_MIN_FRACTION))

    def solve(self, solver: str) -> str:
        return solve_subproblem(self.model.problem, solver)

    def step(self) -> np.ndarray | None:
        d = self.model.d.value
        return None if d is None else self.xk + self.setup.L0 * np.asarray(d, float)

    def value(self) -> float:
        """The last subproblem's optimal value."""
        return float(self.model.problem.value)

    def slack_max(self) -> float:
        """Largest clearance slack of the last solve (program units)."""
        s = self.model.slack
        return float(np.max(s.value)) * self.setup.L0 if s is not None else 0.0

    def bound_slack_max(self) -> float:
        """Largest relative excess over the curvature-bound rows of the last solve."""
        return float(np.max(self.model.bslack.value))


def solve_subproblem(problem, solver: str = "CLARABEL", **options):
    """The solver call, kept apart from the model: ``problem.solve`` with ``solver``."""
    with warnings.catch_warnings():
        # "solution may be inaccurate": the exact clearance check after the solve judges it
        warnings.simplefilter("ignore", UserWarning)
        try:
            problem.solve(solver=solver, canon_backend="COO", **options)
        except Exception:  # a solver failure on a bad linearisation: the caller shrinks
            return "solver_error"
    return problem.status
