"""Closed-form minimum distances between points, segments and arcs.

Every kernel is vectorised over ``N`` pairs (no Python loop over pairs) and
returns ``(d, wa, wb)``: the minimum distance ``d`` (shape ``(N,)``, program
units) and witness points ``wa`` on the first object and ``wb`` on the second
(shape ``(N, 2)``) with ``|wa - wb| = d`` up to rounding. Inputs are points of
shape ``(N, 2)`` (or ``(2,)``, broadcast) and scalars of shape ``(N,)`` (or
``()``). Arcs are ``(c, R, theta0, sweep)``: centre, radius ``> 0``, start
polar angle and signed sweep (radians, ``> 0`` counter-clockwise,
``|sweep| >= 2*pi`` is the whole circle).

Why the candidate sets are complete: the squared distance between a point
on one compact curve and a point on the other is smooth, so its minimum is
either at an end point of one curve (then it is a point-to-curve distance,
solved exactly), or at a pair interior to both where the joining vector is
normal to both curves, or at a common point (``d = 0``). Normal to a line and
radial for a circle means the circle point is ``c +- R n`` (``n`` the line's
unit normal); radial for two circles means both points lie on the line of
centres (four sign choices; concentric arcs have no such pairs, and their
minimum is at an end point). Each kernel evaluates every candidate that is
actually on both curves and keeps the smallest, so ``d`` is always a
distance between two genuine curve points (an upper bound that is exact up
to rounding).

For many primitives at once, :class:`SegmentArray` packs lines, arcs and
spirals into flat arrays and :func:`pair_distance` evaluates arbitrary index
pairs with one masked call per kind combination. Spirals have no closed
form here; their distances are bounded elsewhere (``ccopt.verify``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry.angles import in_sweep_prepared
from ccopt.geometry.primitives import Arc, Line, Spiral

__all__ = [
    "point_point", "point_segment", "point_arc", "segment_segment", "segment_arc",
    "arc_arc", "distance", "SegmentArray", "pair_distance",
    "KIND_LINE", "KIND_ARC", "KIND_SPIRAL",
]


# --------------------------------------------------------------------------- input handling


def _columns(points, scalars=()):
    """Broadcast points (``(..., 2)``) and scalars to 1-D columns of one length.

    Returns ``(xs, ys, ss)``: lists of 1-D float arrays (x and y of each point,
    then each scalar), all of length ``N``.
    """
    pts = [np.asarray(p, dtype=float) for p in points]
    for p in pts:
        if p.shape[-1:] != (2,):
            raise ValueError(f"points must have a trailing axis of length 2, got shape {p.shape}")
    cols = [p[..., 0] for p in pts] + [p[..., 1] for p in pts]
    cols += [np.asarray(s, dtype=float) for s in scalars]
    shapes = {c.shape for c in cols}
    if len(shapes) != 1 or cols[0].ndim != 1:
        cols = np.broadcast_arrays(*cols)
        cols = [np.ravel(c) if c.ndim else c.reshape(1) for c in cols]
    k = len(pts)
    return cols[:k], cols[k:2 * k], cols[2 * k:]


#: Pairs per block: temporaries of this many doubles (64 KiB) stay in cache and
#: in the allocator's pool instead of being page-faulted in for every call.
CHUNK = 8192


def _run_chunked(kernel, cols):
    """Apply ``kernel(*cols) -> (d, wa, wb)`` block by block over 1-D columns."""
    n = cols[0].shape[0]
    if n <= CHUNK:
        return kernel(*cols)
    d = np.empty(n)
    wa = np.empty((n, 2))
    wb = np.empty((n, 2))
    for i in range(0, n, CHUNK):
        sl = slice(i, i + CHUNK)
        d[sl], wa[sl], wb[sl] = kernel(*(c[sl] for c in cols))
    return d, wa, wb


def _stack(x, y):
    out = np.empty((x.shape[0], 2))
    out[:, 0] = x
    out[:, 1] = y
    return out


def _norm(x, y):
    # sqrt(x^2 + y^2) is several times faster than np.hypot on large arrays;
    # over/underflow would need coordinates beyond 1e150, far outside any machine.
    return np.sqrt(x * x + y * y)


def _blend(dst, src, take):
    """``dst[take] = src[take]`` branch-free: ``take`` is a 0/1 float array.

    Random masks make ``np.where``/``np.copyto(where=)`` mispredict on every
    element; this is a subtract, multiply and add. The result can differ from
    ``src`` by one rounding (``x + (y - x)``), far below any tolerance here.
    ``src`` must be finite where ``take`` is 0.
    """
    tmp = np.subtract(src, dst)
    tmp *= take
    dst += tmp


class _Best:
    """Running minimum over candidate pairs, with their witness coordinates.

    Candidates that are not on both curves are offered with ``valid=False``
    and never win; every offered distance and witness must be finite.
    """

    __slots__ = ("d", "ax", "ay", "bx", "by")

    def __init__(self, d, ax, ay, bx, by):
        n = d.shape[0]
        self.d = np.array(d, dtype=float)
        self.ax = np.array(np.broadcast_to(ax, (n,)), dtype=float)
        self.ay = np.array(np.broadcast_to(ay, (n,)), dtype=float)
        self.bx = np.array(np.broadcast_to(bx, (n,)), dtype=float)
        self.by = np.array(np.broadcast_to(by, (n,)), dtype=float)

    def offer(self, d, ax, ay, bx, by, valid=None):
        better = d < self.d
        if valid is not None:
            better &= valid
        if not better.any():
            return
        take = better.astype(float)
        _blend(self.d, d, take)
        _blend(self.ax, ax, take)
        _blend(self.ay, ay, take)
        _blend(self.bx, bx, take)
        _blend(self.by, by, take)

    def result(self):
        return self.d, _stack(self.ax, self.ay), _stack(self.bx, self.by)


class _Arcs:
    """Per-arc quantities every kernel needs, computed once per call."""

    __slots__ = ("cx", "cy", "R", "th0", "sign", "abs_sweep", "e0x", "e0y", "e1x", "e1y")

    def __init__(self, cx, cy, R, th0, sw):
        self.cx, self.cy, self.R, self.th0 = cx, cy, R, th0
        self.sign = np.copysign(1.0, sw)
        self.abs_sweep = np.abs(sw)
        th1 = th0 + sw
        self.e0x = cx + R * np.cos(th0)
        self.e0y = cy + R * np.sin(th0)
        self.e1x = cx + R * np.cos(th1)
        self.e1y = cy + R * np.sin(th1)

    def contains(self, phi):
        """Is polar angle ``phi`` on the arc (see :func:`angle_in_sweep`)."""
        return in_sweep_prepared(phi, self.th0, self.sign, self.abs_sweep)


# --------------------------------------------------------------------------- point kernels


def point_point(p, q):
    """Distance between points ``p`` and ``q``; the witnesses are the points."""
    (px, qx), (py, qy), _ = _columns((p, q))
    d = _norm(px - qx, py - qy)
    return d, _stack(px, py), _stack(qx, qy)


def _point_segment_cols(px, py, ax, ay, bx, by):
    """``(d, t)``: distance from p to segment ab and the foot's fraction t in [0, 1]."""
    rx = bx - ax
    ry = by - ay
    rr = rx * rx + ry * ry
    rr += rr == 0.0          # zero-length segment: w.r = 0, so t = 0 (its start point)
    wx = px - ax
    wy = py - ay
    t = wx * rx
    t += wy * ry
    t /= rr
    np.clip(t, 0.0, 1.0, out=t)
    wx -= t * rx
    wy -= t * ry
    return _norm(wx, wy), t


