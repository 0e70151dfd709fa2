"""Deviation of a tool path from a reference path, for the comparison.

:func:`max_deviation`: the Hausdorff distance between the parts cut with
compensation in force (segments with role ``compensated`` or ``corner``) of
two paths, each measured to the other's whole feed path. Segments the two
paths share are skipped. Along each other segment the distance to the other
path's primitives near it is bounded at samples (lines and arcs exactly, in
closed form; other curves from their samples every ``h`` plus their chords'
gap), and between samples by the distance being 1-Lipschitz; steps are
halved, branch and bound, until each step's bound is within ``h/8`` of the
largest sampled distance, so only the stretches near the maximum are
sampled finely; a line beside a target line, or an arc or spiral beside a
target arc or spiral turning the same way (another controller's corner, a
CAM arc read as a spiral of rounded ends), is bounded in closed form and not
sampled at all; nor is a step of a line whose two ends are nearest one
target line, or a step of an arc or spiral within a target arc's or spiral's
angles (a line running on past the reference's, a corner arc turning a
little further). The largest samples are then measured exactly (curves as
fine chords) for the estimate.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.compare.parts import CONTOUR_ROLES, FEED_ROLES, curvature_samples
from ccopt.compare.parts import in_plane as _in_plane
from ccopt.geometry import Arc, Line, Spiral, point_segment
from ccopt.geometry.bezier_arclength import ARC_LENGTH_REL_TOL
from ccopt.geometry.bezier_batch import batches_by_degree
from ccopt.geometry.curve import curvature_bound
from ccopt.geometry.angles import in_sweep_prepared
from ccopt.geometry.columns import PreparedArcs
from ccopt.geometry.point_distance import point_segment_cols
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import ToolPath


def _same(g, h) -> bool:
    if g is h:
        return True
    if type(g) is not type(h) or not isinstance(g, _BY_VALUE):
        return False
    return g == h


def _shared(src_geoms, dst_geoms) -> list[bool]:
    """Whether each of ``src_geoms`` is one of ``dst_geoms`` (:func:`_same`): lines,
    arcs and spirals by value (a set: two styles offset a program's spiral alike,
    each its own object), other primitives by identity."""
    by_value = {g for g in dst_geoms if isinstance(g, _BY_VALUE)}
    by_id = {id(g) for g in dst_geoms}
    return [id(g) in by_id or (isinstance(g, _BY_VALUE) and g in by_value)
            for g in src_geoms]


#: Primitives :func:`_shared` compares by value (hashable frozen dataclasses).
_BY_VALUE = (Line, Arc, Spiral)


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


#: Values per block of the point-to-primitive pairs: bounds the memory of many
#: samples measured against many primitives.
CHUNK_CELLS = 1 << 18

_LINE, _ARC, _CURVE = 0, 1, 2

#: Nearest curve samples (over all target curves) whose chords bound a point's
#: distance to the curves: more than one, so that a curve whose chord passes
#: nearer than another curve's nearest sample is seen too.
CURVE_NEIGHBOURS = 4


class _Primitives:
    """Primitives as columns, for many points on many of them at once: lines
    and arcs by the formulas of :class:`~ccopt.geometry.Line` and
    :class:`~ccopt.geometry.Arc`, Bezier curves in batches of one degree
    (:class:`~ccopt.geometry.bezier_batch.BezierBatch`), other curves by their
    own ``point``."""

    def __init__(self, geoms):
        m = len(geoms)
        self.geoms = geoms
        self.length = np.array([float(g.length) for g in geoms])
        self.kind = np.full(m, _CURVE, np.int8)
        self.p0, self.p1 = np.zeros((m, 2)), np.zeros((m, 2))
        arc = np.zeros((m, 5))
        arc[:, 2] = 1.0
        #: arcs and spirals: centre, radius at both ends, start angle, sweep
        self.circ = np.full((m, 6), np.nan)
        for i, g in enumerate(geoms):
            if type(g) is Line:
                self.kind[i] = _LINE
                self.p0[i], self.p1[i] = g.p0, g.p1
            elif type(g) is Arc:
                self.kind[i] = _ARC
                arc[i] = (*g.center, g.radius, g.theta0, g.sweep)
                self.circ[i] = (*g.center, g.radius, g.radius, g.theta0, g.sweep)
            elif type(g) is Spiral:
                self.circ[i] = (*g.center, g.rho0, g.rho1, g.theta0, g.sweep)
        self.circular = ~np.isnan(self.circ[:, 0])
        self.arcs = PreparedArcs(*arc.T)
        self.curves = np.flatnonzero(self.kind == _CURVE)
        self.batch, self.row, self.batches = batches_by_degree(geoms)

    def points(self, k, s) -> np.ndarray:
        """``(N, 2)``: the point at arc length ``s`` (clipped) of primitive ``k``, each."""
        s = np.clip(s, 0.0, self.length[k])
        out = np.empty((k.size, 2))
        kind = self.kind[k]
        sel = np.flatnonzero(kind == _LINE)
        if sel.size:
            kk = k[sel]
            L = self.length[kk]
            t = np.where(L > 0.0, s[sel] / np.where(L > 0.0, L, 1.0), s[sel])[:, None]
            out[sel] = (1.0 - t) * self.p0[kk] + t * self.p1[kk]
        sel = np.flatnonzero(kind == _ARC)
        if sel.size:
            kk, A = k[sel], self.arcs
            L = self.length[kk]
            phi = np.where(L > 0.0, A.th0[kk] + A.sign[kk] * A.abs_sweep[kk]
                           * (s[sel] / np.where(L > 0.0, L, 1.0)), A.th0[kk])
            out[sel, 0] = A.cx[kk] + A.R[kk] * np.cos(phi)
            out[sel, 1] = A.cy[kk] + A.R[kk] * np.sin(phi)
        sel = np.flatnonzero(kind == _CURVE)
        for b, batch in enumerate(self.batches):
            rows = sel[self.batch[k[sel]] == b]
            if rows.size:
                r = self.row[k[rows]]
                out[rows] = batch.at("P", r, batch.t_of_s(r, s[rows]))
        for i in np.unique(k[sel[self.batch[k[sel]] < 0]]):
            rows = np.flatnonzero(k == i)
            out[rows] = np.asarray(self.geoms[i].point(s[rows])).reshape(-1, 2)
        return out


class _Distances:
    """Upper bounds of the distances from points to primitives (``targets``):
    lines and arcs exactly (closed form); the other curves by their samples
    every ``h`` of arc length, all in one k-d tree: for each of the
    :data:`CURVE_NEIGHBOURS` nearest samples, the distance to the chords
    beside it on its curve plus the chords' largest gap to that curve,
    ``kappa ds^2 / 8`` (``|p''| = kappa`` by arc length): an upper bound of the
    distance to the curves, within that gap of it where the nearest point
    lies on those chords."""

    def __init__(self, targets: _Primitives, h: float):
        self.t = targets
        self.h = h
        self._sampled: dict = {}
        self._trees: dict = {}
        self._all = None

    def sampled(self, j: int):
        """``(s, points, gap)`` of the curve ``j`` sampled every ``h`` at most."""
        if j not in self._sampled:
            g = self.t.geoms[j]
            s = np.linspace(0.0, g.length, max(2, int(math.ceil(g.length / self.h)) + 1))
            q = _points_between(g, 0.0, g.length, s.size)
            step = s[1] - s[0] + 2.0 * ARC_LENGTH_REL_TOL * g.length
            self._sampled[j] = (s, q, _curvature_cap(g) * step * step / 8.0)
        return self._sampled[j]

    def tree(self, j: int):
        """A k-d tree of the samples of the curve ``j``."""
        from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
        if j not in self._trees:
            self._trees[j] = cKDTree(self.sampled(j)[1])
        return self._trees[j]

    def _every_curve(self):
        """``(points, curve, first, last, gap, tree)``: the samples of every target
        curve, in one array and one k-d tree; per sample its curve's index in
        ``t.curves``; per curve its first and last sample and chord gap."""
        from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
        if self._all is None:
            parts = [self.sampled(int(j)) for j in self.t.curves]
            sizes = np.array([len(q) for _, q, _ in parts])
            last = np.cumsum(sizes) - 1
            Q = np.vstack([q for _, q, _ in parts])
            self._all = (Q, np.repeat(np.arange(sizes.size), sizes), last - sizes + 1, last,
                         np.array([gap for _, _, gap in parts]), cKDTree(Q))
        return self._all

    def to_curves(self, p: np.ndarray) -> np.ndarray:
        """``(N,)``: an upper bound of the distance from each point to the target
        curves (see the class docstring)."""
        Q, curve, first, last, gap, tree = self._every_curve()
        k_near = min(CURVE_NEIGHBOURS, len(Q))
        dk, k = tree.query(p, k=k_near)
        dk, k = dk.reshape(len(p), k_near), k.reshape(len(p), k_near)
        best = dk.min(axis=1)
        px, py = p[:, 0], p[:, 1]
        for col in range(k_near):
            kk = k[:, col]
            c = curve[kk]
            k0 = np.clip(kk - 1, first[c], last[c] - 1)
            k1 = np.clip(kk, first[c], last[c] - 1)
            chord = np.minimum(point_segment_cols(px, py, *Q[k0].T, *Q[k0 + 1].T)[0],
                               point_segment_cols(px, py, *Q[k1].T, *Q[k1 + 1].T)[0])
            best = np.minimum(best, chord + gap[c])
        return best

    def pairs(self, pts: np.ndarray, pi: np.ndarray, pj: np.ndarray) -> np.ndarray:
        """An upper bound of the distance from each point ``pts[pi]`` to primitive
        ``pj``: exact for lines and arcs; for a curve, the bound to every target
        curve (:meth:`to_curves`: no larger than that curve's, so the least
        over a point's pairs is still an upper bound of its distance to them)."""
        t = self.t
        d = np.empty(pi.size)
        kind = t.kind[pj]
        px, py = pts[pi, 0], pts[pi, 1]
        sel = np.flatnonzero(kind == _LINE)
        if sel.size:
            j = pj[sel]
            d[sel] = point_segment_cols(px[sel], py[sel], t.p0[j, 0], t.p0[j, 1],
                                        t.p1[j, 0], t.p1[j, 1])[0]
        sel = np.flatnonzero(kind == _ARC)
        if sel.size:
            d[sel] = _arc_distances(px[sel], py[sel], t.arcs, pj[sel])
        sel = np.flatnonzero(kind == _CURVE)
        if sel.size:
            at = np.unique(pi[sel])               # one bound per point, whatever its curves
            d[sel] = self.to_curves(pts[at])[np.searchsorted(at, pi[sel])]
        return d

    def upper(self, pts: np.ndarray, owner: np.ndarray, local):
        """``(d, line)``: per point, an upper bound of its distance to the
        primitives near its own (``local = (ptr, idx)``: the targets near source
        primitive ``o`` are ``idx[ptr[o]:ptr[o + 1]]``), and the target line it
        is the exact distance to (``-1`` where the least is not a line's);
        points by blocks of about :data:`CHUNK_CELLS` pairs."""
        deg = local[0][owner + 1] - local[0][owner]
        d = np.full(len(pts), math.inf)
        line = np.full(len(pts), -1, np.intp)
        ends = np.cumsum(deg)
        i0 = 0
        while i0 < len(pts):
            i1 = max(i0 + 1, int(np.searchsorted(ends, (ends[i0 - 1] if i0 else 0)
                                                 + CHUNK_CELLS, side="right")))
            i1 = min(i1, len(pts))
            pi, pj, first, n = _expand(owner[i0:i1], local)
            if pi.size:
                dd = self.pairs(pts, pi + i0, pj)
                has = np.flatnonzero(n > 0)
                least = np.minimum.reduceat(dd, first[has])
                d[i0 + has] = least
                # each point's first pair at its least value, if that is a line's
                at = np.where(dd == np.repeat(least, n[has]), np.arange(dd.size), dd.size)
                at = np.minimum.reduceat(at, first[has])
                found = at < dd.size
                j = pj[np.minimum(at, dd.size - 1)]
                line[i0 + has] = np.where(found & (self.t.kind[j] == _LINE), j, -1)
            i0 = i1
        return d, line

    def line_bounds(self, src: "_Primitives", local) -> np.ndarray:
        """Per source primitive, an upper bound of its distance to the targets
        near it at every one of its points: for a line, the least over the
        line targets ``j`` of ``max(d_j(start), d_j(end))`` (the distance to a
        segment, a convex set, is convex along a line: its largest value on
        the line is at an end); ``inf`` for the others."""
        out = np.full(src.length.size, math.inf)
        lines = np.flatnonzero(src.kind == _LINE)
        pi, pj, first, n = _expand(lines, local)
        on_line = self.t.kind[pj] == _LINE
        if not on_line.any():
            return out
        pi, pj = pi[on_line], pj[on_line]
        k = lines[pi]
        far = np.maximum(self.pairs(src.p0, k, pj), self.pairs(src.p1, k, pj))
        at = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
        out[k[at]] = np.minimum.reduceat(far, at)
        return out

    def circular_bounds(self, src: "_Primitives", local) -> np.ndarray:
        """Per source primitive, an upper bound of its distance to the targets
        near it at every one of its points: for an arc or spiral, the least
        over the arc and spiral targets ``j`` turning the same way of the
        distance between the points at the same fraction of the angle of both,
        at most ``|c - c_j| + max(|rho - rho_j|) + max(rho_j) max(|dtheta|)``
        over the two ends (``dtheta`` the difference of the polar angles
        about each one's own centre, wrapped at the start, the end's the
        start's plus that of the sweeps: radius and angle change linearly
        with the fraction on both, and an arc of angle ``x`` is longer than
        its chord); ``inf`` for the others. A controller style's corner arc,
        or a spiral of rounded ends, beside the reference's nearly equal one
        is held by it instead of being sampled."""
        out = np.full(src.length.size, math.inf)
        own = np.flatnonzero(src.circular)
        pi, pj, first, n = _expand(own, local)
        k = own[pi]
        keep = self.t.circular[pj]
        k, pj = k[keep], pj[keep]
        A, B = src.circ, self.t.circ
        keep = np.sign(A[k, 5]) == np.sign(B[pj, 5])
        k, pj = k[keep], pj[keep]
        if not k.size:
            return out
        d0 = np.remainder(A[k, 4] - B[pj, 4] + math.pi, 2.0 * math.pi) - math.pi
        d1 = d0 + A[k, 5] - B[pj, 5]
        bound = (np.hypot(A[k, 0] - B[pj, 0], A[k, 1] - B[pj, 1])
                 + np.maximum(np.abs(A[k, 2] - B[pj, 2]), np.abs(A[k, 3] - B[pj, 3]))
                 + np.maximum(B[pj, 2], B[pj, 3]) * np.maximum(np.abs(d0), np.abs(d1)))
        at = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
        out[k[at]] = np.minimum.reduceat(bound, at)
        return out

    def circular_steps(self, src: "_Primitives", k, pa, pb, local) -> np.ndarray:
        """Per step of a source arc or spiral ``k`` from ``pa`` to ``pb`` (less
        than a quarter turn about its centre ``c``): an upper bound of the
        distance of each point of the step to the targets near ``k``, ``inf``
        where none gives one. For an arc or spiral target ``j`` (centre
        ``c_j``) whose angles hold both ends' polar angles about ``c``: a
        step point at angle ``theta`` is within ``|c - c_j| + |rho(theta) -
        rho_j(theta)|`` of the target's point at that angle about ``c_j``, and
        both polar radii are linear in the angle, so that is largest at an
        end. A corner arc or a rounded-end spiral beside the reference's that
        turns a little more or less (its whole-arc bound,
        :meth:`circular_bounds`, then counts the end's overhang everywhere)
        is held by it instead of being sampled every few ``h``."""
        out = np.full(k.size, math.inf)
        pi, pj, _, _ = _expand(k, local)
        keep = self.t.circular[pj]
        pi, pj = pi[keep], pj[keep]
        if not pi.size:
            return out
        A, B = src.circ[k[pi]], self.t.circ[pj]
        sw = np.abs(B[:, 5])
        ends = []
        for p in (pa, pb):
            vx, vy = p[pi, 0] - A[:, 0], p[pi, 1] - A[:, 1]
            u = np.remainder((np.arctan2(vy, vx) - B[:, 4]) * np.sign(B[:, 5]), 2.0 * math.pi)
            rho_j = B[:, 2] + (B[:, 3] - B[:, 2]) * (u / np.where(sw > 0.0, sw, 1.0))
            ends.append((u, np.abs(np.hypot(vx, vy) - rho_j)))
        (ua, ra), (ub, rb) = ends
        held = (ua <= sw) & (ub <= sw) & (np.abs(ub - ua) < 0.5 * math.pi)
        bound = np.where(held, np.hypot(A[:, 0] - B[:, 0], A[:, 1] - B[:, 1])
                         + np.maximum(ra, rb), math.inf)
        np.minimum.at(out, pi, bound)
        return out

    def exact(self, p: np.ndarray, near: np.ndarray, reach: float) -> float:
        """Distance from one point to the primitives ``near`` within ``reach`` of it
        by their bounding boxes: lines and arcs exactly, other curves by chords
        1/400 of a sample step around their nearest sample."""
        d = math.inf
        for j in near:
            j = int(j)
            g = self.t.geoms[j]
            x0, y0, x1, y1 = g.bbox()
            if p[0] < x0 - reach or p[0] > x1 + reach or p[1] < y0 - reach or p[1] > y1 + reach:
                continue
            if self.t.kind[j] != _CURVE:
                d = min(d, float(self.pairs(p[None], np.zeros(1, np.intp),
                                            np.array([j]))[0]))
                continue
            s = self.sampled(j)[0]
            k = int(self.tree(j).query(p)[1])
            q = _points_between(g, s[max(k - 1, 0)], s[min(k + 1, s.size - 1)], 801)
            d = min(d, float(np.min(point_segment(np.repeat(p[None], len(q) - 1, 0),
                                                  q[:-1], q[1:])[0])))
        return d


def _expand(owner: np.ndarray, local):
    """``(pi, pj, first, n)``: every pair of an item ``pi`` (an index into
    ``owner``) and a target ``pj`` near its source primitive ``owner[pi]``
    (``local = (ptr, idx)``, :meth:`_Distances.upper`), grouped by item;
    ``first`` and ``n``: each item's first pair and count."""
    ptr, idx = local
    n = ptr[owner + 1] - ptr[owner]
    first = np.cumsum(n) - n
    total = int(n.sum())
    pi = np.repeat(np.arange(owner.size), n)
    within = np.arange(total) - np.repeat(first, n)
    return pi, idx[np.repeat(ptr[owner], n) + within], first, n


def _arc_distances(px, py, arcs: PreparedArcs, j) -> np.ndarray:
    """Distances from points ``(px, py)`` to the arcs ``j`` of ``arcs`` (one each):
    radial, ``|rho - R|``, where the point's polar angle is on the arc, else to
    the nearer end point (as :func:`ccopt.geometry.point_arc`)."""
    vx = px - arcs.cx[j]
    vy = py - arcs.cy[j]
    rho = np.hypot(vx, vy)
    radial = in_sweep_prepared(np.arctan2(vy, vx), arcs.th0[j], arcs.sign[j],
                               arcs.abs_sweep[j]) & (rho > 0.0)
    to_end = np.minimum(np.hypot(px - arcs.e0x[j], py - arcs.e0y[j]),
                        np.hypot(px - arcs.e1x[j], py - arcs.e1y[j]))
    return np.where(radial, np.abs(rho - arcs.R[j]), to_end)


def _points_between(g, s0: float, s1: float, n: int) -> np.ndarray:
    return np.asarray(g.point(np.linspace(s0, s1, n))).reshape(-1, 2)


def _box_gaps(a, boxes: np.ndarray) -> np.ndarray:
    """Distances from the boxes ``a`` (``(n, 4)``) to each of ``boxes`` (``(m, 4)``):
    ``(n, m)``, boxes as ``(xmin, ymin, xmax, ymax)`` (0 where they overlap)."""
    a = a[:, None, :]
    dx = np.maximum(np.maximum(a[..., 0] - boxes[:, 2], boxes[:, 0] - a[..., 2]), 0.0)
    dy = np.maximum(np.maximum(a[..., 1] - boxes[:, 3], boxes[:, 1] - a[..., 3]), 0.0)
    return np.hypot(dx, dy)


#: The deviation bound stops refining a primitive's samples once every step's
#: bound is within this share of ``h`` above the largest sampled distance.
BOUND_SLACK_SHARE = 0.125


def _equal_steps(lengths: np.ndarray, h: float):
    """``(owner, s)``: arc lengths every ``h`` at most along each primitive, end
    points included (as ``np.linspace``), with the primitive of each."""
    n = np.maximum(2, np.ceil(lengths / h).astype(np.int64) + 1)
    owner = np.repeat(np.arange(lengths.size), n)
    first = np.cumsum(n) - n
    i = np.arange(owner.size) - np.repeat(first, n)
    last = (n - 1)[owner]
    s = lengths[owner] * (i / last)
    s[i == last] = lengths[owner][i == last]        # the end exactly
    return owner, s


def _along(src: _Primitives, local, dist: _Distances, h: float, coarse_h: float):
    """``(bound, owner, pts, d)``: an upper bound of the distance from the source
    primitives to the targets near each (``local``, :meth:`_Distances.upper`),
    and the samples it rests on (their primitive, points and distance bounds).

    Branch and bound on arc length, every primitive at once: between two
    samples ``ds`` apart the distance is at most ``(d_i + d_i+1 + ds) / 2`` (it
    is 1-Lipschitz; ``ds`` carries twice the arc-length tolerance of curves,
    :data:`ARC_LENGTH_REL_TOL`). Starting every ``coarse_h``, a step is halved
    while that bound exceeds ``BOUND_SLACK_SHARE * h`` plus the largest
    distance sampled so far, so the bound ends within that of the sampled
    maximum and steps far below it are never refined. A line whose
    :meth:`_Distances.line_bounds` is within that already is not refined at
    all (a controller style's line beside the reference's, nearly on it: the
    Lipschitz steps alone would sample it every few ``h``).
    """
    owner, s = _equal_steps(src.length, coarse_h)
    pts = src.points(owner, s)
    d, w = dist.upper(pts, owner, local)
    inner = np.flatnonzero(owner[1:] == owner[:-1])       # consecutive samples on one primitive
    a, b, da, db, k = s[inner], s[inner + 1], d[inner], d[inner + 1], owner[inner]
    wa, wb = w[inner], w[inner + 1]
    pa, pb = pts[inner], pts[inner + 1]           # each step's end points
    slack = 2.0 * ARC_LENGTH_REL_TOL * src.length
    on_line = src.kind == _LINE
    on_circle = src.circular
    least_rho = np.fmin(src.circ[:, 2], src.circ[:, 3])
    all_owner, all_pts, all_d = [owner], [pts], [d]
    top = float(d.max(initial=0.0))
    bound = 0.0
    # a line within the bound's reach all along by its ends, or an arc by the
    # arc it nearly is, needs no samples between
    whole = np.minimum(dist.line_bounds(src, local), dist.circular_bounds(src, local))
    held = whole <= top + BOUND_SLACK_SHARE * h
    if held.any():
        bound = float(whole[held].max())
        live = ~held[k]
        a, b, da, db, k, wa, wb, pa, pb = (v[live] for v in (a, b, da, db, k, wa, wb, pa, pb))
    while a.size:
        step = 0.5 * (da + db + (b - a) + slack[k])
        # on a line, both ends nearest the same target line: no farther from it
        # between them than at an end (the distance to a segment, a convex
        # set, is convex along a line), where the Lipschitz bound would halve
        # a line lying beside its target down to steps of about h
        # (both bounds below carry ``slack`` too: above the rounding of the
        # distances they rest on)
        same = on_line[k] & (wa == wb) & (wa >= 0)
        step = np.where(same, np.minimum(step, np.maximum(da, db) + slack[k]), step)
        # on an arc or spiral, a step of less than a quarter turn beside a
        # target arc or spiral (:meth:`_Distances.circular_steps`)
        turn = np.flatnonzero(on_circle[k] & (b - a < 0.5 * math.pi * least_rho[k]))
        if turn.size:
            kt = k[turn]
            step[turn] = np.minimum(step[turn], slack[kt] + dist.circular_steps(
                src, kt, pa[turn], pb[turn], local))
        mid = 0.5 * (a + b)
        done = (step <= top + BOUND_SLACK_SHARE * h) | (mid <= a) | (mid >= b)
        if done.any():
            bound = max(bound, float(step[done].max()))
        live = ~done
        a, b, da, db, k, mid, wa, wb, pa, pb = (v[live] for v in
                                                (a, b, da, db, k, mid, wa, wb, pa, pb))
        if not a.size:
            break
        pm = src.points(k, mid)
        dm, wm = dist.upper(pm, k, local)
        all_owner.append(k)
        all_pts.append(pm)
        all_d.append(dm)
        top = max(top, float(dm.max()))
        a, b = np.concatenate((a, mid)), np.concatenate((mid, b))
        da, db = np.concatenate((da, dm)), np.concatenate((dm, db))
        wa, wb = np.concatenate((wa, wm)), np.concatenate((wm, wb))
        pa, pb = np.concatenate((pa, pm)), np.concatenate((pm, pb))
        k = np.concatenate((k, k))
    return bound, np.concatenate(all_owner), np.vstack(all_pts), np.concatenate(all_d)


def _near_sets(src_geoms, dst_geoms, coarse_h: float):
    """``(ptr, idx)``: the targets that can hold the nearest point of each source
    primitive (those within the coarse bound of it: its samples' largest
    distance to the targets' samples, plus the sample step), as
    :meth:`_Distances.upper` takes them."""
    from scipy.spatial import cKDTree  # deferred: scipy loads slowly, only this figure needs it
    coarse = cKDTree(_samples(dst_geoms, coarse_h))
    dst_boxes = np.array([g.bbox() for g in dst_geoms], float).reshape(-1, 4)
    src_boxes = np.array([g.bbox() for g in src_geoms], float).reshape(-1, 4)
    lengths = np.array([float(g.length) for g in src_geoms])
    owner, s = _equal_steps(lengths, coarse_h)
    pts = _Primitives(src_geoms).points(owner, s)
    far = coarse.query(pts)[0]
    reach = np.maximum.reduceat(far, np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]]))
    reach = reach + coarse_h
    ptr, idx = [0], []
    rows = max(1, CHUNK_CELLS // max(1, len(dst_geoms)))
    for i in range(0, len(src_geoms), rows):
        gaps = _box_gaps(src_boxes[i:i + rows], dst_boxes)
        for r, near in enumerate(gaps <= reach[i:i + rows, None]):
            hit = np.flatnonzero(near)
            idx.append(hit)
            ptr.append(ptr[-1] + hit.size)
    return np.asarray(ptr, np.intp), np.concatenate(idx).astype(np.intp)


def _one_side(src: ToolPath, dst: ToolPath, h: float):
    """``(estimate, upper bound)`` of the largest distance from the changed contour
    part of ``src`` to ``dst``'s feed path."""
    dst_geoms = [s.geom for s in dst.segments if s.role in FEED_ROLES and _in_plane(s)]
    contour = [s.geom for s in src.segments if s.role in CONTOUR_ROLES and _in_plane(s)]
    src_geoms = [g for g, same in zip(contour, _shared(contour, dst_geoms)) if not same]
    if not src_geoms or not dst_geoms:
        return 0.0, 0.0
    coarse_h = max(50.0 * h, POINT_EPS)
    local = _near_sets(src_geoms, dst_geoms, coarse_h)
    dist = _Distances(_Primitives(dst_geoms), h)
    bound, owner, pts, d = _along(_Primitives(src_geoms), local, dist, h, coarse_h)
    # the five largest samples of each primitive, then the largest of those measured exactly
    order = np.lexsort((-d, owner))
    start = np.flatnonzero(np.r_[True, owner[order][1:] != owner[order][:-1]])
    rank = np.arange(order.size) - np.repeat(start, np.diff(np.r_[start, order.size]))
    best = order[rank < 5]
    best = best[np.argsort(-d[best], kind="stable")][:20]
    ptr, idx = local
    est = 0.0
    for i in best:
        if d[i] <= est:       # min(exact, d) cannot raise the estimate any more
            break
        near = idx[ptr[owner[i]]:ptr[owner[i] + 1]]
        est = max(est, min(dist.exact(pts[i], near, float(d[i]) + h), float(d[i])))
    return est, bound


def max_deviation(path: ToolPath, reference: ToolPath, h: float = 1e-3) -> tuple[float, float]:
    """``(Hausdorff distance, upper bound)`` between the compensated parts of
    ``path`` and ``reference`` (see the module docstring)."""
    a, ba = _one_side(path, reference, h)
    b, bb = _one_side(reference, path, h)
    return max(a, b), max(ba, bb)
