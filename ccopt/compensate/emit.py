"""The PMAC tool path as columns: every move's segment, its corner segments
and the gaps between moves, written as rows of a
:class:`~ccopt.toolpath.SegmentColumns` in the order the machine runs them.

The same order and segments as :func:`ccopt.compensate.pmac.emit_moves`
and :func:`~ccopt.compensate.pmac.emit_tail` (the one-segment-at-a-time
reference, used by the reference route; tests compare both routes): for
move ``i``, the gap before it (when gaps run after the corner arc, or
before the first move), the move's own segment (when it has a length or a
``w`` change), the gap after it (when gaps run before the corner arc), then
its corner segments; the trailing blocks and the automatic lead-out last.
Moves and batch corner arcs are written in bulk; gaps, dwells and corners
decided one at a time are the few rows written one by one.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.batch import SPIRAL, ElementArrays, tool_rows
from ccopt.compensate.corners import tool_geometry
from ccopt.geometry import Line
from ccopt.geometry.columns import put_rows, take_rows
from ccopt.program.model import Block, Motion
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import ARC_ROW, LINE_ROW, OBJECT_ROW, ROLE_CODE, Role, SegmentColumns

#: Class codes of :func:`class_codes` -> role of the move's own segment.
CLASS_ROLE = np.array([ROLE_CODE[Role.UNCOMPENSATED], ROLE_CODE[Role.LEAD_IN],
                       ROLE_CODE[Role.COMPENSATED], ROLE_CODE[Role.LEAD_OUT]], np.int8)
LEAD_IN_CODE, COMP_CODE = 1, 2


def class_codes(k: np.ndarray) -> np.ndarray:
    """Class of each in-plane move from the side in force before and for it:
    0 uncompensated, 1 lead-in, 2 compensated, 3 lead-out."""
    prev = np.r_[0, k[:-1]] if len(k) else np.zeros(0, int)
    return np.where(k == 0, np.where(prev == 0, 0, 3), np.where(prev == 0, 1, 2))


@dataclass
class _Loose:
    """Rows written one at a time (gap moves, the lead-out, corners decided
    one by one), with the blocks they name that are not moves."""

    n_moves: int
    pos: list = field(default_factory=list)
    kind: list = field(default_factory=list)
    geom: list = field(default_factory=list)
    role: list = field(default_factory=list)
    block: list = field(default_factory=list)
    w: list = field(default_factory=list)
    objects: dict = field(default_factory=dict)
    extra_blocks: list = field(default_factory=list)
    dwells: list = field(default_factory=list)

    def row(self, pos: int, kind: int, geom, role: Role, block: int, w0: float, w1: float,
            obj=None) -> None:
        self.pos.append(pos)
        self.kind.append(kind)
        self.geom.append(geom)
        self.role.append(ROLE_CODE[role])
        self.block.append(block)
        self.w.append((w0, w1))
        if obj is not None:
            self.objects[pos] = obj

    def gap(self, blocks, pos: int, at, comp_on: bool) -> int:
        """Blocks with no in-plane motion (Z moves, dwells) at tool point
        ``at`` from row ``pos`` on; returns the next free row."""
        u, v = float(at[0]), float(at[1])
        for blk in blocks:
            if blk.motion is Motion.DWELL:
                self.dwells.append((pos, blk.dwell, blk))
                continue
            Line((u, v), (u, v))            # checked: a non-finite point says so here
            role = Role.RAPID if blk.motion is Motion.RAPID and blk.modal.side == 0 else (
                Role.COMPENSATED if comp_on else Role.UNCOMPENSATED)
            self.row(pos, LINE_ROW, (u, v, u, v, 0.0), role, self.n_moves + len(self.extra_blocks),
                     blk.uvw(blk.start)[2], blk.uvw(blk.end)[2])
            self.extra_blocks.append(blk)
            pos += 1
        return pos


def _moves(scan, arr: ElementArrays, joints):
    """Row kind, geometry and objects of every move's own tool segment, and
    its in-plane length."""
    n = len(scan)
    fast = np.flatnonzero(arr.kind != SPIRAL)
    kind_f, geom_f, objects_f = tool_rows(arr, fast, joints.starts, joints.ends)
    if fast.size == n:
        kind, geom = kind_f, geom_f
        objects = objects_f
    else:
        kind = np.full(n, OBJECT_ROW, np.int8)
        geom = np.zeros((n, 5))
        kind[fast], geom[fast] = kind_f, geom_f
        objects = {int(fast[q]): g for q, g in objects_f.items()}
        objects.update((int(i), None) for i in np.flatnonzero(arr.kind == SPIRAL))
    for i in [i for i, g in objects.items() if g is None]:
        objects[i] = tool_geometry(scan.element(i), joints.starts[i], joints.ends[i])
    length = np.where(kind == LINE_ROW, np.hypot(geom[:, 2] - geom[:, 0], geom[:, 3] - geom[:, 1]),
                      geom[:, 2] * np.abs(geom[:, 4]))
    for i, g in objects.items():
        length[i] = g.length
    return kind, geom, objects, length


def _gap_counts(gaps) -> dict[int, int]:
    """Index -> number of non-dwell blocks of every non-empty gap."""
    return {i: sum(blk.motion is not Motion.DWELL for blk in g) for i, g in gaps.items()}


def emit_columns(scan, arr: ElementArrays, joints,
                 codes: np.ndarray | None = None) -> tuple[SegmentColumns, tuple]:
    """The tool path's rows and dwells (``(row before which, seconds, block)``);
    ``codes``: the moves' :func:`class_codes` when the caller has them."""
    n, k = len(scan), scan.k
    gaps, gaps_after = scan.gaps, decisions.GAP_MOVES_AFTER_CORNER_ARC
    codes = class_codes(k) if codes is None else codes
    m_kind, m_geom, m_objects, length = _moves(scan, arr, joints)
    emitted = (length > POINT_EPS) | (arr.w0 != arr.w1)
    # rows before and after each move's own segment
    counts = _gap_counts(gaps)
    before, after = np.zeros(n, np.int64), np.zeros(n, np.int64)
    for i, c in counts.items():
        if i < n and (gaps_after or i == 0):
            before[i] = c
        if not gaps_after and 0 < i < n:
            after[i - 1] = c
    corner_n = np.zeros(n, np.int64)
    arc_at, arc_rows = joints.arc_rows
    corner_n[arc_at] += 1
    for i, lst in joints.corners.items():
        corner_n[i] += len(lst)
    own = before + emitted
    off = np.concatenate(([0], np.cumsum(own + after + corner_n)))
    loose = _Loose(n)
    comp_on = (k != 0) & (codes != LEAD_IN_CODE)     # a gap before move i runs compensated
    for i in sorted(counts):
        if i < n and (gaps_after or i == 0):
            loose.gap(gaps[i], int(off[i]), joints.starts[i], bool(comp_on[i]))
        if not gaps_after and 0 < i < n:
            loose.gap(gaps[i], int(off[i - 1] + own[i - 1]), joints.ends[i - 1], bool(comp_on[i]))
    for i, lst in joints.corners.items():
        pos = int(off[i] + own[i] + after[i])
        w1 = float(arr.w1[i])
        for j, g in enumerate(lst):
            loose.row(pos + j, OBJECT_ROW, (0.0,) * 5, Role.CORNER, i, w1, w1, g)
    _tail(loose, scan, arr, joints, int(off[-1]))
    total = int(off[-1]) + sum(1 for p in loose.pos if p >= off[-1])
    cols = _fill(total, off[:-1] + before, emitted, m_kind, m_geom, m_objects, codes, arr,
                 (off[arc_at] + own[arc_at] + after[arc_at], arc_at, arc_rows), loose)
    blocks = scan.blocks + loose.extra_blocks if loose.extra_blocks else scan.blocks
    return SegmentColumns(**cols, blocks=blocks), tuple(loose.dwells)