def point_segment(p, a, b):
    """Distance from point ``p`` to segment ``[a, b]``.

    Witnesses: ``p`` itself and the nearest segment point (the foot of the
    perpendicular, clamped to the segment). A zero-length segment is a point.
    """
    (px, ax, bx), (py, ay, by), _ = _columns((p, a, b))
    return _run_chunked(_point_segment_witness_cols, (px, py, ax, ay, bx, by))


def _point_segment_witness_cols(px, py, ax, ay, bx, by):
    d, t = _point_segment_cols(px, py, ax, ay, bx, by)
    return d, _stack(px, py), _stack(ax + t * (bx - ax), ay + t * (by - ay))


def _point_arc_cols(px, py, arc: _Arcs):
    """``(d, qx, qy)``: distance from p to the arc and the nearest arc point."""
    vx = px - arc.cx
    vy = py - arc.cy
    rho = _norm(vx, vy)
    # Radial projection is the answer when p's angle is on the arc; at the
    # centre every arc point is at distance R and the end points say so.
    radial = arc.contains(np.arctan2(vy, vx)) & (rho > 0.0)
    fx = px - arc.e0x
    fy = py - arc.e0y
    d0 = fx * fx + fy * fy
    fx = px - arc.e1x
    fy = py - arc.e1y
    d1 = fx * fx + fy * fy
    to_end = (d1 < d0).astype(float)
    d = np.minimum(d0, d1)
    np.sqrt(d, out=d)
    qx = arc.e0x.copy()
    qy = arc.e0y.copy()
    _blend(qx, arc.e1x, to_end)
    _blend(qy, arc.e1y, to_end)
    if radial.any():
        take = radial.astype(float)
        scale = arc.R / (rho + (rho == 0.0))
        _blend(d, np.abs(rho - arc.R), take)
        vx *= scale
        vy *= scale
        vx += arc.cx
        vy += arc.cy
        _blend(qx, vx, take)
        _blend(qy, vy, take)
    return d, qx, qy


