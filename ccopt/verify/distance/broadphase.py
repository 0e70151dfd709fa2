"""Broad phase: which tool segments can come near which contour elements.

A static uniform grid over the contour. Each contour element's bounding box,
grown by its reach (required clearance plus a margin), is entered in every
cell it covers; each tool segment's bounding box looks up the cells it
covers. A pair is reported once, in the cell holding the lower-left corner of
the intersection of the two boxes, and only when the boxes really overlap, so
no pair with a tool-to-element distance within reach is missed and none is
repeated. Everything is array arithmetic (sort and search, no Python loop
over elements); boxes covering more than :data:`MAX_CELLS` cells (a few very
long elements) are tested against every box of the other side directly.

The cell size is twice the median box size (at least the largest reach), so
a typical box covers one to four cells (measured fastest on long paths).
"""
from __future__ import annotations

import numpy as np

#: A box covering more cells than this is paired by a direct overlap test.
MAX_CELLS = 64

#: Cell size as a multiple of the median box size.
CELL_FACTOR = 2.0

#: Pairs are produced in chunks of about this many to bound memory.
CHUNK = 1 << 18

#: Smallest cell size (program units): boxes that are all points with zero
#: reach would otherwise give a zero cell and divide by it.
MIN_CELL = 1e-12


def _cells(box: np.ndarray, origin: np.ndarray, h: float):
    lo = np.floor((box[:, :2] - origin) / h).astype(np.int64)
    hi = np.floor((box[:, 2:] - origin) / h).astype(np.int64)
    return lo, hi


def _expand(lo: np.ndarray, hi: np.ndarray, ids: np.ndarray, ncol: np.int64):
    """``(cell key, id, cell x, cell y)`` for every cell of every box (``ids`` are the rows)."""
    nx = hi[:, 0] - lo[:, 0] + 1
    ny = hi[:, 1] - lo[:, 1] + 1
    cnt = nx * ny
    if (cnt == 1).all():                           # the common case: one cell each
        return lo[:, 1] * ncol + lo[:, 0], ids, lo[:, 0], lo[:, 1]
    total = int(cnt.sum())
    rep = np.repeat(np.arange(ids.size), cnt)
    start = np.cumsum(cnt) - cnt
    local = np.arange(total, dtype=np.int64) - np.repeat(start, cnt)
    nxr = nx[rep]
    cx = lo[rep, 0] + local % nxr
    cy = lo[rep, 1] + local // nxr
    return cy * ncol + cx, ids[rep], cx, cy


def _overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return ((a[:, 0] <= b[:, 2]) & (b[:, 0] <= a[:, 2])
            & (a[:, 1] <= b[:, 3]) & (b[:, 1] <= a[:, 3]))


def candidate_pairs(tool_box: np.ndarray, elem_box: np.ndarray, reach: np.ndarray):
    """Index pairs ``(tool, element)`` whose boxes come within ``reach[element]``.

    ``tool_box``, ``elem_box``: ``(N, 4)`` ``xmin, ymin, xmax, ymax``;
    ``reach``: ``(M,)`` program units. Returns two ``intp`` arrays. A pair
    whose segments are closer than the element's reach is always included.
    """
    nt, ne = tool_box.shape[0], elem_box.shape[0]
    empty = (np.zeros(0, np.intp), np.zeros(0, np.intp))
    if nt == 0 or ne == 0:
        return empty
    grown = np.empty_like(elem_box, dtype=float)
    grown[:, :2] = elem_box[:, :2] - reach[:, None]
    grown[:, 2:] = elem_box[:, 2:] + reach[:, None]
    allbox = np.concatenate((tool_box, grown))
    ext = np.maximum(allbox[:, 2] - allbox[:, 0], allbox[:, 3] - allbox[:, 1])
    h = float(max(CELL_FACTOR * np.median(ext), float(reach.max(initial=0.0)), MIN_CELL))
    # column by column: numpy's reduction over axis 0 of a narrow array is
    # several times slower than over each strided column
    origin = np.array([allbox[:, 0].min(), allbox[:, 1].min()])
    span = (np.array([allbox[:, 2].max(), allbox[:, 3].max()]) - origin) / h
    ncol = np.int64(np.floor(span[0])) + 2
    if float(span[0] + 2) * float(span[1] + 2) > 2.0 ** 62:
        raise ValueError("broad phase: the path is too large for the grid")
    lo_t, hi_t = _cells(tool_box, origin, h)
    lo_e, hi_e = _cells(grown, origin, h)
    cnt_t = (hi_t[:, 0] - lo_t[:, 0] + 1) * (hi_t[:, 1] - lo_t[:, 1] + 1)
    cnt_e = (hi_e[:, 0] - lo_e[:, 0] + 1) * (hi_e[:, 1] - lo_e[:, 1] + 1)
    big_t = cnt_t > MAX_CELLS
    big_e = cnt_e > MAX_CELLS
    out_t, out_e = [], []

    # Grid join for ordinary boxes.
    ti = np.flatnonzero(~big_t)
    ei = np.flatnonzero(~big_e)
    if ti.size and ei.size:
        _grid_join(tool_box, grown, (lo_t, hi_t, ti), (lo_e, hi_e, ei), ncol, (out_t, out_e))

    # Direct tests for big boxes (each against every box of the other side).
    for i in np.flatnonzero(big_t):
        m = np.flatnonzero(_overlap(np.broadcast_to(tool_box[i], grown.shape), grown))
        out_t.append(np.full(m.size, i, np.intp))
        out_e.append(m)
    small_t = np.flatnonzero(~big_t)
    for j in np.flatnonzero(big_e):
        m = small_t[_overlap(tool_box[small_t], np.broadcast_to(grown[j], (small_t.size, 4)))]
        out_t.append(m)
        out_e.append(np.full(m.size, j, np.intp))
    if not out_t:
        return empty
    return (np.concatenate(out_t).astype(np.intp), np.concatenate(out_e).astype(np.intp))


