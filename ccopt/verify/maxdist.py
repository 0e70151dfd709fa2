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

from ccopt.geometry.angles import TWO_PI, angle_along, angle_in_sweep
from ccopt.geometry.distance import point_arc, point_segment


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


def max_distance(A, ia, B, ib):
    """``(dmax, q, t)`` for rows ``A[ia]`` (lines/arcs) against ``B[ib]`` (lines/arcs).

    ``A``, ``B``: :class:`~ccopt.geometry.SegmentArray`. ``dmax``: largest
    distance from a point of the ``A`` row to the ``B`` row; ``q``: that point;
    ``t``: its fraction along the ``A`` row.
    """
    ia = np.asarray(ia, np.intp)
    ib = np.asarray(ib, np.intp)
    n = ia.size
    a_line = A.kind[ia] == 0
    b_line = B.kind[ib] == 0
    a0, a1 = A.p0[ia], A.p1[ia]
    ca, Ra, tha, swa = A.center[ia], A.radius[ia], A.theta0[ia], A.sweep[ia]
    b0, b1 = B.p0[ib], B.p1[ib]
    cb, Rb, thb, swb = B.center[ib], B.radius[ib], B.theta0[ib], B.sweep[ib]

    def f(q):
        d = np.empty(n)
        if b_line.any():
            d[b_line] = point_segment(q[b_line], b0[b_line], b1[b_line])[0]
        if (~b_line).any():
            m = ~b_line
            d[m] = point_arc(q[m], cb[m], Rb[m], thb[m], swb[m])[0]
        return d

    best = np.full(n, -np.inf)
    bq = np.zeros((n, 2))

    def offer(q, valid):
        q = np.where(np.isfinite(q), q, 0.0)
        d = f(q)
        better = valid & (d > best)
        best[better] = d[better]
        bq[better] = q[better]

    true = np.ones(n, bool)
    offer(a0, true)
    offer(a1, true)

    # Boundary lines of B's pieces, as (point X, direction v, valid).
    bounds = []
    tb, _ = _unit(b1 - b0)
    nb = np.c_[-tb[:, 1], tb[:, 0]]
    # line B: normal lines at both ends
    bounds.append((b0, nb, b_line))
    bounds.append((b1, nb, b_line))
    # arc B: lines through the centre and each end, and the gap bisector
    bisect = thb + swb + np.copysign(1.0, swb) * 0.5 * (TWO_PI - np.abs(swb))
    for ang in (thb, thb + swb, bisect):
        v = np.c_[np.cos(ang), np.sin(ang)]
        bounds.append((cb, v, ~b_line & np.isfinite(ang)))
    for X, v, ok in bounds:
        X = np.where(np.isfinite(X), X, 0.0)
        v = np.where(np.isfinite(v), v, 0.0)
        if (ok & a_line).any():
            q, _, valid = _on_line_segment(a0, a1, X, v)
            offer(q, ok & a_line & valid)
        if (ok & ~a_line).any():
            for q, valid in _on_circle(np.where(np.isfinite(ca), ca, 0.0), np.nan_to_num(Ra), X, v):
                ang = np.arctan2(q[:, 1] - ca[:, 1], q[:, 0] - ca[:, 0])
                offer(q, ok & ~a_line & valid & angle_in_sweep(ang, tha, swa))

    # Interior local maxima.
    # line A vs arc B: foot of c_B on A
    m = a_line & ~b_line
    if m.any():
        t = _fraction_line(a0, a1, np.where(np.isfinite(cb), cb, 0.0))
        offer(a0 + t[:, None] * (a1 - a0), m)
    # arc A: points c_A +- R_A u for directions u
    if (~a_line).any():
        dirs = [(nb, b_line)]                                   # tangent parallel to line B
        u_cc, ok_cc = _unit(np.where(np.isfinite(cb), cb, 0.0) - np.where(np.isfinite(ca), ca, 0.0))
        dirs.append((u_cc, ~b_line & ok_cc))                    # line of centres
        for E in (b0, b1):                                      # opposite the end points
            u_e, ok_e = _unit(E - np.where(np.isfinite(ca), ca, 0.0))
            dirs.append((u_e, true & ok_e))
        for u, ok in dirs:
            for sg in (1.0, -1.0):
                q = ca + sg * Ra[:, None] * u
                ang = np.arctan2(sg * u[:, 1], sg * u[:, 0])
                offer(q, ok & ~a_line & angle_in_sweep(ang, tha, swa))

    t = np.where(a_line, _fraction_line(a0, a1, bq),
                 _fraction_arc(np.where(np.isfinite(ca), ca, 0.0), np.nan_to_num(tha),
                               np.nan_to_num(swa), bq))
    return best, bq, t


def max_distance_to_point(A, ia, P):
    """``(dmax, q)``: largest distance from rows ``A[ia]`` (lines/arcs) to points ``P``."""
    ia = np.asarray(ia, np.intp)
    P = np.asarray(P, float).reshape(-1, 2)
    a0, a1 = A.p0[ia], A.p1[ia]
    d0 = np.hypot(*(a0 - P).T)
    d1 = np.hypot(*(a1 - P).T)
    best = np.maximum(d0, d1)
    bq = np.where((d0 >= d1)[:, None], a0, a1)
    arc = A.kind[ia] != 0
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
