"""No gouge: the smallest distance from the tool path to every contour element.

For every tool segment and every contour element the broad phase
(:func:`~ccopt.verify.distance.candidate_pairs`) says could be within reach (required clearance plus a
margin), the distance is computed:

- exactly for line/arc pairs, by the closed-form kernels of
  :mod:`ccopt.geometry.distance` (one vectorised call for all pairs);
- as a certified lower bound for pairs with a spiral or curve
  (:mod:`ccopt.verify.distance`), tight to a fraction of ``eps``.

Open ends (:data:`ccopt.verify.decisions.OPEN_END_EXEMPTION`): for an
element where the contour stops, tool points whose nearest point on the
element is that end are not counted. The exempt region is convex (a closed
half-plane for a line, a closed wedge about the centre for an arc), so the
tool segment minus the region is at most a few pieces of line or arc, cut
where the segment crosses the region's boundary lines; their exact distances
replace the pair's. This is done only for pairs whose element has an open
end (a few per lead-in and lead-out), all of them at once by
:mod:`ccopt.verify.open_ends` (the functions here do it pair by pair, with the
same figures).

A pair is a gouge when its distance is below the element's clearance minus
``eps``; the depth is ``clearance - distance``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import Arc, Line, distance, pair_distance
from ccopt.geometry.angles import TWO_PI, angle_along, sweep_sign
from ccopt.geometry.columns import put_rows, take_rows, used_rows
from ccopt.tolerances import VERIFY_CERTIFIED_GAP
from ccopt.verify import decisions
from ccopt.verify.distance import candidate_pairs, min_distance
from ccopt.verify.distance.certified_batch import (
    batchable_by_class, batchable_class, min_distance_indexed,
)
from ccopt.verify.contour import Contour
from ccopt.verify.end_clip import BOUNDARY_REL, points_dot
from ccopt.verify.open_ends import (
    OPEN_END_TAPER_SLOPE, TAPER_ARC_PIECES, TAPER_ARC_ROUNDS, TAPER_ARC_TOL, open_end_distances,
)
from ccopt.verify.segments import KIND_ARC, KIND_LINE, Packed


@dataclass(frozen=True, eq=False)
class PairDistances:
    """Distances of every near (tool segment, contour element) pair.

    ``tool``, ``elem``: indices; ``d``: distance (exact) or certified lower
    bound; ``ub``: a distance actually realised (equal to ``d`` when exact);
    ``wt``, ``we``: witness points on the tool segment and the element;
    ``exact``: True for closed-form pairs; ``required``: the distance the
    pair must keep, the element's clearance or, when the tool segment was made
    with a smaller radius (a later pass of the same contour with another
    tool or offset), that radius; ``margin``: ``d - required``;
    ``counted``: the tool segment was made with compensation in force
    (:data:`ccopt.verify.decisions.GOUGE_ONLY_WHILE_COMPENSATED`);
    ``tapered``: the margin comes from the part of the tool segment past an
    open end, by its tapered distance (:data:`ccopt.verify.decisions.OPEN_END_TAPER`),
    not from ``d`` (which is then the distance of the rest, ``inf`` if none).
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
    tapered: np.ndarray
    required: np.ndarray

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


def in_regions(regions, q: np.ndarray, margin=0.0) -> np.ndarray:
    """Points ``q`` inside one of the closed ``regions`` by at least ``margin``."""
    q = np.atleast_2d(q)
    # one margin for all points or one per point, as the subtraction broadcasts
    room = BOUNDARY_REL * (1.0 + np.abs(q).max(axis=1)) - np.asarray(margin, float)
    out = np.zeros(q.shape[0], bool)
    for reg in regions:
        ins = None
        for n, c in reg:
            side = points_dot(q, n) - c <= room
            ins = side if ins is None else ins & side
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


