"""Primitives packed into arrays for the verifier, with exact bounding boxes.

:class:`~ccopt.geometry.SegmentArray` is the geometry package's packed form;
:func:`pack` fills one from a list of primitives without a per-row numpy
assignment (100,000 rows in a few tens of milliseconds) and adds what the
verifier needs besides: exact bounding boxes and the rows that have no
closed-form distance (spirals and parametric curves), which
:mod:`ccopt.verify.distance.certified` bounds instead.

Row kinds: :data:`~ccopt.geometry.KIND_LINE`, :data:`~ccopt.geometry.KIND_ARC`,
:data:`~ccopt.geometry.KIND_SPIRAL`, and :data:`KIND_CURVE` for any other
curve object (a blend), which must offer ``start``, ``end``, ``length``,
``point(s)`` by arc length, ``bbox()`` and ``d2_bound(s0, s1)`` (see
:mod:`ccopt.verify.distance.certified`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import chain
from operator import attrgetter

import numpy as np

from ccopt.geometry import KIND_ARC, KIND_LINE, KIND_SPIRAL, Arc, Line, SegmentArray, Spiral
from ccopt.geometry.angles import angle_in_sweep
from ccopt.geometry.columns import put_rows, take_rows
from ccopt.geometry.spiral import spiral_bboxes, spiral_end_tangents
from ccopt.toolpath import ARC_ROW, LINE_ROW

#: Row kind of a parametric curve (no closed form; certified bounds only).
KIND_CURVE = 3

_P0, _P1, _CENTER = attrgetter("p0"), attrgetter("p1"), attrgetter("center")
_RADIUS, _THETA0, _SWEEP = attrgetter("radius"), attrgetter("theta0"), attrgetter("sweep")
_LENGTH = attrgetter("length")


@dataclass(frozen=True, eq=False)
class Packed:
    """``arr``: the rows; ``bbox``: ``(N, 4)`` ``xmin, ymin, xmax, ymax``;
    ``curved``: row index -> primitive for spiral and curve rows."""

    arr: SegmentArray
    bbox: np.ndarray
    curved: dict
    #: row index -> the line or arc object :meth:`geom` made of it (made once:
    #: the certificate asks for a row once per pair it is in, tens of times
    #: on a dense contour)
    made: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.arr)

    @property
    def exact(self) -> np.ndarray:
        """True for rows with closed-form distances (lines and arcs)."""
        return self.arr.kind <= KIND_ARC

    def geom(self, i: int):
        """Row ``i`` as a primitive object (immutable; one object per row)."""
        i = int(i)
        g = self.curved.get(i)
        if g is None:
            g = self.made.get(i)
            if g is None:
                g = self.made[i] = self.arr.segment(i)
        return g

    def geoms(self, idx: np.ndarray) -> list:
        """:meth:`geom` of each row ``idx``; the line rows not made yet are made
        in one pass (the same objects ``geom`` makes: a contour's elements are
        asked for by the ten thousand)."""
        idx = np.asarray(idx, np.intp)
        A = self.arr
        li = idx[(A.kind[idx] == KIND_LINE) & np.isfinite(A.p0[idx]).all(axis=1)
                 & np.isfinite(A.p1[idx]).all(axis=1)].tolist()
        new = [i for i in dict.fromkeys(li) if i not in self.made]
        if new:
            (x0, y0), (x1, y1) = A.p0[new].T.tolist(), A.p1[new].T.tolist()
            self.made.update(zip(new, map(Line.trusted, x0, y0, x1, y1)))
        return list(map(self.geom, idx.tolist()))


def arc_bbox(center, radius, theta0, sweep, p0, p1) -> np.ndarray:
    """Exact bounding boxes of arcs: end points plus the axis extremes inside
    each sweep (vectorised over rows)."""
    n = radius.shape[0]
    box = np.empty((n, 4))
    box[:, 0] = np.minimum(p0[:, 0], p1[:, 0])
    box[:, 1] = np.minimum(p0[:, 1], p1[:, 1])
    box[:, 2] = np.maximum(p0[:, 0], p1[:, 0])
    box[:, 3] = np.maximum(p0[:, 1], p1[:, 1])
    for q, col, sign, axis in ((0.0, 2, 1.0, 0), (0.5 * math.pi, 3, 1.0, 1),
                               (math.pi, 0, -1.0, 0), (1.5 * math.pi, 1, -1.0, 1)):
        inside = angle_in_sweep(np.full(n, q), theta0, sweep)
        ext = center[:, axis] + sign * radius
        box[:, col] = np.where(inside, ext, box[:, col])
    return box


def _curve_bbox(g) -> tuple[float, float, float, float]:
    if hasattr(g, "bbox"):
        return tuple(float(v) for v in g.bbox())
    cps = getattr(g, "control_points", None)
    if cps is not None:  # convex hull property of Bezier/B-spline curves
        cps = np.asarray(cps, float)
        return (float(cps[:, 0].min()), float(cps[:, 1].min()),
                float(cps[:, 0].max()), float(cps[:, 1].max()))
    raise TypeError(f"cannot bound {type(g).__name__}: give it bbox() or control_points")


def pack(geoms) -> Packed:
    """Pack primitives (Line, Arc, Spiral or curve objects) into a :class:`Packed`."""
    geoms = list(geoms)
    types = list(map(type, geoms))
    lines_i = [i for i, t in enumerate(types) if t is Line]
    arcs_i = [i for i, t in enumerate(types) if t is Arc]
    curved: dict[int, object] = {}
    if len(lines_i) + len(arcs_i) < len(geoms):
        curved = {i: g for i, (g, t) in enumerate(zip(geoms, types)) if t is not Line and t is not Arc}
    return _packed(len(geoms), np.asarray(lines_i, np.intp), _line_points([geoms[i] for i in lines_i]),
                   np.asarray(arcs_i, np.intp), _arc_numbers([geoms[i] for i in arcs_i]), curved)


def pack_columns(columns) -> Packed:
    """:func:`pack` of the segments' geometry of ``columns``
    (:class:`~ccopt.toolpath.SegmentColumns`) read from its arrays: the same
    :class:`Packed`, bit for bit, as ``pack`` of the geometry objects its
    :meth:`~ccopt.toolpath.SegmentColumns.materialise` makes, without making them."""
    lines_i = np.flatnonzero(columns.kind == LINE_ROW)
    arcs_i = np.flatnonzero(columns.kind == ARC_ROW)
    pts = columns.geom[lines_i, :4]
    g = columns.geom[arcs_i]
    arcs = (g[:, :2], g[:, 2], g[:, 3], g[:, 4])
    curved = dict(columns.objects)
    if curved:
        # object rows that hold a line or an arc are packed as pack packs them
        objects_i = sorted(curved)
        extra_lines = [i for i in objects_i if type(curved[i]) is Line]
        extra_arcs = [i for i in objects_i if type(curved[i]) is Arc]
        if extra_lines:
            lines_i = np.concatenate([lines_i, extra_lines])
            pts = np.concatenate([pts, _line_points([curved.pop(i) for i in extra_lines])])
        if extra_arcs:
            arcs_i = np.concatenate([arcs_i, extra_arcs])
            more = _arc_numbers([curved.pop(i) for i in extra_arcs])
            arcs = tuple(np.concatenate([a, b]) for a, b in zip(arcs, more))
    return _packed(len(columns), lines_i, pts, arcs_i, arcs, curved)


def _line_points(lines) -> np.ndarray:
    """``(m, 4)``: ``x0, y0, x1, y1`` of each line."""
    m = len(lines)
    pts = np.empty((m, 4))
    pts[:, :2] = np.fromiter(chain.from_iterable(map(_P0, lines)), float, 2 * m).reshape(m, 2)
    pts[:, 2:] = np.fromiter(chain.from_iterable(map(_P1, lines)), float, 2 * m).reshape(m, 2)
    return pts


def _arc_numbers(arcs):
    """``(centres (m, 2), radii, start angles, sweeps)`` of the arcs."""
    m = len(arcs)
    return (np.fromiter(chain.from_iterable(map(_CENTER, arcs)), float, 2 * m).reshape(m, 2),
            np.fromiter(map(_RADIUS, arcs), float, m), np.fromiter(map(_THETA0, arcs), float, m),
            np.fromiter(map(_SWEEP, arcs), float, m))


def _spiral_numbers(spirals):
    """``(centres (m, 2), rho0, rho1, theta0, sweep, b)`` of the spirals."""
    m = len(spirals)
    return (np.fromiter(chain.from_iterable(map(_CENTER, spirals)), float, 2 * m).reshape(m, 2),
            *(np.fromiter(map(get, spirals), float, m)
              for get in map(attrgetter, ("rho0", "rho1", "theta0", "sweep", "b"))))


def _packed(n: int, li: np.ndarray, pts: np.ndarray, ai: np.ndarray, arcs, curved: dict) -> Packed:
    """The :class:`Packed` of ``n`` rows: lines at rows ``li`` (``pts``, see
    :func:`_line_points`), arcs at rows ``ai`` (``arcs``, see
    :func:`_arc_numbers`) and the ``curved`` objects at theirs."""
    kind = np.empty(n, dtype=np.int8)
    p0 = np.full((n, 2), np.nan)
    p1 = np.full((n, 2), np.nan)
    center = np.full((n, 2), np.nan)
    radius = np.full(n, np.nan)
    radius_end = np.full(n, np.nan)
    theta0 = np.full(n, np.nan)
    sweep = np.full(n, np.nan)
    bbox = np.empty((n, 4))
    if li.size:
        kind[li] = KIND_LINE
        p0[li] = pts[:, :2]
        p1[li] = pts[:, 2:]
        bbox[li, 0] = np.minimum(pts[:, 0], pts[:, 2])
        bbox[li, 1] = np.minimum(pts[:, 1], pts[:, 3])
        bbox[li, 2] = np.maximum(pts[:, 0], pts[:, 2])
        bbox[li, 3] = np.maximum(pts[:, 1], pts[:, 3])
    if ai.size:
        c, R, th0, sw = arcs
        th1 = th0 + sw
        # Same formula as Arc.start / Arc.end, so end points agree bit for bit.
        a0 = np.c_[c[:, 0] + R * np.cos(th0), c[:, 1] + R * np.sin(th0)]
        a1 = np.c_[c[:, 0] + R * np.cos(th1), c[:, 1] + R * np.sin(th1)]
        kind[ai] = KIND_ARC
        p0[ai], p1[ai], center[ai] = a0, a1, c
        radius[ai] = radius_end[ai] = R
        theta0[ai], sweep[ai] = th0, sw
        bbox[ai] = arc_bbox(c, R, th0, sw, a0, a1)
    si = [i for i, g in curved.items() if isinstance(g, Spiral)]
    if si:
        # all spirals at once: the same ends and boxes as their start, end and bbox()
        sc, r0, r1, th0, sw, b = _spiral_numbers([curved[i] for i in si])
        kind[si] = KIND_SPIRAL
        center[si], radius[si], radius_end[si], theta0[si], sweep[si] = sc, r0, r1, th0, sw
        p0[si], p1[si], bbox[si] = spiral_bboxes(sc, r0, r1, th0, sw, b)
    for i, g in curved.items():
        if not isinstance(g, Spiral):
            kind[i] = KIND_CURVE
            p0[i] = g.start
            p1[i] = g.end
            bbox[i] = _curve_bbox(g)
    for a in (kind, p0, p1, center, radius, radius_end, theta0, sweep):
        a.flags.writeable = False
    return Packed(SegmentArray(kind, p0, p1, center, radius, radius_end, theta0, sweep),
                  bbox, curved)


def end_tangents(pk: Packed) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangents at the start and end of every row (zero for points)."""
    A = pk.arr
    n = len(A)
    ts = np.zeros((n, 2))
    te = np.zeros((n, 2))
    # rows by index (take_rows, put_rows): the same values as boolean masks,
    # faster on (n, 2) arrays
    line = np.flatnonzero(A.kind == KIND_LINE)
    d = take_rows(A.p1, line) - take_rows(A.p0, line)
    L = np.hypot(d[:, 0], d[:, 1])
    ok = np.flatnonzero(L > 0.0)
    u = np.zeros_like(d)
    put_rows(u, ok, take_rows(d, ok) / L[ok, None])
    put_rows(ts, line, u)
    put_rows(te, line, u)
    arc = np.flatnonzero(A.kind == KIND_ARC)
    sg = np.copysign(1.0, A.sweep[arc])
    for out, th in ((ts, A.theta0[arc]), (te, A.theta0[arc] + A.sweep[arc])):
        tangent = np.empty((arc.size, 2))
        tangent[:, 0] = -sg * np.sin(th)
        tangent[:, 1] = sg * np.cos(th)
        put_rows(out, arc, tangent)
    spirals = [i for i, g in pk.curved.items() if isinstance(g, Spiral) and g.length > 0.0]
    if spirals:
        _, rho0, rho1, th0, sw, b = _spiral_numbers([pk.curved[i] for i in spirals])
        ts[spirals], te[spirals] = spiral_end_tangents(rho0, rho1, th0, sw, b)
    for i, g in pk.curved.items():
        if not isinstance(g, Spiral) and g.length > 0.0:
            ts[i] = g.start_tangent
            te[i] = g.end_tangent
    return ts, te


def lengths(pk: Packed) -> np.ndarray:
    """In-plane length of every row."""
    A = pk.arr
    out = np.hypot(*(A.p1 - A.p0).T)
    arc = A.kind == KIND_ARC
    out[arc] = A.radius[arc] * np.abs(A.sweep[arc])
    if pk.curved:
        rows = list(pk.curved)
        out[rows] = np.fromiter(map(_LENGTH, pk.curved.values()), float, len(rows))
    return out
