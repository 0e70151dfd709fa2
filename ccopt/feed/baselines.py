"""Hand-written baseline planners, to compare TOPPRA against.

Both plan one trapezoidal speed profile per segment with a constant speed cap
and a constant tangential acceleration chosen so the segment respects the
same limits everywhere along it (a block "budget"):

- on a line ``q'`` is the constant direction ``t`` and ``q'' = 0``: the
  effective limits ``v = min_i vmax_i / |t_i|``, ``a = min_i amax_i / |t_i|``
  are exact;
- on a curved segment, with ``T_i = max |q_i'|`` and ``N_i = max |q_i''|``
  over the segment (sampled every 0.01 rad of turning and at its ends),
  ``v^2 <= amax_i / (2 N_i)`` keeps the centripetal part within half of
  each axis budget, and ``a = min_i (amax_i - N_i v^2) / T_i`` leaves the
  rest for speeding up and slowing down, so ``|q_i' s'' + q_i'' s'^2| <=
  T_i a + N_i v^2 <= amax_i``;
- the programmed feed caps ``v`` (rapids: the axis limits only), and the
  optional tangential and centripetal limits cap ``a`` and ``v``.

With jerk limits ``J_i`` (``AxisLimits.j``) the stop baseline runs a
closed-form 7-phase S-curve per block instead
(:func:`ccopt.feed.jerk.scurve.scurve_rest_to_rest`), with a path jerk
budget: axis ``i``'s jerk is ``q_i''' s'^3 + 3 q_i'' s' s'' + q_i' s'''``, so
with ``M_i = max |q_i'''|`` also taken over the segment, the speed cap obeys
``M_i v^3 <= J_i / 3`` too, the acceleration ``3 N_i v a <= J_i / 3``, and the
path jerk is ``j = min_i (J_i - M_i v^3 - 3 N_i v a) / T_i`` (on a line
``min_i J_i / |t_i|``, exact).

The junction baseline under jerk limits runs the same look-ahead with
jerk-limited speed changes: per block a speed change from its start speed up
to a peak, a cruise and one down to its end speed, each with the
acceleration 0 at its ends (:func:`ccopt.feed.jerk.scurve.scurve_between`),
under the same jerk budget; its passes use the distance of such a change
(its mean speed times its duration), and a junction at a curvature break is
capped as the jerk planner caps it, ``|Delta q_i''| v^2 <= J_i ts``
(``ts`` the interpolation period, 1 ms by default).

Planners:

- :func:`plan_stop_per_block`: stop at the end of every segment (rest to rest
  trapezoid per block, or S-curve under jerk limits), the simplest controller
  behaviour;
- :func:`plan_junction`: grbl-style look-ahead: junction speeds where
  segments meet (0 at tangent breaks and dwells by default, grbl's junction
  deviation speed when ``junction_deviation`` is given, else the smaller of
  the two segment caps), then grbl's backward (deceleration) and forward
  (acceleration) passes, then one trapezoid per segment.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.feed.jerk.profile import CUBIC, JerkProfile
from ccopt.feed.jerk.scurve import (BISECTION_STEPS, integrate_phases, scurve_between,
                                    scurve_rest_to_rest, speed_change_distance)
from ccopt.feed.junction import boundary_speed_caps
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.planners import DEFAULT_TS
from ccopt.feed.profile import FeedProfile
from ccopt.geometry import Arc
from ccopt.tolerances import BUDGET_SAMPLE_ANGLE


def _budget_samples(path: ExactPath) -> tuple[np.ndarray, np.ndarray]:
    """``(segment index, s)`` of the points where each segment's budget is taken:
    its ends, every :data:`BUDGET_SAMPLE_ANGLE` of turning, and on arcs every
    polar angle that is a multiple of pi/2 (where an axis component of ``q'``
    or ``q''`` peaks), so an arc's budget is exact."""
    K = len(path.segments)
    n = np.array([max(3, math.ceil(path.turning(k) / BUDGET_SAMPLE_ANGLE) + 1)
                  for k in range(K)])
    k = np.repeat(np.arange(K), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    frac = (np.arange(k.size) - np.repeat(first, n)) / np.repeat(n - 1, n)
    s = path.offsets[k] + path.lengths[k] * frac
    extra_k, extra_s = [], []
    for i, seg in enumerate(path.segments):
        g = seg.geom
        if isinstance(g, Arc) and g.sweep != 0.0:
            lo, hi = sorted((g.theta0, g.theta0 + g.sweep))
            m = np.arange(math.ceil(lo / (0.5 * math.pi)), math.floor(hi / (0.5 * math.pi)) + 1)
            f = (m * 0.5 * math.pi - g.theta0) / g.sweep
            extra_k.extend([i] * m.size)
            extra_s.extend((path.offsets[i] + path.lengths[i] * np.clip(f, 0.0, 1.0)).tolist())
    if extra_k:
        k = np.concatenate([k, extra_k])
        s = np.concatenate([s, extra_s])
        order = np.argsort(k, kind="stable")
        k, s = k[order], s[order]
    return k, s


def segment_jerk_budgets(path: ExactPath, limits: AxisLimits):
    """``(v_cap, a_tangential, j_path)`` of each segment under jerk limits
    (units/s, units/s^2, units/s^3; see the module docstring)."""
    jlim = limits.jerk_in_plane(path.frame, path.dof)
    v, a = segment_budgets(path, limits)
    k, s = _budget_samples(path)
    starts = np.flatnonzero(np.r_[True, np.diff(k) != 0])
    T, N, M = (np.maximum.reduceat(np.abs(q), starts, axis=0)
               for q in path.eval_orders(k, s, (1, 2, 3)))
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.minimum(v, np.where(M > 0, np.cbrt(jlim / (3.0 * np.where(M > 0, M, 1.0))),
                                   np.inf).min(axis=1))
        a = np.minimum(a, np.where(N > 0, jlim / (9.0 * np.where(N > 0, N, 1.0) * v[:, None]),
                                   np.inf).min(axis=1))
        rest = jlim - M * (v ** 3)[:, None] - 3.0 * N * (v * a)[:, None]
        j = np.where(T > 0, rest / np.where(T > 0, T, 1.0), np.inf).min(axis=1)
    return v, a, j


def segment_budgets(path: ExactPath, limits: AxisLimits) -> tuple[np.ndarray, np.ndarray]:
    """``(v_cap, a_tangential)`` of each segment (units/s, units/s^2)."""
    vlim, alim = limits.in_plane(path.frame, path.dof)
    K = len(path.segments)
    k, s = _budget_samples(path)
    starts = np.flatnonzero(np.r_[True, np.diff(k) != 0])
    q1, q2 = path.eval_orders(k, s, (1, 2))
    q1 = np.abs(q1)
    T = np.maximum.reduceat(q1, starts, axis=0)             # (K, dof)
    N = np.maximum.reduceat(np.abs(q2), starts, axis=0)
    kappa = np.maximum.reduceat(np.linalg.norm(q2, axis=1), starts)
    with np.errstate(divide="ignore", invalid="ignore"):
        v2 = np.minimum(path.feeds ** 2,
                        np.where(T > 0, (vlim / np.where(T > 0, T, 1)) ** 2, np.inf).min(axis=1))
        v2 = np.minimum(v2, np.where(N > 0, alim / (2.0 * np.where(N > 0, N, 1)), np.inf)
                        .min(axis=1))
        if limits.centripetal_acc is not None:
            v2 = np.minimum(v2, np.where(kappa > 0, limits.centripetal_acc
                                         / np.where(kappa > 0, kappa, 1), np.inf))
        a = np.where(T > 0, (alim - N * v2[:, None]) / np.where(T > 0, T, 1), np.inf).min(axis=1)
    if limits.tangential_acc is not None:
        a = np.minimum(a, limits.tangential_acc)
    assert a.shape == (K,)
    return np.sqrt(v2), a


def trapezoid(length: float, v0: float, v1: float, vc: float, a: float):
    """Phases ``[(dt, distance, v_start, sdd), ...]`` of the fastest motion over
    ``length`` from speed ``v0`` to ``v1`` with ``|sdd| <= a`` and speed ``<= vc``.

    The end speeds must be reachable (``|v1^2 - v0^2| <= 2 a length``, which the
    look-ahead passes guarantee); rounding is absorbed.
    """
    v0, v1 = min(v0, vc), min(v1, vc)
    s_acc = (vc * vc - v0 * v0) / (2.0 * a)
    s_dec = (vc * vc - v1 * v1) / (2.0 * a)
    if s_acc + s_dec <= length:
        vp = vc
        cruise = length - s_acc - s_dec
    else:
        vp2 = 0.5 * (2.0 * a * length + v0 * v0 + v1 * v1)
        vp = math.sqrt(max(vp2, v0 * v0, v1 * v1))
        s_acc = max((vp * vp - v0 * v0) / (2.0 * a), 0.0)
        s_dec = max(length - s_acc, 0.0)
        cruise = 0.0
    phases = []
    if vp > v0 and s_acc > 0:
        phases.append(((vp - v0) / a, s_acc, v0, a))
    if cruise > 0:
        phases.append((cruise / vp, cruise, vp, 0.0))
    if vp > v1 and s_dec > 0:
        phases.append(((vp - v1) / a, s_dec, vp, -a))
    return phases


def _trapezoid_knots(path, v_cap, a_tan, v_bound):
    """Knots ``(dt, s, sd, sdd, segment)`` of one trapezoid per segment with
    boundary speeds ``v_bound``; every block end lands exactly on its offset."""
    dt, s, sd, sdd, seg = [], [0.0], [0.0], [], []
    for k in range(len(path.segments)):
        phases = trapezoid(float(path.lengths[k]), float(v_bound[k]), float(v_bound[k + 1]),
                           float(v_cap[k]), float(a_tan[k]))
        for j, (d_t, dist, v_start, acc) in enumerate(phases):
            dt.append(d_t)
            sdd.append(acc)
            seg.append(k)
            sd[-1] = v_start
            last = j == len(phases) - 1
            s.append(float(path.offsets[k + 1]) if last else s[-1] + dist)
            sd.append(max(v_start + acc * d_t, 0.0))
        sd[-1] = float(min(v_bound[k + 1], v_cap[k]))
    return dt, s, sd, sdd, seg


def _junction_speeds(path, limits, v_cap, a_tan, junction_deviation):
    """Boundary speeds after grbl's backward and forward passes."""
    _, alim = limits.in_plane(path.frame, path.dof)
    K = len(path.segments)
    vb = boundary_speed_caps(path, alim, junction_deviation)
    vb[1:-1] = np.minimum(vb[1:-1], np.minimum(v_cap[:-1], v_cap[1:]))
    L = path.lengths
    for k in range(K - 1, -1, -1):  # backward pass: can still slow down to the next junction
        vb[k] = min(vb[k], math.sqrt(vb[k + 1] ** 2 + 2.0 * a_tan[k] * L[k]))
    for k in range(K):  # forward pass: can speed up to it from the previous one
        vb[k + 1] = min(vb[k + 1], math.sqrt(vb[k] ** 2 + 2.0 * a_tan[k] * L[k]))
    return vb


def baseline_knot_positions(path: ExactPath, limits: AxisLimits,
                            junction_deviation: float | None = None,
                            budgets: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Path positions where either baseline switches between accelerating,
    cruising and braking (block ends included).

    The TOPPRA planner adds them to its gridpoints: these are the exact switch
    points of the optimum on straight moves between stops, and with them every
    baseline profile is a feasible point of TOPPRA's discretised problem, whose
    solution is the largest feasible speed at every gridpoint; so TOPPRA can
    never come out slower than a baseline (but for toppra's ``1e-8`` margin on
    squared speeds). ``budgets``: the result of
    :func:`segment_budgets`, if already at hand.
    """
    if not path.segments:
        return np.zeros(0)
    v_cap, a_tan = segment_budgets(path, limits) if budgets is None else budgets
    _, s_stop, _, _, _ = _trapezoid_knots(path, v_cap, a_tan, np.zeros(len(path.segments) + 1))
    vb = _junction_speeds(path, limits, v_cap, a_tan, junction_deviation)
    _, s_junc, _, _, _ = _trapezoid_knots(path, v_cap, a_tan, vb)
    return np.unique(np.concatenate([s_stop, s_junc]))


def plan_stop_per_block(path: ExactPath, limits: AxisLimits, **_ignored) -> FeedProfile:
    """Rest-to-rest trapezoid on every segment (see the module docstring)."""
    if not path.segments:
        return FeedProfile.empty(path, limits, "stop")
    if limits.j is not None:
        return _plan_scurve_per_block(path, limits)
    v_cap, a_tan = segment_budgets(path, limits)
    knots = _trapezoid_knots(path, v_cap, a_tan, np.zeros(len(path.segments) + 1))
    return FeedProfile.from_knots(path, limits, "stop", *knots)


def plan_junction(path: ExactPath, limits: AxisLimits, *,
                  junction_deviation: float | None = None, ts: float = DEFAULT_TS,
                  **_ignored) -> FeedProfile:
    """grbl-style look-ahead with junction speeds (see the module docstring);
    jerk-limited when ``limits.j`` is given (``ts``: the interpolation period
    of the curvature-break rule, s)."""
    if not path.segments:
        return FeedProfile.empty(path, limits, "junction")
    if limits.j is not None:
        return _plan_junction_jerk(path, limits, junction_deviation, ts)
    v_cap, a_tan = segment_budgets(path, limits)
    vb = _junction_speeds(path, limits, v_cap, a_tan, junction_deviation)
    knots = _trapezoid_knots(path, v_cap, a_tan, vb)
    info = {"junction_deviation": junction_deviation if junction_deviation else 0.0}
    return FeedProfile.from_knots(path, limits, "junction", *knots, info=info)


def _plan_scurve_per_block(path: ExactPath, limits: AxisLimits) -> JerkProfile:
    """Rest-to-rest 7-phase S-curve on every segment (see the module docstring)."""
    return JerkProfile.from_pieces(path, limits, "stop", scurve_pieces(path, limits),
                                   {"jerk_limited": 1})


def scurve_pieces(path: ExactPath, limits: AxisLimits) -> dict:
    """The pieces (:meth:`JerkProfile.from_pieces`) of the S-curve per block, dwells left out."""
    v_cap, a_tan, j_path = segment_jerk_budgets(path, limits)
    rows, seg = [], []
    for k in range(len(path.segments)):
        phases = scurve_rest_to_rest(float(path.lengths[k]), float(v_cap[k]), float(a_tan[k]),
                                     float(j_path[k]))
        new = integrate_phases(float(path.offsets[k]), phases, float(path.offsets[k + 1]))
        rows.extend(new)
        seg.extend([k] * len(new))
    cols = np.array(rows, dtype=float).reshape(-1, 8).T
    pieces = dict(zip(("s0", "h", "v0", "v1", "a0", "a1", "j", "dt"), cols))
    pieces.update(kind=np.full(len(rows), CUBIC), segment=np.array(seg, dtype=int))
    return pieces


def _plan_junction_jerk(path: ExactPath, limits: AxisLimits, junction_deviation, ts: float):
    """grbl-style look-ahead under jerk limits (see the module docstring)."""
    v_cap, a_tan, j_path = segment_jerk_budgets(path, limits)
    vb = _jerk_junction_speeds(path, limits, v_cap, a_tan, j_path, junction_deviation, ts)
    rows, seg = [], []
    for k in range(len(path.segments)):
        phases = scurve_between(float(path.lengths[k]), float(vb[k]), float(vb[k + 1]),
                                float(v_cap[k]), float(a_tan[k]), float(j_path[k]))
        new = integrate_phases(float(path.offsets[k]), phases, float(path.offsets[k + 1]),
                               float(vb[k]), float(vb[k + 1]))
        rows.extend(new)
        seg.extend([k] * len(new))
    cols = np.array(rows, dtype=float).reshape(-1, 8).T
    pieces = dict(zip(("s0", "h", "v0", "v1", "a0", "a1", "j", "dt"), cols))
    pieces.update(kind=np.full(len(rows), CUBIC), segment=np.array(seg, dtype=int))
    info = {"junction_deviation": junction_deviation if junction_deviation else 0.0,
            "jerk_limited": 1, "ts": ts}
    return JerkProfile.from_pieces(path, limits, "junction", pieces, info)


def _jerk_junction_speeds(path, limits, v_cap, a_tan, j_path, junction_deviation, ts):
    """Boundary speeds of the jerk-limited look-ahead: the caps of
    :func:`_junction_speeds` and, at a curvature break, ``|Delta q_i''| v^2 <=
    J_i ts`` (the jerk planner's rule); then the backward and forward passes
    with the distance of a jerk-limited speed change
    (:func:`~ccopt.feed.jerk.scurve.speed_change_distance`)."""
    _, alim = limits.in_plane(path.toolpath.plane, path.dof)
    jlim = limits.jerk_in_plane(path.toolpath.plane, path.dof)
    vb = boundary_speed_caps(path, alim, junction_deviation)
    vb[1:-1] = np.minimum(vb[1:-1], np.minimum(v_cap[:-1], v_cap[1:]))
    K = len(path.segments)
    if K > 1:
        at = path.offsets[1:-1]
        jump = np.abs(path.eval_segments(np.arange(1, K), at, 2)
                      - path.eval_segments(np.arange(K - 1), at, 2))
        with np.errstate(divide="ignore"):
            cap = np.where(jump > 0, jlim * ts / np.where(jump > 0, jump, 1.0), np.inf).min(axis=1)
        vb[1:-1] = np.minimum(vb[1:-1], np.sqrt(cap))
    L = path.lengths

    def reach(v_from, k, bound):
        """The largest speed at most ``bound`` that changes to ``v_from`` within block k."""
        a, j = float(a_tan[k]), float(j_path[k])
        if bound <= v_from or speed_change_distance(v_from, bound, a, j) <= L[k]:
            return bound
        lo, hi = v_from, bound
        for _ in range(BISECTION_STEPS):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if speed_change_distance(v_from, mid, a, j) <= L[k] else (lo, mid)
        return lo

    for k in range(K - 1, -1, -1):  # backward pass: can still slow down to the next junction
        vb[k] = reach(float(vb[k + 1]), k, float(vb[k]))
    for k in range(K):  # forward pass: can speed up to it from the previous one
        vb[k + 1] = reach(float(vb[k]), k, float(vb[k + 1]))
    return vb
