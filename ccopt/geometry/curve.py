"""Parametric blend curves: a planar Bezier curve evaluated by arc length.

Optimised lead-ins, lead-outs and corner blends are polynomial curves (a
quintic Bezier matches position, tangent and curvature at both ends). To sit
in a tool path beside lines, arcs and spirals, :class:`BezierCurve` offers the
same interface, parameterised by **arc length** ``s``:

* the curve itself stays the exact polynomial of its control points;
* the Bezier parameter ``t`` in [0, 1] maps to arc length through
  ``s(t) = integral |r'(t)| dt``; the length and ``s -> t`` come from the
  table and safeguarded Newton of :mod:`ccopt.geometry.bezier_arclength`,
  which hold ``|s(t) - s|`` within
  :data:`~ccopt.geometry.bezier_arclength.ARC_LENGTH_REL_TOL` times the
  length, vectorised over arrays of ``s``;
* derivatives by ``s`` follow from those by ``t`` (Bernstein basis matrices,
  one product per array): ``dp/ds = r'/|r'|``,
  ``d2p/ds2 = (r'' - (r''.T) T)/|r'|^2 = kappa N``, curvature
  ``kappa = (r' x r'')/|r'|^3`` (> 0 turning left), and
  ``d3p/ds3 = kappa_s N - kappa^2 T`` with
  ``kappa_s = ((r' x r''')/|r'|^3 - 3 (r' x r'')(r' . r'')/|r'|^5) / |r'|``.

The curve must be regular (``|r'(t)| > 0``); the constructor checks it on a
dense grid and on the derivative's control polygon (a sufficient condition
is that the hodograph's control points stay in an open half-plane).

Bernstein basics shared with the blend mathematics (:mod:`ccopt.geometry.bezier`)
and the formulations: :func:`bernstein` (basis matrix), :func:`derivative_matrix`
(control points of a derivative), :func:`subdivision_matrix` (control points
of a piece ``[t0, t1]``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.geometry.bezier_arclength import ArcLengthTable, bernstein_basis, hodograph


# --------------------------------------------------------------------------- Bernstein basics


def bernstein(t, n: int) -> np.ndarray:
    """Bernstein basis of degree ``n`` at ``t``: ``(len(t), n + 1)``."""
    t = np.atleast_1d(np.asarray(t, float))[:, None]
    k = np.arange(n + 1)[None, :]
    binom = np.array([math.comb(n, i) for i in range(n + 1)], float)[None, :]
    return binom * t ** k * (1.0 - t) ** (n - k)


def derivative_matrix(n: int, order: int = 1) -> np.ndarray:
    """``D`` with ``control points of d^order r/dt^order = D @ P`` (degree ``n - order``)."""
    M = np.eye(n + 1)
    deg = n
    for _ in range(order):
        M = deg * (M[1:] - M[:-1])
        deg -= 1
    return M


def subdivision_matrix(n: int, t0: float, t1: float) -> np.ndarray:
    """``S`` with ``S @ P`` the control points of the piece ``[t0, t1]``."""
    # blossom: the piece's i-th control point is the blossom at (t0 x (n-i), t1 x i)
    S = np.zeros((n + 1, n + 1))
    for i in range(n + 1):
        args = [t0] * (n - i) + [t1] * i
        # de Casteljau with different parameters per level (blossoming)
        coeff = np.eye(n + 1)
        for u in args:
            coeff = (1.0 - u) * coeff[:-1] + u * coeff[1:]
        S[i] = coeff[0]
    return S


# --------------------------------------------------------------------------- certified bounds
#
# A Bezier curve is a convex combination of its control points at every t, and
# so are its derivatives of theirs (the hodograph's control points). The bounds
# below rest on that alone: a linear function of the curve (a projection, a
# cross product with a fixed vector) lies between its values at the control
# points. They are exact up to floating-point rounding of the control points.


def de_casteljau_split(ctrl, t: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Control points of the pieces ``[0, t]`` and ``[t, 1]`` of the Bezier ``ctrl``.

    The left piece starts at ``ctrl[0]`` and the right one ends at ``ctrl[-1]``
    bit for bit, and the two share their middle point bit for bit (the same
    array value), so pieces split this way join exactly.
    """
    pts = np.array(ctrl, dtype=float)
    n = len(pts) - 1
    left = np.empty_like(pts)
    right = np.empty_like(pts)
    for r in range(n + 1):
        left[r] = pts[0]
        right[n - r] = pts[n - r]
        pts = (1.0 - t) * pts[:-1] + t * pts[1:]
    return left, right


