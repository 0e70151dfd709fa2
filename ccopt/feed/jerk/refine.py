"""Where the ``jerk`` planner's grid is too coarse: the axis jerk inside curved intervals.

The LP (:mod:`ccopt.feed.jerk.lp`) imposes the axis jerk at the gridpoints
(and at three inner points of intervals whose curvature changes). Between
them the profile is known exactly (an ``SLINEAR`` interval: ``alpha``
linear in ``s``, ``b`` quadratic), and on a curved interval its axis jerk

    j_i = q_i' s' alpha' + 3 q_i'' s' alpha + q_i''' s'^3,   s' = sqrt(b)

is a sum of terms that change along the interval (``q'`` and ``q''`` turn,
``b`` and ``alpha`` move) and can cancel at both ends but not between them.
On the corner arcs of bench/feed.py's pocket (radius 0.5 mm, jerk 20,000
mm/s^3) the speed dipped to 0.4 mm/s inside the arc and wiggled from one
gridpoint to the next, and the jerk between them reached 1.098 of the limit
with every gridpoint within it. :func:`jerk_over_inside` finds such
intervals from the LP's own ``(b, alpha)``; the planner splits them
(:func:`ccopt.feed.jerk.planner.plan_jerk`) and :func:`replan_locally`
plans a window around them again, its ends held at the last plan's state
(the profile between stops depends on all of it, so a window is the
planner's own approximation, as its overlapping windows are; planning the
whole stretch again instead gave bench/feed.py's 1,000-block pocket a 0.6 %
shorter cycle for 50 % more CPU).

Straight intervals are not checked here: their only inner excess, the
speed's peak where ``alpha`` changes sign, is bounded in the LP itself
(:meth:`~ccopt.feed.jerk.lp.WindowLP.peaks_over`); nor are the constant-jerk
pieces at stops (their jerk is constant in time by construction).
"""
from __future__ import annotations

import numpy as np

from ccopt.feed.jerk.lp import SLINEAR, JerkGrid, WindowLP
from ccopt.feed.jerk.windows import cover_peaks, threads
from ccopt.feed.path import ExactPath
from ccopt.verify.limits import LIMITS_TOL
from ccopt.workers import map_in_threads

#: Fractions of an interval where the axis jerk is checked.
CHECK_POINTS = np.arange(1, 8) / 8.0
#: Relative excess over the jerk limit that splits an interval: a tenth of the
#: certificate's tolerance (:data:`ccopt.verify.limits.LIMITS_TOL`), the rest
#: left for what lies between the checked points.
REFINE_TOL = LIMITS_TOL / 10.0
#: Refinement passes at most, and the most pieces one pass splits an interval
#: into: the excess over the limit falls with the square of the spacing, so an
#: interval goes into ``sqrt(excess / REFINE_TOL)`` pieces, 2 to MAX_SPLIT.
MAX_PASSES = 4
MAX_SPLIT = 16


