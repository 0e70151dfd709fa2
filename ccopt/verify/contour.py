"""The contour: which programmed elements are part surface, and on which side.

See :mod:`ccopt.verify.decisions` for the rules (fully compensated moves are
the contour; side-change moves are transitions; radius-change moves keep the
smaller radius; where the contour stops its ends are *open*).

The programmed geometry of each element is exactly
:func:`ccopt.toolpath.block_geometry` of its block; lines and arcs are built
here with array arithmetic (same formulas, tested equal), spirals through
``block_geometry`` itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.errors import ProgramError
from ccopt.geometry import KIND_ARC, KIND_LINE, KIND_SPIRAL, SegmentArray
from ccopt.geometry.angles import TWO_PI
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.toolpath import block_geometry
from ccopt.verify.segments import Packed, arc_bbox, pack

#: Why a move is or is not part of the contour.
STATUS_OFF = "off"                  # compensation off for the move (uncompensated, lead-out)
STATUS_LEAD_IN = "lead-in"          # on for the move, off before it
STATUS_STEADY = "steady"            # on before and during, same side and radius
STATUS_RADIUS_CHANGE = "radius-change"  # on before and during, new radius introduced over it
STATUS_SIDE_CHANGE = "side-change"  # on before and during, new side introduced over it


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
    open_start, open_end: the contour stops at that end (see
        :data:`ccopt.verify.decisions.OPEN_END_EXEMPTION`).
    plane: plane of compensation.
    move_of: ``id(block) -> (status, k, r, element index or -1)`` for every
        in-plane move of the program.
    notes: what the verifier assumed (e.g. a radius taken from the tool path).
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
    move_of: dict = field(repr=False)
    notes: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.blocks)

    def element_line(self, j: int) -> int | None:
        b = self.blocks[int(j)]
        return b.source.line if b is not None else None

    def lookup(self, block: Block | None):
        """``(status, k, r, element index or -1)`` of a tool segment's block, or ``None``."""
        if block is None:
            return None
        hit = self.move_of.get(id(block))
        if hit is None:
            # A tool path whose blocks are equal copies (e.g. a program read twice).
            hit = self._by_value().get(block)
        return hit

    def _by_value(self) -> dict:
        cache = self.__dict__.get("_value_cache")
        if cache is None:
            cache = {}
            for key, val in self.move_of.items():
                cache[self._blocks_by_id[key]] = val
            object.__setattr__(self, "_value_cache", cache)
        return cache


def effective_side_radius(block: Block, radius: float | None, side: int | None) -> tuple[int, float]:
    """Side and radius in force for ``block`` after ``radius=``/``side=`` overrides
    (the same rule compensation applies; ``(0, 0.0)`` when off)."""
    k = block.modal.side
    if k == 0:
        return 0, 0.0
    if side is not None:
        k = side
    r = radius if radius is not None else block.modal.radius
    if r is None:
        s = block.source
        raise ProgramError("cutter compensation is on but no cutter radius is set", s.file,
                           s.line, s.col)
    return int(k), float(r)


def _uniform_program_radius(moves, k) -> float | None:
    radii = {b.modal.radius for b, kk in zip(moves, k) if kk != 0}
    return radii.pop() if len(radii) == 1 and None not in radii else None


