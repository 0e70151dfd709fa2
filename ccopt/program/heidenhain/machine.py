"""The modal state of a Klartext run and the blocks it makes.

:class:`Machine` keeps the tool position, the working plane (from the tool
axis of ``TOOL CALL``), the pole ``CC`` and its plane, radius compensation
``RL``/``RR``/``R0`` and the compensation value, the feed, and the contour
element last made (for ``CT``, ``RND``, ``CHF``, ``DEP``). It turns pieces of
plane geometry (:mod:`.contour`) into :class:`~ccopt.program.model.Block`.
"""
from __future__ import annotations

import math
from dataclasses import replace

from ccopt.errors import ProgramError
from ccopt.program.heidenhain import contour
from ccopt.program.heidenhain.values import Parameters
from ccopt.program.model import (MAX_PROGRAM_COORDINATE, PLANE_AXES, Block, Modal, Motion,
                                 Source, Vec3, out_of_range)

#: Tool axis of ``TOOL CALL`` -> working plane.
PLANE_OF_AXIS = {"Z": "XY", "Y": "ZX", "X": "YZ"}
#: A pair of axes -> the plane they span (``CC X.. Z..`` selects ZX).
PLANE_OF_PAIR = {frozenset("XY"): "XY", frozenset("ZX"): "ZX", frozenset("YZ"): "YZ"}
_AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2}
#: ``Program.meta`` key: source of an APPR/DEP block -> what it is
#: (``{"dir": "APPR"|"DEP", "kind": "LT"|"LN"|"CT"|"LCT", "length", "radius",
#: "cca"}``), read by the ``heidenhain`` compensation style.
LEADS = "heidenhain_leads"


