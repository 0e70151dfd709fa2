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
from ccopt.program.model import Block, Motion, Program
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
    for blk in program.blocks:
        k, r = effective_side_radius(blk, radius, side)
        if blk.modal.plane != prev_plane:
            if prev_side != 0 or k != 0:
                raise _err(blk, f"plane change ({prev_plane} to {blk.modal.plane}, NORMAL/G17-G19) "
                                "while cutter compensation is on: turn it off (CC0/G40) first")
            if moves:
                raise _err(blk, "moves in more than one plane in one program are not supported "
                                "by the compensation engine yet")
            plane = blk.modal.plane
        prev_plane = blk.modal.plane
        if k != 0 and blk.move_time is not None and blk.motion.is_move:
            raise _err(blk, "TM (move time) moves cannot be compensated: program a feed rate F "
                            "while cutter compensation is on")
        prev_side = k
        if blk.motion.is_move and blk.in_plane:
            if style == "pmac" and blk.motion is Motion.RAPID and not decisions.PMAC_OFFSET_RAPIDS:
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
