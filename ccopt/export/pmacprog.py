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

from ccopt.errors import ProgramError
from ccopt.export.arcfit import DEFAULT_TOL, fit_located, fit_tolerance
from ccopt.export.gcode import bezier_pieces, fmt, written_as_line
from ccopt.export.text import with_header
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.program.model import PLANE_AXES
from ccopt.toolpath import ToolPath, starts_at_origin

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
    lines = ["CLOSE", f"OPEN PROG {program_number} CLEAR", NORMAL[path.plane], "ABS"]
    moves: list = []
    mode = None
    feed = None
    axes = _PlaneWords(path.plane, digits)
    coords = axes.coords

    def emit(idx, new_mode, text, f, geom=None, bound=0.0):
        nonlocal mode, feed
        words = []
        if new_mode != mode:
            words.append(new_mode)
            mode = new_mode
        if f is not None and f != feed:
            words.append(f"F{fmt(f, 6)}")
            feed = f
        lines.append(" ".join(words + [text]))
        moves.append((idx, geom, bound))

    def circle(idx, piece, w, f, bound=0.0):
        su, sv = round(piece.start[0], digits), round(piece.start[1], digits)
        if written_as_line(piece, (axes.at, (su, sv)), _rounded(piece.end, digits), digits):
            emit(idx, "RAPID" if f is None else "LINEAR", coords(piece.end, w), f,
                 Line(piece.start, piece.end), bound + piece.length)
            return
        i, j = piece.center[0] - su, piece.center[1] - sv
        # PMAC has no rapid circle: a circle in a rapid segment keeps the last feed
        emit(idx, "CIRCLE2" if piece.sweep > 0 else "CIRCLE1",
             f"{coords(piece.end, w)} {axes.centre(i, j)}",
             f if f is not None else feed, piece, bound)

    dwell_at = _dwells_before(path)
    if path.segments and not starts_at_origin(path):
        first = path.segments[0]
        emit(-1, "RAPID", coords(first.start, first.w0), None)
    for idx, seg in enumerate(path.segments):
        for seconds in dwell_at.get(idx, ()):
            lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
        if seg.plane != axes.plane:
            # a path in several planes: NORMAL before the first move in the next
            lines.append(NORMAL[seg.plane])
            axes.set_plane(seg.plane)
        g = seg.geom
        _not_synchronised(seg)
        if isinstance(g, Line):
            emit(idx, "RAPID" if seg.feed is None else "LINEAR", coords(g.end, seg.w1), seg.feed, g)
        elif isinstance(g, (Arc, Spiral)):
            total = g.length
            s_acc = 0.0
            for piece in _pieces(g):
                s_acc += piece.length
                circle(idx, piece, seg.w0 + (seg.w1 - seg.w0) * min(s_acc / total, 1.0),
                       seg.feed)
        elif isinstance(g, BezierCurve):
            for fp, w in fit_located(seg, bezier_pieces, g, seg.w0, seg.w1,
                                     fit_tolerance(seg_tol.get(idx, tol), digits)):
                if isinstance(fp.geom, Line):
                    emit(idx, "RAPID" if seg.feed is None else "LINEAR", coords(fp.geom.end, w),
                         seg.feed, fp.geom, fp.bound)
                else:
                    circle(idx, fp.geom, w, seg.feed, fp.bound)
        else:
            raise ValueError(f"cannot export a {type(g).__name__} segment to PMAC yet")
    for seconds in dwell_at.get(len(path.segments), ()):
        lines.append(f"DWELL {fmt(seconds * 1000.0, 3)}")
    lines.append("CLOSE")
    return with_header("\n".join(lines) + "\n", header, "pmac"), moves
