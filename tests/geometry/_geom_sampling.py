"""Independent samplers and random generators for the geometry tests.

Everything here is written from the definitions (a segment is a0 + t (a1 - a0),
an arc is c + R (cos, sin) of theta0 + t*sweep) and never calls ccopt, so the
tests compare the kernels against figures derived a different way.
"""
from __future__ import annotations

import numpy as np

TAU = 2.0 * np.pi


def sample_segment(a0, a1, m):
    """(n, m, 2) samples of n segments at m uniform fractions; spacing (n,)."""
    t = np.linspace(0.0, 1.0, m)
    a0 = np.asarray(a0, float)[:, None, :]
    a1 = np.asarray(a1, float)[:, None, :]
    pts = a0 + t[None, :, None] * (a1 - a0)
    return pts, np.hypot(*(a1 - a0)[:, 0, :].T) / (m - 1)


def sample_arc(c, R, th0, sw, m):
    """(n, m, 2) samples of n arcs at m uniform angles; arc-length spacing (n,)."""
    t = np.linspace(0.0, 1.0, m)
    R = np.asarray(R, float)
    ang = np.asarray(th0, float)[:, None] + np.asarray(sw, float)[:, None] * t[None, :]
    c = np.asarray(c, float)
    pts = np.stack([c[:, 0, None] + R[:, None] * np.cos(ang),
                    c[:, 1, None] + R[:, None] * np.sin(ang)], axis=-1)
    return pts, R * np.abs(sw) / (m - 1)


def sampled_min(P, Q, chunk=40):
    """Per-pair min over all sample pairs of P (n, m, 2) and Q (n, k, 2)."""
    out = np.empty(P.shape[0])
    for i in range(0, P.shape[0], chunk):
        p = P[i:i + chunk, :, None, :]
        q = Q[i:i + chunk, None, :, :]
        out[i:i + chunk] = np.sqrt(((p - q) ** 2).sum(-1)).min(axis=(1, 2))
    return out


def dist_to_segment(p, a0, a1):
    """Distance of points p (n, 2) to segments, by projection (reference)."""
    r = a1 - a0
    rr = (r * r).sum(-1)
    t = np.where(rr > 0, ((p - a0) * r).sum(-1) / np.where(rr > 0, rr, 1), 0.0)
    t = np.clip(t, 0, 1)
    return np.hypot(*(p - a0 - t[:, None] * r).T)


def on_arc(p, c, R, th0, sw, tol):
    """Reference test that points p (n, 2) lie on arcs within tol (length)."""
    v = p - c
    rho = np.hypot(v[:, 0], v[:, 1])
    ang = np.arctan2(v[:, 1], v[:, 0])
    rel = np.mod((ang - th0) * np.sign(np.where(sw == 0, 1.0, sw)), TAU)
    inside = (rel <= np.abs(sw) + tol / R) | (rel >= TAU - tol / R) | (np.abs(sw) >= TAU)
    return (np.abs(rho - R) <= tol) & inside


def random_points(rng, n, lo=-5.0, hi=5.0):
    return rng.uniform(lo, hi, (n, 2))


def random_segments(rng, n):
    a0 = random_points(rng, n)
    a1 = random_points(rng, n)
    # A few degenerate (zero-length) and very short segments.
    k = max(n // 40, 1)
    a1[:k] = a0[:k]
    a1[k:2 * k] = a0[k:2 * k] + rng.normal(0, 1e-7, (k, 2))
    return a0, a1


def random_arcs(rng, n):
    c = random_points(rng, n, -4, 4)
    R = rng.uniform(0.2, 4.0, n)
    th0 = rng.uniform(-10.0, 10.0, n)        # un-normalised start angles on purpose
    sw = rng.uniform(-7.0, 7.0, n)           # some beyond a full turn
    k = max(n // 40, 1)
    sw[:k] = 0.0                             # degenerate: a single point
    sw[k:2 * k] = TAU * np.sign(rng.uniform(-1, 1, k))
    return c, R, th0, sw
