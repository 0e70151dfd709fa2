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
same arithmetic in the same order, so every figure is the same to the last
bit: a dot product of two 2-vectors is numpy's ``@`` (BLAS, with a fused
multiply-add), which :func:`numpy.vecdot` calls row by row, and the scalar
``math.hypot``, ``math.atan2``, ``math.acos``, ``math.cos`` and ``math.sin``
stay :mod:`math`'s (numpy's own differ from them in the last bit).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import KIND_ARC, KIND_LINE
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import math_each
from ccopt.geometry.distance import SegmentRows
from ccopt.tolerances import POINT_EPS
from ccopt.verify.clearance import BOUNDARY_REL
from ccopt.verify.distance import max_distance
from ccopt.verify.segments import Packed, pack, pack_rows

#: A tool segment runs alongside its element when more than this length of it
#: (program units) lies alongside; touching the band's edge at a point does
#: not count (an arc swept the wrong way meets the element's sector only at
#: its two ends).
ALONGSIDE_MIN_LENGTH = POINT_EPS

#: Boundary lines per pair: two per end region (a line's region has one).
_PLANES = 4
#: Cuts per pair: the ends 0 and 1, and up to two crossings per boundary line.
_CUTS = 2 + 2 * _PLANES


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row by row ``a[k] @ b[k]`` of ``(N, 2)`` rows, as numpy's ``@`` gives it."""
    return np.vecdot(np.ascontiguousarray(a), np.ascontiguousarray(b))


