"""How far an exported program, read back, lies from the computed tool path.

Each written move meant a geometry (the computed segment, or a line or arc
fitted to a spiral or curve within a certified bound); the reader gives back
what the written numbers say. :func:`displacement` bounds the distance
between the two from their defining points; :func:`roundtrip_error` is the
largest displacement plus bound over the moves (program units).

A read-back made from columns (:func:`ccopt.export.readback.readback_path`
of a column path) is measured from its columns (:func:`move_displacements`):
its lines, arcs and spirals against the meant ones row by row, with the same
floating-point operations as :func:`displacement` (``math``'s ``hypot``,
``cos`` and ``sin`` element by element, sums in the same order), so the figure
is the same to the last bit, and no segment object is made for it.
"""
from __future__ import annotations

import math
from itertools import repeat
from operator import attrgetter, itemgetter

import numpy as np

from ccopt.export.bulk import points, polar_points
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.columns import math_each
from ccopt.toolpath import ARC_ROW, LINE_ROW, SegmentColumns, ToolPath

_SOURCE, _MEANT, _BOUND = itemgetter(0), itemgetter(1), itemgetter(2)
_P0, _P1, _CENTER = attrgetter("p0"), attrgetter("p1"), attrgetter("center")
_RADIUS, _THETA0, _SWEEP = attrgetter("radius"), attrgetter("theta0"), attrgetter("sweep")
_RHO0, _RHO1 = attrgetter("rho0"), attrgetter("rho1")
#: Kinds of geometry told apart here (by exact type, as the rows were made)
LINE, ARC, SPIRAL, OTHER, NONE = range(5)
_KIND = {Line: LINE, Arc: ARC, Spiral: SPIRAL, type(None): NONE}


def displacement(meant, got) -> float:
    """Bound on the distance between two lines, or two arcs/spirals about
    nearly the same centre, from their defining points.

    Lines: the larger end point displacement (a segment lies within that of
    the other). Arcs and spirals: centre displacement plus the larger change of
    radius at either end plus the end point displacements.
    """
    dev = max(math.dist(meant.start, got.start), math.dist(meant.end, got.end))
    if isinstance(meant, Line) or isinstance(got, Line):
        if type(meant) is not type(got):
            return math.inf
        return dev
    r_m = (meant.radius, meant.radius) if isinstance(meant, Arc) else (meant.rho0, meant.rho1)
    r_g = (got.radius, got.radius) if isinstance(got, Arc) else (got.rho0, got.rho1)
    if (meant.sweep > 0) != (got.sweep > 0) or abs(abs(meant.sweep) - abs(got.sweep)) > math.pi:
        return math.inf
    dr = max(abs(r_m[0] - r_g[0]), abs(r_m[1] - r_g[1]))
    return dev + math.dist(meant.center, got.center) + dr


def roundtrip_error(back: ToolPath, moves: list) -> float:
    """Largest deviation of the read-back path from the computed one: per move,
    the displacement of the read-back geometry from the geometry the writer
    meant, plus that geometry's certified bound (the arc and line fit).

    ``moves[m] = (source segment, meant geometry, bound)`` as the writers
    return them; a move with source ``-1`` (the writer's own rapid) or no
    meant geometry is not measured."""
    if back.columns is not None:
        # NaN (a move not measured) never wins, as it never would in max()
        return float(np.fmax.reduce(move_displacements(back.columns, moves), initial=0.0))
    worst = 0.0
    for seg, (src, meant, bound) in zip(back.segments, moves):
        if src < 0 or meant is None:
            continue
        worst = max(worst, displacement(meant, seg.geom) + bound)
    return worst


def move_displacements(cols: SegmentColumns, moves: list) -> np.ndarray:
    """Per move, :func:`displacement` of the read-back row (``cols``, one row
    per move) from the meant geometry plus the bound; NaN for a move not
    measured. A line read back as a line, and an arc or spiral as an arc or
    spiral, is done in bulk; the rest (a curve, a line where an arc was meant)
    one by one."""
    n = len(moves)
    src = np.fromiter(map(_SOURCE, moves), np.intp, n)
    meant = list(map(_MEANT, moves))
    bound = np.fromiter(map(_BOUND, moves), float, n)
    meant_kind = np.fromiter(map(_KIND.get, map(type, meant), repeat(OTHER)), np.int8, n)
    used = (src >= 0) & (meant_kind != NONE)
    got_kind = np.where(cols.kind == LINE_ROW, LINE, np.where(cols.kind == ARC_ROW, ARC, OTHER))
    for q, g in cols.objects.items():
        got_kind[q] = _KIND.get(type(g), OTHER)
    lines = np.flatnonzero(used & (meant_kind == LINE) & (got_kind == LINE))
    rounds = np.flatnonzero(used & ((meant_kind == ARC) | (meant_kind == SPIRAL))
                            & ((got_kind == ARC) | (got_kind == SPIRAL)))
    out = np.full(n, np.nan)
    if lines.size:
        out[lines] = _line_displacements([meant[q] for q in lines.tolist()],
                                         cols.geom[lines]) + bound[lines]
    if rounds.size:
        out[rounds] = _round_displacements(_round([meant[q] for q in rounds.tolist()]),
                                           _round_rows(cols, rounds)) + bound[rounds]
    rest = used.copy()
    rest[lines] = rest[rounds] = False
    for q in np.flatnonzero(rest).tolist():
        out[q] = displacement(meant[q], _row_geometry(cols, q)) + bound[q]
    return out