def clip_pieces(g, regions, inside: bool = False) -> list:
    """The pieces (lines/arcs) of ``g`` outside the closed ``regions`` (with
    ``inside``: the pieces inside them)."""
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
        if bool(in_regions(regions, mid)[0]) == inside:
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


def tapered_pair(tool_geom, regions, tapers):
    """``(f, wt, we)``: the smallest tapered distance (:func:`tapered_distance`)
    of the part of ``tool_geom`` inside each region (one :class:`EndTaper`
    per region), its tool point and the end point; ``f = inf`` when no part
    of it is inside."""
    if tool_geom.length == 0.0:
        return _tapered_point(np.asarray(tool_geom.start, float), regions, tapers)
    best = (math.inf, None, None)
    for reg, taper in zip(regions, tapers):
        for piece in clip_pieces(tool_geom, [reg], inside=True):
            f, wt = tapered_distance(piece, taper)
            if f < best[0]:
                best = (f, wt, tuple(map(float, taper.point)))
    return best


# --------------------------------------------------------------------------- the taper


@dataclass(frozen=True)
class EndTaper:
    """An open end with its taper (:data:`ccopt.verify.decisions.OPEN_END_TAPER`):
    the end ``point`` P, the unit direction ``past`` leading away from the
    element (its tangent there, continued), and the unit normal ``tool_side``
    towards the programmed side of compensation. A tool point ``q`` past the
    end by ``s = past . (q - P)`` counts by ``|q - P| + s`` against the
    clearance: the clearance asked of it shrinks by one unit per unit past
    the end, from the full clearance at the end's normal line."""

    point: np.ndarray
    past: np.ndarray
    tool_side: np.ndarray


def end_tapers(contour: Contour, j: int) -> list[EndTaper]:
    """The tapers of element ``j``'s open ends, in :func:`exempt_regions`' order."""
    A = contour.elements.arr
    kind = int(A.kind[j])
    ends = [e for e, is_open in ((0, contour.open_start[j]), (1, contour.open_end[j]))
            if is_open]
    out = []
    for e in ends:
        if kind == KIND_LINE:
            d = A.p1[j] - A.p0[j]
            t = d / math.hypot(*d)
            P = A.p0[j] if e == 0 else A.p1[j]
        else:
            sw = float(A.sweep[j])
            th = float(A.theta0[j]) + (0.0 if e == 0 else sw)
            sg = sweep_sign(sw)
            t = np.array([-sg * math.sin(th), sg * math.cos(th)])
            P = A.center[j] + float(A.radius[j]) * np.array([math.cos(th), math.sin(th)])
        left = np.array([-t[1], t[0]])
        out.append(EndTaper(np.asarray(P, float), -t if e == 0 else t,
                            float(contour.side[j]) * left))
    return out


def _on_end_normal(piece, taper: EndTaper) -> bool:
    """A line piece running along the end's normal on the tool side (the tool
    centre going straight back onto the end point, Fagor's cancellation in
    place, rule 4): not tapered, as before the taper."""
    if not isinstance(piece, Line):
        return False
    pts = np.array([piece.p0, piece.p1], float) - taper.point
    slack = BOUNDARY_REL * (1.0 + float(np.abs(np.asarray(piece.p0)).max())
                            + float(np.abs(np.asarray(piece.p1)).max()))
    return bool((np.abs(points_dot(pts, taper.past)) <= slack).all()
                and (points_dot(pts, taper.tool_side) >= -slack).all())


def tapered_distance(piece, taper: EndTaper):
    """``(min over the piece of |q - P| + s(q), witness q)`` for a line or arc
    ``piece`` lying past the open end (``inf`` for a piece along the end's
    normal on the tool side). Exact for lines (the function is convex along a
    line: its stationary point in closed form); for arcs a Lipschitz
    branch-and-bound within :data:`TAPER_ARC_TOL` of the minimum, from below."""
    if _on_end_normal(piece, taper):
        return math.inf, None
    if isinstance(piece, Line):
        return _tapered_line(piece, taper)
    return _tapered_arc(piece, taper)


