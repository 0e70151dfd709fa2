"""Figures of a tool path for the comparison: length, curvature, continuity,
deviation from a reference.

Continuity classes at a join between consecutive in-plane segments:
``"G2"`` (position, tangent and curvature agree), ``"G1"`` (position and
tangent), ``"G0"`` (position only), ``"gap"``. Tolerances: positions
:data:`ccopt.tolerances.VERIFY_EPS`, tangents
:data:`ccopt.tolerances.VERIFY_TANGENT_BREAK` (radians), curvature
:data:`CURVATURE_TOL` (1/units, relative to ``max(1, |kappa|)``).

Curvature of lines and arcs is exact; spirals and Bezier curves are sampled
(:data:`CURVE_SAMPLES` points, end points included), which is what a
comparison figure needs.

Deviation (:func:`max_deviation`): the Hausdorff distance between the parts
cut with compensation in force (segments with role ``compensated`` or
``corner``) of two paths, each measured to the other's whole feed path.
Segments the two paths share are skipped; the others are sampled every
``h`` of arc length and measured with the exact point-line/point-arc kernels
(spirals and curves of the other path as chords). The figure returned is the
sampled maximum; ``bound`` adds ``h/2`` (distance to a set is 1-Lipschitz)
and the chords' sagitta, an upper bound of the true value.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Arc, Line, point_arc, point_segment
from ccopt.tolerances import POINT_EPS, VERIFY_EPS, VERIFY_TANGENT_BREAK
from ccopt.toolpath import Role, ToolPath

#: Curvature jumps below this (1/units, times max(1, |kappa|)) count as none.
CURVATURE_TOL = 1e-6

#: Samples per spiral or curve for curvature figures.
CURVE_SAMPLES = 257

_ORDER = {"gap": 0, "G0": 1, "G1": 2, "G2": 3}
CONTOUR_ROLES = (Role.COMPENSATED, Role.CORNER)
FEED_ROLES = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)


def worst(classes) -> str | None:
    classes = list(classes)
    return min(classes, key=_ORDER.__getitem__) if classes else None


def curvature_samples(g) -> np.ndarray:
    """Signed curvature along a primitive (1/units)."""
    if isinstance(g, Line):
        return np.zeros(2)
    if isinstance(g, Arc):
        return np.full(2, math.copysign(1.0 / g.radius, g.sweep))
    s = np.linspace(0.0, g.length, CURVE_SAMPLES)
    return np.atleast_1d(np.asarray(g.curvature(s), float))


def end_curvatures(g) -> tuple[float, float]:
    if isinstance(g, Line):
        return 0.0, 0.0
    if isinstance(g, Arc):
        k = math.copysign(1.0 / g.radius, g.sweep)
        return k, k
    return float(g.curvature(0.0)), float(g.curvature(g.length))


def _in_plane(seg) -> bool:
    return seg.length > POINT_EPS


def join_class(a, b) -> tuple[str, float, float, float]:
    """``(class, gap, tangent angle, curvature jump)`` of the join ``a`` -> ``b``."""
    gap = math.dist(a.end, b.start)
    ta = np.asarray(a.geom.end_tangent, float)
    tb = np.asarray(b.geom.start_tangent, float)
    ang = math.atan2(abs(ta[0] * tb[1] - ta[1] * tb[0]), float(ta @ tb))
    ka = end_curvatures(a.geom)[1]
    kb = end_curvatures(b.geom)[0]
    jump = abs(kb - ka)
    if gap > VERIFY_EPS:
        return "gap", gap, ang, jump
    if ang > VERIFY_TANGENT_BREAK:
        return "G0", gap, ang, jump
    if jump > CURVATURE_TOL * max(1.0, abs(ka), abs(kb)):
        return "G1", gap, ang, jump
    return "G2", gap, ang, jump


def joins(path: ToolPath, roles=FEED_ROLES) -> list[tuple[int, str, float, float, float]]:
    """Every join between consecutive in-plane segments whose roles are in
    ``roles``: ``(index of the second segment, class, gap, angle, jump)``.
    A segment with no in-plane motion (a plunge) interrupts the path."""
    segs = path.segments
    out = []
    for i in range(1, len(segs)):
        a, b = segs[i - 1], segs[i]
        if a.role in roles and b.role in roles and _in_plane(a) and _in_plane(b):
            out.append((i, *join_class(a, b)))
    return out


def path_figures(path: ToolPath, join_indices=None) -> dict:
    """Length, curvature and continuity figures of ``path``.

    ``join_indices``: the boundaries the variant made (segment index after
    each); ``continuity`` is the worst class among them (``None`` if none),
    ``path_continuity`` the worst over every feed join of the path.
    """
    feed = [s for s in path.segments if s.role in FEED_ROLES and _in_plane(s)]
    kmax = max((float(np.max(np.abs(curvature_samples(s.geom)))) for s in feed), default=0.0)
    all_joins = joins(path)
    g1 = [j for j in all_joins if j[1] in ("G1", "G2")]
    jump = max((j[4] for j in g1), default=0.0)
    by_index = {j[0]: j for j in all_joins}
    mine = [by_index[i] for i in (join_indices or []) if i in by_index]
    return {
        "length": float(path.length),
        "feed_length": float(sum(s.length for s in feed)),
        "max_curvature": kmax,
        "max_curvature_jump": float(jump),
        "tangent_breaks": int(sum(1 for j in all_joins if j[1] in ("G0", "gap"))),
        "continuity": worst(j[1] for j in mine),
        "path_continuity": worst(j[1] for j in all_joins),
        "joins": [{"segment": j[0], "class": j[1], "angle": j[3], "curvature_jump": j[4]}
                  for j in mine],
    }


# --------------------------------------------------------------------------- deviation


def _same(g, h) -> bool:
    if g is h:
        return True
    if type(g) is not type(h) or not isinstance(g, (Line, Arc)):
        return False
    return g == h


def _as_pieces(geoms, h: float):
    """Lines and arcs as they are; other curves as chords ``(lines, arcs, sag)``."""
    lines, arcs, sag = [], [], 0.0
    for g in geoms:
        if isinstance(g, Line):
            lines.append((g.p0, g.p1))
        elif isinstance(g, Arc):
            arcs.append((g.center, g.radius, g.theta0, g.sweep))
        else:
            n = max(2, int(math.ceil(g.length / h)) + 1)
            s = np.linspace(0.0, g.length, n)
            pts = np.asarray(g.point(s))
            kmax = float(np.max(np.abs(curvature_samples(g))))
            sag = max(sag, kmax * (g.length / (n - 1)) ** 2 / 8.0)
            lines += [(tuple(p), tuple(q)) for p, q in zip(pts[:-1], pts[1:])]
    return lines, arcs, sag


def _dist_to(points: np.ndarray, lines, arcs) -> np.ndarray:
    d = np.full(len(points), np.inf)
    for a, b in lines:
        d = np.minimum(d, point_segment(points, a, b)[0])
    for c, R, th0, sw in arcs:
        d = np.minimum(d, point_arc(points, c, R, th0, sw)[0])
    return d


def _one_side(src: ToolPath, dst: ToolPath, h: float):
    dst_geoms = [s.geom for s in dst.segments if s.role in FEED_ROLES and _in_plane(s)]
    pts = []
    for s in src.segments:
        if s.role not in CONTOUR_ROLES or not _in_plane(s):
            continue
        if any(_same(s.geom, g) for g in dst_geoms):
            continue
        n = max(2, int(math.ceil(s.length / h)) + 1)
        pts.append(np.asarray(s.geom.point(np.linspace(0.0, s.length, n))))
    if not pts:
        return 0.0, 0.0
    lines, arcs, sag = _as_pieces(dst_geoms, h)
    d = _dist_to(np.vstack(pts), lines, arcs)
    return float(d.max()), sag


def max_deviation(path: ToolPath, reference: ToolPath, h: float = 2e-3) -> tuple[float, float]:
    """``(sampled Hausdorff distance, certified upper bound)`` between the
    compensated parts of ``path`` and ``reference`` (see the module docstring)."""
    a, sa = _one_side(path, reference, h)
    b, sb = _one_side(reference, path, h)
    dev = max(a, b)
    if dev == 0.0:
        return 0.0, 0.0
    return dev, dev + 0.5 * h + max(sa, sb)
