"""What the CasADi and CVXPY lead blends share: the problem in numbers.

A lead (see :mod:`ccopt.compare.leads`; a lead-out is handed over reversed)
becomes a Bezier curve ``P[0..n]`` (degree ``n``, :data:`DEGREE` by default: a
quintic) from the approach point ``A`` to the host tool segment at arc length
``sigma`` (``J``), matching the host's position, tangent and curvature there
(:func:`ccopt.geometry.bezier.g2_end`). Decision vector
``x = [P1, ..., P(n-3), a, e, sigma]`` (points flattened); ``P0 = A``, and
``P(n-2), P(n-1), Pn`` follow from ``(a, e, sigma)``.

Where the blend joins: by default ``sigma = 0``, PMAC's first compensated
point ``J0``. A closed contour starts and ends there (lead-in and lead-out
meet), and joining further along would leave the stretch between ``J0`` and
``J`` uncut; ``join="free"`` lets ``sigma`` range over the host (for open
contours where that is acceptable).

Clearance from the contour: every element the verifier checks that comes
within reach of the lead, exactly, by where the foot of each curve sample lies
on it (:mod:`ccopt_formulations.clearance`: the supporting line, the circle of an
arc, or an end point), re-classified at every iterate. The curve's two ends
are PMAC's own points and are not constrained.

Curvature: every blend turns no tighter than :func:`curvature_bound`, the
larger of ``a / v^2`` and ``kappa_ref``: ``v`` the speed the lead must carry
(its programmed feed, at most the slowest in-plane axis speed) and ``a`` the
smallest in-plane axis acceleration, so that the tool can follow any turn of
the lead at that speed with a normal acceleration no axis exceeds, unless the
reference path itself turns tighter (``kappa_ref``, its largest curvature: the
machine slows for that turn anyway). A hook of a micrometre radius is not a
lead. The CasADi model
imposes :data:`CURVATURE_MODEL_SHARE` of it at its samples, and
:func:`run_leads` checks it densely (:func:`too_tight`) before such a blend is
taken. (The CVXPY model imposes it through its curvature rows.) What jerk does
to the speed (the normal acceleration ``v^2 kappa`` must build up at the jerk
limit) is the planner's to time: the search of :mod:`ccopt_formulations.lead_timing`
minimises the planned cycle time itself.

The verifier has the last word (:meth:`BlendProblem.check`, on the segments a
blend changed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected, deepest
from ccopt.compare.parts import FEED_ROLES, curvature_samples
from ccopt.compare.leads import Lead, LeadGeometry, outside_leads, splice
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.bezier import DIVISION_FLOOR, g2_end, jerk_gram, speed_profile_time
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt_formulations.clearance import checked_distance, contour_elements, near, row_margin
from ccopt_formulations.lead_timing import SEARCH_EVALUATIONS, LeadTimer, refine

DEGREE = 5

#: Weight of the jerk term, relative: ``mu = W_JERK * T0 / L0^2`` (``T0 = L0 / F``).
W_JERK = 1e-5

#: Contour elements farther than this many cutter radii (plus half the approach)
#: from the reference lead are not constrained; at most E_MAX nearest are.
REACH = 2.0
E_MAX = 8

#: The free control points stay within this many ``L0`` (approach distance +
#: host reach + r) of the approach point ``A``: a blend is a local
#: replacement of the lead. (With 1000 L0, IPOPT could stop at a "solution"
#: thousands of mm away on fagor-g136-g139, certified but 30x slower.)
CONTROL_REACH = 3.0

#: The share of the bound the models impose at their samples (the curve between
#: samples may turn a little tighter; :func:`too_tight` checks the whole bound).
CURVATURE_MODEL_SHARE = 0.8


def curvature_bound(problem: BlendProblem, feed: float) -> float:
    """Largest curvature (1/units) an optimised lead with programmed ``feed``
    (units/s) may have: the larger of ``a / v^2`` and ``kappa_ref``.

    ``a / v^2``: ``v = min(feed, slowest in-plane axis speed)`` and ``a`` the
    smallest in-plane axis acceleration (the problem's limits, else
    :data:`~ccopt.compare.contract.DEFAULT_ACC` and the feed): at that curvature
    and speed the normal acceleration ``v^2 kappa`` is ``a``, which every axis
    can give whatever the direction of the turn, so the lead is cut at its feed.
    ``kappa_ref``: the largest curvature of the reference path's feed moves (a
    controller's corner arcs of the cutter radius, the contour's own arcs): the
    machine slows for that turn on this program anyway, so a lead may turn as
    tightly."""
    a = float(np.min(problem.acc()))
    v = float(feed)
    if problem.limits is not None:
        vmax, _ = problem.limits.in_plane(problem.reference.plane, 2)
        v = min(v, float(np.min(vmax)))
    kref = max((float(np.max(np.abs(curvature_samples(s.geom)))) for s in
                problem.reference.segments if s.role in FEED_ROLES and s.length > 0),
               default=0.0)
    return max(a / (v * v) if v > 0.0 else math.inf, kref)


@dataclass
class LeadSetup:
    """One lead as numbers for a model (see the module docstring)."""

    lead: Lead
    lg: LeadGeometry
    A: np.ndarray
    host_kind: str                  # "line" | "arc" (a spiral host: its osculating circle at the join)
    H0: np.ndarray
    t0: np.ndarray
    n_free_dir: np.ndarray          # unit normal to the free side at H0
    center: np.ndarray | None       # arc host
    rho: float                      # arc host tool radius
    sweep_sign: float               # arc host
    own_outside: bool               # arc host: tool outside its element circle
    theta0: float
    sigma_lo: float
    sigma_hi: float
    r: float
    feed: float
    acc: np.ndarray                 # in-plane axis acceleration limits (a_u, a_v)
    L0: float
    elements: list                  # contour elements within reach (ccopt_formulations.clearance)
    kappa_max: float = math.inf    # curvature bound (1/units), :func:`curvature_bound`
    w_jerk: float = W_JERK
    degree: int = DEGREE
    refine: int = 1                 # clearance samples are multiplied by this
    options: dict = field(default_factory=dict)

    @property
    def n_free(self) -> int:
        """Free control points ``P1 .. P(n-3)``."""
        return self.degree - 3

    @property
    def nx(self) -> int:
        return 2 * self.n_free + 3

    # -- host frame --------------------------------------------------------------------
    def host_frame(self, sigma: float):
        """``(J, t, kappa)`` on the host at arc length ``sigma`` (numpy)."""
        if self.host_kind == "line":
            return self.H0 + sigma * self.t0, self.t0.copy(), 0.0
        phi = self.theta0 + self.sweep_sign * sigma / self.rho
        J = self.center + self.rho * np.array([math.cos(phi), math.sin(phi)])
        t = self.sweep_sign * np.array([-math.sin(phi), math.cos(phi)])
        return J, t, self.sweep_sign / self.rho

    def controls(self, x) -> np.ndarray:
        """Control points ``(6, 2)`` of decision vector ``x``."""
        x = np.asarray(x, float)
        J, t, k = self.host_frame(x[-1])
        free = x[:2 * self.n_free].reshape(-1, 2)
        return np.vstack([self.A, free, g2_end(J, t, k, x[-3], x[-2], self.degree)])

    @property
    def T0(self) -> float:
        return self.L0 / self.feed

    def objective(self, x, m: int = 81) -> float:
        """Time to run the blend from rest and go on at the feed (speed profile,
        :func:`~ccopt.geometry.bezier.speed_profile_time`), plus the host time it
        skips, plus the jerk term: what both models minimise."""
        P = self.controls(x)
        host_left = (self.lg.host_length - x[-1]) / self.feed
        return self.traversal_time(x, m) + host_left + self.jerk_weight * float(
            np.sum(P * (jerk_gram(self.degree) @ P)))

    def traversal_time(self, x, m: int = 81) -> float:
        return speed_profile_time(self.controls(x), self.feed, self.acc, m=m)

    @property
    def jerk_weight(self) -> float:
        return self.w_jerk * self.T0 / self.L0 ** 2

    # -- first guess -----------------------------------------------------------------
    def initial(self) -> np.ndarray:
        """A curve along the reference: from ``A`` towards ``J0`` then onto the host."""
        sigma = 0.5 * (self.sigma_lo + self.sigma_hi)
        J, t, k = self.host_frame(sigma)
        d = float(np.linalg.norm(J - self.A))
        a = max(0.2 * d, 1e-3 * self.L0)
        corner = self.H0
        m = self.n_free
        pts = [self.A + (0.3 + 0.3 * i / max(m - 1, 1)) * (corner - self.A)
               + (0.2 * d * i / max(m - 1, 1)) * self.n_free_dir for i in range(m)]
        return np.r_[np.ravel(pts), a, 0.0, sigma]

    def bounds(self):
        """``(lower, upper)`` of ``x``."""
        big = CONTROL_REACH * self.L0
        m = self.n_free
        lo = np.r_[np.tile(self.A - big, m), 1e-3 * self.L0, -self.L0, self.sigma_lo]
        hi = np.r_[np.tile(self.A + big, m), 2.0 * self.L0, self.L0, self.sigma_hi]
        return lo, hi

    # -- checks ----------------------------------------------------------------------
    def sample_t(self, m: int) -> np.ndarray:
        return np.linspace(0.0, 1.0, m)

    def clearance_violation(self, x, m: int = 401) -> float:
        """Largest ``clearance - distance`` over curve samples (ends excluded) and
        the elements within reach (<= 0 when the curve keeps its clearance there)."""
        if not self.elements:
            return -math.inf
        pts = bernstein(self.sample_t(m)[1:-1], self.degree) @ self.controls(x)
        return max(float(np.max(el.clearance - checked_distance(el, pts)))
                   for el in self.elements)


# --------------------------------------------------------------------------- first guess


#: The first guesses :func:`first_guess` tries when :meth:`LeadSetup.initial`
#: does not do: each free point at ``A + along (J - A) + across |J - A| n``
#: (``J`` the join, ``n`` the unit normal of ``J - A``), the legs ``a`` at these
#: multiples of ``|J - A|``, ``e = 0``. Beyond ``J`` (``along`` > 1) and to either
#: side, so that a guess can go round an open end of the contour or make a U-turn
#: onto the host (fagor-g136-g138's 170 degree episodes need both).
GUESS_ALONG = (0.1, 0.4, 0.7, 1.0, 1.3)
GUESS_ACROSS = (-0.6, -0.3, 0.0, 0.3, 0.6)
GUESS_LEGS = (0.1, 0.2, 0.4)


def guess_grid(setup: LeadSetup) -> np.ndarray:
    """Candidate decision vectors (rows; see :data:`GUESS_ALONG`): the first and the
    last free point on the grid, those between them evenly between."""
    sigma = 0.5 * (setup.sigma_lo + setup.sigma_hi)
    J = setup.host_frame(sigma)[0]
    d = float(np.linalg.norm(J - setup.A))
    u = (J - setup.A) / max(d, DIVISION_FLOOR)
    nrm = np.array([-u[1], u[0]])
    grid = np.array([setup.A + al * (J - setup.A) + ac * d * nrm
                     for al in GUESS_ALONG for ac in GUESS_ACROSS])
    first, last = np.repeat(grid, len(grid), axis=0), np.tile(grid, (len(grid), 1))
    w = np.linspace(0.0, 1.0, setup.n_free) if setup.n_free > 1 else np.zeros(1)
    free = first[:, None, :] + w[None, :, None] * (last - first)[:, None, :]
    rows = [np.c_[free.reshape(len(first), -1), np.full((len(first), 3), (leg * d, 0.0, sigma))]
            for leg in GUESS_LEGS]
    return np.vstack(rows)


def _model_violation(setup: LeadSetup, pts: np.ndarray) -> np.ndarray:
    """Largest violation of the models' clearance rows (``clearance - distance``; beyond
    an open end of a line or an arc the half-plane and ``|p - E| >= r``) at the points
    ``pts`` (``(N, m, 2)``), per row ``N``."""
    N, m = pts.shape[:2]
    flat = pts.reshape(-1, 2)
    worst = np.full(N, -np.inf)
    for el in setup.elements:
        worst = np.maximum(worst, np.max(-row_margin(el, flat).reshape(N, m), axis=1))
    return worst


def _shape(setup: LeadSetup, X: np.ndarray, m: int):
    """``(samples, regular, within the curvature the models impose, time proxy)`` of
    the candidate rows ``X`` at ``m`` samples (``(N, m, 2)``, then per row); the time
    proxy runs each sample's piece at the feed or at the speed its curvature
    allows, ``sqrt(a / kappa)``."""
    n = setup.degree
    P = _controls_many(setup, X)
    t = np.linspace(0.0, 1.0, m)
    pts = bernstein(t, n) @ P                                  # (N, m, 2)
    d1 = (bernstein(t, n - 1) @ derivative_matrix(n, 1)) @ P
    d2 = (bernstein(t, n - 2) @ derivative_matrix(n, 2)) @ P
    sp = np.hypot(d1[..., 0], d1[..., 1])
    kappa = np.abs(d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]) / np.maximum(
        sp, DIVISION_FLOOR) ** 3
    regular = np.all(sp >= V_MIN_FRACTION * setup.L0, axis=1)
    bent = np.all(kappa <= CURVATURE_MODEL_SHARE * setup.kappa_max, axis=1)
    v = np.minimum(setup.feed, np.sqrt(float(np.min(setup.acc)) / np.maximum(kappa,
                                                                              DIVISION_FLOOR)))
    ds = np.hypot(*np.moveaxis(np.diff(pts, axis=1), -1, 0))
    T = np.sum(2.0 * ds / (v[:, :-1] + v[:, 1:]), axis=1)
    return pts, regular, bent, T


def _controls_many(setup: LeadSetup, X: np.ndarray) -> np.ndarray:
    """:meth:`LeadSetup.controls` of many rows ``X`` (``(N, n+1, 2)``)."""
    N = len(X)
    P = np.empty((N, setup.degree + 1, 2))
    P[:, 0] = setup.A
    P[:, 1:setup.n_free + 1] = X[:, :2 * setup.n_free].reshape(N, -1, 2)
    for key in {tuple(r) for r in X[:, -3:]}:
        rows = np.all(X[:, -3:] == key, axis=1)
        J, t, k = setup.host_frame(key[2])
        P[rows, setup.n_free + 1:] = g2_end(J, t, k, key[0], key[1], setup.degree)
    return P


#: Curve samples at which :func:`first_guess` judges a guess (the models' own
#: clearance samples before any refinement), and candidates judged at once.
GUESS_SAMPLES = 61
GUESS_BLOCK = 128


def first_guess(setup: LeadSetup, m: int = GUESS_SAMPLES) -> np.ndarray:
    """Where a model starts: :meth:`LeadSetup.initial` when it keeps the models'
    clearance rows and is regular at ``m`` samples, else the fastest of
    :func:`guess_grid` that does and turns within the imposed curvature (by the
    time proxy of :func:`_shape`), else the one nearest to that.

    (The models take the clearance case of every sample at their first guess: a
    guess through the band of an element, or round the wrong side of an end, can
    leave them no feasible point near it: fagor-g136-g138's 170 degree episodes,
    leadin-outside-arc's lead-in, fagor-seed-line-cancel's lead-in.)"""
    x = setup.initial()
    pts, regular, _, _ = _shape(setup, x[None, :], m)
    if regular[0] and _model_violation(setup, pts[:, 1:-1])[0] <= 0.0:
        return x
    X = guess_grid(setup)
    pts, regular, bent, T = _shape(setup, X, m)
    # the fastest regular, bounded candidate keeping the clearance rows, judged in order
    # of time, a block at a time (most of the cost is the clearance)
    order = np.flatnonzero(regular & bent)
    order = order[np.argsort(T[order], kind="stable")]
    for k in range(0, len(order), GUESS_BLOCK):
        rows = order[k:k + GUESS_BLOCK]
        ok = _model_violation(setup, pts[rows, 1:-1]) <= 0.0
        if ok.any():
            return X[rows[np.argmax(ok)]]
    viol = _model_violation(setup, pts[:, 1:-1])
    misfit = (~regular).astype(float) + (~bent).astype(float)
    return X[np.argmin(np.maximum(viol, 0.0) + setup.L0 * misfit)]


def lead_setup(problem: BlendProblem, lead: Lead, *, join: str = "start",
               refine: int = 1, w_jerk: float = W_JERK, degree: int = DEGREE) -> LeadSetup:
    """Numbers for one lead of ``problem.reference`` (see the module docstring)."""
    ref = problem.reference
    lg = lead.geometry(ref)
    host = lg.host
    r = problem.cutter_radius
    if r <= 0:
        raise BlendRejected("no cutter radius: nothing to blend")
    A = np.asarray(lg.approach, float)
    H0 = np.asarray(host.start, float)
    t0 = np.asarray(host.start_tangent, float)
    n_free = lg.side * np.array([-t0[1], t0[0]])
    center, rho, sgn, outside, th0 = None, 0.0, 1.0, True, 0.0
    if isinstance(host, Line):
        kind = "line"
    elif isinstance(host, Arc) or (isinstance(host, Spiral) and join == "start"):
        # a spiral joined at its start: a G2 join reads only the host's point, tangent
        # and curvature there, which its osculating circle has (the models get that arc)
        kind = "arc"
        if isinstance(host, Arc):
            center, rho = np.asarray(host.center, float), float(host.radius)
            sgn, th0 = math.copysign(1.0, host.sweep), float(host.theta0)
        else:
            rho, sgn = 1.0 / abs(k := float(host.curvature(0.0))), math.copysign(1.0, k)
            center = H0 + sgn * rho * np.array([-t0[1], t0[0]])
            th0 = math.atan2(H0[1] - center[1], H0[0] - center[0])
        # the tool is outside its element circle when the free side points away from the centre
        outside = float(n_free @ (H0 - center)) > 0.0
    else:
        raise BlendRejected(f"lead-{lg.kind}: host segment is a {type(host).__name__}; only "
                            "line and arc hosts are supported, and spirals with join=start")
    L_host = float(host.length)
    if join == "free":
        lo, hi = min(0.5 * r, 0.25 * L_host), 0.9 * L_host
    elif join == "start":
        lo = hi = 0.0
    else:
        raise ValueError(f"join must be 'start' or 'free', not {join!r}")
    acc = problem.acc()
    feed = float(lg.feed) if lg.feed else (float(max(problem.limits.v[:2]))
                                          if problem.limits is not None else 1.0)
    L0 = float(np.linalg.norm(H0 - A)) + hi + r
    corridor = np.vstack([A, H0, H0 + hi * t0]) if hi > 0 else np.vstack([A, H0])
    elements = near(contour_elements(problem.contour), corridor,
                    REACH * r + 0.5 * float(np.linalg.norm(H0 - A)), limit=E_MAX)
    return LeadSetup(lead, lg, A, kind, H0, t0, n_free, center, rho, sgn, outside, th0, lo, hi,
                     r, feed, acc, L0, elements, curvature_bound(problem, feed), w_jerk, int(degree),
                     int(refine))


def blend_geometry(setup: LeadSetup, x) -> BezierCurve:
    """The blend curve of the decision vector ``x``."""
    return BezierCurve(setup.controls(x))


# --------------------------------------------------------------------------- the shared driver


#: The models keep the curve's speed ``|r'(t)| >= V_MIN_FRACTION * L0`` at their
#: samples (a regular curve). A solution whose speed falls below half that
#: between the samples (seen at :data:`REGULARITY_SAMPLES` values of ``t``)
#: has a near-cusp, a hairpin of micrometre radius: it is not taken (it
#: passes the clearance checks, but no controller should be sent it, and the
#: feed grid follows its curvature with hundreds of thousands of points).
V_MIN_FRACTION = 0.02
REGULARITY_SAMPLES = 4097


def near_cusp(setup: "LeadSetup", geom) -> str | None:
    """Why ``geom`` is not a regular enough blend, or ``None`` (see :data:`V_MIN_FRACTION`)."""
    P = np.asarray(geom.control_points, float)
    n = len(P) - 1
    t = np.linspace(0.0, 1.0, REGULARITY_SAMPLES)
    speed = np.hypot(*(bernstein(t, n - 1) @ (n * np.diff(P, axis=0))).T)
    floor = 0.5 * V_MIN_FRACTION * setup.L0
    i = int(np.argmin(speed))
    if speed[i] < floor:
        return (f"near-cusp: the blend's speed |r'(t)| falls to {speed[i]:.3g} at t = {t[i]:.4f} "
                f"(below {floor:.3g} between the model's samples)")
    return None


def too_tight(setup: "LeadSetup", geom) -> str | None:
    """Why ``geom`` turns tighter than ``setup.kappa_max``, or ``None`` (curvature
    ``|r' x r''| / |r'|^3`` at :data:`REGULARITY_SAMPLES` values of ``t``)."""
    P = np.asarray(geom.control_points, float)
    n = len(P) - 1
    t = np.linspace(0.0, 1.0, REGULARITY_SAMPLES)
    d1 = bernstein(t, n - 1) @ (n * np.diff(P, axis=0))
    d2 = bernstein(t, n - 2) @ (n * (n - 1) * np.diff(P, 2, axis=0))
    k = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(*d1.T) ** 3
    i = int(np.argmax(k))
    if k[i] > setup.kappa_max:
        return (f"curvature {k[i]:.3g} at t = {t[i]:.4f} above the bound "
                f"{setup.kappa_max:.3g} (1/units)")
    return None


def _is_blend(setup: LeadSetup, x, curvature_bounded: bool) -> bool:
    """Whether ``x`` is a blend the search may take: within the bounds of ``x``,
    regular (:func:`near_cusp`), within the curvature bound when the model
    imposes it (:func:`too_tight`) and clear of the contour at the models'
    clearance samples (the verifier checks between them)."""
    lo, hi = setup.bounds()
    slack = BOUND_SLACK * setup.L0          # a solver's rounding at an active bound
    if np.any(x < lo - slack) or np.any(x > hi + slack):
        return False
    geom = blend_geometry(setup, x)
    if near_cusp(setup, geom) is not None or (curvature_bounded and too_tight(setup, geom)):
        return False
    return setup.clearance_violation(x, m=CLEARANCE_SAMPLES * setup.refine) <= 0.0


#: How far (relative to ``L0``) a decision vector may lie outside
#: :meth:`LeadSetup.bounds` and still count as within them (CLARABEL returns
#: a fixed join ``sigma = 0`` as ``-1e-12``).
BOUND_SLACK = 1e-9

#: Curve samples at which the search of :func:`run_leads` checks a blend's
#: clearance (the verifier then checks the chosen one exactly).
CLEARANCE_SAMPLES = 401

#: Clearance sample multipliers tried in turn when the verifier rejects a blend
#: (between samples a curve may come closer than at them; denser samples, less).
ATTEMPTS = (1, 3, 9)


def _made(path, cand, neighbours: bool = True) -> list[int]:
    """The segments of ``cand`` the splice made, and their neighbours (a lead-out's
    blend is the curve reversed, a new object, so it is found by what is new, not
    by the curve); ``neighbours=False``: the made ones alone."""
    old = {id(s) for s in path.segments}
    made = [i for i, s in enumerate(cand.segments) if id(s) not in old]
    if not neighbours:
        return made
    return sorted({j for i in made for j in (i - 1, i, i + 1) if 0 <= j < len(cand.segments)})


def _beside(problem: BlendProblem, path, cand) -> bool:
    """Whether a rejected ``cand`` passes on the segments the splice made alone: its
    violation then lies on a neighbour the splice left as it was (PMAC's own host
    gouging, as on sidechange-reversal), which no denser samples can move."""
    try:
        problem.check(cand, _made(path, cand, neighbours=False))
    except BlendRejected:
        return False
    return True


def _searched(problem: BlendProblem, path, lead: Lead, setup: LeadSetup, x, name: str,
              curvature_bounded: bool, evaluations: int):
    """``(decision vectors to try in turn, what the search reports)``: the
    planner search's faster blend (:func:`ccopt_formulations.lead_timing.refine`,
    ``evaluations`` planner runs) before the model's ``x``, or ``x`` alone when
    there are no limits or no runs to spend."""
    if problem.limits is None or evaluations <= 0:
        return [x], {}
    fast, timed = refine(setup, x, LeadTimer(problem, path, lead, name),
                         lambda z: _is_blend(setup, z, curvature_bounded), evaluations)
    return ([fast, x] if fast is not x else [x]), timed


def _first_certified(problem: BlendProblem, path, lead: Lead, setup: LeadSetup, tries,
                     name: str):
    """``(x, candidate path, None)`` for the first decision vector of ``tries`` whose
    blend, spliced into ``path``, the verifier certifies on the segments it made
    (:meth:`BlendProblem.check`), else ``(last x, its path, the last reason)``."""
    err = None
    for x in tries:
        cand = splice(path, lead, [blend_geometry(setup, x)], float(x[-1]), style=name)
        try:
            problem.check(cand, _made(path, cand))
        except BlendRejected as exc:
            err = str(exc)
            continue
        return x, cand, None
    return x, cand, err


def refuse_lasting(problem: BlendProblem, leads: list[Lead]) -> None:
    """:class:`BlendRejected` saying why, when no lead blend of
    ``problem.reference`` can be certified: a gouge, gap or side violation of
    the start path outside every lead (:func:`~ccopt.compare.leads.outside_leads`)
    stays in every blended path, so solving the leads would be work for a row
    certain to be uncertified (on LinuxCNC's crazy-paths every controller's
    path gouges between its leads)."""
    cert = problem.reference_verdict
    outside = [] if cert.ok else outside_leads(cert.violations, leads)
    if outside:
        raise BlendRejected(f"the path it starts from is not certified away from its leads "
                            f"({deepest(outside)}, {len(outside)} violation(s) outside every "
                            f"lead): no lead blend can make it so")


def run_leads(problem: BlendProblem, solve_lead, name: str,
              attempts: tuple[int, ...] = ATTEMPTS,
              curvature_bounded: bool = True) -> BlendOutcome:
    """Replace every lead of the reference with ``solve_lead(setup) -> (x, info)``.

    Each blend is spliced in and certified on the segments it changed
    (:meth:`BlendProblem.check`); when the verifier rejects it the lead is
    solved again with denser clearance
    samples (``attempts``, :data:`ATTEMPTS` by default), and when every attempt
    fails PMAC's lead stays
    and the reason is reported in ``info["leads"]``. No lead replaced at all
    is a :class:`BlendRejected`. ``curvature_bounded``: refuse a blend over the
    curvature bound (:func:`too_tight`), for models that impose it.
    """
    opts = dict(problem.options)
    join = str(opts.get("join", "start"))
    w_jerk = float(opts.get("w_jerk", W_JERK))
    degree = int(opts.get("degree", DEGREE))
    search = int(opts.get("search", SEARCH_EVALUATIONS))
    if degree < 5:
        raise BlendRejected(f"degree must be at least 5 for a G2 blend with a free start, "
                            f"got {degree}")
    path = problem.reference
    leads = problem.leads()
    if not leads:
        raise BlendRejected("the reference path has no lead-in or lead-out to replace")
    refuse_lasting(problem, leads)
    report = []
    for ld in reversed(leads):
        entry = {"lead": ld.kind, "segment": ld.host}
        last_err = None
        problem.report(f"{name}: blend {len(report) + 1}/{len(leads)}")
        for scale in attempts:
            try:
                setup = lead_setup(problem, ld, join=join, refine=scale, w_jerk=w_jerk,
                                   degree=degree)
                x, info = solve_lead(setup)
                geom = blend_geometry(setup, x)
            except BlendRejected as exc:
                last_err = str(exc)
                break
            except RuntimeError as exc:
                # the solver found no solution: denser samples only add constraints,
                # they cannot make the model feasible (they fix what lies between samples)
                last_err = f"{type(exc).__name__}: {exc}"
                break
            except ValueError as exc:     # e.g. a curve that is not regular between samples
                last_err = f"{type(exc).__name__}: {exc}"
                continue
            cusp = near_cusp(setup, geom) or (too_tight(setup, geom) if curvature_bounded
                                              else None)
            if cusp is not None:
                last_err = cusp      # denser samples next time (the models scale with refine)
                continue
            tries, timed = _searched(problem, path, ld, setup, x, name, curvature_bounded,
                                     search)
            x, cand, last_err = _first_certified(problem, path, ld, setup, tries, name)
            geom = blend_geometry(setup, x)
            if last_err is not None:
                if _beside(problem, path, cand):
                    break
                continue
            path = cand
            entry.update({f"solver_{k}": v for k, v in info.items()})
            entry.update(timed)
            entry.update(status="ok", refine=scale, sigma=float(x[-1]),
                         curvature_bound=setup.kappa_max if curvature_bounded else None,
                         proxy_time=float(setup.objective(x)),
                         control_points=[list(p) for p in geom.control_points])
            last_err = None
            break
        if last_err is not None:
            entry.update(status="kept PMAC lead", reason=last_err)
        report.append(entry)
    if all(e["status"] != "ok" for e in report):
        raise BlendRejected("; ".join(f"lead-{e['lead']}: {e.get('reason')}" for e in report))
    # each blend was checked on its own segments (BlendProblem.check); compare certifies all
    return BlendOutcome(path, {"leads": report[::-1]})
