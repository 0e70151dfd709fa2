"""PMAC motion program of a tool path: LINEAR / CIRCLE1 / CIRCLE2 / RAPID.

A CIRCLE move whose end lies at another distance from the centre than its
start is PMAC's native spiral (radius changing linearly with angle, PMAC User
Manual, CIRCLE), the same curve as ccopt's :class:`~ccopt.geometry.Spiral`, so
spirals are exported exactly. Bezier blend curves become CIRCLE arcs and
LINEAR moves within ``tol`` (:func:`ccopt.export.arcfit.fit_bezier`, certified
bound), as in G-code. Centre vectors are incremental from the move start
(PMAC's default ``INC(R)``); feeds are units per second (Isx90 = 1000). No
compensation words (the program is the tool-centre path itself). Each
segment is written in its own plane: ``NORMAL K-1`` (XY), ``J-1`` (ZX) or
``I-1`` (YZ, docs/pmac.md) first and wherever the plane changes.
"""
from __future__ import annotations

from itertools import repeat
from operator import attrgetter, eq, is_, ne

import numpy as np

from ccopt.errors import ProgramError
from ccopt.export.arcfit import DEFAULT_TOL, fit_located, fit_tolerance
from ccopt.export.bulk import (ARC, LINE, PlainColumns, changes, fmt_many, rounded,
                               run_ends)
from ccopt.export.gcode import bezier_pieces, fmt, run_arcs, written_as_line
from ccopt.export.machine import stand_in
from ccopt.export.text import with_header
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import paused_gc
from ccopt.program.model import PLANE_AXES
from ccopt.toolpath import ToolPath, starts_at_origin

_BLOCK, _PLANE, _PITCH = attrgetter("block"), attrgetter("plane"), attrgetter("per_revolution")
NORMAL = {"XY": "NORMAL K-1", "ZX": "NORMAL J-1", "YZ": "NORMAL I-1"}
AXES = "XYZ"
CENTRE = "IJK"


class _PlaneWords:
    """The axis letters of the current plane's ``(u, v, w)`` and its centre words."""

    def __init__(self, plane: str, digits: int):
        self.digits = digits
        self.at = None                 # the last written (u, v), rounded
        self.set_plane(plane)

    def set_plane(self, plane: str) -> None:
        self.plane = plane
        iu, iv, iw = PLANE_AXES[plane]
        self.letters = (AXES[iu], AXES[iv], AXES[iw])
        self.centres = (CENTRE[iu], CENTRE[iv])

    def coords(self, uv, w) -> str:
        """The axis words of a move's end; it is remembered as the written
        point the next move starts from (in-plane, rounded as written)."""
        (U, V, W), d = self.letters, self.digits
        self.at = (round(uv[0], d), round(uv[1], d))
        return f"{U}{fmt(uv[0], d)} {V}{fmt(uv[1], d)} {W}{fmt(w, d)}"

    def centre(self, i: float, j: float) -> str:
        (CI, CJ), d = self.centres, self.digits
        return f"{CI}{fmt(i, d)} {CJ}{fmt(j, d)}"


def _pieces(g):
    """PMAC cannot sweep more than one turn in a CIRCLE move: halve until it fits."""
    if abs(g.sweep) <= TWO_PI:
        return [g]
    a, b = g.split(g.length / 2)
    return _pieces(a) + _pieces(b)


def _rounded(p, digits: int) -> tuple[float, float]:
    """The in-plane point ``p`` rounded as it is written."""
    return round(p[0], digits), round(p[1], digits)


def _dwells_before(path: ToolPath) -> dict[int, list[float]]:
    """The dwells (seconds) before each segment index, in order."""
    out: dict[int, list[float]] = {}
    for idx, seconds, _ in path.dwells:
        out.setdefault(idx, []).append(seconds)
    return out


def _not_synchronised(seg) -> None:
    """A spindle-synchronised move (``G33``, ``G33.1``, ``G76``) is refused,
    located: PMAC synchronises through an external time base that its motion
    program does not hold."""
    block = seg.block
    if block is not None and block.per_revolution is not None:
        s = block.source
        raise ProgramError("a spindle-synchronised move (G33, G33.1, G76) cannot be written "
                           "as a PMAC motion program (PMAC synchronises through an external "
                           "time base its program does not hold); export G-code; nothing "
                           "written", s.file, s.line, s.col)


