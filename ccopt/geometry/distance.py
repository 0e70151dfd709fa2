"""Closed-form minimum distances between points, segments and arcs.

Every kernel is vectorised over ``N`` pairs (no Python loop over pairs) and
returns ``(d, wa, wb)``: the minimum distance ``d`` (shape ``(N,)``, program
units) and witness points ``wa`` on the first object and ``wb`` on the second
(shape ``(N, 2)``) with ``|wa - wb| = d`` up to rounding. Inputs are points of
shape ``(N, 2)`` (or ``(2,)``, broadcast) and scalars of shape ``(N,)`` (or
``()``). Arcs are ``(c, R, theta0, sweep)``: centre, radius ``> 0``, start
polar angle and signed sweep (radians, ``> 0`` counter-clockwise,
``|sweep| >= 2*pi`` is the whole circle).

Why the candidate sets are complete: the squared distance between a point
on one compact curve and a point on the other is smooth, so its minimum is
either at an end point of one curve (then it is a point-to-curve distance,
solved exactly), or at a pair interior to both where the joining vector is
normal to both curves, or at a common point (``d = 0``). Normal to a line and
radial for a circle means the circle point is ``c +- R n`` (``n`` the line's
unit normal); radial for two circles means both points lie on the line of
centres (four sign choices; concentric arcs have no such pairs, and their
minimum is at an end point). Each kernel evaluates every candidate that is
actually on both curves and keeps the smallest, so ``d`` is always a
distance between two genuine curve points (an upper bound that is exact up
to rounding).

The kernels live in :mod:`ccopt.geometry.point_distance` (a point against a
point, a segment or an arc) and :mod:`ccopt.geometry.curve_distance`
(segment-segment, segment-arc, arc-arc), on the column plumbing of
:mod:`ccopt.geometry.columns`; they are re-exported here. This module adds
:func:`distance` for two primitive objects and, for many primitives at once,
:class:`SegmentArray`, which packs lines, arcs and spirals into flat arrays,
and :func:`pair_distance`, which evaluates arbitrary index pairs with one
masked call per kind combination. Spirals have no closed form here; their
distances are bounded elsewhere (``ccopt.verify``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ccopt.geometry.columns import put_rows, take_rows
from ccopt.geometry.curve_distance import arc_arc, segment_arc, segment_segment
from ccopt.geometry.point_distance import point_arc, point_point, point_segment
from ccopt.geometry.primitives import Arc, Line, Spiral

__all__ = [
    "point_point", "point_segment", "point_arc", "segment_segment", "segment_arc",
    "arc_arc", "distance", "SegmentArray", "pair_distance",
    "KIND_LINE", "KIND_ARC", "KIND_SPIRAL",
]


# --------------------------------------------------------------------------- objects


def _is_point(obj) -> bool:
    if isinstance(obj, (Line, Arc, Spiral)):
        return False
    return np.shape(obj) == (2,)


def distance(a, b):
    """Minimum distance between two primitives: ``(d, wa, wb)`` as floats/tuples.

    ``a`` and ``b`` are :class:`Line`, :class:`Arc` or points (a pair of
    floats). ``wa`` is the witness on ``a``, ``wb`` on ``b``. Spirals have no
    closed form and raise ``ValueError``.
    """
    for obj in (a, b):
        if isinstance(obj, Spiral):
            raise ValueError("distance(): spirals are not in the closed-form set; "
                             "bound them with ccopt.verify")
        if not (isinstance(obj, (Line, Arc)) or _is_point(obj)):
            raise TypeError(f"distance() takes Line, Arc or (x, y) points, not {type(obj).__name__}")
    swap = False
    order = {Line: 1, Arc: 2}
    rank_a = 0 if _is_point(a) else order[type(a)]
    rank_b = 0 if _is_point(b) else order[type(b)]
    if rank_a > rank_b:
        a, b, swap = b, a, True
        rank_a, rank_b = rank_b, rank_a
    if rank_a == 0:
        if rank_b == 0:
            d, wa, wb = point_point(a, b)
        elif rank_b == 1:
            d, wa, wb = point_segment(a, b.p0, b.p1)
        else:
            d, wa, wb = point_arc(a, b.center, b.radius, b.theta0, b.sweep)
    elif rank_a == 1:
        if rank_b == 1:
            d, wa, wb = segment_segment(a.p0, a.p1, b.p0, b.p1)
        else:
            d, wa, wb = segment_arc(a.p0, a.p1, b.center, b.radius, b.theta0, b.sweep)
    else:
        d, wa, wb = arc_arc(a.center, a.radius, a.theta0, a.sweep,
                            b.center, b.radius, b.theta0, b.sweep)
    wa_t = (float(wa[0, 0]), float(wa[0, 1]))
    wb_t = (float(wb[0, 0]), float(wb[0, 1]))
    if swap:
        wa_t, wb_t = wb_t, wa_t
    return float(d[0]), wa_t, wb_t


# --------------------------------------------------------------------------- packed segments

KIND_LINE = 0
KIND_ARC = 1
KIND_SPIRAL = 2


@dataclass(frozen=True, eq=False)
class SegmentArray:
    """Many primitives packed into flat, read-only arrays (one row each).

    Attributes
    ----------
    kind: ``int8`` codes, :data:`KIND_LINE`, :data:`KIND_ARC` or :data:`KIND_SPIRAL`.
    p0, p1: ``(N, 2)`` start and end points (all kinds).
    center: ``(N, 2)`` centre (NaN for lines).
    radius: ``(N,)`` arc radius, or a spiral's start radius ``rho0`` (NaN for lines).
    radius_end: ``(N,)`` end radius (equal to ``radius`` for arcs, ``rho1`` for spirals).
    theta0, sweep: ``(N,)`` start polar angle and signed sweep, radians (NaN for lines).
    """

    kind: np.ndarray
    p0: np.ndarray
    p1: np.ndarray
    center: np.ndarray
    radius: np.ndarray
    radius_end: np.ndarray
    theta0: np.ndarray
    sweep: np.ndarray

    @classmethod
    def from_segments(cls, segments) -> "SegmentArray":
        segs = list(segments)
        n = len(segs)
        kind = np.empty(n, dtype=np.int8)
        p0 = np.empty((n, 2))
        p1 = np.empty((n, 2))
        center = np.full((n, 2), np.nan)
        radius = np.full(n, np.nan)
        radius_end = np.full(n, np.nan)
        theta0 = np.full(n, np.nan)
        sweep = np.full(n, np.nan)
        for i, g in enumerate(segs):
            p0[i] = g.start
            p1[i] = g.end
            if isinstance(g, Line):
                kind[i] = KIND_LINE
                continue
            if isinstance(g, Arc):
                kind[i] = KIND_ARC
                radius[i] = radius_end[i] = g.radius
            elif isinstance(g, Spiral):
                kind[i] = KIND_SPIRAL
                radius[i] = g.rho0
                radius_end[i] = g.rho1
            else:
                raise TypeError(f"SegmentArray holds Line, Arc and Spiral, not {type(g).__name__}")
            center[i] = g.center
            theta0[i] = g.theta0
            sweep[i] = g.sweep
        for arr in (kind, p0, p1, center, radius, radius_end, theta0, sweep):
            arr.flags.writeable = False
        return cls(kind, p0, p1, center, radius, radius_end, theta0, sweep)

    def __len__(self) -> int:
        return int(self.kind.shape[0])

    def segment(self, i: int):
        """Row ``i`` as a primitive object again."""
        k = int(self.kind[i])
        if k == KIND_LINE:
            return Line(tuple(self.p0[i]), tuple(self.p1[i]))
        if k == KIND_ARC:
            return Arc(tuple(self.center[i]), self.radius[i], self.theta0[i], self.sweep[i])
        return Spiral(tuple(self.center[i]), self.radius[i], self.radius_end[i],
                      self.theta0[i], self.sweep[i])


@dataclass(frozen=True, eq=False)
class SegmentRows:
    """Rows ``idx`` of a :class:`SegmentArray` of lines and arcs as columns:
    ``line`` (True for a line, else an arc), end points ``p0``, ``p1``
    ``(M, 2)``, and the arc's centre ``c`` ``(M, 2)``, radius ``R``, start
    angle ``th`` and signed sweep ``sw`` (radians; NaN for lines)."""

    line: np.ndarray
    p0: np.ndarray
    p1: np.ndarray
    c: np.ndarray
    R: np.ndarray
    th: np.ndarray
    sw: np.ndarray

    @staticmethod
    def columns(S: SegmentArray, idx) -> tuple:
        """The fields of rows ``idx`` of ``S``, in the order of the class's."""
        return (S.kind[idx] == KIND_LINE, S.p0[idx], S.p1[idx], S.center[idx], S.radius[idx],
                S.theta0[idx], S.sweep[idx])

    @classmethod
    def take(cls, S: SegmentArray, idx) -> "SegmentRows":
        return cls(*cls.columns(S, idx))

    def finite_center(self) -> np.ndarray:
        """Centres with the NaN of line rows replaced by 0 (mask those rows out)."""
        return np.where(np.isfinite(self.c), self.c, 0.0)


