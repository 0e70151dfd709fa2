"""Open ends of the clearance check, for many pairs at once.

For a (tool segment, contour element) pair whose element has an open end
(:data:`ccopt.verify.decisions.OPEN_END_EXEMPTION`) the tool segment is cut at
the element's end regions (:mod:`ccopt.verify.end_clip`); the pieces outside
them count by their exact distance to the element, and the pieces inside the
region of each open end by their tapered distance to that end
(:data:`ccopt.verify.decisions.OPEN_END_TAPER`): ``|q - P| + s`` for a tool
point ``q`` past the end ``P`` by ``s``, exact for a line piece, bracketed
within :data:`TAPER_ARC_TOL` from below by branch and bound for an arc piece.

Per pair this is :func:`~ccopt.verify.clearance.clipped_distance` and
:func:`~ccopt.verify.clearance.tapered_pair`, done for every pair in numpy
columns with the same arithmetic in the same order (each dot product as
numpy's ``@`` gives it there, :func:`~ccopt.verify.end_clip.row_dot` or
:func:`~ccopt.verify.end_clip.matrix_row_dot`; ``math.hypot``, ``math.cos``
and ``math.sin`` as :mod:`math` gives them), so every figure is the same to
the last bit. Lengths are program units, angles radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import KIND_LINE, pair_distance
from ccopt.geometry.columns import math_each
from ccopt.verify.end_clip import (
    BOUNDARY_REL, EndPlanes, ToolRows, matrix_row_dot, piece_rows, region_pieces, row_dot,
)
from ccopt.verify.segments import Packed

#: Units of clearance given up per unit past an open end
#: (:data:`ccopt.verify.decisions.OPEN_END_TAPER`).
OPEN_END_TAPER_SLOPE = 1.0

#: The tapered distance of an arc piece is bracketed to within this (program
#: units) from below: far under any eps the verifier is run with.
TAPER_ARC_TOL = 1e-10
#: The branch and bound starts from this many equal parts of an arc piece ...
TAPER_ARC_PIECES = 16
#: ... and halves the parts still in question at most this many times.
TAPER_ARC_ROUNDS = 60


@dataclass(frozen=True, eq=False)
class OpenEndDistances:
    """Per pair: ``d``, ``wt``, ``we``: the exact distance of the part of the
    tool segment outside the end regions (``inf``, witnesses NaN, when none
    is left); ``f``, ``wf``: the smallest tapered distance of its parts
    inside them (``inf``, NaN when none) and its tool point; ``end``: the
    end point it is tapered to. Only for the pairs ``done``: the element has
    an end region (not a point, not a full circle) and the tool segment a
    positive length (a tool point is left to the scalar code)."""

    done: np.ndarray
    d: np.ndarray
    wt: np.ndarray
    we: np.ndarray
    f: np.ndarray
    wf: np.ndarray
    end: np.ndarray


def open_end_distances(tool: Packed, E: Packed, si: np.ndarray, ej: np.ndarray,
                       start: np.ndarray, end: np.ndarray, side: np.ndarray) -> OpenEndDistances:
    """:class:`OpenEndDistances` of tool segments ``si`` (lines and arcs)
    against elements ``ej`` (lines and arcs) whose start
    (``start``) or end (``end``) is open (per pair), ``side``: the element's
    side of compensation (+1 left, -1 right)."""
    seg = ToolRows.take(tool, si)
    planes = EndPlanes.of(E, ej, start, end)
    m = si.size
    outside, *inside = region_pieces(seg, planes, (None, 0, 1))
    pair, u0, u1 = outside
    pieces, _ = piece_rows(seg, pair, u0, u1)
    dp, wtp, wep = pair_distance(pieces, np.arange(pair.size), E.arr, ej[pair])
    d, wt, we = np.full(m, np.inf), np.full((m, 2), np.nan), np.full((m, 2), np.nan)
    k = _first_smallest(pair, dp)
    d[pair[k]], wt[pair[k]], we[pair[k]] = dp[k], wtp[k], wep[k]
    # the parts inside each open end's region, region by region
    region = np.repeat([0, 1], [inside[0][0].size, inside[1][0].size])
    pair, u0, u1 = (np.concatenate((x, y)) for x, y in zip(*inside))
    order = np.argsort(pair, kind="stable")
    pair, u0, u1, region = pair[order], u0[order], u1[order], region[order]
    point, past, tool_side = _end_tapers(E, ej[pair], region, side[pair])
    fp, wp = _tapered_pieces(seg, pair, u0, u1, point, past, tool_side)
    f, wf, at = np.full(m, np.inf), np.full((m, 2), np.nan), np.full((m, 2), np.nan)
    k = _first_smallest(pair, fp)
    f[pair[k]], wf[pair[k]], at[pair[k]] = fp[k], wp[k], point[k]
    done = planes.used.any(axis=1) & (seg.length > 0.0)
    return OpenEndDistances(done, d, wt, we, f, wf, at)


def _first_smallest(group: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Index of the first smallest value below ``inf`` of each run of equal
    ``group`` (sorted) in ``v``, NaN never (a running minimum started at
    ``inf`` and replaced by a smaller value); runs with none have none."""
    if not v.size:
        return np.zeros(0, np.intp)
    starts = np.flatnonzero(np.r_[True, group[1:] != group[:-1]])
    run = np.repeat(np.arange(starts.size), np.diff(np.r_[starts, v.size]))
    low = np.fmin.reduceat(v, starts)
    cand = np.flatnonzero((v == low[run]) & (v < np.inf))
    return cand[np.r_[True, run[cand[1:]] != run[cand[:-1]]]] if cand.size else cand


