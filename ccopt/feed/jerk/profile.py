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
  and a sample time is mapped to ``x`` by the closed-form solution of the
  motion (:func:`_slinear_at`), polished by Newton steps on that integral.

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
    """``(x, v, a, j)`` at times ``tau`` into ``SLINEAR`` pieces.

    On such a piece ``s'' = a0 + c x`` (``c = (a1 - a0) / h``): a linear ODE
    in time whose solution from ``x = 0``, ``s' = v0`` is
    ``x(tau) = a0 C(tau) + v0 S(tau)`` with ``C = (cosh(k tau) - 1) / c``,
    ``S = sinh(k tau) / k`` (``k = sqrt(c)``; ``cos`` and ``sin`` of
    ``sqrt(-c) tau`` for ``c < 0``), by their power series where ``|c| tau^2``
    is small (no cancellation). :data:`POLISH_STEPS` Newton steps on the
    duration integral (:func:`slinear_time`, which gives the pieces'
    durations; its quadrature differs from the exact integral by up to 1e-7
    where a piece's speed doubles) then put ``x`` where that integral says,
    to rounding (tests/feed/test_jerk_profile_pieces.py)."""
    b0 = v0 * v0
    c = np.divide(a1 - a0, h, out=np.zeros_like(h), where=h > 0)
    C, S = _cosh_sinh_terms(c, tau)
    x = np.clip(a0 * C + v0 * S, 0.0, h)
    b = np.maximum(b0 + 2.0 * a0 * x + c * x * x, 0.0)
    for _ in range(POLISH_STEPS):
        x = np.clip(x - (slinear_time(b0, a0, a1, h, x) - tau) * np.sqrt(b), 0.0, h)
        b = np.maximum(b0 + 2.0 * a0 * x + c * x * x, 0.0)
    v = np.sqrt(np.maximum(b0 + 2.0 * a0 * x + c * x * x, 0.0))
    acc = a0 + c * x
    return x, v, acc, v * c


#: Newton steps from the closed form to the root of :func:`slinear_time`
#: (each squares the relative error: 1e-7, 1e-14, rounding).
POLISH_STEPS = 2
#: ``|c| tau^2`` under which :func:`_cosh_sinh_terms` sums the power series
#: (:data:`SERIES_TERMS` terms: the first left out is under 2e-16 of the sum).
SERIES_BELOW = 0.5
SERIES_TERMS = 8


def _cosh_sinh_terms(c: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``C = sum_{n>=1} c^(n-1) tau^(2n) / (2n)!`` and ``S = sum_{n>=0} c^n
    tau^(2n+1) / (2n+1)!``: ``(cosh(k tau) - 1) / c`` and ``sinh(k tau) / k``
    with ``k = sqrt(c)`` (for ``c < 0`` the same with ``cos`` and ``sin`` of
    ``sqrt(-c) tau``)."""
    z = c * tau * tau
    C, S = np.zeros_like(tau), np.zeros_like(tau)
    term_c, term_s = 0.5 * tau * tau, tau.copy()
    for n in range(1, SERIES_TERMS + 1):
        C += term_c
        S += term_s
        term_c = term_c * z / ((2 * n + 1) * (2 * n + 2))
        term_s = term_s * z / ((2 * n) * (2 * n + 1))
    big = np.abs(z) >= SERIES_BELOW
    if big.any():
        cb, tb = c[big], tau[big]
        k = np.sqrt(np.abs(cb))
        pos = cb > 0.0
        with np.errstate(over="ignore", invalid="ignore"):
            C[big] = np.where(pos, 0.5 * (np.expm1(k * tb) + np.expm1(-k * tb)),
                              np.cos(k * tb) - 1.0) / cb
            S[big] = np.where(pos, np.sinh(k * tb), np.sin(k * tb)) / k
    return C, S
