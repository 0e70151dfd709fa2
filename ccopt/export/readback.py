"""An exported program read back as a tool path, move by move on the computed one.

:func:`readback_path` reads the exported text with ccopt's own reader and
gives each move the role and source block of the computed segment it was
written for, keeping what was read back: the geometry, the out-of-plane
``w`` at its ends (program units) and its feed (program units per second).
A read-back whose programmed path is a column path
(:func:`ccopt.toolpath.programmed_path`) becomes one too, made from its
columns (:func:`readback_columns`): no segment object is made unless one is
asked for; :func:`readback_segments` is the same path segment by segment
(the reference, and the road for segments with no block).
"""
from __future__ import annotations

from itertools import repeat
from operator import attrgetter, is_not, itemgetter

import numpy as np

from ccopt.errors import ProgramError
from ccopt.geometry import Arc, Line
from ccopt.program import read_text
from ccopt.toolpath import (FITTED_PIECES, OBJECT_ROW, ROLE_CODE, TOOL_TIP, PathSegment, Role,
                            SegmentColumns, ToolPath, programmed_path)

_SOURCE = itemgetter(0)
_ROLE, _BLOCK, _GEOM, _FEED = (attrgetter(a) for a in ("role", "block", "geom", "feed"))


def readback_path(text: str, dialect: str, original: ToolPath, moves: list, file: str,
                  parameters: dict | None = None) -> ToolPath:
    """Read exported text back and give each move the role and source block of
    the tool-path segment it came from (``moves`` as the writers return it:
    ``(source segment, meant geometry, fit bound)``, source ``-1`` for a move
    of the writer's own, a rapid); ``parameters``: the numbered parameters
    (a parameter file's) the program was read with, so its work offsets read
    back the same."""
    prog = read_text(text, file, dialect, parameters=parameters if dialect == "gcode" else None)
    back = programmed_path(prog)
    if len(back) != len(moves):
        raise ProgramError(f"read-back has {len(back)} moves, {len(moves)} were written", file)
    return readback_columns(back, original, moves, file)


def readback_columns(back: ToolPath, original: ToolPath, moves: list, file: str) -> ToolPath:
    """:func:`readback_path` of the programmed path ``back`` of the text read
    back (one move per written move), made from its columns when it has them
    (else :func:`readback_segments`)."""
    src = np.fromiter(map(_SOURCE, moves), np.intp, len(moves))
    columns = _readback_columns(back, original, src)
    if columns is None:
        return readback_segments(back, original, moves, file)
    written = src >= 0
    exact = _exact_rows(original)
    pieces = np.flatnonzero(written)[~exact[src[written]]]
    return ToolPath.from_columns(columns, style=original.style, radius=original.radius,
                                 dwells=back.dwells, units=original.units,
                                 meta=_meta(file, pieces.tolist(), original, moves),
                                 plane=original.plane)


def readback_segments(back: ToolPath, original: ToolPath, moves: list, file: str) -> ToolPath:
    """:func:`readback_path` of the programmed path ``back`` of the text read
    back, made segment by segment."""
    segs, pieces = [], []
    for m, (seg, (src, _, _)) in enumerate(zip(back.segments, moves)):
        if src < 0:
            segs.append(PathSegment(seg.geom, Role.RAPID, seg.block, seg.w0, seg.w1, None))
        else:
            o = original.segments[src]
            segs.append(PathSegment(seg.geom, o.role, o.block, seg.w0, seg.w1, seg.feed))
            if not isinstance(o.geom, (Line, Arc)):
                pieces.append(m)      # an arc or line fitted to a spiral or blend curve
    return ToolPath(tuple(segs), plane=original.plane, style=original.style,
                    radius=original.radius, dwells=back.dwells, units=original.units,
                    meta=_meta(file, pieces, original, moves))


def _meta(file: str, pieces: list[int], original: ToolPath, moves: list) -> dict:
    """The read-back path's meta: what it is, its fitted pieces
    (:data:`FITTED_PIECES`) and, for a lathe path, its tool-tip moves."""
    meta = {"readback_of": file, FITTED_PIECES: tuple(pieces)}
    if original.meta.get(TOOL_TIP):
        # a lathe path: the read-back moves carry the tool tip as the computed ones
        written = {}
        for m, (src, _, _) in enumerate(moves):
            written.setdefault(src, []).append(m)
        meta[TOOL_TIP] = tuple((m, how, du, dv) for i, how, du, dv in original.meta[TOOL_TIP]
                               for m in written.get(i, ()))
    return meta


def _readback_columns(back: ToolPath, original: ToolPath,
                      src: np.ndarray) -> SegmentColumns | None:
    """The read-back rows of ``back``'s columns, each move ``m`` on the
    computed segment ``src[m]`` (``< 0``: a rapid of the writer's own, on its
    block read back); ``None`` when ``back`` has no columns or a computed
    segment has no block (its plane is then the path's: the reference's)."""
    cols = back.columns
    if cols is None:
        return None
    roles, blocks = _source_rows(original)
    back_blocks = list(map(cols.blocks.__getitem__, cols.block.tolist()))
    # the rapid's block read back, else the computed segment's; a rapid has no feed
    rows = [blocks[s] if s >= 0 else b for s, b in zip(src.tolist(), back_blocks)]
    if not all(map(is_not, rows, repeat(None))):
        return None
    feed = [f if s >= 0 else None for s, f in zip(src.tolist(), map(_FEED, back_blocks))]
    written = src >= 0
    role = np.full(len(src), ROLE_CODE[Role.RAPID], np.int8)
    role[written] = roles[src[written]]
    return SegmentColumns(cols.kind, cols.geom, cols.objects, role,
                          np.arange(len(src), dtype=np.int64), rows, cols.w, feed)


def _source_rows(path: ToolPath) -> tuple[np.ndarray, list]:
    """Each segment's role code and block (from its columns when it has them)."""
    cols = path.columns
    if cols is not None:
        return cols.role, list(map(cols.blocks.__getitem__, cols.block.tolist()))
    segs = path.segments
    roles = np.fromiter(map(ROLE_CODE.__getitem__, map(_ROLE, segs)), np.int8, len(segs))
    return roles, list(map(_BLOCK, segs))


def _exact_rows(path: ToolPath) -> np.ndarray:
    """Whether each segment is a line or an arc (not a spiral or curve, which
    an export writes as fitted pieces)."""
    cols = path.columns
    if cols is not None:
        exact = cols.kind != OBJECT_ROW
        for q, g in cols.objects.items():
            exact[q] = isinstance(g, (Line, Arc))
        return exact
    return np.fromiter((isinstance(g, (Line, Arc)) for g in map(_GEOM, path.segments)), bool,
                       len(path.segments))
