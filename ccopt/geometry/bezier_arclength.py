"""Arc length of a planar Bezier curve and its inverse, vectorised over arrays.

The curve stays an exact polynomial; what is approximate here is the map
between its parameter ``t`` in [0, 1] and the arc length ``s`` (program
units), and each approximation has a stated tolerance:

* **the table** :class:`ArcLengthTable` holds ``s(t)`` at knots of ``t``. Each
  piece's length is Gauss-Legendre quadrature (:data:`GL_NODES` nodes) of the
  speed ``|r'(t)|``; a piece is halved until the quadrature of the piece and
  the sum over its two halves differ by at most :data:`ARC_LENGTH_REL_TOL`
  times the curve's length times the piece's share of ``[0, 1]`` (so the
  estimates add up to at most that tolerance over the curve), and the halves'
  sum is kept. The speed of a regular curve is smooth, so the estimate is
  the usual one of a converging quadrature (not a certified bound).
* **the inverse** :meth:`ArcLengthTable.t_of_s` returns ``t`` with
  ``|s(t) - s| <= ARC_LENGTH_REL_TOL * length`` (``s(t)`` measured from the
  piece's knot by the same quadrature on ``[t_knot, t]``): a cubic Hermite
  guess of ``t(s)`` inside the piece (``dt/ds = 1/|r'|`` at both knots),
  then Newton steps ``t -= (s(t) - s) / |r'(t)|`` kept inside a bracket that
  shrinks with every residual (a step leaving it is replaced by bisection),
  each point stopping as soon as its residual is within the tolerance, or
  after a Newton step ``delta`` whose Taylor remainder
  ``max|r''| delta^2 / 2`` (``|s''(t)| = |r'.r''|/|r'| <= |r''|``, bounded
  by the largest control point of ``r''``) is within half of it.

:func:`bernstein_basis` is the Bernstein basis as a matrix (``t`` values by
``n + 1``), so evaluating a curve or its hodographs at many ``t`` is one
matrix product; at ``t = 0`` and ``t = 1`` it is exactly a unit row (the
curve's end points come out bit for bit).
"""
from __future__ import annotations

import functools
import math

import numpy as np

#: The arc-length table and its inverse hold ``|s(t) - s|`` within this times
#: the curve's length: about 5,000 ulps of a length, far below any programmed
#: resolution (1e-4 mm on 1 m is 1e-7) and far above the rounding of a
#: quadrature sum (a few ulps), so the stop is always reached.
ARC_LENGTH_REL_TOL = 1e-12

#: Gauss-Legendre nodes per piece of the table and per residual.
GL_NODES = 8

#: Equal pieces of ``[0, 1]`` the table starts from before halving.
FIRST_PIECES = 16

#: Halvings of a table piece at most (a piece of 2^-30 of ``[0, 1]``): a
#: regular curve's speed needs a handful; the cap only ends the loop on a
#: curve whose speed nearly vanishes (its table then keeps the last estimate).
MAX_HALVINGS = 30

#: Newton/bisection rounds of the inverse at most: bisection alone halves the
#: bracket each round, so 64 rounds reach adjacent floats of ``t``.
MAX_INVERSION_ROUNDS = 64

_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_NODES)


def bernstein_basis(t: np.ndarray, n: int) -> np.ndarray:
    """Bernstein basis of degree ``n`` at ``t`` (1-D): ``(len(t), n + 1)``,
    ``B[:, i] = C(n, i) t^i (1 - t)^(n - i)``."""
    t = np.asarray(t, float).reshape(-1, 1)
    i, comb = _binomials(n)
    # whole-array powers: a few array operations whatever the degree (a loop per
    # power was most of the time of evaluating blend curves, called per curve)
    return comb * t ** i * (1.0 - t) ** (n - i)