def _end_tapers(E: Packed, ej: np.ndarray, region: np.ndarray, side: np.ndarray):
    """``(point, past, tool_side)`` ``(M, 2)`` each of the end ``region`` (0 the
    start, 1 the end) of elements ``ej``
    (:class:`~ccopt.verify.clearance.EndTaper`)."""
    A = E.arr
    line = A.kind[ej] == KIND_LINE
    li, ai = np.flatnonzero(line), np.flatnonzero(~line)
    t, point = np.empty((ej.size, 2)), np.empty((ej.size, 2))
    p0, p1 = A.p0[ej[li]], A.p1[ej[li]]
    dd = p1 - p0
    t[li] = dd / math_each(math.hypot, dd[:, 0], dd[:, 1])[:, None]
    point[li] = np.where((region[li] == 0)[:, None], p0, p1)
    k = ej[ai]
    sw = A.sweep[k]
    th = A.theta0[k] + np.where(region[ai] == 0, 0.0, sw)
    sg = np.copysign(1.0, sw)
    cos, sin = math_each(math.cos, th), math_each(math.sin, th)
    t[ai] = np.stack((-sg * sin, sg * cos), axis=1)
    point[ai] = A.center[k] + A.radius[k][:, None] * np.stack((cos, sin), axis=1)
    left = np.stack((-t[:, 1], t[:, 0]), axis=1)
    past = np.where((region == 0)[:, None], -t, t)
    return point, past, side[:, None] * left


def _tapered_pieces(seg: ToolRows, pair, u0, u1, point, past, tool_side):
    """``(f, witness)`` of each piece ``u0..u1`` of the segments ``pair``
    (:func:`~ccopt.verify.clearance.tapered_distance`; ``inf``, NaN for a
    line piece along the end's normal on the tool side)."""
    line = seg.line[pair]
    f, w = np.full(pair.size, np.inf), np.full((pair.size, 2), np.nan)
    li, ai = np.flatnonzero(line), np.flatnonzero(~line)
    k = pair[li]
    p, dd = seg.p0[k], seg.p1[k] - seg.p0[k]
    a, b = p + u0[li, None] * dd, p + u1[li, None] * dd
    tapered = ~_on_end_normal(a, b, point[li], past[li], tool_side[li])
    li = li[tapered]
    if li.size:
        f[li], w[li] = _tapered_lines(a[tapered], b[tapered], point[li], past[li])
    if ai.size:
        k = pair[ai]
        arcs = (seg.c[k], seg.R[k], seg.th[k] + seg.sw[k] * u0[ai], seg.sw[k] * (u1[ai] - u0[ai]))
        f[ai], w[ai] = _tapered_arcs(*arcs, point[ai], past[ai])
    return f, w


