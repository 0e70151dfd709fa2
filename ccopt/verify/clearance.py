"""No gouge: the smallest distance from the tool path to every contour element.

For every tool segment and every contour element the broad phase
(:mod:`.broadphase`) says could be within reach (required clearance plus a
margin), the distance is computed:

- exactly for line/arc pairs, by the closed-form kernels of
  :mod:`ccopt.geometry.distance` (one vectorised call for all pairs);
- as a certified lower bound for pairs with a spiral or curve
  (:mod:`.certified`), tight to a fraction of ``eps``.

Open ends (:data:`ccopt.verify.decisions.OPEN_END_EXEMPTION`): for an
element where the contour stops, tool points whose nearest point on the
element is that end are not counted. The exempt region is convex (a closed
half-plane for a line, a closed wedge about the centre for an arc), so the
tool segment minus the region is at most a few pieces of line or arc, cut
where the segment crosses the region's boundary lines; their exact distances
replace the pair's. This is done only for pairs whose element has an open
end (a few per lead-in and lead-out).

A pair is a gouge when its distance is below the element's clearance minus
``eps``; the depth is ``clearance - distance``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import Arc, Line, distance, pair_distance
from ccopt.geometry.angles import TWO_PI, angle_along, sweep_sign
from ccopt.tolerances import VERIFY_CERTIFIED_GAP
from ccopt.verify import certified
from ccopt.verify.broadphase import candidate_pairs
from ccopt.verify.contour import Contour
from ccopt.verify.segments import KIND_ARC, KIND_LINE, Packed


@dataclass(frozen=True, eq=False)
class PairDistances:
    """Distances of every near (tool segment, contour element) pair.

    ``tool``, ``elem``: indices; ``d``: distance (exact) or certified lower
    bound; ``ub``: a distance actually realised (equal to ``d`` when exact);
    ``wt``, ``we``: witness points on the tool segment and the element;
    ``exact``: True for closed-form pairs; ``margin``: ``d - clearance``;
    ``counted``: the tool segment was made with compensation in force
    (:data:`ccopt.verify.decisions.GOUGE_ONLY_WHILE_COMPENSATED`).
    Pairs wholly exempted at an open end are left out.
    """

    tool: np.ndarray
    elem: np.ndarray
    d: np.ndarray
    ub: np.ndarray
    wt: np.ndarray
    we: np.ndarray
    exact: np.ndarray
    margin: np.ndarray
    counted: np.ndarray
    reach: np.ndarray

    def __len__(self) -> int:
        return int(self.tool.size)


# --------------------------------------------------------------------------- open ends


def end_regions(E: Packed, j: int, start: bool, end: bool) -> list[list[tuple[np.ndarray, float]]]:
    """Convex regions ``[[(n, c), ...], ...]`` (``n . q <= c`` for all) of the
    points whose nearest point on element ``j`` is its start (``start``) or
    its end (``end``): a closed half-plane behind the end of a line, a closed
    wedge about the centre (polar angles outside the sweep, nearer that end)
    for an arc. Spirals and curves get none."""
    A = E.arr
    kind = int(A.kind[j])
    regions = []
    if kind == KIND_LINE:
        p0, p1 = A.p0[j], A.p1[j]
        d = p1 - p0
        L = math.hypot(*d)
        if L == 0.0:
            return []
        t = d / L
        if start:
            regions.append([(t, float(t @ p0))])
        if end:
            regions.append([(-t, float(-t @ p1))])
        return regions
    if kind != KIND_ARC:
        return []
    c = A.center[j]
    sw = float(A.sweep[j])
    gap = TWO_PI - abs(sw)
    if gap <= 0.0:
        return []
    sg = sweep_sign(sw)
    th0 = float(A.theta0[j])
    th1 = th0 + sw
    half = 0.5 * gap
    wedges = []
    if start:
        wedges.append((th0 - half, th0) if sg > 0 else (th0, th0 + half))
    if end:
        wedges.append((th1, th1 + half) if sg > 0 else (th1 - half, th1))
    for a, b in wedges:
        da = np.array([math.cos(a), math.sin(a)])
        db = np.array([math.cos(b), math.sin(b)])
        n1 = np.array([da[1], -da[0]])          # cross(da, q - c) >= 0
        n2 = np.array([-db[1], db[0]])          # cross(q - c, db) >= 0
        regions.append([(n1, float(n1 @ c)), (n2, float(n2 @ c))])
    return regions


def exempt_regions(contour: Contour, j: int):
    """Regions of tool points exempt from element ``j`` at its open ends."""
    return end_regions(contour.elements, j, bool(contour.open_start[j]),
                       bool(contour.open_end[j]))


#: Points within this (relative to the coordinates) of an exempt region's
#: boundary count as on it: a tool segment laid along the boundary (a lead-in
#: on the normal at the contour's end) must not flicker in and out by rounding.
BOUNDARY_REL = 1e-12


def in_regions(regions, q: np.ndarray, margin=0.0) -> np.ndarray:
    """Points ``q`` inside one of the closed ``regions`` by at least ``margin``."""
    q = np.atleast_2d(q)
    margin = np.broadcast_to(np.asarray(margin, float), (q.shape[0],))
    slack = BOUNDARY_REL * (1.0 + np.abs(q).max(axis=1))
    out = np.zeros(q.shape[0], bool)
    for reg in regions:
        ins = np.ones(q.shape[0], bool)
        for n, c in reg:
            ins &= q @ n - c <= slack - margin
        out |= ins
    return out


def _crossings(g, n: np.ndarray, c: float) -> list[float]:
    """Fractions (0..1 of length) where primitive ``g`` crosses the line ``n . q = c``."""
    if isinstance(g, Line):
        f0 = float(np.dot(n, g.p0)) - c
        f1 = float(np.dot(n, g.p1)) - c
        if f0 == f1:
            return []
        t = f0 / (f0 - f1)
        return [t] if 0.0 <= t <= 1.0 else []
    nn = math.hypot(*n)
    k = (c - float(np.dot(n, g.center))) / (g.radius * nn)
    if abs(k) > 1.0:
        return []
    psi = math.atan2(n[1], n[0])
    acs = math.acos(k)
    out = []
    full = abs(g.sweep)
    for phi in (psi + acs, psi - acs):
        along = float(angle_along(phi, g.theta0, g.sweep))
        if along <= full:
            out.append(along / full if full > 0 else 0.0)
    return out


def _piece(g, u0: float, u1: float):
    if isinstance(g, Line):
        p = np.asarray(g.p0)
        d = np.asarray(g.p1) - p
        return Line(tuple(p + u0 * d), tuple(p + u1 * d))
    return Arc(g.center, g.radius, g.theta0 + g.sweep * u0, g.sweep * (u1 - u0))


def clip_pieces(g, regions) -> list:
    """The pieces (lines/arcs) of ``g`` outside the closed ``regions``."""
    cuts = {0.0, 1.0}
    for reg in regions:
        for n, c in reg:
            cuts.update(_crossings(g, n, c))
    cuts = sorted(cuts)
    L = g.length
    out = []
    for u0, u1 in zip(cuts, cuts[1:]):
        if u1 - u0 <= 0.0:
            continue
        mid = g.point(0.5 * (u0 + u1) * L)
        if not in_regions(regions, mid)[0]:
            out.append(_piece(g, u0, u1))
    return out


def clipped_distance(tool_geom, elem_geom, regions):
    """Exact ``(d, wt, we)`` from the part of ``tool_geom`` outside ``regions``
    to ``elem_geom`` (both lines/arcs); ``d = inf`` when nothing is left."""
    if tool_geom.length == 0.0:
        if in_regions(regions, np.asarray(tool_geom.start))[0]:
            return (math.inf, None, None)
        return distance(tool_geom.start, elem_geom)
    best = (math.inf, None, None)
    for piece in clip_pieces(tool_geom, regions):
        d, wt, we = distance(piece, elem_geom)
        if d < best[0]:
            best = (d, wt, we)
    return best


# --------------------------------------------------------------------------- all pairs


#: The broad phase looks this many ``eps`` beyond an element's clearance ...
REACH_MARGIN_EPS = 10.0
#: ... and at least this far (program units), so a tiny ``eps`` still leaves
#: room for the rounding of the boxes (a few ulps of coordinates up to ~1e6).
REACH_MARGIN_MIN = 1e-9


def reach_of(contour: Contour, eps: float) -> np.ndarray:
    """How far from an element the broad phase looks: its clearance plus a margin."""
    return contour.clearance + max(REACH_MARGIN_EPS * eps, REACH_MARGIN_MIN)


def pair_distances(tool: Packed, contour: Contour, eps: float,
                   counted: np.ndarray | None = None) -> PairDistances:
    """Distances of every tool segment to every contour element within reach.

    ``counted``: per tool segment, whether its pairs count as gouges (all by default).
    """
    # In the plane of compensation only: a tool position counts whatever its
    # out-of-plane coordinate (conservative: a tool above the part is checked
    # as if at depth; a verifier decision, docs/compensation.md section 8.2).
    E = contour.elements
    reach = reach_of(contour, eps)
    it, je = candidate_pairs(tool.bbox, E.bbox, reach)
    n = it.size
    d = np.full(n, np.inf)
    wt = np.zeros((n, 2))
    we = np.zeros((n, 2))
    exact = tool.exact[it] & E.exact[je]
    if exact.any():
        sel = np.flatnonzero(exact)
        d[sel], wt[sel], we[sel] = pair_distance(tool.arr, it[sel], E.arr, je[sel])
    ub = d.copy()
    tol = VERIFY_CERTIFIED_GAP * eps
    open_elem = contour.open_start | contour.open_end
    for q in np.flatnonzero(~exact):
        j = int(je[q])
        tg, eg = tool.geom(it[q]), E.geom(j)
        regions = exempt_regions(contour, j) if open_elem[j] and certified.is_exact(eg) else []
        ex = None
        if regions:
            ex = (lambda pts, m, R=regions: in_regions(R, pts, m),
                  lambda pts, R=regions: in_regions(R, pts))
        if certified.is_exact(tg) and not certified.is_exact(eg):
            b = certified.min_distance(eg, tg, tol, cap=float(reach[j]))
            b = certified.Bound(b.lb, b.ub, b.wb, b.wa, b.converged, b.pieces)
        else:
            b = certified.min_distance(tg, eg, tol, cap=float(reach[j]), exempt=ex)
        d[q], ub[q] = b.lb, b.ub
        if b.wa is not None:
            wt[q], we[q] = b.wa, b.wb
    # open ends for exact pairs: recompute without the exempt part of the tool segment
    for q in np.flatnonzero(exact & open_elem[je]):
        j = int(je[q])
        regions = exempt_regions(contour, j)
        if not regions:
            continue
        dd, a, b = clipped_distance(tool.geom(it[q]), E.geom(j), regions)
        d[q] = ub[q] = dd
        if a is not None:
            wt[q], we[q] = a, b
    keep = np.isfinite(d) & (d <= reach[je])
    margin = d - contour.clearance[je]
    cnt = np.ones(n, bool) if counted is None else np.asarray(counted, bool)[it]
    return PairDistances(it[keep], je[keep], d[keep], ub[keep], wt[keep], we[keep],
                         exact[keep], margin[keep], cnt[keep], reach)
