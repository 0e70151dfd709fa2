"""Fault injection on compensated tool paths (issue 16): each function takes a
tool path and returns faulty copies with what the fault must produce.

The geometry here is worked out from the programmed blocks directly (feet on
lines, radial projection on arcs), not with the verifier's kernels:

* ``moved_segments``: a cut segment (compensated or corner) moved toward its
  element by ``d``: a line along its element's normal, an arc concentric with
  its element to a radius ``d`` nearer, a corner arc about its corner point to
  radius ``r - d``;
* ``moved_points``: the end point shared by two cut segments moved by ``d``
  toward its nearest contour point (both segments keep meeting there: a line
  gets the new end, an arc is replaced by the arc through its other end, its
  middle and the new end);
* ``flipped_arcs``: an arc with the same ends swept the other way round;
* ``dropped_segments``: a cut segment left out;
* ``pushed_leads``: where a lead meets the cut (the tool point ``Q`` at ``r``
  from the contour point ``P``), the lead bent through ``Q'`` and back to
  ``Q`` (a lead line ``A -> Q`` becomes ``A -> Q' -> Q``, any other lead gets
  the detour ``Q -> Q' -> Q``): ``Q'`` either alongside the element, ``r - d``
  from a point of it, or just past the end, ``r - d`` out along ``Q - P`` and
  ``d/4`` beyond the end.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, ToolPath

CUT = (Role.COMPENSATED, Role.CORNER)
LEADS = (Role.LEAD_IN, Role.LEAD_OUT)


def xy(p) -> np.ndarray:
    return np.array([float(p[0]), float(p[1])])


def arc_span(block):
    """``(centre, radius, theta0, sweep)`` of an arc block (one turn at most)."""
    c, a, b = xy(block.center), xy(block.start), xy(block.end)
    th0 = math.atan2(*(a - c)[::-1])
    th1 = math.atan2(*(b - c)[::-1])
    ccw = block.motion.value == "ccw"
    gap = ((th1 - th0) if ccw else (th0 - th1)) % (2 * math.pi)
    if gap == 0.0:
        gap = 2 * math.pi
    return c, float(np.hypot(*(a - c))), th0, gap if ccw else -gap


def nearest_on_block(q: np.ndarray, block):
    """``(distance, point)`` from ``q`` to the block's programmed in-plane geometry."""
    if block.motion.is_arc:
        c, R, th0, sw = arc_span(block)
        phi = math.atan2(*(q - c)[::-1])
        along = ((phi - th0) * math.copysign(1.0, sw)) % (2 * math.pi)
        if along <= abs(sw):
            w = c + R * np.array([math.cos(phi), math.sin(phi)])
            return float(np.hypot(*(q - w))), w
        ends = [xy(block.start), xy(block.end)]
    else:
        a, b = xy(block.start), xy(block.end)
        t = b - a
        u = min(max(float((q - a) @ t) / float(t @ t), 0.0), 1.0)
        ends = [a + u * t]
    d = [float(np.hypot(*(q - e))) for e in ends]
    k = int(np.argmin(d))
    return d[k], ends[k]


def nearest_on_contour(q: np.ndarray, blocks):
    best = min((nearest_on_block(q, b) + (b,) for b in blocks), key=lambda t: t[0])
    return best


def with_segments(path: ToolPath, i: int, count: int, segs) -> ToolPath:
    """``path`` with segments ``i .. i+count-1`` replaced by ``segs``."""
    s = list(path.segments)
    s[i:i + count] = segs
    return replace(path, segments=tuple(s))


def arc_through(a: np.ndarray, m: np.ndarray, b: np.ndarray):
    """The arc from ``a`` through ``m`` to ``b`` (a line when they are collinear)."""
    cross = (m[0] - a[0]) * (b[1] - a[1]) - (m[1] - a[1]) * (b[0] - a[0])
    if abs(cross) < 1e-12 * float(np.hypot(*(b - a))) ** 2:
        return Line(tuple(a), tuple(b))
    # circumcentre
    A = np.array([m - a, b - a]) * 2.0
    rhs = np.array([m @ m - a @ a, b @ b - a @ a])
    c = np.linalg.solve(A, rhs)
    R = float(np.hypot(*(a - c)))
    th0 = math.atan2(*(a - c)[::-1])
    th1 = math.atan2(*(b - c)[::-1])
    ccw = cross > 0.0
    gap = ((th1 - th0) if ccw else (th0 - th1)) % (2 * math.pi)
    return Arc(tuple(c), R, th0, gap if ccw else -gap)