def _fill(total, move_pos, emitted, m_kind, m_geom, m_objects, codes, arr, arcs, loose):
    """The columns' arrays: moves and batch corner arcs in bulk, loose rows one by one."""
    kind = np.empty(total, np.int8)
    geom = np.zeros((total, 5))
    role = np.empty(total, np.int8)
    block = np.empty(total, np.int64)
    w = np.empty((total, 2))
    at = move_pos[emitted]
    moved = np.flatnonzero(emitted)
    kind[at] = m_kind[moved]
    put_rows(geom, at, take_rows(m_geom, moved))
    move_role = CLASS_ROLE[codes]
    move_role[(codes == 0) & arr.rapid] = ROLE_CODE[Role.RAPID]
    role[at], block[at] = move_role[moved], moved
    w[at, 0], w[at, 1] = arr.w0[moved], arr.w1[moved]
    objects = {int(move_pos[i]): g for i, g in m_objects.items() if emitted[i]}
    arc_pos, arc_at, arc_rows = arcs
    kind[arc_pos], role[arc_pos] = ARC_ROW, ROLE_CODE[Role.CORNER]
    put_rows(geom, arc_pos, arc_rows)
    block[arc_pos] = arc_at
    w[arc_pos, 0] = w[arc_pos, 1] = arr.w1[arc_at]
    if loose.pos:
        p = np.array(loose.pos, np.int64)
        kind[p], geom[p], role[p] = loose.kind, loose.geom, loose.role
        block[p], w[p] = loose.block, loose.w
        objects.update(loose.objects)
    return dict(kind=kind, geom=geom, objects=objects, role=role, block=block, w=w)


def _tail(loose: _Loose, scan, arr: ElementArrays, joints, pos: int) -> None:
    """The blocks after the last in-plane move, and the automatic lead-out:
    it happens before the first trailing block with compensation off, or at
    the very end (as :func:`ccopt.compensate.pmac.emit_tail`)."""
    n = len(scan)
    trailing: list[Block] = scan.gaps[n]
    if joints.tail_return is None and scan.k[-1] == 0:
        loose.gap(trailing, pos, joints.ends[-1], False)
        return
    split = next((q for q, blk in enumerate(trailing) if blk.modal.side == 0), len(trailing))
    pos = loose.gap(trailing[:split], pos, joints.ends[-1], True)
    end = joints.ends[-1]
    if joints.tail_return is not None:
        start, end = joints.tail_return
        a = (float(start[0]), float(start[1]))
        b = (float(end[0]), float(end[1]))
        w_last = float(arr.w1[n - 1])
        loose.row(pos, OBJECT_ROW, (0.0,) * 5, Role.LEAD_OUT, n - 1, w_last, w_last, Line(a, b))
        pos += 1
    loose.gap(trailing[split:], pos, end, False)
