"""PMAC / Turbo PMAC cutter radius compensation — the reference style.

Rules: docs/compensation.md, section 4 "PMAC / Turbo PMAC style", from the
PMAC User Manual pp.184-194 and the Turbo PMAC User Manual pp.294-302. The
engine walks the in-plane moves once; at each boundary between two of them it
decides a *joint*: where the incoming move's tool path ends, which corner
segments are added, and where the outgoing move's tool path starts. Each
move's exact tool segment is then its geometry between those two points
(:func:`corners.tool_geometry`).

Move classes (by the side in force before and for the move):
``uncompensated`` (off, off), ``lead-in`` (off, on), ``compensated`` (on, on),
``lead-out`` (on, off).
"""
from __future__ import annotations

import numbers
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import (
    Corner, Element, carrier_intersections, classify, corner_arc, corner_side, reversal_sweep,
    tool_geometry, turn,
)
from ccopt.compensate.batch import (
    ARC, SPIRAL, ElementArrays, classify_turn, corner_tangents, corner_turn, nearest_corner_points,
    offset_points,
)
from ccopt.compensate.emit import COMP_CODE, class_codes, emit_columns
from ccopt.compensate.planes import by_plane
from ccopt.compensate.scan import ScanResult, scan_program
from ccopt.geometry import Arc, Line
from ccopt.geometry.columns import paused_gc, put_rows, take_rows
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.tolerances import PMAC_BREAK_COS, POINT_EPS
from ccopt.toolpath import PathSegment, Role, ToolPath

UNCOMP, LEAD_IN, COMP, LEAD_OUT = "uncompensated", "lead-in", "compensated", "lead-out"
#: Programs of fewer in-plane moves are written segment by segment: the
#: column route's fixed cost (some sixty numpy calls, about 0.1 ms) is more
#: than making a few dozen segments costs.
COLUMNS_MIN_MOVES = 64
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


