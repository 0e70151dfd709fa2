"""The tool path's segments as the verifier reads them, one row each.

:class:`SegmentRows` holds what the checks ask of each tool segment: its
geometry packed (:class:`~ccopt.verify.segments.Packed`), its role, its
out-of-plane coordinates and its source block. A path that compensation
made as columns (:class:`~ccopt.toolpath.SegmentColumns`, the PMAC style on
a program of any length) is read from them directly, so verifying it makes
no :class:`~ccopt.toolpath.PathSegment` object; any other path is read from
its segments. Both give the same rows, bit for bit
(:func:`~ccopt.verify.segments.pack_columns`).
"""
from __future__ import annotations

from dataclasses import dataclass
from operator import attrgetter
from typing import Sequence

import numpy as np

from ccopt.geometry import Arc
from ccopt.program.model import Block
from ccopt.toolpath import ARC_ROW, OBJECT_ROW, ROLES, SegmentColumns, ToolPath
from ccopt.verify.segments import Packed, pack, pack_columns

_GEOM, _ROLE, _BLOCK = attrgetter("geom"), attrgetter("role"), attrgetter("block")
_W0, _W1 = attrgetter("w0"), attrgetter("w1")
ROLE_CODES = {r: q for q, r in enumerate(ROLES)}


@dataclass(frozen=True, eq=False)
class SegmentRows:
    """Per tool segment ``i``: ``tool`` row ``i`` (packed geometry, program
    units); ``role[i]``, an index into :data:`ccopt.toolpath.ROLES`; ``w0[i]``,
    ``w1[i]``, the out-of-plane coordinate at its start and end;
    ``block_index[i]``, an index into ``blocks`` (-1: no block); ``is_arc[i]``,
    whether its geometry is an :class:`~ccopt.geometry.Arc`."""

    tool: Packed
    role: np.ndarray
    w0: np.ndarray
    w1: np.ndarray
    block_index: np.ndarray
    blocks: Sequence[Block | None]
    is_arc: np.ndarray

    @classmethod
    def of(cls, toolpath: ToolPath) -> "SegmentRows":
        """The rows of ``toolpath``: from its columns when it has them."""
        columns = toolpath.columns
        if columns is not None:
            return cls._of_columns(columns)
        return cls._of_segments(toolpath.segments)

    @classmethod
    def _of_segments(cls, segs) -> "SegmentRows":
        n = len(segs)
        geoms = list(map(_GEOM, segs))
        role = np.fromiter(map(ROLE_CODES.__getitem__, map(_ROLE, segs)), np.int8, n)
        w0 = np.fromiter(map(_W0, segs), float, n)
        w1 = np.fromiter(map(_W1, segs), float, n)
        blocks = list(map(_BLOCK, segs))
        index = np.arange(n, dtype=np.intp)
        index[[q for q, b in enumerate(blocks) if b is None]] = -1
        is_arc = np.fromiter((isinstance(g, Arc) for g in geoms), bool, n)
        return cls(pack(geoms), role, w0, w1, index, blocks, is_arc)

    @classmethod
    def _of_columns(cls, columns: SegmentColumns) -> "SegmentRows":
        is_arc = columns.kind == ARC_ROW
        for q in np.flatnonzero(columns.kind == OBJECT_ROW).tolist():
            is_arc[q] = isinstance(columns.objects[q], Arc)
        return cls(pack_columns(columns), columns.role.astype(np.int8),
                   columns.w[:, 0].astype(float), columns.w[:, 1].astype(float),
                   columns.block.astype(np.intp), columns.blocks, is_arc)

    def __len__(self) -> int:
        return len(self.role)

    def block(self, i: int) -> Block | None:
        """The source block of segment ``i`` (``None``: made by no block)."""
        q = int(self.block_index[i])
        return self.blocks[q] if q >= 0 else None

    def info(self, i: int) -> tuple[int | None, str]:
        """``(source line, role)`` of segment ``i``, as a violation lists them."""
        blk = self.block(i)
        return (blk.source.line if blk is not None else None), ROLES[int(self.role[i])].value
