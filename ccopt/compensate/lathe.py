"""LinuxCNC's lathe compensation: the controlled point is the imaginary tool tip.

A lathe tool (orientation ``Q`` 1..8 in the tool table, or ``G41.1/G42.1 L<q>``)
compensating in ``G18`` is offset like a mill tool: the *centre* of its nose
radius ``r`` runs at ``r`` from the contour. But the point the machine moves
is the imaginary tip, where the tool's two flat edges would meet: the centre
moved by ``r`` along X and/or Z, by orientation, as LinuxCNC's
``latheorigin_x``/``latheorigin_z`` (``interp_queue.cc``) do to every move it
sends while compensation is on::

    X: -r for Q 1, 2, 6;  +r for Q 3, 4, 8
    Z: -r for Q 2, 3, 7;  +r for Q 1, 4, 5        (Q 9 and 0: no offset)

The entry move ends at the moved point (an entry arc is preceded by a straight
move to its moved start, as LinuxCNC sends), the exit move starts there, and
the moves between are moved whole. :func:`ccopt.toolpath.tool_centre_path`
undoes it for the verifier, which checks the nose centre against the part.
"""
from __future__ import annotations

from ccopt.geometry import Line, translated
from ccopt.program.model import PLANE_AXES
from ccopt.toolpath import TOOL_TIP, PathSegment, Role, ToolPath

_X_MINUS, _X_PLUS = (1, 2, 6), (3, 4, 8)
_Z_MINUS, _Z_PLUS = (2, 3, 7), (1, 4, 5)
_MOVED = (Role.COMPENSATED, Role.CORNER)


def tip_offset(orientation: int, radius: float) -> tuple[float, float]:
    """``(dx, dz)`` from the nose centre to the controlled point (program units)."""
    dx = -radius if orientation in _X_MINUS else radius if orientation in _X_PLUS else 0.0
    dz = -radius if orientation in _Z_MINUS else radius if orientation in _Z_PLUS else 0.0
    return dx, dz


def controlled_point_path(path: ToolPath, radius_override: float | None = None) -> ToolPath:
    """``path`` (nose-centre path in ``G18``) as the controlled point moves,
    where a lathe tool compensates; unchanged otherwise. ``path.meta[TOOL_TIP]``
    records what moved, for :func:`~ccopt.toolpath.tool_centre_path`."""
    if "ZX" not in path.planes:
        return path
    iu, iv, _ = PLANE_AXES["ZX"]         # (u, v) = (Z, X)
    segments: list[PathSegment] = []
    moved: list[tuple[int, str, float, float]] = []
    index_map: list[int] = []
    for seg in path.segments:
        index_map.append(len(segments))
        du, dv = _offset_uv(seg, radius_override, iu, iv) if seg.plane == "ZX" else (0.0, 0.0)
        if (du, dv) == (0.0, 0.0) or seg.role not in (Role.LEAD_IN, Role.LEAD_OUT, *_MOVED):
            segments.append(seg)
            continue
        g = seg.geom
        if seg.role in _MOVED:
            segments.append(_with(seg, translated(g, du, dv)))
            moved.append((len(segments) - 1, "whole", du, dv))
        elif seg.role is Role.LEAD_IN and isinstance(g, Line):
            segments.append(_with(seg, Line(g.p0, (g.p1[0] + du, g.p1[1] + dv))))
            moved.append((len(segments) - 1, "end", du, dv))
        elif seg.role is Role.LEAD_IN:
            start = g.start
            segments.append(PathSegment(Line(start, (start[0] + du, start[1] + dv)), seg.role,
                                        seg.block, seg.w0, seg.w0, seg.feed))
            moved.append((len(segments) - 1, "added", du, dv))
            segments.append(_with(seg, translated(g, du, dv)))
            moved.append((len(segments) - 1, "whole", du, dv))
        else:  # lead-out: LinuxCNC's exit move is straight
            segments.append(_with(seg, Line((g.p0[0] + du, g.p0[1] + dv), g.p1)))
            moved.append((len(segments) - 1, "start", du, dv))
    if not moved:
        return path
    dwells = tuple((index_map[i] if i < len(index_map) else len(segments), t, b)
                   for i, t, b in path.dwells)
    return ToolPath(tuple(segments), plane=path.plane, style=path.style, radius=path.radius,
                    dwells=dwells, units=path.units, meta={**path.meta, TOOL_TIP: tuple(moved)})


def _offset_uv(seg: PathSegment, radius_override, iu: int, iv: int) -> tuple[float, float]:
    modal = seg.block.modal if seg.block is not None else None
    if modal is None or modal.orientation in (0, 9):
        return 0.0, 0.0
    r = radius_override if radius_override is not None else (modal.radius or 0.0)
    dx, dz = tip_offset(modal.orientation, r)
    by_axis = {0: dx, 2: dz}             # machine axis index -> offset
    return by_axis.get(iu, 0.0), by_axis.get(iv, 0.0)


def _with(seg: PathSegment, geom) -> PathSegment:
    return PathSegment(geom, seg.role, seg.block, seg.w0, seg.w1, seg.feed)
