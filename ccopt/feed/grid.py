"""Gridpoints for TOPPRA on an :class:`~ccopt.feed.path.ExactPath`.

Every segment boundary is a gridpoint (so curvature breaks and tangent
breaks sit exactly on one, evaluated one-sidedly by the constraints), and each
segment gets its own interior points, at least ``min_intervals`` intervals,
so a short segment is never skipped over. Inside a segment the spacing is the
finest of

- ``min(braking, S) / density`` where ``S`` is the segment length and
  ``braking = v^2 / a``, ``v`` the segment's speed cap (feed, or the
  smallest axis velocity limit for rapids) and ``a`` the largest axis
  acceleration limit. TOPPRA's profile is piecewise constant-acceleration
  between gridpoints, so a switch from speeding up to cruising (or braking)
  that falls inside an interval costs time, of relative order
  ``ds^2 / (8 braking S)``; with ``density = 16`` the worst seen on single
  moves (without the baselines' switch points, which remove it on straight
  moves) is 5e-4 of the duration, on a short move that never cruises;
- ``max_angle`` radians of tangent turning (constraints are imposed at
  gridpoints; between two of them an axis component of ``q'`` or ``q''``
  along an arc can exceed its gridpoint values by about ``max_angle^2 / 8``
  relative: 3e-4 for the default 0.05);

and at most ``max_intervals`` per segment. :func:`refine` adds further
points (the TOPPRA planner adds the baselines' switch points).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ccopt.feed.path import ExactPath


@dataclass(frozen=True)
class GridOptions:
    """How densely to grid the path (see the module docstring)."""

    density: float = 16.0
    max_angle: float = 0.05
    min_intervals: int = 4
    max_intervals: int = 2000
    ds: float | None = None  # a fixed maximum spacing (units) instead of braking / density
    #: add the baselines' switch points (see ccopt.feed.baselines.baseline_knot_positions)
    baseline_knots: bool = True
    #: extra points closer than this to a gridpoint are dropped (units)
    min_spacing: float = 1e-7

    def __post_init__(self):
        if not self.density > 0 or not self.max_angle > 0:
            raise ValueError("density and max_angle must be > 0")
        if self.min_intervals < 2:
            # two stops one interval apart would pin the speed to zero in between
            raise ValueError("min_intervals must be >= 2")
        if self.max_intervals < self.min_intervals:
            raise ValueError("max_intervals must be >= min_intervals")
        if self.ds is not None and not self.ds > 0:
            raise ValueError("ds must be > 0")


def intervals_per_segment(path: ExactPath, v_axis: np.ndarray, a_axis: np.ndarray,
                          options: GridOptions = GridOptions()) -> np.ndarray:
    """Number of grid intervals on each segment of ``path``."""
    S = path.lengths
    if options.ds is not None:
        ds = np.full(S.size, options.ds)
    else:
        v = np.minimum(path.feeds, float(np.min(v_axis)))
        ds = np.minimum(v * v / float(np.max(a_axis)), S) / options.density
    n = np.ceil(S / ds)
    turn = np.array([path.turning(k) for k in range(S.size)])
    n = np.maximum(n, np.ceil(turn / options.max_angle))
    n = np.clip(n, options.min_intervals, options.max_intervals)
    return n.astype(int)


def gridpoints(path: ExactPath, v_axis, a_axis, options: GridOptions = GridOptions()) -> np.ndarray:
    """Strictly increasing gridpoints from 0 to ``path.length``, every boundary included."""
    n = intervals_per_segment(path, np.asarray(v_axis, float), np.asarray(a_axis, float), options)
    k = np.repeat(np.arange(n.size), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    j = np.arange(k.size) - np.repeat(first, n)
    pts = path.offsets[k] + path.lengths[k] * (j / n[k])
    pts = np.concatenate([pts, path.offsets[-1:]])
    # boundaries exactly (j == 0 gives offsets[k] + 0.0, already exact)
    if np.any(np.diff(pts) <= 0.0):
        pts = np.unique(pts)
    return pts


def refine(points: np.ndarray, extra, min_spacing: float) -> np.ndarray:
    """``points`` plus those of ``extra`` at least ``min_spacing`` from every one of them."""
    extra = np.asarray(extra, dtype=float)
    extra = extra[(extra > points[0]) & (extra < points[-1])]
    if extra.size == 0:
        return points
    i = np.searchsorted(points, extra)
    gap = np.minimum(np.abs(points[np.minimum(i, points.size - 1)] - extra),
                     np.abs(extra - points[np.maximum(i - 1, 0)]))
    extra = np.unique(extra[gap >= min_spacing])
    if extra.size > 1:
        keep = np.r_[True, np.diff(extra) >= min_spacing]
        extra = extra[keep]
    return np.union1d(points, extra)
