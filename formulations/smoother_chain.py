"""Short corner arcs between chords, absorbed into one corner for the smoother.

A CAM program's chorded freeform (``cases/freeform-hsm``) gives PMAC's path a
vertex at every chord end: at a concave one the two offset lines meet in a
tangent break; at a convex one PMAC adds a corner arc of the cutter radius
``r`` turning by the chord angle ``theta`` (a few hundredths of a radian), so
the path is line, short arc, line, short arc, ... Local G2 blends at both ends
of such an arc have a few hundredths of a millimetre to take curvature from 0
to ``1/r`` and back: under jerk limits (``v^3 dkappa/ds <= j``) that is slow.

:func:`chain_path` absorbs such an arc: its two lines are extended to meet at
their corner ``V`` (``r (1/cos(theta/2) - 1)`` outside the arc's apex, at most
:data:`APEX_SHARE` of the band), and the join becomes one line-line corner,
which the smoother blends as a whole with the outward closed form of
:mod:`ccopt_formulations.smoother_joins` (a curve through ``V`` that keeps
outside both lines alongside their chords, hence outside the arc's circle,
which lies inside both). Nothing else changes: the lines stay on PMAC's path
(the verifier's contact rule wants every chord's tool segment within ``r`` of
it), and every blend is checked against PMAC's path itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ccopt.compare.figures import joins as path_joins
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, ToolPath

#: An absorbed corner arc's apex may lie at most this share of the band inside
#: the corner of its lines (the rest of the band is for the blend).
APEX_SHARE = 0.25
#: Smallest |sin| of the turn between two lines for which their intersection is
#: taken (below, the lines are parallel for this purpose: the arc is kept).
MIN_SIN_TURN = 1e-6


@dataclass
class Chain:
    """What :func:`chain_path` did: the new path, for each of its segments the index
    of the reference segment it came from (``origin``), and the reference indices of
    the corner arcs absorbed (``absorbed``)."""

    path: ToolPath
    origin: list
    absorbed: set


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _intersect(p, t, q, u):
    """Intersection of the lines ``p + s t`` and ``q + s u`` (``None`` if parallel)."""
    den = t[0] * u[1] - t[1] * u[0]
    if abs(den) < MIN_SIN_TURN:
        return None
    s = ((q[0] - p[0]) * u[1] - (q[1] - p[1]) * u[0]) / den
    return np.asarray(p, float) + s * np.asarray(t, float)


def _is_line(seg) -> bool:
    return isinstance(seg.geom, Line) and seg.length > 0


def _absorbable(segs, joins, i, band) -> bool:
    """Whether segment ``i`` is a short corner arc between two lines (G1 both ends)."""
    s = segs[i]
    if s.role is not Role.CORNER or not isinstance(s.geom, Arc) or not 0 < i < len(segs) - 1:
        return False
    if joins.get(i) != "G1" or joins.get(i + 1) != "G1":
        return False
    if not (_is_line(segs[i - 1]) and _is_line(segs[i + 1])):
        return False
    th = s.geom.sweep
    return abs(th) < math.pi / 2 and \
        s.geom.radius * (1.0 / math.cos(th / 2.0) - 1.0) <= APEX_SHARE * band


def chain_path(path: ToolPath, band: float) -> Chain:
    """The path with its short convex corner arcs between two lines absorbed
    (module docstring); ``band``: what the blends may use (program units)."""
    segs = list(path.segments)
    joins = {i: cls for i, cls, *_ in path_joins(path)}
    ends, corners = {}, set()
    for i in range(len(segs)):
        if not _absorbable(segs, joins, i, band):
            continue
        a, b = segs[i - 1].geom, segs[i + 1].geom
        V = _intersect(a.p0, _unit(np.subtract(a.p1, a.p0)), b.p0, _unit(np.subtract(b.p1, b.p0)))
        if V is None:
            continue
        corners.add(i)
        ends[(i - 1, 1)] = ends[(i + 1, 0)] = V
    out, origin = [], []
    for i, s in enumerate(segs):
        if i in corners:
            continue
        if (i, 0) in ends or (i, 1) in ends:
            p0 = ends.get((i, 0), s.geom.p0)
            p1 = ends.get((i, 1), s.geom.p1)
            s = replace(s, geom=Line(tuple(map(float, p0)), tuple(map(float, p1))))
        out.append(s)
        origin.append(i)
    new = ToolPath(tuple(out), plane=path.plane, style=path.style, radius=path.radius,
                   dwells=_dwells(path, origin), units=path.units, meta=dict(path.meta))
    return Chain(new, origin, corners)


def _dwells(path, origin):
    """The reference's dwells on the new segment indices (a dwell before reference
    segment ``d`` goes before the first new segment from ``d`` on)."""
    out = []
    for d, sec, blk in path.dwells:
        k = next((j for j, o in enumerate(origin) if o >= d), len(origin))
        out.append((k, sec, blk))
    return tuple(out)
