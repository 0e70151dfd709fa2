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

from ccopt.geometry.angles import angle_in_sweep
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


def _stack(x, y):
    out = np.empty((x.shape[0], 2))
    out[:, 0] = x
    out[:, 1] = y
    return out


class _Best:
    """Running minimum over candidate pairs, with their witness coordinates.

    Candidates not on both curves are passed with ``valid=False`` (or an
    infinite distance) and never win.
    """

    __slots__ = ("d", "ax", "ay", "bx", "by")

    def __init__(self, d, ax, ay, bx, by):
        n = d.shape[0]
        self.d = np.array(d, dtype=float)
        self.ax = np.broadcast_to(ax, (n,)).astype(float)
        self.ay = np.broadcast_to(ay, (n,)).astype(float)
        self.bx = np.broadcast_to(bx, (n,)).astype(float)
        self.by = np.broadcast_to(by, (n,)).astype(float)

    def offer(self, d, ax, ay, bx, by, valid=None):
        better = d < self.d
        if valid is not None:
            better &= valid
        np.copyto(self.d, d, where=better)
        np.copyto(self.ax, ax, where=better)
        np.copyto(self.ay, ay, where=better)
        np.copyto(self.bx, bx, where=better)
        np.copyto(self.by, by, where=better)

    def result(self):
        return self.d, _stack(self.ax, self.ay), _stack(self.bx, self.by)


# --------------------------------------------------------------------------- point kernels


def point_point(p, q):
    """Distance between points ``p`` and ``q``; the witnesses are the points."""
    (px, qx), (py, qy), _ = _columns((p, q))
    d = np.hypot(px - qx, py - qy)
    return d, _stack(px, py), _stack(qx, qy)


def _point_segment_cols(px, py, ax, ay, bx, by):
    """``(d, t)``: distance from p to segment ab and the foot's fraction t in [0, 1]."""
    rx = bx - ax
    ry = by - ay
    rr = rx * rx + ry * ry
    wx = px - ax
    wy = py - ay
    # A zero-length segment is its start point: any denominator works as w.r = 0.
    t = (wx * rx + wy * ry) / np.where(rr > 0.0, rr, 1.0)
    np.clip(t, 0.0, 1.0, out=t)
    wx -= t * rx
    wy -= t * ry
    return np.hypot(wx, wy), t


def point_segment(p, a, b):
    """Distance from point ``p`` to segment ``[a, b]``.

    Witnesses: ``p`` itself and the nearest segment point (the foot of the
    perpendicular, clamped to the segment). A zero-length segment is a point.
    """
    (px, ax, bx), (py, ay, by), _ = _columns((p, a, b))
    d, t = _point_segment_cols(px, py, ax, ay, bx, by)
    return d, _stack(px, py), _stack(ax + t * (bx - ax), ay + t * (by - ay))


def _arc_ends(cx, cy, R, th0, sw):
    th1 = th0 + sw
    return (cx + R * np.cos(th0), cy + R * np.sin(th0),
            cx + R * np.cos(th1), cy + R * np.sin(th1))


def _point_arc_cols(px, py, cx, cy, R, th0, sw, ends=None):
    """``(d, qx, qy)``: distance from p to the arc and the nearest arc point."""
    vx = px - cx
    vy = py - cy
    rho = np.hypot(vx, vy)
    # Radial projection is the answer when p's angle is on the arc; at the
    # centre every arc point is at distance R and the end points say so.
    inside = angle_in_sweep(np.arctan2(vy, vx), th0, sw) & (rho > 0.0)
    e0x, e0y, e1x, e1y = _arc_ends(cx, cy, R, th0, sw) if ends is None else ends
    d0 = np.hypot(px - e0x, py - e0y)
    d1 = np.hypot(px - e1x, py - e1y)
    first = d0 <= d1
    d = np.where(first, d0, d1)
    qx = np.where(first, e0x, e1x)
    qy = np.where(first, e0y, e1y)
    if inside.any():
        scale = R / np.where(inside, rho, 1.0)
        np.copyto(d, np.abs(rho - R), where=inside)
        np.copyto(qx, cx + vx * scale, where=inside)
        np.copyto(qy, cy + vy * scale, where=inside)
    return d, qx, qy


def point_arc(p, c, R, theta0, sweep):
    """Distance from point ``p`` to the arc ``(c, R, theta0, sweep)``.

    ``|rho - R|`` (``rho = |p - c|``) with the radial projection as witness
    when ``p``'s polar angle lies inside the sweep; otherwise the nearer end
    point. A point at the centre is at distance ``R`` (witness: the start).
    Witnesses: ``p`` and the arc point.
    """
    (px, cx), (py, cy), (R, th0, sw) = _columns((p, c), (R, theta0, sweep))
    d, qx, qy = _point_arc_cols(px, py, cx, cy, R, th0, sw)
    return d, _stack(px, py), _stack(qx, qy)


# --------------------------------------------------------------------------- segment-segment


