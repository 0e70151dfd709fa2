"""Where to evaluate a constant-acceleration profile so its maxima are known to a bound.

A profile's figures (the largest axis velocity, acceleration and jerk ratios,
feed and centripetal ratios) are maxima over continuous time. Sampling every
``dt`` seconds finds them only approximately, and costs one evaluation of the
exact path per ``dt`` whatever the geometry (a 2,000 s program at 1 ms: two
million). Here each piece of constant path acceleration is evaluated at both
its ends (with its own acceleration) and at a step chosen from the geometry
and the motion so that, with ``f`` any of the figures' quantities,

    max over the piece of f  <=  max over its samples of f  +  FIGURE_TOL * limit

(a stated bound, not an estimate). The argument: on a step ``h`` between
samples, a function with ``|f''| <= M`` exceeds the larger of its two end
values by at most ``M h^2 / 8``. With path speed ``v <= V``, path
acceleration ``|u| = A`` (constant on the piece, ``s''' = 0``) and ``K_n``
upper bounds of ``|q^(n)(s)|`` on the segment (arc length ``s``, ``|q'| = 1``):

    velocity     q' v:              |f''| <= K3 V^3 + 3 K2 V A
    acceleration q'' v^2 + q' u:    |f''| <= K4 V^4 + 6 K3 V^2 A + 3 K2 A^2
    jerk         q''' v^3 + 3 q'' v u:
                                    |f''| <= K5 V^5 + 10 K4 V^3 A + 15 K3 V A^2
    centripetal  kappa v^2:         |f''| <= k2 V^4 + 5 k1 V^2 A + 2 K2 A^2

(``k1``, ``k2`` bounds of ``|kappa'|``, ``|kappa''|``). The speed is linear
in time on a piece, so ``V`` is the larger end speed; the feed and the
tangential acceleration are exact at the ends. Bounds of the path's
derivatives (Frenet: ``q'' = kappa N``, ``q''' = kappa' N - kappa^2 T``,
``q'''' = (kappa'' - kappa^3) N - 3 kappa kappa' T``, ``q''''' = (kappa''' -
6 kappa^2 kappa') N - (4 kappa kappa'' - kappa^4 + 3 kappa'^2) T``):

- a line: all zero, so a piece of a line needs its two ends only (its speed
  is monotone and its acceleration constant: the maxima there are exact);
- an arc of radius ``R``: ``|q^(n)| = R^(1-n)``;
- an Archimedean spiral ``rho = rho0 + b phi`` (``rho >= rho_min > 0``):
  ``kappa = (rho^2 + 2 b^2) / m^3`` with ``m = sqrt(rho^2 + b^2)``, largest
  at ``rho_min``; ``kappa' = -b h(rho)`` with ``h = rho (rho^2 + 4 b^2) / m^6``,
  so ``|kappa'| <= 4 |b| / rho^3``; ``kappa'' = -b^2 h'(rho) / m`` and
  ``kappa''' = -(b^3 / m) d/drho (h' / m)`` (``d rho / ds = b / m``), each
  term bounded with ``rho, |b| <= m``: ``|h'| <= 28 / m^4``, ``|h''| <= 270 / m^5``,
  so ``|kappa''| <= 28 b^2 / rho^5`` and ``|kappa'''| <= 300 |b|^3 / rho^7``;
- a segment that also moves ``w`` (a helix): the in-plane derivatives times
  ``(L / S)^n <= 1``, ``w'' = 0``: the plane's bounds hold.

Other curves (the smoother's) have no such bounds here: their pieces are
sampled every ``dt`` as before. A component of a vector is at most its norm,
and each axis's ratio is measured against the smallest limit of the axes, so
the bound holds for every axis.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Arc, Line, Spiral

#: The figures' stated accuracy, as a fraction of the limit they are measured
#: against (ratio units): the true maximum over a piece is at most the sampled
#: one plus this. Ten times finer than the 4 decimals ``ccopt feed`` prints.
FIGURE_TOL = 1e-4

def derivative_bounds(geoms) -> np.ndarray:
    """``(K, 6)`` upper bounds on each segment of ``|q''|, |q'''|, |q''''|``, the
    curvature's first two arc-length derivatives, and ``|q'''''|`` (units^-1 ..
    units^-4), see the module docstring; ``inf`` where no bound is known."""
    out = np.full((len(geoms), 6), np.inf)
    for i, g in enumerate(geoms):
        if type(g) is Line:
            out[i] = 0.0
        elif type(g) is Arc:
            k = 1.0 / float(g.radius)
            out[i] = (k, k * k, k ** 3, 0.0, 0.0, k ** 4)
        elif type(g) is Spiral and g.sweep != 0.0:
            rho = min(float(g.rho0), float(g.rho1))
            b = abs(float(g.rho1) - float(g.rho0)) / abs(float(g.sweep))
            m = math.hypot(rho, b)
            kappa = (rho * rho + 2.0 * b * b) / m ** 3
            k1 = 4.0 * b / rho ** 3
            k2 = 28.0 * b * b / rho ** 5
            k3 = 300.0 * b ** 3 / rho ** 7
            k5 = k3 + 6.0 * kappa * kappa * k1 + 4.0 * kappa * k2 + kappa ** 4 + 3.0 * k1 * k1
            out[i] = (kappa, kappa * kappa + k1, kappa ** 3 + 3.0 * kappa * k1 + k2, k1, k2, k5)
    return out


def _step(M: np.ndarray, allowance: float) -> np.ndarray:
    """Largest step with error ``M h^2 / 8`` at most ``allowance``; ``inf`` where ``M`` is 0."""
    with np.errstate(divide="ignore"):
        return np.sqrt(np.where(M > 0.0, 8.0 * allowance / M, np.inf))


def piece_steps(bounds: np.ndarray, segment: np.ndarray, speed: np.ndarray, acc: np.ndarray,
                v_min: float, a_min: float, j_min: float | None,
                centripetal: float | None, dt: float) -> np.ndarray:
    """The sampling step (s) of each piece: ``bounds`` from :func:`derivative_bounds`
    of the piece's ``segment`` (-1: a dwell, whose ends suffice), ``speed`` its
    larger end speed ``V``, ``acc`` its ``|s''|``; ``*_min`` the smallest axis
    limits. ``dt`` where the segment has no known bounds."""
    B = bounds[np.maximum(segment, 0)]
    K2, K3, K4, k1, k2, K5 = (B[:, c] for c in range(6))
    V, A = speed, acc
    with np.errstate(invalid="ignore"):     # inf * 0 on a line at rest: no bound needed
        Mv = np.nan_to_num(K3 * V ** 3 + 3.0 * K2 * V * A, nan=0.0)
        Ma = np.nan_to_num(K4 * V ** 4 + 6.0 * K3 * V * V * A + 3.0 * K2 * A * A, nan=0.0)
        h = np.minimum(_step(Mv, FIGURE_TOL * v_min), _step(Ma, FIGURE_TOL * a_min))
        if j_min is not None:
            Mj = np.nan_to_num(K5 * V ** 5 + 10.0 * K4 * V ** 3 * A + 15.0 * K3 * V * A * A,
                               nan=0.0)
            h = np.minimum(h, _step(Mj, FIGURE_TOL * j_min))
        if centripetal is not None:
            Mc = np.nan_to_num(k2 * V ** 4 + 5.0 * k1 * V * V * A + 2.0 * K2 * A * A, nan=0.0)
            h = np.minimum(h, _step(Mc, FIGURE_TOL * centripetal))
    unknown = ~np.isfinite(B).all(axis=1) & (segment >= 0)
    h = np.where(unknown, dt, h)
    return np.where(segment < 0, np.inf, h)


def piece_times(t: np.ndarray, steps: np.ndarray):
    """``(piece, tau)``: each piece's index and times into it (s), its start, every
    ``steps[k]`` (evened out to divide the piece) and its end."""
    tau_k = np.diff(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        n = np.where(np.isfinite(steps) & (steps > 0), np.ceil(tau_k / steps), 1.0)
    n = np.maximum(n, 1.0).astype(np.int64)
    piece = np.repeat(np.arange(tau_k.size), n + 1)
    first = np.concatenate([[0], np.cumsum(n + 1)[:-1]])
    j = np.arange(piece.size) - np.repeat(first, n + 1)
    tau = tau_k[piece] * (j / n[piece])
    return piece, tau
