"""ISO/RS274 G-code of a tool path: G0/G1 lines, G2/G3 arcs with I/J/K.

Each segment is written in its own plane: ``G17``/``G18``/``G19`` stands in
the first line and again wherever the plane changes.

The exported program carries no compensation words: it is the tool-centre
path itself. Given the program, it keeps the machine's words and the
program's work coordinates (:mod:`.machine`). Spirals become arcs and Bezier
blend curves arcs and lines within ``tol`` (:mod:`.arcfit`, certified
bound). Feeds are written per minute (G94).
"""
from __future__ import annotations

import math
from itertools import repeat
from operator import attrgetter, eq, is_

import numpy as np

from ccopt.errors import ProgramError
from ccopt.export.arcfit import fit_arcs, fit_bezier, fit_located, fit_tolerance
from ccopt.export.bulk import (ARC, OTHER, PlainColumns, changes, fmt_many, rounded,
                               run_ends)
from ccopt.export.machine import (MachineWords, machine_prefix, stand_in, written_frame,
                                  written_offset)
from ccopt.export.text import with_header
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import math_each, paused_gc
from ccopt.program.model import PLANE_AXES
from ccopt.toolpath import ToolPath, starts_at_origin

PLANE_WORD = {"XY": "G17", "ZX": "G18", "YZ": "G19"}
AXES = "XYZ"
CENTRE = "IJK"

_BLOCK, _PLANE, _PITCH = attrgetter("block"), attrgetter("plane"), attrgetter("per_revolution")
#: Rounding allowance when counting an arc's full turns: a sweep of exactly
#: n full turns (up to rounding) is n turns, written P<n>, not n + 1.
_TURNS_SLACK = 1e-12


def fmt(x: float, digits: int = 6) -> str:
    """A coordinate with ``digits`` decimals, trailing zeros removed."""
    s = f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


#: An arc of less than half a turn whose written end lies within this many
#: units of the last decimal of its written start (:func:`written_as_line`).
SHORT_CHORD_UNITS = 4


def written_as_line(arc, starts, end, digits: int) -> bool:
    """Whether ``arc`` (less than half a turn) must be written as a straight
    move: its written end ``end`` (in-plane, rounded to ``digits``) lies within
    :data:`SHORT_CHORD_UNITS` of the last decimal of one of ``starts`` (the
    written point the reader starts from, and the arc's own start rounded).

    Written as an arc there, the reader (LinuxCNC's and PMAC's rules alike)
    takes an end at the start for a full turn, and an end a rounding step
    behind the start, seen from the rounded centre, for all but a sliver of
    one: a corner arc of 1.8e-7 rad (radius 1.5 mm) after a contour written
    with 6 decimals read back as a full circle. Written as a line, the move
    stays within the arc's length of the arc (the bound the caller adds)."""
    if abs(arc.sweep) >= math.pi:
        return False
    near = SHORT_CHORD_UNITS * 10.0 ** -digits
    return any(p is not None and math.hypot(end[0] - p[0], end[1] - p[1]) <= near
               for p in starts)


def written_as_lines(sweep, ends, before, starts, digits: int) -> np.ndarray:
    """:func:`written_as_line` of many arcs at once: ``sweep`` ``(n,)``, the
    rounded written ``ends`` and ``starts`` ``(n, 2)``, and ``before``
    ``(n, 2)``, the written point the reader starts each from (NaN: none)."""
    near = SHORT_CHORD_UNITS * 10.0 ** -digits

    def within(p) -> np.ndarray:
        return math_each(math.hypot, ends[:, 0] - p[:, 0], ends[:, 1] - p[:, 1]) <= near

    return (np.abs(sweep) < math.pi) & (within(before) | within(starts))


