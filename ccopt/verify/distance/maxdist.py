"""Exact largest distance from a segment or arc to another segment or arc.

``max_{q in A} dist(q, B)`` is what the contact check needs: the tool segment
``A`` must stay within ``r + eps`` of its programmed element ``B`` all along.
``f(q) = dist(q, B)`` is continuous and, restricted to ``A``, piecewise
smooth; its largest value is at an end point of ``A``, at a local maximum
inside one piece, or on a piece boundary. The pieces of the plane are:

- for a line ``B``: the band where the foot falls inside ``B``
  (``f = |signed distance to the line|``) and the two caps beyond its ends
  (``f = |q - end|``), separated by the normal lines at the ends;
- for an arc ``B``: the sector of polar angles inside the sweep
  (``f = |rho - R|``, ``rho = |q - c|``) and the two halves of the gap
  (``f = |q - end|``), separated by the rays through the end points and the
  gap's bisector.

Local maxima inside a piece: along a line ``A`` the distance to a point or
a line is convex (no interior maximum) and ``|rho - R|`` has one where
``rho`` is smallest (the foot of ``c`` on ``A``); along an arc ``A`` the
signed distance to a line is extreme where ``A``'s tangent is parallel to
``B`` (``c_A +- R_A n``), ``rho`` is extreme on the line of centres, and the
distance to an end point ``E`` is largest opposite ``E``
(``c_A - R_A (E - c_A)/|E - c_A|``). Every candidate that lies on ``A`` is
evaluated with the exact point kernels; boundaries are taken as whole lines
(extra candidates are harmless: each is a genuine point of ``A``). The
result is exact up to rounding, with the maximising point and its fraction
along ``A`` (0..1 of the length).
"""
from __future__ import annotations

import numpy as np

from ccopt.geometry import KIND_LINE
from ccopt.geometry.angles import TWO_PI, angle_along, angle_in_sweep
from ccopt.geometry.distance import SegmentRows, point_arc, point_segment


def _unit(v):
    n = np.hypot(v[:, 0], v[:, 1])
    return v / np.where(n > 0.0, n, 1.0)[:, None], n > 0.0


def _on_line_segment(a0, a1, X, v):
    """Crossing of segment ``a0 a1`` with the line ``X + s v``: ``(point, t, valid)``."""
    r = a1 - a0
    den = r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0]
    w = X - a0
    num = w[:, 0] * v[:, 1] - w[:, 1] * v[:, 0]
    ok = np.abs(den) > 0.0
    t = num / np.where(ok, den, 1.0)
    ok &= (t >= 0.0) & (t <= 1.0)
    t = np.clip(t, 0.0, 1.0)
    return a0 + t[:, None] * r, t, ok


def _on_circle(c, R, X, v):
    """The two crossings of circle ``(c, R)`` with the line ``X + s v``: list of ``(point, valid)``."""
    w = X - c
    vv = np.einsum("ij,ij->i", v, v)
    b = np.einsum("ij,ij->i", v, w)
    cc = np.einsum("ij,ij->i", w, w) - R * R
    disc = b * b - vv * cc
    ok = (disc >= 0.0) & (vv > 0.0)
    sq = np.sqrt(np.where(ok, disc, 0.0))
    den = np.where(vv > 0.0, vv, 1.0)
    out = []
    for sg in (1.0, -1.0):
        s = (-b + sg * sq) / den
        out.append((X + s[:, None] * v, ok))
    return out


def _fraction_line(a0, a1, q):
    r = a1 - a0
    rr = np.einsum("ij,ij->i", r, r)
    t = np.einsum("ij,ij->i", q - a0, r) / np.where(rr > 0.0, rr, 1.0)
    return np.clip(t, 0.0, 1.0)


def _fraction_arc(c, th0, sw, q):
    ang = np.arctan2(q[:, 1] - c[:, 1], q[:, 0] - c[:, 0])
    along = angle_along(ang, th0, sw)
    full = np.abs(sw)
    along = np.where(along > full, np.where(along - full < TWO_PI - along, full, 0.0), along)
    return np.clip(along / np.where(full > 0.0, full, 1.0), 0.0, 1.0)


class _Farthest:
    """Running maximum over candidate points ``q`` of the ``A`` rows of the
    exact distance from ``q`` to the ``B`` rows: ``d`` and the point ``q``."""

    def __init__(self, b: SegmentRows):
        self.b = b
        n = b.line.size
        self.d = np.full(n, -np.inf)
        self.q = np.zeros((n, 2))

    def distance(self, q: np.ndarray) -> np.ndarray:
        b = self.b
        d = np.empty(b.line.size)
        if b.line.any():
            d[b.line] = point_segment(q[b.line], b.p0[b.line], b.p1[b.line])[0]
        if (~b.line).any():
            m = ~b.line
            d[m] = point_arc(q[m], b.c[m], b.R[m], b.th[m], b.sw[m])[0]
        return d

    def offer(self, q: np.ndarray, valid: np.ndarray) -> None:
        """Keep the candidates ``q`` (rows flagged ``valid``) that are farther."""
        q = np.where(np.isfinite(q), q, 0.0)
        d = self.distance(q)
        better = valid & (d > self.d)
        self.d[better] = d[better]
        self.q[better] = q[better]