def _on_end_normal(a, b, point, past, tool_side) -> np.ndarray:
    """Line pieces ``a..b`` running along the end's normal on the tool side
    (:func:`~ccopt.verify.clearance._on_end_normal`)."""
    slack = BOUNDARY_REL * (1.0 + np.abs(a).max(axis=1) + np.abs(b).max(axis=1))
    wa, wb = a - point, b - point
    return ((np.abs(matrix_row_dot(wa, past)) <= slack)
            & (np.abs(matrix_row_dot(wb, past)) <= slack)
            & (matrix_row_dot(wa, tool_side) >= -slack)
            & (matrix_row_dot(wb, tool_side) >= -slack))


def _taper_f(q, point, past, rows: int) -> np.ndarray:
    """``|q - P| + slope s`` of points ``q``, each evaluated among ``rows``
    points at once by the scalar code (its dot product as ``@`` gives it)."""
    w = q - point
    dot = row_dot if rows == 1 else matrix_row_dot
    return np.hypot(w[:, 0], w[:, 1]) + OPEN_END_TAPER_SLOPE * dot(w, past)


def _tapered_lines(a, b, point, past):
    """``(f, witness)`` of line pieces ``a..b`` (:func:`~ccopt.verify.clearance._tapered_line`):
    the smallest of the function at both ends and at its stationary point."""
    d = b - a
    L = math_each(math.hypot, d[:, 0], d[:, 1])
    f, w = np.empty(L.size), np.empty((L.size, 2))
    z = np.flatnonzero(L == 0.0)
    f[z], w[z] = _taper_f(a[z], point[z], past[z], 1), a[z]
    k = np.flatnonzero(L > 0.0)
    a, d, L, point, past = a[k], d[k], L[k], point[k], past[k]
    e = d / L[:, None]
    w0 = a - point
    p = row_dot(w0, e)
    r = w0 - p[:, None] * e
    m = math_each(math.hypot, r[:, 0], r[:, 1])
    c = -OPEN_END_TAPER_SLOPE * row_dot(past, e)
    stationary = np.abs(c) < 1.0
    with np.errstate(invalid="ignore", divide="ignore"):
        s = c * m / np.sqrt(1.0 - c * c) - p
    s = np.where(0.0 > s, 0.0, s)           # max(s, 0.0) ...
    s = np.where(L < s, L, s)               # ... then min(s, L), as Python's
    cands = np.stack((np.zeros(L.size), L, s), axis=1) / L[:, None]
    pts = a[:, None, :] + cands[:, :, None] * d[:, None, :]
    fc = np.full((L.size, 3), np.inf)
    for j in range(3):
        on = stationary if j == 2 else np.ones(L.size, bool)
        fc[on, j] = _taper_f(pts[on, j], point[on], past[on], 2)
    j = np.argmin(fc, axis=1)
    f[k], w[k] = fc[np.arange(L.size), j], pts[np.arange(L.size), j]
    return f, w


