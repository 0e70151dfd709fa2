"""What an exported G-code program keeps for the machine that runs it.

The reader recorded, per block, the machine words read before it
(:attr:`Block.words`: tool changes, spindle, coolant, tool length, stops) and
the work coordinate frame it was programmed in (:attr:`Block.frame`). The
G-code writer asks :class:`MachineWords`, segment by segment, what to write
before a move and in which frame to write its coordinates, so the export

* writes every block's words before its first move or dwell, in program
  order (a block that makes no segment still has its words written, at the
  next one), the words after the last block and the program end as written
  (``M30`` stays ``M30``; ``M2`` when the program had none);
* writes the A B C U V W positions the program carried (:attr:`Block.axes`)
  on the last move of each block, where they change;
* writes coordinates in the program's work coordinates, selecting the same
  ``G54``-``G59.3``, with ``G10 L2`` (and its ``R`` rotation) where the
  program set an origin to other values than the parameters it was read with, ``G52`` where the
  ``G92``/``G52`` offset changes, and ``G53`` (machine coordinates) on the
  moves the program wrote under ``G53``.

Coordinates are program units; an offset is machine minus work coordinates.
"""
from __future__ import annotations

from itertools import repeat
from operator import attrgetter, is_, is_not
from types import SimpleNamespace

import numpy as np

from ccopt.program.model import (AXES_USED, PROGRAM_END, START_PARAMETERS, TRAILING_WORDS,
                                 Block, Frame, Program, Vec3)

#: Coordinate system 1 .. 9 -> its G-code.
SYSTEM_CODE = {1: "G54", 2: "G55", 3: "G56", 4: "G57", 5: "G58", 6: "G59",
               7: "G59.1", 8: "G59.2", 9: "G59.3"}
_NO_OFFSET: Vec3 = (0.0, 0.0, 0.0)
_EXTRA = "ABCUVW"
_NO_AXES = (0.0,) * 6
_WORDS, _FRAME, _AXES = attrgetter("words"), attrgetter("frame"), attrgetter("axes")
#: What a move without a block (made by hand) has of one: no frame, no axes
#: carried, no spindle synchronisation.
NO_BLOCK = SimpleNamespace(frame=None, axes=None, per_revolution=None)


def _fmt(x: float) -> str:
    s = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _extra(axes) -> str:
    """`` A.. B..`` for the non-zero of A B C U V W ``axes`` (none: empty)."""
    if not axes:
        return ""
    return "".join(f" {a}{_fmt(v)}" for a, v in zip(_EXTRA, axes) if v != 0.0)


def _xyz(p: Vec3) -> str:
    return f"X{_fmt(p[0])} Y{_fmt(p[1])} Z{_fmt(p[2])}"