def max_distance(A, ia, B, ib):
    """``(dmax, q, t)`` for rows ``A[ia]`` (lines/arcs) against ``B[ib]`` (lines/arcs).

    ``A``, ``B``: :class:`~ccopt.geometry.SegmentArray`. ``dmax``: largest
    distance from a point of the ``A`` row to the ``B`` row; ``q``: that point;
    ``t``: its fraction along the ``A`` row.
    """
    a = SegmentRows.take(A, np.asarray(ia, np.intp))
    b = SegmentRows.take(B, np.asarray(ib, np.intp))
    far = _Farthest(b)
    every = np.ones(a.line.size, bool)
    far.offer(a.p0, every)
    far.offer(a.p1, every)
    tb, _ = _unit(b.p1 - b.p0)
    nb = np.c_[-tb[:, 1], tb[:, 0]]                 # normal of a line B
    _offer_boundary_crossings(far, a, b, nb)
    _offer_interior_maxima(far, a, b, nb)
    t = np.where(a.line, _fraction_line(a.p0, a.p1, far.q),
                 _fraction_arc(a.finite_center(), np.nan_to_num(a.th), np.nan_to_num(a.sw),
                               far.q))
    return far.d, far.q, t


def _offer_boundary_crossings(far: _Farthest, a: SegmentRows, b: SegmentRows, nb: np.ndarray) -> None:
    """Offer the crossings of ``A`` with the boundary lines of ``B``'s pieces:
    for a line ``B`` the normal lines at both ends; for an arc ``B`` the lines
    through the centre and each end, and the gap's bisector."""
    bounds = [(b.p0, nb, b.line), (b.p1, nb, b.line)]
    bisect = b.th + b.sw + np.copysign(1.0, b.sw) * 0.5 * (TWO_PI - np.abs(b.sw))
    for ang in (b.th, b.th + b.sw, bisect):
        v = np.c_[np.cos(ang), np.sin(ang)]
        bounds.append((b.c, v, ~b.line & np.isfinite(ang)))
    ca = a.finite_center()
    for X, v, ok in bounds:
        X = np.where(np.isfinite(X), X, 0.0)
        v = np.where(np.isfinite(v), v, 0.0)
        if (ok & a.line).any():
            q, _, valid = _on_line_segment(a.p0, a.p1, X, v)
            far.offer(q, ok & a.line & valid)
        if (ok & ~a.line).any():
            for q, valid in _on_circle(ca, np.nan_to_num(a.R), X, v):
                ang = np.arctan2(q[:, 1] - a.c[:, 1], q[:, 0] - a.c[:, 0])
                far.offer(q, ok & ~a.line & valid & angle_in_sweep(ang, a.th, a.sw))


def _offer_interior_maxima(far: _Farthest, a: SegmentRows, b: SegmentRows, nb: np.ndarray) -> None:
    """Offer the local maxima inside a piece: for a line ``A`` against an arc
    ``B`` the foot of ``B``'s centre; for an arc ``A`` the points ``c_A +- R_A u``
    where its tangent is parallel to a line ``B``, on the line of centres, and
    opposite each end point of ``B``."""
    m = a.line & ~b.line
    if m.any():
        t = _fraction_line(a.p0, a.p1, b.finite_center())
        far.offer(a.p0 + t[:, None] * (a.p1 - a.p0), m)
    if not (~a.line).any():
        return
    ca = a.finite_center()
    dirs = [(nb, b.line)]                                   # tangent parallel to line B
    u_cc, ok_cc = _unit(b.finite_center() - ca)
    dirs.append((u_cc, ~b.line & ok_cc))                    # line of centres
    for E in (b.p0, b.p1):                                  # opposite the end points
        u_e, ok_e = _unit(E - ca)
        dirs.append((u_e, ok_e))
    for u, ok in dirs:
        for sg in (1.0, -1.0):
            q = a.c + sg * a.R[:, None] * u
            ang = np.arctan2(sg * u[:, 1], sg * u[:, 0])
            far.offer(q, ok & ~a.line & angle_in_sweep(ang, a.th, a.sw))


def max_distance_to_point(A, ia, P):
    """``(dmax, q)``: largest distance from rows ``A[ia]`` (lines/arcs) to points ``P``."""
    ia = np.asarray(ia, np.intp)
    P = np.asarray(P, float).reshape(-1, 2)
    a0, a1 = A.p0[ia], A.p1[ia]
    d0 = np.hypot(*(a0 - P).T)
    d1 = np.hypot(*(a1 - P).T)
    best = np.maximum(d0, d1)
    bq = np.where((d0 >= d1)[:, None], a0, a1)
    arc = A.kind[ia] != KIND_LINE
    if arc.any():
        c, R = A.center[ia][arc], A.radius[ia][arc]
        u, ok = _unit(c - P[arc])
        # farthest point of the circle from P: c + R (c - P)/|c - P|; any point if P = c
        q = c + R[:, None] * u
        ang = np.arctan2(u[:, 1], u[:, 0])
        valid = ok & angle_in_sweep(ang, A.theta0[ia][arc], A.sweep[ia][arc])
        d = np.hypot(*(q - P[arc]).T)
        take = valid & (d > best[arc])
        idx = np.flatnonzero(arc)[take]
        best[idx] = d[take]
        bq[idx] = q[take]
    return best, bq
