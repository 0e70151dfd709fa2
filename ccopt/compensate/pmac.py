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

import numbers
from dataclasses import dataclass, field

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, reversal_sweep, tool_geometry,
    turn,
)
from ccopt.compensate.batch import (
    ARC, SPIRAL, ElementArrays, classify_turn, corner_turn, nearest_corner_points,
    offset_points, tool_segments,
)
from ccopt.compensate.scan import ScanResult, scan_program
from ccopt.geometry import Arc, Line
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
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
        if ccbuf is not None and not (isinstance(ccbuf, numbers.Integral) and ccbuf >= 0):
            raise ValueError(f"ccbuf must be a whole number >= 0 or None, got {ccbuf!r}")
        self.break_cos = float(break_cos)
        self.ccbuf = None if ccbuf is None else int(ccbuf)

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
                hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
                x = decisions.nearest_root(decisions.behind_corner(hits, P, ti), A, B)
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
        # Radius 0 in force at the corner (CCR0, or a change from 0 starting
        # here): the tool is on the programmed point, no corner is added.
        if cb == LEAD_OUT:
            r_here = a.r
        elif ca == LEAD_IN:
            # the lead-in's own radius: a change (e.g. from CCR0) made after
            # it is introduced over b (decisions.RADIUS_CHANGE_OVER_NEXT_MOVE)
            r_here = a.r
        elif a.k != b.k:
            r_here = max(a.r, b.r)
        else:
            r_here = a.r
        if r_here <= 0.0:
            return Joint(P, P)
        if cb == LEAD_OUT:
            return self.lead_out_corner(a, b, a.k, a.r)
        # b is fully compensated
        if ca == LEAD_IN:
            return self.lead_in_corner(a, b, b.k, a.r)
        if a.k != b.k:
            return self.side_change_corner(a, b)
        look_ahead_ok = self.ccbuf is None or gap <= self.ccbuf
        # A radius change is introduced over b: the corner uses the old radius
        # (decisions.RADIUS_CHANGE_OVER_NEXT_MOVE).
        return self.full_corner(a, b, a.k, a.r, look_ahead_ok)

    def batch_corners(self, arr: ElementArrays, ia: np.ndarray):
        """:meth:`full_corner` for many joints at once (same side, no gap, no
        spiral, look-ahead available). Returns ``(done, end_prev, start_next,
        arcs)``; joints not ``done`` (reversals, near-degenerate intersections)
        go to :meth:`joint`."""
        k, r = arr.k[ia], arr.r[ia]
        c, d = corner_turn(arr, ia)
        kind = classify_turn(k, c, d)
        A, B = offset_points(arr, ia, k, r)
        X, found, delicate = nearest_corner_points(arr, ia, k, r, A, B)
        inside, outside, tangent = kind == 0, kind == 1, kind == 2
        # radius 0 at the corner: the programmed point, no arc (as joint())
        zero = r <= 0.0
        inside, outside, tangent = inside & ~zero, outside & ~zero, tangent | zero
        sharp = outside & (d < self.break_cos)
        shallow = outside & ~sharp
        shallow_arc = shallow & ~found & (decisions.SHALLOW_WITHOUT_INTERSECTION == "arc")
        has_arc = sharp | shallow_arc
        use_x = (inside | shallow) & found
        done = tangent | has_arc | ((inside | shallow) & ~delicate)
        done &= ~(delicate & (inside | shallow))
        end_prev = np.where(use_x[:, None], X, A)
        start_next = np.where(use_x[:, None], X, np.where(has_arc[:, None], B, A))
        o = k[:, None] * np.c_[-arr.te[ia][:, 1], arr.te[ia][:, 0]]
        arcs = {"has": has_arc, "theta0": np.arctan2(o[:, 1], o[:, 0]),
                "sweep": np.arctan2(c, d)}
        return done, end_prev, start_next, arcs

    # -- the whole program ---------------------------------------------------------
    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        scan = scan_program(program, radius=radius, side=side, style=self.name)
        return assemble(self, scan, program)


def classes_of(k: np.ndarray) -> list[str]:
    """Class of each in-plane move from the side in force before and for it."""
    prev = np.r_[0, k[:-1]] if len(k) else np.zeros(0, int)
    codes = np.where(k == 0, np.where(prev == 0, 0, 3), np.where(prev == 0, 1, 2))
    names = (UNCOMP, LEAD_IN, COMP, LEAD_OUT)
    return [names[c] for c in codes]


