"""Many Bezier curves of one degree, by arc length, evaluated together.

A smoothed tool path has hundreds of blend curves; the feed planners
evaluate the path at every gridpoint for each derivative order, so calling
each curve's own methods (:class:`~ccopt.geometry.curve.BezierCurve`) costs
one arc-length inversion and a dozen small array operations per curve per
call: on freeform-hsm's smoothed path (302 curves, 14,000 gridpoints) a
quarter of its jerk-limited plan. :class:`BezierBatch` holds the curves'
control points, hodographs and arc-length tables as arrays and does the
same work for all curves at once: a point ``i`` on curve ``c[i]``.

The inversion ``s -> t`` is :meth:`ccopt.geometry.bezier_arclength.ArcLengthTable.t_of_s`
run on every point together (the same knots, Hermite guess, Newton steps in
a shrinking bracket and stopping rules, each point with its own curve's
coefficients), so it meets the same bound, ``|s(t) - s| <= ARC_LENGTH_REL_TOL
* length`` of its curve; the derivatives by arc length are the curve's
formulas (:func:`~ccopt.geometry.curve.unit_tangent`,
:func:`~ccopt.geometry.curve.d2_from`, :func:`~ccopt.geometry.curve.d3_from`).
Numbers agree with the curves' own methods to rounding (the tests: within a
few ulps of the path's size); ``s = 0`` and ``s = length`` give the end
points exactly.
"""
from __future__ import annotations

import numpy as np

from ccopt.geometry.bezier_arclength import (
    _GL_W, _GL_X, MAX_INVERSION_ROUNDS, bernstein_basis, bezier_points,
)
from ccopt.geometry.curve import BezierCurve