def _lead_corner_kind(k: int, tr) -> Corner:
    """The corner class at the end of a lead-in or the start of a lead-out: a
    full reversal counts as outside (the 180-degree arc) or, without
    :data:`decisions.LEAD_REVERSAL_IS_OUTSIDE`, as inside (no arc)."""
    kind = classify(k, tr)
    if kind is Corner.REVERSAL and not decisions.LEAD_REVERSAL_IS_OUTSIDE:
        return Corner.INSIDE
    return kind


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
            # move in time and treats the corner as outside (rule 6).
            return Joint(A, B, [corner_arc(P, r, ti, tj, k)] if kind is not Corner.TANGENT else [])
        if kind is Corner.TANGENT:
            return Joint(A, A)
        if kind is Corner.REVERSAL:
            if not (a.is_line and b.is_line):
                hits = carrier_intersections(a.carrier(True, k, r), b.carrier(False, k, r))
                near = corner_side(hits, P, ti, decisions.REVERSAL_INTERSECTION_BEHIND_CORNER)
                x = decisions.nearest_root(near, A, B)
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
        if x is None:
            if decisions.SHALLOW_WITHOUT_INTERSECTION == "arc":
                return Joint(A, B, [corner_arc(P, r, ti, tj, k)])
            return Joint(A, A)      # "gradual": as an inside corner without one
        return Joint(x, x)

    @staticmethod
    def _intersection(a: Element, b: Element, ka: int, kb: int, ra: float, rb: float, A, B):
        hits = carrier_intersections(a.carrier(True, ka, ra), b.carrier(False, kb, rb))
        return decisions.nearest_root(hits, A, B)

    def lead_in_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the lead-in, ``b`` the first fully compensated move (rule 2)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = _lead_corner_kind(k, turn(ti, tj))
        B = b.offset_point(False, k, r)
        if kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(B, B)
        A = a.offset_point(True, k, r)
        sweep = reversal_sweep(k) if kind is Corner.REVERSAL else None
        return Joint(A, B, [corner_arc(P, r, ti, tj, k, sweep)])

    def lead_out_corner(self, a: Element, b: Element, k: int, r: float) -> Joint:
        """``a`` is the last compensated move, ``b`` the lead-out (rule 5)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        kind = _lead_corner_kind(k, turn(ti, tj))
        A = a.offset_point(True, k, r)
        if kind in (Corner.INSIDE, Corner.TANGENT):
            return Joint(A, A)
        B = b.offset_point(False, k, r)
        sweep = reversal_sweep(k) if kind is Corner.REVERSAL else None
        return Joint(A, B, [corner_arc(P, r, ti, tj, k, sweep)])

    def side_change_corner(self, a: Element, b: Element) -> Joint:
        """``CC1`` <-> ``CC2`` between two compensated moves (rule 4)."""
        P = a.end
        ti, tj = a.t_end, b.t_start
        A = a.offset_point(True, a.k, a.r)
        B = b.offset_point(False, b.k, b.r)
        tr = turn(ti, tj)
        if (classify(a.k, tr) is Corner.REVERSAL
                and decisions.SIDE_CHANGE_REVERSAL == "arc-then-gradual"):
            # 180-degree arc on the old side, then the gradual change over the
            # next move (otherwise, "gradual": the change alone, from A).
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
            # it is introduced over b (a radius change is introduced linearly
            # over the next move: docs/compensation.md, rule 4)
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
        # (docs/compensation.md, rule 4: radius change over the next move).
        return self.full_corner(a, b, a.k, a.r, look_ahead_ok)

    def batch_corners(self, arr: ElementArrays, ia: np.ndarray):
        """:meth:`full_corner` for many joints at once (same side, no gap, no
        spiral, look-ahead available). Returns ``(done, end_prev, start_next,
        arcs)``; joints not ``done`` (reversals, near-degenerate intersections)
        go to :meth:`joint`."""
        k, r = arr.k[ia], arr.r[ia]
        te, ts = corner_tangents(arr, ia)
        c, d = corner_turn(te, ts)
        kind = classify_turn(k, c, d)
        A, B = offset_points(arr, ia, k, r, te, ts)
        X, found, delicate = nearest_corner_points(arr, ia, k, r, A, B, te, ts)
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
        # the corner arc's start angle: the outward normal k * (-t_y, t_x); only
        # the corners with an arc are read (NaN elsewhere)
        arcs = {"has": has_arc, "theta0": np.full(ia.size, np.nan),
                "sweep": np.full(ia.size, np.nan)}
        q = np.flatnonzero(has_arc)
        kq, teq = k[q], te[q]
        arcs["theta0"][q] = np.arctan2(kq * teq[:, 0], kq * -teq[:, 1])
        arcs["sweep"][q] = np.arctan2(c[q], d[q])
        return done, end_prev, start_next, arcs

    # -- the whole program ---------------------------------------------------------
    @by_plane
    def compensate(self, program: Program, radius: float | None = None,
                   side: int | None = None) -> ToolPath:
        with paused_gc():       # one object per block and segment: see paused_gc
            scan = scan_program(program, radius=radius, side=side, style=self.name)
            return assemble(self, scan, program)


def classes_of(k: np.ndarray) -> "MoveClasses":
    """Class of each in-plane move from the side in force before and for it."""
    return MoveClasses(class_codes(k))


class MoveClasses(Sequence):
    """The class names (:data:`UNCOMP`, :data:`LEAD_IN`, :data:`COMP`,
    :data:`LEAD_OUT`) of the in-plane moves, from their codes
    (:func:`~ccopt.compensate.emit.class_codes`, kept as :attr:`codes`): a
    name is looked up when asked for, since on a long program the joints are
    mostly decided in bulk from the codes and few names are ever read."""

    NAMES = (UNCOMP, LEAD_IN, COMP, LEAD_OUT)

    def __init__(self, codes: np.ndarray):
        self.codes = codes

    def __len__(self) -> int:
        return len(self.codes)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return list(map(self.NAMES.__getitem__, self.codes[i].tolist()))
        return self.NAMES[self.codes[i]]

    def __iter__(self):
        return map(self.NAMES.__getitem__, self.codes.tolist())


@dataclass
class Joints:
    """Every joint of a program decided: tool point where each move starts and
    ends, the corner geometries added after move ``i`` (``corners[i]``), and
    the automatic lead-out ``(from, to)`` at the end (``None`` when there is
    none)."""

    starts: np.ndarray
    ends: np.ndarray
    corners: dict[int, list] = field(default_factory=dict)
    tail_return: tuple | None = None
    #: corner arcs decided in bulk: (move indices, rows ``(cu, cv, radius,
    #: theta0, sweep)``), one arc after each of those moves
    arc_rows: tuple = (np.zeros(0, np.int64), np.zeros((0, 5)))


def check_arc_offsets(scan: ScanResult, arr: ElementArrays, classes: MoveClasses) -> None:
    """The offset of a fully compensated arc must exist (rule 7);
    lead-in and lead-out arcs are spirals that only reach the offset at one
    end. Raises CompensationError at the first arc whose offset vanishes."""
    k, r = scan.k, scan.r
    comp = classes.codes == COMP_CODE
    vanishes = (comp & (arr.kind == ARC) & (k != 0)
                & (arr.offset_radius(np.arange(len(scan)), k, r) <= POINT_EPS))
    for i in np.flatnonzero(comp & ((arr.kind == SPIRAL) | vanishes)):
        scan.element(i).check_offset(int(k[i]), float(r[i]))


def _batch_joints(style, scan: ScanResult, arr: ElementArrays, classes: MoveClasses,
                  joints: Joints) -> np.ndarray:
    """Decide the ordinary joints in bulk (``style.batch_corners``: both moves
    compensated on one side, no gap, no spiral); the joints left to
    ``style.joint`` one at a time."""
    n, k = len(scan), scan.k
    comp = classes.codes == COMP_CODE
    gap_counts = scan.gaps.sizes()[1:n]
    ia = np.flatnonzero(comp[:-1] & comp[1:] & (k[:-1] == k[1:]) & (gap_counts == 0)
                        & (arr.kind[:-1] != SPIRAL) & (arr.kind[1:] != SPIRAL))
    if not len(ia):
        return np.arange(n - 1)
    done, e_prev, s_next, arcs = style.batch_corners(arr, ia)
    at = np.flatnonzero(done)
    put_rows(joints.ends, ia[at], take_rows(e_prev, at))
    put_rows(joints.starts, ia[at] + 1, take_rows(s_next, at))
    q = np.flatnonzero(done & arcs["has"])
    rows = np.empty((q.size, 5))
    rows[:, 0:2] = take_rows(arr.E, ia[q])
    rows[:, 2], rows[:, 3], rows[:, 4] = scan.r[ia[q]], arcs["theta0"][q], arcs["sweep"][q]
    bad = ~(np.isfinite(rows).all(axis=1) & (rows[:, 2] > 0.0))
    for c in rows[bad].tolist():        # the checked constructor says what is wrong
        Arc((c[0], c[1]), c[2], c[3], c[4])
    joints.arc_rows = (ia[q], rows)
    handled = np.zeros(n - 1, bool)
    handled[ia[done]] = True
    return np.flatnonzero(~handled)


def decide_joints(style, scan: ScanResult, arr: ElementArrays, classes: MoveClasses,
                  vectorised: bool) -> Joints:
    """Every joint of the program, and where the last move ends."""
    n, k = len(scan), scan.k
    joints = Joints(np.full((n, 2), np.nan), np.full((n, 2), np.nan))
    joints.starts[0] = arr.S[0]
    todo = np.arange(n - 1)
    if vectorised and n > 1 and hasattr(style, "batch_corners"):
        todo = _batch_joints(style, scan, arr, classes, joints)
    for i in todo:
        j = style.joint(scan.element(i), classes[i], scan.element(i + 1), classes[i + 1],
                        len(scan.gaps[i + 1]))
        joints.ends[i] = j.end_prev
        joints.starts[i + 1] = j.start_next
        if j.corner:
            joints.corners[int(i)] = j.corner
    if k[-1] != 0:
        # Still on at the end of the in-plane moves: the last move ends at its
        # offset end, and PMAC's automatic zero-distance lead-out returns to
        # the programmed point (decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT;
        # without it the path stays at the offset).
        last = scan.element(n - 1)
        joints.ends[-1] = last.offset_point(True, last.k, last.r)
        if decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT:
            joints.tail_return = (joints.ends[-1], last.end)
    else:
        joints.ends[-1] = arr.E[-1]
    return joints


def tool_geometries(scan: ScanResult, joints: Joints) -> list:
    """The exact tool geometry of every move between its joints, one at a
    time (:func:`corners.tool_geometry`: the reference route)."""
    return [tool_geometry(scan.element(i), joints.starts[i], joints.ends[i])
            for i in range(len(scan))]


class SegmentList:
    """The tool path's segments and dwells, in the order the machine runs them."""

    def __init__(self) -> None:
        self.segs: list[PathSegment] = []
        self.dwells: list[tuple[int, float, Block]] = []

    def gap(self, blocks: list[Block], at, comp_on: bool) -> None:
        """Blocks with no in-plane motion (Z moves, dwells) at tool point ``at``."""
        for blk in blocks:
            if blk.motion is Motion.DWELL:
                self.dwells.append((len(self.segs), blk.dwell, blk))
                continue
            w0 = blk.uvw(blk.start)[2]
            w1 = blk.uvw(blk.end)[2]
            role = Role.RAPID if blk.motion is Motion.RAPID and blk.modal.side == 0 else (
                Role.COMPENSATED if comp_on else Role.UNCOMPENSATED)
            self.segs.append(PathSegment(Line(_pt(at), _pt(at)), role, blk, w0, w1, blk.feed))

    def add(self, geom, role: Role, blk: Block, w0: float, w1: float) -> None:
        self.segs.append(PathSegment(geom, role, blk, w0, w1, blk.feed))