def _grid_join(tool_box: np.ndarray, grown: np.ndarray, tools, elems, ncol: np.int64,
               out) -> None:
    """Append to ``out = (tool ids, element ids)`` the pairs of ordinary boxes
    that overlap, in cell order: ``tools = (lo, hi, ids)`` the tool boxes'
    lower and upper cells and the rows taking part, ``elems`` the same for the
    grown element boxes."""
    lo_t, hi_t, ti = tools
    lo_e, hi_e, ei = elems
    ek, eid, _, _ = _expand(lo_e[ei], hi_e[ei], ei, ncol)
    order = np.argsort(ek, kind="stable")
    ek, eid = ek[order], eid[order]
    tk, tid, tcx, tcy = _expand(lo_t[ti], hi_t[ti], ti, ncol)
    first = np.searchsorted(ek, tk, side="left")
    last = np.searchsorted(ek, tk, side="right")
    cnt = last - first
    keep = cnt > 0
    tid, tcx, tcy, first, cnt = tid[keep], tcx[keep], tcy[keep], first[keep], cnt[keep]
    csum = np.cumsum(cnt)
    # One contiguous column per coordinate: most candidates fail a test, and
    # gathering single columns of the survivors only is cheaper than whole rows.
    ltx, lty = np.ascontiguousarray(lo_t[:, 0]), np.ascontiguousarray(lo_t[:, 1])
    lex, ley = np.ascontiguousarray(lo_e[:, 0]), np.ascontiguousarray(lo_e[:, 1])
    tx0, ty0, tx1, ty1 = (np.ascontiguousarray(tool_box[:, k]) for k in range(4))
    gx0, gy0, gx1, gy1 = (np.ascontiguousarray(grown[:, k]) for k in range(4))
    pos = 0
    while pos < tid.size:                       # chunks of ~CHUNK candidate pairs
        base = csum[pos - 1] if pos else 0
        stop = max(int(np.searchsorted(csum, base + CHUNK, side="right")), pos + 1)
        c = cnt[pos:stop]
        rep = np.repeat(np.arange(pos, stop), c)
        off = np.arange(int(c.sum())) - np.repeat(np.cumsum(c) - c, c)
        pt = tid[rep]
        pe = eid[first[rep] + off]
        # Report each pair once, in the cell of the lower-left corner of the
        # two boxes' overlap: cell (max of the lower cells), floor being monotone.
        ok = np.maximum(ltx[pt], lex[pe]) == tcx[rep]
        ok &= np.maximum(lty[pt], ley[pe]) == tcy[rep]
        k = np.flatnonzero(ok)
        pt, pe = pt[k], pe[k]
        # the boxes' overlap (as _overlap), x first, then y on the pairs left
        k = np.flatnonzero((tx0[pt] <= gx1[pe]) & (gx0[pe] <= tx1[pt]))
        pt, pe = pt[k], pe[k]
        k = np.flatnonzero((ty0[pt] <= gy1[pe]) & (gy0[pe] <= ty1[pt]))
        out[0].append(pt[k])
        out[1].append(pe[k])
        pos = stop