def bernstein_product(a, b) -> np.ndarray:
    """Bernstein coefficients (degree ``m + k``) of the product of two scalar
    polynomials given by their Bernstein coefficients ``a`` (degree ``m``) and
    ``b`` (degree ``k``): ``c_l = sum_{i+j=l} C(m,i) C(k,j) / C(m+k,l) a_i b_j``."""
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    m, k = len(a) - 1, len(b) - 1
    ca = np.array([math.comb(m, i) for i in range(m + 1)], float) * a
    cb = np.array([math.comb(k, j) for j in range(k + 1)], float) * b
    num = np.convolve(ca, cb)
    return num / np.array([math.comb(m + k, l) for l in range(m + k + 1)], float)


def cross_bernstein(P, Q) -> np.ndarray:
    """Bernstein coefficients of the scalar ``P(t) x Q(t)`` (``x1*y2 - y1*x2``)
    of two planar Bezier curves given by their control points."""
    P = np.asarray(P, float)
    Q = np.asarray(Q, float)
    return bernstein_product(P[:, 0], Q[:, 1]) - bernstein_product(P[:, 1], Q[:, 0])


def hodographs(ctrl) -> tuple[np.ndarray, np.ndarray]:
    """Control points of ``r'(t)`` and ``r''(t)`` (a single zero point when the
    degree is too low to have them)."""
    P = np.asarray(ctrl, float)
    n = len(P) - 1
    D1 = derivative_matrix(n, 1) @ P if n >= 1 else np.zeros((1, 2))
    D2 = derivative_matrix(n, 2) @ P if n >= 2 else np.zeros((1, 2))
    return D1, D2


def speed_lower_bound(ctrl) -> float:
    """A lower bound of the speed ``|r'(t)|`` on ``[0, 1]``; ``<= 0`` means none found.

    ``|r'(t)| >= r'(t).u >= min_i d_i.u`` for any unit ``u`` (``d_i`` the
    hodograph's control points). Tried directions: the mean of the ``d_i``,
    the chord and the end tangents; the best is kept. Positive only when the
    hodograph's control polygon lies in an open half-plane (and one of those
    directions shows it), which subdivision achieves for a regular curve.
    """
    P = np.asarray(ctrl, float)
    D1, _ = hodographs(P)
    best = -math.inf
    for u in (D1.mean(axis=0), P[-1] - P[0], D1[0], D1[-1]):
        nu = math.hypot(u[0], u[1])
        if nu > 0.0:
            best = max(best, float(np.min(D1 @ (u / nu))))
    return best