def _taper_f(q: np.ndarray, taper: EndTaper) -> np.ndarray:
    w = np.atleast_2d(q) - taper.point
    return np.hypot(w[:, 0], w[:, 1]) + OPEN_END_TAPER_SLOPE * points_dot(w, taper.past)


def _tapered_line(piece: Line, taper: EndTaper):
    a = np.asarray(piece.p0, float)
    d = np.asarray(piece.p1, float) - a
    L = math.hypot(*d)
    cands = [0.0, L]
    if L > 0.0:
        e = d / L
        w0 = a - taper.point
        p = float(w0 @ e)
        m = math.hypot(*(w0 - p * e))
        c = -OPEN_END_TAPER_SLOPE * float(taper.past @ e)
        if abs(c) < 1.0:
            # d/du (|w0 + u e| + k past.(w0 + u e)) = 0
            cands.append(min(max(c * m / math.sqrt(1.0 - c * c) - p, 0.0), L))
        pts = a + np.outer(np.asarray(cands) / L, d)
    else:
        pts = a[None, :]
    f = _taper_f(pts, taper)
    k = int(np.argmin(f))
    return float(f[k]), (float(pts[k, 0]), float(pts[k, 1]))


def _tapered_arc(piece: Arc, taper: EndTaper):
    """Branch and bound: |q - P| + s(q) changes by at most (1 + slope) per unit
    of arc length, so over a piece of length l it is at least the mean of its
    end values minus (1 + slope) l / 2."""
    lip = 1.0 + OPEN_END_TAPER_SLOPE
    c, R = np.asarray(piece.center, float), float(piece.radius)
    theta0, sweep = piece.theta0, piece.sweep

    def at(th):
        return c + R * np.stack((np.cos(th), np.sin(th)), axis=1)

    u0 = np.linspace(0.0, 1.0, TAPER_ARC_PIECES + 1)
    a, b = u0[:-1], u0[1:]
    best, wit = math.inf, None
    lb_out = math.inf
    for _ in range(TAPER_ARC_ROUNDS):
        ta, tb = theta0 + sweep * a, theta0 + sweep * b
        fa, fb = _taper_f(at(ta), taper), _taper_f(at(tb), taper)
        low = min(fa.min(), fb.min())
        if low < best:
            best = float(low)
            # the first smallest of the starts, then of the ends
            k = int(np.argmin(fa)) if fa.min() <= fb.min() else int(np.argmin(fb)) + fa.size
            th = ta[k] if k < fa.size else tb[k - fa.size]
            wit = tuple(map(float, at(np.array([th]))[0]))
        lb = 0.5 * (fa + fb) - 0.5 * lip * R * np.abs(sweep) * (b - a)
        keep = lb < best - TAPER_ARC_TOL
        if not keep.any():
            break
        a, b = a[keep], b[keep]
        mid = 0.5 * (a + b)
        a, b = np.concatenate((a, mid)), np.concatenate((mid, b))
    else:
        lb_out = float(lb[keep].min())
    return min(best, lb_out), wit


def _tapered_point(q: np.ndarray, regions, tapers):
    best = (math.inf, None, None)
    for reg, taper in zip(regions, tapers):
        if in_regions([reg], q)[0]:
            d = float(_taper_f(q, taper)[0])
            if d < best[0]:
                best = (d, (float(q[0]), float(q[1])), tuple(map(float, taper.point)))
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


#: Exact pairs per call of the vectorised kernel: its temporaries (a dozen
#: arrays per pair) stay a few tens of MB on paths with millions of candidate
#: pairs, instead of hundreds (issue 17: export of 20,000 blocks under 300 MB).
PAIR_CHUNK = 1 << 16


