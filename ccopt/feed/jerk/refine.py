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
intervals from the LP's own ``(b, alpha)``; the planner splits them and
plans again (:func:`ccopt.feed.jerk.planner.plan_jerk`).

Straight intervals are not checked here: their only inner excess, the
speed's peak where ``alpha`` changes sign, is bounded in the LP itself
(:meth:`~ccopt.feed.jerk.lp.WindowLP.peaks_over`); nor are the constant-jerk
pieces at stops (their jerk is constant in time by construction).
"""
from __future__ import annotations

import numpy as np

from ccopt.feed.jerk.lp import SLINEAR, JerkGrid
from ccopt.feed.path import ExactPath
from ccopt.verify.limits import LIMITS_TOL

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
                     j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(over, excess)``, both ``(N,)``: the ``SLINEAR`` intervals of ``g`` on
    curved geometry whose axis jerk at :data:`CHECK_POINTS` exceeds ``j``
    (axis limits, plane order) by more than :data:`REFINE_TOL`, and each
    interval's largest relative excess there (0 where not checked), for the
    profile ``b`` (units^2/s^2) and ``alpha`` (units/s^2) at the gridpoints
    (NaN where no LP planned)."""
    b0, b1 = b[:-1], b[1:]
    curved = np.any((g.q2[1, :-1] != 0.0) | (g.q2[0, 1:] != 0.0), axis=1)
    use = (g.kind == SLINEAR) & curved & np.isfinite(b0) & np.isfinite(b1)
    if g.lone is not None:
        use &= ~g.lone
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
    q1, q2, q3 = (path.eval_segments(seg, s.ravel(), o).reshape(*s.shape, -1) for o in (1, 2, 3))
    jerk = (q1 * (v * c[:, None])[..., None] + 3.0 * q2 * (v * ax)[..., None]
            + q3 * (v * bx)[..., None])
    ratio = np.abs(jerk) / np.asarray(j, float)
    excess[k] = np.maximum(np.max(ratio, axis=(1, 2)) - 1.0, 0.0)
    return excess > REFINE_TOL, excess