def curvature_bound(ctrl, max_depth: int = 30) -> float:
    """A certified upper bound of ``|kappa(t)|`` on ``[0, 1]`` (1/program units).

    On a piece, ``|kappa| = |r' x r''| / |r'|^3`` is at most the smaller of
    ``max|r''| / min|r'|^2`` and ``max|r' x r''| / min|r'|^3``, with
    ``max|r''| <= max_i |e_i|`` (``e_i`` the control points of ``r''``: the
    norm is convex), ``max|r' x r''|`` at most the largest Bernstein
    coefficient of that polynomial in magnitude (exact 0 on a straight
    curve) and ``min|r'|`` from :func:`speed_lower_bound`. Where that
    lower bound is not positive, or to tighten it, the piece is halved by de
    Casteljau; the bound is the largest over the pieces. ``inf`` when some
    piece still has no positive speed bound after ``max_depth`` halvings (the
    speed vanishes: a cusp or a point where the curve stops). A speed bound
    within the rounding of the coordinates (``64 (n+1) eps max|P_i|``) counts
    as none. A line (degree 1) has curvature 0.
    """
    P = np.asarray(ctrl, float)
    if len(P) < 3:
        return 0.0
    worst = 0.0
    stack = [(P, 0)]
    while stack:
        Q, depth = stack.pop()
        vmin = speed_lower_bound(Q)
        # The hodograph's control points are differences of the coordinates:
        # a speed bound within their rounding is no evidence of motion.
        noise = 64.0 * len(Q) * np.finfo(float).eps * float(np.max(np.abs(Q)))
        if vmin > noise and vmin ** 3 > 0.0:
            D1, D2 = hodographs(Q)
            acc = float(np.max(np.hypot(D2[:, 0], D2[:, 1])))
            turn = float(np.max(np.abs(cross_bernstein(D1, D2))))
            worst = max(worst, min(acc / (vmin * vmin), turn / (vmin * vmin * vmin)))
            continue
        if depth >= max_depth:
            return math.inf
        left, right = de_casteljau_split(Q)
        stack.append((left, depth + 1))
        stack.append((right, depth + 1))
    return worst


def _bernstein_to_power(b: np.ndarray) -> np.ndarray:
    """Power-basis coefficients ``c_j`` (``sum c_j t^j``) of Bernstein coefficients ``b``."""
    n = len(b) - 1
    c = np.zeros(n + 1)
    for j in range(n + 1):
        c[j] = math.comb(n, j) * sum((-1) ** (j - i) * math.comb(j, i) * b[i]
                                     for i in range(j + 1))
    return c


#: Power-basis coefficients below this fraction of the largest are rounding
#: left over from the basis change (exact zeros in exact arithmetic).
POWER_COEFF_NOISE_REL = 1e-14

#: Polynomial roots whose imaginary part is at most this are real: a double
#: root splits into a pair about sqrt(eps) ~ 1e-8 apart, the candidate is
#: only a candidate (its sign change is tested), so the bound is generous.
ROOT_IMAG_TOL = 1e-7

#: Values of ``r' x r''`` within this fraction of its largest Bernstein
#: coefficient have no sign (rounding of the cross product).
CROSS_SIGN_NOISE_REL = 1e-12


def inflections(ctrl) -> list[float]:
    """Parameters ``t`` in ``(0, 1)`` where the curvature of the Bezier ``ctrl``
    changes sign, ascending.

    The candidates are the real roots of ``r' x r''`` (power basis); the sign
    of ``r' x r''`` between consecutive candidates decides which are sign
    changes. Values within rounding of zero (``1e-12`` of the largest
    Bernstein coefficient) have no sign, so a touching zero (even multiplicity,
    computed as a cluster of near roots) is not an inflection. Each sign
    change is polished by bisection to adjacent floats of ``t``.
    """
    P = np.asarray(ctrl, float)
    if len(P) < 3:
        return []
    D1, D2 = hodographs(P)
    k = cross_bernstein(D1, D2)
    scale = float(np.max(np.abs(k)))
    if scale == 0.0:
        return []                      # a straight curve: no turn at all
    c = _bernstein_to_power(k)
    nz = np.flatnonzero(np.abs(c) > POWER_COEFF_NOISE_REL * np.max(np.abs(c)))
    cand = []
    if len(nz) and nz[-1] >= 1:
        roots = np.polynomial.polynomial.polyroots(c[: nz[-1] + 1])
        cand = sorted(float(r.real) for r in roots
                      if abs(r.imag) <= ROOT_IMAG_TOL and 0.0 < r.real < 1.0)
    noise = CROSS_SIGN_NOISE_REL * scale

    def sign_at(t: float) -> float:
        v = float(bernstein(np.array([t]), len(k) - 1)[0] @ k)
        return 0.0 if abs(v) <= noise else math.copysign(1.0, v)

    edges = [0.0, *cand, 1.0]
    mids = [0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])]
    signed = [(m, sg) for m in mids if (sg := sign_at(m)) != 0.0]
    out = []
    for (lo, s_lo), (hi, s_hi) in zip(signed[:-1], signed[1:]):
        if s_lo == s_hi:
            continue
        while True:                    # bisection to adjacent floats
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            sg = sign_at(mid)
            if sg == 0.0:
                lo = hi = mid
                break
            if sg == s_lo:
                lo = mid
            else:
                hi = mid
        out.append(0.5 * (lo + hi))
    return out