def emit_moves(out: SegmentList, scan: ScanResult, classes: MoveClasses, geoms: list,
               joints: Joints) -> None:
    """Each move's tool segment, its corner segments and the gaps between moves.

    A gap (moves with no in-plane component, dwells) between two moves runs at
    the compensated corner point after the added corner segments
    (decisions.GAP_MOVES_AFTER_CORNER_ARC), or else before them, where the
    incoming move ends.
    """
    n, k = len(scan), scan.k
    plane_w = PLANE_AXES[scan.plane][2]
    gaps_after = decisions.GAP_MOVES_AFTER_CORNER_ARC

    def comp_on(i: int) -> bool:     # gap before move i runs compensated
        return k[i] != 0 and classes[i] != LEAD_IN

    # One pass over plain lists with the look-ups hoisted: this loop runs once
    # per block of the program.
    gaps, corners, segs = scan.gaps, joints.corners, out.segs
    rapid, corner_role = Motion.RAPID, Role.CORNER
    for i, (blk, cls, geom) in enumerate(zip(scan.blocks, classes, geoms)):
        if gaps[i] and (gaps_after or i == 0):
            out.gap(gaps[i], joints.starts[i], comp_on(i))
        motion = blk.motion
        role = Role.RAPID if cls == UNCOMP and motion is rapid else ROLE_OF[cls]
        w0, w1 = blk.start[plane_w], blk.end[plane_w]
        if geom.length > POINT_EPS or w0 != w1:
            segs.append(PathSegment(geom, role, blk, w0, w1, blk.feed))
        if not gaps_after and i + 1 < n and gaps[i + 1]:
            out.gap(gaps[i + 1], joints.ends[i], comp_on(i + 1))
        if corners and i in corners:
            for cg in corners[i]:
                segs.append(PathSegment(cg, corner_role, blk, w1, w1, blk.feed))