def bezier_points(basis: np.ndarray, P: np.ndarray) -> np.ndarray:
    """``(N, 2)`` points ``sum_i basis[:, i] P_i`` of Bezier curves: ``P`` the
    control points ``(n + 1, 2)`` of one curve, or ``(N, n + 1, 2)`` one curve
    per row. Summed term by term in one order either way, so a row comes out
    bit for bit as its curve alone gives it (a matrix product's summation
    order is the BLAS's: :mod:`ccopt.verify.distance.certified_batch` relies on this)."""
    out = basis[:, 0, None] * P[..., 0, :]
    for i in range(1, basis.shape[1]):
        out += basis[:, i, None] * P[..., i, :]
    return out


@functools.lru_cache(maxsize=None)
def _binomials(n: int) -> tuple[np.ndarray, np.ndarray]:
    """``(0..n, C(n, 0..n))`` as float arrays."""
    return np.arange(n + 1, dtype=float), np.array([math.comb(n, i) for i in range(n + 1)],
                                                   float)


def hodograph(ctrl: np.ndarray) -> np.ndarray:
    """Control points of ``r'(t)`` (degree one lower; one zero point for a point)."""
    n = len(ctrl) - 1
    return n * np.diff(ctrl, axis=0) if n >= 1 else np.zeros((1, ctrl.shape[1]))


def power_coefficients(b: np.ndarray) -> np.ndarray:
    """Power-basis coefficients (rows: ``t^0 .. t^n``) of Bernstein coefficients ``b``
    (rows: control points): ``c_j = C(n, j) sum_i (-1)^(j-i) C(j, i) b_i``."""
    n = len(b) - 1
    M = np.array([[math.comb(n, j) * math.comb(j, i) * (-1) ** (j - i) if i <= j else 0
                   for i in range(n + 1)] for j in range(n + 1)], float)
    return M @ b