class _Writer:
    """The lines of a PMAC program being written, its moves ``(source segment,
    meant geometry, fit bound)``, and the mode and feed they leave in force."""

    def __init__(self, path: ToolPath, program_number: int, digits: int):
        self.lines = ["CLOSE", f"OPEN PROG {program_number} CLEAR", NORMAL[path.plane], "ABS"]
        self.moves: list = []
        self.mode = None
        self.feed = None
        self.axes = _PlaneWords(path.plane, digits)
        self.digits = digits

    def emit(self, idx, new_mode, text, f, geom=None, bound=0.0) -> None:
        words = []
        if new_mode != self.mode:
            words.append(new_mode)
            self.mode = new_mode
        if f is not None and f != self.feed:
            words.append(f"F{fmt(f, 6)}")
            self.feed = f
        self.lines.append(" ".join(words + [text]))
        self.moves.append((idx, geom, bound))

    def circle(self, idx, piece, w, f, bound=0.0) -> None:
        axes, digits = self.axes, self.digits
        su, sv = round(piece.start[0], digits), round(piece.start[1], digits)
        if written_as_line(piece, (axes.at, (su, sv)), _rounded(piece.end, digits), digits):
            self.emit(idx, "RAPID" if f is None else "LINEAR", axes.coords(piece.end, w), f,
                      Line(piece.start, piece.end), bound + piece.length)
            return
        i, j = piece.center[0] - su, piece.center[1] - sv
        # PMAC has no rapid circle: a circle in a rapid segment keeps the last feed
        self.emit(idx, "CIRCLE2" if piece.sweep > 0 else "CIRCLE1",
                  f"{axes.coords(piece.end, w)} {axes.centre(i, j)}",
                  f if f is not None else self.feed, piece, bound)

    def segment(self, idx: int, seg, tol: float) -> None:
        """Write segment ``idx``'s moves (a blend curve fitted within ``tol``)."""
        g = seg.geom
        _not_synchronised(seg)
        if isinstance(g, Line):
            self.emit(idx, "RAPID" if seg.feed is None else "LINEAR",
                      self.axes.coords(g.end, seg.w1), seg.feed, g)
        elif isinstance(g, (Arc, Spiral)):
            total = g.length
            s_acc = 0.0
            for piece in _pieces(g):
                s_acc += piece.length
                self.circle(idx, piece, seg.w0 + (seg.w1 - seg.w0) * min(s_acc / total, 1.0),
                            seg.feed)
        elif isinstance(g, BezierCurve):
            for fp, w in fit_located(seg, bezier_pieces, g, seg.w0, seg.w1, tol):
                if isinstance(fp.geom, Line):
                    self.emit(idx, "RAPID" if seg.feed is None else "LINEAR",
                              self.axes.coords(fp.geom.end, w), seg.feed, fp.geom, fp.bound)
                else:
                    self.circle(idx, fp.geom, w, seg.feed, fp.bound)
        else:
            raise ValueError(f"cannot export a {type(g).__name__} segment to PMAC yet")

    def run(self, cols: PlainColumns, a: int, b: int) -> None:
        """Write segments ``a`` .. ``b - 1``, lines and arcs of at most a turn
        in the current plane, as :meth:`segment` writes them one by one."""
        d = self.digits
        u, v = cols.end[a:b, 0], cols.end[a:b, 1]
        fu, fv, ru, rv = fmt_many(u, d), fmt_many(v, d), rounded(u, d), rounded(v, d)
        # machine coordinates: no shift (x - 0.0 is x, to the bit)
        arcs, starts, as_line = run_arcs(cols, a, b, (ru, rv), self.axes.at, (0.0, 0.0), d)
        rows = arcs + a
        feeds = cols.feeds[a:b]
        w = cols.w1[a:b].copy()
        w0 = cols.w0[rows]
        # an arc's end w as segment() interpolates it over its one piece
        w[arcs] = w0 + (cols.w1[rows] - w0) * np.minimum((0.0 + cols.length[rows]) /
                                                          cols.length[rows], 1.0)
        modes = ["RAPID" if f is None else "LINEAR" for f in feeds]
        U, V, W = self.axes.letters
        texts = [f"{U}{x} {V}{y} {W}{z}" for x, y, z in zip(fu, fv, fmt_many(w, d))]
        circles = ~as_line                  # the arcs written as arcs
        CI, CJ = self.axes.centres
        i = fmt_many(cols.center[rows[circles], 0] - starts[circles, 0], d)
        j = fmt_many(cols.center[rows[circles], 1] - starts[circles, 1], d)
        for k, sweep, ik, jk in zip(arcs[circles].tolist(), cols.sweep[rows[circles]].tolist(),
                                    i, j):
            modes[k] = "CIRCLE2" if sweep > 0 else "CIRCLE1"
            texts[k] = f"{texts[k]} {CI}{ik} {CJ}{jk}"
        self._lines(modes, feeds, texts)
        moves = [(idx, g, 0.0) for idx, g in enumerate(cols.geoms[a:b], a)]
        for k in arcs[as_line].tolist():
            g = cols.geoms[a + k]
            moves[k] = (a + k, Line(g.start, g.end), 0.0 + g.length)
        self.moves += moves
        self.axes.at = (float(ru[-1]), float(rv[-1]))

    def _lines(self, modes: list[str], feeds: list, texts: list[str]) -> None:
        """The lines of moves in ``modes`` at ``feeds`` (``None``: the feed in
        force) saying ``texts``, each with the mode and feed words that change
        (as :meth:`emit` writes them)."""
        words = [""] * len(modes)
        if modes[0] != self.mode:
            words[0] = f"{modes[0]} "
        for k in np.flatnonzero(np.fromiter(map(ne, modes[1:], modes), bool)).tolist():
            words[k + 1] = f"{modes[k + 1]} "
        for k in changes(feeds, self.feed):
            words[k] += f"F{fmt(feeds[k], 6)} "
            self.feed = feeds[k]
        self.mode = modes[-1]
        self.lines += map(str.__add__, words, texts)


