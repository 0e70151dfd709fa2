"""Graded grids: where a time-optimal speed can change along a line or an arc.

:func:`ccopt.feed.grid.gridpoints` with ``ramps`` keeps the braking-based
spacing only within the *ramp zones* at both ends of a segment (twice the
longest speed ramp the limits allow there, :func:`ramp_lengths`) and grows
the spacing geometrically in between, where the time-optimal speed is its cap
(constant on lines and arcs) and any gridding represents it exactly
(:func:`graded_grids`); curves get the same zones in their braking measure
(:func:`braking_measure`, :func:`curve_zones`), under jerk limits also around
the places inside them where the speed can leave the feed
(:func:`curve_braking`).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ccopt.feed.path import ExactPath


class Ramps(NamedTuple):
    """The limits a graded grid's ramp zones are worked out from, besides the
    axis velocity and acceleration limits (plane order): the path's
    tangential and centripetal acceleration limits (units/s^2, None: not
    set), and for a planner that also limits the jerk, the axis jerk limits
    (units/s^3, plane order; None: the profile is limited by the acceleration
    alone, as TOPPRA's)."""

    tangential_acc: float | None
    centripetal_acc: float | None
    jerk: np.ndarray | None = None

def braking_measure(sigma, S, ds, zone):
    """Part 1 of the measure ``M`` at ``sigma`` into segments of length ``S``:
    ``sigma / ds`` when ``zone`` is ``inf``; else a density ``1 / ds`` within
    ``zone`` of both ends, ``1 / (ds + (GRADE_RATIO - 1) (d - zone))`` at
    distance ``d > zone`` from the nearer end (the spacing grows by about
    :data:`GRADE_RATIO` per interval), integrated in closed form."""
    g = GRADE_RATIO - 1.0
    z = np.minimum(zone, 0.5 * S)

    def half(d):
        return np.where(d <= z, d / ds, z / ds + np.log1p(g * np.maximum(d - z, 0.0) / ds) / g)

    return np.where(sigma <= 0.5 * S, half(sigma),
                    2.0 * half(0.5 * S) - half(np.maximum(S - sigma, 0.0)))


def curve_zones(path: ExactPath, k, s, v_axis, a_axis, ramps) -> np.ndarray:
    """Ramp zone (:func:`ramp_lengths`) of every sampled curve ``k`` (indexed by
    segment), from the largest ``|q''|`` of its samples; ``inf`` without
    ``ramps`` (a :class:`Ramps`, or its first two fields) and with jerk limits
    (:func:`curve_braking` grades those curves around their critical samples)."""
    zone = np.full(path.lengths.size, np.inf)
    if ramps is None or Ramps(*ramps).jerk is not None:
        return zone
    tangential_acc, centripetal_acc = ramps[:2]
    c = np.zeros(path.lengths.size)
    np.maximum.at(c, k, path.curvature_norm(k, s))
    ks = np.unique(k)
    feed = path.feeds[ks]
    side = c[ks] * feed * feed
    a_min = float(np.min(a_axis))
    ok = _feed_is_cap(feed, side, v_axis, centripetal_acc) & (side < a_min)
    a_t = np.inf if tangential_acc is None else float(tangential_acc)
    with np.errstate(invalid="ignore"):
        zone[ks] = np.where(ok, feed * feed / np.minimum(a_min - side, a_t), np.inf)
    return zone


#: Under jerk limits, a curve's sample is *critical* where its own terms take
#: more than this share of a limit at the feed: ``|q'''| f^3`` of the axis
#: jerk, ``|q''| f^2`` of the axis acceleration (there the speed can fall
#: below the feed). Any share in (0, 1) grids correctly; a smaller one makes
#: more samples anchors (denser grids), a larger one longer ramp zones.
CRITICAL_SHARE = 0.5


def curve_braking(path: ExactPath, k, s, ds, v_axis, a_axis, ramps) -> np.ndarray:
    """Part 1 of the measure ``M`` on each piece between consecutive samples
    ``(k, s)`` of the curves (pieces across two segments: any value).

    Without jerk limits the ramp zones of :func:`curve_zones` at both ends of
    each curve (:func:`braking_measure`). With them the speed can also leave
    the feed inside a curve, where its own terms take more than
    :data:`CRITICAL_SHARE` of a limit at the feed: such samples are anchors as
    the ends are, the spacing ``ds`` is kept within the ramp zone
    (:func:`curved_ramp`, from the largest ``|q''|`` and ``|q'''|`` of the
    curve's other samples) of every anchor and grows beyond it; a curve with
    no such zone (the feed above the axis velocity share, no jerk left) stays
    even."""
    r = Ramps(*ramps)
    if r.jerk is None:
        zone = curve_zones(path, k, s, v_axis, a_axis, ramps)[k]
        F = braking_measure(s - path.offsets[k], path.lengths[k], ds[k], zone)
        return F[1:] - F[:-1]
    feed = path.feeds[k]
    c = path.curvature_norm(k, s)
    c3 = np.linalg.norm(path.eval_segments(k, s, 3), axis=1)
    j_min, a_min = float(np.min(r.jerk)), float(np.min(a_axis))
    with np.errstate(invalid="ignore"):
        # a curve run at rapid (feed inf): where |q''| or |q'''| is 0 its term
        # is NaN, not critical (no demand there), elsewhere inf, critical
        critical = ((c3 * feed ** 3 > CRITICAL_SHARE * j_min)
                    | (c * feed * feed > CRITICAL_SHARE * a_min))
    first = np.r_[True, k[1:] != k[:-1]]
    last = np.r_[k[1:] != k[:-1], True]
    anchor = critical | first | last
    # the curve's largest |q''|, |q'''| away from its critical samples
    ks = np.unique(k)
    cn, c3n = np.zeros(path.lengths.size), np.zeros(path.lengths.size)
    np.maximum.at(cn, k[~critical], c[~critical])
    np.maximum.at(c3n, k[~critical], c3[~critical])
    f = path.feeds[ks]
    a_t = np.inf if r.tangential_acc is None else float(r.tangential_acc)
    zone_k = np.full(path.lengths.size, np.inf)
    with np.errstate(invalid="ignore"):
        # a curve run at rapid (feed inf) whose every sample is critical: 0 * inf,
        # NaN, and never a cap (_feed_is_cap wants a finite feed)
        ok = _feed_is_cap(f, cn[ks] * f * f, v_axis, r.centripetal_acc)
        a_p = np.minimum(a_min - cn[ks] * f * f, a_t)
        zone_k[ks] = np.where(ok, curved_ramp(f, cn[ks], c3n[ks], a_p, j_min), np.inf)
    # each piece between its anchors: the last at or before its start, the
    # first at or after its end (a curve's ends are anchors: never another curve's)
    idx = np.arange(k.size)
    lo = np.maximum.accumulate(np.where(anchor, idx, 0))[:-1]
    hi = np.minimum.accumulate(np.where(anchor, idx, k.size - 1)[::-1])[::-1][1:]
    length = s[hi] - s[lo]
    zone = zone_k[k[:-1]]
    dsk = ds[k[:-1]]
    with np.errstate(invalid="ignore", divide="ignore"):
        out = (braking_measure(s[1:] - s[lo], length, dsk, zone)
               - braking_measure(s[:-1] - s[lo], length, dsk, zone))
    return np.where(length > 0.0, out, 0.0)


def curved_ramp(f, c, c3, a_p, j_min):
    """Twice the longest speed ramp (units) to or from the feed ``f`` on a curve
    with ``|q''| <= c`` and ``|q'''| <= c3`` (an arc: ``c3 = c^2``), under the
    tangential acceleration ``a_p`` its centripetal part leaves and the axis
    jerk limit ``j_min``; ``inf`` where no jerk is left. The axis jerk is
    ``q''' s'^3 + 3 q'' s' s'' + q' s'''``: the curve's own terms take at most
    ``c3 f^3 + 3 c f a`` at path acceleration ``a``, so with ``a`` at most
    half of what the jerk the first term leaves allows, ``(j_min - c3 f^3) /
    (6 c f)``, the path keeps a jerk of at least half that
    (:func:`scurve_ramp` under the smaller ``a`` and that jerk: a longer ramp,
    so a wider zone)."""
    f, c, c3, a_p = (np.asarray(x, float) for x in (f, c, c3, a_p))
    left = j_min - c3 * f ** 3
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.minimum(a_p, np.where(c * f > 0.0, left / (6.0 * c * f), np.inf))
        j = left - 3.0 * c * f * a
        return np.where((left > 0.0) & (a > 0.0), scurve_ramp(f, a, j), np.inf)


#: Graded grids (:func:`gridpoints` with ``ramps``): the spacing grows by this
#: factor per interval away from the end zones, where the speed is at its cap.
GRADE_RATIO = 2.0

#: Graded grids: an arc is graded only when its feed is at most this fraction of
#: the smallest axis velocity limit (an interval's velocity bound uses the
#: largest ``|q_j'|`` on it plus a small allowance, which must not bind).
GRADE_FEED_SHARE = 0.99


def _feed_is_cap(feed, side, v_axis, centripetal_acc) -> np.ndarray:
    """Where a segment's speed cap is its feed: the feed finite and within
    :data:`GRADE_FEED_SHARE` of the smallest axis velocity limit, and its
    centripetal acceleration at the feed ``side`` (units/s^2) within the
    centripetal limit (None: not set)."""
    ok = np.isfinite(feed) & (feed <= GRADE_FEED_SHARE * float(np.min(v_axis)))
    if centripetal_acc is not None:
        ok &= side <= float(centripetal_acc)
    return ok


def ramp_lengths(path: ExactPath, ks: np.ndarray, v_axis, a_axis, tangential_acc,
                 centripetal_acc, jerk=None) -> np.ndarray:
    """Twice the longest speed ramp (units) on each constant-curvature segment
    ``ks``, or ``inf`` where none is bounded.

    On a line the path speed cap is ``v_c = min(feed, min_j V_j / |q_j'|)`` and
    the path acceleration at least ``a_p = min(min_j A_j / |q_j'|, a_t)``
    everywhere on it, so from any speed the profile reaches the cap (or falls
    from it to any end speed) within ``v_c^2 / (2 a_p)``. On an arc with
    ``|q''| = c``, feed ``f <= min_j V_j`` (the feed is the cap all along it)
    and ``c f^2`` below ``min_j A_j`` (and at most the centripetal limit), the
    tangential acceleration left is at least ``a_p = min(min_j A_j - c f^2, a_t)``
    (``|q_j'' s'^2| <= c f^2`` leaves that much of every axis's limit);
    elsewhere ``inf``. No margin is kept below ``min_j A_j``: the ramp grows
    as the centripetal part takes more of the limit, and a ramp longer than
    half the segment leaves it evenly gridded (:func:`_graded`).

    With axis jerk limits ``jerk`` (plane order) the ramp is an S-curve's
    (:func:`scurve_ramp`) under that ``a_p`` and the path jerk every axis
    allows along a line, ``min_j J_j / |q_j'|``; on an arc under what the
    arc's own terms of the axis jerk leave (:func:`curved_ramp`)
    (:data:`ccopt.feed.jerk.planner.GRADED` uses these zones).
    """
    mid = path.offsets[ks] + 0.5 * path.lengths[ks]
    q1, q2 = path.eval_orders(ks, mid, (1, 2))
    q1 = np.abs(q1)
    c = np.linalg.norm(q2, axis=1)
    feed = path.feeds[ks]
    a_t = np.inf if tangential_acc is None else float(tangential_acc)
    with np.errstate(divide="ignore", invalid="ignore"):
        v_line = np.minimum(feed, np.where(q1 > 0, v_axis / q1, np.inf).min(axis=1))
        a_line = np.minimum(np.where(q1 > 0, a_axis / q1, np.inf).min(axis=1), a_t)
        a_min = float(np.min(a_axis))
        side = c * feed * feed
        arc_ok = _feed_is_cap(feed, side, v_axis, centripetal_acc) & (side < a_min)
        a_arc = np.minimum(a_min - side, a_t)
        if jerk is None:
            ramp = np.where(c == 0.0, v_line * v_line / a_line,
                            np.where(arc_ok, feed * feed / a_arc, np.inf))
        else:
            j_line = np.where(q1 > 0, np.asarray(jerk, float) / q1, np.inf).min(axis=1)
            arc = curved_ramp(feed, c, c * c, a_arc, float(np.min(jerk)))
            ramp = np.where(c == 0.0, scurve_ramp(v_line, a_line, j_line),
                            np.where(arc_ok, arc, np.inf))
    return np.where(np.isfinite(ramp) & (ramp >= 0.0), ramp, np.inf)


def scurve_ramp(v, a, j):
    """Twice the distance (units) within which a profile under path
    acceleration ``a`` and jerk ``j`` goes from any state on a segment to its
    speed cap ``v``, or from the cap to any end state: first its acceleration
    to 0, from at most ``a_max = min(a, sqrt(2 j v))`` (a larger one would
    carry the speed past ``v``, or below 0), in ``a_max / j`` seconds at most
    ``v`` fast; then the S-curve from rest to ``v``, ``v (v / a + a / j) / 2``
    where it reaches ``a`` (``v j >= a^2``), else ``v sqrt(v / j)``. Twice,
    as :func:`ramp_lengths` keeps twice the ramp; as ``j`` grows it tends to
    ``v^2 / a``, the zone without jerk limits."""
    with np.errstate(divide="ignore", invalid="ignore"):
        a_max = np.minimum(a, np.sqrt(2.0 * j * v))
        s_curve = np.where(v * j >= a * a, 0.5 * v * (v / a + a / j), v * np.sqrt(v / j))
        return 2.0 * (s_curve + v * a_max / j)


def _graded(S: float, zone: float, ds: float, h_cap: float) -> np.ndarray | None:
    """Interior gridpoints (offsets into a segment of length ``S``): spacing
    ``ds`` within ``zone`` of either end, then growing by :data:`GRADE_RATIO`
    per interval up to ``h_cap``; ``None`` when the zones cover the segment."""
    if 2.0 * zone >= S:
        return None
    m = int(np.ceil(zone / ds))
    near = ds * np.arange(1, m + 1)
    grow = [near[-1]]
    h = ds
    while True:
        h = min(h * GRADE_RATIO, h_cap)
        if grow[-1] + h >= 0.5 * S:
            break
        grow.append(grow[-1] + h)
    half = np.concatenate([near[:-1], grow])
    gap = S - 2.0 * half[-1]
    k = max(1, int(np.ceil(gap / h_cap)))
    middle = half[-1] + gap * np.arange(1, k) / k
    return np.concatenate([half, middle, S - half[::-1]])


def graded_grids(path: ExactPath, n: np.ndarray, ds: np.ndarray, v_axis, a_axis,
                  options, ramps: tuple) -> dict[int, np.ndarray]:
    """``{k: interior gridpoints}`` of the lines and arcs whose even grid is set by
    the braking spacing ``ds`` but whose speed ramps are short: they keep
    ``ds`` within twice the longest ramp (:func:`ramp_lengths`) of both ends,
    where TOPPRA's switch points can fall, and grow the spacing geometrically
    in between, where the time-optimal speed is its cap (constant on these
    segments) and any gridding represents it exactly. The turning and
    ``min_intervals`` of ``options`` (a :class:`~ccopt.feed.grid.GridOptions`) still bound
    every interval. Used only where it at least
    halves the segment's intervals."""
    out: dict[int, np.ndarray] = {}
    if options.ds is not None:
        return out
    ks = np.flatnonzero(path.constant_curvature)
    if ks.size == 0:
        return out
    zone = ramp_lengths(path, ks, v_axis, a_axis, *Ramps(*ramps))
    step = min(options.max_angle, options.max_curvature_change, options.max_curvature_bend)
    n_turn = np.maximum(np.ceil(path.uniform_turning / step), options.min_intervals)
    for j, k in enumerate(ks):
        S = float(path.lengths[k])
        if not np.isfinite(zone[j]):
            continue
        inner = _graded(S, zone[j], float(ds[k]), S / n_turn[k])
        if inner is not None and 2 * (inner.size + 1) <= n[k]:
            out[int(k)] = path.offsets[k] + inner
    return out