def speed_at(C1: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``|r'(t)|`` from the power-basis coefficients ``C1`` of the hodograph
    (:func:`power_coefficients`; Horner's rule, one pass per degree)."""
    x = np.full(t.shape, C1[-1, 0])
    y = np.full(t.shape, C1[-1, 1])
    for cx, cy in C1[-2::-1]:
        x = x * t + cx
        y = y * t + cy
    return np.hypot(x, y)


def gauss_legendre(C1: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Arc length from ``t = a`` to ``t = b`` (arrays) by :data:`GL_NODES`-point
    Gauss-Legendre quadrature of the speed (``C1`` as in :func:`speed_at`)."""
    half = 0.5 * (b - a)
    x = half[:, None] * _GL_X[None, :] + (0.5 * (a + b))[:, None]
    return half * (speed_at(C1, x) @ _GL_W)


class ArcLengthTable:
    """``s(t)`` of a regular Bezier curve at knots ``t_k`` (ascending, ``0`` to ``1``)
    and its inverse (see the module docstring).

    Attributes: ``knots_t``, ``knots_s`` (program units, ``knots_s[-1]`` the
    length), ``knots_speed`` (``|r'(t_k)|``), ``tol`` (the inverse's residual
    bound, program units).
    """

    def __init__(self, D1: np.ndarray):
        """``D1``: control points of the hodograph ``r'(t)`` (program units)."""
        self._C1 = C1 = power_coefficients(D1)
        # max |r''(t)| <= the largest control point of r'' (a convex combination of them)
        D2 = hodograph(D1) if len(D1) > 1 else np.zeros((1, 2))
        self._acc = float(np.max(np.hypot(D2[:, 0], D2[:, 1])))
        edges = np.linspace(0.0, 1.0, FIRST_PIECES + 1)
        a, b = edges[:-1], edges[1:]
        coarse = gauss_legendre(C1, a, b)
        total = float(coarse.sum())
        done_a, done_s = [], []
        for _ in range(MAX_HALVINGS):
            m = 0.5 * (a + b)
            left = gauss_legendre(C1, a, m)
            right = gauss_legendre(C1, m, b)
            ok = np.abs(left + right - coarse) <= ARC_LENGTH_REL_TOL * total * (b - a)
            done_a += [a[ok], m[ok]]
            done_s += [left[ok], right[ok]]
            keep = ~ok
            if not keep.any():
                break
            a, b = np.concatenate((a[keep], m[keep])), np.concatenate((m[keep], b[keep]))
            coarse = np.concatenate((left[keep], right[keep]))
        else:  # the speed nearly vanishes somewhere: keep what the last halving gave
            done_a.append(a)
            done_s.append(coarse)
        a = np.concatenate(done_a)
        order = np.argsort(a, kind="stable")
        pieces = np.concatenate(done_s)[order]
        self.knots_t = np.r_[a[order], 1.0]
        self.knots_s = np.r_[0.0, np.cumsum(pieces)]
        self.knots_speed = speed_at(C1, self.knots_t)
        self.tol = ARC_LENGTH_REL_TOL * float(self.knots_s[-1])

    @property
    def length(self) -> float:
        """Length of the curve (program units)."""
        return float(self.knots_s[-1])

    def _guess(self, j: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Cubic Hermite interpolation of ``t(s)`` on piece ``j`` (slopes ``1/|r'|``)."""
        t0, t1 = self.knots_t[j], self.knots_t[j + 1]
        s0, h = self.knots_s[j], self.knots_s[j + 1] - self.knots_s[j]
        safe = np.where(h > 0.0, h, 1.0)
        x = np.where(h > 0.0, (s - s0) / safe, 0.0)
        m0 = h / self.knots_speed[j]
        m1 = h / self.knots_speed[j + 1]
        x2, x3 = x * x, x * x * x
        t = ((2 * x3 - 3 * x2 + 1) * t0 + (x3 - 2 * x2 + x) * m0
             + (-2 * x3 + 3 * x2) * t1 + (x3 - x2) * m1)
        return np.clip(t, t0, t1)

    def t_of_s(self, s) -> np.ndarray:
        """``t`` with ``|s(t) - s| <= tol`` for each ``s`` (1-D array, clipped to
        ``[0, length]``); ``0`` and ``length`` give ``t = 0`` and ``1`` exactly."""
        s = np.clip(np.asarray(s, float).reshape(-1), 0.0, self.length)
        # the ends by definition: the curve's end points come out exactly
        t = np.where(s >= self.length, 1.0, 0.0)
        active = np.flatnonzero((s > 0.0) & (s < self.length))
        if not active.size:
            return t
        last = len(self.knots_t) - 2
        j = np.clip(np.searchsorted(self.knots_s, s, side="right") - 1, 0, last)
        t[active] = self._guess(j[active], s[active])
        lo, hi = self.knots_t[j], self.knots_t[j + 1]      # fancy indexing: copies
        for _ in range(MAX_INVERSION_ROUNDS):
            ja, ta = j[active], t[active]
            res = (self.knots_s[ja] + gauss_legendre(self._C1, self.knots_t[ja], ta)
                   - s[active])
            open_ = np.abs(res) > self.tol
            active, res, ta = active[open_], res[open_], ta[open_]
            if not active.size:
                break
            below = res < 0.0
            lo[active] = np.where(below, ta, lo[active])
            hi[active] = np.where(below, hi[active], ta)
            delta = res / speed_at(self._C1, ta)
            step = ta - delta
            la, ha = lo[active], hi[active]
            inside = (step > la) & (step < ha)
            new = np.where(inside, step, 0.5 * (la + ha))
            # a bracket down to adjacent floats: t is as good as a double gets
            stuck = (new <= la) | (new >= ha) | (new == ta)
            # Taylor: a Newton step leaves |s(t) - s| <= max|s''| delta^2 / 2 (s'' = r'.r''/|r'|)
            converged = inside & (0.5 * self._acc * delta * delta <= 0.5 * self.tol)
            t[active] = np.where(stuck, ta, new)
            active = active[~(stuck | converged)]
            if not active.size:
                break
        return t
