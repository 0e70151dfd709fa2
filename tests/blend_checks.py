"""Independent checks for blends (tests only): the contour from the program's
blocks, point distances by their own formulas, joins by the primitives' own
end tangents and curvatures. Nothing here calls ccopt.compare, formulations or
ccopt.verify, so the figures those report can be checked against it."""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, block_geometry


def contour(program):
    """Programmed geometry of every fully compensated in-plane move (compensation
    on for it and for the in-plane move before it, same side): the part surface."""
    out, prev = [], None
    for b in program.blocks:
        if not b.in_plane:
            continue
        if b.modal.side and prev is not None and prev.modal.side == b.modal.side:
            out.append(block_geometry(b))
        prev = b
    return out


def dist_point_segment(p, a, b):
    p, a, b = np.asarray(p, float), np.asarray(a, float), np.asarray(b, float)
    d = b - a
    t = np.clip(((p - a) @ d) / max(float(d @ d), 1e-300), 0.0, 1.0)
    q = a + t[:, None] * d
    return np.hypot(*(p - q).T)


def dist_point_arc(p, arc: Arc):
    p = np.asarray(p, float)
    c = np.asarray(arc.center, float)
    v = p - c
    ang = np.arctan2(v[:, 1], v[:, 0])
    # fraction of the sweep reached by the point's polar angle
    rel = (ang - arc.theta0) * math.copysign(1.0, arc.sweep)
    rel = np.mod(rel, 2 * math.pi)
    inside = rel <= abs(arc.sweep) + 1e-15
    radial = np.abs(np.hypot(v[:, 0], v[:, 1]) - arc.radius)
    e0, e1 = np.asarray(arc.start), np.asarray(arc.end)
    ends = np.minimum(np.hypot(*(p - e0).T), np.hypot(*(p - e1).T))
    return np.where(inside, radial, ends)


def dist_to(p, geoms):
    d = np.full(len(p), np.inf)
    for g in geoms:
        if isinstance(g, Line):
            d = np.minimum(d, dist_point_segment(p, g.p0, g.p1))
        elif isinstance(g, Arc):
            d = np.minimum(d, dist_point_arc(p, g))
        else:
            q = bezier_points(g, 4001) if hasattr(g, "control_points") else \
                np.asarray(g.point(np.linspace(0.0, g.length, 4001)))
            a, b = q[:-1], q[1:]
            e = b - a
            for k in range(0, len(p), 256):
                pk = np.asarray(p[k:k + 256], float)[:, None, :]
                t = np.clip(((pk - a) * e).sum(-1) / np.maximum((e * e).sum(-1), 1e-300), 0, 1)
                w = pk - (a + t[..., None] * e)
                d[k:k + 256] = np.minimum(d[k:k + 256], np.hypot(w[..., 0], w[..., 1]).min(1))
    return d


def bezier_points(curve, n=2001):
    """Points of a Bezier curve by de Casteljau on its control points."""
    P = np.asarray(curve.control_points, float)
    t = np.linspace(0.0, 1.0, n)[:, None, None]
    pts = np.broadcast_to(P, (n,) + P.shape).copy()
    for r in range(1, len(P)):
        pts[:, :len(P) - r] = (1 - t) * pts[:, :len(P) - r] + t * pts[:, 1:len(P) - r + 1]
    return pts[:, 0]


def end_curvature(g, at_end: bool) -> float:
    if isinstance(g, Line):
        return 0.0
    if isinstance(g, Arc):
        return math.copysign(1.0 / g.radius, g.sweep)
    return float(g.curvature(g.length if at_end else 0.0))


def join_ok(a, b, tol_t=1e-7, tol_k=1e-6):
    """``(gap, tangent angle, curvature jump)`` between segment geometries ``a`` -> ``b``."""
    gap = math.dist(a.end, b.start)
    ta, tb = np.asarray(a.end_tangent), np.asarray(b.start_tangent)
    ang = math.atan2(abs(ta[0] * tb[1] - ta[1] * tb[0]), float(ta @ tb))
    jump = abs(end_curvature(a, True) - end_curvature(b, False))
    return gap, ang, jump


#: The feed roles of a tool path (rapids left out).
FEED_ROLES = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)


def largest_curvature(g) -> float:
    """Largest |curvature| of a primitive: 0 for a line, 1/R for an arc, other
    curves sampled from their own derivatives at 4,001 points."""
    if isinstance(g, Line):
        return 0.0
    if isinstance(g, Arc):
        return 1.0 / g.radius
    s = np.linspace(0.0, g.length, 4001)
    return float(np.max(np.abs(g.curvature(s))))


def lead_curvature_bound(seg, limits, ref) -> float:
    """The optimised leads' stated bound for the lead segment ``seg`` (issue 30
    item 3), the larger of ``a / v^2`` and ``kappa_ref``: ``a`` the smaller of
    the in-plane axis accelerations of ``limits``, ``v`` the segment's
    programmed feed, at most the slower in-plane axis speed (the turn whose
    normal acceleration at that speed is what every axis can give), and
    ``kappa_ref`` the largest curvature of the feed segments of ``ref``, the
    path the blends were made from (lines 0, arcs 1/R, other curves sampled)."""
    axes = {"XY": (0, 1), "ZX": (2, 0), "YZ": (1, 2)}[ref.plane]
    a = min(limits.a[i] for i in axes)
    v = min([seg.feed] + [limits.v[i] for i in axes])
    kref = max((largest_curvature(s.geom) for s in ref.segments
                if s.role in FEED_ROLES and s.length > 0), default=0.0)
    return max(a / v ** 2, kref)


def lead_curves(path):
    """``(segment, Bezier curve)`` of each lead of ``path`` an optimised blend made."""
    return [(s, s.geom) for s in path.segments
            if s.role in (Role.LEAD_IN, Role.LEAD_OUT) and s.geom.__class__.__name__ == "BezierCurve"]


def _basis(t, n):
    """Bernstein basis of degree ``n`` at ``t`` (rows)."""
    k = np.arange(n + 1)
    return np.array([math.comb(n, i) for i in k]) * t[:, None] ** k * (1 - t[:, None]) ** (n - k)


def bezier_max_curvature(g) -> float:
    """Largest |r' x r''| / |r'|^3 of a Bezier curve at 20,001 values of its
    parameter (derivatives by the hodograph: differences of the control points)."""
    P = np.asarray(g.control_points, float)
    n = len(P) - 1
    t = np.linspace(0.0, 1.0, 20001)
    d1 = _basis(t, n - 1) @ (n * np.diff(P, axis=0))
    d2 = _basis(t, n - 2) @ (n * (n - 1) * np.diff(P, 2, axis=0))
    return float(np.max(np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
                        / np.hypot(d1[:, 0], d1[:, 1]) ** 3))
