"""PMAC / Turbo PMAC cutter radius compensation — the reference style.

Rules: spec "PMAC / Turbo PMAC style", from the PMAC User Manual pp.184-194
and the Turbo PMAC User Manual pp.294-302. The engine walks the in-plane
moves once; at each boundary between two of them it decides a *joint*: where
the incoming move's tool path ends, which corner segments are added, and
where the outgoing move's tool path starts. Each move's exact tool segment is
then its geometry between those two points (:func:`corners.tool_geometry`).

Move classes (by the side in force before and for the move):
``uncompensated`` (off, off), ``lead-in`` (off, on), ``compensated`` (on, on),
``lead-out`` (on, off).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, element_of,
    offset_dir, reversal_sweep, tool_geometry, turn,
)
from ccopt.compensate.scan import ScanResult, scan_program
from ccopt.geometry import Line
from ccopt.program.model import Block, Motion, Program
from ccopt.tolerances import PMAC_BREAK_COS, POINT_EPS
from ccopt.toolpath import PathSegment, Role, ToolPath

UNCOMP, LEAD_IN, COMP, LEAD_OUT = "uncompensated", "lead-in", "compensated", "lead-out"
ROLE_OF = {UNCOMP: Role.UNCOMPENSATED, LEAD_IN: Role.LEAD_IN, COMP: Role.COMPENSATED,
           LEAD_OUT: Role.LEAD_OUT}


@dataclass
class Joint:
    """Decision at the boundary between move ``i`` and move ``i+1``."""

    end_prev: np.ndarray
    start_next: np.ndarray
    corner: list = field(default_factory=list)  # exact Arc/Line geometries, role corner


def _pt(p) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


class PmacStyle:
    """The PMAC rules. ``break_cos`` is Isx99; ``ccbuf`` Turbo's ``DEFINE CCBUF``
    (``None``: unlimited look-ahead through non-plane moves)."""

    name = "pmac"

    def __init__(self, break_cos: float = PMAC_BREAK_COS, ccbuf: int | None = None):
        if not -1.0 <= break_cos <= 1.0:
            raise ValueError("break_cos must be in [-1, 1]")
        self.break_cos = float(break_cos)
        self.ccbuf = ccbuf

    # -- joints ------------------------------------------------------------------
    def full_corner(self, a: Element, b: Element, k: int, r: float, look_ahead_ok: bool) -> Joint:
        """Both moves fully compensated on side ``k`` with radius ``r`` at the corner."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, k, r)
        B = b.offset_point(False, k, r)
        tr = turn(ti, tj)
        kind = classify(k, tr)
        if not look_ahead_ok:
            # Turbo CCBUF exhausted: the controller could not see the next
            # move in time and treats the corner as outside (spec rule 6).
            return Joint(A, B, [corner_arc(P, r, ti, tj, k)] if kind is not Corner.TANGENT else [])
        if kind is Corner.TANGENT:
            return Joint(A, A)
        if kind is Corner.REVERSAL:
            if not (a.is_line and b.is_line):
                x = self._intersection(a, b, k, k, r, r, A, B)
                if x is not None:
                    return Joint(x, x)
            return Joint(A, B, [corner_arc(P, r, ti, tj, k, reversal_sweep(k))])
        if kind is Corner.INSIDE:
            x = self._intersection(a, b, k, k, r, r, A, B)
            if x is None:
                # No intersection: the change is introduced linearly over the
                # next move (Turbo p.301): it starts where this one ends.
                return Joint(A, A)
            return Joint(x, x)
        # outside
        if tr.d < self.break_cos:
            return Joint(A, B, [corner_arc(P, r, ti, tj, k)])
        x = self._intersection(a, b, k, k, r, r, A, B)
        if x is None and decisions.SHALLOW_WITHOUT_INTERSECTION == "arc":
            return Joint(A, B, [corner_arc(P, r, ti, tj, k)])
        return Joint(x, x)

    @staticmethod
    def _intersection(a: Element, b: Element, ka: int, kb: int, ra: float, rb: float, A, B):
        hits = carrier_intersections(a.carrier(True, ka, ra), b.carrier(False, kb, rb))
        return decisions.nearest_root(hits, A, B)

    def lead_in_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the lead-in, ``b`` the first fully compensated move (spec 2)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = classify(k, turn(ti, tj))
        B = b.offset_point(False, k, r)
        if kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(B, B)
        A = a.offset_point(True, k, r)
        sweep = reversal_sweep(k) if kind is Corner.REVERSAL else None
        return Joint(A, B, [corner_arc(P, r, ti, tj, k, sweep)])

    def lead_out_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the last compensated move, ``b`` the lead-out (spec 5)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = classify(k, turn(ti, tj))
        A = a.offset_point(True, k, r)
        if kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(A, A)
        B = b.offset_point(False, k, r)
        sweep = reversal_sweep(k) if kind is Corner.REVERSAL else None
        return Joint(A, B, [corner_arc(P, r, ti, tj, k, sweep)])

    def side_change_corner(self, a: Element, b: Element) -> Joint:
        """``CC1`` <-> ``CC2`` between two compensated moves (spec 4)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, a.k, a.r)
        B = b.offset_point(False, b.k, b.r)
        tr = turn(ti, tj)
        if classify(a.k, tr) is Corner.REVERSAL:
            # decisions.SIDE_CHANGE_REVERSAL: 180-degree arc on the old side,
            # then the gradual change over the next move.
            arc = corner_arc(P, a.r, ti, tj, a.k, reversal_sweep(a.k))
            return Joint(A, np.asarray(arc.end, float), [arc])
        x = self._intersection(a, b, a.k, b.k, a.r, b.r, A, B)
        if x is None:
            return Joint(A, A)
        return Joint(x, x)

    def joint(self, a: Element, ca: str, b: Element, cb: str, gap: int) -> Joint:
        P = a.end
        if cb in (UNCOMP, LEAD_IN):
            # a ends on the programmed point (it is uncompensated or a lead-out).
            return Joint(P, P)
        if cb == LEAD_OUT:
            return self.lead_out_corner(a, b, a.k, a.r)
        # b is fully compensated
        if ca == LEAD_IN:
            return self.lead_in_corner(a, b, b.k, b.r)
        if a.k != b.k:
            return self.side_change_corner(a, b)
        look_ahead_ok = self.ccbuf is None or gap <= self.ccbuf
        # A radius change is introduced over b: the corner uses the old radius
        # (decisions.RADIUS_CHANGE_OVER_NEXT_MOVE).
        return self.full_corner(a, b, a.k, a.r, look_ahead_ok)

    # -- the whole program ---------------------------------------------------------
    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        scan = scan_program(program, radius=radius, side=side, style=self.name)
        return assemble(self, scan, program)


def classes_of(elements: list[Element]) -> list[str]:
    out = []
    prev_k = 0
    for el in elements:
        if el.k == 0:
            out.append(UNCOMP if prev_k == 0 else LEAD_OUT)
        else:
            out.append(LEAD_IN if prev_k == 0 else COMP)
        prev_k = el.k
    return out


def assemble(style, scan: ScanResult, program: Program) -> ToolPath:
    """Turn the scanned elements into a ToolPath using ``style.joint``."""
    els = scan.elements
    classes = classes_of(els)
    for el, cl in zip(els, classes):
        # The offset of a fully compensated arc must exist (spec rule 7);
        # lead-in/out arcs are spirals that only reach the offset at one end.
        if cl == COMP:
            el.check_offset(el.k, el.r)
    n = len(els)
    starts: list[np.ndarray] = [None] * n  # type: ignore[list-item]
    ends: list[np.ndarray] = [None] * n  # type: ignore[list-item]
    corners: list[list] = [[] for _ in range(n)]
    if n:
        starts[0] = els[0].start
    for i in range(n - 1):
        j = style.joint(els[i], classes[i], els[i + 1], classes[i + 1], len(scan.gaps[i + 1]))
        ends[i] = j.end_prev
        starts[i + 1] = j.start_next
        corners[i] = j.corner
    tail_return = None
    if n:
        last = els[-1]
        if last.k != 0:
            # Still on at the end of the in-plane moves: PMAC's automatic
            # zero-distance lead-out (decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT).
            ends[-1] = last.offset_point(True, last.k, last.r)
            tail_return = (ends[-1], last.end)
        else:
            ends[-1] = last.end

    segs: list[PathSegment] = []
    dwells: list[tuple[int, float, Block]] = []

    def emit_gap(blocks: list[Block], at: np.ndarray, comp_on_default: bool) -> None:
        for blk in blocks:
            if blk.motion is Motion.DWELL:
                dwells.append((len(segs), blk.dwell, blk))
                continue
            w0 = blk.uvw(blk.start)[2]
            w1 = blk.uvw(blk.end)[2]
            role = Role.RAPID if blk.motion is Motion.RAPID and blk.modal.side == 0 else (
                Role.COMPENSATED if comp_on_default else Role.UNCOMPENSATED)
            segs.append(PathSegment(Line(_pt(at), _pt(at)), role, blk, w0, w1, blk.feed))

    if n == 0:
        emit_gap(scan.gaps[0], np.asarray(scan.start_uv, float), False)
    for i, el in enumerate(els):
        emit_gap(scan.gaps[i], starts[i], el.k != 0 and classes[i] != LEAD_IN)
        geom = tool_geometry(el, starts[i], ends[i])
        role = ROLE_OF[classes[i]]
        if classes[i] == UNCOMP and el.block.motion is Motion.RAPID:
            role = Role.RAPID
        if geom.length > POINT_EPS or el.w0 != el.w1:
            segs.append(PathSegment(geom, role, el.block, el.w0, el.w1, el.block.feed))
        for cg in corners[i]:
            segs.append(PathSegment(cg, Role.CORNER, el.block, el.w1, el.w1, el.block.feed))
    if n:
        trailing = scan.gaps[n]
        if tail_return is not None:
            # The return happens before the first trailing block with
            # compensation off, or at the very end.
            split = next((q for q, blk in enumerate(trailing) if blk.modal.side == 0), len(trailing))
            emit_gap(trailing[:split], tail_return[0], True)
            last = els[-1]
            segs.append(PathSegment(Line(_pt(tail_return[0]), _pt(tail_return[1])), Role.LEAD_OUT,
                                    last.block, last.w1, last.w1, last.block.feed))
            emit_gap(trailing[split:], tail_return[1], False)
        else:
            emit_gap(trailing, ends[-1], False)
    radius = max((el.r for el in els if el.k != 0), default=0.0)
    return ToolPath(tuple(segs), plane=scan.plane, style=style.name, radius=radius,
                    dwells=tuple(dwells), units=program.units,
                    meta={"break_cos": getattr(style, "break_cos", None)})
