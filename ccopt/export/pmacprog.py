"""PMAC motion program of a tool path: LINEAR / CIRCLE1 / CIRCLE2 / RAPID.

A CIRCLE move whose end lies at another distance from the centre than its
start is PMAC's native spiral (radius changing linearly with angle, PMAC User
Manual, CIRCLE), the same curve as ccopt's :class:`~ccopt.geometry.Spiral`, so
spirals are exported exactly. Centre vectors are incremental from the move
start (PMAC's default ``INC(R)``); feeds are units per second (Isx90 = 1000).
No compensation words (the program is the tool-centre path itself).
"""
from __future__ import annotations

import math

from ccopt.export.gcode import fmt
from ccopt.geometry import Arc, Line, Spiral
from ccopt.program.model import PLANE_AXES
from ccopt.toolpath import ToolPath

NORMAL = {"XY": "NORMAL K-1", "ZX": "NORMAL J-1", "YZ": "NORMAL I-1"}
AXES = "XYZ"
CENTRE = "IJK"


def _pieces(g):
    """PMAC cannot sweep more than one turn in a CIRCLE move: halve until it fits."""
    if abs(g.sweep) <= 2 * math.pi:
        return [g]
    a, b = g.split(g.length / 2)
    return _pieces(a) + _pieces(b)


def write_pmac(path: ToolPath, header: list[str] | None = None, digits: int = 6,
               program_number: int = 1):
    """PMAC text of ``path``; returns ``(text, moves)`` as :func:`write_gcode`
    (spirals are native, so every bound is 0)."""
    iu, iv, iw = PLANE_AXES[path.plane]
    U, V, W = AXES[iu], AXES[iv], AXES[iw]
    CI, CJ = CENTRE[iu], CENTRE[iv]
    lines = [f"; {h}" for h in header or []]
    lines += ["CLOSE", f"OPEN PROG {program_number} CLEAR", NORMAL[path.plane], "ABS"]
    moves: list = []
    mode = None
    feed = None

    def coords(uv, w):
        return f"{U}{fmt(uv[0], digits)} {V}{fmt(uv[1], digits)} {W}{fmt(w, digits)}"

    def emit(idx, new_mode, text, f, geom=None):
        nonlocal mode, feed
        words = []
        if new_mode != mode:
            words.append(new_mode)
            mode = new_mode
        if f is not None and f != feed:
            words.append(f"F{fmt(f, 6)}")
            feed = f
        lines.append(" ".join(words + [text]))
        moves.append((idx, geom, 0.0))

    dwell_at: dict[int, list[float]] = {}
    for idx, seconds, _ in path.dwells:
        dwell_at.setdefault(idx, []).append(seconds)
    if path.segments:
        first = path.segments[0]
        emit(-1, "RAPID", coords(first.start, first.w0), None)
    for idx, seg in enumerate(path.segments):
        for seconds in dwell_at.get(idx, ()):
            lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
        g = seg.geom
        if isinstance(g, Line):
            emit(idx, "RAPID" if seg.feed is None else "LINEAR", coords(g.end, seg.w1), seg.feed, g)
        elif isinstance(g, (Arc, Spiral)):
            total = g.length
            s_acc = 0.0
            for piece in _pieces(g):
                s_acc += piece.length
                w = seg.w0 + (seg.w1 - seg.w0) * min(s_acc / total, 1.0)
                su, sv = round(piece.start[0], digits), round(piece.start[1], digits)
                i, j = piece.center[0] - su, piece.center[1] - sv
                emit(idx, "CIRCLE2" if piece.sweep > 0 else "CIRCLE1",
                     f"{coords(piece.end, w)} {CI}{fmt(i, digits)} {CJ}{fmt(j, digits)}",
                     seg.feed if seg.feed is not None else feed, piece)
        else:
            raise ValueError(f"cannot export a {type(g).__name__} segment to PMAC yet")
    for seconds in dwell_at.get(len(path.segments), ()):
        lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
    lines.append("CLOSE")
    return "\n".join(lines) + "\n", moves
