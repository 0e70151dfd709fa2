"""The part of each tool segment alongside its contour element, for many pairs at once.

For the contact check (:mod:`ccopt.verify.contact`), a pair with no closed
form: the tool segment is cut where it crosses the boundary lines of its
element's end regions (:func:`~ccopt.verify.clearance.end_regions`: the
half-plane behind each end of a line, the wedge beyond each end of an arc),
the pieces outside every region are the part alongside the element, and the
exact farthest-point kernel (:func:`~ccopt.verify.distance.max_distance`)
measures the pieces of every pair in one call.

Per pair this is :func:`~ccopt.verify.clearance.clip_pieces` of the segment
by :func:`~ccopt.verify.clearance.end_regions` of its element, done with the
same arithmetic in the same order (:mod:`ccopt.verify.end_clip`), so every
figure is the same to the last bit.
"""
from __future__ import annotations

import numpy as np

from ccopt.tolerances import POINT_EPS
from ccopt.verify.distance import max_distance
from ccopt.verify.end_clip import CUTS, EndPlanes, ToolRows, piece_rows, region_pieces
from ccopt.verify.segments import Packed, pack

#: A tool segment runs alongside its element when more than this length of it
#: (program units) lies alongside; touching the band's edge at a point does
#: not count (an arc swept the wrong way meets the element's sector only at
#: its two ends).
ALONGSIDE_MIN_LENGTH = POINT_EPS


def farthest_clipped(tool: Packed, E: Packed, si: np.ndarray, ej: np.ndarray):
    """``(dmax, witness)``: for each tool segment ``si`` (a line or arc), the
    exact largest distance to its element ``ej`` (a line or arc) from its part
    alongside the element (outside both end regions), and the tool point where
    it is reached; ``inf`` and the segment's start where no more than
    :data:`ALONGSIDE_MIN_LENGTH` of it lies alongside (it does not run along
    the element at all)."""
    si, ej = np.asarray(si, np.intp), np.asarray(ej, np.intp)
    seg = ToolRows.take(tool, si)
    [(pair, u0, u1)] = region_pieces(seg, EndPlanes.of(E, ej))
    pieces, length = piece_rows(seg, pair, u0, u1)
    # each pair's length alongside, summed piece after piece
    per = np.zeros((si.size, CUTS - 1))
    first = np.searchsorted(pair, pair)
    per[pair, np.arange(pair.size) - first] = length
    total = np.zeros(si.size)
    for col in per.T:
        total = total + col
    along = total > ALONGSIDE_MIN_LENGTH
    dmax = np.full(si.size, np.inf)
    wq = seg.start()
    take = np.flatnonzero(along[pair])
    if take.size:
        uniq, at = np.unique(ej[pair[take]], return_inverse=True)
        B = pack([E.geom(j) for j in uniq.tolist()]).arr
        dm, q, _ = max_distance(pieces, take, B, at.reshape(-1))
        k = _first_largest(pair[take], dm)
        dmax[pair[take][k]], wq[pair[take][k]] = dm[k], q[k]
    return dmax, wq


def _first_largest(group: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Index of the first largest value of each run of equal ``group`` (sorted)
    in ``v``, a NaN first (as :func:`numpy.argmax` of each run)."""
    starts = np.flatnonzero(np.r_[True, group[1:] != group[:-1]])
    nan = np.isnan(v)
    top = np.maximum.reduceat(v, starts)
    run = np.repeat(np.arange(starts.size), np.diff(np.r_[starts, v.size]))
    cand = np.flatnonzero((v == top[run]) | (nan & np.logical_or.reduceat(nan, starts)[run]))
    return cand[np.r_[True, run[cand[1:]] != run[cand[:-1]]]]