def pair_distances(tool: Packed, contour: Contour, eps: float,
                   counted: np.ndarray | None = None,
                   tool_radius: np.ndarray | None = None) -> PairDistances:
    """Distances of every tool segment to every contour element within reach.

    ``counted``: per tool segment, whether its pairs count as gouges (all by
    default). ``tool_radius``: per tool segment, the cutter radius it was made
    with (``inf`` where unknown; default: unknown everywhere): a pair asks the
    smaller of it and the element's clearance, so each pass of a program that
    runs one contour with several radii is held to its own radius (a finishing
    pass at r = 3 is no gouge of the roughing pass's r = 5 elements).
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
    sel = np.flatnonzero(exact)
    every = sel.size == n          # no spiral or curve: chunks are slices
    for lo in range(0, sel.size, PAIR_CHUNK):
        part = slice(lo, lo + PAIR_CHUNK) if every else sel[lo:lo + PAIR_CHUNK]
        got = pair_distance(tool.arr, it[part], E.arr, je[part])
        d[part] = got[0]
        put_rows(wt, part, got[1])
        put_rows(we, part, got[2])
    ub = d.copy()
    tol = VERIFY_CERTIFIED_GAP * eps
    open_elem = contour.open_start | contour.open_end
    _certified_pairs(tool, contour, it, je, np.flatnonzero(~exact), reach, tol, (d, ub, wt, we))
    # open ends for exact pairs: recompute without the exempt part of the tool
    # segment (d), and the part past an open end by its tapered distance (f)
    f = d.copy()
    tapered = np.zeros(n, bool)
    _open_ends(tool, contour, it, je, np.flatnonzero(exact & open_elem[je]),
               (d, ub, f, wt, we, tapered))
    keep = np.isfinite(f) & (f <= reach[je])
    required = contour.clearance[je]
    if tool_radius is not None:
        required = np.minimum(required, np.asarray(tool_radius, float)[it])
    margin = f - required
    cnt = np.ones(n, bool) if counted is None else np.asarray(counted, bool)[it]
    at = np.flatnonzero(keep)
    return PairDistances(it[at], je[at], d[at], ub[at], take_rows(wt, at), take_rows(we, at),
                         exact[at], margin[at], cnt[at], reach, tapered[at], required[at])


def _open_ends(tool: Packed, contour: Contour, it, je, pairs, out) -> None:
    """The open-end exemption and taper of the ``pairs`` (exact, their element
    with an open end), written into ``out = (d, ub, f, wt, we, tapered)``:
    :func:`clipped_distance` and :func:`tapered_pair` of each pair, all pairs
    with a tool segment of positive length at once
    (:func:`~ccopt.verify.open_ends.open_end_distances`), the others (a tool
    point) one by one."""
    if not pairs.size:
        return
    d, ub, f, wt, we, tapered = out
    E = contour.elements
    j = je[pairs]
    got = open_end_distances(tool, E, it[pairs], j, contour.open_start[j], contour.open_end[j],
                             contour.side[j])
    q = pairs[got.done]
    d[q] = ub[q] = f[q] = got.d[got.done]
    has = got.done & np.isfinite(got.d)
    put_rows(wt, pairs[has], got.wt[has])
    put_rows(we, pairs[has], got.we[has])
    if decisions.OPEN_END_TAPER:
        under = got.done & (got.f < got.d)
        f[pairs[under]], tapered[pairs[under]] = got.f[under], True
        put_rows(wt, pairs[under], got.wf[under])
        put_rows(we, pairs[under], got.end[under])
    for q in pairs[~got.done].tolist():
        j = int(je[q])
        regions = exempt_regions(contour, j)
        if not regions:
            continue
        tg = tool.geom(it[q])
        dd, a, b = clipped_distance(tg, E.geom(j), regions)
        d[q] = ub[q] = f[q] = dd
        if a is not None:
            wt[q], we[q] = a, b
        if decisions.OPEN_END_TAPER:
            ff, a, b = tapered_pair(tg, regions, end_tapers(contour, j))
            if ff < dd:
                f[q], tapered[q] = ff, True
                wt[q], we[q] = a, b


def _certified_pairs(tool: Packed, contour: Contour, it, je, pairs, reach, tol: float, out):
    """Certified bounds of the ``pairs`` (indices into ``it``, ``je``) with a
    spiral or curve, written into ``out = (d, ub, wt, we)``: lower bound, upper
    bound and witnesses. Spiral, arc and line pairs go through one vectorised
    branch and bound (:mod:`.certified_batch`, the same bounds as one at a
    time); other curves one by one."""
    d, ub, wt, we = out
    E = contour.elements
    pairs = np.asarray(pairs, np.intp)
    if not pairs.size:
        return
    # each tool segment and element once, though it is in many pairs
    ti, tinv = used_rows(it[pairs], len(tool))
    ej, einv = used_rows(je[pairs], len(E))
    tgs, egs = tool.geoms(ti), E.geoms(ej)
    # the pairs as indices into one list of objects, the curved one first (an
    # exact element only ever has the exemption): no Python work per pair
    objs = tgs + egs
    t_at, e_at = tinv, len(tgs) + einv
    swapped = tool.exact[ti][t_at] & ~E.exact[ej][einv]
    a_at, b_at = np.where(swapped, e_at, t_at), np.where(swapped, t_at, e_at)
    exemption = _exemptions(contour, ej)
    ex_objs = list(exemption.values())
    ex_at = np.full(ej.size, -1, np.intp)
    ex_at[list(exemption)] = np.arange(len(ex_objs))
    ex_at = ex_at[einv]
    ok = _batchable_pairs(tgs, egs, tinv, einv, swapped)
    caps = reach[je[pairs]]
    batch, one = np.flatnonzero(ok), np.flatnonzero(~ok)
    # every pair of spirals, arcs and lines in one vectorised branch and bound,
    # its bounds as arrays
    res = min_distance_indexed(objs, a_at[batch], objs, b_at[batch], tol, caps[batch], ex_objs,
                               ex_at[batch])
    q = pairs[batch]
    d[q], ub[q] = res.lb, res.ub
    has = np.flatnonzero(~np.isinf(res.ub))        # a witness realises a finite ub
    flip = swapped[batch][has][:, None]
    wa, wb = take_rows(res.wa, has), take_rows(res.wb, has)
    put_rows(wt, q[has], np.where(flip, wb, wa))
    put_rows(we, q[has], np.where(flip, wa, wb))
    for m in one.tolist():
        ex = ex_objs[ex_at[m]] if ex_at[m] >= 0 else None
        b = min_distance(objs[a_at[m]], objs[b_at[m]], tol, cap=float(caps[m]), exempt=ex)
        q = pairs[m]
        d[q], ub[q] = b.lb, b.ub
        if b.wa is not None:
            wt[q], we[q] = (b.wb, b.wa) if swapped[m] else (b.wa, b.wb)


def _exemptions(contour: Contour, ej) -> dict:
    """Per element (by its place in ``ej``): the open-end exemption of a line or
    arc element with open ends, as :func:`min_distance` takes it."""
    E = contour.elements
    open_elem = contour.open_start | contour.open_end
    out = {}
    for k in np.flatnonzero(open_elem[ej] & E.exact[ej]):
        regions = exempt_regions(contour, int(ej[k]))
        if regions:
            out[k] = (lambda pts, m, R=regions: in_regions(R, pts, m),
                      lambda pts, R=regions: in_regions(R, pts))
    return out


def _batchable_pairs(tgs, egs, tinv, einv, swapped) -> np.ndarray:
    """:func:`~ccopt.verify.distance.batchable` of each pair ``(a, b)`` (``a`` the
    curved one), from each distinct tool segment's and element's kind."""
    def classes(gs):
        return np.array([batchable_class(g) for g in gs], np.int8).reshape(len(gs))
    tc, ec = classes(tgs)[tinv], classes(egs)[einv]
    return batchable_by_class(np.where(swapped, ec, tc), np.where(swapped, tc, ec))