#: A curve whose speed ``|r'(t)|`` falls to this times ``max(1, |control
#: points|)`` on the check grid is not regular (the arc-length map needs it > 0).
REGULAR_SPEED_REL = 1e-12

#: Inversions ``s -> t`` a curve keeps for reuse (the feed planners evaluate up to
#: four orders, on both sides of the gridpoints, at the same arc lengths).
RECENT_INVERSIONS = 8

#: Speed samples of the regularity check (equal steps of ``t``, ends included).
REGULAR_CHECK_SAMPLES = 2049

#: A root of a hodograph component is real when its imaginary part is below
#: this (the roots of the low-degree hodographs used here are well separated).
BBOX_ROOT_IMAG_TOL = 1e-12


def _at(ctrl: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Points of the Bezier ``ctrl`` at parameters ``t`` (1-D): one basis product."""
    return bernstein_basis(t, len(ctrl) - 1) @ ctrl


def unit_tangent(r1: np.ndarray) -> np.ndarray:
    """``dp/ds = r' / |r'|`` from the parameter derivative ``r'`` (``(N, 2)``)."""
    return r1 / np.hypot(*r1.T)[:, None]


def d2_from(r1: np.ndarray, r2: np.ndarray) -> np.ndarray:
    """``d2p/ds2`` (units^-1) from ``r'`` and ``r''`` (``(N, 2)`` each): the part
    of ``r''`` normal to the tangent over ``|r'|^2``."""
    v2 = np.einsum("ij,ij->i", r1, r1)
    T = r1 / np.sqrt(v2)[:, None]
    return (r2 - np.einsum("ij,ij->i", r2, T)[:, None] * T) / v2[:, None]


def d3_from(r1: np.ndarray, r2: np.ndarray, r3: np.ndarray) -> np.ndarray:
    """``d3p/ds3 = kappa_s N - kappa^2 T`` (units^-2) from ``r'``, ``r''`` and
    ``r'''`` (``(N, 2)`` each)."""
    v = np.hypot(r1[:, 0], r1[:, 1])
    T = r1 / v[:, None]
    N = np.c_[-T[:, 1], T[:, 0]]
    c12 = r1[:, 0] * r2[:, 1] - r1[:, 1] * r2[:, 0]
    c13 = r1[:, 0] * r3[:, 1] - r1[:, 1] * r3[:, 0]
    kappa = c12 / v ** 3
    dkappa = (c13 / v ** 3 - 3.0 * c12 * np.einsum("ij,ij->i", r1, r2) / v ** 5) / v
    return dkappa[:, None] * N - (kappa * kappa)[:, None] * T


@dataclass(frozen=True, eq=False)
class BezierCurve:
    """Planar Bezier curve of ``degree`` = len(control_points) - 1, by arc length.

    ``control_points`` are in program units. Immutable; equality is identity.
    Arc lengths ``s`` are clipped to ``[0, length]``; a scalar ``s`` gives one
    point ``(2,)`` (or a float), an array ``(N,)`` gives ``(N, 2)`` (or ``(N,)``).
    """

    control_points: tuple
    _P: np.ndarray = field(init=False, repr=False)
    _D1: np.ndarray = field(init=False, repr=False)
    _D2: np.ndarray = field(init=False, repr=False)
    _D3: np.ndarray = field(init=False, repr=False)
    _table: ArcLengthTable = field(init=False, repr=False)
    # recent inversions {s as bytes: t}: toppra and the profile sampler ask for the
    # point and its derivatives at the same s one order (and one side) at a time
    _recent: dict = field(init=False, repr=False)
    _box: tuple | None = field(init=False, repr=False)

    def __post_init__(self):
        P = np.asarray(self.control_points, dtype=float)
        if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2:
            raise ValueError("a Bezier curve needs at least two 2-D control points")
        if not np.all(np.isfinite(P)):
            raise ValueError("control points must be finite")
        object.__setattr__(self, "control_points", tuple(map(tuple, P.tolist())))
        object.__setattr__(self, "_P", P)
        D1, D2, D3 = _hodographs(P)
        object.__setattr__(self, "_D1", D1)
        object.__setattr__(self, "_D2", D2)
        object.__setattr__(self, "_D3", D3)
        grid = np.linspace(0.0, 1.0, REGULAR_CHECK_SAMPLES)
        speed_check = np.hypot(*_at(D1, grid).T)
        if speed_check.min() <= REGULAR_SPEED_REL * max(1.0, float(np.abs(P).max())):
            raise ValueError("the Bezier curve is not regular (its speed vanishes)")
        object.__setattr__(self, "_table", ArcLengthTable(D1))
        object.__setattr__(self, "_recent", {})
        object.__setattr__(self, "_box", None)

    def __reduce__(self):
        # the control points and the arc-length table travel (to and from worker
        # processes): the table is most of the construction's cost, paid once
        return (_restored, (self.control_points, self._table))

    # -- parameter t --------------------------------------------------------------
    @property
    def degree(self) -> int:
        return len(self._P) - 1

    def _t(self, s) -> np.ndarray:
        """Parameters at arc lengths ``s`` (1-D, clipped); the last
        :data:`RECENT_INVERSIONS` answers are reused (read-only arrays)."""
        s = np.clip(np.atleast_1d(np.asarray(s, dtype=float)).reshape(-1), 0.0, self.length)
        key = s.tobytes()
        recent = self._recent
        t = recent.get(key)
        if t is None:
            t = self._table.t_of_s(s)
            t.setflags(write=False)
            if len(recent) >= RECENT_INVERSIONS:
                recent.pop(next(iter(recent)))      # the oldest (dicts keep insertion order)
            recent[key] = t
        return t

    def t_of_s(self, s) -> np.ndarray:
        """Bezier parameter at arc length ``s`` (vectorised, clipped to [0, length]):
        ``|s(t) - s|`` at most :data:`~ccopt.geometry.bezier_arclength.ARC_LENGTH_REL_TOL`
        times the length."""
        return self._t(s).copy()

    # -- interface shared with Line / Arc / Spiral -----------------------------------
    @property
    def length(self) -> float:
        return self._table.length

    @property
    def start(self):
        return tuple(map(float, self._P[0]))

    @property
    def end(self):
        return tuple(map(float, self._P[-1]))

    def _tangent_t(self, t):
        return unit_tangent(_at(self._D1, np.atleast_1d(t)))

    @property
    def start_tangent(self):
        return tuple(map(float, self._tangent_t(0.0)[0]))

    @property
    def end_tangent(self):
        return tuple(map(float, self._tangent_t(1.0)[0]))

    def _out(self, arr, s):
        return arr[0] if np.ndim(s) == 0 else arr

    def point(self, s):
        return self._out(_at(self._P, self._t(s)), s)

    def tangent(self, s):
        return self._out(self._tangent_t(self._t(s)), s)

    d1 = tangent

    def normal(self, s):
        t = np.atleast_2d(self.tangent(s))
        return self._out(np.c_[-t[:, 1], t[:, 0]], s)

    def _derivs(self, s, order: int = 2):
        """``r'``, ``r''`` (and ``r'''`` for ``order`` 3) at arc lengths ``s``."""
        t = self._t(s)
        out = [_at(self._D1, t)]
        for D, k in ((self._D2, 2), (self._D3, 3))[: order - 1]:
            out.append(_at(D, t) if self.degree >= k else np.zeros_like(out[0]))
        return out

    def curvature(self, s):
        r1, r2 = self._derivs(s)
        k = (r1[:, 0] * r2[:, 1] - r1[:, 1] * r2[:, 0]) / np.hypot(*r1.T) ** 3
        return float(k[0]) if np.ndim(s) == 0 else k

    def d2(self, s):
        return self._out(d2_from(*self._derivs(s)), s)

    def d3(self, s):
        """``d3p/ds3 = kappa_s N - kappa^2 T`` (units^-2; see the module docstring)."""
        return self._out(d3_from(*self._derivs(s, 3)), s)

    def bbox(self) -> tuple[float, float, float, float]:
        """Exact bounding box: end points and the roots of each derivative component
        (computed once)."""
        if self._box is None:
            object.__setattr__(self, "_box", self._bbox())
        return self._box

    def _bbox(self) -> tuple[float, float, float, float]:
        ts = [0.0, 1.0]
        n1 = len(self._D1) - 1
        for axis in range(2):
            # power-basis coefficients of the hodograph component (degree n1)
            coeffs = np.zeros(n1 + 1)
            for i, c in enumerate(self._D1[:, axis]):
                for j in range(i, n1 + 1):
                    coeffs[j] += c * math.comb(n1, i) * math.comb(n1 - i, j - i) * (-1) ** (j - i)
            if np.any(coeffs[1:] != 0):
                for root in np.roots(coeffs[::-1]):
                    if abs(root.imag) < BBOX_ROOT_IMAG_TOL and 0.0 < root.real < 1.0:
                        ts.append(float(root.real))
        pts = _at(self._P, np.array(ts))
        return (float(pts[:, 0].min()), float(pts[:, 1].min()),
                float(pts[:, 0].max()), float(pts[:, 1].max()))

    def split(self, s: float) -> tuple["BezierCurve", "BezierCurve"]:
        t = float(self._t(s)[0])
        left, right = [], []
        pts = self._P.copy()
        while len(pts):
            left.append(pts[0].copy())
            right.append(pts[-1].copy())
            pts = (1 - t) * pts[:-1] + t * pts[1:]
        return BezierCurve(np.array(left)), BezierCurve(np.array(right[::-1]))

    def reversed(self) -> "BezierCurve":
        return BezierCurve(self._P[::-1].copy())


def _restored(control_points: tuple, table: ArcLengthTable) -> BezierCurve:
    """A pickled :class:`BezierCurve` as it was made: its control points (checked
    then) and its arc-length table; the hodographs are derived again (exactly:
    differences of the same floats)."""
    curve = object.__new__(BezierCurve)
    P = np.asarray(control_points, dtype=float)
    D1, D2, D3 = _hodographs(P)
    for name, value in (("control_points", control_points), ("_P", P), ("_D1", D1),
                        ("_D2", D2), ("_D3", D3), ("_table", table), ("_recent", {}),
                        ("_box", None)):
        object.__setattr__(curve, name, value)
    return curve


def _hodographs(P: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Control points of the first three derivatives of the Bezier curve ``P``
    (``[[0, 0]]`` past its degree)."""
    D1 = hodograph(P)
    D2 = hodograph(D1) if len(D1) > 1 else np.zeros((1, 2))
    D3 = hodograph(D2) if len(D2) > 1 else np.zeros((1, 2))
    return D1, D2, D3
