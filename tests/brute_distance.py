"""Distances worked out in the tests, independently of ccopt's kernels: points
to a line segment or an arc by their formulas (foot of the perpendicular on a
line; on an arc the radial gap where the point's angle is on it, else the
nearer end), and the one-sided Hausdorff distance of primitives sampled along
their arc length. Lengths in program units."""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Line


def point_distances(q, g) -> np.ndarray:
    """``(N,)``: exact distances of points ``q`` (``(N, 2)``) to a line segment or an arc."""
    q = np.asarray(q, float).reshape(-1, 2)
    if isinstance(g, Line):
        p0, p1 = np.asarray(g.p0, float), np.asarray(g.p1, float)
        d = p1 - p0
        t = np.clip(((q - p0) @ d) / (d @ d), 0.0, 1.0)
        return np.hypot(*(q - (p0 + t[:, None] * d)).T)
    c = np.asarray(g.center, float)
    v = q - c
    rel = np.remainder((np.arctan2(v[:, 1], v[:, 0]) - g.theta0) * math.copysign(1.0, g.sweep),
                       2.0 * math.pi)
    ends = np.minimum(np.hypot(*(q - np.asarray(g.start)).T), np.hypot(*(q - np.asarray(g.end)).T))
    return np.where(rel <= abs(g.sweep), np.minimum(ends, np.abs(np.hypot(*v.T) - g.radius)), ends)


def one_sided_deviation(src, dst, spacing: float | None = None, points: int | None = None) -> float:
    """The largest distance from the primitives ``src`` to the lines and arcs
    ``dst``, over points of each ``src`` primitive every ``spacing`` of its arc
    length, or ``points`` of them (end points included): the true value is at
    most one step above it."""
    worst = 0.0
    for g in src:
        n = points if points is not None else max(2, int(math.ceil(g.length / spacing)) + 1)
        q = np.asarray(g.point(np.linspace(0.0, g.length, n)), float).reshape(-1, 2)
        worst = max(worst, float(np.min([point_distances(q, t) for t in dst], axis=0).max()))
    return worst