class BezierBatch:
    """Bezier curves of one degree (:class:`~ccopt.geometry.curve.BezierCurve`),
    as arrays; every method takes ``c`` (the curve of each point, indices
    into ``curves``) and in-curve arc lengths ``s`` (program units, clipped
    to ``[0, length]`` of each point's curve)."""

    def __init__(self, curves):
        curves = list(curves)
        if not curves:
            raise ValueError("a batch needs at least one curve")
        degrees = {c.degree for c in curves}
        if len(degrees) != 1:
            raise ValueError(f"a batch holds curves of one degree, not {sorted(degrees)}")
        self.degree = n = degrees.pop()
        self.P = np.array([c._P for c in curves])                       # (m, n + 1, 2)
        self.D1 = np.array([c._D1 for c in curves])
        self.D2 = np.array([c._D2 for c in curves])
        self.D3 = np.array([c._D3 for c in curves])
        tables = [c._table for c in curves]
        self.C1 = np.array([t._C1 for t in tables])                      # (m, n, 2)
        self.acc = np.array([t._acc for t in tables])
        self.tol = np.array([t.tol for t in tables])
        self.length = np.array([t.length for t in tables])
        # knots padded to one width: s past a curve's last knot (+inf) is never <= s
        width = max(len(t.knots_t) for t in tables)
        self.knots_t = np.ones((len(tables), width))
        self.knots_s = np.full((len(tables), width), np.inf)
        self.knots_speed = np.ones((len(tables), width))
        self.last_piece = np.array([len(t.knots_t) - 2 for t in tables])
        for i, t in enumerate(tables):
            k = len(t.knots_t)
            self.knots_t[i, :k] = t.knots_t
            self.knots_s[i, :k] = t.knots_s
            self.knots_speed[i, :k] = t.knots_speed
        self._n = n

    # -- arc length -----------------------------------------------------------

    def _speed(self, cx, cy, t):
        """``|r'(t)|`` with each row's power coefficients ``cx, cy`` (``(N, n)``,
        as :func:`~ccopt.geometry.bezier_arclength.speed_at`); ``t`` ``(N,)``
        or ``(N, q)``."""
        extra = (None,) * (t.ndim - 1)
        x = np.broadcast_to(cx[(slice(None), -1) + extra], t.shape).copy()
        y = np.broadcast_to(cy[(slice(None), -1) + extra], t.shape).copy()
        for j in range(cx.shape[1] - 2, -1, -1):
            x = x * t + cx[(slice(None), j) + extra]
            y = y * t + cy[(slice(None), j) + extra]
        return np.hypot(x, y)

    def _arc_length(self, cx, cy, a, b):
        """Arc length from ``t = a`` to ``t = b`` per row (Gauss-Legendre, as
        :func:`~ccopt.geometry.bezier_arclength.gauss_legendre`)."""
        half = 0.5 * (b - a)
        x = half[:, None] * _GL_X[None, :] + (0.5 * (a + b))[:, None]
        return half * (self._speed(cx, cy, x) @ _GL_W)

    def _knots_at_or_below(self, c, s) -> np.ndarray:
        """How many knots of curve ``c[i]`` are at or below ``s[i]``, each: a
        binary search over every row at once (each row ascending, padded with
        +inf), gathering one knot per point and round instead of a whole row."""
        lo = np.zeros(c.size, np.intp)                  # knots[:lo] <= s
        hi = np.full(c.size, self.knots_s.shape[1], np.intp)   # knots[hi:] > s
        while True:
            open_ = np.flatnonzero(lo < hi)
            if not open_.size:
                return lo
            mid = (lo[open_] + hi[open_]) // 2
            at_or_below = self.knots_s[c[open_], mid] <= s[open_]
            lo[open_] = np.where(at_or_below, mid + 1, lo[open_])
            hi[open_] = np.where(at_or_below, hi[open_], mid)

    def t_of_s(self, c, s) -> np.ndarray:
        """Bezier parameter of each point: ``|s(t) - s| <= tol`` of its curve
        (see the module docstring); ``0`` and ``length`` give ``t = 0`` and ``1``."""
        c = np.asarray(c, dtype=np.intp).reshape(-1)
        L = self.length[c]
        s = np.clip(np.asarray(s, float).reshape(-1), 0.0, L)
        t = np.where(s >= L, 1.0, 0.0)
        active = np.flatnonzero((s > 0.0) & (s < L))
        if not active.size:
            return t
        ca, sa = c[active], s[active]
        # each point's piece: its curve's knots at or below s, less one (padding is +inf)
        j = np.minimum(self._knots_at_or_below(ca, sa) - 1, self.last_piece[ca])
        j = np.maximum(j, 0)
        t0, t1 = self.knots_t[ca, j], self.knots_t[ca, j + 1]
        s0, h = self.knots_s[ca, j], self.knots_s[ca, j + 1] - self.knots_s[ca, j]
        # cubic Hermite guess of t(s) on the piece (slopes 1/|r'| at its knots)
        safe = np.where(h > 0.0, h, 1.0)
        x = np.where(h > 0.0, (sa - s0) / safe, 0.0)
        m0, m1 = h / self.knots_speed[ca, j], h / self.knots_speed[ca, j + 1]
        x2, x3 = x * x, x * x * x
        guess = ((2 * x3 - 3 * x2 + 1) * t0 + (x3 - 2 * x2 + x) * m0
                 + (-2 * x3 + 3 * x2) * t1 + (x3 - x2) * m1)
        ta = np.clip(guess, t0, t1)
        lo, hi = t0.copy(), t1.copy()
        cx, cy = self.C1[ca, :, 0], self.C1[ca, :, 1]
        acc, tol = self.acc[ca], self.tol[ca]
        live = np.arange(active.size)            # rows of the points still iterating
        out = ta.copy()
        for _ in range(MAX_INVERSION_ROUNDS):
            res = s0[live] + self._arc_length(cx[live], cy[live], t0[live], out[live]) - sa[live]
            open_ = np.abs(res) > tol[live]
            live, res = live[open_], res[open_]
            if not live.size:
                break
            tl = out[live]
            below = res < 0.0
            lo[live] = np.where(below, tl, lo[live])
            hi[live] = np.where(below, hi[live], tl)
            delta = res / self._speed(cx[live], cy[live], tl)
            step = tl - delta
            la, ha = lo[live], hi[live]
            inside = (step > la) & (step < ha)
            new = np.where(inside, step, 0.5 * (la + ha))
            stuck = (new <= la) | (new >= ha) | (new == tl)
            converged = inside & (0.5 * acc[live] * delta * delta <= 0.5 * tol[live])
            out[live] = np.where(stuck, tl, new)
            live = live[~(stuck | converged)]
            if not live.size:
                break
        t[active] = out
        return t

    # -- points and derivatives -------------------------------------------------

    def at(self, which: str, c, t) -> np.ndarray:
        """``(N, 2)``: the curve (``"P"``) or a hodograph (``"D1"``, ``"D2"``,
        ``"D3"``) of each point's curve at parameters ``t``; zero where the
        degree is too low to have it."""
        ctrl = getattr(self, which)[np.asarray(c, dtype=np.intp)]        # (N, k + 1, 2)
        return bezier_points(bernstein_basis(t, ctrl.shape[1] - 1), ctrl)

    def derivatives(self, c, t, order: int) -> list[np.ndarray]:
        """``r'``, ``r''`` (and ``r'''`` for ``order`` 3) at parameters ``t``, as
        :meth:`~ccopt.geometry.curve.BezierCurve._derivs` gives them."""
        out = [self.at("D1", c, t)]
        for name, k in (("D2", 2), ("D3", 3))[: order - 1]:
            out.append(self.at(name, c, t) if self.degree >= k else np.zeros_like(out[0]))
        return out


def batches_by_degree(geoms) -> tuple[np.ndarray, np.ndarray, list[BezierBatch]]:
    """The Bezier curves among ``geoms`` in batches, one per degree: ``(batch,
    row, batches)``, ``batch[i]`` the batch of ``geoms[i]`` (-1: not a Bezier
    curve) and ``row[i]`` its row there."""
    batch = np.full(len(geoms), -1, dtype=np.intp)
    row = np.zeros(len(geoms), dtype=np.intp)
    by_degree: dict[int, list[int]] = {}
    for i, g in enumerate(geoms):
        if type(g) is BezierCurve:
            by_degree.setdefault(g.degree, []).append(i)
    batches = []
    for members in by_degree.values():
        batch[members] = len(batches)
        row[members] = np.arange(len(members))
        batches.append(BezierBatch([geoms[i] for i in members]))
    return batch, row, batches