class Machine:
    """The state of one run (see the module docstring)."""

    def __init__(self, file: str, q: Parameters, tool_table: dict | None):
        self.file = file
        self.q = q
        self.tool_table = tool_table or {}
        self.tool_radii: dict = {}          # TOOL DEF n R.. -> radius
        self.blocks: list[Block] = []
        self.pos: list[float] = [0.0, 0.0, 0.0]
        self.units = "mm"
        self.plane = "XY"
        self.pole: Vec3 | None = None
        self.pole_plane = "XY"
        self.side = 0
        self.radius: float | None = None
        self.tool: int | None = None
        self.feed: float | None = None      # units per second
        self.tool_feed: float | None = None
        self.speed: float | None = None     # spindle speed S of TOOL CALL, rev/min
        self.last_rapid = True
        self.datum = [0.0, 0.0, 0.0]
        #: CYCL DEF 10: the turn of the working plane about the tool axis,
        #: degrees counter-clockwise from its first axis (0: none)
        self.rot = 0.0
        self.last_piece = None              # the contour element last made, and its block
        self.last_block_index = -1
        self.meta: dict = {LEADS: {}}
        self._modals: dict = {}

    # -- coordinates ------------------------------------------------------------------
    def target(self, coords: dict) -> list[float]:
        """The end point the coordinate words give (absolute, incremental, or
        the current position for an axis not written), in machine coordinates:
        the datum shift added, and under a rotation (CYCL DEF 10) the words
        read along the turned axes of the working plane."""
        i, j, k = PLANE_AXES[self.plane]
        if self.rot != 0.0 and any(_AXIS_INDEX[a] in (i, j) for a in coords):
            work = self.to_work(self.pos)
            for axis, (value, inc) in coords.items():
                n = _AXIS_INDEX[axis]
                work[n] = work[n] + value if inc else value
            out = self.to_machine(work)
            out[k] = work[k] + self.datum[k] if "XYZ"[k] in coords else self.pos[k]
            return out
        # no word in the turned plane: its two axes stay exactly where they are
        out = list(self.pos)
        for axis, (value, inc) in coords.items():
            i = _AXIS_INDEX[axis]
            out[i] = self.pos[i] + value if inc else value + self.datum[i]
        return out

    def to_machine(self, work) -> list[float]:
        """Machine coordinates of the program point ``work``: turned by
        :attr:`rot` in the working plane, then shifted by the datum."""
        i, j, _ = PLANE_AXES[self.plane]
        p = list(work)
        p[i], p[j] = contour.rotate_about((p[i], p[j]), (0.0, 0.0), math.radians(self.rot))
        return [p[k] + self.datum[k] for k in range(3)]

    def to_work(self, machine) -> list[float]:
        """The program point of the machine point ``machine`` (inverse of :meth:`to_machine`)."""
        i, j, _ = PLANE_AXES[self.plane]
        p = [machine[k] - self.datum[k] for k in range(3)]
        p[i], p[j] = contour.rotate_about((p[i], p[j]), (0.0, 0.0), -math.radians(self.rot))
        return p

    def uv(self, p, plane: str) -> contour.Pt:
        i, j, _ = PLANE_AXES[plane]
        return (float(p[i]), float(p[j]))

    def xyz(self, uv: contour.Pt, w: float, plane: str) -> Vec3:
        i, j, k = PLANE_AXES[plane]
        p = [0.0, 0.0, 0.0]
        p[i], p[j], p[k] = uv[0], uv[1], w
        return (p[0], p[1], p[2])

    def feed_from(self, value: float | None, st_line: int, col: int,
                  fauto: bool = False) -> None:
        """``F`` as written (per minute; INCH programs: 0.1 inch per minute);
        ``fauto``: ``FAUTO``, the ``F`` of ``TOOL CALL``."""
        if fauto:
            if self.tool_feed is None:
                raise ProgramError("FAUTO without an F in TOOL CALL", self.file, st_line, col)
            value = self.tool_feed
        if value is None:
            return
        if value <= 0:
            raise ProgramError(f"F{value:g}: the feed rate must be positive", self.file,
                               st_line, col)
        self.feed = value / 60.0 / (10.0 if self.units == "inch" else 1.0)

    # -- blocks ------------------------------------------------------------------------
    def modal(self, plane: str | None = None, side: int | None = None) -> Modal:
        key = (plane or self.plane, self.units, self.side if side is None else side,
               self.radius, self.tool)
        got = self._modals.get(key)
        if got is None:
            # one object per modal state, shared by its blocks (as the other readers)
            got = self._modals[key] = Modal(plane=key[0], units=key[1], side=key[2],
                                            radius=key[3], tool=key[4])
        return got

    def emit(self, src: Source, motion: Motion, end, *, center=None, turns: int = 0,
             plane: str | None = None, side: int | None = None, rapid: bool = False,
             mcodes: tuple = (), surface: str | None = None, cycle: str | None = None,
             feed: float | None = None, dwell: float = 0.0) -> Block:
        """Append the block from the current position to ``end`` and move there."""
        start = (self.pos[0], self.pos[1], self.pos[2])
        end = tuple(float(v) for v in end)
        for v in end:
            if not math.isfinite(v) or out_of_range(v):
                raise ProgramError("a coordinate of this block is out of range", src.file,
                                   src.line, src.col)
        if center is not None and any(out_of_range(v) for v in center):
            # as the G-code and PMAC readers bound a centre: an arc whose end
            # lies a micrometre off the tangent (a CT) has a radius of 1e9
            raise ProgramError(f"the centre of this arc lies beyond +-"
                               f"{MAX_PROGRAM_COORDINATE:g} program units: the arc is a "
                               "straight line to the machine's precision; program it with L",
                               src.file, src.line, src.col)
        if motion.is_move and not rapid and (feed or self.feed) is None:
            raise ProgramError("a feed move before any feed rate: program F (or FMAX)",
                               src.file, src.line, src.col)
        blk = Block(src, Motion.RAPID if rapid and motion is Motion.LINE else motion, start,
                    end, self.modal(plane, side), center=center, turns=turns,
                    feed=None if rapid else (feed or self.feed), mcodes=mcodes,
                    surface=surface, cycle=cycle, dwell=dwell)
        self.blocks.append(blk)
        self.pos = list(end)
        return blk

    def emit_piece(self, src: Source, piece, w1: float, plane: str, **kw) -> Block:
        """A piece (line or arc in ``plane``) from the current position, the
        out-of-plane coordinate going to ``w1``."""
        end = self.xyz(piece[2], w1, plane)
        if piece[0] == "line":
            return self.emit(src, Motion.LINE, end, plane=plane, **kw)
        sweep = piece[4]
        w0 = self.pos[PLANE_AXES[plane][2]]
        turns = max(math.ceil(abs(sweep) / (2 * math.pi) - contour.POINT_EPS) - 1, 0)
        return self.emit(src, Motion.ARC_CCW if sweep > 0 else Motion.ARC_CW, end,
                         center=self.xyz(piece[3], w0, plane), turns=turns, plane=plane, **kw)

    def replace_end(self, index: int, uv: contour.Pt) -> None:
        """Move the in-plane end of block ``index`` (the last one) to ``uv``."""
        blk = self.blocks[index]
        _, _, k = PLANE_AXES[blk.modal.plane]
        end = self.xyz(uv, blk.end[k], blk.modal.plane)
        self.blocks[index] = replace(blk, end=end)
        self.pos = list(end)

    def set_tool_radius(self, tool: int | None, dr: float, src: Source) -> None:
        """The compensation value after ``TOOL CALL``: the tool's radius (tool
        table, TOOL DEF) plus ``DR``; ``None`` when no radius is known."""
        self.tool = tool
        base = None
        if tool is not None and tool in self.tool_radii:
            base = self.tool_radii[tool]
        elif tool is not None and tool in self.tool_table:
            base = float(self.tool_table[tool]) / 2.0
        self.radius = None if base is None else base + dr
        if self.radius is not None and self.radius < 0:
            raise ProgramError(f"tool radius {base:g} with DR{dr:+g} is negative", src.file,
                               src.line, src.col)
