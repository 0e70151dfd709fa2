"""What a blend gets, what it gives back, and the pieces optimised blends share.

A blend is a callable ``blend(problem: BlendProblem) -> ToolPath | BlendOutcome``
registered under a name (see :mod:`ccopt.compare.registry`). It receives the
program, PMAC's compensated path (the *reference*), the contour the verifier
checks against, the machine limits and the options; it returns the whole tool
path of its variant. Optimised blends call :meth:`BlendProblem.accept` on
their result: a blend is accepted only when the verifier certifies the
segments it made (clearance between samples too), else
:class:`BlendRejected` is raised.

Bezier helpers (numpy, shared by the CasADi and CVXPY models):

- :func:`bernstein` ``(t, n)``: the ``(len(t), n+1)`` basis matrix, so the
  points of a curve with control points ``P`` are ``bernstein(t, n) @ P``
  (with :func:`derivative_matrix` and :func:`subdivision_matrix`, defined in
  :mod:`ccopt.geometry.curve` and re-exported here);
- :func:`g2_end` / :func:`g2_start`: control points that give a curve of
  degree ``n`` the position, tangent and curvature of a host at one end. At
  the end ``J`` with unit tangent ``t``, left normal ``n`` and curvature
  ``kappa``: ``P[n] = J``, ``P[n-1] = J - a t``,
  ``P[n-2] = J + (e - 2a) t + (n/(n-1)) kappa a^2 n`` for any leg ``a > 0``
  and any ``e`` (then ``r'(1) = n a t`` and ``kappa(1) = kappa``);
- :func:`jerk_gram`: ``G`` with ``integral_0^1 |r'''(t)|^2 dt = sum(P.T @ G @ P)``
  (the third derivative of a degree-``n`` curve, a jerk proxy);
- :func:`time_proxy`: ``integral ds * sqrt(1/F^2 + |kappa|/a)``, the time to run
  a curve at the feed ``F`` or at the speed the acceleration ``a`` allows on
  its curvature, whichever is lower (within a factor sqrt 2).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Mapping

import numpy as np

from ccopt.feed.limits import AxisLimits
# The Bezier basics live in geometry (the exporter needs them too); re-exported here
# for the formulations that import them from compare.
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt.geometry.curve import subdivision_matrix as subdivision_matrix
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath


class BlendRejected(RuntimeError):
    """A blend could not be made or was not certified (the message says why)."""


@dataclass(frozen=True)
class BlendOutcome:
    """A blend's tool path and what it wants reported (solver, iterations, ...)."""

    toolpath: ToolPath
    info: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False)
class BlendProblem:
    """Everything a blend may use.

    Attributes
    ----------
    program: the part program.
    reference: PMAC's compensated path of it (the comparison's reference;
        ``None`` only for controller styles run when PMAC refused the program).
    limits: machine limits (``None`` when none were given; blends that
        optimise time then assume :data:`DEFAULT_ACC` and the programmed feed).
    delta: tolerance band of the smoother (program units); ``None`` means 1 %
        of the cutter radius.
    options: blend options by name (e.g. ``lead_radius``).
    radius, side: the compensation overrides the reference was made with.
    """

    program: Program
    reference: ToolPath
    limits: AxisLimits | None = None
    delta: float | None = None
    options: Mapping[str, Any] = field(default_factory=dict)
    radius: float | None = None
    side: Any = None

    @property
    def cutter_radius(self) -> float:
        return float(self.reference.radius)

    @property
    def band(self) -> float:
        """The smoother's tolerance band: ``delta`` or 1 % of the cutter radius."""
        return float(self.delta) if self.delta is not None else 0.01 * self.cutter_radius

    @cached_property
    def contour(self):
        """The verifier's contour of the program (:func:`ccopt.verify.contour_of`)."""
        from ccopt.verify import contour_of
        from ccopt.verify.run import SIDES
        return contour_of(self.program, radius=self.radius, side=SIDES[self.side],
                          toolpath_radius=self.reference.radius if self.radius is None else None)

    def acc(self) -> np.ndarray:
        """In-plane axis acceleration limits ``(a_u, a_v)`` used by the time models."""
        if self.limits is None:
            return np.array([DEFAULT_ACC, DEFAULT_ACC])
        _, a = self.limits.in_plane(self.reference.plane, 2)
        return np.asarray(a, float)

    def leads(self):
        from ccopt.compare.leads import find_leads
        return find_leads(self.reference)

    def certify(self, toolpath: ToolPath):
        from ccopt.verify import verify
        return verify(toolpath, self.program, radius=self.radius, side=self.side)

    def accept(self, toolpath: ToolPath, segments) -> Any:
        """Certify ``toolpath``; :class:`BlendRejected` when a gouge, gap or side
        violation lies on one of ``segments`` (indices of the segments the blend
        made or trimmed). Returns the certificate."""
        cert = self.certify(toolpath)
        mine = set(int(i) for i in segments)
        bad = [v for v in cert.violations
               if v.kind in ("gouge", "gap", "side") and v.tool_segment in mine]
        if bad:
            v = max(bad, key=lambda v: v.depth)
            raise BlendRejected(f"verifier: {v.kind} of depth {v.depth:.3g} on blend segment "
                                f"{v.tool_segment} ({len(bad)} violation(s))")
        return cert