def run_arcs(cols: PlainColumns, a: int, b: int, ends, at, shift, digits: int):
    """The arcs among segments ``a`` .. ``b - 1`` written one after another:
    their places in the run, their written starts ``(k, 2)`` (machine minus
    ``shift``, rounded), and which of them are written as lines
    (:func:`written_as_lines`); ``ends``: the run's rounded written ends
    ``(u, v)``, ``at``: the written point before the run (or None)."""
    (ru, rv), (du, dv) = ends, shift
    arcs = np.flatnonzero(cols.kind[a:b] == ARC)
    rows = arcs + a
    at = at if at is not None else (math.nan, math.nan)
    before = np.column_stack((np.r_[at[0], ru[:-1]], np.r_[at[1], rv[:-1]]))[arcs]
    starts = np.column_stack((rounded(cols.start[rows, 0] - du, digits),
                              rounded(cols.start[rows, 1] - dv, digits)))
    return arcs, starts, written_as_lines(cols.sweep[rows], np.column_stack((ru[arcs], rv[arcs])),
                                          before, starts, digits)


class _Writer:
    def __init__(self, path: ToolPath, digits: int):
        self.path = path
        self.digits = digits
        self.set_plane(path.plane)
        self.lines: list[str] = []
        self.source: list[int] = []   # original segment index of each move line
        self.intended: list = []      # (geometry meant by the line, certified bound)
        self.feed: float | None = None
        self.shift = (0.0, 0.0, 0.0)   # machine minus written (u, v, w) of the next moves
        self.rotated = None            # or the rotated frame they are written in
        self.prefix = ""               # "G53 " for moves written in machine coordinates
        self.at = None                 # the last written (u, v), rounded

    def set_frame(self, block) -> None:
        """Write the next moves in ``block``'s frame (work coordinates, or
        machine coordinates under G53)."""
        off = written_offset(block)
        iu, iv, iw = PLANE_AXES[self.plane]
        self.shift = (off[iu], off[iv], off[iw])
        self.rotated = written_frame(block)
        self.prefix = machine_prefix(block)

    def written(self, u: float, v: float, w: float) -> tuple[float, float, float]:
        """Written (work) coordinates of the machine point ``(u, v, w)`` of the plane."""
        if self.rotated is None:
            du, dv, dw = self.shift
            return (u - du, v - dv, w - dw)
        iu, iv, iw = PLANE_AXES[self.plane]
        p = [0.0, 0.0, 0.0]
        p[iu], p[iv], p[iw] = u, v, w
        q = self.rotated.to_work((p[0], p[1], p[2]))
        return (q[iu], q[iv], q[iw])

    def set_plane(self, plane: str) -> None:
        """Write the coordinates of ``plane`` from now on: its ``(u, v, w)`` axis
        letters and arc-centre words."""
        self.plane = plane
        iu, iv, iw = PLANE_AXES[plane]
        self.u, self.v, self.w = AXES[iu], AXES[iv], AXES[iw]
        self.ci, self.cj = CENTRE[iu], CENTRE[iv]

    def coords(self, uv, w) -> str:
        """The axis words of a move's end; it is remembered as the written
        point the next move starts from (in-plane, rounded as written)."""
        u, v, w = self.written(uv[0], uv[1], w)
        self.at = (round(u, self.digits), round(v, self.digits))
        return (f"{self.u}{fmt(u, self.digits)} {self.v}{fmt(v, self.digits)} "
                f"{self.w}{fmt(w, self.digits)}")

    def feed_word(self, feed: float | None) -> str:
        if feed is None or feed == self.feed:
            return ""
        self.feed = feed
        return f" F{fmt(feed * 60.0, 4)}"

    def move(self, idx: int, text: str, geom=None, bound: float = 0.0) -> None:
        self.lines.append(text)
        self.source.append(idx)
        self.intended.append((geom, bound))

    def line(self, idx: int, g: Line, w1: float, feed, bound: float = 0.0) -> None:
        if feed is None:
            self.move(idx, f"{self.prefix}G0 {self.coords(g.end, w1)}", g, bound)
        else:
            self.move(idx, f"{self.prefix}G1 {self.coords(g.end, w1)}{self.feed_word(feed)}", g,
                      bound)

    def synchronised(self, idx: int, g: Line, w1: float, per_rev: float) -> None:
        """A move synchronised to the spindle: ``G33 ... K`` (per revolution
        along the path, as the reader takes it; F stays as it was)."""
        self.move(idx, f"{self.prefix}G33 {self.coords(g.end, w1)} K{fmt(per_rev, 9)}", g)

    def arc(self, idx: int, arc: Arc, w0: float, w1: float, feed, bound: float = 0.0) -> None:
        s, e = arc.start, arc.end
        word = "G3" if arc.sweep > 0 else "G2"
        # Incremental centre from the *written* start keeps the reader's
        # start and end radii consistent after rounding.
        su, sv, _ = self.written(s[0], s[1], w0)
        su, sv = round(su, self.digits), round(sv, self.digits)
        eu, ev, _ = self.written(e[0], e[1], w1)
        if written_as_line(arc, (self.at, (su, sv)), (round(eu, self.digits),
                                                     round(ev, self.digits)), self.digits):
            self.line(idx, Line(s, e), w1, feed, bound + arc.length)
            return
        cu, cv, _ = self.written(arc.center[0], arc.center[1], w0)
        i, j = cu - su, cv - sv
        turns = max(int(math.ceil(abs(arc.sweep) / TWO_PI - _TURNS_SLACK)) - 1, 0)
        p = f" P{turns + 1}" if turns else ""
        self.move(idx, f"{word} {self.coords(e, w1)} {self.ci}{fmt(i, self.digits)} "
                       f"{self.cj}{fmt(j, self.digits)}{p}{self.feed_word(feed)}", arc, bound)


