"""``JerkProfile``: a feed profile with bounded jerk.

The profiles of the ``jerk`` planner (:mod:`ccopt.feed.jerk.planner`) and of
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
