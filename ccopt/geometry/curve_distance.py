"""Closed-form minimum distances between segments and arcs, vectorised.

:func:`segment_segment`, :func:`segment_arc` and :func:`arc_arc` each
evaluate every candidate pair of the complete set described in
:mod:`ccopt.geometry.distance` (end points against the other curve,
interior pairs normal to both curves, crossings) and keep the smallest.
Each returns ``(d, wa, wb)``: distances ``(N,)`` in program units and the
witnesses on the first and second curve ``(N, 2)``. Arcs are
``(c, R, theta0, sweep)`` (radians, ``sweep > 0`` counter-clockwise).
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry.columns import (
    PreparedArcs, RunningMin, blend, columns, norm, run_chunked, stack_xy,
)
from ccopt.geometry.point_distance import point_arc_cols, point_segment_cols

__all__ = ["segment_segment", "segment_arc", "arc_arc"]


# --------------------------------------------------------------------------- segment-segment


def segment_segment(a0, a1, b0, b1):
    """Distance between segments ``[a0, a1]`` and ``[b0, b1]``.

    Two segments in the plane either cross (``d = 0`` up to rounding: ``d``
    is then the gap between the crossing computed on each segment, ~1e-16)
    or are closest with an end point of one of them involved, so the four
    end-point-to-segment distances complete the set. Collinear overlaps are
    caught by those too (an end point lies on the other segment).
    Zero-length segments are points.
    """
    (a0x, a1x, b0x, b1x), (a0y, a1y, b0y, b1y), _ = columns((a0, a1, b0, b1))
    return run_chunked(_segment_segment_cols, (a0x, a0y, a1x, a1y, b0x, b0y, b1x, b1y))



def _segment_segment_cols(a0x, a0y, a1x, a1y, b0x, b0y, b1x, b1y):
    """:func:`segment_segment` on 1-D columns: segment A from ``a0`` to ``a1``, B from
    ``b0`` to ``b1``; witnesses ``a0 + tA r`` on A and ``b0 + uB s`` on B
    (``r = a1 - a0``, ``s = b1 - b0``)."""
    rx = a1x - a0x
    ry = a1y - a0y
    sx = b1x - b0x
    sy = b1y - b0y
    wx = b0x - a0x
    wy = b0y - a0y
    best, tA, uB = _nearest_end_pair(rx, ry, sx, sy, wx, wy)
    _offer_crossing(best, tA, uB, a0x, a0y, b0x, b0y, rx, ry, sx, sy, wx, wy)
    np.sqrt(best, out=best)
    return best, _points_along(a0x, a0y, rx, ry, tA), _points_along(b0x, b0y, sx, sy, uB)


def _clamp01(v):
    """Clip ``v`` to ``[0, 1]`` in place (a fraction along a segment)."""
    np.maximum(v, 0.0, out=v)
    np.minimum(v, 1.0, out=v)
    return v


def _gap2(ex, ey, k, fx, fy):
    """``|e - k f|^2`` from explicit differences (the expanded dot form cancels)."""
    gx = ex - k * fx
    gy = ey - k * fy
    gx *= gx
    gy *= gy
    gx += gy
    return gx


def _inverse_square_length(x, y):
    """``1 / (x^2 + y^2)``, and 1 for a zero-length vector: every dot product
    with it is then 0, so the clamped fraction is 0 (the segment's start)."""
    inv = x * x
    inv += y * y
    inv += inv == 0.0
    np.reciprocal(inv, out=inv)
    return inv


def _ends_onto(ex, ey, fx, fy, gx, gy, e_dot, g_dot, inv_ff):
    """The nearer of two end points ``e`` and ``e + g`` to the segment from the
    origin along ``f``: ``(squared distance, fraction along f, 0.0 for e / 1.0
    for e + g)``. ``e_dot = e . f``, ``g_dot = g . f``, ``inv_ff = 1 / |f|^2``."""
    t1 = _clamp01(e_dot * inv_ff)
    d1 = _gap2(ex, ey, t1, fx, fy)
    t2 = _clamp01((e_dot + g_dot) * inv_ff)
    d2 = _gap2(ex + gx, ey + gy, t2, fx, fy)
    on_second = (d2 < d1).astype(float)
    blend(t1, t2, on_second)                # t1 now the fraction of the nearer end
    return np.minimum(d1, d2), t1, on_second


def _nearest_end_pair(rx, ry, sx, sy, wx, wy):
    """Best of the four end-point-to-segment candidates of segments
    A = ``a0 + t r`` and B = ``b0 + u s`` (``w = b0 - a0``):
    ``(squared distance, tA, uB)``."""
    wr = wx * rx
    wr += wy * ry
    ws = wx * sx
    ws += wy * sy
    rs = rx * sx
    rs += ry * sy
    inv_rr = _inverse_square_length(rx, ry)
    inv_ss = _inverse_square_length(sx, sy)
    # End points of B onto A: b0 - a0 = w, b1 - a0 = w + s.
    dB, t_on_a, on_b1 = _ends_onto(wx, wy, rx, ry, sx, sy, wr, rs, inv_rr)
    # End points of A onto B: a0 - b0 = -w, a1 - b0 = -w + r.
    best, u_on_b, on_a1 = _ends_onto(-wx, -wy, sx, sy, rx, ry, -ws, rs, inv_ss)
    # Choose between the two groups: (t_on_a, on_b1) versus (on_a1, u_on_b).
    take_b = (dB < best).astype(float)
    np.minimum(best, dB, out=best)
    tA = on_a1
    blend(tA, t_on_a, take_b)
    uB = u_on_b
    blend(uB, on_b1, take_b)
    return best, tA, uB


def _offer_crossing(best, tA, uB, a0x, a0y, b0x, b0y, rx, ry, sx, sy, wx, wy):
    """Where A and B properly cross (each one's ends strictly on both sides of
    the other's line), offer the crossing in place of ``(best, tA, uB)``."""
    o1 = rx * wy - ry * wx                  # side of b0 w.r.t. line A
    rxs = rx * sy - ry * sx
    o2 = o1 + rxs                           # side of b1
    o3 = wx * sy - wy * sx                  # side of a0 w.r.t. line B (= cross(s, a0 - b0))
    o4 = o3 - rxs                           # side of a1
    cross = (o1 * o2 < 0.0) & (o3 * o4 < 0.0)
    ic = np.flatnonzero(cross)
    if not ic.size:
        return
    tc = o3[ic] / (o3[ic] - o4[ic])
    uc = o1[ic] / (o1[ic] - o2[ic])
    # The crossing is scored by the gap between its two computed witnesses
    # (rounding level) rather than declared 0: for nearly collinear
    # overlapping segments the side tests are rounding noise and tc, uc
    # meaningless, and then the end-point candidates (also ~0) must win.
    gx = (a0x[ic] + tc * rx[ic]) - (b0x[ic] + uc * sx[ic])
    gy = (a0y[ic] + tc * ry[ic]) - (b0y[ic] + uc * sy[ic])
    d2c = gx * gx + gy * gy
    take = d2c < best[ic]
    it = ic[take]
    best[it] = d2c[take]
    tA[it] = tc[take]
    uB[it] = uc[take]


def _points_along(x0, y0, dx, dy, f):
    """Rows ``(x0 + f dx, y0 + f dy)``, ``(N, 2)``; ``dx``, ``dy`` are overwritten."""
    dx *= f
    dx += x0
    dy *= f
    dy += y0
    return stack_xy(dx, dy)

# --------------------------------------------------------------------------- segment-arc


def _segment_arc_cols(a0x, a0y, a1x, a1y, cx, cy, R, th0, sw):
    arc = PreparedArcs(cx, cy, R, th0, sw)
    rx = a1x - a0x
    ry = a1y - a0y
    L = norm(rx, ry)
    inv_L = 1.0 / (L + (L == 0.0))
    ex = rx * inv_L
    ex += L == 0.0                          # any unit vector serves a zero-length segment
    ey = ry * inv_L
    nx, ny = -ey, ex                        # left normal of the segment
    gx = arc.cx - a0x
    gy = arc.cy - a0y
    along_c = gx * ex + gy * ey             # foot of the centre, length from a0
    h = gx * nx + gy * ny                   # signed centre offset from the line
    R = arc.R

    # End points of the segment against the arc.
    d, qx, qy = point_arc_cols(a0x, a0y, arc)
    best = RunningMin(d, a0x, a0y, qx, qy)
    d, qx, qy = point_arc_cols(a1x, a1y, arc)
    best.offer(d, a1x, a1y, qx, qy)
    # End points of the arc against the segment.
    for qx, qy in ((arc.e0x, arc.e0y), (arc.e1x, arc.e1y)):
        d, t = point_segment_cols(qx, qy, a0x, a0y, a1x, a1y)
        best.offer(d, a0x + t * rx, a0y + t * ry, qx, qy)
    # Interior-interior: circle points c +- R n, both with foot along_c.
    foot_ok = (along_c >= 0.0) & (along_c <= L)
    if foot_ok.any():
        fx = a0x + along_c * ex
        fy = a0y + along_c * ey
        psi = np.arctan2(ny, nx)
        for sgn in (1.0, -1.0):
            ok = foot_ok & arc.contains(psi if sgn > 0 else psi + math.pi)
            best.offer(np.abs(h + sgn * R), fx, fy, arc.cx + sgn * R * nx, arc.cy + sgn * R * ny, ok)
    # Crossings of the segment with the arc: c + (+-w) e - h n, w the half chord.
    w2 = (R - h) * (R + h)
    meets = w2 >= 0.0
    if meets.any():
        w = np.sqrt(np.maximum(w2, 0.0))
        zero = np.zeros_like(w)
        for sgn in (1.0, -1.0):
            along = along_c + sgn * w
            vx = sgn * w * ex - h * nx
            vy = sgn * w * ey - h * ny
            ok = meets & (along >= 0.0) & (along <= L) & arc.contains(np.arctan2(vy, vx))
            best.offer(zero, a0x + along * ex, a0y + along * ey, arc.cx + vx, arc.cy + vy, ok)
    return best.result()


def segment_arc(a0, a1, c, R, theta0, sweep):
    """Distance between segment ``[a0, a1]`` and arc ``(c, R, theta0, sweep)``.

    Witnesses: ``wa`` on the segment, ``wb`` on the arc. Candidates: crossings
    (``d = 0``), the circle points ``c +- R n`` whose perpendicular foot is on
    the segment and whose angle is on the arc (``d = |h +- R|``, ``h`` the
    signed distance of ``c`` from the line), and the four end-point-to-curve
    distances.
    """
    (a0x, a1x, cx), (a0y, a1y, cy), (R, th0, sw) = columns((a0, a1, c), (R, theta0, sweep))
    return run_chunked(_segment_arc_cols, (a0x, a0y, a1x, a1y, cx, cy, R, th0, sw))



# --------------------------------------------------------------------------- arc-arc


def _arc_arc_cols(c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2):
    A = PreparedArcs(c1x, c1y, R1, th1, sw1)
    B = PreparedArcs(c2x, c2y, R2, th2, sw2)
    # End points of each arc against the other arc (this also covers concentric arcs).
    d, qx, qy = point_arc_cols(A.e0x, A.e0y, B)
    best = RunningMin(d, A.e0x, A.e0y, qx, qy)
    d, qx, qy = point_arc_cols(A.e1x, A.e1y, B)
    best.offer(d, A.e1x, A.e1y, qx, qy)
    d, qx, qy = point_arc_cols(B.e0x, B.e0y, A)
    best.offer(d, qx, qy, B.e0x, B.e0y)
    d, qx, qy = point_arc_cols(B.e1x, B.e1y, A)
    best.offer(d, qx, qy, B.e1x, B.e1y)

    gx = B.cx - A.cx
    gy = B.cy - A.cy
    D = norm(gx, gy)
    apart = D > 0.0
    if not apart.any():
        return best.result()
    inv_D = 1.0 / (D + ~apart)
    ux = gx * inv_D                         # unit vector c1 -> c2 (0 when concentric)
    uy = gy * inv_D
    psi = np.arctan2(uy, ux)
    psi_back = psi + math.pi
    R1, R2 = A.R, B.R
    # Interior pairs on the line of centres: p = c1 + s1 R1 u, q = c2 + s2 R2 u.
    on1 = {1.0: A.contains(psi), -1.0: A.contains(psi_back)}
    on2 = {1.0: B.contains(psi), -1.0: B.contains(psi_back)}
    for s1 in (1.0, -1.0):
        px = A.cx + s1 * R1 * ux
        py = A.cy + s1 * R1 * uy
        for s2 in (1.0, -1.0):
            ok = apart & on1[s1] & on2[s2]
            if ok.any():
                best.offer(np.abs(D + s2 * R2 - s1 * R1), px, py,
                           B.cx + s2 * R2 * ux, B.cy + s2 * R2 * uy, ok)
    # Crossings: c1 + a u +- h u_perp with a = (D^2 + R1^2 - R2^2) / (2D).
    a = (D * D + R1 * R1 - R2 * R2) * (0.5 * inv_D)
    h2 = (R1 - a) * (R1 + a)
    meets = apart & (h2 >= 0.0)
    if meets.any():
        h = np.sqrt(np.maximum(h2, 0.0))
        zero = np.zeros_like(h)
        for sgn in (1.0, -1.0):
            vx = a * ux - sgn * h * uy       # crossing relative to c1
            vy = a * uy + sgn * h * ux
            px = A.cx + vx
            py = A.cy + vy
            ok = meets & A.contains(np.arctan2(vy, vx)) & B.contains(np.arctan2(py - B.cy, px - B.cx))
            best.offer(zero, px, py, px, py, ok)
    return best.result()


def arc_arc(c1, R1, th1, sw1, c2, R2, th2, sw2):
    """Distance between arcs ``(c1, R1, th1, sw1)`` and ``(c2, R2, th2, sw2)``.

    Witnesses: ``wa`` on the first arc, ``wb`` on the second. Candidates:
    crossings (``d = 0``), the four line-of-centres pairs
    ``c1 +- R1 u``, ``c2 +- R2 u`` (``u`` the unit vector from ``c1`` to
    ``c2``) that lie on both arcs, and the four end-point-to-arc distances.
    """
    (c1x, c2x), (c1y, c2y), (R1, th1, sw1, R2, th2, sw2) = columns(
        (c1, c2), (R1, th1, sw1, R2, th2, sw2))
    return run_chunked(_arc_arc_cols, (c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2))
