"""Tool segments cut at their elements' end regions, for many pairs at once.

The end regions of a contour element (:func:`~ccopt.verify.clearance.end_regions`:
the half-plane behind each end of a line, the wedge beyond each end of an
arc) are bounded by lines. Each (tool segment, element) pair's segment is cut
where it crosses those lines, and each piece between two cuts lies wholly
inside the regions or wholly outside them, told by its middle point. The
contact check (:mod:`ccopt.verify.alongside`) measures the pieces outside;
the open ends of the clearance check (:mod:`ccopt.verify.open_ends`) the
pieces outside and, region by region, the pieces inside.

Per pair this is :func:`~ccopt.verify.clearance.clip_pieces` of the segment
by the element's regions, done with the same arithmetic in the same order, so
every figure is the same to the last bit: a dot product of two 2-vectors is
numpy's ``@`` (BLAS, with a fused multiply-add), which :func:`numpy.vecdot`
calls row by row (:func:`row_dot`), and the scalar ``math.hypot``,
``math.atan2``, ``math.acos``, ``math.cos`` and ``math.sin`` stay
:mod:`math`'s (numpy's own differ from them in the last bit).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import KIND_ARC, KIND_LINE, SegmentArray
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import math_each
from ccopt.geometry.distance import SegmentRows
from ccopt.verify.segments import Packed

#: Points within this (relative to the coordinates) of an end region's
#: boundary count as on it: a tool segment laid along the boundary (a lead-in
#: on the normal at the contour's end) must not flicker in and out by rounding.
BOUNDARY_REL = 1e-12

#: Boundary lines per pair: two per end region (a line's region has one).
PLANES = 4
#: Cuts per pair: the ends 0 and 1, and up to two crossings per boundary line.
CUTS = 2 + 2 * PLANES


def row_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row by row ``a[k] @ b[k]`` of ``(N, 2)`` rows, as numpy's ``@`` gives it
    for two 2-vectors (or one row of a matrix)."""
    return np.vecdot(np.ascontiguousarray(a), np.ascontiguousarray(b))


