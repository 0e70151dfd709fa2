"""LinuxCNC cutter radius compensation (``G41``/``G42``/``G41.1``/``G42.1``, ``G40``).

Rules: docs/compensation.md, section 5 "LinuxCNC style", re-derived from
LinuxCNC's interpreter (``src/emc/rs274ngc/interp_convert.cc``: ``convert_straight_comp1/2``,
``convert_arc_comp1/2``, ``convert_cutter_compensation_off``; and
``interp_queue.cc``: ``move_endpoint_and_flush``) and checked against its own
test suite (``tests/conformance/linuxcnc/crazy-paths``).

How LinuxCNC works, and therefore how this module works
-------------------------------------------------------
LinuxCNC compensates one block at a time, looking *back*, never ahead. It
keeps the tool position ``c`` (where the last compensated move ends: always
``P + r*o(t)`` with ``P`` the last programmed point and ``t`` the tangent the
last programmed move ended with) and a *queue* holding the last compensated
move, not yet sent to the machine. When the next block arrives:

* **Entry** (first move after ``G41``/``G42``), straight from the current
  point ``S`` to ``P``: the move ends at ``P + r*n``, ``n`` perpendicular to
  ``P - S`` on the tool side; the entry is an error when ``|P - S| <= r``.
  An entry *arc* ends at ``E + r*o(t_E)`` on the arc's offset and runs on the
  circle through ``S`` and that point whose centre lies on the normal at the
  end; an error when ``|E - S| <= r``.
* **Outside corner** (the path turns away from the tool side by more than
  :data:`~ccopt.tolerances.LINUXCNC_CONCAVE_CORNER`): the queued move is sent
  unchanged, then an arc of radius ``r`` about ``P`` from ``c`` to
  ``P + r*o(t_next)`` (a straight traverse instead for ``G0``), then the next
  move is queued.
* **Inside corner** (turning toward the tool side by more than the
  tolerance): the queued move's end point is pulled back to the intersection
  of the two offsets (line-line, line-arc, arc-line, arc-arc, each with
  LinuxCNC's choice of root) and sent; the next move starts there. A queued
  straight that would then run backwards, or a queued arc whose sweep would
  grow, gouges: an error.
* **Within the tolerance of straight**: the queued move is sent unchanged and
  the next move starts at ``c`` (for a slight turn either way this leaves a
  tiny diagonal step, as LinuxCNC does).
* **Exit** (``G40``): the queued move is sent with its offset end point and
  the next move, which must be straight, runs from there to its programmed
  end point.

Moves with no motion in the plane and dwells while compensation is on are
queued behind the move before them: they run at that move's (possibly
pulled-back) end, before any corner arc.

Every canonical move LinuxCNC would emit is one :class:`PathSegment` here,
in the same order (also zero-length ones): a ``STRAIGHT_TRAVERSE`` is a line
of a ``G0`` block (feed ``None``), a ``STRAIGHT_FEED`` a line of a ``G1``
block, an ``ARC_FEED`` an :class:`Arc` (or a :class:`Spiral` where LinuxCNC
sends an arc whose end radius differs from its start radius, the slight-turn
case). Arc sweeps follow LinuxCNC's ``find_turn``: from the start to the end
in the arc's direction, a full turn when they coincide, plus ``|turn| - 1``
extra full turns.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import offset_dir, perp
from ccopt.compensate.lathe import controlled_point_path
from ccopt.compensate.planes import change_plane
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.program.model import Block, Motion, Program
from ccopt.tolerances import (
    LINUXCNC_ARC_GROWTH,
    LINUXCNC_CONCAVE_CORNER,
    LINUXCNC_TOLERANCE_EQUAL,
    SPIRAL_RADIUS_REL_TOL,
)
from ccopt.toolpath import STRAIGHT_JOINS, PathSegment, Role, ToolPath, effective_side_radius


#: The style's "straight on" turn tolerance (radians), exported under its old
#: name; the value lives in :data:`ccopt.tolerances.LINUXCNC_CONCAVE_CORNER`.
CONCAVE_TOLERANCE = LINUXCNC_CONCAVE_CORNER

LEFT, RIGHT = 1, -1


def find_turn(start, centre, turn: int, end) -> float:
    """Signed sweep (radians) of a LinuxCNC ``ARC_FEED`` from ``start`` to ``end``.

    ``turn`` > 0 counter-clockwise, < 0 clockwise, ``|turn| - 1`` extra full
    turns. Coinciding polar angles make a full turn (the sweep is in
    ``(0, 2 pi]`` for ``|turn| = 1``).
    """
    if turn == 0:
        return 0.0
    a = math.atan2(start[1] - centre[1], start[0] - centre[0])
    b = math.atan2(end[1] - centre[1], end[0] - centre[0])
    if turn > 0:
        if b <= a:
            b += TWO_PI
        return (b - a) + (turn - 1) * TWO_PI
    if a <= b:
        a += TWO_PI
    return (b - a) + (turn + 1) * TWO_PI


def tool_inside_arc(k: int, turn: int) -> bool:
    """The tool is on the centre's side of an arc: left of a counter-clockwise
    arc or right of a clockwise one."""
    return (k == LEFT and turn > 0) or (k == RIGHT and turn < 0)


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / math.hypot(v[0], v[1])


def _pt(p) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


@dataclass
class _Move:
    """One canonical move (``STRAIGHT_*`` or ``ARC_FEED``), start implied."""

    kind: str                      # "line" | "arc"
    end: np.ndarray                # in-plane end point
    w1: float                      # out-of-plane end coordinate
    block: Block
    role: Role
    rapid: bool = False
    direction: np.ndarray | None = None   # lines: the gouge-check direction
    centre: np.ndarray | None = None      # arcs
    turn: int = 0                          # arcs: LinuxCNC turn (+-n)
    programmed_sweep: float = 0.0          # arcs: 0 = never checked (corner arcs)
    join: float = 0.0                      # beta of a slight turn taken as straight on


@dataclass
class _Dwell:
    seconds: float
    block: Block


def _straight_join(beta: float, small: float) -> float:
    """``beta`` for a turn of at most ``small`` either way (straight on), else 0."""
    return beta if -small <= beta <= small else 0.0


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


class LinuxcncStyle:
    """The LinuxCNC rules (no options: LinuxCNC has none for compensation)."""

    name = "linuxcnc"

    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        if radius is not None and radius < 0:
            raise CompensationError(f"--radius {radius:g} must be >= 0", program.file)
        # the controlled point of a lathe tool is its imaginary tip (lathe.py)
        return controlled_point_path(_Interpreter(program, radius, side).run(), radius)


class _Interpreter:
    """LinuxCNC's compensation state machine over a :class:`Program`."""

    def __init__(self, program: Program, radius: float | None, side: int | None):
        self.program = program
        self.radius_override = radius
        self.side_override = side
        self.plane = program.blocks[0].modal.plane if program.blocks else "XY"
        start = program.blocks[0].uvw(program.start) if program.blocks else (0.0, 0.0, 0.0)
        # LinuxCNC's "current" point (tool position as the interpreter sees it)
        # and "programmed" point (last programmed end, while compensating).
        self.cur = np.array(start[:2], float)
        self.cur_w = float(start[2])
        self.prog = self.cur.copy()
        # What was last sent to the machine: segments start there.
        self.tip = self.cur.copy()
        self.tip_w = self.cur_w
        self.k = 0
        self.r = 0.0
        self.first = True
        self.arc_not_allowed = False
        self.queue: list = []
        self.endpoint = self.cur.copy()   # start point of the first queued move
        self.endpoint_valid = False
        self.segs: list[PathSegment] = []
        self.dwells: list[tuple[int, float, Block]] = []
        self.used_radius = 0.0
        self.exit_pending = False
        self.joins: dict[int, float] = {}    # STRAIGHT_JOINS of the tool path

    # -- the machine side: sending moves ----------------------------------------
    def send(self, item) -> None:
        if isinstance(item, _Dwell):
            self.dwells.append((len(self.segs), item.seconds, item.block))
            return
        s = self.tip
        if item.kind == "line":
            geom = Line(_pt(s), _pt(item.end))
        else:
            geom = self._arc_geometry(s, item)
        feed = None if item.rapid else item.block.feed
        self.joins.update({len(self.segs): item.join} if item.join else {})
        self.segs.append(PathSegment(geom, item.role, item.block, self.tip_w, item.w1, feed))
        self.tip = np.asarray(item.end, float).copy()
        self.tip_w = item.w1

    @staticmethod
    def _arc_geometry(s, item: _Move):
        c = item.centre
        rs = math.hypot(s[0] - c[0], s[1] - c[1])
        re = math.hypot(item.end[0] - c[0], item.end[1] - c[1])
        if rs <= 0.0 or re <= 0.0:
            raise _err(item.block, "a compensated arc would pass through its own centre; "
                                   "use a smaller cutter or change the arc")
        sweep = find_turn(s, c, item.turn, item.end)
        th0 = math.atan2(s[1] - c[1], s[0] - c[0])
        if abs(re - rs) <= SPIRAL_RADIUS_REL_TOL * max(1.0, rs):
            return Arc(_pt(c), rs, th0, sweep)
        return Spiral(_pt(c), rs, re, th0, sweep)

    def enqueue(self, item) -> None:
        if isinstance(item, _Dwell) and not self.queue:
            self.send(item)
            return
        self.queue.append(item)

    def dequeue(self) -> None:
        """Send everything queued as it is (LinuxCNC ``dequeue_canons``)."""
        self.endpoint_valid = False
        for item in self.queue:
            self.send(item)
        self.queue.clear()

    def set_endpoint(self, p) -> None:
        self.endpoint = np.asarray(p, float).copy()
        self.endpoint_valid = True

    def move_endpoint_and_flush(self, x, block: Block) -> None:
        """Move the end of every queued move to ``x``, check it, send them.

        A gouge is reported at ``block``, the block being converted, as
        LinuxCNC does (decisions.LINUXCNC_ERROR_LOCATION ``"converting-block"``),
        or at the queued move's own block (``"queued-block"``).
        """
        x = np.asarray(x, float)
        if not self.queue:
            return
        at_converting = decisions.LINUXCNC_ERROR_LOCATION == "converting-block"
        for item in self.queue:
            if isinstance(item, _Dwell):
                continue
            where = block if at_converting else item.block
            if item.kind == "arc":
                sweep = find_turn(self.endpoint, item.centre, item.turn, x)
                if (item.programmed_sweep and self.endpoint_valid
                        and abs(sweep) > abs(item.programmed_sweep) + LINUXCNC_ARC_GROWTH):
                    raise _err(where, f"arc move of line {item.block.source.line} in a concave "
                                      "corner cannot be reached by the tool without gouging "
                                      "(the pulled-back arc would sweep further than "
                                      "programmed): use a smaller cutter or a longer arc")
            else:
                new_dir = x - self.endpoint
                if self.endpoint_valid and float(np.dot(item.direction, new_dir)) < 0.0:
                    what = "straight traverse" if item.rapid else "straight feed"
                    raise _err(where, f"{what} of line {item.block.source.line} in a concave "
                                      "corner cannot be reached by the tool without gouging "
                                      "(it is shorter than the corner's pull-back): use a "
                                      "smaller cutter or a longer move")
            item.end = x.copy()
        self.dequeue()
        self.set_endpoint(x)

    def front_arc(self) -> _Move | None:
        """The queued move when it is an arc (LinuxCNC looks at the queue's front)."""
        for item in self.queue:
            if isinstance(item, _Move):
                return item if item.kind == "arc" else None
        return None

    # -- the program -----------------------------------------------------------
    def run(self) -> ToolPath:
        prev_modal = None
        for blk in self.program.blocks:
            self.state_change(blk, prev_modal)
            prev_modal = blk.modal
            if blk.motion is Motion.DWELL:
                self.enqueue(_Dwell(blk.dwell, blk))
                continue
            self.move(blk)
        # Program end while on: whatever is queued is sent as it is and the
        # path ends at the last offset point; LinuxCNC has no automatic
        # lead-out (docs/compensation.md, LinuxCNC program end while on).
        self.dequeue()
        plane = self.segs[0].plane if self.segs else self.plane
        return ToolPath(tuple(self.segs), plane=plane, style=LinuxcncStyle.name,
                        radius=self.used_radius, dwells=tuple(self.dwells),
                        units=self.program.units,
                        meta={STRAIGHT_JOINS: dict(self.joins)} if self.joins else {})

    def state_change(self, blk: Block, prev_modal) -> None:
        """``G40``/``G41``/``G42`` between the previous block and this one."""
        m = blk.modal
        was_on = prev_modal is not None and prev_modal.side != 0
        if m.plane != self.plane:
            was_on = change_plane(self, blk, was_on)
        if m.side == 0:
            if was_on:
                self.compensation_off(blk)
            return
        if was_on:
            if (m.side, m.radius, m.tool) != (prev_modal.side, prev_modal.radius, prev_modal.tool):
                raise _err(blk, "cannot turn cutter radius compensation on when it is already on "
                                "(LinuxCNC refuses G41/G42 after G41/G42): program G40 first")
            return
        # G41/G42 (or G41.1/G42.1) switches it on: the next move is the entry.
        if m.plane == "YZ":
            raise _err(blk, "LinuxCNC compensates in the XY (G17) and XZ (G18) planes only, "
                            "not in G19: change the plane or remove the compensation")
        self.k, self.r = effective_side_radius(blk, self.radius_override, self.side_override)
        self.first = True

    def compensation_off(self, blk: Block) -> None:
        """``G40`` (before ``blk``): send the queued move with its offset end;
        the next move, which must be straight, starts there."""
        if self.k != 0 and self.r > 0.0:
            # LinuxCNC moves the queued end to where it already is (checking
            # it) and then forgets the offset: "current" is the programmed point.
            self.move_endpoint_and_flush(self.cur, blk)
            self.dequeue()
            self.cur = self.prog.copy()
            self.arc_not_allowed = True
            self.exit_pending = True
        self.k, self.r = 0, 0.0
        self.first = True

    def move(self, blk: Block) -> None:
        is_arc = blk.motion.is_arc
        if is_arc and self.arc_not_allowed:
            raise _err(blk, "the move just after turning cutter compensation off (G40) must be "
                            "straight, not an arc: add a G1 exit move before the arc")
        if not is_arc:
            self.arc_not_allowed = False
        end = blk.uvw(blk.end)
        p = np.array(end[:2], float)
        w = float(end[2])
        if self.k == 0 or self.r <= 0.0:
            self.uncompensated(blk, p, w)
            return
        self.used_radius = max(self.used_radius, self.r)
        if is_arc:
            (self.arc_entry if self.first else self.arc_compensated)(blk, p, w)
        else:
            (self.straight_entry if self.first else self.straight_compensated)(blk, p, w)

    def uncompensated(self, blk: Block, p, w) -> None:
        rapid = blk.motion is Motion.RAPID
        role = Role.RAPID if rapid else Role.UNCOMPENSATED
        if self.exit_pending:
            role = Role.LEAD_OUT
            self.exit_pending = False
        if blk.motion.is_arc:
            c = np.array(blk.center_uv, float)
            turn = (blk.turns + 1) * (1 if blk.motion is Motion.ARC_CCW else -1)
            self.send(_Move("arc", p, w, blk, role, centre=c, turn=turn))
        else:
            self.send(_Move("line", p, w, blk, role, rapid=rapid))
        self.cur = p.copy()
        self.cur_w = w
        self.prog = p.copy()

    # -- entry -----------------------------------------------------------------
    def straight_entry(self, blk: Block, p, w) -> None:
        S = self.cur
        dist = math.hypot(*(p - S))
        if dist <= self.r:
            raise _err(blk, f"cutter compensation entry move is {dist:.6g} long, not longer than "
                            f"the cutter radius {self.r:.6g}: start the entry further from the "
                            "contour")
        n = offset_dir(_unit(p - S), self.k)
        end = p + self.r * n
        self.set_endpoint(S)
        # LinuxCNC records the entry's normal as its direction: the entry can
        # never be reported as reversed (its offset line is at distance r).
        self.enqueue(_Move("line", end, w, blk, Role.LEAD_IN, rapid=blk.motion is Motion.RAPID,
                           direction=n))
        self.first = False
        self.cur, self.cur_w, self.prog = end, w, p.copy()

    def arc_entry(self, blk: Block, p, w) -> None:
        S = self.cur
        r, k = self.r, self.k
        C = np.array(blk.center_uv, float)
        turn = (blk.turns + 1) * (1 if blk.motion is Motion.ARC_CCW else -1)
        chord = math.hypot(*(p - S))
        if chord <= r:
            raise _err(blk, f"radius of the cutter compensation entry arc is not greater than "
                            f"the cutter radius {r:.6g}: its end point is only {chord:.6g} from "
                            "its start; start the entry further from the contour")
        R = math.hypot(*(C - S))
        inside = tool_inside_arc(k, turn)
        if inside and R <= r:
            raise _err(blk, f"entry arc radius {R:.6g} is not larger than the cutter radius "
                            f"{r:.6g} with the tool inside it: use a smaller cutter or a "
                            "larger arc")
        g = _unit(C - p) if inside else _unit(p - C)
        end = p + r * g
        # The entry runs on the circle through S and the offset end point whose
        # centre lies on the arc's normal at the end (the line end -> C).
        u = _unit(C - end)
        chord_vec = S - end
        cos_a = float(np.dot(chord_vec, u)) / math.hypot(*chord_vec)
        if abs(cos_a) < LINUXCNC_TOLERANCE_EQUAL:
            raise _err(blk, "cutter compensation entry arc is not possible here (its chord is "
                            "perpendicular to the arc's normal at the end): use a smaller cutter "
                            "or a straight entry")
        c_len = float(np.dot(chord_vec, chord_vec)) / (2.0 * float(np.dot(chord_vec, u)))
        B = end + c_len * u
        self.enqueue(_Move("arc", end, w, blk, Role.LEAD_IN, centre=B, turn=turn,
                           programmed_sweep=find_turn(S, B, turn, end)))
        # LinuxCNC sets no end point for the entry arc: it is never gouge-checked.
        self.endpoint_valid = False
        self.first = False
        self.cur, self.cur_w, self.prog = end, w, p.copy()

    # -- fully compensated moves ----------------------------------------------------
    def _beta(self, t_new) -> tuple[float, np.ndarray]:
        """LinuxCNC's corner angle ``beta`` in ``[-pi/2, 3pi/2)``: ``-k`` times the
        turn from the last tangent to ``t_new`` (> 0 turning away from the tool
        side), plus the last tangent, as LinuxCNC infers it from ``c - P``."""
        n = (self.cur - self.prog) / self.r
        t_prev = -self.k * perp(n)
        phi = math.atan2(t_prev[0] * t_new[1] - t_prev[1] * t_new[0],
                         t_prev[0] * t_new[0] + t_prev[1] * t_new[1])
        beta = -self.k * phi
        if beta < -math.pi / 2:
            beta += TWO_PI
        return beta, _unit(t_prev)

    def straight_compensated(self, blk: Block, p, w) -> None:
        rapid = blk.motion is Motion.RAPID
        c, op, r, k = self.cur, self.prog, self.r, self.k
        if p[0] == op[0] and p[1] == op[1]:
            # No motion in the plane: the move runs where the tool is, queued
            # behind the move before it (it follows that move's end).
            self.enqueue(_Move("line", c.copy(), w, blk, Role.COMPENSATED, rapid=rapid,
                               direction=np.zeros(2)))
            self.cur_w = w
            return
        t_new = _unit(p - op)
        beta, t_prev = self._beta(t_new)
        end = p + r * offset_dir(t_new, k)
        mid = op + r * offset_dir(t_new, k)
        small = LINUXCNC_CONCAVE_CORNER
        front = self.front_arc()
        concave = beta < -small or beta > math.pi + small or (
            beta > math.pi - small and front is not None and not tool_inside_arc(k, front.turn))
        if not concave and beta > small:
            # Outside corner: the queued move keeps its end, an arc about the
            # programmed corner (a traverse for G0) goes round to the new offset.
            self.move_endpoint_and_flush(c, blk)
            if rapid:
                self.send(_Move("line", mid, self.cur_w, blk, Role.CORNER, rapid=True))
            else:
                self.send(_Move("arc", mid, self.cur_w, blk, Role.CORNER, centre=op.copy(),
                                turn=-k))
            self.set_endpoint(mid)
        elif concave:
            if front is None:
                x = self._pull_back_line_line(blk, beta, t_prev)
            else:
                x = self._pull_back_arc_line(blk, front, t_new)
            self.move_endpoint_and_flush(x, blk)
        else:
            # Within the tolerance of straight on: nothing to adjust. LinuxCNC's
            # code (and its crazy-paths output) treat a slight turn either way
            # as straight on (docs/compensation.md, LinuxCNC slight turn).
            self.dequeue()
            self.set_endpoint(c)
        self.enqueue(_Move("line", end, w, blk, Role.COMPENSATED, rapid=rapid,
                           direction=p - op, join=_straight_join(beta, small)))
        self.cur, self.cur_w, self.prog = end, w, p.copy()

    def _pull_back_line_line(self, blk: Block, beta: float, t_prev) -> np.ndarray:
        """Intersection of the two offset lines, found by backing up from ``c``
        along the last tangent by ``r / tan(half the inside corner angle)``."""
        half_corner = (beta + math.pi) / 2.0
        if half_corner == 0.0:
            raise _err(blk, "zero-degree inside corner: the move turns straight back into the "
                            "material and cannot be compensated; change the path")
        retreat = self.r / math.tan(half_corner)
        return self.cur - retreat * t_prev

    def _pull_back_arc_line(self, blk: Block, front: _Move, t_new) -> np.ndarray:
        """Where the queued arc's tool circle meets the new line's offset line.

        Of the two intersections LinuxCNC takes, measured along ``t_new`` from
        the circle centre's foot on that line, the one behind it when the tool
        is inside the queued arc and the one ahead of it when outside. This is
        the geometric statement of LinuxCNC's point, which it computes from the
        queued arc's programmed radius +- r; the two differ only for an entry
        arc whose re-centred centre falls beyond the programmed end
        (docs/compensation.md, LinuxCNC arc-to-line pull-back).
        """
        k, r = self.k, self.r
        Cp = front.centre
        rad = math.hypot(*(front.end - Cp))
        q0 = self.prog + r * offset_dir(t_new, k)   # a point of the offset line
        q = float(np.dot(Cp - q0, t_new))
        foot = q0 + q * t_new
        h2 = rad * rad - float(np.sum((Cp - foot) ** 2))
        if h2 < 0.0:
            raise _err(blk, "arc to straight motion makes a corner the compensated tool can't "
                            "fit in without gouging: use a smaller cutter or change the corner")
        ahead = math.sqrt(h2)
        if tool_inside_arc(k, front.turn):
            ahead = -ahead
        return foot + ahead * t_new

    def arc_compensated(self, blk: Block, p, w) -> None:
        c, op, r, k = self.cur, self.prog, self.r, self.k
        C = np.array(blk.center_uv, float)
        ccw = blk.motion is Motion.ARC_CCW
        turn = (blk.turns + 1) * (1 if ccw else -1)
        R = math.hypot(*(C - p))
        inside = tool_inside_arc(k, turn)
        if inside and R <= r:
            raise _err(blk, f"concave arc radius {R:.6g} is not larger than the cutter radius "
                            f"{r:.6g}: the tool cannot follow it; use a smaller cutter or a "
                            "larger arc")
        to_c = _unit(C - op)
        t_new = -perp(to_c) if ccw else perp(to_c)
        beta, t_prev = self._beta(t_new)
        g = _unit(C - p) if inside else _unit(p - C)
        new_end = p + r * g
        small = LINUXCNC_CONCAVE_CORNER
        programmed_sweep = find_turn(op, C, turn, p)
        concave = beta < -small or beta > math.pi + small or (
            abs(beta - math.pi) < small and not inside)
        if concave:
            front = self.front_arc()
            new_rad = R - r if inside else R + r
            if front is None:
                x = self._pull_back_line_arc(blk, C, new_rad, inside, t_prev)
            else:
                x = self._pull_back_arc_arc(blk, front, C, new_rad, turn)
            self.move_endpoint_and_flush(x, blk)
        elif beta > small:
            # Outside corner: send the queued move as it is, then the corner arc.
            mid = op + r * offset_dir(t_new, k)
            self.dequeue()
            self.send(_Move("arc", mid, self.cur_w, blk, Role.CORNER, centre=op.copy(), turn=-k))
            self.set_endpoint(mid)
        else:
            self.dequeue()
            self.set_endpoint(c)
        self.enqueue(_Move("arc", new_end, w, blk, Role.COMPENSATED, centre=C, turn=turn,
                           programmed_sweep=programmed_sweep,
                           join=0.0 if concave else _straight_join(beta, small)))
        self.cur, self.cur_w, self.prog = new_end, w, p.copy()

    def _pull_back_line_arc(self, blk: Block, C, new_rad: float, inside: bool, t_prev):
        """Where the last move's offset line meets the new arc's offset circle:
        of the two points, the one ahead of the centre along the last tangent
        when the tool is inside the arc, the one behind it when outside."""
        q = float(np.dot(self.cur - C, t_prev))
        foot = self.cur - q * t_prev
        h2 = new_rad * new_rad - float(np.sum((foot - C) ** 2))
        if h2 < 0.0:
            raise _err(blk, "arc move in a concave corner cannot be reached by the tool without "
                            "gouging (the offset line misses the arc's offset): use a smaller "
                            "cutter or change the corner")
        along = math.sqrt(h2) if inside else -math.sqrt(h2)
        return C + (foot - C) + along * t_prev

    def _pull_back_arc_arc(self, blk: Block, front: _Move, C, new_rad: float, turn: int):
        """Where the queued arc's tool circle meets the new arc's offset circle:
        of the two points (mirror images in the line of centres), the one left
        of ``Cp -> C`` when (tool inside the queued arc) == (new arc CCW)."""
        Cp = front.centre
        old_rad = math.hypot(*(front.end - Cp))
        d = math.hypot(*(C - Cp))
        if old_rad == 0.0 or d == 0.0:
            raise _err(blk, "arc to arc motion is invalid because the arcs have the same centre: "
                            "LinuxCNC cannot compensate it; join them into one arc")
        a = (old_rad ** 2 + d ** 2 - new_rad ** 2) / (2.0 * old_rad * d)
        if a > 1.0 or a < -1.0:
            raise _err(blk, "arc to arc motion makes a corner the compensated tool can't fit in "
                            "without gouging: use a smaller cutter or change the corner")
        pull = math.acos(a)
        left = tool_inside_arc(self.k, front.turn) == (turn > 0)
        ang = math.atan2(C[1] - Cp[1], C[0] - Cp[0]) + (pull if left else -pull)
        return Cp + old_rad * np.array([math.cos(ang), math.sin(ang)])


__all__ = ["CONCAVE_TOLERANCE", "LinuxcncStyle", "find_turn"]