def _write_run(wr: _Writer, cols: PlainColumns, a: int, b: int) -> None:
    """Write segments ``a`` .. ``b - 1``, lines and arcs in the writer's plane
    and unrotated frame with nothing to write between them but their moves,
    as :meth:`_Writer.line` and :meth:`_Writer.arc` write them one by one."""
    d, (du, dv, dw) = wr.digits, wr.shift
    u, v = cols.end[a:b, 0] - du, cols.end[a:b, 1] - dv
    fu, fv, ru, rv = fmt_many(u, d), fmt_many(v, d), rounded(u, d), rounded(v, d)
    arcs, starts, as_line = run_arcs(cols, a, b, (ru, rv), wr.at, (du, dv), d)
    rows = arcs + a
    feeds = cols.feeds[a:b]
    rapid, feed = f"{wr.prefix}G0 ", f"{wr.prefix}G1 "
    heads = [rapid if f is None else feed for f in feeds]
    tails = [""] * len(feeds)
    for k in changes(feeds, wr.feed):       # as feed_word writes them
        tails[k] = f" F{fmt(feeds[k] * 60.0, 4)}"
        wr.feed = feeds[k]
    circles = ~as_line                      # the arcs written as arcs
    sweep = cols.sweep[rows[circles]]
    turns = np.maximum(np.ceil(np.abs(sweep) / TWO_PI - _TURNS_SLACK).astype(np.int64) - 1, 0)
    i = fmt_many(cols.center[rows[circles], 0] - du - starts[circles, 0], d)
    j = fmt_many(cols.center[rows[circles], 1] - dv - starts[circles, 1], d)
    ci, cj = f" {wr.ci}", f" {wr.cj}"
    for k, sw, ik, jk, t in zip(arcs[circles].tolist(), sweep.tolist(), i, j, turns.tolist()):
        heads[k] = "G3 " if sw > 0 else "G2 "
        tails[k] = f"{ci}{ik}{cj}{jk}{f' P{t + 1}' if t else ''}{tails[k]}"
    wr.lines += map("".join, zip(heads, repeat(wr.u), fu, repeat(f" {wr.v}"), fv,
                                 repeat(f" {wr.w}"), fmt_many(cols.w1[a:b] - dw, d), tails))
    wr.source += range(a, b)
    intended = list(zip(cols.geoms[a:b], repeat(0.0)))
    for k in arcs[as_line].tolist():
        g = cols.geoms[a + k]
        intended[k] = (Line(g.start, g.end), 0.0 + g.length)
    wr.intended += intended
    wr.at = (float(ru[-1]), float(rv[-1]))


