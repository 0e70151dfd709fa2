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
Segments the two paths share are skipped. Along each other segment the
distance to the other path's primitives near it is bounded at samples (lines
and arcs exactly, in closed form; other curves from their samples every
``h`` plus their chords' gap), and between samples by the distance being
1-Lipschitz; steps are halved, branch and bound, until each step's bound is
within ``h/8`` of the largest sampled distance, so only the stretches near
the maximum are sampled finely. The largest samples are then measured
exactly (curves as fine chords) for the estimate.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Arc, Line, point_segment
from ccopt.geometry.bezier_arclength import ARC_LENGTH_REL_TOL
from ccopt.geometry.curve import curvature_bound
from ccopt.geometry.columns import PreparedArcs
from ccopt.geometry.point_distance import point_segment_cols
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


def _shared(src_geoms, dst_geoms) -> list[bool]:
    """Whether each of ``src_geoms`` is one of ``dst_geoms`` (:func:`_same`): lines and
    arcs by value (a set), other primitives by identity."""
    by_value = {g for g in dst_geoms if isinstance(g, (Line, Arc))}
    by_id = {id(g) for g in dst_geoms}
    return [id(g) in by_id or (isinstance(g, (Line, Arc)) and g in by_value)
            for g in src_geoms]


def _points(g, n: int) -> np.ndarray:
    """``n`` points along a primitive, equally spaced in arc length, end points included."""
    return np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2)


def _samples(geoms, h: float) -> np.ndarray:
    """Points every ``h`` of arc length at most, end points included."""
    pts = [_points(g, max(2, int(math.ceil(g.length / h)) + 1)) for g in geoms]
    return np.vstack(pts) if pts else np.zeros((0, 2))


def _curvature_cap(g) -> float:
    """An upper bound of ``|kappa|`` along a curve: certified for a Bezier curve
    (:func:`~ccopt.geometry.curve.curvature_bound`), else the largest sampled
    curvature plus 1 %."""
    cps = getattr(g, "control_points", None)
    if cps is not None:
        return curvature_bound(cps)
    return 1.01 * float(np.max(np.abs(curvature_samples(g))))


#: Values per block of the point-to-primitive tables (``(points, primitives)``):
#: bounds the memory of a long primitive measured against many.
CHUNK_CELLS = 1 << 18