def segment_segment(a0, a1, b0, b1):
    """Distance between segments ``[a0, a1]`` and ``[b0, b1]``.

    Two segments in the plane either cross (``d = 0`` up to rounding: ``d``
    is then the gap between the crossing computed on each segment, ~1e-16)
    or are closest with an end point of one of them involved, so the four
    end-point-to-segment distances complete the set.
    Collinear overlaps are caught by those too (an end point lies on the other
    segment). Zero-length segments are points.
    """
    (a0x, a1x, b0x, b1x), (a0y, a1y, b0y, b1y), _ = _columns((a0, a1, b0, b1))
    rx = a1x - a0x
    ry = a1y - a0y
    sx = b1x - b0x
    sy = b1y - b0y
    wx = b0x - a0x
    wy = b0y - a0y
    rr = rx * rx + ry * ry
    ss = sx * sx + sy * sy
    rr[rr == 0.0] = 1.0      # zero-length: every dot below is 0, so t = 0
    ss[ss == 0.0] = 1.0
    wr = wx * rx + wy * ry
    ws = wx * sx + wy * sy
    rs = rx * sx + ry * sy

    def clamp(v):
        np.maximum(v, 0.0, out=v)
        np.minimum(v, 1.0, out=v)
        return v

    def dist2(ex, ey, fx, fy, k):
        """|e - k f|^2 with explicit differences (no cancellation-prone expansion)."""
        ex = ex - k * fx
        ey = ey - k * fy
        ex *= ex
        ey *= ey
        ex += ey
        return ex

    # Fractions tA along A and uB along B of the current best pair.
    # b0 onto A.
    t = clamp(wr / rr)
    best = dist2(wx, wy, rx, ry, t)
    tA = t
    uB = np.zeros_like(t)
    # b1 onto A: b1 - a0 = w + s.
    t = clamp((wr + rs) / rr)
    d2 = dist2(wx + sx, wy + sy, rx, ry, t)
    m = d2 < best
    np.copyto(best, d2, where=m)
    np.copyto(tA, t, where=m)
    np.copyto(uB, 1.0, where=m)
    # a0 onto B: a0 - b0 = -w.
    u = clamp(-ws / ss)
    d2 = dist2(wx, wy, sx, sy, -u)          # |-w - u s| = |w + u s|
    m = d2 < best
    np.copyto(best, d2, where=m)
    np.copyto(tA, 0.0, where=m)
    np.copyto(uB, u, where=m)
    # a1 onto B: a1 - b0 = r - w.
    u = clamp((rs - ws) / ss)
    d2 = dist2(rx - wx, ry - wy, sx, sy, u)
    m = d2 < best
    np.copyto(best, d2, where=m)
    np.copyto(tA, 1.0, where=m)
    np.copyto(uB, u, where=m)
    # Proper crossing: each segment's ends strictly on both sides of the other's line.
    o1 = rx * wy - ry * wx                  # side of b0 w.r.t. line A
    rxs = rx * sy - ry * sx
    o2 = o1 + rxs                           # side of b1
    o3 = wx * sy - wy * sx                  # side of a0 w.r.t. line B (= cross(s, a0 - b0))
    o4 = o3 - rxs                           # side of a1
    cross = (o1 * o2 < 0.0) & (o3 * o4 < 0.0)
    if cross.any():
        ic = np.nonzero(cross)[0]
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
    wa = np.empty((best.shape[0], 2))
    wb = np.empty_like(wa)
    wa[:, 0] = a0x + tA * rx
    wa[:, 1] = a0y + tA * ry
    wb[:, 0] = b0x + uB * sx
    wb[:, 1] = b0y + uB * sy
    return best, wa, wb


# --------------------------------------------------------------------------- segment-arc