def emit_tail(out: SegmentList, scan: ScanResult, joints: Joints) -> None:
    """The blocks after the last in-plane move, and the automatic lead-out:
    it happens before the first trailing block with compensation off, or at
    the very end."""
    trailing = scan.gaps[len(scan)]
    if joints.tail_return is None and scan.k[-1] == 0:
        out.gap(trailing, joints.ends[-1], False)
        return
    last_blk = scan.blocks[-1]
    w_last = last_blk.end[PLANE_AXES[scan.plane][2]]
    split = next((q for q, blk in enumerate(trailing) if blk.modal.side == 0), len(trailing))
    out.gap(trailing[:split], joints.ends[-1], True)
    end = joints.ends[-1]
    if joints.tail_return is not None:
        start, end = joints.tail_return
        out.add(Line(_pt(start), _pt(end)), Role.LEAD_OUT, last_blk, w_last, w_last)
    out.gap(trailing[split:], end, False)


def assemble(style, scan: ScanResult, program: Program, vectorised: bool = True,
             columns: bool | None = None) -> ToolPath:
    """Turn the scanned moves into a ToolPath using ``style.joint``.

    With ``vectorised`` (the default) the joints a style can decide in bulk
    (``style.batch_corners``, when it has one) go through :mod:`.batch`, and
    with ``columns`` the path is written as columns (:mod:`.emit`: tool
    segments in bulk, no object per segment until asked for); every other
    joint and segment through the one-at-a-time reference. ``columns=None``:
    with ``vectorised``, for programs of at least :data:`COLUMNS_MIN_MOVES`
    moves. All routes give the same path (tested).
    """
    n, k, r = len(scan), scan.k, scan.r
    out = SegmentList()
    radius = float(r[k != 0].max()) if n and (k != 0).any() else 0.0
    meta = {"break_cos": getattr(style, "break_cos", None)}
    if n == 0:
        out.gap(scan.gaps[0], np.asarray(scan.start_uv, float), False)
    else:
        classes = classes_of(k)
        arr = ElementArrays.from_blocks(scan.blocks, scan.plane, k, r, scan.columns)
        check_arc_offsets(scan, arr, classes)
        joints = decide_joints(style, scan, arr, classes, vectorised)
        if columns is None:
            columns = vectorised and n >= COLUMNS_MIN_MOVES
        if columns:
            # the path as columns: no object per segment until asked for
            rows, dwells = emit_columns(scan, arr, joints, classes.codes)
            return ToolPath.from_columns(rows, plane=scan.plane, style=style.name,
                                         radius=radius, dwells=dwells, units=program.units,
                                         meta=meta)
        arc_at, arc_rows = joints.arc_rows
        for i, (cu, cv, radius_i, theta0, sweep) in zip(arc_at.tolist(), arc_rows.tolist()):
            joints.corners[i] = [Arc((cu, cv), radius_i, theta0, sweep)]
        emit_moves(out, scan, classes, tool_geometries(scan, joints), joints)
        emit_tail(out, scan, joints)
    return ToolPath(tuple(out.segs), plane=scan.plane, style=style.name, radius=radius,
                    dwells=tuple(out.dwells), units=program.units, meta=meta)