class _Distances:
    """Distances from points to primitives: lines and arcs exactly (closed form);
    another curve by its samples every ``h`` of arc length (a k-d tree, built once
    per curve): the distance to the chords beside the nearest sample plus the
    chords' largest gap to the curve, ``kappa ds^2 / 8`` (``|p''| = kappa`` by arc
    length), an upper bound within that gap of the true distance."""

    def __init__(self, h: float):
        self.h = h
        self._curves = {}

    def curve(self, g):
        """``(s, points, tree, gap)`` of the curve ``g`` sampled every ``h`` at most."""
        from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
        key = id(g)
        if key not in self._curves:
            s = np.linspace(0.0, g.length, max(2, int(math.ceil(g.length / self.h)) + 1))
            q = _points_between(g, 0.0, g.length, s.size)
            step = s[1] - s[0] + 2.0 * ARC_LENGTH_REL_TOL * g.length
            self._curves[key] = (g, s, q, cKDTree(q), _curvature_cap(g) * step * step / 8.0)
        return self._curves[key][1:]

    def upper(self, pts: np.ndarray, near: "_Near") -> np.ndarray:
        """``(N,)``: an upper bound of the distance from each point to the primitives
        of ``near`` (exact where they are lines and arcs)."""
        d = np.full(len(pts), math.inf)
        # points by blocks: a block times the primitives stays near CHUNK_CELLS values
        block = max(1, CHUNK_CELLS // max(1, near.size))
        for i in range(0, len(pts), block):
            px, py = pts[i:i + block, :1], pts[i:i + block, 1:]
            if near.lines is not None:
                d[i:i + block] = point_segment_cols(px, py, *near.lines)[0].min(axis=1)
            if near.arcs is not None:
                d[i:i + block] = np.minimum(d[i:i + block],
                                            _arc_distances(px, py, near.arcs).min(axis=1))
        px, py = pts[:, 0], pts[:, 1]
        for g in near.curves:
            s, q, tree, gap = self.curve(g)
            dk, k = tree.query(pts)
            k0 = np.clip(k - 1, 0, len(q) - 2)
            k1 = np.clip(k, 0, len(q) - 2)
            chord = np.minimum(point_segment_cols(px, py, *q[k0].T, *q[k0 + 1].T)[0],
                               point_segment_cols(px, py, *q[k1].T, *q[k1 + 1].T)[0])
            d = np.minimum(d, np.minimum(dk, chord + gap))
        return d

    def exact(self, p: np.ndarray, geoms, reach: float) -> float:
        """Distance from one point to the primitives within ``reach`` of it by their
        bounding boxes: lines and arcs exactly, other curves by chords 1/400 of a
        sample step around their nearest sample."""
        d = math.inf
        for g in geoms:
            x0, y0, x1, y1 = g.bbox()
            if p[0] < x0 - reach or p[0] > x1 + reach or p[1] < y0 - reach or p[1] > y1 + reach:
                continue
            if isinstance(g, (Line, Arc)):
                d = min(d, float(self.upper(p[None], _Near([g]))[0]))
                continue
            s, _, tree, _ = self.curve(g)
            k = int(tree.query(p)[1])
            q = _points_between(g, s[max(k - 1, 0)], s[min(k + 1, s.size - 1)], 801)
            d = min(d, float(np.min(point_segment(np.repeat(p[None], len(q) - 1, 0),
                                                  q[:-1], q[1:])[0])))
        return d


class _Near:
    """Primitives as arrays for :meth:`_Distances.upper`: ``lines`` (the columns
    ``ax, ay, bx, by``, each ``(1, m)``), ``arcs`` (:class:`PreparedArcs` of
    ``(1, m)`` columns), ``None`` when there are none; ``curves`` the others."""

    def __init__(self, geoms):
        lines = [g for g in geoms if isinstance(g, Line)]
        arcs = [g for g in geoms if isinstance(g, Arc)]
        self.curves = [g for g in geoms if not isinstance(g, (Line, Arc))]
        self.lines = None
        if lines:
            ends = np.array([(*g.p0, *g.p1) for g in lines], float).T
            self.lines = tuple(col[None, :] for col in ends)
        self.size = len(lines) + len(arcs)
        self.arcs = None
        if arcs:
            cols = np.array([(*g.center, g.radius, g.theta0, g.sweep) for g in arcs], float).T
            self.arcs = PreparedArcs(*(col[None, :] for col in cols))


def _arc_distances(px, py, arcs: PreparedArcs) -> np.ndarray:
    """Distances from points ``(px, py)`` (``(N, 1)``) to arcs (``(1, m)``): radial,
    ``|rho - R|``, where the point's polar angle is on the arc, else to the nearer
    end point (as :func:`ccopt.geometry.point_arc`)."""
    vx = px - arcs.cx
    vy = py - arcs.cy
    rho = np.hypot(vx, vy)
    radial = arcs.contains(np.arctan2(vy, vx)) & (rho > 0.0)
    to_end = np.minimum(np.hypot(px - arcs.e0x, py - arcs.e0y),
                        np.hypot(px - arcs.e1x, py - arcs.e1y))
    return np.where(radial, np.abs(rho - arcs.R), to_end)


def _points_between(g, s0: float, s1: float, n: int) -> np.ndarray:
    return np.asarray(g.point(np.linspace(s0, s1, n))).reshape(-1, 2)


def _box_gaps(a, boxes: np.ndarray) -> np.ndarray:
    """Distances from the box ``a`` to each of ``boxes`` (``(m, 4)``), boxes as
    ``(xmin, ymin, xmax, ymax)`` (0 where they overlap)."""
    dx = np.maximum(np.maximum(a[0] - boxes[:, 2], boxes[:, 0] - a[2]), 0.0)
    dy = np.maximum(np.maximum(a[1] - boxes[:, 3], boxes[:, 1] - a[3]), 0.0)
    return np.hypot(dx, dy)


#: The deviation bound stops refining a primitive's samples once every step's
#: bound is within this share of ``h`` above the largest sampled distance.
BOUND_SLACK_SHARE = 0.125


def _along(g, local: "_Near", dist: _Distances, h: float, coarse_h: float, known: float):
    """``(bound, pts, d)``: an upper bound of the distance from the primitive ``g`` to
    ``local``, and the samples it rests on (points and their distance bounds).

    Branch and bound on arc length: between two samples ``ds`` apart the
    distance is at most ``(d_i + d_i+1 + ds) / 2`` (it is 1-Lipschitz; ``ds``
    carries twice the arc-length tolerance of curves,
    :data:`ARC_LENGTH_REL_TOL`). Starting every ``coarse_h``, a step is halved
    while that bound exceeds ``BOUND_SLACK_SHARE * h`` plus the largest
    distance sampled so far (here or ``known``, on the primitives before), so
    the bound ends within that of the sampled maximum and steps far below it
    are never refined.
    """
    s = np.linspace(0.0, g.length, max(2, int(math.ceil(g.length / coarse_h)) + 1))
    pts = _points_between(g, 0.0, g.length, s.size)
    d = dist.upper(pts, local)
    slack = 2.0 * ARC_LENGTH_REL_TOL * g.length
    a, b, da, db = s[:-1], s[1:], d[:-1], d[1:]
    all_pts, all_d = [pts], [d]
    top = max(known, float(d.max()))
    bound = 0.0
    while a.size:
        step = 0.5 * (da + db + (b - a) + slack)
        done = (step <= top + BOUND_SLACK_SHARE * h) | (0.5 * (a + b) <= a) | (0.5 * (a + b) >= b)
        if done.any():
            bound = max(bound, float(step[done].max()))
        a, b, da, db = a[~done], b[~done], da[~done], db[~done]
        if not a.size:
            break
        m = 0.5 * (a + b)
        pm = np.asarray(g.point(m)).reshape(-1, 2)
        dm = dist.upper(pm, local)
        all_pts.append(pm)
        all_d.append(dm)
        top = max(top, float(dm.max()))
        # (np.concatenate: np.r_ costs ten times more, in this loop per primitive)
        a, b = np.concatenate((a, m)), np.concatenate((m, b))
        da, db = np.concatenate((da, dm)), np.concatenate((dm, db))
    return bound, np.vstack(all_pts), np.concatenate(all_d)


def _one_side(src: ToolPath, dst: ToolPath, h: float):
    """``(estimate, upper bound)`` of the largest distance from the changed contour
    part of ``src`` to ``dst``'s feed path."""
    from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
    dst_geoms = [s.geom for s in dst.segments if s.role in FEED_ROLES and _in_plane(s)]
    contour = [s.geom for s in src.segments if s.role in CONTOUR_ROLES and _in_plane(s)]
    src_geoms = [g for g, same in zip(contour, _shared(contour, dst_geoms)) if not same]
    if not src_geoms or not dst_geoms:
        return 0.0, 0.0
    coarse_h = max(50.0 * h, POINT_EPS)
    coarse = cKDTree(_samples(dst_geoms, coarse_h))
    dst_boxes = np.array([g.bbox() for g in dst_geoms], float).reshape(-1, 4)
    dist = _Distances(h)
    bound, top, cand = 0.0, 0.0, []
    for g in src_geoms:
        # which dst primitives can hold the nearest point: those within the coarse bound
        box = g.bbox()
        reach = float(np.max(coarse.query(_samples([g], coarse_h))[0])) + coarse_h
        local = [dst_geoms[i] for i in np.flatnonzero(_box_gaps(box, dst_boxes) <= reach)]
        b, pts, d = _along(g, _Near(local), dist, h, coarse_h, top)
        bound = max(bound, b)
        top = max(top, float(d.max()))
        best = np.argsort(d)[-5:]
        cand += [(float(d[i]), pts[i], local) for i in best]
    cand.sort(key=lambda c: c[0], reverse=True)
    est = 0.0
    for dd, p, local in cand[:20]:
        if dd <= est:       # min(exact, dd) cannot raise the estimate any more
            break
        est = max(est, min(dist.exact(p, local, dd + h), dd))
    return est, bound


def max_deviation(path: ToolPath, reference: ToolPath, h: float = 1e-3) -> tuple[float, float]:
    """``(Hausdorff distance, upper bound)`` between the compensated parts of
    ``path`` and ``reference`` (see the module docstring)."""
    a, ba = _one_side(path, reference, h)
    b, bb = _one_side(reference, path, h)
    return max(a, b), max(ba, bb)