def jerk_over_inside(path: ExactPath, g: JerkGrid, b: np.ndarray, alpha: np.ndarray,
                     j: np.ndarray, where: np.ndarray | None = None
                     ) -> tuple[np.ndarray, np.ndarray]:
    """``(over, excess)``, both ``(N,)``: the ``SLINEAR`` intervals of ``g`` on
    curved geometry whose axis jerk at :data:`CHECK_POINTS` exceeds ``j``
    (axis limits, plane order) by more than :data:`REFINE_TOL`, and each
    interval's largest relative excess there (0 where not checked), for the
    profile ``b`` (units^2/s^2) and ``alpha`` (units/s^2) at the gridpoints
    (NaN where no LP planned); ``where``: ``(N,)``, the intervals to check
    (default all; the others count as within the limit)."""
    b0, b1 = b[:-1], b[1:]
    curved = np.any((g.q2[1, :-1] != 0.0) | (g.q2[0, 1:] != 0.0), axis=1)
    use = (g.kind == SLINEAR) & curved & np.isfinite(b0) & np.isfinite(b1)
    if g.lone is not None:
        use &= ~g.lone
    if where is not None:
        use &= where
    k = np.flatnonzero(use)
    excess = np.zeros(g.kind.size)
    if k.size == 0:
        return excess > REFINE_TOL, excess
    h = g.s[k + 1] - g.s[k]
    a0, a1 = alpha[k], alpha[k + 1]
    c = (a1 - a0) / h                                        # alpha' (1/s^2)
    x = CHECK_POINTS[None, :] * h[:, None]                   # (K, P)
    bx = np.maximum(b0[k][:, None] + 2.0 * a0[:, None] * x + c[:, None] * x * x, 0.0)
    ax = a0[:, None] + c[:, None] * x
    v = np.sqrt(bx)
    s = g.s[k][:, None] + x
    seg = np.repeat(path.locate(0.5 * (g.s[k] + g.s[k + 1])), CHECK_POINTS.size)
    q1, q2, q3 = (q.reshape(*s.shape, -1) for q in path.eval_orders(seg, s.ravel(), (1, 2, 3)))
    jerk = (q1 * (v * c[:, None])[..., None] + 3.0 * q2 * (v * ax)[..., None]
            + q3 * (v * bx)[..., None])
    ratio = np.abs(jerk) / np.asarray(j, float)
    excess[k] = np.maximum(np.max(ratio, axis=(1, 2)) - 1.0, 0.0)
    return excess > REFINE_TOL, excess



def split_points(s: np.ndarray, over: np.ndarray, excess: np.ndarray) -> np.ndarray:
    """The gridpoints that split the intervals ``over`` of the gridpoints ``s``
    (:func:`jerk_over_inside`): each into ``sqrt(excess / REFINE_TOL)`` equal
    pieces, 2 to :data:`MAX_SPLIT` (the excess falls with the square of the
    spacing)."""
    k = np.flatnonzero(over)
    m = np.clip(np.ceil(np.sqrt(excess[k] / REFINE_TOL)), 2, MAX_SPLIT).astype(int)
    frac = np.concatenate([np.arange(1, n) / n for n in m]) if k.size else np.zeros(0)
    at = np.repeat(k, m - 1)
    return s[at] + frac * (s[at + 1] - s[at])

#: Gridpoints a local re-plan reaches beyond the intervals it refines, on each
#: side (up to the stops; doubled while its LP is infeasible, see
#: :func:`replan_locally`).
LOCAL_MARGIN = 40