def point_arc(p, c, R, theta0, sweep):
    """Distance from point ``p`` to the arc ``(c, R, theta0, sweep)``.

    ``|rho - R|`` (``rho = |p - c|``) with the radial projection as witness
    when ``p``'s polar angle lies inside the sweep; otherwise the nearer end
    point. A point at the centre is at distance ``R`` (witness: an end point).
    Witnesses: ``p`` and the arc point.
    """
    (px, cx), (py, cy), (R, th0, sw) = _columns((p, c), (R, theta0, sweep))
    return _run_chunked(_point_arc_witness_cols, (px, py, cx, cy, R, th0, sw))


def _point_arc_witness_cols(px, py, cx, cy, R, th0, sw):
    d, qx, qy = _point_arc_cols(px, py, _Arcs(cx, cy, R, th0, sw))
    return d, _stack(px, py), _stack(qx, qy)


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
    (a0x, a1x, b0x, b1x), (a0y, a1y, b0y, b1y), _ = _columns((a0, a1, b0, b1))
    return _run_chunked(_segment_segment_cols, (a0x, a0y, a1x, a1y, b0x, b0y, b1x, b1y))


def _segment_segment_cols(a0x, a0y, a1x, a1y, b0x, b0y, b1x, b1y):
    rx = a1x - a0x
    ry = a1y - a0y
    sx = b1x - b0x
    sy = b1y - b0y
    wx = b0x - a0x
    wy = b0y - a0y
    wr = wx * rx
    wr += wy * ry
    ws = wx * sx
    ws += wy * sy
    rs = rx * sx
    rs += ry * sy
    inv_rr = rx * rx
    inv_rr += ry * ry
    inv_rr += inv_rr == 0.0     # zero-length: every dot with it is 0, so t = 0
    np.reciprocal(inv_rr, out=inv_rr)
    inv_ss = sx * sx
    inv_ss += sy * sy
    inv_ss += inv_ss == 0.0
    np.reciprocal(inv_ss, out=inv_ss)

    def clamp01(v):
        np.maximum(v, 0.0, out=v)
        np.minimum(v, 1.0, out=v)
        return v

    def gap2(ex, ey, k, fx, fy):
        """|e - k f|^2 from explicit differences (the expanded dot form cancels)."""
        gx = ex - k * fx
        gy = ey - k * fy
        gx *= gx
        gy *= gy
        gx += gy
        return gx

    # Witnesses are a0 + tA r on A and b0 + uB s on B.
    # End points of B onto A: b0 - a0 = w, b1 - a0 = w + s.
    t1 = clamp01(wr * inv_rr)
    d1 = gap2(wx, wy, t1, rx, ry)
    t2 = clamp01((wr + rs) * inv_rr)
    d2 = gap2(wx + sx, wy + sy, t2, rx, ry)
    on_b1 = (d2 < d1).astype(float)
    dB = np.minimum(d1, d2)
    _blend(t1, t2, on_b1)                   # t1 now the A fraction of the better B end
    # End points of A onto B: a0 - b0 = -w, a1 - b0 = r - w.
    u3 = clamp01(ws * -inv_ss)
    d3 = gap2(wx, wy, -u3, sx, sy)          # |-w - u s| = |w + u s|
    u4 = clamp01((rs - ws) * inv_ss)
    d4 = gap2(rx - wx, ry - wy, u4, sx, sy)
    on_a1 = (d4 < d3).astype(float)
    best = np.minimum(d3, d4)
    _blend(u3, u4, on_a1)                   # u3 now the B fraction of the better A end
    # Choose between the two groups: (t1, on_b1) versus (on_a1, u3).
    take_b = (dB < best).astype(float)
    np.minimum(best, dB, out=best)
    tA = on_a1
    _blend(tA, t1, take_b)
    uB = u3
    _blend(uB, on_b1, take_b)
    # Proper crossing: each segment's ends strictly on both sides of the other's line.
    o1 = rx * wy - ry * wx                  # side of b0 w.r.t. line A
    rxs = rx * sy - ry * sx
    o2 = o1 + rxs                           # side of b1
    o3 = wx * sy - wy * sx                  # side of a0 w.r.t. line B (= cross(s, a0 - b0))
    o4 = o3 - rxs                           # side of a1
    cross = (o1 * o2 < 0.0) & (o3 * o4 < 0.0)
    ic = np.flatnonzero(cross)
    if ic.size:
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
    np.sqrt(best, out=best)
    n = best.shape[0]
    wa = np.empty((n, 2))
    wb = np.empty((n, 2))
    rx *= tA
    rx += a0x
    ry *= tA
    ry += a0y
    wa[:, 0] = rx
    wa[:, 1] = ry
    sx *= uB
    sx += b0x
    sy *= uB
    sy += b0y
    wb[:, 0] = sx
    wb[:, 1] = sy
    return best, wa, wb