def pair_distance(A: SegmentArray, idx_a, B: SegmentArray, idx_b):
    """Distances between rows ``A[idx_a[k]]`` and ``B[idx_b[k]]`` for every ``k``.

    Returns ``(d, wa, wb)`` of shapes ``(N,)``, ``(N, 2)``, ``(N, 2)`` (``wa``
    on the ``A`` row, ``wb`` on the ``B`` row). Dispatches each kind
    combination (line-line, line-arc, arc-line, arc-arc) with a boolean mask
    to the vectorised kernel. ``ValueError`` if any referenced row is a spiral.
    """
    ia = np.asarray(idx_a, dtype=np.intp).ravel()
    ib = np.asarray(idx_b, dtype=np.intp).ravel()
    if ia.shape != ib.shape:
        raise ValueError(f"idx_a and idx_b differ in length ({ia.size} vs {ib.size})")
    ka = A.kind[ia]
    kb = B.kind[ib]
    spiral = (ka == KIND_SPIRAL) | (kb == KIND_SPIRAL)
    if spiral.any():
        k = int(np.argmax(spiral))
        raise ValueError(
            f"pair_distance: {int(spiral.sum())} pair(s) involve a spiral (first: pair {k}, "
            f"A row {int(ia[k])}, B row {int(ib[k])}); spirals have no closed-form distance")
    n = ia.size
    if n == 0:
        return np.empty(0), np.empty((0, 2)), np.empty((0, 2))
    d = np.empty(n)
    wa = np.empty((n, 2))
    wb = np.empty((n, 2))
    a_line = ka == KIND_LINE
    b_line = kb == KIND_LINE
    for mask, case in ((a_line & b_line, "ll"), (a_line & ~b_line, "la"),
                       (~a_line & b_line, "al"), (~a_line & ~b_line, "aa")):
        if mask.all():
            sel = slice(None)
            ja, jb = ia, ib
        else:
            sel = np.nonzero(mask)[0]
            if sel.size == 0:
                continue
            ja, jb = ia[sel], ib[sel]
        # rows of the (n, 2) point arrays by take: numpy's fancy indexing of
        # a narrow 2-D array is several times slower for the same values
        if case == "ll":
            r = segment_segment(take_rows(A.p0, ja), take_rows(A.p1, ja), take_rows(B.p0, jb),
                                take_rows(B.p1, jb))
        elif case == "la":
            r = segment_arc(take_rows(A.p0, ja), take_rows(A.p1, ja), take_rows(B.center, jb),
                            B.radius[jb], B.theta0[jb], B.sweep[jb])
        elif case == "al":
            dd, w_line, w_arc = segment_arc(take_rows(B.p0, jb), take_rows(B.p1, jb),
                                            take_rows(A.center, ja), A.radius[ja],
                                            A.theta0[ja], A.sweep[ja])
            r = (dd, w_arc, w_line)
        else:
            r = arc_arc(take_rows(A.center, ja), A.radius[ja], A.theta0[ja], A.sweep[ja],
                        take_rows(B.center, jb), B.radius[jb], B.theta0[jb], B.sweep[jb])
        if isinstance(sel, slice):
            d[sel], wa[sel], wb[sel] = r
        else:
            d[sel] = r[0]
            put_rows(wa, sel, r[1])
            put_rows(wb, sel, r[2])
    return d, wa, wb