def profile_at(s_old: np.ndarray, b_old: np.ndarray, alpha_old: np.ndarray,
               s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(b, alpha)`` of the profile planned on gridpoints ``s_old`` at the
    gridpoints ``s`` (a superset), exactly: inside an ``SLINEAR`` interval
    ``alpha`` is linear in ``s`` and ``b`` quadratic (points are only ever
    added inside such intervals)."""
    k = np.clip(np.searchsorted(s_old, s, side="right") - 1, 0, s_old.size - 2)
    h = s_old[k + 1] - s_old[k]
    x = s - s_old[k]
    a0, a1 = alpha_old[k], alpha_old[k + 1]
    c = (a1 - a0) / h
    b = np.maximum(b_old[k] + 2.0 * a0 * x + c * x * x, 0.0)
    alpha = a0 + c * x
    on = s_old[k] == s                                   # the old gridpoints as they were
    b[on], alpha[on] = b_old[k[on]], alpha_old[k[on]]
    last = s == s_old[-1]
    b[last], alpha[last] = b_old[-1], alpha_old[-1]
    return b, alpha


def replan_locally(g: JerkGrid, b: np.ndarray, alpha: np.ndarray, new: np.ndarray,
                   scale: float) -> tuple[np.ndarray, np.ndarray, list[tuple[int, int]],
                                          list[tuple[int, int]]]:
    """The profile ``(b, alpha)`` on the refined grid ``g`` (the last plan
    there, :func:`profile_at`) planned again around the ``new`` gridpoints:
    a window of :data:`LOCAL_MARGIN` gridpoints beyond them on each side
    (clipped at stops), its ends held at the last plan's state, one LP with
    that plan's speed as the bound (``b <= bhat = b_last``: the jerk rows exact
    at every gridpoint, and never faster than the last plan there). The
    pseudo-jerk rounds from that speed instead
    (:func:`~ccopt.feed.jerk.windows.solve_rounds`) wander: they planned
    bench/feed.py's 1,000-block pocket 0.3 % faster but its 100-block one
    2.9 % slower (a stretch then fell back to the S-curve). Returns ``(b, alpha,
    failed, replanned)``: ``failed`` the stretches ``(lo, hi)`` (stop to stop)
    whose window stayed infeasible up to its stops, for the caller to plan
    whole; ``replanned`` the windows ``(lo, hi)`` planned again (gridpoints)."""
    b, alpha = b.copy(), alpha.copy()
    stops = np.flatnonzero(g.stop)
    at = np.searchsorted(g.s, new)
    groups: dict[tuple[int, int], list] = {}
    for span in _spans(at, stops):
        groups.setdefault(span[:2], []).append(span)
    # stretches are independent (a window never reaches past its stretch's
    # stops, where b and alpha are 0): each stretch's spans in turn, the
    # stretches in threads (each writes only its own part of b and alpha)
    tasks = list(groups.values())
    done = map_in_threads(lambda spans: _replan_stretch(g, b, alpha, spans, scale), tasks,
                     threads(len(tasks)))
    failed = [f for fs, _ in done for f in fs]
    replanned = [r for _, rs in done for r in rs]
    return b, alpha, failed, replanned


def _replan_stretch(g: JerkGrid, b: np.ndarray, alpha: np.ndarray, spans, scale: float):
    """:func:`replan_locally` of the ``spans`` of one stretch, in turn, ``b``
    and ``alpha`` changed in place: ``(failed, replanned)``."""
    failed, replanned = [], []
    for lo_s, hi_s, i_lo, i_hi in spans:
        margin = LOCAL_MARGIN
        while True:
            lo, hi = max(lo_s, i_lo - margin), min(hi_s, i_hi + margin)
            bhat = b[lo:hi + 1] / scale
            start = None if lo == lo_s else (bhat[0], alpha[lo] / scale)
            end = None if hi == hi_s else (bhat[-1], alpha[hi] / scale)
            lp = WindowLP(g, lo, hi, bhat, start, scale, end)
            out = cover_peaks(lp, bhat, bhat, lp.solve(bhat, bhat))
            if out is not None and np.all(out[0][~g.stop[lo:hi + 1]] > 0.0):
                b[lo:hi + 1], alpha[lo:hi + 1] = out[0] * scale, out[1] * scale
                replanned.append((lo, hi))
                break
            if lo == lo_s and hi == hi_s:
                failed.append((lo_s, hi_s))
                break
            margin *= 2
    return failed, replanned


def _spans(at: np.ndarray, stops: np.ndarray) -> list[tuple[int, int, int, int]]:
    """The new gridpoints ``at`` (indices) in clusters, per stretch between
    ``stops``: ``(stretch start, stretch end, first, last)``, clusters
    closer than twice :data:`LOCAL_MARGIN` joined."""
    out: list[list[int]] = []
    which = np.searchsorted(stops, at) - 1
    for i, w in zip(at, which):
        lo_s, hi_s = int(stops[w]), int(stops[w + 1])
        if out and out[-1][0] == lo_s and i - out[-1][3] <= 2 * LOCAL_MARGIN:
            out[-1][3] = int(i)
        else:
            out.append([lo_s, hi_s, int(i) - 1, int(i)])
    return [(a, b_, max(lo, a), min(hi + 1, b_)) for a, b_, lo, hi in out]
