"""A program's blocks as columns: the fields every stage reads, read once.

Compensation's scan and the verifier's contour both read the motion, start
and end points and modal state of every block. On a long program reading
them (one pass over the :class:`~ccopt.program.model.Block` objects per
field) costs more than the arithmetic done on the arrays afterwards, so
:func:`columns_of` reads them once and keeps the result with the program
(a program is immutable, so its columns never go stale).

Coordinates are absolute machine ``(x, y, z)`` in program units, as in the
blocks; motions are coded as their place in :data:`MOTIONS`.
"""
from __future__ import annotations

from dataclasses import dataclass
from itertools import chain
from operator import attrgetter
from typing import Sequence

import numpy as np

from ccopt.program.model import Block, Modal, Motion, Program

#: ``motion_code[q]`` is the place of block ``q``'s motion in this tuple.
MOTIONS: tuple[Motion, ...] = tuple(Motion)
RAPID_CODE, LINE_CODE, CW_CODE, CCW_CODE, DWELL_CODE = (
    MOTIONS.index(m) for m in (Motion.RAPID, Motion.LINE, Motion.ARC_CW, Motion.ARC_CCW,
                               Motion.DWELL))
_CODE_OF = {m: q for q, m in enumerate(MOTIONS)}
_MOTION, _MODAL, _START, _END = (attrgetter(a) for a in ("motion", "modal", "start", "end"))
_MOVE_TIME = attrgetter("move_time")


@dataclass(frozen=True, eq=False)
class BlockColumns:
    """Per block ``q`` of a program (arrays read-only):

    motions[q]: its :class:`Motion`; motion_code[q]: the same as an index
    into :data:`MOTIONS` (``int8``); modals[q]: its :class:`Modal` object;
    start[q], end[q]: ``(x, y, z)`` (``(n, 3)`` float); modal_first: the
    first block of each run of blocks sharing one :class:`Modal` object (a
    new run wherever the object changes, so a look-up per modal state is
    one per run); timed: whether any block has a PMAC ``TM`` move time.
    """

    motions: tuple[Motion, ...]
    motion_code: np.ndarray
    modals: tuple[Modal, ...]
    start: np.ndarray
    end: np.ndarray
    modal_first: np.ndarray
    timed: bool

    def __len__(self) -> int:
        return len(self.motions)

    @property
    def is_arc(self) -> np.ndarray:
        """Whether each block is an arc (clockwise or counter-clockwise)."""
        return (self.motion_code == CW_CODE) | (self.motion_code == CCW_CODE)

    def planes(self) -> set[str]:
        """The planes of the blocks' modal states (each run's looked at once)."""
        return {self.modals[q].plane for q in self.modal_first.tolist()}

    def modal_runs(self) -> np.ndarray:
        """How many blocks each run of :attr:`modal_first` holds."""
        return np.diff(np.r_[self.modal_first, len(self.motions)])


def columns_of(program: Program) -> BlockColumns:
    """The columns of ``program``'s blocks: read on first use and kept with
    it, so compensating and verifying one program reads its blocks once."""
    got = program.__dict__.get("_columns")
    if got is None:
        got = block_columns(program.blocks)
        object.__setattr__(program, "_columns", got)     # a cache, not a field
    return got


def block_columns(blocks: Sequence[Block]) -> BlockColumns:
    """The columns of ``blocks`` (each field read in one C-level pass)."""
    n = len(blocks)
    motions = tuple(map(_MOTION, blocks))
    modals = tuple(map(_MODAL, blocks))
    code = np.fromiter(map(_CODE_OF.__getitem__, motions), np.int8, n)
    start = triples_column(map(_START, blocks), n)
    end = triples_column(map(_END, blocks), n)
    ids = np.fromiter(map(id, modals), np.int64, n)
    first = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]]) if n else np.zeros(0, np.intp)
    timed = any(t is not None for t in set(map(_MOVE_TIME, blocks)))
    for arr in (code, start, end, first):
        arr.flags.writeable = False
    return BlockColumns(motions, code, modals, start, end, first, timed)


def triples_column(triples, n: int) -> np.ndarray:
    """``(n, 3)`` float array of ``n`` coordinate triples."""
    return np.fromiter(chain.from_iterable(triples), float, 3 * n).reshape(n, 3)
