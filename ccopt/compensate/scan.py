"""First pass of every style: split a program into in-plane moves and gaps.

The in-plane moves become :class:`~ccopt.compensate.corners.Element` objects
with their effective side and radius (after ``radius=``/``side=`` overrides);
moves with no in-plane component (Z only) and dwells between two in-plane
moves are the *gap* before the next move: they are skipped when looking for
the next move and run at the compensated corner point (rule 6 of docs/compensation.md).
Conditions no style can compensate are reported here, located.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import Element, element_of
from ccopt.errors import CompensationError
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.toolpath import effective_side_radius


@dataclass
class ScanResult:
    """In-plane moves in order with their effective side ``k`` and radius
    ``r``; ``gaps[i]`` are the non-plane blocks before move ``i`` and
    ``gaps[len(blocks)]`` the trailing ones.

    :meth:`element` builds the exact :class:`Element` of one move on demand
    (cached): long programs mostly go through the array route of
    :mod:`.batch` and never need most of them.
    """

    blocks: list[Block]
    k: np.ndarray
    r: np.ndarray
    gaps: list[list[Block]]
    plane: str
    start_uv: tuple[float, float]
    _cache: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.blocks)

    def element(self, i: int) -> Element:
        el = self._cache.get(i)
        if el is None:
            el = self._cache[i] = element_of(self.blocks[i], int(self.k[i]), float(self.r[i]))
        return el

    @property
    def elements(self) -> list[Element]:
        return [self.element(i) for i in range(len(self.blocks))]


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def scan_program(program: Program, radius: float | None = None, side: int | None = None,
                 style: str = "pmac") -> ScanResult:
    if radius is not None and radius < 0:
        raise CompensationError(f"--radius {radius:g} must be >= 0", program.file)
    if side not in (None, 1, -1):
        raise CompensationError("side must be left (+1) or right (-1)", program.file)
    moves: list[Block] = []
    ks: list[int] = []
    rs: list[float] = []
    gaps: list[list[Block]] = [[]]
    plane = program.blocks[0].modal.plane if program.blocks else "XY"
    prev_side = 0
    prev_plane = plane
    # Side and radius depend on the block's modal state alone: one look-up per
    # modal state (shared by the blocks it governs), not one per block; the
    # first block of a state still raises, located, when it has no radius.
    in_force: dict[int, tuple[int, float]] = {}
    rapid_uncompensated = style == "pmac" and not decisions.PMAC_OFFSET_RAPIDS
    for blk, in_plane in zip(program.blocks, _in_plane(program.blocks)):
        modal = blk.modal
        kr = in_force.get(id(modal))
        if kr is None:
            kr = in_force[id(modal)] = effective_side_radius(blk, radius, side)
        k, r = kr
        if modal.plane != prev_plane:
            if prev_side != 0 or k != 0:
                raise _err(blk, f"plane change ({prev_plane} to {modal.plane}, NORMAL/G17-G19) "
                                "while cutter compensation is on: turn it off (CC0/G40) first")
            if moves:
                raise _err(blk, "moves in more than one plane in one program are not supported "
                                "by the compensation engine yet")
            plane = modal.plane
        prev_plane = modal.plane
        is_move = blk.motion is not Motion.DWELL
        if k != 0 and blk.move_time is not None and is_move:
            raise _err(blk, "TM (move time) moves cannot be compensated: program a feed rate F "
                            "while cutter compensation is on")
        prev_side = k
        if in_plane:
            if rapid_uncompensated and blk.motion is Motion.RAPID:
                # A rapid runs uncompensated: the move before it ends as for
                # a lead-out, the move after it is a lead-in.
                k, r = 0, 0.0
            moves.append(blk)
            ks.append(k)
            rs.append(r)
            gaps.append([])
        else:
            gaps[-1].append(blk)
    start = program.blocks[0].uvw(program.start)[:2] if program.blocks else (0.0, 0.0)
    return ScanResult(moves, np.array(ks, dtype=int), np.array(rs, dtype=float), gaps, plane,
                      (float(start[0]), float(start[1])))


_ARCS = frozenset((Motion.ARC_CW, Motion.ARC_CCW))


def _in_plane(blocks) -> list[bool]:
    """:attr:`Block.in_plane` of every block, in bulk: a move that is an arc,
    or a straight move whose in-plane coordinates change (``hypot > 0``
    exactly when either difference is non-zero)."""
    out = []
    for blk in blocks:
        motion = blk.motion
        if motion is Motion.DWELL:
            out.append(False)
        elif motion in _ARCS:
            out.append(True)
        else:
            i, j, _ = PLANE_AXES[blk.modal.plane]
            a, b = blk.start, blk.end
            out.append(a[i] != b[i] or a[j] != b[j])
    return out
