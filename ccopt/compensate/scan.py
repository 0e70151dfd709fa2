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
from ccopt.program.columns import DWELL_CODE, RAPID_CODE, columns_of
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
    gaps: "GapList"
    plane: str
    start_uv: tuple[float, float]
    _cache: dict = field(default_factory=dict, repr=False)
    #: the moves' start and end ``(n, 3)`` machine coordinates, motions and
    #: arc and rapid flags, when the scan read them in bulk (:class:`batch.ElementArrays` reuses them)
    columns: dict | None = None

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


class GapList:
    """``gaps[i]``, ``i`` in ``0..n`` (negative counts from the end): the
    non-plane blocks before move ``i`` (``gaps[n]``: the trailing ones), an
    empty tuple where there are none. Held sparse: most moves of a long
    program have no gap."""

    __slots__ = ("_gaps", "_size")

    def __init__(self, gaps: dict[int, list[Block]], size: int):
        self._gaps, self._size = gaps, size

    @classmethod
    def from_lists(cls, lists: list[list[Block]]) -> "GapList":
        return cls({i: g for i, g in enumerate(lists) if g}, len(lists))

    def __len__(self) -> int:
        return self._size

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[q] for q in range(*i.indices(self._size))]
        if i < 0:
            i += self._size
        if not 0 <= i < self._size:
            raise IndexError("gap index out of range")
        return self._gaps.get(i, ())

    def items(self):
        """``(i, blocks)`` of the non-empty gaps, in order."""
        return sorted(self._gaps.items())

    def sizes(self) -> np.ndarray:
        """Number of blocks of every gap, ``(len(self),)``."""
        out = np.zeros(self._size, np.int64)
        for i, g in self._gaps.items():
            out[i] = len(g)
        return out


#: Programs of fewer blocks are scanned one block at a time: the bulk scan's
#: fixed cost (numpy calls, about 40 us) is more than the loop's there.
BULK_MIN_BLOCKS = 64


def _err(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def scan_program(program: Program, radius: float | None = None, side: int | None = None,
                 style: str = "pmac", bulk: bool | None = None) -> ScanResult:
    """The program's in-plane moves with their side and radius, and the
    gaps between them; raises :class:`CompensationError`, located, on what
    no style can compensate. With ``bulk`` (``None``: programs of at least
    :data:`BULK_MIN_BLOCKS` blocks), a program in one plane with no ``TM``
    move and nothing to refuse is read in bulk (:func:`_scan_columns`);
    anything else one block at a time (:func:`_scan_blocks`, the reference).
    Both give the same scan (tested)."""
    if radius is not None and radius < 0:
        raise CompensationError(f"--radius {radius:g} must be >= 0", program.file)
    if side not in (None, 1, -1):
        raise CompensationError("side must be left (+1) or right (-1)", program.file)
    if bulk is None:
        bulk = len(program.blocks) >= BULK_MIN_BLOCKS
    fast = _scan_columns(program, radius, side, style) if bulk else None
    return fast if fast is not None else _scan_blocks(program, radius, side, style)


def _scan_blocks(program: Program, radius: float | None, side: int | None,
                 style: str) -> ScanResult:
    """:func:`scan_program` one block at a time."""
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
    return ScanResult(moves, np.array(ks, dtype=int), np.array(rs, dtype=float),
                      GapList.from_lists(gaps), plane, (float(start[0]), float(start[1])))


def _side_radius_by_modal(blocks, cols, radius, side, plane: str):
    """Side and radius of every block (one look-up per run of blocks that
    share a modal state, ``cols`` the program's :class:`BlockColumns`), or
    ``None`` when a look-up refuses (the one-at-a-time scan then raises it,
    in program order) or a state is in another plane than ``plane``."""
    modals = cols.modals
    in_force: dict[int, tuple[int, float]] = {}
    ks, rs = [], []
    for q in cols.modal_first.tolist():
        kr = in_force.get(id(modals[q]))
        if kr is None:
            if modals[q].plane != plane:
                return None
            try:
                kr = in_force[id(modals[q])] = effective_side_radius(blocks[q], radius, side)
            except CompensationError:
                return None
        ks.append(kr[0])
        rs.append(kr[1])
    runs = cols.modal_runs()
    return np.repeat(np.array(ks, int), runs), np.repeat(np.array(rs, float), runs)


def _scan_columns(program: Program, radius: float | None, side: int | None,
                  style: str) -> ScanResult | None:
    """:func:`scan_program` in bulk (the blocks' fields read once each into
    arrays), or ``None`` when the program needs the one-at-a-time scan: more
    than one plane, a ``TM`` move, or a block it refuses."""
    blocks = program.blocks
    n = len(blocks)
    if n == 0:
        return None
    cols = columns_of(program)
    if cols.timed:
        return None
    plane = cols.modals[0].plane
    kr = _side_radius_by_modal(blocks, cols, radius, side, plane)
    if kr is None:
        return None
    k, r = kr
    motions, code = cols.motions, cols.motion_code
    dwell = code == DWELL_CODE
    arc = cols.is_arc
    rapid = code == RAPID_CODE
    st, en = cols.start, cols.end
    i, j, _ = PLANE_AXES[plane]
    in_plane = ~dwell & (arc | (st[:, i] != en[:, i]) | (st[:, j] != en[:, j]))
    if style == "pmac" and not decisions.PMAC_OFFSET_RAPIDS:
        # A rapid runs uncompensated: the move before it ends as for a
        # lead-out, the move after it is a lead-in.
        k = np.where(in_plane & rapid, 0, k)
        r = np.where(in_plane & rapid, 0.0, r)
    idx = np.flatnonzero(in_plane)
    moves = list(blocks) if idx.size == n else [blocks[q] for q in idx.tolist()]
    gaps: dict[int, list[Block]] = {}
    before = np.cumsum(in_plane) if idx.size < n else None
    for q in np.flatnonzero(~in_plane).tolist():
        gaps.setdefault(int(before[q]), []).append(blocks[q])
    start = blocks[0].uvw(program.start)[:2]
    if idx.size < n:
        st, en, arc, rapid, k, r = (v[idx] for v in (st, en, arc, rapid, k, r))
        motions = [motions[q] for q in idx.tolist()]
    # else every block is an in-plane move: the arrays as they are
    columns = {"start": st, "end": en, "arc": arc, "rapid": rapid, "motions": motions}
    return ScanResult(moves, k, r, GapList(gaps, idx.size + 1), plane,
                      (float(start[0]), float(start[1])), columns=columns)


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