#: Acceleration assumed by time proxies when no limits are given (units/s^2).
DEFAULT_ACC = 1000.0


# --------------------------------------------------------------------------- contour samples


@dataclass(frozen=True)
class ContourSamples:
    """Points of the contour every ``h`` (element ends included): ``points``
    ``(M, 2)``, ``element`` ``(M,)``, ``clearance`` ``(M,)`` (the element's),
    and ``margin``: how much a distance to the nearest sample may exceed the
    distance to the contour (added to every sampled clearance constraint)."""

    points: np.ndarray
    element: np.ndarray
    clearance: np.ndarray
    margin: float
    h: float


def contour_samples(contour, h: float) -> ContourSamples:
    """Sample every contour element every ``h`` (at most).

    The margin: a point at distance ``D >= r`` from an element is within
    ``sqrt(D^2 + (1 + D/R) (h/2)^2)`` of a sample (``R`` the smallest radius
    of a convex arc, infinite for lines), so ``(1 + r/R) h^2 / (8 r)`` covers
    the sampling for distances near ``r``.
    """
    from ccopt.geometry import Arc
    pts, elem, clr = [], [], []
    rmin = math.inf
    for j in range(len(contour)):
        g = contour.elements.geom(j)
        L = float(g.length)
        n = max(2, int(math.ceil(L / h)) + 1)
        s = np.linspace(0.0, L, n)
        pts.append(np.asarray(g.point(s)).reshape(-1, 2))
        elem.append(np.full(n, j))
        clr.append(np.full(n, float(contour.clearance[j])))
        if isinstance(g, Arc):
            rmin = min(rmin, g.radius)
        elif not hasattr(g, "p0"):
            k = float(np.max(np.abs(np.asarray(g.curvature(s)))))
            if k > 0:
                rmin = min(rmin, 1.0 / k)
    if not pts:
        return ContourSamples(np.zeros((0, 2)), np.zeros(0, int), np.zeros(0), 0.0, h)
    clr_all = np.concatenate(clr)
    r = float(clr_all.max()) if clr_all.size else 1.0
    margin = (1.0 + (r / rmin if math.isfinite(rmin) else 0.0)) * h * h / (8.0 * max(r, 1e-9))
    return ContourSamples(np.vstack(pts), np.concatenate(elem), clr_all, margin, h)


# --------------------------------------------------------------------------- Bezier helpers