def synchronised_pitch(seg) -> float | None:
    """The units per spindle revolution of a segment made by a spindle-
    synchronised block (``G33``, ``G76``'s cuts), or None; refused, located,
    where the export cannot keep the synchronisation: a rigid tap (``G33.1``,
    whose way back reverses the spindle) and a curve (G33 moves straight)."""
    block = seg.block
    per_rev = block.per_revolution if block is not None else None
    if per_rev is None:
        return None
    s = block.source
    if block.cycle == "G33.1":
        raise ProgramError("rigid tapping (G33.1) is not exported yet: its way back reverses "
                           "the spindle, which a G33 cannot say; nothing written",
                           s.file, s.line, s.col)
    if not isinstance(seg.geom, Line):
        raise ProgramError("a spindle-synchronised move made a curve of the tool path (a "
                           "compensation corner?): G33 moves straight; nothing written",
                           s.file, s.line, s.col)
    return per_rev


def bezier_pieces(g: BezierCurve, w0: float, w1: float, tol: float):
    """``(FittedPiece, w at its end)`` for the lines and arcs replacing ``g``.

    The out-of-plane coordinate goes from ``w0`` to ``w1`` in proportion to
    the length of the pieces (a helix-like climb along the curve), landing on
    ``w1`` exactly at the end.
    """
    pieces = fit_bezier(g, tol)
    lengths = [p.geom.length for p in pieces]
    total = sum(lengths)
    out = []
    acc = 0.0
    for k, (p, L) in enumerate(zip(pieces, lengths)):
        acc += L
        w = w1 if k == len(pieces) - 1 else w0 + (w1 - w0) * (acc / total)
        out.append((p, w))
    return out


def _write_segment(wr: _Writer, idx: int, seg, tol: float) -> float:
    """Write segment ``idx``'s moves (a spiral or a blend curve fitted within
    ``tol``); the largest fitting error."""
    g = seg.geom
    max_err = 0.0
    per_rev = synchronised_pitch(seg)
    if per_rev is not None:
        wr.synchronised(idx, g, seg.w1, per_rev)
    elif isinstance(g, Line):
        wr.line(idx, g, seg.w1, seg.feed)
    elif isinstance(g, Arc):
        wr.arc(idx, g, seg.w0, seg.w1, seg.feed)
    elif isinstance(g, Spiral):
        pieces = fit_located(seg, fit_arcs, g, tol)
        total = g.length
        s_acc = 0.0
        for piece in pieces:
            s_acc += piece.arc.length
            w = seg.w0 + (seg.w1 - seg.w0) * min(s_acc / total, 1.0)
            wr.arc(idx, piece.arc, seg.w0, w, seg.feed, piece.bound)
            max_err = max(max_err, piece.bound)
    elif isinstance(g, BezierCurve):
        for piece, w in fit_located(seg, bezier_pieces, g, seg.w0, seg.w1, tol):
            if isinstance(piece.geom, Line):
                wr.line(idx, piece.geom, w, seg.feed, piece.bound)
            else:
                wr.arc(idx, piece.geom, seg.w0, w, seg.feed, piece.bound)
            max_err = max(max_err, piece.bound)
    else:
        raise ValueError(f"cannot export a {type(g).__name__} segment to G-code yet")
    return max_err


def _joins(path: ToolPath, cols: PlainColumns, machine: MachineWords,
           dwell_at: dict) -> tuple[np.ndarray, np.ndarray]:
    """Which segments continue a run (:func:`_write_run`) from the one before
    them: a line or arc, not synchronised, in the same plane, with no dwell
    before it and nothing of the machine's to write (:meth:`MachineWords.quiet`);
    and each segment's block's place in the program."""
    segments = path.segments
    n = len(segments)
    blocks = list(map(_BLOCK, segments))
    joins, order = machine.quiet(blocks)
    joins &= cols.kind != OTHER
    planes = list(map(_PLANE, segments))
    joins[1:] &= np.fromiter(map(eq, planes[1:], planes), bool, n - 1)
    joins &= np.fromiter(map(is_, map(_PITCH, stand_in(blocks)), repeat(None)), bool, n)
    joins[[i for i in dwell_at if i < n]] = False
    return joins, order


