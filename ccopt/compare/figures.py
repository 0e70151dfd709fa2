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
``h`` of arc length and their nearest samples of the other path found (a
k-d tree); the worst points are then measured exactly (point-line and
point-arc kernels, curves as fine chords). The bound is the largest
nearest-sample distance plus ``h/2``: a sample of the other path is a point
of it, and the distance to a set is 1-Lipschitz, so this bounds the true
value from above.
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


def _points(g, n: int) -> np.ndarray:
    """``n`` points along a primitive, end points included (Bezier curves by their
    own parameter: no arc-length inversion needed for a set of points)."""
    cps = getattr(g, "control_points", None)
    if cps is not None:
        P = np.asarray(cps, float)
        deg = len(P) - 1
        t = np.linspace(0.0, 1.0, n)[:, None]
        k = np.arange(deg + 1)[None, :]
        binom = np.array([math.comb(deg, i) for i in range(deg + 1)], float)[None, :]
        return (binom * t ** k * (1.0 - t) ** (deg - k)) @ P
    return np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2)


def _samples(geoms, h: float) -> np.ndarray:
    """Points every ``h`` at most (curves: enough parameter steps that their
    length between samples is below ``h`` for a regular parametrisation)."""
    pts = []
    for g in geoms:
        n = max(2, int(math.ceil(g.length / h)) + 1)
        if getattr(g, "control_points", None) is not None:
            n *= 4  # speed along t varies: oversample
        pts.append(_points(g, n))
    return np.vstack(pts) if pts else np.zeros((0, 2))


def _curve_params(g, n: int) -> np.ndarray:
    return np.linspace(0.0, 1.0 if getattr(g, "control_points", None) is not None else g.length, n)


def _eval(g, u: np.ndarray) -> np.ndarray:
    cps = getattr(g, "control_points", None)
    if cps is not None:
        P = np.asarray(cps, float)
        deg = len(P) - 1
        t = u[:, None]
        k = np.arange(deg + 1)[None, :]
        binom = np.array([math.comb(deg, i) for i in range(deg + 1)], float)[None, :]
        return (binom * t ** k * (1.0 - t) ** (deg - k)) @ P
    return np.asarray(g.point(u)).reshape(-1, 2)


def _exact_distance(p: np.ndarray, geoms, h: float, reach: float) -> float:
    """Distance from one point to the primitives within ``reach`` of it by their
    bounding boxes: lines and arcs exactly, other curves by a fine local search
    around their nearest sample (chords 1/400 of a sample step)."""
    d = math.inf
    for g in geoms:
        x0, y0, x1, y1 = g.bbox()
        if p[0] < x0 - reach or p[0] > x1 + reach or p[1] < y0 - reach or p[1] > y1 + reach:
            continue
        if isinstance(g, Line):
            d = min(d, float(point_segment(p[None], g.p0, g.p1)[0][0]))
        elif isinstance(g, Arc):
            d = min(d, float(point_arc(p[None], g.center, g.radius, g.theta0, g.sweep)[0][0]))
        else:
            n = max(2, 4 * int(math.ceil(g.length / h)) + 1)
            u = _curve_params(g, n)
            q = _eval(g, u)
            k = int(np.argmin(np.hypot(*(q - p).T)))
            lo, hi = u[max(k - 1, 0)], u[min(k + 1, n - 1)]
            q = _eval(g, np.linspace(lo, hi, 801))
            d = min(d, float(np.min(point_segment(np.repeat(p[None], len(q) - 1, 0),
                                                  q[:-1], q[1:])[0])))
    return d


def _box_gap(a, b) -> float:
    """Distance between two boxes ``(xmin, ymin, xmax, ymax)`` (0 when they overlap)."""
    dx = max(a[0] - b[2], b[0] - a[2], 0.0)
    dy = max(a[1] - b[3], b[1] - a[3], 0.0)
    return math.hypot(dx, dy)


def _one_side(src: ToolPath, dst: ToolPath, h: float):
    """``(estimate, upper bound)`` of the largest distance from the changed contour
    part of ``src`` to ``dst``'s feed path."""
    from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
    dst_geoms = [s.geom for s in dst.segments if s.role in FEED_ROLES and _in_plane(s)]
    src_geoms = [s.geom for s in src.segments
                 if s.role in CONTOUR_ROLES and _in_plane(s)
                 and not any(_same(s.geom, g) for g in dst_geoms)]
    if not src_geoms or not dst_geoms:
        return 0.0, 0.0
    coarse_h = max(50.0 * h, POINT_EPS)
    coarse = cKDTree(_samples(dst_geoms, coarse_h))
    dst_boxes = [g.bbox() for g in dst_geoms]
    bound, cand = 0.0, []
    for g in src_geoms:
        # which dst primitives can hold the nearest point: those within the coarse bound
        box = g.bbox()
        reach = float(np.max(coarse.query(_samples([g], coarse_h))[0])) + coarse_h
        local = [d for d, b in zip(dst_geoms, dst_boxes) if _box_gap(box, b) <= reach]
        tree = cKDTree(_samples(local, h))
        pts = _samples([g], h)
        d, _ = tree.query(pts)
        # a sample of dst is a point of dst, so d bounds the distance from above; between
        # two samples of src (arc length ds apart) it is at most (d_i + d_i+1 + ds)/2,
        # the distance being 1-Lipschitz; with curvature at most kappa a chord c spans
        # an arc ds <= (2/kappa) asin(kappa c / 2) (kappa: the largest sampled curvature)
        c = np.hypot(*np.diff(pts, axis=0).T)
        kmax = 1.01 * float(np.max(np.abs(curvature_samples(g))))
        if kmax > 0:
            ds = 2.0 / kmax * np.arcsin(np.minimum(1.0, 0.5 * kmax * c))
            ds = np.where(0.5 * kmax * c >= 1.0, np.inf, ds)
        else:
            ds = c
        bound = max(bound, float(np.max(0.5 * (d[:-1] + d[1:] + ds))))
        top = np.argsort(d)[-5:]
        cand += [(float(d[i]), pts[i], local) for i in top]
    cand.sort(key=lambda c: c[0])
    est = max(min(_exact_distance(p, local, h, dd + h), dd) for dd, p, local in cand[-20:])
    return est, bound


def max_deviation(path: ToolPath, reference: ToolPath, h: float = 1e-3) -> tuple[float, float]:
    """``(Hausdorff distance, upper bound)`` between the compensated parts of
    ``path`` and ``reference`` (see the module docstring)."""
    a, ba = _one_side(path, reference, h)
    b, bb = _one_side(reference, path, h)
    return max(a, b), max(ba, bb)
