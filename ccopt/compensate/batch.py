"""Array form of the shared corner machinery, for long runs of ordinary corners.

:mod:`.corners` is the readable reference, one corner at a time. Here the same
formulas run over all elements at once: the programmed geometry as arrays
(:class:`ElementArrays`), offset points, carrier intersections with the
nearest-root rule, and the exact tool segments between corner points. Styles
use it for the joints their rules make ordinary (same side, no gap, no
spiral) and fall back to the reference for everything else; tests require
both routes to give the same path to 1e-9.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from operator import attrgetter

import numpy as np

from ccopt.compensate import decisions
from ccopt.compensate.corners import FULL_TURN_SLACK
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import put_rows, take_rows
from ccopt.geometry.intersect_many import circles_circles, lines_circles, lines_lines
from ccopt.program.columns import triples_column
from ccopt.program.model import PLANE_AXES, Block, Motion
from ccopt.tolerances import (
    OFFSET_CIRCLE_REL_TOL, POINT_EPS, SPIRAL_RADIUS_REL_TOL, TOOL_ARC_SAME_RADIUS_REL_TOL, TURN_EPS,
)
from ccopt.toolpath import ARC_ROW, LINE_ROW, OBJECT_ROW

LINE, ARC, SPIRAL = 0, 1, 2
#: An arc whose end meets its start within this length (relative to max(1, R))
#: is a full circle: the tolerance of ``geometry.Arc.from_points``, which
#: ``toolpath.block_geometry`` builds the same moves with.
FULL_CIRCLE_GAP = 1e-9


def _perp(t: np.ndarray) -> np.ndarray:
    out = np.empty_like(t)
    out[:, 0] = -t[:, 1]
    out[:, 1] = t[:, 0]
    return out


def wrap_pi(a: np.ndarray) -> np.ndarray:
    """Angles folded into (-pi, pi] (same rule as :func:`corners.wrap_pi`)."""
    a = np.fmod(a + math.pi, TWO_PI)
    a = np.where(a <= 0.0, a + TWO_PI, a)
    return a - math.pi


_ARC_MOTIONS = frozenset((Motion.ARC_CW, Motion.ARC_CCW))
_RAPID = frozenset((Motion.RAPID,))


@dataclass
class ElementArrays:
    """Programmed in-plane moves as arrays (plane coordinates).

    kind: LINE/ARC/SPIRAL; S, E: start/end points; C: centre (nan for lines);
    R: start radius; sgn: +1 counter-clockwise, -1 clockwise, 0 line;
    theta0, sweep: programmed start angle and signed sweep; ts, te: unit
    tangents at start and end; k, r: side and radius in force; w0, w1:
    out-of-plane coordinate at start and end; rapid: the move is a rapid.
    """

    kind: np.ndarray
    S: np.ndarray
    E: np.ndarray
    C: np.ndarray
    R: np.ndarray
    sgn: np.ndarray
    theta0: np.ndarray
    sweep: np.ndarray
    ts: np.ndarray
    te: np.ndarray
    k: np.ndarray
    r: np.ndarray
    w0: np.ndarray | None = None
    w1: np.ndarray | None = None
    rapid: np.ndarray | None = None

    @classmethod
    def from_blocks(cls, blocks: list[Block], plane: str, k: np.ndarray, r: np.ndarray,
                    columns: dict | None = None):
        """The arrays of ``blocks`` in ``plane``; ``columns`` (``start``,
        ``end``, ``motions`` of these blocks, as a bulk scan read them) saves
        reading them again."""
        i, j, w = PLANE_AXES[plane]
        n = len(blocks)
        # the blocks' fields straight into arrays (fromiter over flattened
        # tuples: no per-block list or tuple-of-tuples conversion)
        if columns is None:
            st = triples_column(map(attrgetter("start"), blocks), n)
            en = triples_column(map(attrgetter("end"), blocks), n)
            motions = list(map(attrgetter("motion"), blocks))
            motion_arc = np.fromiter(map(_ARC_MOTIONS.__contains__, motions), bool, n)
            rapid = np.fromiter(map(_RAPID.__contains__, motions), bool, n)
        else:
            st, en, motions = columns["start"], columns["end"], columns["motions"]
            motion_arc, rapid = columns["arc"], columns["rapid"]
        ccw = np.zeros(n, bool)
        arcs = np.flatnonzero(motion_arc).tolist()
        if arcs:
            ccw[arcs] = [motions[q] is Motion.ARC_CCW for q in arcs]
        # centres and extra turns belong to arcs alone: read for those
        ce = np.full((n, 3), math.nan)
        turns = np.zeros(n)
        if arcs:
            nan3 = (math.nan, math.nan, math.nan)
            ce[arcs] = [nan3 if blocks[q].center is None else blocks[q].center for q in arcs]
            turns[arcs] = [blocks[q].turns for q in arcs]
        S, E, C = st[:, [i, j]], en[:, [i, j]], ce[:, [i, j]]
        # lines: their tangent; the arcs' quantities are worked out for the
        # arcs alone (a line's radius and angle are NaN, from its NaN centre)
        d = E - S
        L = np.hypot(d[:, 0], d[:, 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            ts = d / L[:, None]
        te = ts.copy()
        kind = np.full(n, LINE)
        sgn = np.zeros(n)
        R0 = np.full(n, math.nan)
        th0 = np.full(n, math.nan)
        sweep = np.zeros(n)
        if arcs:
            a = np.asarray(arcs, np.intp)
            got = _arc_geometry(take_rows(S, a), take_rows(E, a), take_rows(C, a), ccw[a],
                                turns[a])
            kind[a], sgn[a], R0[a], th0[a], sweep[a] = got[:5]
            put_rows(ts, a, got[5])
            put_rows(te, a, got[6])
        return cls(kind, S, E, C, R0, sgn, th0, sweep, ts, te,
                   np.asarray(k, float), np.asarray(r, float), st[:, w], en[:, w], rapid)

    def offset_radius(self, idx: np.ndarray, k: np.ndarray, r: np.ndarray) -> np.ndarray:
        """Offset arc radius ``R - k*r`` counter-clockwise, ``R + k*r`` clockwise."""
        return self.R[idx] - k * r * self.sgn[idx]


def _arc_geometry(S, E, C, ccw, turns):
    """``(kind, sgn, R0, theta0, sweep, ts, te)`` of arc moves from ``S`` to
    ``E`` about ``C`` (:meth:`ElementArrays.from_blocks`)."""
    R0 = np.hypot(*(S - C).T)
    R1 = np.hypot(*(E - C).T)
    # Same spiral criterion as toolpath.block_geometry.
    spiral = np.abs(R1 - R0) > SPIRAL_RADIUS_REL_TOL * np.maximum(1.0, R0)
    kind = np.where(spiral, SPIRAL, ARC)
    sgn = np.where(ccw, 1.0, -1.0)
    th0 = np.arctan2(S[:, 1] - C[:, 1], S[:, 0] - C[:, 0])
    th1 = np.arctan2(E[:, 1] - C[:, 1], E[:, 0] - C[:, 0])
    # geometry.angles.sweep_between, elementwise (full circle when the gap
    # is within FULL_CIRCLE_GAP*max(1, R) as a length).
    gap = np.fmod(np.where(ccw, th1 - th0, th0 - th1), TWO_PI)
    gap = np.where(gap < 0.0, gap + TWO_PI, gap)
    with np.errstate(invalid="ignore", divide="ignore"):
        full_if_below = FULL_CIRCLE_GAP * np.maximum(1.0, R0) / R0
    full = (gap <= full_if_below) | (TWO_PI - gap <= full_if_below) | (gap >= TWO_PI)
    gap = np.where(full, TWO_PI, gap) + TWO_PI * turns
    sweep = np.where(ccw, gap, -gap)
    th_end = th0 + sweep
    ts = sgn[:, None] * np.c_[-np.sin(th0), np.cos(th0)]
    te = sgn[:, None] * np.c_[-np.sin(th_end), np.cos(th_end)]
    return kind, sgn, R0, th0, sweep, ts, te


def nearest_corner_points(arr: ElementArrays, ia: np.ndarray, k: np.ndarray, r: np.ndarray,
                          A: np.ndarray, B: np.ndarray, te: np.ndarray, ts: np.ndarray):
    """Intersections of the offsets of elements ``ia`` and ``ia + 1`` (side
    ``k``, radius ``r``) nearest the nominal points ``A``, ``B``
    (decisions.nearest_root, vectorised); ``te``, ``ts``: the unit tangents
    where ``ia`` ends and ``ia + 1`` starts (:func:`corner_tangents`).

    Returns ``(X, found, delicate)``: ``found`` false where the carriers miss,
    ``delicate`` where the configuration is near-degenerate and the scalar
    reference must decide.
    """
    ib = ia + 1
    m = len(ia)
    X = np.full((m, 2), np.nan)
    found = np.zeros(m, bool)
    delicate = np.zeros(m, bool)
    la = arr.kind[ia] == LINE
    lb = arr.kind[ib] == LINE
    Ra = np.where(la, np.nan, arr.offset_radius(ia, k, r))
    Rb = np.where(lb, np.nan, arr.offset_radius(ib, k, r))
    Ca, Cb = take_rows(arr.C, ia), take_rows(arr.C, ib)
    for mask, fn, args in (
        (la & lb, lines_lines, (A, te, B, ts)),
        (la & ~lb, lines_circles, (A, te, Cb, Rb)),
        (~la & lb, lines_circles, (B, ts, Ca, Ra)),
        (~la & ~lb, circles_circles, (Ca, Ra, Cb, Rb)),
    ):
        sel = np.flatnonzero(mask)
        if not sel.size:
            continue
        # every corner of one kind (a path of lines): the arrays as they are
        sel = slice(None) if sel.size == m else sel
        x1, x2, n, deli = fn(*(_pick(v, sel) for v in args))
        two = np.flatnonzero(n == 2)
        if two.size:
            # of two roots, the one nearer both nominal points (costs only
            # where there are two: two lines meet once)
            a, b = _pick(A, sel)[two], _pick(B, sel)[two]
            x1t, x2t = x1[two], x2[two]
            cost1 = np.hypot(*(x1t - a).T) + np.hypot(*(x1t - b).T)
            cost2 = np.hypot(*(x2t - a).T) + np.hypot(*(x2t - b).T)
            # ties keep the first candidate, like the scalar loop (strict <)
            pick2 = two[cost2 < cost1]
            x1[pick2] = x2[pick2]
        put_rows(X, sel, x1)
        found[sel] = n > 0
        delicate[sel] = deli
    return X, found, delicate


def _pick(v: np.ndarray, sel) -> np.ndarray:
    """Rows ``sel`` (an index array or ``slice(None)``) of ``v``."""
    return v if isinstance(sel, slice) else take_rows(v, sel)


def corner_tangents(arr: ElementArrays, ia: np.ndarray):
    """``(te, ts)``: the unit tangents where elements ``ia`` end and ``ia + 1`` start."""
    return take_rows(arr.te, ia), take_rows(arr.ts, ia + 1)


def corner_turn(te: np.ndarray, ts: np.ndarray):
    """Cross ``c`` and dot ``d`` of the turn from tangents ``te`` to ``ts``
    (:func:`corner_tangents`)."""
    c = te[:, 0] * ts[:, 1] - te[:, 1] * ts[:, 0]
    d = te[:, 0] * ts[:, 0] + te[:, 1] * ts[:, 1]
    return c, d


def offset_points(arr: ElementArrays, ia: np.ndarray, k: np.ndarray, r: np.ndarray,
                  te: np.ndarray, ts: np.ndarray):
    """Nominal offset points ``A = P + r*o(t_in)`` and ``B = P + r*o(t_out)``
    at the ends ``P`` of elements ``ia`` (tangents ``te``, ``ts``: :func:`corner_tangents`)."""
    P = take_rows(arr.E, ia)
    A = P + (k * r)[:, None] * _perp(te)
    B = P + (k * r)[:, None] * _perp(ts)
    return A, B


def classify_turn(k: np.ndarray, c: np.ndarray, d: np.ndarray, eps: float = TURN_EPS):
    """Codes 0 inside, 1 outside, 2 tangent, 3 reversal (as :func:`corners.classify`)."""
    kc = k * c
    return np.where(kc > eps, 0, np.where(kc < -eps, 1, np.where(d > 0, 2, 3)))


def tool_arc_sweeps(theta0, sweep, th_s, th_e) -> np.ndarray:
    """:func:`corners.tool_arc_sweep`, elementwise (same rule, same decision)."""
    if decisions.ARC_SWEEP_CONTINUOUS:
        return sweep + wrap_pi(th_e - (theta0 + sweep)) - wrap_pi(th_s - theta0)
    ccw = sweep > 0
    gap = np.fmod(np.where(ccw, th_e - th_s, th_s - th_e), TWO_PI)
    gap = np.where(gap <= 0.0, gap + TWO_PI, gap)          # (0, 2 pi]
    extra = np.maximum(np.ceil(np.abs(sweep) / TWO_PI - FULL_TURN_SLACK) - 1.0, 0.0)
    return np.where(ccw, 1.0, -1.0) * (gap + TWO_PI * extra)


def tool_rows(arr: ElementArrays, idx: np.ndarray, starts: np.ndarray, ends: np.ndarray):
    """Exact tool geometry of line and arc elements ``idx`` between corner
    points, as :func:`corners.tool_geometry` builds it one at a time, as rows
    of a :class:`~ccopt.toolpath.SegmentColumns` (no object per segment).

    Returns ``(kind, geom, objects)``: ``kind`` and ``geom`` one row per
    element (``LINE_ROW`` ``(u0, v0, u1, v1, -)``, ``ARC_ROW`` ``(cu, cv,
    radius, theta0, sweep)``), ``objects`` position -> geometry of the
    ``OBJECT_ROW`` rows: a spiral, or ``None`` where the caller must build
    it with the reference (an arc through its own centre). Lines and arcs
    are checked finite here in bulk; a bad one is made with the checked
    constructor, which says what is wrong.
    """
    m = len(idx)
    kind = np.full(m, OBJECT_ROW, np.int8)
    geom = np.zeros((m, 5))
    objects: dict = {}
    lines = arr.kind[idx] == LINE
    at = np.flatnonzero(lines)
    s, e = take_rows(starts, idx[at]), take_rows(ends, idx[at])
    kind[at] = LINE_ROW
    if at.size == m:                            # all lines: every row, in order
        geom[:, 0:2], geom[:, 2:4] = s, e
    else:
        geom[at, 0:2], geom[at, 2:4] = s, e
    # column by column: numpy's axis-1 reduction of a narrow array is slow
    bad = ~(np.isfinite(s[:, 0]) & np.isfinite(s[:, 1]) & np.isfinite(e[:, 0])
            & np.isfinite(e[:, 1]))
    for q in np.flatnonzero(bad).tolist():
        Line((float(s[q, 0]), float(s[q, 1])), (float(e[q, 0]), float(e[q, 1])))
    q_arc = np.flatnonzero(~lines)
    if q_arc.size:
        _arc_rows(arr, idx[q_arc], starts, ends, q_arc, kind, geom, objects)
    return kind, geom, objects


def _arc_rows(arr: ElementArrays, idx, starts, ends, at, kind, geom, objects) -> None:
    """:func:`tool_rows` of arc elements ``idx``, written at positions ``at``."""
    s, e = take_rows(starts, idx), take_rows(ends, idx)
    C = take_rows(arr.C, idx)
    rs = np.hypot(*(s - C).T)
    re = np.hypot(*(e - C).T)
    th_s = np.arctan2(s[:, 1] - C[:, 1], s[:, 0] - C[:, 0])
    th_e = np.arctan2(e[:, 1] - C[:, 1], e[:, 0] - C[:, 0])
    th0, sw = arr.theta0[idx], arr.sweep[idx]
    sweep = tool_arc_sweeps(th0, sw, th_s, th_e)
    same_r = np.abs(re - rs) <= TOOL_ARC_SAME_RADIUS_REL_TOL * np.maximum(1.0, rs)
    # corners.tool_geometry: both ends on the offset circle -> exactly that arc
    on = arr.offset_radius(idx, arr.k[idx], arr.r[idx])
    tol = OFFSET_CIRCLE_REL_TOL * np.maximum(1.0, on)
    on_offset = (on > 0) & (np.abs(rs - on) <= tol) & (np.abs(re - on) <= tol)
    away = (rs > POINT_EPS) & (re > POINT_EPS)
    radius = np.where(on_offset, on, rs)
    is_arc = away & (on_offset | same_r)
    rows = np.c_[C, radius, th_s, sweep]
    fine = np.isfinite(rows).all(axis=1)
    kind[at[is_arc & fine]] = ARC_ROW
    geom[at[is_arc]] = rows[is_arc]
    for q in np.flatnonzero(is_arc & ~fine).tolist():     # says what is wrong
        Arc((float(C[q, 0]), float(C[q, 1])), float(radius[q]), float(th_s[q]), float(sweep[q]))
    for q in np.flatnonzero(~is_arc).tolist():
        objects[int(at[q])] = (Spiral((float(C[q, 0]), float(C[q, 1])), float(rs[q]),
                                      float(re[q]), float(th_s[q]), float(sweep[q]))
                               if away[q] else None)


__all__ = ["ARC", "ElementArrays", "LINE", "SPIRAL", "classify_turn", "corner_tangents",
           "corner_turn",
           "nearest_corner_points", "offset_points", "tool_rows", "wrap_pi"]