def _segment_arc_cols(a0x, a0y, a1x, a1y, cx, cy, R, th0, sw):
    rx = a1x - a0x
    ry = a1y - a0y
    L = np.hypot(rx, ry)
    Ls = np.where(L > 0.0, L, 1.0)
    ex = np.where(L > 0.0, rx / Ls, 1.0)    # any unit vector serves a point-segment
    ey = ry / Ls
    nx, ny = -ey, ex                        # left normal of the segment
    gx = cx - a0x
    gy = cy - a0y
    along_c = gx * ex + gy * ey             # foot of the centre, length from a0
    h = gx * nx + gy * ny                   # signed centre offset from the line

    # End points of the segment against the arc.
    ends = _arc_ends(cx, cy, R, th0, sw)
    d, qx, qy = _point_arc_cols(a0x, a0y, cx, cy, R, th0, sw, ends)
    best = _Best(d, a0x, a0y, qx, qy)
    d, qx, qy = _point_arc_cols(a1x, a1y, cx, cy, R, th0, sw, ends)
    best.offer(d, a1x, a1y, qx, qy)
    # End points of the arc against the segment.
    e0x, e0y, e1x, e1y = ends
    for qx, qy in ((e0x, e0y), (e1x, e1y)):
        d, t = _point_segment_cols(qx, qy, a0x, a0y, a1x, a1y)
        best.offer(d, a0x + t * rx, a0y + t * ry, qx, qy)
    # Interior-interior: circle points c +- R n, both with foot along_c.
    foot_ok = (along_c >= 0.0) & (along_c <= L)
    if foot_ok.any():
        fx = a0x + along_c * ex
        fy = a0y + along_c * ey
        psi = np.arctan2(ny, nx)
        for sgn in (1.0, -1.0):
            ok = foot_ok & angle_in_sweep(psi if sgn > 0 else psi + math.pi, th0, sw)
            best.offer(np.abs(h + sgn * R), fx, fy, cx + sgn * R * nx, cy + sgn * R * ny, ok)
    # Crossings of the segment with the arc: c + (+-w) e - h n, w the half chord.
    w2 = (R - h) * (R + h)
    meets = w2 >= 0.0
    if meets.any():
        w = np.sqrt(np.where(meets, w2, 0.0))
        zero = np.zeros_like(w)
        for sgn in (1.0, -1.0):
            along = along_c + sgn * w
            vx = sgn * w * ex - h * nx
            vy = sgn * w * ey - h * ny
            ok = meets & (along >= 0.0) & (along <= L) & angle_in_sweep(np.arctan2(vy, vx), th0, sw)
            best.offer(zero, a0x + along * ex, a0y + along * ey, cx + vx, cy + vy, ok)
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
    return _segment_arc_cols(a0x, a0y, a1x, a1y, cx, cy, R, th0, sw)


# --------------------------------------------------------------------------- arc-arc


def _arc_arc_cols(c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2):
    ends1 = _arc_ends(c1x, c1y, R1, th1, sw1)
    ends2 = _arc_ends(c2x, c2y, R2, th2, sw2)
    e10x, e10y, e11x, e11y = ends1
    e20x, e20y, e21x, e21y = ends2
    # End points of each arc against the other arc (this also covers concentric arcs).
    d, qx, qy = _point_arc_cols(e10x, e10y, c2x, c2y, R2, th2, sw2, ends2)
    best = _Best(d, e10x, e10y, qx, qy)
    d, qx, qy = _point_arc_cols(e11x, e11y, c2x, c2y, R2, th2, sw2, ends2)
    best.offer(d, e11x, e11y, qx, qy)
    d, qx, qy = _point_arc_cols(e20x, e20y, c1x, c1y, R1, th1, sw1, ends1)
    best.offer(d, qx, qy, e20x, e20y)
    d, qx, qy = _point_arc_cols(e21x, e21y, c1x, c1y, R1, th1, sw1, ends1)
    best.offer(d, qx, qy, e21x, e21y)

    gx = c2x - c1x
    gy = c2y - c1y
    D = np.hypot(gx, gy)
    apart = D > 0.0
    if not apart.any():
        return best.result()
    Ds = np.where(apart, D, 1.0)
    ux = gx / Ds                            # unit vector c1 -> c2
    uy = gy / Ds
    psi = np.arctan2(uy, ux)
    # Interior pairs on the line of centres: p = c1 + s1 R1 u, q = c2 + s2 R2 u.
    on1 = {1.0: angle_in_sweep(psi, th1, sw1), -1.0: angle_in_sweep(psi + math.pi, th1, sw1)}
    on2 = {1.0: angle_in_sweep(psi, th2, sw2), -1.0: angle_in_sweep(psi + math.pi, th2, sw2)}
    for s1 in (1.0, -1.0):
        for s2 in (1.0, -1.0):
            ok = apart & on1[s1] & on2[s2]
            if ok.any():
                best.offer(np.abs(D + s2 * R2 - s1 * R1),
                           c1x + s1 * R1 * ux, c1y + s1 * R1 * uy,
                           c2x + s2 * R2 * ux, c2y + s2 * R2 * uy, ok)
    # Crossings: c1 + a u +- h u_perp with a = (D^2 + R1^2 - R2^2) / (2D).
    a = (D * D + R1 * R1 - R2 * R2) / (2.0 * Ds)
    h2 = (R1 - a) * (R1 + a)
    meets = apart & (h2 >= 0.0)
    if meets.any():
        h = np.sqrt(np.where(meets, h2, 0.0))
        zero = np.zeros_like(h)
        for sgn in (1.0, -1.0):
            vx = a * ux - sgn * h * uy       # crossing relative to c1
            vy = a * uy + sgn * h * ux
            px = c1x + vx
            py = c1y + vy
            ok = (meets & angle_in_sweep(np.arctan2(vy, vx), th1, sw1)
                  & angle_in_sweep(np.arctan2(py - c2y, px - c2x), th2, sw2))
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
    return _arc_arc_cols(c1x, c1y, R1, th1, sw1, c2x, c2y, R2, th2, sw2)


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