def jerk_gram(n: int) -> np.ndarray:
    """``G`` (``(n+1, n+1)``) with ``integral |r'''|^2 dt = trace(P.T G P)``."""
    if n < 3:
        return np.zeros((n + 1, n + 1))
    D = derivative_matrix(n, 3)
    m = n - 3
    # Gram matrix of the degree-m Bernstein basis on [0, 1]
    B = np.array([[math.comb(m, i) * math.comb(m, j) / (math.comb(2 * m, i + j) * (2 * m + 1))
                   for j in range(m + 1)] for i in range(m + 1)])
    return D.T @ B @ D


def g2_end(J, t, kappa: float, a: float, e: float, n: int) -> np.ndarray:
    """Control points ``P[n-2], P[n-1], P[n]`` ending at ``J`` with tangent ``t``
    and curvature ``kappa`` (see the module docstring)."""
    J = np.asarray(J, float)
    t = np.asarray(t, float)
    nl = np.array([-t[1], t[0]])
    c = n * kappa * a * a / (n - 1)
    return np.array([J + (e - 2.0 * a) * t + c * nl, J - a * t, J])


def g2_start(P0, t, kappa: float, a: float, e: float, n: int) -> np.ndarray:
    """Control points ``P[0], P[1], P[2]`` starting at ``P0`` with tangent ``t``
    and curvature ``kappa``."""
    P0 = np.asarray(P0, float)
    t = np.asarray(t, float)
    nl = np.array([-t[1], t[0]])
    c = n * kappa * a * a / (n - 1)
    return np.array([P0, P0 + a * t, P0 + (2.0 * a + e) * t + c * nl])


def curve_samples(P: np.ndarray, t: np.ndarray):
    """``(points, speed |r'|, signed curvature)`` of the Bezier ``P`` at ``t``."""
    n = len(P) - 1
    pts = bernstein(t, n) @ P
    d1 = bernstein(t, n - 1) @ (derivative_matrix(n, 1) @ P)
    d2 = bernstein(t, n - 2) @ (derivative_matrix(n, 2) @ P) if n >= 2 else np.zeros_like(d1)
    sp = np.hypot(d1[:, 0], d1[:, 1])
    k = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(sp, 1e-300) ** 3
    return pts, sp, k


def simpson_weights(m: int) -> np.ndarray:
    """Composite Simpson weights on ``m`` (odd) equally spaced points of [0, 1]."""
    if m < 3 or m % 2 == 0:
        raise ValueError("Simpson needs an odd number >= 3 of points")
    w = np.ones(m)
    w[1:-1:2] = 4.0
    w[2:-1:2] = 2.0
    return w / (3.0 * (m - 1))


def time_proxy(P: np.ndarray, feed: float, acc: float, m: int = 65, eps_k: float = 1e-3) -> float:
    """``integral sqrt(1/F^2 + sqrt(kappa^2 + eps_k^2)/a) ds`` over the Bezier ``P``
    (seconds), by Simpson on ``m`` points of ``t``."""
    t = np.linspace(0.0, 1.0, m)
    _, sp, k = curve_samples(np.asarray(P, float), t)
    f = sp * np.sqrt(1.0 / feed ** 2 + np.sqrt(k * k + eps_k * eps_k) / acc)
    return float(simpson_weights(m) @ f)


def path_frame(P: np.ndarray, t: np.ndarray):
    """``(points, unit tangent q', q'' = kappa * normal, |r'|)`` of the Bezier ``P`` at ``t``
    (derivatives by arc length)."""
    n = len(P) - 1
    pts = bernstein(t, n) @ P
    d1 = bernstein(t, n - 1) @ (derivative_matrix(n, 1) @ P)
    d2 = bernstein(t, n - 2) @ (derivative_matrix(n, 2) @ P)
    sp = np.hypot(d1[:, 0], d1[:, 1])
    T = d1 / sp[:, None]
    K = (d2 - np.einsum("ij,ij->i", d2, T)[:, None] * T) / (sp * sp)[:, None]
    return pts, T, K, sp