def _joins(path: ToolPath, cols: PlainColumns, dwells: dict) -> np.ndarray:
    """Which segments continue a run (:meth:`_Writer.run`) from the one before
    them: a line, or an arc of at most a turn and of finite non-zero length,
    not synchronised, in the same plane, with no dwell before it."""
    segments = path.segments
    n = len(segments)
    arc = cols.kind == ARC
    joins = (cols.kind == LINE) | (arc & (np.abs(cols.sweep) <= TWO_PI) & (cols.length > 0.0)
                                   & np.isfinite(cols.length))
    planes = list(map(_PLANE, segments))
    joins[1:] &= np.fromiter(map(eq, planes[1:], planes), bool, n - 1)
    pitches = map(_PITCH, stand_in(list(map(_BLOCK, segments))))
    joins &= np.fromiter(map(is_, pitches, repeat(None)), bool, n)
    joins[[i for i in dwells if i < n]] = False
    return joins


def write_pmac(path: ToolPath, header: list[str] | None = None, digits: int = 6,
               program_number: int = 1, tol: float | None = None,
               seg_tol: dict[int, float] | None = None):
    """PMAC text of ``path``; returns ``(text, moves)`` as :func:`write_gcode`.

    Spirals are native, so their bound is 0; Bezier curves become arcs and
    lines within ``tol`` (program units; default :data:`DEFAULT_TOL` for the
    path's units), each move with its certified bound; ``seg_tol`` gives some
    segments (by index) a tighter tolerance.
    """
    if tol is None:
        tol = DEFAULT_TOL[path.units]
    seg_tol = seg_tol or {}
    wr = _Writer(path, program_number, digits)
    dwell_at = _dwells_before(path)
    if path.segments and not starts_at_origin(path):
        first = path.segments[0]
        wr.emit(-1, "RAPID", wr.axes.coords(first.start, first.w0), None)
    with paused_gc():       # many small objects, none in a cycle: see paused_gc
        cols = PlainColumns(path)
        ends = run_ends(_joins(path, cols, dwell_at))
        idx = 0
        while idx < len(path.segments):
            seg = path.segments[idx]
            for seconds in dwell_at.get(idx, ()):
                wr.lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
            if seg.plane != wr.axes.plane:
                # a path in several planes: NORMAL before the first move in the next
                wr.lines.append(NORMAL[seg.plane])
                wr.axes.set_plane(seg.plane)
            wr.segment(idx, seg, fit_tolerance(seg_tol.get(idx, tol), digits))
            idx += 1
            if ends[idx - 1] > idx:
                wr.run(cols, idx, ends[idx - 1])
                idx = ends[idx - 1]
    for seconds in dwell_at.get(len(path.segments), ()):
        wr.lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
    wr.lines.append("CLOSE")
    return with_header("\n".join(wr.lines) + "\n", header, "pmac"), wr.moves