def assemble(style, scan: ScanResult, program: Program, vectorised: bool = True) -> ToolPath:
    """Turn the scanned moves into a ToolPath using ``style.joint``.

    With ``vectorised`` (the default) the joints a style can decide in bulk
    (``style.batch_corners``, when it has one) and the line/arc tool segments
    go through :mod:`.batch`; every other joint and segment through the
    one-at-a-time reference. Both routes give the same path (tested).
    """
    n = len(scan)
    k, r = scan.k, scan.r
    classes = classes_of(k)
    comp = np.array([c == COMP for c in classes], bool)
    arr = ElementArrays.from_blocks(scan.blocks, scan.plane, k, r) if n else None
    # The offset of a fully compensated arc must exist (spec rule 7); lead-in
    # and lead-out arcs are spirals that only reach the offset at one end.
    if n:
        bad = comp & (arr.kind == ARC) & (arr.offset_radius(np.arange(n), k, r) <= POINT_EPS) & (k != 0)
        for i in np.flatnonzero(comp & ((arr.kind == SPIRAL) | bad)):
            scan.element(i).check_offset(int(k[i]), float(r[i]))
    starts = np.full((n, 2), np.nan)
    ends = np.full((n, 2), np.nan)
    corners: dict[int, list] = {}
    if n:
        starts[0] = arr.S[0]
    todo = np.arange(max(n - 1, 0))
    if vectorised and n > 1 and hasattr(style, "batch_corners"):
        gap_counts = np.array([len(g) for g in scan.gaps[1:n]], int)
        ia = np.flatnonzero(comp[:-1] & comp[1:] & (k[:-1] == k[1:]) & (gap_counts == 0)
                            & (arr.kind[:-1] != SPIRAL) & (arr.kind[1:] != SPIRAL))
        if len(ia):
            done, e_prev, s_next, arcs = style.batch_corners(arr, ia)
            ends[ia[done]] = e_prev[done]
            starts[ia[done] + 1] = s_next[done]
            for q in np.flatnonzero(done & arcs["has"]):
                corners[int(ia[q])] = [Arc(_pt(arr.E[ia[q]]), float(r[ia[q]]),
                                           float(arcs["theta0"][q]), float(arcs["sweep"][q]))]
            handled = np.zeros(n - 1, bool)
            handled[ia[done]] = True
            todo = np.flatnonzero(~handled)
    for i in todo:
        j = style.joint(scan.element(i), classes[i], scan.element(i + 1), classes[i + 1],
                        len(scan.gaps[i + 1]))
        ends[i] = j.end_prev
        starts[i + 1] = j.start_next
        if j.corner:
            corners[int(i)] = j.corner
    tail_return = None
    if n:
        if k[-1] != 0:
            # Still on at the end of the in-plane moves: PMAC's automatic
            # zero-distance lead-out (decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT).
            last = scan.element(n - 1)
            ends[-1] = last.offset_point(True, last.k, last.r)
            tail_return = (ends[-1], last.end)
        else:
            ends[-1] = arr.E[-1]

    # exact tool geometry of every move
    geoms: list = [None] * n
    if n:
        fast = np.flatnonzero(arr.kind != SPIRAL) if vectorised else np.zeros(0, int)
        for i, g in zip(fast, tool_segments(arr, fast, starts, ends)):
            geoms[i] = g
        for i in range(n):
            if geoms[i] is None:
                geoms[i] = tool_geometry(scan.element(i), starts[i], ends[i])

    segs: list[PathSegment] = []
    dwells: list[tuple[int, float, Block]] = []

    def emit_gap(blocks: list[Block], at: np.ndarray, comp_on: bool) -> None:
        for blk in blocks:
            if blk.motion is Motion.DWELL:
                dwells.append((len(segs), blk.dwell, blk))
                continue
            w0 = blk.uvw(blk.start)[2]
            w1 = blk.uvw(blk.end)[2]
            role = Role.RAPID if blk.motion is Motion.RAPID and blk.modal.side == 0 else (
                Role.COMPENSATED if comp_on else Role.UNCOMPENSATED)
            segs.append(PathSegment(Line(_pt(at), _pt(at)), role, blk, w0, w1, blk.feed))

    if n == 0:
        emit_gap(scan.gaps[0], np.asarray(scan.start_uv, float), False)
    plane_w = PLANE_AXES[scan.plane][2]
    for i, blk in enumerate(scan.blocks):
        if scan.gaps[i]:
            emit_gap(scan.gaps[i], starts[i], k[i] != 0 and classes[i] != LEAD_IN)
        geom = geoms[i]
        role = ROLE_OF[classes[i]]
        if classes[i] == UNCOMP and blk.motion is Motion.RAPID:
            role = Role.RAPID
        w0, w1 = blk.start[plane_w], blk.end[plane_w]
        if geom.length > POINT_EPS or w0 != w1:
            segs.append(PathSegment(geom, role, blk, w0, w1, blk.feed))
        for cg in corners.get(i, ()):
            segs.append(PathSegment(cg, Role.CORNER, blk, w1, w1, blk.feed))
    if n:
        trailing = scan.gaps[n]
        last_blk = scan.blocks[-1]
        w_last = last_blk.end[plane_w]
        if tail_return is not None:
            # The return happens before the first trailing block with
            # compensation off, or at the very end.
            split = next((q for q, blk in enumerate(trailing) if blk.modal.side == 0), len(trailing))
            emit_gap(trailing[:split], tail_return[0], True)
            segs.append(PathSegment(Line(_pt(tail_return[0]), _pt(tail_return[1])), Role.LEAD_OUT,
                                    last_blk, w_last, w_last, last_blk.feed))
            emit_gap(trailing[split:], tail_return[1], False)
        else:
            emit_gap(trailing, ends[-1], False)
    radius = float(r[k != 0].max()) if n and (k != 0).any() else 0.0
    return ToolPath(tuple(segs), plane=scan.plane, style=style.name, radius=radius,
                    dwells=tuple(dwells), units=program.units,
                    meta={"break_cos": getattr(style, "break_cos", None)})