def cut_indices(path: ToolPath, contour_lines: set[int]):
    """Cut segments of part moves, with a length."""
    return [i for i, s in enumerate(path.segments) if s.role in CUT and s.length > 0.0
            and s.block is not None and (s.role is Role.CORNER or s.block.source.line in contour_lines)]


# --------------------------------------------------------------------------- injections


def moved_segments(path: ToolPath, d: float, r: float, contour_lines: set[int]):
    """``(name, path, i)``: cut segment ``i`` moved ``d`` toward its element."""
    for i in cut_indices(path, contour_lines):
        s = path.segments[i]
        g, blk = s.geom, s.block
        if s.role is Role.CORNER:
            if not isinstance(g, Arc):
                continue                    # Fagor G137 corner lines: no corner point to move to
            new = Arc(g.center, g.radius - d, g.theta0, g.sweep)
        elif isinstance(g, Line) and not blk.motion.is_arc:
            a, b = xy(blk.start), xy(blk.end)
            t = (b - a) / float(np.hypot(*(b - a)))
            n = np.array([-t[1], t[0]])
            side = math.copysign(1.0, float((xy(g.p0) + xy(g.p1) - 2 * a) @ n))
            shift = -side * d * n
            new = Line(tuple(xy(g.p0) + shift), tuple(xy(g.p1) + shift))
        elif isinstance(g, Arc) and blk.motion.is_arc:
            R_e = arc_span(blk)[1]
            new = Arc(g.center, g.radius + math.copysign(d, R_e - g.radius), g.theta0, g.sweep)
        else:
            raise AssertionError(f"segment {i}: {type(g).__name__} for a {blk.motion.value} block")
        yield f"move segment {i} ({s.role.value}) by {d:g}", with_segments(path, i, 1, [replace(s, geom=new)]), i


def _with_end(seg, end: np.ndarray, at_start: bool):
    g = seg.geom
    if isinstance(g, Line):
        return replace(seg, geom=Line(tuple(end), g.p1) if at_start else Line(g.p0, tuple(end)))
    mid = xy(g.point(0.5 * g.length))
    a, b = (end, xy(g.end)) if at_start else (xy(g.start), end)
    return replace(seg, geom=arc_through(a, mid, b))


def moved_points(path: ToolPath, d: float, contour_lines: set[int], blocks):
    """``(name, path, (i, i+1), nearest distance, its block)``: the point shared by
    cut segments ``i`` and ``i+1`` moved ``d`` toward its nearest contour point."""
    cut = set(cut_indices(path, contour_lines))
    for i in sorted(cut):
        if i + 1 not in cut:
            continue
        s0, s1 = path.segments[i], path.segments[i + 1]
        if not all(isinstance(s.geom, (Line, Arc)) for s in (s0, s1)):
            continue
        X = xy(s0.geom.end)
        dist, w, blk = nearest_on_contour(X, blocks)
        Xn = X + d * (w - X) / dist
        new = [_with_end(s0, Xn, False), _with_end(s1, Xn, True)]
        yield (f"move point {i}/{i + 1} by {d:g}", with_segments(path, i, 2, new), (i, i + 1),
               dist, blk)


def flipped_arcs(path: ToolPath, contour_lines: set[int]):
    for i in cut_indices(path, contour_lines):
        s = path.segments[i]
        g = s.geom
        if isinstance(g, Arc) and abs(g.sweep) < 2 * math.pi:
            flip = Arc(g.center, g.radius, g.theta0, g.sweep - math.copysign(2 * math.pi, g.sweep))
            yield f"flip arc {i} ({s.role.value})", with_segments(path, i, 1, [replace(s, geom=flip)]), i


def dropped_segments(path: ToolPath, contour_lines: set[int], min_length: float):
    for i in cut_indices(path, contour_lines):
        if path.segments[i].length > min_length:
            yield f"drop segment {i}", with_segments(path, i, 1, []), i


