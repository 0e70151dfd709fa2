"""``JerkProfile``: a feed profile with bounded jerk, and the 7-phase S-curve.

The profiles of the ``jerk`` planner (:mod:`ccopt.feed.jerk_planner`) and of
the jerk-limited ``stop`` baseline are chains of pieces with continuous
path position ``s``, speed ``s'`` and acceleration ``s''``, of two kinds:

- ``CUBIC``: constant path jerk ``s''' = j`` in time,
  ``s(tau) = s0 + v0 tau + a0 tau^2 / 2 + j tau^3 / 6`` (the S-curve's phases,
  and the planner's pieces that start or end at rest);
- ``SLINEAR``: the path acceleration linear in path position,
  ``s''(x) = a0 + (a1 - a0) x / h`` over the piece's length ``h``, so the
  squared speed ``b(x) = v0^2 + 2 a0 x + (a1 - a0) x^2 / h`` is quadratic and
  the jerk is ``s''' = s' (a1 - a0) / h``; its duration is the integral of
  ``1 / sqrt(b)``, taken by :data:`GAUSS_NODES`-point Gauss-Legendre (``b`` is
  bounded away from 0 on such a piece: the pieces that reach rest are cubic),
  and a sample time is mapped to ``x`` by Newton's method on that integral.

The knot arrays of :class:`FeedProfile` hold each piece's start and end
(``t, s, sd``) and its mean acceleration ``sdd`` (speed change over duration),
so code that reads them sees the right times, positions and speeds;
:meth:`JerkProfile.motion` (and so :meth:`~FeedProfile.sample` and
:meth:`~FeedProfile.at`) evaluates the pieces exactly.
:meth:`~FeedProfile.speed_at` reads the knots as constant-acceleration
pieces: exact at the knots, approximate between them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.feed.profile import FeedProfile

CUBIC, SLINEAR = 0, 1

#: Gauss-Legendre nodes per ``SLINEAR`` piece for its duration (``1/sqrt(b)``
#: with ``b`` quadratic and positive: exact to rounding for the ratios of end
#: speeds the planner's grid allows).
GAUSS_NODES = 8
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GAUSS_NODES)

#: Newton steps mapping a sample time to a position inside an ``SLINEAR`` piece.
NEWTON_STEPS = 8

#: Bisection steps for the peak speed of :func:`scurve_between` (2^-60 of the bracket).
BISECTION_STEPS = 60


def slinear_time(b0, a0, a1, h, x) -> np.ndarray:
    """Time (s) to run ``x`` (units) into ``SLINEAR`` pieces (arrays, broadcast)."""
    b0, a0, a1, h, x = np.broadcast_arrays(*(np.asarray(z, float) for z in (b0, a0, a1, h, x)))
    c = np.divide(a1 - a0, h, out=np.zeros_like(h), where=h > 0)
    xm = 0.5 * x
    y = xm[..., None] * (_GL_X + 1.0)
    b = b0[..., None] + 2.0 * a0[..., None] * y + c[..., None] * y * y
    return xm * np.sum(_GL_W / np.sqrt(np.maximum(b, 0.0) + np.finfo(float).tiny), axis=-1)


@dataclass(frozen=True, eq=False)
class JerkProfile(FeedProfile):
    """A profile of ``CUBIC`` and ``SLINEAR`` pieces (see the module docstring).

    Per piece (arrays of the length of ``sdd``): ``kind``, ``acc0`` (``s''`` at
    its start), ``acc1`` (at its end) and ``jerk`` (``s'''`` of a cubic piece;
    unused for ``SLINEAR``). Dwells are cubic pieces of zero motion, segment -1.
    """

    kind: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    acc0: np.ndarray = field(default_factory=lambda: np.zeros(0))
    acc1: np.ndarray = field(default_factory=lambda: np.zeros(0))
    jerk: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @classmethod
    def from_pieces(cls, path, limits, planner: str, pieces: dict, info: dict | None = None):
        """From piece arrays ``kind, s0, h, v0, v1, a0, a1, j, dt, segment``
        (dwells of :attr:`ExactPath.dwells` are inserted here)."""
        p = {k: np.asarray(v) for k, v in pieces.items()}
        for d in sorted(path.dwells, key=lambda d: d.s, reverse=True):
            i = int(np.searchsorted(p["s0"], d.s, side="left"))
            for key, val in (("kind", CUBIC), ("s0", d.s), ("h", 0.0), ("v0", 0.0), ("v1", 0.0),
                             ("a0", 0.0), ("a1", 0.0), ("j", 0.0), ("dt", d.seconds),
                             ("segment", -1)):
                p[key] = np.insert(p[key], i, val)
        t = np.concatenate([[0.0], np.cumsum(p["dt"])])
        s = np.concatenate([p["s0"], [p["s0"][-1] + p["h"][-1]]]) if p["s0"].size else np.zeros(1)
        sd = np.concatenate([p["v0"], p["v1"][-1:]]) if p["v0"].size else np.zeros(1)
        mean_acc = np.divide(p["v1"] - p["v0"], p["dt"], out=np.zeros(p["dt"].size),
                             where=p["dt"] > 0)
        return cls(path, limits, planner, t, s, sd, mean_acc, p["segment"].astype(int),
                   dict(info or {}), p["kind"].astype(int), p["a0"].astype(float),
                   p["a1"].astype(float), p["j"].astype(float))

    def motion(self, times: np.ndarray):
        M = self.sdd.size
        idx = np.clip(np.searchsorted(self.t, times, side="right") - 1, 0, M - 1)
        dt = self.t[idx + 1] - self.t[idx]
        tau = np.clip(times - self.t[idx], 0.0, dt)
        s0, v0, a0, a1 = self.s[idx], self.sd[idx], self.acc0[idx], self.acc1[idx]
        h = self.s[idx + 1] - s0
        j = self.jerk[idx]
        x = v0 * tau + 0.5 * a0 * tau ** 2 + j * tau ** 3 / 6.0
        v = v0 + a0 * tau + 0.5 * j * tau ** 2
        acc = a0 + j * tau
        lin = self.kind[idx] == SLINEAR
        if lin.any():
            xl, vl, al, jl = _slinear_at(v0[lin], a0[lin], a1[lin], h[lin], tau[lin])
            x[lin], v[lin], acc[lin], j = xl, vl, al, j.copy()
            j[lin] = jl
        x = np.clip(x, 0.0, h)
        return s0 + x, np.maximum(v, 0.0), acc, j, self.segment[idx]


def _slinear_at(v0, a0, a1, h, tau):
    """``(x, v, a, j)`` at times ``tau`` into ``SLINEAR`` pieces (Newton on the time)."""
    b0 = v0 * v0
    c = np.divide(a1 - a0, h, out=np.zeros_like(h), where=h > 0)
    # first guess: constant acceleration a0
    x = np.clip(v0 * tau + 0.5 * a0 * tau * tau, 0.0, h)
    for _ in range(NEWTON_STEPS):
        b = np.maximum(b0 + 2.0 * a0 * x + c * x * x, 0.0)
        err = slinear_time(b0, a0, a1, h, x) - tau
        x = np.clip(x - err * np.sqrt(b), 0.0, h)
    v = np.sqrt(np.maximum(b0 + 2.0 * a0 * x + c * x * x, 0.0))
    acc = a0 + c * x
    return x, v, acc, v * c


# -- the 7-phase S-curve, rest to rest -------------------------------------------

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
