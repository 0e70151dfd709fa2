"""Closed-form distances from points to points, segments and arcs, vectorised.

Each kernel returns ``(d, wa, wb)``: the distance ``d`` (shape ``(N,)``,
program units), the point itself as ``wa`` and the nearest point of the
other object as ``wb`` (shape ``(N, 2)``). The ``*_cols`` forms work on the
1-D columns of :mod:`ccopt.geometry.columns` and are the building blocks of
the curve-to-curve kernels (:mod:`ccopt.geometry.curve_distance`), whose
candidate sets include every end point against the other curve. Arcs are
``(c, R, theta0, sweep)`` (radians, ``sweep > 0`` counter-clockwise).
"""
from __future__ import annotations

import numpy as np

from ccopt.geometry.columns import PreparedArcs, blend, columns, norm, run_chunked, stack_xy

__all__ = ["point_point", "point_segment", "point_arc", "point_segment_cols", "point_arc_cols"]


def point_point(p, q):
    """Distance between points ``p`` and ``q``; the witnesses are the points."""
    (px, qx), (py, qy), _ = columns((p, q))
    d = norm(px - qx, py - qy)
    return d, stack_xy(px, py), stack_xy(qx, qy)


def point_segment_cols(px, py, ax, ay, bx, by):
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
    return norm(wx, wy), t


def point_segment(p, a, b):
    """Distance from point ``p`` to segment ``[a, b]``.

    Witnesses: ``p`` itself and the nearest segment point (the foot of the
    perpendicular, clamped to the segment). A zero-length segment is a point.
    """
    (px, ax, bx), (py, ay, by), _ = columns((p, a, b))
    return run_chunked(_point_segment_witness_cols, (px, py, ax, ay, bx, by))


def _point_segment_witness_cols(px, py, ax, ay, bx, by):
    d, t = point_segment_cols(px, py, ax, ay, bx, by)
    return d, stack_xy(px, py), stack_xy(ax + t * (bx - ax), ay + t * (by - ay))


def point_arc_cols(px, py, arc: PreparedArcs):
    """``(d, qx, qy)``: distance from p to the arc and the nearest arc point."""
    vx = px - arc.cx
    vy = py - arc.cy
    rho = norm(vx, vy)
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
    blend(qx, arc.e1x, to_end)
    blend(qy, arc.e1y, to_end)
    if radial.any():
        take = radial.astype(float)
        scale = arc.R / (rho + (rho == 0.0))
        blend(d, np.abs(rho - arc.R), take)
        vx *= scale
        vy *= scale
        vx += arc.cx
        vy += arc.cy
        blend(qx, vx, take)
        blend(qy, vy, take)
    return d, qx, qy


def point_arc(p, c, R, theta0, sweep):
    """Distance from point ``p`` to the arc ``(c, R, theta0, sweep)``.

    ``|rho - R|`` (``rho = |p - c|``) with the radial projection as witness
    when ``p``'s polar angle lies inside the sweep; otherwise the nearer end
    point. A point at the centre is at distance ``R`` (witness: an end point).
    Witnesses: ``p`` and the arc point.
    """
    (px, cx), (py, cy), (R, th0, sw) = columns((p, c), (R, theta0, sweep))
    return run_chunked(_point_arc_witness_cols, (px, py, cx, cy, R, th0, sw))


def _point_arc_witness_cols(px, py, cx, cy, R, th0, sw):
    d, qx, qy = point_arc_cols(px, py, PreparedArcs(cx, cy, R, th0, sw))
    return d, stack_xy(px, py), stack_xy(qx, qy)