# --------------------------------------------------------------------------- segment-arc


def _segment_arc_cols(a0x, a0y, a1x, a1y, cx, cy, R, th0, sw):
    arc = _Arcs(cx, cy, R, th0, sw)
    rx = a1x - a0x
    ry = a1y - a0y
    L = _norm(rx, ry)
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
    d, qx, qy = _point_arc_cols(a0x, a0y, arc)
    best = _Best(d, a0x, a0y, qx, qy)
    d, qx, qy = _point_arc_cols(a1x, a1y, arc)
    best.offer(d, a1x, a1y, qx, qy)
    # End points of the arc against the segment.
    for qx, qy in ((arc.e0x, arc.e0y), (arc.e1x, arc.e1y)):
        d, t = _point_segment_cols(qx, qy, a0x, a0y, a1x, a1y)
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
    (a0x, a1x, cx), (a0y, a1y, cy), (R, th0, sw) = _columns((a0, a1, c), (R, theta0, sweep))
    return _run_chunked(_segment_arc_cols, (a0x, a0y, a1x, a1y, cx, cy, R, th0, sw))


# --------------------------------------------------------------------------- arc-arc


def _arc_arc_cols(c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2):
    A = _Arcs(c1x, c1y, R1, th1, sw1)
    B = _Arcs(c2x, c2y, R2, th2, sw2)
    # End points of each arc against the other arc (this also covers concentric arcs).
    d, qx, qy = _point_arc_cols(A.e0x, A.e0y, B)
    best = _Best(d, A.e0x, A.e0y, qx, qy)
    d, qx, qy = _point_arc_cols(A.e1x, A.e1y, B)
    best.offer(d, A.e1x, A.e1y, qx, qy)
    d, qx, qy = _point_arc_cols(B.e0x, B.e0y, A)
    best.offer(d, qx, qy, B.e0x, B.e0y)
    d, qx, qy = _point_arc_cols(B.e1x, B.e1y, A)
    best.offer(d, qx, qy, B.e1x, B.e1y)

    gx = B.cx - A.cx
    gy = B.cy - A.cy
    D = _norm(gx, gy)
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
    (c1x, c2x), (c1y, c2y), (R1, th1, sw1, R2, th2, sw2) = _columns(
        (c1, c2), (R1, th1, sw1, R2, th2, sw2))
    return _run_chunked(_arc_arc_cols, (c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2))


