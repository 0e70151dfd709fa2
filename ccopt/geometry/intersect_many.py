"""Vectorised intersections of many carrier pairs at once (infinite lines, full circles).

The scalar :mod:`ccopt.geometry.intersect` is the readable reference; these
kernels do the same algebra on arrays of pairs, for the compensation engine's
long runs of ordinary corners. Each returns two candidate points per pair and
a count ``n`` (0, 1 or 2). Pairs within ``near`` (relative) of a degenerate
configuration — parallel lines, tangency — are flagged in ``delicate`` so the
caller can hand them to the scalar reference, whose tolerance rules decide.

Shapes: points and directions ``(m, 2)``, radii ``(m,)``; directions are unit.
"""
from __future__ import annotations

import numpy as np

#: Relative closeness to parallel lines or tangency below which a pair is
#: ``delicate`` and goes to the scalar reference: far above the rounding of
#: these formulas (~1e-15), far below a real corner's turn.
DELICATE_REL = 1e-9


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def lines_lines(p: np.ndarray, d: np.ndarray, q: np.ndarray, e: np.ndarray,
                near: float = DELICATE_REL):
    """Line ``p + t*d`` with line ``q + u*e``: ``(x, x, n, delicate)``."""
    den = _cross(d, e)
    delicate = np.abs(den) <= near
    # parallel pairs (delicate) give inf/nan here; the caller never reads them
    with np.errstate(divide="ignore", invalid="ignore"):
        t = _cross(q - p, e) / den
        x = p + t[:, None] * d
    n = np.where(delicate, 0, 1)
    return x, x, n, delicate


def lines_circles(p: np.ndarray, d: np.ndarray, c: np.ndarray, R: np.ndarray,
                  near: float = DELICATE_REL):
    """Line ``p + t*d`` with circle ``(c, R)``: candidates ordered by ``t``."""
    g = c - p
    along = np.einsum("ij,ij->i", g, d)          # foot of the centre along the line
    h = _cross(d, g)                             # signed distance of the centre (left > 0)
    gap = np.abs(np.abs(h) - R)
    delicate = gap <= near * R
    w = np.sqrt(np.maximum((R - h) * (R + h), 0.0))
    foot = p + along[:, None] * d
    x1 = foot - w[:, None] * d
    x2 = foot + w[:, None] * d
    n = np.where(np.abs(h) < R, 2, 0)
    return x1, x2, n, delicate


def circles_circles(c1: np.ndarray, R1: np.ndarray, c2: np.ndarray, R2: np.ndarray,
                    near: float = DELICATE_REL):
    """Circle ``(c1, R1)`` with circle ``(c2, R2)``: the first candidate lies left of c1 -> c2."""
    g = c2 - c1
    D = np.hypot(g[:, 0], g[:, 1])
    rsum = R1 + R2
    delicate = (D <= near * np.maximum(R1, R2)) | (np.abs(D - rsum) <= near * rsum) | (
        np.abs(D - np.abs(R1 - R2)) <= near * rsum)
    # concentric pairs (delicate) give inf/nan here; the caller never reads them
    with np.errstate(divide="ignore", invalid="ignore"):
        u = g / D[:, None]
        a = (D * D + R1 * R1 - R2 * R2) / (2.0 * D)
        h = np.sqrt(np.maximum((R1 - a) * (R1 + a), 0.0))
        base = c1 + a[:, None] * u
        left = np.c_[-u[:, 1], u[:, 0]]
        x1 = base + h[:, None] * left
        x2 = base - h[:, None] * left
    n = np.where((D < rsum) & (D > np.abs(R1 - R2)), 2, 0)
    return x1, x2, n, delicate