def lead_junctions(path: ToolPath, contour_lines: set[int], air_lines: set[int]):
    """``(k, into_cut)``: junctions between a lead (lead-in/out, or a compensated
    move on an air line) and a cut segment: the lead is ``k``, the cut ``k+1``
    (``into_cut``) or ``k-1``."""
    segs = path.segments

    def lead(s):
        return s.length > 0.0 and (s.role in LEADS or (
            s.role is Role.COMPENSATED and s.block is not None and s.block.source.line in air_lines))

    def cut(s):
        return s.role in CUT and s.length > 0.0 and (
            s.role is Role.CORNER or s.block.source.line in contour_lines)

    for k, s in enumerate(segs):
        if not lead(s):
            continue
        if k + 1 < len(segs) and cut(segs[k + 1]):
            yield k, True
        if k > 0 and cut(segs[k - 1]):
            yield k, False


def pushed_leads(path: ToolPath, d: float, radius, contour_lines: set[int],
                 air_lines: set[int], blocks):
    """``(name, path, new segment indices, Q', depth at least)``: the lead bent
    toward the part (see the module docstring); ``radius(block)`` is the cutter
    radius in force for a block."""
    for k, into in lead_junctions(path, contour_lines, air_lines):
        s = path.segments[k]
        Q = xy(s.geom.end if into else s.geom.start)
        dist, P, blk = nearest_on_contour(Q, blocks)
        r = radius(blk)
        assert abs(dist - r) < 1e-9, (k, dist, r)
        # the element's direction into it from P (the contour goes on from P),
        # the way beyond its end, and its normal toward the tool side there
        inward = _into_element(blk, P)
        past = -inward
        at_start = np.hypot(*(P - xy(blk.start))) <= np.hypot(*(P - xy(blk.end)))
        t = inward if at_start else -inward
        n = blk.modal.side * np.array([-t[1], t[0]])
        # (a) alongside: r - d from the element point a little way in from P
        L = _block_length(blk)
        w = _point_along(blk, P, min(r, 0.5 * L))
        Qa = w + (r - d) * (Q - w) / float(np.hypot(*(Q - w)))
        yield (f"push lead {k} alongside by {d:g}",) + _bent(path, k, into, Q, Qa) + (d,)
        # (b) just past the end of the element
        Qb = P + (r - d) * n + 0.25 * d * past
        yield (f"push lead {k} past the end by {d:g}",) + _bent(path, k, into, Q, Qb) + (0.5 * d,)


def _bent(path: ToolPath, k: int, into: bool, Q: np.ndarray, Qn: np.ndarray):
    s = path.segments[k]
    g = s.geom
    if isinstance(g, Line):
        if into:
            new = [replace(s, geom=Line(g.p0, tuple(Qn))), replace(s, geom=Line(tuple(Qn), tuple(Q)))]
        else:
            new = [replace(s, geom=Line(tuple(Q), tuple(Qn))), replace(s, geom=Line(tuple(Qn), g.p1))]
        return with_segments(path, k, 1, new), (k, k + 1), Qn
    spike = [replace(s, geom=Line(tuple(Q), tuple(Qn))), replace(s, geom=Line(tuple(Qn), tuple(Q)))]
    if into:
        return with_segments(path, k, 1, [s] + spike), (k + 1, k + 2), Qn
    return with_segments(path, k, 1, spike + [s]), (k, k + 1), Qn


def _block_length(blk) -> float:
    if blk.motion.is_arc:
        _, R, _, sw = arc_span(blk)
        return R * abs(sw)
    return float(np.hypot(*(xy(blk.end) - xy(blk.start))))


def _into_element(blk, P: np.ndarray) -> np.ndarray:
    """Unit direction from ``P`` (an end of the block) into the block."""
    at_start = np.hypot(*(P - xy(blk.start))) <= np.hypot(*(P - xy(blk.end)))
    if blk.motion.is_arc:
        c, R, th0, sw = arc_span(blk)
        th = th0 if at_start else th0 + sw
        t = math.copysign(1.0, sw) * np.array([-math.sin(th), math.cos(th)])
    else:
        t = xy(blk.end) - xy(blk.start)
        t = t / float(np.hypot(*t))
    return t if at_start else -t


def _point_along(blk, P: np.ndarray, length: float) -> np.ndarray:
    """The block's point ``length`` into it from its end ``P``."""
    at_start = np.hypot(*(P - xy(blk.start))) <= np.hypot(*(P - xy(blk.end)))
    if blk.motion.is_arc:
        c, R, th0, sw = arc_span(blk)
        th = th0 + math.copysign(length / R, sw) if at_start else th0 + sw - math.copysign(length / R, sw)
        return c + R * np.array([math.cos(th), math.sin(th)])
    return P + length * _into_element(blk, P)