# --------------------------------------------------------------------------- objects


def _is_point(obj) -> bool:
    if isinstance(obj, (Line, Arc, Spiral)):
        return False
    return np.shape(obj) == (2,)


def distance(a, b):
    """Minimum distance between two primitives: ``(d, wa, wb)`` as floats/tuples.

    ``a`` and ``b`` are :class:`Line`, :class:`Arc` or points (a pair of
    floats). ``wa`` is the witness on ``a``, ``wb`` on ``b``. Spirals have no
    closed form and raise ``ValueError``.
    """
    for obj in (a, b):
        if isinstance(obj, Spiral):
            raise ValueError("distance(): spirals are not in the closed-form set; "
                             "bound them with ccopt.verify")
        if not (isinstance(obj, (Line, Arc)) or _is_point(obj)):
            raise TypeError(f"distance() takes Line, Arc or (x, y) points, not {type(obj).__name__}")
    swap = False
    order = {Line: 1, Arc: 2}
    rank_a = 0 if _is_point(a) else order[type(a)]
    rank_b = 0 if _is_point(b) else order[type(b)]
    if rank_a > rank_b:
        a, b, swap = b, a, True
        rank_a, rank_b = rank_b, rank_a
    if rank_a == 0:
        if rank_b == 0:
            d, wa, wb = point_point(a, b)
        elif rank_b == 1:
            d, wa, wb = point_segment(a, b.p0, b.p1)
        else:
            d, wa, wb = point_arc(a, b.center, b.radius, b.theta0, b.sweep)
    elif rank_a == 1:
        if rank_b == 1:
            d, wa, wb = segment_segment(a.p0, a.p1, b.p0, b.p1)
        else:
            d, wa, wb = segment_arc(a.p0, a.p1, b.center, b.radius, b.theta0, b.sweep)
    else:
        d, wa, wb = arc_arc(a.center, a.radius, a.theta0, a.sweep,
                            b.center, b.radius, b.theta0, b.sweep)
    wa_t = (float(wa[0, 0]), float(wa[0, 1]))
    wb_t = (float(wb[0, 0]), float(wb[0, 1]))
    if swap:
        wa_t, wb_t = wb_t, wa_t
    return float(d[0]), wa_t, wb_t


# --------------------------------------------------------------------------- packed segments

KIND_LINE = 0
KIND_ARC = 1
KIND_SPIRAL = 2


@dataclass(frozen=True, eq=False)
class SegmentArray:
    """Many primitives packed into flat, read-only arrays (one row each).

    Attributes
    ----------
    kind: ``int8`` codes, :data:`KIND_LINE`, :data:`KIND_ARC` or :data:`KIND_SPIRAL`.
    p0, p1: ``(N, 2)`` start and end points (all kinds).
    center: ``(N, 2)`` centre (NaN for lines).
    radius: ``(N,)`` arc radius, or a spiral's start radius ``rho0`` (NaN for lines).
    radius_end: ``(N,)`` end radius (equal to ``radius`` for arcs, ``rho1`` for spirals).
    theta0, sweep: ``(N,)`` start polar angle and signed sweep, radians (NaN for lines).
    """

    kind: np.ndarray
    p0: np.ndarray
    p1: np.ndarray
    center: np.ndarray
    radius: np.ndarray
    radius_end: np.ndarray
    theta0: np.ndarray
    sweep: np.ndarray

    @classmethod
    def from_segments(cls, segments) -> "SegmentArray":
        segs = list(segments)
        n = len(segs)
        kind = np.empty(n, dtype=np.int8)
        p0 = np.empty((n, 2))
        p1 = np.empty((n, 2))
        center = np.full((n, 2), np.nan)
        radius = np.full(n, np.nan)
        radius_end = np.full(n, np.nan)
        theta0 = np.full(n, np.nan)
        sweep = np.full(n, np.nan)
        for i, g in enumerate(segs):
            p0[i] = g.start
            p1[i] = g.end
            if isinstance(g, Line):
                kind[i] = KIND_LINE
                continue
            if isinstance(g, Arc):
                kind[i] = KIND_ARC
                radius[i] = radius_end[i] = g.radius
            elif isinstance(g, Spiral):
                kind[i] = KIND_SPIRAL
                radius[i] = g.rho0
                radius_end[i] = g.rho1
            else:
                raise TypeError(f"SegmentArray holds Line, Arc and Spiral, not {type(g).__name__}")
            center[i] = g.center
            theta0[i] = g.theta0
            sweep[i] = g.sweep
        for arr in (kind, p0, p1, center, radius, radius_end, theta0, sweep):
            arr.flags.writeable = False
        return cls(kind, p0, p1, center, radius, radius_end, theta0, sweep)

    def __len__(self) -> int:
        return int(self.kind.shape[0])

    def segment(self, i: int):
        """Row ``i`` as a primitive object again."""
        k = int(self.kind[i])
        if k == KIND_LINE:
            return Line(tuple(self.p0[i]), tuple(self.p1[i]))
        if k == KIND_ARC:
            return Arc(tuple(self.center[i]), self.radius[i], self.theta0[i], self.sweep[i])
        return Spiral(tuple(self.center[i]), self.radius[i], self.radius_end[i],
                      self.theta0[i], self.sweep[i])


