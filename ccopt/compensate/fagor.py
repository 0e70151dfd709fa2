"""Fagor 8070 cutter radius compensation (G41/G42/G40, G136/G137, G138/G139).

Rules: docs/compensation.md, section 6 "Fagor 8070 style", from the CNC 8070
Programming manual (ref 0504), chapter 9 "Tool compensation" (activation, section 9.1.5
"Cancellation of tool radius compensation"). Like PMAC, the control looks
ahead: the engine walks the in-plane moves once and decides a *joint* at each
boundary (where the incoming tool path ends, which transition segments are
added, where the outgoing one starts); each move's tool segment is then its
geometry between those points (:func:`corners.tool_geometry`).

* **Outside corners** (every one, while on) get the transition selected by the
  outgoing block's modal state: ``G136`` circular, an arc of radius ``r``
  about the programmed corner ``P`` from ``A = P + r*o(t_in)`` to
  ``B = P + r*o(t_out)``; ``G137`` linear (:func:`linear_transition`).
  Inside corners: the offsets' intersection, whatever G136/G137.
* **Activation** (first in-plane move after G41/G42, a straight move):
  ``G138`` direct: it ends at ``B``; ``G139`` (default) at an outside corner:
  it ends at ``P + r*o(t_lead)`` and the transition goes on to ``B``. Inside
  corners behave as G138. The activation block's G138/G139 decides.
* **Cancellation** (first motion block after G40, which must be linear):
  ``G138``: the last move ends at ``A`` and the cancellation goes straight to
  its programmed end; ``G139`` at an outside corner: the last move ends at
  ``A``, the transition goes to ``B = P + r*o(t_out)``, then straight to the
  end. A cancellation block that does not move in the plane cancels where
  the tool is: during that block the tool goes from ``A`` to the programmed
  end ``P`` of the last compensated move (Fagor rule 4, both seed programs).
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, reversal_sweep, tool_geometry,
    turn,
)
from ccopt.compensate.pmac import Joint, PmacStyle, SegmentList
from ccopt.compensate.planes import by_plane
from ccopt.compensate.scan import scan_program
from ccopt.errors import CompensationError
from ccopt.geometry import Line
from ccopt.program.model import Block, Motion, Program
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role, ToolPath

UNCOMP, LEAD_IN, COMP, LEAD_OUT = "uncompensated", "lead-in", "compensated", "lead-out"
#: |t_in x t_out| at or below this: the two tangent lines of a G137 corner are
#: parallel (no meeting point; only rounding gets here, as the corner is then
#: tangent) and the transition is the straight A -> B.
_PARALLEL_CROSS = 1e-12

ROLE_OF = {UNCOMP: Role.UNCOMPENSATED, LEAD_IN: Role.LEAD_IN, COMP: Role.COMPENSATED,
           LEAD_OUT: Role.LEAD_OUT}


def _pt(p) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


def _line(a, b) -> Line:
    return Line(_pt(a), _pt(b))


def _corner_kind(k: int, tr) -> Corner:
    """The corner class while on: a reversal is an outside corner of 180
    degrees (decisions.FAGOR_REVERSAL_IS_OUTSIDE: the half-turn arc or the G137
    construction beyond 90 degrees), or else an inside corner (the offsets'
    intersection, or the change over the next move)."""
    kind = classify(k, tr)
    if kind is Corner.REVERSAL and not decisions.FAGOR_REVERSAL_IS_OUTSIDE:
        return Corner.INSIDE
    return kind


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def linear_transition(A, B, t_in, t_out, d: float, r: float) -> list[np.ndarray]:
    """Corner points of a G137 linear transition from ``A`` to ``B`` (both
    included), Fagor rule 2 and :data:`decisions.FAGOR_G137_LINEAR_TRANSITION`.

    Turning by at most 90 degrees (``d = t_in . t_out >= 0``): the tangent lines
    at ``A`` (along ``t_in``) and ``B`` (along ``t_out``) meet at ``X``:
    ``[A, X, B]``. Beyond 90 degrees: each offset is extended by ``r`` along its
    tangent past the corner, ``A' = A + r*t_in`` and ``B' = B - r*t_out``, and
    the two ends are joined: ``[A, A', B', B]``.
    """
    A = np.asarray(A, float)
    B = np.asarray(B, float)
    t_in = np.asarray(t_in, float)
    t_out = np.asarray(t_out, float)
    if d >= 0.0:
        cross = t_in[0] * t_out[1] - t_in[1] * t_out[0]
        if abs(cross) > _PARALLEL_CROSS:
            w = B - A
            s = (w[0] * t_out[1] - w[1] * t_out[0]) / cross
            return [A, A + s * t_in, B]
        return [A, B]
    return [A, A + r * t_in, B - r * t_out, B]


class _FagorSegments(SegmentList):
    """Segments as PMAC's, with Fagor's in-place cancellation in a gap."""

    def gap(self, blocks: list[Block], at, on: bool, cancel: tuple | None = None) -> None:
        """Non-plane blocks at ``at``; ``cancel = (block, from, to)``: that
        block cancels compensation in place, moving the tool from ``from`` to
        ``to``, and the blocks after it run there, uncompensated."""
        pos = np.asarray(at, float)
        for blk in blocks:
            if blk.motion is Motion.DWELL:
                self.dwells.append((len(self.segs), blk.dwell, blk))
                continue
            w0 = blk.uvw(blk.start)[2]
            w1 = blk.uvw(blk.end)[2]
            if cancel is not None and blk is cancel[0]:
                self.add(_line(cancel[1], cancel[2]), Role.LEAD_OUT, blk, w0, w1)
                pos = np.asarray(cancel[2], float)
                on = False
                continue
            role = Role.RAPID if blk.motion is Motion.RAPID and not on else (
                Role.COMPENSATED if on else Role.UNCOMPENSATED)
            self.add(_line(pos, pos), role, blk, w0, w1)


class FagorStyle:
    """The Fagor 8070 rules. The modal G136/G137 and G138/G139 come from the
    program (``Modal.corner``, ``Modal.start_end``); ``corner``/``start_end``
    options override them everywhere (``"circular"|"linear"``,
    ``"direct"|"contour"``)."""

    name = "fagor"

    def __init__(self, corner: str | None = None, start_end: str | None = None):
        if corner not in (None, "circular", "linear"):
            raise ValueError("corner must be 'circular' (G136) or 'linear' (G137)")
        if start_end not in (None, "direct", "contour"):
            raise ValueError("start_end must be 'direct' (G138) or 'contour' (G139)")
        self.corner = corner
        self.start_end = start_end
        self._pmac = PmacStyle()

    def _corner_mode(self, a: Element, b: Element) -> str:
        """G136/G137 at the corner between ``a`` and ``b``: the outgoing
        block's (the cancellation block's at the end), or the incoming one's
        (decisions.FAGOR_MODAL_OF_CORNER)."""
        blk = b.block if decisions.FAGOR_MODAL_OF_CORNER == "outgoing-block" else a.block
        return self.corner or blk.modal.corner

    # G138/G139: the activation block's at the start, the cancellation
    # block's at the end.

    def _start_end(self, blk: Block) -> str:
        return self.start_end or blk.modal.start_end

    # -- transitions ------------------------------------------------------------
    def transition(self, P, A, B, t_in, t_out, k: int, r: float, mode: str, reversal: bool,
                   merge_in: bool, merge_out: bool) -> Joint:
        """The outside-corner joint from ``A`` to ``B`` about ``P``.

        ``merge_in``/``merge_out``: the incoming/outgoing tool segment is a line
        along its own offset, so a linear transition's first/last piece (which
        lies on that line) becomes part of it instead of a separate segment
        (decisions.FAGOR_G137_LINEAR_TRANSITION: the ISG G25 block counts).
        """
        if r <= POINT_EPS:
            # radius 0 (D with no radius): A, B and P coincide, nothing to add
            return Joint(A, B)
        if mode == "circular":
            sweep = reversal_sweep(k) if reversal else None
            return Joint(A, B, [corner_arc(P, r, t_in, t_out, k, sweep)])
        d = -1.0 if reversal else float(np.dot(t_in, t_out))
        pts = linear_transition(A, B, t_in, t_out, d, r)
        end_prev, start_next = pts[0], pts[-1]
        if decisions.FAGOR_G137_LINEAR_TRANSITION != "tangent-lines-isg-g25":
            merge_in = merge_out = False     # "tangent-lines": every piece its own segment
        if merge_in and len(pts) >= 2:
            pts = pts[1:]
            end_prev = pts[0]
        if merge_out and len(pts) >= 2:
            pts = pts[:-1]
            start_next = pts[-1]
        pieces = [_line(a, b) for a, b in zip(pts, pts[1:])
                  if math.hypot(*(np.asarray(b) - np.asarray(a))) > POINT_EPS]
        return Joint(end_prev, start_next, pieces)

    # -- joints ------------------------------------------------------------------
    def full_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, k, r)
        B = b.offset_point(False, k, r)
        kind = _corner_kind(k, turn(ti, tj))
        if kind is Corner.TANGENT:
            return Joint(A, A)
        if kind is Corner.INSIDE:
            hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
            x = decisions.nearest_root(hits, A, B)
            if x is None:
                # As PMAC (docs/compensation.md, "Fagor changes while on"):
                # the change is introduced over the next move.
                return Joint(A, A)
            return Joint(x, x)
        return self.transition(P, A, B, ti, tj, k, r, self._corner_mode(a, b),
                               kind is Corner.REVERSAL, a.is_line, b.is_line)

    def lead_in_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the activation move, ``b`` the first compensated move."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        B = b.offset_point(False, k, r)
        kind = _corner_kind(k, turn(ti, tj))
        if kind in (Corner.INSIDE, Corner.TANGENT) or self._start_end(a.block) == "direct":
            return Joint(B, B)
        A = a.offset_point(True, k, r)
        return self.transition(P, A, B, ti, tj, k, r, self._corner_mode(a, b),
                               kind is Corner.REVERSAL, False, b.is_line)

    def lead_out_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the last compensated move, ``b`` the cancellation move."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, k, r)
        kind = _corner_kind(k, turn(ti, tj))
        if kind in (Corner.INSIDE, Corner.TANGENT) or self._start_end(b.block) == "direct":
            return Joint(A, A)
        B = b.offset_point(False, k, r)
        return self.transition(P, A, B, ti, tj, k, r, self._corner_mode(a, b),
                               kind is Corner.REVERSAL, a.is_line, False)

    def joint(self, a: Element, ca: str, b: Element, cb: str) -> Joint:
        if cb in (UNCOMP, LEAD_IN):
            # a ends where it is programmed (off or the cancellation move), or
            # at its offset end when the cancellation happened in place.
            if ca in (LEAD_IN, COMP):
                return Joint(a.offset_point(True, a.k, a.r), a.end)
            return Joint(a.end, a.end)
        if cb == LEAD_OUT:
            return self.lead_out_corner(a, b, a.k, a.r)
        if ca == LEAD_IN:
            return self.lead_in_corner(a, b, b.k, b.r)
        if a.k != b.k:
            # Side changes while on follow the PMAC rule (docs/compensation.md,
            # "Fagor changes while on").
            return self._pmac.side_change_corner(a, b)
        # A radius change (new D) is introduced over b, as PMAC.
        return self.full_corner(a, b, a.k, a.r)

    # -- the whole program ---------------------------------------------------------
    @by_plane
    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        scan = scan_program(program, radius=radius, side=side, style=self.name)
        els = scan.elements
        classes, cancel_at = self._classes(els, scan.gaps)
        for el, cl in zip(els, classes):
            if cl == COMP:
                el.check_offset(el.k, el.r)
        out = _FagorSegments()
        if not els:
            out.gap(scan.gaps[0], np.asarray(scan.start_uv, float), False)
        else:
            starts, ends, corners = self._joints(els, classes)
            self._emit_moves(out, scan.gaps, els, classes, cancel_at, starts, ends, corners)
            self._emit_tail(out, scan.gaps[-1], els[-1], ends[-1], cancel_at[-1])
        radius = max((el.r for el in els if el.k != 0), default=0.0)
        return ToolPath(tuple(out.segs), plane=scan.plane, style=self.name, radius=radius,
                        dwells=tuple(out.dwells), units=program.units,
                        meta={"corner": self.corner, "start_end": self.start_end})

    def _joints(self, els: list[Element], classes: list[str]):
        """Tool start and end point of every move and the transition segments
        after each; the last move ends at its offset end while still on."""
        n = len(els)
        starts: list = [None] * n
        ends: list = [None] * n
        corners: list[list] = [[] for _ in range(n)]
        starts[0] = els[0].start
        for i in range(n - 1):
            j = self.joint(els[i], classes[i], els[i + 1], classes[i + 1])
            ends[i], starts[i + 1], corners[i] = j.end_prev, j.start_next, j.corner
        last = els[-1]
        ends[-1] = last.offset_point(True, last.k, last.r) if last.k != 0 else last.end
        return starts, ends, corners

    def _emit_move(self, out: _FagorSegments, el: Element, cl: str, start, end) -> None:
        """One move's tool segment from ``start`` to ``end`` (a style with
        approach and retraction moves of its own overrides it: siemens.py)."""
        geom = tool_geometry(el, start, end)
        role = ROLE_OF[cl]
        if cl == UNCOMP and el.block.motion is Motion.RAPID:
            role = Role.RAPID
        if geom.length > POINT_EPS or el.w0 != el.w1:
            out.add(geom, role, el.block, el.w0, el.w1)

    @staticmethod
    def _corner_block(els: list[Element], i: int) -> Block:
        """The block the transition after move ``i`` belongs to (its feed):
        the incoming move's on the Fagor (a style may say otherwise)."""
        return els[i].block

    def _emit_moves(self, out: _FagorSegments, gaps, els, classes, cancel_at, starts, ends,
                    corners) -> None:
        """Each move, its transition and the gaps between moves. A gap runs
        after the transition, where the next move starts
        (decisions.FAGOR_GAP_MOVES_AFTER_TRANSITION), or else before it; a gap
        holding an in-place cancellation runs where the last compensated move
        ends."""
        n = len(els)
        gaps_after = decisions.FAGOR_GAP_MOVES_AFTER_TRANSITION

        def cancels(i: int) -> bool:    # gap i cancels compensation in place
            prev_on = i > 0 and els[i - 1].k != 0 and classes[i - 1] in (LEAD_IN, COMP)
            return prev_on and cancel_at[i] is not None

        for i, el in enumerate(els):
            if cancels(i):
                out.gap(gaps[i], ends[i - 1], True, (cancel_at[i], ends[i - 1], els[i - 1].end))
            elif gaps_after or i == 0:
                out.gap(gaps[i], starts[i], classes[i] in (COMP, LEAD_OUT))
            self._emit_move(out, el, classes[i], starts[i], ends[i])
            if not gaps_after and i + 1 < n and not cancels(i + 1):
                out.gap(gaps[i + 1], ends[i], classes[i + 1] in (COMP, LEAD_OUT))
            owner = self._corner_block(els, i)
            for cg in corners[i]:
                out.add(cg, Role.CORNER, owner, el.w1, el.w1)

    @staticmethod
    def _emit_tail(out: _FagorSegments, trailing: list[Block], last: Element, end,
                   cancel_blk: Block | None) -> None:
        """The blocks after the last in-plane move. Still on at program end:
        cancelled in place (decisions.FAGOR_PROGRAM_END_WHILE_ON
        ``"cancel-in-place"``: straight from the offset end to the programmed
        end), or ``"stay-at-offset"``."""
        if last.k == 0:
            out.gap(trailing, end, False)
        elif cancel_blk is not None:
            out.gap(trailing, end, True, (cancel_blk, end, last.end))
        else:
            out.gap(trailing, end, True)
            if decisions.FAGOR_PROGRAM_END_WHILE_ON == "cancel-in-place":
                out.add(_line(end, last.end), Role.LEAD_OUT, last.block, last.w1, last.w1)

    @staticmethod
    def _classes(els: list[Element], gaps: list[list[Block]]):
        """Move classes, and for each gap the block that cancels compensation
        in place (the first motion block after G40 when it does not move in
        the plane), or ``None``."""
        classes: list[str] = []
        cancel_at: list[Block | None] = [None] * (len(els) + 1)
        on = False
        for i in range(len(els) + 1):
            if on:
                first_off = next((b for b in gaps[i] if b.motion.is_move and b.modal.side == 0), None)
                if first_off is not None:
                    cancel_at[i] = first_off
                    on = False
            if i == len(els):
                break
            el = els[i]
            if el.k == 0:
                if on:
                    if el.block.motion.is_arc:
                        raise _err(el.block, "the move that cancels cutter compensation (the "
                                             "first move in the plane after G40) must be "
                                             "linear (G00/G01), not an arc: add a straight "
                                             "exit move before the arc")
                    classes.append(LEAD_OUT)
                else:
                    classes.append(UNCOMP)
                on = False
            else:
                if on:
                    classes.append(COMP)
                else:
                    if el.block.motion.is_arc and decisions.FAGOR_ARC_ACTIVATION_IS_AN_ERROR:
                        raise _err(el.block, "the move that activates cutter compensation (the "
                                             "first move in the plane after G41/G42) must be "
                                             "linear (G00/G01), not an arc: add a straight "
                                             "approach move")
                    classes.append(LEAD_IN)
                on = True
        return classes, cancel_at


__all__ = ["FagorStyle", "linear_transition"]
