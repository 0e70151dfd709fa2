"""The contour: which programmed elements are part surface, and on which side.

The rules (the verifier's decisions, docs/compensation.md section 8.1):
fully compensated moves are the contour; side-change moves are transitions;
radius-change moves keep the smaller radius; where the contour stops its ends
are *open* (:data:`ccopt.verify.decisions.OPEN_END_EXEMPTION`).

The programmed geometry of each element is exactly
:func:`ccopt.toolpath.block_geometry` of its block; lines and arcs are built
here with array arithmetic (same formulas, tested equal), spirals through
``block_geometry`` itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import chain, repeat
from operator import attrgetter, is_

import numpy as np

from ccopt.geometry import KIND_ARC, KIND_LINE, KIND_SPIRAL, SegmentArray
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.arclength import END_POINT_REL_TOL
from ccopt.program.columns import CCW_CODE, DWELL_CODE, BlockColumns, columns_of
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.tolerances import SPIRAL_RADIUS_REL_TOL, VERIFY_EPS
from ccopt.toolpath import block_geometry, effective_side_radius
from ccopt.verify import decisions
from ccopt.verify.segments import Packed, arc_bbox, pack
from ccopt.verify.surface import WHY_LEAD_IN, WHY_LEAD_OUT, WHY_SIDE_CHANGE, surface_of

#: Why a move is or is not part of the contour.
STATUS_OFF = "off"                  # compensation off for the move (uncompensated, lead-out)
STATUS_LEAD_IN = "lead-in"          # on for the move, off before it
STATUS_STEADY = "steady"            # on before and during, same side and radius
STATUS_RADIUS_CHANGE = "radius-change"  # on before and during, new radius introduced over it
STATUS_SIDE_CHANGE = "side-change"  # on before and during, new side introduced over it
STATUS_AIR = "air"                  # on before and during, but a lead in air (surface.py)
STATUS_NAMES = (STATUS_OFF, STATUS_LEAD_IN, STATUS_STEADY, STATUS_RADIUS_CHANGE, STATUS_SIDE_CHANGE,
                STATUS_AIR)
_SIDE, _RADIUS = attrgetter("side"), attrgetter("radius")
_CENTER, _TURNS = attrgetter("center"), attrgetter("turns")

#: The program's radius and the tool path's are the same when they differ by
#: at most this times ``max(1, r)`` (a radius written to a file and read back).
RADIUS_SAME_REL = 1e-12


@dataclass(frozen=True, eq=False)
class Contour:
    """The part surface of a program, element by element.

    Attributes
    ----------
    blocks: the contour element's block, per element.
    elements: :class:`~ccopt.verify.segments.Packed` programmed geometry.
    side: ``+1`` left / ``-1`` right, per element.
    radius: cutter radius in force for the element (program units).
    clearance: required tool-centre distance (the radius, or the smaller of
        the two around a radius change).
    steady: contact and side are required along the element's tool segment.
    open_start, open_end: the contour stops at that end and is open there:
        tool points beyond it are exempt from the element (all False when
        :data:`ccopt.verify.decisions.OPEN_END_EXEMPTION` is off).
    plane: plane of compensation.
    moves: every in-plane move of the program, in order; per move:
        ``move_status`` (a ``STATUS_*``), ``move_k``, ``move_r`` (side and radius
        in force), ``move_element`` (its contour element, or -1),
        ``move_start``, ``move_end`` (its in-plane end points, ``(n, 2)``).
    notes: what the verifier assumed (e.g. a radius taken from the tool path).
    surface: which fully compensated moves were taken as part and which as
        air, and why (:meth:`ccopt.verify.surface.Surface.report`).
    """

    blocks: tuple[Block, ...]
    elements: Packed
    side: np.ndarray
    radius: np.ndarray
    clearance: np.ndarray
    steady: np.ndarray
    open_start: np.ndarray
    open_end: np.ndarray
    plane: str
    moves: tuple[Block, ...] = field(repr=False)
    move_status: np.ndarray = field(repr=False)
    move_k: np.ndarray = field(repr=False)
    move_r: np.ndarray = field(repr=False)
    move_element: np.ndarray = field(repr=False)
    move_start: np.ndarray = field(repr=False)
    move_end: np.ndarray = field(repr=False)
    notes: tuple[str, ...] = ()
    surface: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.blocks)

    def element_line(self, j: int) -> int | None:
        b = self.blocks[int(j)]
        return b.source.line if b is not None else None

    def move_indices(self, blocks) -> np.ndarray:
        """Index into :attr:`moves` of each block (-1 when it is not an in-plane
        move of the program, or ``None``). Blocks are matched by identity, and
        by value for a tool path whose blocks are equal copies."""
        blocks = list(blocks)
        if len(blocks) == len(self.moves) and all(map(is_, blocks, self.moves)):
            # the common case: a path compensated from this program lists its
            # in-plane moves, the contour's moves, in order
            return np.arange(len(blocks), dtype=np.intp)
        by_id = self.__dict__.get("_by_id")
        if by_id is None:
            by_id = dict(zip(map(id, self.moves), range(len(self.moves))))
            object.__setattr__(self, "_by_id", by_id)
        out = np.fromiter(map(by_id.get, map(id, blocks), repeat(-1)), np.intp, len(blocks))
        miss = [q for q in np.flatnonzero(out < 0) if blocks[q] is not None]
        if miss:
            by_val = self.__dict__.get("_by_value")
            if by_val is None:
                by_val = {}
                for q, b in enumerate(self.moves):
                    by_val.setdefault(b, q)
                object.__setattr__(self, "_by_value", by_val)
            for q in miss:
                out[q] = by_val.get(blocks[q], -1)
        return out


def element_geometry(blocks: list[Block], plane: str, st=None, en=None, ce=None, is_arc=None,
                     ccw=None, turns=None) -> Packed:
    """Programmed geometry of ``blocks`` by :func:`block_geometry`'s rules, packed
    (in-plane start, end, centre, arc flags and turns may be passed if known).

    Lines and spirals are :func:`block_geometry`'s to the bit; arcs are made
    with numpy's ``hypot``, ``arctan2``, ``cos`` and ``sin``, whose results can
    differ from :mod:`math`'s (which :func:`block_geometry` uses) in the last
    bit: on seeded random arcs (radii 0.01 to 100 about centres within 100)
    about 7 % differ from the :class:`~ccopt.geometry.Arc` of their block,
    the radius and start angle by at most an ulp, the sweep by at most 1e-15
    rad and the end points by at most 1.1e-15 times the coordinates' size,
    far below every tolerance the verifier applies (:mod:`ccopt.tolerances`)."""
    n = len(blocks)
    if n == 0:
        return pack([])
    i, j, _ = PLANE_AXES[plane]
    if st is None:
        st = np.array([b.start for b in blocks], float).reshape(n, 3)[:, [i, j]]
        en = np.array([b.end for b in blocks], float).reshape(n, 3)[:, [i, j]]
        nan3 = (math.nan, math.nan, math.nan)
        ce = np.array([b.center if b.center is not None else nan3 for b in blocks],
                      float).reshape(n, 3)[:, [i, j]]
        is_arc = np.array([b.motion.is_arc for b in blocks], bool)
        ccw = np.array([b.motion is Motion.ARC_CCW for b in blocks], bool)
        turns = np.array([b.turns for b in blocks], float)
    R0 = np.hypot(*(st - ce).T)
    R1 = np.hypot(*(en - ce).T)
    spiral = is_arc & (np.abs(R1 - R0) > SPIRAL_RADIUS_REL_TOL * np.maximum(1.0, R0))
    arc = is_arc & ~spiral
    kind = np.where(is_arc, np.where(spiral, KIND_SPIRAL, KIND_ARC), KIND_LINE).astype(np.int8)
    p0, p1 = st.copy(), en.copy()
    center = np.where(is_arc[:, None], ce, np.nan)
    radius = np.where(is_arc, R0, np.nan)
    radius_end = np.where(is_arc, R0, np.nan)
    theta0 = np.full(n, np.nan)
    sweep = np.full(n, np.nan)
    bbox = np.c_[np.minimum(st[:, 0], en[:, 0]), np.minimum(st[:, 1], en[:, 1]),
                 np.maximum(st[:, 0], en[:, 0]), np.maximum(st[:, 1], en[:, 1])]
    if arc.any():
        a = np.flatnonzero(arc)
        c, R = ce[a], R0[a]
        th0 = np.arctan2(st[a, 1] - c[:, 1], st[a, 0] - c[:, 0])
        th1 = np.arctan2(en[a, 1] - c[:, 1], en[a, 0] - c[:, 0])
        # geometry.angles.sweep_between with Arc.from_points' full-circle bound.
        gap = np.where(ccw[a], th1 - th0, th0 - th1)
        gap = np.fmod(gap, TWO_PI)
        gap = np.where(gap < 0.0, gap + TWO_PI, gap)
        fib = END_POINT_REL_TOL * np.maximum(1.0, R) / R
        gap = np.where((gap <= fib) | (TWO_PI - gap <= fib) | (gap >= TWO_PI), TWO_PI, gap)
        gap = gap + TWO_PI * turns[a]
        sw = np.where(ccw[a], gap, -gap)
        theta0[a], sweep[a] = th0, sw
        e = th0 + sw
        p0[a] = np.c_[c[:, 0] + R * np.cos(th0), c[:, 1] + R * np.sin(th0)]
        p1[a] = np.c_[c[:, 0] + R * np.cos(e), c[:, 1] + R * np.sin(e)]
        bbox[a] = arc_bbox(c, R, th0, sw, p0[a], p1[a])
    curved = {}
    for q in np.flatnonzero(spiral):
        g = block_geometry(blocks[q])
        curved[int(q)] = g
        p0[q], p1[q] = g.start, g.end
        center[q] = g.center
        radius[q], radius_end[q] = g.rho0, g.rho1
        theta0[q], sweep[q] = g.theta0, g.sweep
        bbox[q] = g.bbox()
    for arr in (kind, p0, p1, center, radius, radius_end, theta0, sweep):
        arr.flags.writeable = False
    return Packed(SegmentArray(kind, p0, p1, center, radius, radius_end, theta0, sweep), bbox,
                  curved)


def contour_of(program: Program, radius: float | None = None, side: int | None = None,
               toolpath_radius: float | None = None, *, part_lines=None,
               eps: float = VERIFY_EPS) -> Contour:
    """The contour of ``program`` (docs/compensation.md section 8.1).

    ``radius``/``side`` override the program as in
    :func:`ccopt.compensate.compensate`. ``toolpath_radius`` is the radius the
    tool path says it was made with
    (:data:`~ccopt.verify.decisions.RADIUS_FROM_TOOLPATH_WHEN_UNIFORM`).
    ``part_lines``: the program lines that are part surface (``"A-B,C-D"`` or
    pairs), else the markers and the closed-loop rule decide
    (:mod:`ccopt.verify.surface`); ``eps``: how near a loop must close.
    """
    mv = _InPlaneMoves.of(program)
    k, r, notes = _sides_and_radii(mv, columns_of(program), radius, side, toolpath_radius)
    n = len(mv.moves)
    prev_k = np.r_[0, k[:-1]] if n else k
    prev_r = np.r_[0.0, r[:-1]] if n else r
    # The contour is the fully compensated moves: compensation on for the move
    # and for the one before (lead-ins approach the contour, they are not part
    # surface); a move introducing a side change is a transition (the tool
    # crosses it from one side to the other); one introducing a radius change
    # is part surface with the smaller radius and no contact requirement (PMAC
    # rule 4 makes the offset vary along it). These are verifier decisions with
    # no alternative the verifier could take (docs/compensation.md section 8.1).
    on = (k != 0) & (prev_k != 0)
    side_change = on & (k != prev_k)
    radius_change = on & ~side_change & (r != prev_r)
    steady = on & ~side_change & ~radius_change
    # Of those, the part surface: a closed loop's moves, or what the user says
    # (surface.py); the others are leads in air, checked against the part only.
    surf = surface_of(mv.moves, steady | radius_change, mv.start, mv.end, mv.is_arc, eps,
                      part_lines, program.file)
    air = (steady | radius_change) & ~surf.part
    steady, radius_change = steady & surf.part, radius_change & surf.part
    in_contour = steady | radius_change
    status = np.zeros(n, np.int8)
    status[(k != 0) & (prev_k == 0)] = STATUS_NAMES.index(STATUS_LEAD_IN)
    status[steady] = STATUS_NAMES.index(STATUS_STEADY)
    status[radius_change] = STATUS_NAMES.index(STATUS_RADIUS_CHANGE)
    status[side_change] = STATUS_NAMES.index(STATUS_SIDE_CHANGE)
    status[air] = STATUS_NAMES.index(STATUS_AIR)
    elem_idx = np.where(in_contour, np.cumsum(in_contour) - 1, -1)
    sel = np.flatnonzero(in_contour)
    prev_in = np.r_[False, in_contour[:-1]] if n else in_contour
    next_in = np.r_[in_contour[1:], False] if n else in_contour
    if decisions.OPEN_END_EXEMPTION:
        # where the contour stops, tool points beyond the element's end are not
        # checked against it (clearance.exempt_regions)
        open_start, open_end = ~prev_in[sel], ~next_in[sel]
    else:
        open_start, open_end = np.zeros(sel.size, bool), np.zeros(sel.size, bool)
    cblocks = tuple(map(mv.moves.__getitem__, sel.tolist())) if sel.size < n \
        else tuple(mv.moves)
    elements = mv.elements(sel, cblocks)
    if decisions.OPEN_END_EXEMPTION:
        _close_joined_ends(elements, open_start, open_end, np.cumsum(~prev_in[sel]), eps)
    clearance = np.where(radius_change[sel], np.minimum(r[sel], prev_r[sel]), r[sel])
    return Contour(cblocks, elements, k[sel], r[sel], clearance, steady[sel], open_start,
                   open_end, mv.plane, tuple(mv.moves), status, k, r, elem_idx, mv.start,
                   mv.end, tuple(notes),
                   surf.report(mv.moves, in_contour | air, _approaches(k, prev_k, side_change)))


def _close_joined_ends(elements: Packed, open_start: np.ndarray, open_end: np.ndarray,
                       episode: np.ndarray, eps: float) -> None:
    """An end is open only where the surface really stops: a start that
    another element of the same run of contour moves (``episode``, one number
    per run, non-decreasing) ends at within ``eps``, or an end another one
    starts at, is a joint of the surface, not an open end (in place). A closed
    loop entered by a lead is the case: its first element follows the lead in
    the program, but its start is where its last element ends, so a lead
    leaving the loop's corner is held to that corner. Another pass's element
    meeting it there is no joint (passes are separate runs, each with its own
    leads).

    Only a run's first start and last end can be open (``open_start``,
    ``open_end`` are false elsewhere), so each run's elements are compared
    with its two ends at once: linear in the elements, no search tree.
    Within ``eps`` is ``dx**2 + dy**2 <= eps**2``, as
    ``scipy.spatial.cKDTree.query_ball_point`` counts it."""
    n = episode.size
    if not n or not (open_start.any() or open_end.any()):
        return
    first = np.flatnonzero(np.r_[True, episode[1:] != episode[:-1]])
    last = np.r_[first[1:], n] - 1
    run = np.repeat(np.arange(first.size), np.diff(np.r_[first, n]))
    at = np.arange(n)
    p0, p1 = elements.arr.p0, elements.arr.p1
    for opened, ends, here, there in ((open_start, first, p0, p1), (open_end, last, p1, p0)):
        end = ends[run]                           # each element's run's end in question
        gap = there - here[end]
        met = (gap[:, 0] * gap[:, 0] + gap[:, 1] * gap[:, 1] <= eps * eps) & (at != end)
        joined = ends[np.unique(run[met])]
        opened[joined[opened[joined]]] = False


def _approaches(k: np.ndarray, prev_k: np.ndarray, side_change: np.ndarray) -> dict[int, str]:
    """Move index -> why, for the moves that approach or leave the contour (air)."""
    out = {int(q): WHY_LEAD_IN for q in np.flatnonzero((k != 0) & (prev_k == 0))}
    out.update((int(q), WHY_LEAD_OUT) for q in np.flatnonzero((k == 0) & (prev_k != 0)))
    out.update((int(q), WHY_SIDE_CHANGE) for q in np.flatnonzero(side_change))
    return out


@dataclass(frozen=True, eq=False)
class _InPlaneMoves:
    """The program's in-plane moves (dwells and moves without an in-plane
    component left out): their blocks, their places in the program
    (``index``), motion codes (:data:`ccopt.program.columns.MOTIONS`), and
    in-plane start and end points and arc flags as arrays (``(n, 2)``,
    ``(n,)``), in the plane of compensation."""

    plane: str
    moves: list
    index: np.ndarray
    code: np.ndarray
    start: np.ndarray
    end: np.ndarray
    is_arc: np.ndarray

    @classmethod
    def of(cls, program: Program) -> "_InPlaneMoves":
        # from the program's columns (read once per program, shared with
        # compensation): this runs once per verification over up to millions
        # of blocks
        cols = columns_of(program)
        blocks = program.blocks
        moving = np.flatnonzero(cols.motion_code != DWELL_CODE)
        plane = (cols.modals[moving[0]].plane if moving.size
                 else (cols.modals[0].plane if blocks else "XY"))
        i0, j0, _ = PLANE_AXES[plane]
        arc = cols.is_arc[moving]
        st = cols.start[moving][:, [i0, j0]]
        en = cols.end[moving][:, [i0, j0]]
        # Block.in_plane, for all moves at once
        inp = arc | (np.hypot(*(en - st).T) > 0.0)
        if not inp.all():
            moving, arc, st, en = moving[inp], arc[inp], st[inp], en[inp]
        moves = list(blocks) if moving.size == len(blocks) else \
            [blocks[q] for q in moving.tolist()]
        return cls(plane, moves, moving, cols.motion_code[moving], st, en, arc)

    def elements(self, sel: np.ndarray, cblocks: tuple) -> Packed:
        """Programmed geometry of the moves ``sel`` (whose blocks are ``cblocks``)."""
        i0, j0, _ = PLANE_AXES[self.plane]
        nc = len(cblocks)
        ccw = self.code[sel] == CCW_CODE
        carc = self.is_arc[sel]
        ce = np.full((nc, 2), np.nan)
        turns = np.zeros(nc)
        arcs_q = np.flatnonzero(carc)
        if arcs_q.size:
            ab = [cblocks[q] for q in arcs_q]
            na = len(ab)
            cc = np.fromiter(chain.from_iterable(map(_CENTER, ab)), float, 3 * na).reshape(na, 3)
            ce[arcs_q] = cc[:, [i0, j0]]
            turns[arcs_q] = np.fromiter(map(_TURNS, ab), float, na)
        return element_geometry(list(cblocks), self.plane, self.start[sel], self.end[sel], ce,
                                carc, ccw, turns)


def _sides_and_radii(mv: _InPlaneMoves, cols: BlockColumns, radius: float | None,
                     side: int | None, toolpath_radius: float | None):
    """``(k, r, notes)``: side (+1 left, -1 right, 0 off) and cutter radius in
    force for each of the moves ``mv`` (of a program whose columns are
    ``cols``) after the overrides, and what the verifier assumed. Each modal
    state is read once per run of blocks sharing it."""
    n = len(mv.moves)
    heads = [cols.modals[q] for q in cols.modal_first.tolist()]
    run_of = np.repeat(np.arange(len(heads)), cols.modal_runs())[mv.index]
    k = np.fromiter(map(_SIDE, heads), int, len(heads))[run_of]
    rad = list(map(_RADIUS, heads))                     # per run; None: never set
    unset = np.fromiter((x is None for x in rad), bool, len(rad))[run_of]
    on_radii = {rad[u] for u in np.unique(run_of[k != 0]).tolist()}
    notes: list[str] = []
    if radius is None and toolpath_radius is not None and toolpath_radius > 0.0:
        radius = _radius_from_toolpath(on_radii, float(toolpath_radius), notes)
    if radius is None and None in on_radii:
        q = int(np.flatnonzero((k != 0) & unset)[0])
        effective_side_radius(mv.moves[q], None, None)      # raises, located
    if radius is not None:
        r = np.full(n, float(radius))
    else:
        r = np.array([0.0 if x is None else x for x in rad], float)[run_of]
    if side is not None:
        k = np.where(k != 0, int(side), 0)
    return k, np.where(k != 0, r, 0.0), notes


def _radius_from_toolpath(on_radii: set, toolpath_radius: float, notes: list) -> float | None:
    """The radius to verify with instead of the program's (``None``: the
    program's), given the set of radii of the compensated blocks and the tool
    path's radius; appends a note when it takes the tool path's."""
    if None in on_radii:
        notes.append(f"the program sets no cutter radius: verified with the tool path's "
                     f"{toolpath_radius:g}")
        return toolpath_radius
    if not decisions.RADIUS_FROM_TOOLPATH_WHEN_UNIFORM or len(on_radii) != 1:
        return None
    r_prog = next(iter(on_radii))
    if abs(r_prog - toolpath_radius) > RADIUS_SAME_REL * max(1.0, r_prog):
        notes.append(f"the program's radius {r_prog:g} differs from the tool path's "
                     f"{toolpath_radius:g}: verified with {toolpath_radius:g} "
                     "(a compensate(radius=...) override)")
        return toolpath_radius
    return None