def pair_distance(A: SegmentArray, idx_a, B: SegmentArray, idx_b):
    """Distances between rows ``A[idx_a[k]]`` and ``B[idx_b[k]]`` for every ``k``.

    Returns ``(d, wa, wb)`` of shapes ``(N,)``, ``(N, 2)``, ``(N, 2)`` (``wa``
    on the ``A`` row, ``wb`` on the ``B`` row). Dispatches each kind
    combination (line-line, line-arc, arc-line, arc-arc) with a boolean mask
    to the vectorised kernel. ``ValueError`` if any referenced row is a spiral.
    """
    ia = np.asarray(idx_a, dtype=np.intp).ravel()
    ib = np.asarray(idx_b, dtype=np.intp).ravel()
    if ia.shape != ib.shape:
        raise ValueError(f"idx_a and idx_b differ in length ({ia.size} vs {ib.size})")
    ka = A.kind[ia]
    kb = B.kind[ib]
    spiral = (ka == KIND_SPIRAL) | (kb == KIND_SPIRAL)
    if spiral.any():
        k = int(np.argmax(spiral))
        raise ValueError(
            f"pair_distance: {int(spiral.sum())} pair(s) involve a spiral (first: pair {k}, "
            f"A row {int(ia[k])}, B row {int(ib[k])}); spirals have no closed-form distance")
    n = ia.size
    if n == 0:
        return np.empty(0), np.empty((0, 2)), np.empty((0, 2))
    d = np.empty(n)
    wa = np.empty((n, 2))
    wb = np.empty((n, 2))
    a_line = ka == KIND_LINE
    b_line = kb == KIND_LINE
    for mask, case in ((a_line & b_line, "ll"), (a_line & ~b_line, "la"),
                       (~a_line & b_line, "al"), (~a_line & ~b_line, "aa")):
        if mask.all():
            sel = slice(None)
            ja, jb = ia, ib
        else:
            sel = np.nonzero(mask)[0]
            if sel.size == 0:
                continue
            ja, jb = ia[sel], ib[sel]
        if case == "ll":
            r = segment_segment(A.p0[ja], A.p1[ja], B.p0[jb], B.p1[jb])
        elif case == "la":
            r = segment_arc(A.p0[ja], A.p1[ja], B.center[jb], B.radius[jb],
                            B.theta0[jb], B.sweep[jb])
        elif case == "al":
            dd, w_line, w_arc = segment_arc(B.p0[jb], B.p1[jb], A.center[ja], A.radius[ja],
                                            A.theta0[ja], A.sweep[ja])
            r = (dd, w_arc, w_line)
        else:
            r = arc_arc(A.center[ja], A.radius[ja], A.theta0[ja], A.sweep[ja],
                        B.center[jb], B.radius[jb], B.theta0[jb], B.sweep[jb])
        d[sel], wa[sel], wb[sel] = r
    return d, wa, wb