def _write_one(wr: _Writer, machine: MachineWords, path: ToolPath, idx: int, dwells,
               tol: float) -> float:
    """Write segment ``idx`` with what goes before and on it: the ``dwells``
    before it, its plane and machine words, its frame, its moves (fitted within
    ``tol``), the A B C U V W of its block's end; the largest fitting error."""
    seg = path.segments[idx]
    for seconds, block in dwells:
        wr.lines += machine.before(block)
        wr.lines.append(f"G4 P{fmt(seconds, 4)}")
    if seg.plane != wr.plane:
        # a path in several planes: the plane word before its first move
        wr.lines.append(PLANE_WORD[seg.plane])
        wr.set_plane(seg.plane)
    wr.lines += machine.before(seg.block)
    wr.set_frame(seg.block)
    err = _write_segment(wr, idx, seg, tol)
    if idx + 1 == len(path.segments) or path.segments[idx + 1].block is not seg.block:
        # the carried axes end with their block's last move
        wr.lines[-1] += machine.axes_words(seg.block)
    return err


def _write_segments(wr: _Writer, machine: MachineWords, path: ToolPath, dwell_at: dict,
                    tol_of) -> float:
    """Write the path's segments, runs of plain lines and arcs in bulk
    (:func:`_write_run`), the others one by one, each fitted within
    ``tol_of(index)``; the largest fitting error."""
    cols = PlainColumns(path)
    joins, order = _joins(path, cols, machine, dwell_at)
    ends = run_ends(joins)
    max_err = 0.0
    idx = 0
    while idx < len(path.segments):
        max_err = max(max_err, _write_one(wr, machine, path, idx, dwell_at.get(idx, ()),
                                          tol_of(idx)))
        end = ends[idx]
        if end > idx + 1 and wr.rotated is None:
            _write_run(wr, cols, idx + 1, end)
            machine.passed(int(order[idx + 1:end].max()))
            idx = end
        else:
            idx += 1
    return max_err


def write_gcode(path: ToolPath, tol: float, header: list[str] | None = None, digits: int = 6,
                seg_tol: dict[int, float] | None = None, radius_mode: bool = False,
                program=None):
    """G-code text of ``path``.

    Returns ``(text, moves, max_fit_error)``: ``moves[m] = (source, geometry,
    bound)`` for the m-th move: the index of the tool-path segment it came from
    (-1 for the initial positioning rapid), the exact geometry the line means
    before rounding, and the certified deviation of that geometry from the
    segment (0 for lines and arcs, the fit bound for arcs replacing a spiral
    and for lines and arcs replacing a Bezier curve); ``max_fit_error`` is the
    largest such bound. ``seg_tol`` gives some segments (by index) a tighter
    fit tolerance than ``tol``. ``radius_mode``: the mode line says ``G8``
    (lathe radius mode), for a program that used G7: the written X words are
    radii, which a lathe left in diameter mode would read as diameters.
    ``program``: the program the path was made from; its machine words and
    work coordinates are kept (:class:`~ccopt.export.machine.MachineWords`).
    """
    wr = _Writer(path, digits)
    machine = MachineWords(program)
    seg_tol = seg_tol or {}
    out = ["%"]
    modes = f"{PLANE_WORD[path.plane]} G90 G94" + (" G8" if radius_mode else "")
    number = program.meta.get("program_number") if program is not None else None
    if isinstance(number, int):
        out.append(f"O{number}")
    out.append(f"G21 {modes}" if path.units == "mm" else f"G20 {modes}")
    dwell_at: dict[int, list] = {}
    for idx, seconds, block in path.dwells:
        dwell_at.setdefault(idx, []).append((seconds, block))
    if path.segments and not starts_at_origin(path):
        first = path.segments[0]
        wr.lines += machine.before(first.block)
        wr.set_frame(first.block)
        wr.move(-1, f"G0 {wr.coords(first.start, first.w0)}")  # positioning, no segment
    with paused_gc():       # many small objects, none in a cycle: see paused_gc
        max_err = _write_segments(wr, machine, path, dwell_at,
                                  lambda idx: fit_tolerance(seg_tol.get(idx, tol), digits))
        moves = list(zip(wr.source, *zip(*wr.intended)))
    for seconds, block in dwell_at.get(len(path.segments), ()):
        wr.lines += machine.before(block)
        wr.lines.append(f"G4 P{fmt(seconds, 4)}")
    out += wr.lines
    out += machine.finish() + ["%"]
    return with_header("\n".join(out) + "\n", header, "gcode"), moves, max_err