class MachineWords:
    """The machine's words and frames of ``program`` for one export.

    ``program`` may be ``None`` (a foreign path, a PMAC program): then nothing
    is added, coordinates are machine coordinates and the program ends ``M2``.
    """

    def __init__(self, program: Program | None):
        blocks = program.blocks if program is not None else ()
        self.blocks = blocks
        self.index = dict(zip(map(id, blocks), range(len(blocks))))
        self.flushed = 0              # blocks whose words are written: [0, flushed)
        meta = program.meta if program is not None else {}
        self.trailing = tuple(meta.get(TRAILING_WORDS, ()))
        self.end = meta.get(PROGRAM_END) or "M2"
        params = meta.get(START_PARAMETERS) or {}
        # what the machine holds before the program runs (its parameter file)
        self.origins = {n: (tuple(params.get(5201 + 20 * n + k, 0.0) for k in range(3)),
                            params.get(5210 + 20 * n, 0.0))
                        for n in SYSTEM_CODE}
        applied = params.get(5210, 0.0) == 1.0
        self.axis_offset = (tuple(params.get(5211 + k, 0.0) for k in range(3))
                            if applied else _NO_OFFSET)
        self.system: int | None = None
        self.axes: tuple[float, ...] | None = None   # A .. W last written
        self.axes_used = meta.get(AXES_USED, "")
        self.axes_offset = tuple(params.get(5214 + k, 0.0) for k in range(6)) if applied \
            else _NO_AXES

    def before(self, block: Block | None) -> list[str]:
        """Lines to write before a move or dwell made from ``block``."""
        out: list[str] = []
        k = self.index.get(id(block)) if block is not None else None
        if k is not None and k >= self.flushed:
            for b in self.blocks[self.flushed:k + 1]:
                out += b.words
            self.flushed = k + 1
        if block is not None and block.frame is not None:
            out += self._frame_lines(block.frame)
        return out

    def quiet(self, blocks: list) -> tuple[np.ndarray, np.ndarray]:
        """Which of the moves made from ``blocks`` (in writing order) need
        nothing written before or on them once the move before them is
        written: the same frame (object) as that move's, no A B C U V W
        carried, and no block with words between the blocks of the moves
        before and its own. Returns that mask (the first move's False) and
        each block's place in the program (-1: none) for :meth:`passed`."""
        n = len(blocks)
        order = np.fromiter(map(self.index.get, map(id, blocks), repeat(-1)), np.int64, n)
        # worded[i]: the program's blocks with words among its first i
        worded = np.zeros(len(self.blocks) + 1, np.int64)
        np.cumsum(np.fromiter(map(bool, map(_WORDS, self.blocks)), bool, len(self.blocks)),
                  out=worded[1:])
        # the words of the blocks after the furthest one reached so far, up
        # to this move's own, come before it: none there, nothing to write
        reached = np.maximum.accumulate(order)
        blocks = stand_in(blocks)
        frames = np.fromiter(map(id, map(_FRAME, blocks)), np.uint64, n)
        out = np.zeros(n, dtype=bool)
        out[1:] = (worded[order[1:] + 1] <= worded[reached[:-1] + 1]) & (frames[1:] == frames[:-1])
        carried = np.fromiter(map(is_not, map(_AXES, blocks), repeat(None)), bool, n)
        return out & ~carried, order

    def passed(self, place: int) -> None:
        """The moves made up to the block at ``place`` in the program were
        written, with nothing before them (:meth:`quiet`)."""
        self.flushed = max(self.flushed, place + 1)

    def _frame_lines(self, frame: Frame) -> list[str]:
        out = []
        key = (frame.origin, frame.rotation) + ((frame.axes_origin,) if frame.axes_origin
                                                 and any(frame.axes_origin) else ())
        if self.origins.get(frame.system) != key:
            turn = f" R{_fmt(frame.rotation)}" if frame.rotation != 0.0 or \
                self.origins.get(frame.system, ((), 0.0))[1] != 0.0 else ""
            out.append(f"G10 L2 P{frame.system} {_xyz(frame.origin)}{turn}"
                       f"{_extra(frame.axes_origin)}")
            self.origins[frame.system] = key
        if frame.system != self.system:
            out.append(SYSTEM_CODE[frame.system])
            self.system = frame.system
        extra = frame.axes_offset or _NO_AXES
        if frame.axis_offset != self.axis_offset or extra != self.axes_offset:
            changed = "".join(f" {a}{_fmt(v)}" for a, v, w in
                              zip(_EXTRA, extra, self.axes_offset) if v != w)
            out.append(f"G52 {_xyz(frame.axis_offset)}{changed}")
            self.axis_offset, self.axes_offset = frame.axis_offset, extra
        return out

    def axes_words(self, block: Block | None) -> str:
        """`` A.. B..`` for the A B C U V W a move from ``block`` ends at that
        differ from the last written (work coordinates; machine under G53)."""
        if block is None or block.axes is None:
            return ""
        axes = block.axes
        if block.frame is not None and not block.frame.machine:
            axes = block.frame.axes_to_work(axes)
        last, self.axes = self.axes, axes
        return "".join(f" {a}{_fmt(v)}" for k, (a, v) in enumerate(zip(_EXTRA, axes))
                       if a in self.axes_used and (last is None or v != last[k]))

    def finish(self) -> list[str]:
        """The words not yet written, those after the last block, the end."""
        out: list[str] = []
        for b in self.blocks[self.flushed:]:
            out += b.words
        self.flushed = len(self.blocks)
        return out + list(self.trailing) + [self.end]


def stand_in(blocks: list) -> list:
    """``blocks`` with :data:`NO_BLOCK` for each ``None`` (a move made by hand)."""
    if any(map(is_, blocks, repeat(None))):
        return [NO_BLOCK if b is None else b for b in blocks]
    return blocks


def written_offset(block: Block | None) -> Vec3:
    """Machine minus written coordinates of a move made from ``block``: its
    frame's offset, none under ``G53`` or without a frame (of an unrotated
    frame: :func:`written_frame` holds for any)."""
    if block is None or block.frame is None or block.frame.machine:
        return _NO_OFFSET
    return block.frame.offset


def written_frame(block: Block | None) -> Frame | None:
    """The rotated frame a move made from ``block`` is written in, else None
    (unrotated frames shift by :func:`written_offset`)."""
    if block is None or block.frame is None or block.frame.machine \
            or block.frame.rotation == 0.0:
        return None
    return block.frame


def machine_prefix(block: Block | None) -> str:
    """``"G53 "`` for a move the program wrote in machine coordinates."""
    return "G53 " if block is not None and block.frame is not None and block.frame.machine \
        else ""