def _u_interval(T, K, b, acc):
    """Feasible path accelerations ``u = s''`` at squared speed ``b`` under
    ``|T_k u + K_k b| <= a_k`` for each axis ``k`` (vectorised): ``(lo, hi)``."""
    lo = np.full(np.shape(b), -np.inf)
    hi = np.full(np.shape(b), np.inf)
    for k, a in enumerate(acc):
        tk, kk = T[:, k], K[:, k]
        with np.errstate(divide="ignore", invalid="ignore"):
            l1 = (-a - kk * b) / tk
            h1 = (a - kk * b) / tk
        pos, neg, zero = tk > 1e-12, tk < -1e-12, np.abs(tk) <= 1e-12
        lo = np.where(pos, np.maximum(lo, l1), np.where(neg, np.maximum(lo, h1), lo))
        hi = np.where(pos, np.minimum(hi, h1), np.where(neg, np.minimum(hi, l1), hi))
        bad = zero & (np.abs(kk * b) > a)
        lo = np.where(bad, np.inf, lo)
        hi = np.where(bad, -np.inf, hi)
    return lo, hi


def speed_profile_time(P: np.ndarray, feed: float, acc, m: int = 81,
                       v_start: float = 0.0) -> float:
    """Time (s) to run the Bezier ``P`` from ``v_start`` and go on at the feed.

    ``acc``: the in-plane axis acceleration limits ``(a_x, a_y)`` (a scalar
    means both). The curve is cut at ``m`` equally spaced ``t``; at each cut
    the axis accelerations ``q' s'' + q'' s'^2`` stay within the limits and
    the speed within ``feed`` (TOPP's discrete model, as TOPPRA solves it,
    by forward and backward passes); each piece runs at constant path
    acceleration. What the end speed ``v_end`` costs afterwards, accelerating
    back to the feed along the end tangent, is added:
    ``(feed - v_end)^2 / (2 a_end feed)``.
    """
    acc = np.broadcast_to(np.asarray(acc, float), (2,))
    t = np.linspace(0.0, 1.0, m)
    pts, T, K, _ = path_frame(np.asarray(P, float), t)
    ds = np.hypot(*np.diff(pts, axis=0).T)
    # largest squared speed each cut allows (bisection: feasible b form an interval [0, bmax])
    lo_b = np.zeros(m)
    hi_b = np.full(m, feed * feed)
    ul, uh = _u_interval(T, K, hi_b, acc)
    ok = ul <= uh
    for _ in range(60):
        mid = 0.5 * (lo_b + hi_b)
        ul, uh = _u_interval(T, K, mid, acc)
        f = ul <= uh
        lo_b = np.where(f, mid, lo_b)
        hi_b = np.where(f, hi_b, mid)
    b = np.where(ok, feed * feed, lo_b)
    b[0] = min(b[0], v_start ** 2)
    for i in range(m - 1):
        _, uh = _u_interval(T[i:i + 1], K[i:i + 1], b[i:i + 1], acc)
        b[i + 1] = min(b[i + 1], b[i] + 2.0 * ds[i] * max(float(uh[0]), 0.0))
    for i in range(m - 2, -1, -1):
        ul, _ = _u_interval(T[i + 1:i + 2], K[i + 1:i + 2], b[i + 1:i + 2], acc)
        b[i] = min(b[i], b[i + 1] - 2.0 * ds[i] * min(float(ul[0]), 0.0))
    v = np.sqrt(np.maximum(b, 0.0))
    den = v[:-1] + v[1:]
    with np.errstate(divide="ignore"):
        dt = np.where(den > 0, 2.0 * ds / np.where(den > 0, den, 1.0), np.inf)
    a_end = end_acceleration(T[-1], acc)
    return float(dt.sum() + (feed - v[-1]) ** 2 / (2.0 * a_end * feed))


def end_acceleration(direction, acc) -> float:
    """Largest path acceleration along a straight ``direction`` under axis limits ``acc``."""
    d = np.abs(np.asarray(direction, float))
    acc = np.broadcast_to(np.asarray(acc, float), d.shape)
    with np.errstate(divide="ignore"):
        return float(np.min(np.where(d > 1e-12, acc / np.maximum(d, 1e-300), np.inf)))