def _line_displacements(meant: list, geom: np.ndarray) -> np.ndarray:
    """:func:`displacement` of lines read back as rows ``(u0, v0, u1, v1, -)``
    from the lines ``meant``: the larger end point distance."""
    k = len(meant)
    ends = (points(map(_P0, meant), k) - geom[:, 0:2], points(map(_P1, meant), k) - geom[:, 2:4])
    # math.dist of two points is the hypot of their differences, bit for bit
    start, end = (math_each(math.hypot, d[:, 0], d[:, 1]) for d in ends)
    # max(a, b) of Python: b only where it is larger
    return np.where(end > start, end, start)


def _round(geoms: list) -> tuple:
    """``(center (k, 2), start radius, end radius, theta0, sweep)`` of arcs
    and spirals (an arc's radius at both ends)."""
    k = len(geoms)
    c = points(map(_CENTER, geoms), k)
    th, sw = (np.fromiter(map(get, geoms), float, k) for get in (_THETA0, _SWEEP))
    r0, r1 = np.empty(k), np.empty(k)
    arcs = [i for i, g in enumerate(geoms) if type(g) is Arc]
    spirals = [i for i, g in enumerate(geoms) if type(g) is Spiral]
    for rows, gets in ((arcs, (_RADIUS, _RADIUS)), (spirals, (_RHO0, _RHO1))):
        picked = list(map(geoms.__getitem__, rows))
        for r, get in zip((r0, r1), gets):
            r[rows] = np.fromiter(map(get, picked), float, len(rows))
    return c, r0, r1, th, sw


def _round_rows(cols: SegmentColumns, rows: np.ndarray) -> tuple:
    """:func:`_round` of rows ``rows`` of ``cols`` (arc rows and spiral objects)."""
    c, r0 = cols.geom[rows, 0:2].copy(), cols.geom[rows, 2].copy()
    r1, th, sw = r0.copy(), cols.geom[rows, 3].copy(), cols.geom[rows, 4].copy()
    objects = np.flatnonzero(cols.kind[rows] != ARC_ROW)
    if objects.size:
        oc, o0, o1, oth, osw = _round([cols.objects[q] for q in rows[objects].tolist()])
        c[objects], r0[objects], r1[objects], th[objects], sw[objects] = oc, o0, o1, oth, osw
    return c, r0, r1, th, sw


def _round_displacements(meant: tuple, got: tuple) -> np.ndarray:
    """:func:`displacement` of arcs and spirals ``got`` from ``meant`` (both as
    :func:`_round` gives them)."""
    (c_m, r0_m, r1_m, th_m, sw_m), (c_g, r0_g, r1_g, th_g, sw_g) = meant, got
    dist = []
    for rm, rg, phi_m, phi_g in ((r0_m, r0_g, th_m, th_g),                   # start
                                 (r1_m, r1_g, th_m + sw_m, th_g + sw_g)):    # end
        xm, ym = polar_points(c_m[:, 0], c_m[:, 1], rm, phi_m)
        xg, yg = polar_points(c_g[:, 0], c_g[:, 1], rg, phi_g)
        dist.append(math_each(math.hypot, xm - xg, ym - yg))
    dev = np.where(dist[1] > dist[0], dist[1], dist[0])
    d0, d1 = np.abs(r0_m - r0_g), np.abs(r1_m - r1_g)
    centres = math_each(math.hypot, c_m[:, 0] - c_g[:, 0], c_m[:, 1] - c_g[:, 1])
    out = dev + centres + np.where(d1 > d0, d1, d0)
    apart = ((sw_m > 0) != (sw_g > 0)) | (np.abs(np.abs(sw_m) - np.abs(sw_g)) > math.pi)
    out[apart] = math.inf
    return out


def _row_geometry(cols: SegmentColumns, q: int):
    """The geometry of row ``q`` as the path's segment would hold it."""
    if cols.kind[q] == LINE_ROW:
        return Line.trusted(*cols.geom[q, :4].tolist())
    if cols.kind[q] == ARC_ROW:
        a, b, c, d, e = cols.geom[q].tolist()
        return Arc((a, b), c, d, e)
    return cols.objects[q]


__all__ = ["displacement", "move_displacements", "roundtrip_error"]
