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
which lies inside both). A corner arc far shorter still, between a line and
a curve (:func:`_beside_curve`: where a CAM fillet written with a few decimals
meets its line; or two lines too nearly parallel to intersect), goes too,
the line ending at the next segment's start (or starting at the last one's
end). Nothing else changes: the lines stay on PMAC's path
(the verifier's contact rule wants every chord's tool segment within ``r`` of
it), and every blend is checked against PMAC's path itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ccopt.compare.figures import joins as path_joins
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, ToolPath

#: An absorbed corner arc's apex may lie at most this share of the band inside
#: the corner of its lines (the rest of the band is for the blend).
APEX_SHARE = 0.25
#: The part of the verifier's gouge tolerance by which a line ended at a curve
#: past a tiny corner arc (:func:`_beside_curve`) may come closer to the part
#: than the controller's path: a thousandth, so such a move is never what a
#: certificate turns on (on the tests' generated plates, written with 3-6
#: decimals, it is at most 2.4e-7 mm, against a tolerance of 1e-3 mm).
APPROACH_SHARE = 1e-3
#: Smallest |sin| of the turn between two lines for which their intersection is
#: taken (below, the lines are parallel for this purpose: the arc is kept).
MIN_SIN_TURN = 1e-6


@dataclass
class Chain:
    """What :func:`chain_path` did: the new path, for each of its segments the index
    of the reference segment it came from (``origin``), and the reference indices of
    the corner arcs absorbed (``absorbed``), of which those beside a curve
    (``beside_curve``, :func:`_beside_curve`: not outward corners)."""

    path: ToolPath
    origin: list
    absorbed: set
    beside_curve: set = field(default_factory=set)


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


def _beside_curve(segs, joins, i, band, approach) -> int | None:
    """Whether segment ``i`` is a corner arc so short, between a line and a
    curve (or two lines too nearly parallel for :func:`_intersect`: the
    first), G1 both ends, that the line may end (or start) at the arc's far
    end instead: its chord ``2 r sin(theta/2)`` at most :data:`APEX_SHARE` of
    the band, ``r (1 - cos theta)``, the most the line then comes closer to
    the part (at that end), at most ``approach``, and the line long enough
    to turn by less than ``theta``. Then the side of the line (-1 before, +1
    after), else None.

    A CAM program's tangent fillets written with few decimals leave tiny turns
    where a fillet meets a line; the controller's corner arc there (a
    tenth of a micrometre long, curvature ``1/r``) leaves no room for a blend
    on its side, and a blend that ends on it with its curvature bends into the
    part alongside the line (``(1/r) x^2 / 2`` at ``x`` before the join): no
    blend there can pass the checks. Moving the line's end by the chord
    makes the join a line to the curve, which the smoother blends as any
    other."""
    s = segs[i]
    if s.role is not Role.CORNER or not isinstance(s.geom, Arc) or not 0 < i < len(segs) - 1:
        return None
    if joins.get(i) != "G1" or joins.get(i + 1) != "G1":
        return None
    r, th = s.geom.radius, abs(s.geom.sweep)
    if 2.0 * r * math.sin(min(th, math.pi) / 2.0) > APEX_SHARE * band \
            or r * (1.0 - math.cos(min(th, math.pi))) > approach:
        return None
    before, after = _is_line(segs[i - 1]), _is_line(segs[i + 1])
    if not (before or after) or (before and after and math.sin(th) >= MIN_SIN_TURN):
        return None                 # two curves; two lines that meet (_absorbable)
    # the line turns by about r (1 - cos theta) / its length: no more than the
    # arc did, so its other join gets no sharper turn than the one removed
    line = segs[i - 1] if before else segs[i + 1]
    if r * (1.0 - math.cos(min(th, math.pi))) > th * line.length:
        return None
    return -1 if before else 1


def chain_path(path: ToolPath, band: float, approach: float = 0.0) -> Chain:
    """The path with its short convex corner arcs between two lines absorbed
    (module docstring); ``band``: what the blends may use (program units);
    ``approach``: how much closer to the part a line ended at a curve past a
    tiny corner arc may come (program units; 0: none is)."""
    segs = list(path.segments)
    joins = {i: cls for i, cls, *_ in path_joins(path)}
    ends, corners, beside = {}, set(), set()
    for i in range(len(segs)):
        side = _beside_curve(segs, joins, i, band, approach)
        if side is not None and i - 1 not in corners:
            corners.add(i)
            beside.add(i)
            if side < 0:
                ends[(i - 1, 1)] = np.asarray(segs[i + 1].start, float)
            else:
                ends[(i + 1, 0)] = np.asarray(segs[i - 1].end, float)
            continue
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
    return Chain(new, origin, corners, beside)


def _dwells(path, origin):
    """The reference's dwells on the new segment indices (a dwell before reference
    segment ``d`` goes before the first new segment from ``d`` on)."""
    out = []
    for d, sec, blk in path.dwells:
        k = next((j for j, o in enumerate(origin) if o >= d), len(origin))
        out.append((k, sec, blk))
    return tuple(out)
