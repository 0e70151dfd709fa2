"""The 7-phase S-curve in closed form: the fastest motion over a length under
bounds on the path speed, acceleration and jerk, from rest to rest or between
two speeds, as phases of constant path jerk.

Used by the jerk-limited baselines (:mod:`ccopt.feed.baselines`: an S-curve
per block, or per block between junction speeds), and through
:func:`ccopt.feed.baselines.scurve_pieces` by the ``jerk`` planner on a
stretch that is one straight block (:mod:`ccopt.feed.jerk.planner`); the
phases become ``CUBIC`` pieces of a :class:`~ccopt.feed.jerk.profile.JerkProfile`
(:func:`integrate_phases`).
"""
from __future__ import annotations

import math

#: Bisection steps for the peak speed of :func:`scurve_between` (2^-60 of the bracket).
BISECTION_STEPS = 60



def scurve_rest_to_rest(length: float, v: float, a: float, j: float) -> list[tuple[float, float]]:
    """Phases ``[(duration, jerk), ...]`` of the fastest motion over ``length``
    from rest to rest with ``|s'| <= v``, ``|s''| <= a``, ``|s'''| <= j``.

    The closed form: the speed ramps to its peak ``vp`` in ``Ta`` with an
    acceleration trapezoid (``vp j >= a^2``: ``Ta = vp / a + a / j``, ramp
    distance ``vp Ta / 2``) or triangle (``Ta = 2 sqrt(vp / j)``); the peak is
    ``v`` if both ramps fit in ``length``, else the largest that does:
    ``vp^2 / a + vp a / j = length`` (trapezoid) or
    ``vp = (length^2 j / 4)^(1/3)`` (triangle). Zero-length phases are left out.
    """
    if length <= 0.0:
        return []

    def ramp(vp):
        if vp * j >= a * a:
            return vp / a - a / j, a / j       # constant-acceleration time, jerk time
        return 0.0, math.sqrt(vp / j)

    def ramp_distance(vp):
        t_const, t_jerk = ramp(vp)
        return 0.5 * vp * (t_const + 2.0 * t_jerk)

    vp = v
    if 2.0 * ramp_distance(vp) > length:
        vp = 0.5 * a * (-(a / j) + math.sqrt((a / j) ** 2 + 4.0 * length / a))
        if vp * j < a * a:
            vp = (length * length * j / 4.0) ** (1.0 / 3.0)
        vp = min(vp, v)
    t_const, t_jerk = ramp(vp)
    cruise = max(length - 2.0 * ramp_distance(vp), 0.0) / vp
    phases = [(t_jerk, j), (t_const, 0.0), (t_jerk, -j), (cruise, 0.0),
              (t_jerk, -j), (t_const, 0.0), (t_jerk, j)]
    return [(d, jj) for d, jj in phases if d > 0.0]


def speed_change(v0: float, v1: float, a: float, j: float) -> list[tuple[float, float]]:
    """Phases ``[(duration, jerk), ...]`` of the fastest change of speed from
    ``v0`` to ``v1`` with ``|s''| <= a``, ``|s'''| <= j``, the acceleration 0
    at both ends: jerk ``+-j`` for ``a / j``, constant acceleration for
    ``|dv| / a - a / j``, jerk ``-+j`` for ``a / j`` when ``|dv| >= a^2 / j``;
    else two jerk phases of ``sqrt(|dv| / j)``. Its distance is its mean
    speed ``(v0 + v1) / 2`` times its duration (the acceleration pulse is
    symmetric in time)."""
    dv = v1 - v0
    if dv == 0.0:
        return []
    sign = 1.0 if dv > 0.0 else -1.0
    if abs(dv) * j >= a * a:
        phases = [(a / j, sign * j), (abs(dv) / a - a / j, 0.0), (a / j, -sign * j)]
    else:
        t = math.sqrt(abs(dv) / j)
        phases = [(t, sign * j), (t, -sign * j)]
    return [(d, jj) for d, jj in phases if d > 0.0]


def speed_change_distance(v0: float, v1: float, a: float, j: float) -> float:
    """Distance (units) of :func:`speed_change` from ``v0`` to ``v1``."""
    return 0.5 * (v0 + v1) * sum(d for d, _ in speed_change(v0, v1, a, j))


def scurve_between(length: float, v0: float, v1: float, v: float, a: float,
                   j: float) -> list[tuple[float, float]]:
    """Phases ``[(duration, jerk), ...]`` of the fastest motion over ``length``
    from speed ``v0`` to ``v1`` (acceleration 0 at both ends) with
    ``s' <= v``, ``|s''| <= a``, ``|s'''| <= j``: a :func:`speed_change` up to
    a peak ``vp``, a cruise at ``vp``, one down to ``v1``; ``vp`` is ``v``
    when both changes fit in ``length``, else the largest that does
    (bisection: the distance grows with ``vp``). ``length`` must hold the
    change from ``v0`` to ``v1`` (:func:`speed_change_distance`), which a
    look-ahead guarantees; the peak is then at least ``max(v0, v1)``."""
    if length <= 0.0:
        return []

    def need(vp):
        return speed_change_distance(v0, vp, a, j) + speed_change_distance(vp, v1, a, j)

    vp = v
    if need(vp) > length:
        lo, hi = max(v0, v1), v
        for _ in range(BISECTION_STEPS):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if need(mid) <= length else (lo, mid)
        vp = lo
    cruise = max(length - need(vp), 0.0) / vp if vp > 0.0 else 0.0
    phases = speed_change(v0, vp, a, j) + [(cruise, 0.0)] + speed_change(vp, v1, a, j)
    return [(d, jj) for d, jj in phases if d > 0.0]


def integrate_phases(s0: float, phases, end: float, v0: float = 0.0, v_end: float = 0.0):
    """Knots of constant-jerk ``phases`` from speed ``v0`` (rest by default),
    acceleration 0, at ``s0``: arrays ``(s0, h, v0, v1, a0, a1, j, dt)`` per
    phase; the last phase ends exactly at ``end`` at speed ``v_end`` with
    acceleration 0 (rounding absorbed)."""
    rows = []
    s, v, acc = s0, v0, 0.0
    for i, (d, jj) in enumerate(phases):
        ds = v * d + 0.5 * acc * d * d + jj * d ** 3 / 6.0
        v1 = v + acc * d + 0.5 * jj * d * d
        a1 = acc + jj * d
        last = i == len(phases) - 1
        if last:
            ds, v1, a1 = end - s, v_end, 0.0
        rows.append((s, max(ds, 0.0), v, max(v1, 0.0), acc, a1, jj, d))
        s, v, acc = s + ds, max(v1, 0.0), a1
    return rows
