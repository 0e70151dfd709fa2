"""Lead-ins and lead-outs of a tool path: where they are, and how to replace them.

A *lead-in* is the run of segments from the approach point ``A`` (the start of
the first ``lead-in`` segment) up to the first fully compensated segment, the
*host*, which the tool reaches at its start ``J``; PMAC's outside lead-in
has a corner arc in that run. A *lead-out* is the mirror image: from the end
of the last compensated segment (the host) through corner arcs and
``lead-out`` segments to the departure point ``Q``.

Every blend in :mod:`ccopt.compare` is written for a lead-in only: a lead-out
is handed over *reversed* (:meth:`Lead.geometry`), so the approach point is
``Q``, the host is the last compensated segment travelled backwards and the
free side flips. :func:`splice` puts the blend back the right way round.

Sign convention: ``side = +1`` when the free side of the tool path (away from
the part, where the tool comes from) is on the LEFT of the host's direction
of travel, ``-1`` on the right. It is measured from the geometry (host tool
segment against its programmed element), so radius and side overrides need
no bookkeeping.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ccopt.geometry import Line
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import PathSegment, Role, ToolPath, block_geometry

#: Roles a lead run may contain besides its own (PMAC's outside lead-in arc).
_LEAD_IN_RUN = (Role.LEAD_IN, Role.CORNER)
_LEAD_OUT_RUN = (Role.LEAD_OUT, Role.CORNER)


@dataclass(frozen=True)
class LeadGeometry:
    """A lead seen as a lead-in: reach ``host`` (travelled forward from its
    start) from ``approach``. ``side``: the free side of the host (+1 left).
    ``host_length``: how much of the host a blend may use."""

    approach: tuple[float, float]
    host: object
    side: int
    feed: float | None
    kind: str  # "in" | "out"

    @property
    def host_length(self) -> float:
        return float(self.host.length)


@dataclass(frozen=True)
class Lead:
    """Indices into a tool path: segments ``first..last`` (inclusive) are the
    lead run, ``host`` the compensated segment it joins."""

    kind: str   # "in" | "out"
    first: int
    last: int
    host: int

    def geometry(self, path: ToolPath) -> LeadGeometry:
        segs = path.segments
        host = segs[self.host]
        side = free_side(host)
        if self.kind == "in":
            return LeadGeometry(segs[self.first].start, host.geom, side,
                                segs[self.first].feed, "in")
        return LeadGeometry(segs[self.last].end, host.geom.reversed(), -side,
                            segs[self.last].feed, "out")


def _in_plane(seg: PathSegment) -> bool:
    return seg.length > POINT_EPS


def find_leads(path: ToolPath) -> list[Lead]:
    """Every lead-in and lead-out of ``path`` with a host of positive length,
    in path order."""
    segs = path.segments
    n = len(segs)
    out: list[Lead] = []
    i = 0
    while i < n:
        r = segs[i].role
        if r is Role.LEAD_IN and (i == 0 or segs[i - 1].role is not Role.LEAD_IN):
            j = i
            while j < n and segs[j].role in _LEAD_IN_RUN:
                j += 1
            if j < n and segs[j].role is Role.COMPENSATED and _in_plane(segs[j]):
                out.append(Lead("in", i, j - 1, j))
            i = j
            continue
        if r is Role.LEAD_OUT and (i == 0 or segs[i - 1].role is not Role.LEAD_OUT):
            k = i - 1
            while k >= 0 and segs[k].role is Role.CORNER:
                k -= 1
            m = i
            while m + 1 < n and segs[m + 1].role is Role.LEAD_OUT:
                m += 1
            if k >= 0 and segs[k].role is Role.COMPENSATED and _in_plane(segs[k]):
                out.append(Lead("out", k + 1, m, k))
            i = m + 1
            continue
        i += 1
    return out


#: Violations a change of the leads can never remove where they lie outside them.
LASTING_KINDS = ("gouge", "gap", "side")


def outside_leads(violations, leads: list[Lead]) -> list:
    """The gouge, gap and side ``violations`` (of a path's certificate) on tool
    segments no change of ``leads`` touches: outside every lead's run, host
    and their neighbours (a lead blend replaces the run and at most part of
    the host; :meth:`~ccopt.compare.contract.BlendProblem.check` certifies
    those and their neighbours). Every path that differs from this one only
    at its leads keeps them: the same segment against the same contour."""
    reach: set[int] = set()
    for ld in leads:
        reach.update(range(min(ld.first, ld.host) - 1, max(ld.last, ld.host) + 2))
    return [v for v in violations if v.kind in LASTING_KINDS
            and v.tool_segment is not None and v.tool_segment not in reach]


def free_side(host: PathSegment) -> int:
    """+1 when the tool segment ``host`` lies LEFT of its programmed element
    (so the free side, away from the part, is its left), else -1."""
    g = host.geom
    mid = g.point(0.5 * g.length)
    t = g.tangent(0.5 * g.length)
    if host.block is not None:
        b = host.block
        e = block_geometry(b)
        # the programmed point nearest the tool point: sample the element finely
        s = np.linspace(0.0, e.length, 257)
        pts = e.point(s)
        q = pts[int(np.argmin(np.hypot(*(pts - mid).T)))]
        off = mid - q
        if math.hypot(*off) > POINT_EPS:
            return 1 if (-t[1] * off[0] + t[0] * off[1]) > 0.0 else -1
        side = b.modal.side
        if side:
            return int(side)
    raise ValueError("cannot tell the side of a host segment without its programmed block")


def split_segment(seg: PathSegment, s: float) -> tuple[PathSegment, PathSegment]:
    """Two segments meeting at arc length ``s``; ``w`` interpolated linearly."""
    a, b = seg.geom.split(s)
    L = seg.length
    w = seg.w0 + (seg.w1 - seg.w0) * (s / L if L > 0 else 0.0)
    return replace(seg, geom=a, w1=w), replace(seg, geom=b, w0=w)


def splice(path: ToolPath, lead: Lead, blend_geoms, s_join: float, *, style: str,
           role: Role | None = None, meta: dict | None = None) -> ToolPath:
    """``path`` with ``lead`` replaced by ``blend_geoms``, which run from the
    approach point to the host at arc length ``s_join`` as given by
    :meth:`Lead.geometry` (so, for a lead-out, *backwards*).

    The blend segments take the lead run's role, block and feed; ``w`` runs
    linearly over them by length. ``meta["joins"]`` lists the segment
    boundaries the blend made (index of the segment after each boundary).
    """
    segs = list(path.segments)
    host = segs[lead.host]
    geoms = [g for g in blend_geoms if g.length > POINT_EPS]
    if lead.kind == "in":
        src = segs[lead.first]
        if s_join > POINT_EPS:
            _, rest = split_segment(host, s_join)
        else:
            rest = host
        w_start, w_end = src.w0, rest.w0
        new = _blend_segments(geoms, src, role or Role.LEAD_IN, w_start, w_end)
        i0, i1 = lead.first, lead.host + 1
        repl = new + [rest]
        joins = list(range(i0 + 1, i0 + len(new) + 1))
    else:
        src = segs[lead.last]
        L = host.length
        if s_join > POINT_EPS:
            keep, _ = split_segment(host, L - s_join)
        else:
            keep = host
        geoms = [g.reversed() for g in reversed(geoms)]
        new = _blend_segments(geoms, src, role or Role.LEAD_OUT, keep.w1, src.w1)
        i0, i1 = lead.host, lead.last + 1
        repl = [keep] + new
        joins = list(range(i0 + 1, i0 + len(new) + 1))
    out = replace_range(path, i0, i1, repl, style=style)
    m = dict(out.meta)
    m["joins"] = sorted(set(m.get("joins", [])) | set(joins))
    if meta:
        m.update(meta)
    return replace(out, meta=m)


def _blend_segments(geoms, src: PathSegment, role: Role, w0: float, w1: float):
    total = sum(g.length for g in geoms) or 1.0
    out, acc = [], 0.0
    for g in geoms:
        a = w0 + (w1 - w0) * acc / total
        acc += g.length
        b = w0 + (w1 - w0) * acc / total
        out.append(PathSegment(g, role, src.block, a, b, src.feed))
    return out


def replace_range(path: ToolPath, i0: int, i1: int, new_segments, *, style: str) -> ToolPath:
    """``path`` with ``segments[i0:i1]`` replaced; dwells and recorded joins
    after the range move with it (a dwell inside the range goes to its start)."""
    segs = list(path.segments)
    shift = len(new_segments) - (i1 - i0)
    dwells = []
    for d, sec, blk in path.dwells:
        if d <= i0:
            dwells.append((d, sec, blk))
        elif d >= i1:
            dwells.append((d + shift, sec, blk))
        else:
            dwells.append((i0, sec, blk))
    meta = dict(path.meta)
    if "joins" in meta:
        meta["joins"] = [j if j <= i0 else j + shift for j in meta["joins"] if not i0 < j < i1]
    return ToolPath(tuple(segs[:i0] + list(new_segments) + segs[i1:]), plane=path.plane,
                    style=style, radius=path.radius, dwells=tuple(dwells), units=path.units,
                    meta=meta)


def lead_joins(path: ToolPath) -> list[int]:
    """Segment boundaries made by the leads of ``path``: the recorded
    ``meta["joins"]`` if a blend recorded them, else every boundary inside a
    lead run and between the run and its host."""
    if "joins" in path.meta:
        return list(path.meta["joins"])
    out: list[int] = []
    for ld in find_leads(path):
        if ld.kind == "in":
            out += list(range(ld.first + 1, ld.host + 1))
        else:
            out += list(range(ld.host + 1, ld.last + 1))
    return sorted(set(out))


def straight_line(a, b) -> Line:
    return Line((float(a[0]), float(a[1])), (float(b[0]), float(b[1])))