def matrix_row_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row by row ``a[k] @ b[k]`` as numpy's ``@`` gives the rows of an
    ``(M, 2)`` matrix (``M >= 2``) times a 2-vector: BLAS's matrix-vector
    product fuses the multiply-add the other way round from its dot product,
    so it is :func:`row_dot` of the rows with their two columns swapped."""
    return np.vecdot(np.ascontiguousarray(a[:, ::-1]), np.ascontiguousarray(b[:, ::-1]))


def points_dot(pts: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``pts @ v`` of ``(M, 2)`` points and a 2-vector, with the bits numpy's
    ``@`` gives on the machines measured (:func:`row_dot` for one row,
    :func:`matrix_row_dot` for more), but through the one dot kernel the batch
    roads use too: BLAS picks its matrix-vector kernel by the processor, and
    another one might fuse differently from the dot kernel, where this stays
    the same road as the batch's on every machine."""
    pts = np.asarray(pts, float)
    rows = np.broadcast_to(np.asarray(v, float), pts.shape)
    return row_dot(pts, rows) if pts.shape[0] == 1 else matrix_row_dot(pts, rows)


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
    def of(cls, E: Packed, ej: np.ndarray, start=True, end=True) -> "EndPlanes":
        """The end regions of elements ``ej`` (lines and arcs; none for others):
        of the start where ``start``, of the end where ``end`` (per pair)."""
        A = E.arr
        m = ej.size
        n, c = np.zeros((m, PLANES, 2)), np.zeros((m, PLANES))
        used = np.zeros((m, PLANES), bool)
        kind = A.kind[ej]
        li = np.flatnonzero(kind == KIND_LINE)
        p0, p1 = A.p0[ej[li]], A.p1[ej[li]]
        d = p1 - p0
        L = math_each(math.hypot, d[:, 0], d[:, 1])
        ok = L != 0.0                       # a point has no direction: no regions
        li, t = li[ok], d[ok] / L[ok, None]
        n[li, 0], c[li, 0] = t, row_dot(t, p0[ok])
        n[li, 2], c[li, 2] = -t, row_dot(-t, p1[ok])
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
            n[ai, 2 * r], c[ai, 2 * r] = n1, row_dot(n1, centre)
            n[ai, 2 * r + 1], c[ai, 2 * r + 1] = n2, row_dot(n2, centre)
            used[ai, 2 * r] = used[ai, 2 * r + 1] = True
        used[:, :2] &= np.asarray(start, bool).reshape(-1, 1)
        used[:, 2:] &= np.asarray(end, bool).reshape(-1, 1)
        return cls(n, c, used)

    def inside_each(self, pair: np.ndarray, q: np.ndarray) -> np.ndarray:
        """``(M, 2)``: points ``q`` ``(M, 2)`` inside the region of the start
        (column 0) and of the end (column 1) of pair ``pair``
        (:func:`~ccopt.verify.clearance.in_regions` of each point alone)."""
        slack = BOUNDARY_REL * (1.0 + np.abs(q).max(axis=1))
        out = self.used[pair][:, ::2].copy()
        for k in range(PLANES):
            out[:, k // 2] &= (row_dot(q, self.n[pair, k]) - self.c[pair, k] <= slack) \
                | ~self.used[pair, k]
        return out


@dataclass(frozen=True, eq=False)
class ToolRows(SegmentRows):
    """The tool segments of the pairs (:class:`~ccopt.geometry.distance.SegmentRows`)
    and their ``length``."""

    length: np.ndarray

    @classmethod
    def take(cls, T: Packed, si: np.ndarray) -> "ToolRows":
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


def _crossings(seg: ToolRows, planes: EndPlanes) -> np.ndarray:
    """``(P, 8)``: the fractions (0..1 of length) where each segment crosses
    each of its boundary lines, two columns per line (NaN for none)."""
    m = seg.line.size
    cross = np.full((m, PLANES, 2), np.nan)
    pair, k = np.nonzero(planes.used)
    n, c = planes.n[pair, k], planes.c[pair, k]
    q = np.flatnonzero(seg.line[pair])
    f0 = row_dot(n[q], seg.p0[pair[q]]) - c[q]
    f1 = row_dot(n[q], seg.p1[pair[q]]) - c[q]
    ok = f0 != f1
    t = f0 / np.where(ok, f0 - f1, 1.0)
    cross[pair[q], k[q], 0] = np.where(ok & (0.0 <= t) & (t <= 1.0), t, np.nan)
    q = np.flatnonzero(~seg.line[pair])
    a = pair[q]
    nx, ny = n[q, 0], n[q, 1]
    ratio = (c[q] - row_dot(n[q], seg.c[a])) / (seg.R[a] * math_each(math.hypot, nx, ny))
    ok = ~(np.abs(ratio) > 1.0)
    psi, acs = math_each(math.atan2, ny, nx), math_each(math.acos, np.where(ok, ratio, 0.0))
    full = np.abs(seg.sw[a])
    for s, phi in enumerate((psi + acs, psi - acs)):
        along = np.mod((phi - seg.th[a]) * np.copysign(1.0, seg.sw[a]), TWO_PI)
        at = np.where(full > 0.0, along / np.where(full > 0.0, full, 1.0), 0.0)
        cross[a, k[q], s] = np.where(ok & (along <= full), at, np.nan)
    return cross.reshape(m, 2 * PLANES)


def region_pieces(seg: ToolRows, planes: EndPlanes, regions=(None,)) -> list:
    """For each of ``regions``: ``None``, the pieces of the segments (of
    positive length) outside all their regions; ``r``, their pieces inside
    region ``r`` (0: the start's, 1: the end's), cut at its own boundary lines
    only. Each as ``(pair, u0, u1)``, in pair and fraction order."""
    m = seg.line.size
    cross = _crossings(seg, planes)
    cuts = np.full((len(regions), m, CUTS), np.nan)
    cuts[:, :, 0], cuts[:, :, 1] = 0.0, 1.0
    for v, r in enumerate(regions):
        # a region's two lines are two columns each of the crossings
        cols = slice(0, 2 * PLANES) if r is None else slice(PLANES * r, PLANES * (r + 1))
        cuts[v, :, 2 + cols.start:2 + cols.stop] = cross[:, cols]
    # a set of cuts: a crossing at -0.0 is the end 0.0
    cuts[cuts == 0.0] = 0.0
    cuts = np.sort(cuts, axis=2)
    u0, u1 = cuts[:, :, :-1], cuts[:, :, 1:]
    live = (u1 - u0 > 0.0) & (seg.length > 0.0)[None, :, None]
    v, pair, col = np.nonzero(live)
    a, b = u0[v, pair, col], u1[v, pair, col]
    mid = seg.point(pair, 0.5 * (a + b) * seg.length[pair])
    ins = planes.inside_each(pair, mid)
    want = [~(ins[:, 0] | ins[:, 1]) if r is None else ins[:, r] for r in regions]
    keep = np.choose(v, want)
    out = []
    for w in range(len(regions)):
        k = np.flatnonzero(keep & (v == w))
        out.append((pair[k], a[k], b[k]))
    return out


def piece_rows(seg: ToolRows, pair: np.ndarray, u0: np.ndarray, u1: np.ndarray):
    """``(SegmentArray, lengths)`` of the pieces ``u0..u1`` of the segments
    ``pair`` (as :func:`~ccopt.verify.clearance.clip_pieces` makes them; an
    arc's ends as :func:`~ccopt.verify.segments.pack` gives them)."""
    n = pair.size
    line = seg.line[pair]
    li, ai = np.flatnonzero(line), np.flatnonzero(~line)
    p0, p1, centre = np.full((n, 2), np.nan), np.full((n, 2), np.nan), np.full((n, 2), np.nan)
    R, th0, sw = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    k = pair[li]
    p, d = seg.p0[k], seg.p1[k] - seg.p0[k]
    p0[li], p1[li] = p + u0[li, None] * d, p + u1[li, None] * d
    k = pair[ai]
    centre[ai], R[ai] = seg.c[k], seg.R[k]
    th0[ai], sw[ai] = seg.th[k] + seg.sw[k] * u0[ai], seg.sw[k] * (u1[ai] - u0[ai])
    for ends, th in ((p0, th0[ai]), (p1, th0[ai] + sw[ai])):
        ends[ai, 0] = centre[ai, 0] + R[ai] * np.cos(th)
        ends[ai, 1] = centre[ai, 1] + R[ai] * np.sin(th)
    length = np.empty(n)
    dl = p1[li] - p0[li]
    length[li] = math_each(math.hypot, dl[:, 0], dl[:, 1])
    length[ai] = R[ai] * np.abs(sw[ai])
    kind = np.where(line, KIND_LINE, KIND_ARC).astype(np.int8)
    return SegmentArray(kind, p0, p1, centre, R, R.copy(), th0, sw), length