def element_geometry(blocks: list[Block], plane: str, st=None, en=None) -> Packed:
    """Programmed geometry of ``blocks`` as :func:`block_geometry` makes it, packed
    (``st``, ``en``: their in-plane start and end points, if already known)."""
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
    spiral = is_arc & (np.abs(R1 - R0) > 1e-9 * np.maximum(1.0, R0))
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
        fib = 1e-9 * np.maximum(1.0, R) / R
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
               toolpath_radius: float | None = None) -> Contour:
    """The contour of ``program`` (see :mod:`ccopt.verify.decisions`).

    ``radius``/``side`` override the program as in
    :func:`ccopt.compensate.compensate`. ``toolpath_radius`` is the radius the
    tool path says it was made with
    (:data:`~ccopt.verify.decisions.RADIUS_FROM_TOOLPATH_WHEN_UNIFORM`).
    """
    allmoves = [b for b in program.blocks if b.motion.is_move]
    plane = allmoves[0].modal.plane if allmoves else (program.blocks[0].modal.plane
                                                      if program.blocks else "XY")
    i0, j0, _ = PLANE_AXES[plane]
    m = len(allmoves)
    st_all = np.array([b.start for b in allmoves], float).reshape(m, 3)[:, [i0, j0]]
    en_all = np.array([b.end for b in allmoves], float).reshape(m, 3)[:, [i0, j0]]
    arc_all = np.fromiter((b.motion.is_arc for b in allmoves), bool, m)
    # Block.in_plane, for all moves at once
    inp = arc_all | (np.hypot(*(en_all - st_all).T) > 0.0)
    moves = [b for b, ok in zip(allmoves, inp) if ok]
    st_mv, en_mv = st_all[inp], en_all[inp]
    notes: list[str] = []
    raw_k = [b.modal.side for b in moves]
    if radius is None and toolpath_radius is not None and toolpath_radius > 0.0:
        r_prog = _uniform_program_radius(moves, raw_k)
        if r_prog is None and any(b.modal.radius is None for b, kk in zip(moves, raw_k) if kk):
            radius = float(toolpath_radius)
            notes.append(f"the program sets no cutter radius: verified with the tool path's "
                         f"{toolpath_radius:g}")
        elif r_prog is not None and abs(r_prog - toolpath_radius) > 1e-12 * max(1.0, r_prog):
            radius = float(toolpath_radius)
            notes.append(f"the program's radius {r_prog:g} differs from the tool path's "
                         f"{toolpath_radius:g}: verified with {toolpath_radius:g} "
                         "(a compensate(radius=...) override)")
    n = len(moves)
    k = np.fromiter((b.modal.side for b in moves), int, n)
    rad = [b.modal.radius for b in moves]
    if radius is None and any(rr is None for rr, kk in zip(rad, k) if kk):
        q = next(q for q in range(n) if k[q] and rad[q] is None)
        effective_side_radius(moves[q], None, None)      # raises, located
    r = np.array([0.0 if rr is None else rr for rr in rad], float) if radius is None \
        else np.full(n, float(radius))
    if side is not None:
        k = np.where(k != 0, int(side), 0)
    r = np.where(k != 0, r, 0.0)
    prev_k = np.r_[0, k[:-1]] if n else k
    prev_r = np.r_[0.0, r[:-1]] if n else r
    on = (k != 0) & (prev_k != 0)
    side_change = on & (k != prev_k)
    radius_change = on & ~side_change & (r != prev_r)
    steady = on & ~side_change & ~radius_change
    in_contour = steady | radius_change
    status = np.full(n, STATUS_OFF, dtype=object)
    status[(k != 0) & (prev_k == 0)] = STATUS_LEAD_IN
    status[steady] = STATUS_STEADY
    status[radius_change] = STATUS_RADIUS_CHANGE
    status[side_change] = STATUS_SIDE_CHANGE
    idx = np.cumsum(in_contour) - 1
    elem_idx = np.where(in_contour, idx, -1).tolist()
    move_of = {id(b): v for b, v in zip(moves, zip(status.tolist(), k.tolist(), r.tolist(),
                                                     elem_idx))}
    sel = np.flatnonzero(in_contour)
    prev_in = np.r_[False, in_contour[:-1]] if n else in_contour
    next_in = np.r_[in_contour[1:], False] if n else in_contour
    cblocks = tuple(moves[q] for q in sel)
    elements = element_geometry(list(cblocks), plane, st_mv[sel], en_mv[sel])
    clearance = np.where(radius_change[sel], np.minimum(r[sel], prev_r[sel]), r[sel])
    c = Contour(cblocks, elements, k[sel], r[sel], clearance, steady[sel],
                ~prev_in[sel], ~next_in[sel], plane, move_of, tuple(notes))
    object.__setattr__(c, "_blocks_by_id", {id(b): b for b in moves})
    return c