def _tapered_arcs(c, R, theta0, sweep, point, past):
    """``(f, witness)`` of arc pieces (:func:`~ccopt.verify.clearance._tapered_arc`):
    the branch and bound of every piece at once, round by round. The parts in
    question are kept in one list, the kept ones then the halves made of
    them, as the scalar code keeps each piece's: each piece's parts in its
    order (so its first smallest is the scalar code's)."""
    m = R.size
    half_lip = 0.5 * (1.0 + OPEN_END_TAPER_SLOPE) * R * np.abs(sweep)
    arc = _ArcTaper(np.column_stack((theta0, sweep, c, R, point, past)))
    u = np.linspace(0.0, 1.0, TAPER_ARC_PIECES + 1)
    own = np.repeat(np.arange(m), TAPER_ARC_PIECES)
    fu = arc.f(np.tile(u, m), np.repeat(np.arange(m), u.size)).reshape(m, u.size)
    a, b = np.tile(u[:-1], m), np.tile(u[1:], m)
    fa, fb = fu[:, :-1].ravel(), fu[:, 1:].ravel()
    best, wit, lb_out = np.full(m, np.inf), np.full((m, 2), np.nan), np.full(m, np.inf)
    for rnd in range(TAPER_ARC_ROUNDS):
        fa_min, fb_min = _smallest(fa, own, m), _smallest(fb, own, m)
        low = np.where(fb_min < fa_min, fb_min, fa_min)
        better = np.flatnonzero(low < best)
        if better.size:
            # the first smallest of the starts, then of the ends
            from_a = (fa_min <= fb_min)[better]
            ka, kb = _first_at(fa, fa_min, own, m)[better], _first_at(fb, fb_min, own, m)[better]
            best[better] = low[better]
            wit[better] = arc.point(np.where(from_a, a[ka], b[kb]), better)
        lb = 0.5 * (fa + fb) - half_lip[own] * (b - a)
        keep = lb < (best - TAPER_ARC_TOL)[own]
        if rnd == TAPER_ARC_ROUNDS - 1:
            left = np.bincount(own[keep], minlength=m) > 0
            kept_min = _smallest(lb[keep], own[keep], m)
            lb_out[left] = kept_min[left]
            break
        a, b, fa, fb, own = a[keep], b[keep], fa[keep], fb[keep], own[keep]
        if not own.size:
            break
        mid = 0.5 * (a + b)
        f_mid = arc.f(mid, own)
        a, b = np.concatenate((a, mid)), np.concatenate((mid, b))
        fa, fb = np.concatenate((fa, f_mid)), np.concatenate((f_mid, fb))
        own = np.concatenate((own, own))
    return np.where(lb_out < best, lb_out, best), wit


@dataclass(frozen=True, eq=False)
class _ArcTaper:
    """Per arc piece: ``theta0, sweep, cx, cy, R, Px, Py, past_x, past_y``
    (``(m, 9)``): its points and their tapered distance
    (:func:`~ccopt.verify.clearance._tapered_arc`'s ``at`` and ``_taper_f``)."""

    rows: np.ndarray

    def point(self, u: np.ndarray, own: np.ndarray) -> np.ndarray:
        """The points at fractions ``u`` of pieces ``own``."""
        g = self.rows[own]
        th = g[:, 0] + g[:, 1] * u
        return g[:, 2:4] + g[:, 4:5] * np.stack((np.cos(th), np.sin(th)), axis=1)

    def f(self, u: np.ndarray, own: np.ndarray) -> np.ndarray:
        """The tapered distance at fractions ``u`` of pieces ``own`` (each
        among many points, as the scalar code evaluates them)."""
        g = self.rows[own]
        th = g[:, 0] + g[:, 1] * u
        q = g[:, 2:4] + g[:, 4:5] * np.stack((np.cos(th), np.sin(th)), axis=1)
        return _taper_f(q, g[:, 5:7], g[:, 7:9], 2)


def _smallest(v: np.ndarray, own: np.ndarray, m: int) -> np.ndarray:
    """Per piece ``0..m-1``: the smallest of its values ``v`` (``own``: each
    value's piece; NaN if one is NaN, as :meth:`numpy.ndarray.min`; ``inf``
    for a piece with none)."""
    out = np.full(m, np.inf)
    np.minimum.at(out, own, v)
    return out


def _first_at(v: np.ndarray, low: np.ndarray, own: np.ndarray, m: int) -> np.ndarray:
    """Per piece, the index of its first value equal to its ``low`` (its first
    NaN where ``low`` is NaN), as :func:`numpy.argmin` of its values in order."""
    hit = np.flatnonzero((v == low[own]) | (np.isnan(v) & np.isnan(low[own])))
    out = np.full(m, v.size)
    np.minimum.at(out, own[hit], hit)
    return out