@dataclass(frozen=True, eq=False)
class EndPlanes:
    """The end regions of one element per pair, as boundary half-planes
    ``n . q <= c``: ``n`` ``(P, 4, 2)``, ``c`` ``(P, 4)``; planes 0-1 bound
    the region of the start, 2-3 that of the end; ``used``: the plane is one
    of its region's (a line's region has one plane, a full circle none)."""

    n: np.ndarray
    c: np.ndarray
    used: np.ndarray

    @classmethod
    def of(cls, E: Packed, ej: np.ndarray) -> "EndPlanes":
        """Both end regions of elements ``ej`` (lines and arcs; none for others)."""
        A = E.arr
        m = ej.size
        n, c = np.zeros((m, _PLANES, 2)), np.zeros((m, _PLANES))
        used = np.zeros((m, _PLANES), bool)
        kind = A.kind[ej]
        li = np.flatnonzero(kind == KIND_LINE)
        p0, p1 = A.p0[ej[li]], A.p1[ej[li]]
        d = p1 - p0
        L = math_each(math.hypot, d[:, 0], d[:, 1])
        ok = L != 0.0                       # a point has no direction: no regions
        li, t = li[ok], d[ok] / L[ok, None]
        n[li, 0], c[li, 0] = t, _dot(t, p0[ok])
        n[li, 2], c[li, 2] = -t, _dot(-t, p1[ok])
        used[li, 0] = used[li, 2] = True
        ai = np.flatnonzero(kind == KIND_ARC)
        sw, th0, centre = A.sweep[ej[ai]], A.theta0[ej[ai]], A.center[ej[ai]]
        gap = TWO_PI - np.abs(sw)
        ok = gap > 0.0                      # a full circle has no ends
        ai, sw, th0, centre, half = ai[ok], sw[ok], th0[ok], centre[ok], 0.5 * gap[ok]
        th1 = th0 + sw
        ccw = np.copysign(1.0, sw) > 0
        wedges = ((np.where(ccw, th0 - half, th0), np.where(ccw, th0, th0 + half)),
                  (np.where(ccw, th1, th1 - half), np.where(ccw, th1 + half, th1)))
        for r, (a, b) in enumerate(wedges):
            # cross(da, q - c) >= 0 and cross(q - c, db) >= 0
            n1 = np.stack((math_each(math.sin, a), -math_each(math.cos, a)), axis=1)
            n2 = np.stack((-math_each(math.sin, b), math_each(math.cos, b)), axis=1)
            n[ai, 2 * r], c[ai, 2 * r] = n1, _dot(n1, centre)
            n[ai, 2 * r + 1], c[ai, 2 * r + 1] = n2, _dot(n2, centre)
            used[ai, 2 * r] = used[ai, 2 * r + 1] = True
        return cls(n, c, used)

    def inside(self, pair: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Points ``q`` ``(M, 2)`` inside one of the regions of pair ``pair``
        (:func:`~ccopt.verify.clearance.in_regions` of each point alone)."""
        slack = BOUNDARY_REL * (1.0 + np.abs(q).max(axis=1))
        out = np.zeros(pair.size, bool)
        for r in (0, 1):
            ins = self.used[pair, 2 * r].copy()
            for k in (2 * r, 2 * r + 1):
                ins &= (_dot(q, self.n[pair, k]) - self.c[pair, k] <= slack) \
                    | ~self.used[pair, k]
            out |= ins
        return out


@dataclass(frozen=True, eq=False)
class _Segments(SegmentRows):
    """The tool segments of the pairs (:class:`~ccopt.geometry.distance.SegmentRows`)
    and their ``length``."""

    length: np.ndarray

    @classmethod
    def take(cls, T: Packed, si: np.ndarray) -> "_Segments":
        line, p0, p1, c, R, th, sw = SegmentRows.columns(T.arr, si)
        d = p1 - p0
        length = np.where(line, math_each(math.hypot, d[:, 0], d[:, 1]), R * np.abs(sw))
        return cls(line, p0, p1, c, R, th, sw, length)

    def start(self) -> np.ndarray:
        """Start points (an arc's as :attr:`~ccopt.geometry.Arc.start` gives it)."""
        out = self.p0.copy()
        a = np.flatnonzero(~self.line)
        out[a, 0] = self.c[a, 0] + self.R[a] * math_each(math.cos, self.th[a])
        out[a, 1] = self.c[a, 1] + self.R[a] * math_each(math.sin, self.th[a])
        return out

    def point(self, k: np.ndarray, s: np.ndarray) -> np.ndarray:
        """The points at arc length ``s`` along segments ``k`` (of positive length)."""
        L = self.length[k]
        f = np.clip(s, 0.0, L) / L
        u = 1.0 - f
        out = np.empty((k.size, 2))
        phi = self.th[k] + self.sw[k] * f
        for a in (0, 1):
            trig = np.cos(phi) if a == 0 else np.sin(phi)
            out[:, a] = np.where(self.line[k], u * self.p0[k, a] + f * self.p1[k, a],
                                 self.c[k, a] + self.R[k] * trig)
        return out


def _cuts(seg: _Segments, planes: EndPlanes) -> np.ndarray:
    """``(P, 10)``: the fractions (0..1 of length) where each segment crosses
    its boundary lines, with 0 and 1, sorted (NaN for none, last)."""
    m = seg.line.size
    cuts = np.full((m, _CUTS), np.nan)
    cuts[:, 0], cuts[:, 1] = 0.0, 1.0
    for k in range(_PLANES):
        nk, ck = planes.n[:, k], planes.c[:, k]
        q = np.flatnonzero(planes.used[:, k] & seg.line)
        f0 = _dot(nk[q], seg.p0[q]) - ck[q]
        f1 = _dot(nk[q], seg.p1[q]) - ck[q]
        ok = f0 != f1
        t = f0 / np.where(ok, f0 - f1, 1.0)
        cuts[q, 2 + 2 * k] = np.where(ok & (0.0 <= t) & (t <= 1.0), t, np.nan)
        q = np.flatnonzero(planes.used[:, k] & ~seg.line)
        nx, ny = nk[q, 0], nk[q, 1]
        ratio = (ck[q] - _dot(nk[q], seg.c[q])) / (seg.R[q] * math_each(math.hypot, nx, ny))
        ok = ~(np.abs(ratio) > 1.0)
        psi, acs = math_each(math.atan2, ny, nx), math_each(math.acos, np.where(ok, ratio, 0.0))
        full = np.abs(seg.sw[q])
        for s, phi in enumerate((psi + acs, psi - acs)):
            along = np.mod((phi - seg.th[q]) * np.copysign(1.0, seg.sw[q]), TWO_PI)
            at = np.where(full > 0.0, along / np.where(full > 0.0, full, 1.0), 0.0)
            cuts[q, 2 + 2 * k + s] = np.where(ok & (along <= full), at, np.nan)
    # a set of cuts: a crossing at -0.0 is the end 0.0
    cuts[cuts == 0.0] = 0.0
    return np.sort(cuts, axis=1)


def _pieces_outside(seg: _Segments, planes: EndPlanes):
    """The pieces of the segments outside their regions, in pair and
    fraction order: ``(pair, u0, u1)``."""
    cuts = _cuts(seg, planes)
    u0, u1 = cuts[:, :-1], cuts[:, 1:]
    live = (u1 - u0 > 0.0) & (seg.length > 0.0)[:, None]
    pair, col = np.nonzero(live)
    a, b = u0[pair, col], u1[pair, col]
    mid = seg.point(pair, 0.5 * (a + b) * seg.length[pair])
    out = ~planes.inside(pair, mid)
    return pair[out], a[out], b[out]


def _packed_pieces(seg: _Segments, pair: np.ndarray, u0: np.ndarray, u1: np.ndarray):
    """``(Packed, lengths)`` of the pieces ``u0..u1`` of the segments ``pair``
    (as :func:`~ccopt.verify.clearance.clip_pieces` makes them)."""
    line = seg.line[pair]
    li, ai = np.flatnonzero(line), np.flatnonzero(~line)
    p, d = seg.p0[pair[li]], seg.p1[pair[li]] - seg.p0[pair[li]]
    pts = np.concatenate((p + u0[li, None] * d, p + u1[li, None] * d), axis=1)
    k = pair[ai]
    arcs = (seg.c[k], seg.R[k], seg.th[k] + seg.sw[k] * u0[ai], seg.sw[k] * (u1[ai] - u0[ai]))
    length = np.empty(pair.size)
    length[li] = math_each(math.hypot, pts[:, 2] - pts[:, 0], pts[:, 3] - pts[:, 1])
    length[ai] = arcs[1] * np.abs(arcs[3])
    return pack_rows(pair.size, li, pts, ai, arcs), length


def farthest_clipped(tool: Packed, E: Packed, si: np.ndarray, ej: np.ndarray):
    """``(dmax, witness)``: for each tool segment ``si`` (a line or arc), the
    exact largest distance to its element ``ej`` (a line or arc) from its part
    alongside the element (outside both end regions), and the tool point where
    it is reached; ``inf`` and the segment's start where no more than
    :data:`ALONGSIDE_MIN_LENGTH` of it lies alongside (it does not run along
    the element at all)."""
    si, ej = np.asarray(si, np.intp), np.asarray(ej, np.intp)
    seg = _Segments.take(tool, si)
    pair, u0, u1 = _pieces_outside(seg, EndPlanes.of(E, ej))
    pk, length = _packed_pieces(seg, pair, u0, u1)
    # each pair's length alongside, summed piece after piece
    per = np.zeros((si.size, _CUTS - 1))
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
        dm, q, _ = max_distance(pk.arr, take, B, at.reshape(-1))
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
