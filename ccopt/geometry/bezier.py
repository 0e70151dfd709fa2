"""Bezier mathematics of blend curves: G2 end conditions, energies, time models.

Numpy only, on control points ``P`` (``(n+1, 2)``, program units) of a planar
Bezier curve ``r(t)``, ``t`` in [0, 1]. The Bernstein basics they build on
(:func:`~ccopt.geometry.curve.bernstein`, :func:`~ccopt.geometry.curve.derivative_matrix`,
:func:`~ccopt.geometry.curve.subdivision_matrix`) are in :mod:`ccopt.geometry.curve`.

- :func:`g2_end` / :func:`g2_start`: control points that give a curve of
  degree ``n`` the position, tangent and curvature of a host at one end. At
  the end ``J`` with unit tangent ``t``, left normal ``n`` and curvature
  ``kappa`` (> 0 turning left): ``P[n] = J``, ``P[n-1] = J - a t``,
  ``P[n-2] = J + (e - 2a) t + (n/(n-1)) kappa a^2 n`` for any leg ``a > 0``
  and any ``e`` (then ``r'(1) = n a t`` and ``kappa(1) = kappa``);
- :func:`bernstein_gram`, :func:`derivative_gram`, :func:`energy_root`,
  :func:`bezier_energy`: ``integral_0^1 |d^k r/dt^k|^2 dt`` as a quadratic form
  of the control points (:func:`jerk_gram`: ``k = 3``, a jerk proxy);
- :func:`speed_profile_time`: the time of TOPP's discrete model on the curve
  under axis acceleration limits (what the optimised blends minimise).
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry.curve import bernstein, derivative_matrix

#: Stands for a zero speed or direction component in a division: only keeps
#: the quotient finite (the result is then huge, or masked out).
DIVISION_FLOOR = 1e-300

#: A unit tangent component at most this (in magnitude) gives its axis no share
#: of the path acceleration: the axis sees only the centripetal term.
TANGENT_COMPONENT_EPS = 1e-12


# --------------------------------------------------------------------------- G2 end conditions


def g2_end(J, t, kappa: float, a: float, e: float, n: int) -> np.ndarray:
    """Control points ``P[n-2], P[n-1], P[n]`` ending at ``J`` with unit tangent ``t``
    and signed curvature ``kappa`` (see the module docstring; ``a``, ``e`` in
    program units)."""
    J = np.asarray(J, float)
    t = np.asarray(t, float)
    nl = np.array([-t[1], t[0]])
    c = n * kappa * a * a / (n - 1)
    return np.array([J + (e - 2.0 * a) * t + c * nl, J - a * t, J])


def g2_start(P0, t, kappa: float, a: float, e: float, n: int) -> np.ndarray:
    """Control points ``P[0], P[1], P[2]`` starting at ``P0`` with unit tangent ``t``
    and signed curvature ``kappa``."""
    P0 = np.asarray(P0, float)
    t = np.asarray(t, float)
    nl = np.array([-t[1], t[0]])
    c = n * kappa * a * a / (n - 1)
    return np.array([P0, P0 + a * t, P0 + (2.0 * a + e) * t + c * nl])


# --------------------------------------------------------------------------- energies


def bernstein_gram(m: int) -> np.ndarray:
    """Gram matrix of the degree-``m`` Bernstein basis on [0, 1]:
    ``B[i, j] = integral_0^1 b_i(t) b_j(t) dt``."""
    return np.array([[math.comb(m, i) * math.comb(m, j) / (math.comb(2 * m, i + j) * (2 * m + 1))
                      for j in range(m + 1)] for i in range(m + 1)])


def gram_sqrt_factor(G: np.ndarray) -> np.ndarray:
    """``R`` with ``R.T @ R = G`` for a symmetric positive semidefinite ``G``
    (eigenvalues rounded below zero count as zero): ``q.T G q = |R q|^2``."""
    w, V = np.linalg.eigh(0.5 * (G + G.T))
    return (V * np.sqrt(np.clip(w, 0.0, None))).T


def derivative_gram(n: int, order: int) -> np.ndarray:
    """``G`` (``(n+1, n+1)``) with ``integral |d^order r/dt^order|^2 dt = trace(P.T G P)``
    (zero when the degree ``n`` is below ``order``)."""
    if n < order:
        return np.zeros((n + 1, n + 1))
    D = derivative_matrix(n, order)
    return D.T @ bernstein_gram(n - order) @ D


def jerk_gram(n: int) -> np.ndarray:
    """``G`` (``(n+1, n+1)``) with ``integral |r'''|^2 dt = trace(P.T G P)``."""
    return derivative_gram(n, 3)


def energy_root(n: int, order: int) -> np.ndarray:
    """``R`` with ``integral |d^order r/dt^order|^2 dt = |R P_x|^2 + |R P_y|^2`` (the
    form a conic solver takes: a sum of squares, affine in the control points)."""
    return gram_sqrt_factor(bernstein_gram(n - order)) @ derivative_matrix(n, order)


def bezier_energy(P: np.ndarray, order: int) -> float:
    """``integral_0^1 |d^order r/dt^order|^2 dt`` of the Bezier ``P``."""
    n = len(P) - 1
    Q = derivative_matrix(n, order) @ P
    return float(np.sum(Q * (bernstein_gram(n - order) @ Q)))


# --------------------------------------------------------------------------- samples


def curve_samples(P: np.ndarray, t: np.ndarray):
    """``(points, speed |r'|, signed curvature)`` of the Bezier ``P`` at ``t``
    (curvature > 0 turning left, 1/program units)."""
    n = len(P) - 1
    pts = bernstein(t, n) @ P
    d1 = bernstein(t, n - 1) @ (derivative_matrix(n, 1) @ P)
    d2 = bernstein(t, n - 2) @ (derivative_matrix(n, 2) @ P) if n >= 2 else np.zeros_like(d1)
    sp = np.hypot(d1[:, 0], d1[:, 1])
    k = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(sp, DIVISION_FLOOR) ** 3
    return pts, sp, k


def path_frame(P: np.ndarray, t: np.ndarray):
    """``(points, unit tangent q', q'' = kappa * normal, |r'|)`` of the Bezier ``P`` at ``t``
    (derivatives by arc length)."""
    n = len(P) - 1
    pts = bernstein(t, n) @ P
    d1 = bernstein(t, n - 1) @ (derivative_matrix(n, 1) @ P)
    d2 = bernstein(t, n - 2) @ (derivative_matrix(n, 2) @ P)
    sp = np.hypot(d1[:, 0], d1[:, 1])
    T = d1 / sp[:, None]
    K = (d2 - np.einsum("ij,ij->i", d2, T)[:, None] * T) / (sp * sp)[:, None]
    return pts, T, K, sp


# --------------------------------------------------------------------------- time models


def path_acceleration_interval(T, K, b, acc):
    """Feasible path accelerations ``u = s''`` at squared speed ``b`` under
    ``|T_k u + K_k b| <= a_k`` for each axis ``k`` (vectorised): ``(lo, hi)``;
    ``lo > hi`` where no ``u`` is feasible."""
    lo = np.full(np.shape(b), -np.inf)
    hi = np.full(np.shape(b), np.inf)
    for k, a in enumerate(acc):
        tk, kk = T[:, k], K[:, k]
        with np.errstate(divide="ignore", invalid="ignore"):
            l1 = (-a - kk * b) / tk
            h1 = (a - kk * b) / tk
        pos = tk > TANGENT_COMPONENT_EPS
        neg = tk < -TANGENT_COMPONENT_EPS
        zero = np.abs(tk) <= TANGENT_COMPONENT_EPS
        lo = np.where(pos, np.maximum(lo, l1), np.where(neg, np.maximum(lo, h1), lo))
        hi = np.where(pos, np.minimum(hi, h1), np.where(neg, np.minimum(hi, l1), hi))
        bad = zero & (np.abs(kk * b) > a)
        lo = np.where(bad, np.inf, lo)
        hi = np.where(bad, -np.inf, hi)
    return lo, hi


def _interval_at(t, k, b: float, acc) -> tuple[float, float]:
    """:func:`path_acceleration_interval` at one cut (``t``, ``k``: its unit
    tangent and ``q''`` as sequences of floats), in floats: the same
    operations, so the same values, without numpy's cost per call (the
    forward and backward passes of :func:`speed_profile_time` go cut by
    cut, 400 calls per curve: 3.4 of the main job's 124 CPU s as arrays)."""
    lo, hi = -math.inf, math.inf
    for tk, kk, a in zip(t, k, acc):
        if tk > TANGENT_COMPONENT_EPS:
            lo, hi = max(lo, (-a - kk * b) / tk), min(hi, (a - kk * b) / tk)
        elif tk < -TANGENT_COMPONENT_EPS:
            lo, hi = max(lo, (a - kk * b) / tk), min(hi, (-a - kk * b) / tk)
        elif abs(kk * b) > a:
            return math.inf, -math.inf
    return lo, hi


def _speed_caps(T, K, feed: float, acc) -> np.ndarray:
    """Largest squared speed each cut allows, at most ``feed^2`` (bisection: the
    feasible squared speeds form an interval ``[0, bmax]``)."""
    m = len(T)
    lo_b = np.zeros(m)
    hi_b = np.full(m, feed * feed)
    ul, uh = path_acceleration_interval(T, K, hi_b, acc)
    ok = ul <= uh
    for _ in range(60):
        mid = 0.5 * (lo_b + hi_b)
        ul, uh = path_acceleration_interval(T, K, mid, acc)
        f = ul <= uh
        lo_b = np.where(f, mid, lo_b)
        hi_b = np.where(f, hi_b, mid)
    return np.where(ok, feed * feed, lo_b)


def speed_profile_time(P: np.ndarray, feed: float, acc, m: int = 81,
                       v_start: float = 0.0) -> float:
    """Time (s) to run the Bezier ``P`` from ``v_start`` and go on at the feed.

    ``acc``: the in-plane axis acceleration limits ``(a_x, a_y)`` (a scalar
    means both). The curve is cut at ``m`` equally spaced ``t``; at each cut
    the axis accelerations ``q' s'' + q'' s'^2`` stay within the limits and
    the speed within ``feed`` (TOPP's discrete model, as TOPPRA solves it,
    by forward and backward passes); each piece runs at constant path
    acceleration. What the end speed ``v_end`` costs afterwards, accelerating
    back to the feed along the end tangent, is added:
    ``(feed - v_end)^2 / (2 a_end feed)``.
    """
    acc = np.broadcast_to(np.asarray(acc, float), (2,))
    t = np.linspace(0.0, 1.0, m)
    pts, T, K, _ = path_frame(np.asarray(P, float), t)
    ds = np.hypot(*np.diff(pts, axis=0).T)
    b = _speed_caps(T, K, feed, acc).tolist()
    b[0] = min(b[0], v_start ** 2)
    Tl, Kl, dl, al = T.tolist(), K.tolist(), ds.tolist(), acc.tolist()
    for i in range(m - 1):
        uh = _interval_at(Tl[i], Kl[i], b[i], al)[1]
        b[i + 1] = min(b[i + 1], b[i] + 2.0 * dl[i] * max(uh, 0.0))
    for i in range(m - 2, -1, -1):
        ul = _interval_at(Tl[i + 1], Kl[i + 1], b[i + 1], al)[0]
        b[i] = min(b[i], b[i + 1] - 2.0 * dl[i] * min(ul, 0.0))
    v = np.sqrt(np.maximum(np.asarray(b), 0.0))
    den = v[:-1] + v[1:]
    with np.errstate(divide="ignore"):
        dt = np.where(den > 0, 2.0 * ds / np.where(den > 0, den, 1.0), np.inf)
    a_end = end_acceleration(T[-1], acc)
    return float(dt.sum() + (feed - v[-1]) ** 2 / (2.0 * a_end * feed))


def end_acceleration(direction, acc) -> float:
    """Largest path acceleration along a straight ``direction`` under axis limits ``acc``."""
    d = np.abs(np.asarray(direction, float))
    acc = np.broadcast_to(np.asarray(acc, float), d.shape)
    with np.errstate(divide="ignore"):
        return float(np.min(np.where(d > TANGENT_COMPONENT_EPS,
                                     acc / np.maximum(d, DIVISION_FLOOR), np.inf)))
