"""The speed bound of the ``jerk`` planner: TOPPRA's acceleration-limited speed.

See :mod:`ccopt.feed.jerk_planner`: on a stretch with no stop, planned in
overlapping windows, the pseudo-jerk rounds start from the squared speed of
the time-optimal profile under the velocity and acceleration limits alone
(TOPPRA), an upper bound of every jerk-limited speed, and never let ``b``
rise above it (a window from rest to rest needs none of this: it starts from
:func:`ccopt.feed.jerk_windows.rest_bound`).

On a program planned in worker processes (:mod:`ccopt.feed.jerk_windows`)
TOPPRA runs in the workers too, one instance per task: a task's gridpoints
go from a stop to a stop, and the path between them is a path of its own
(:func:`stretch_path`) that TOPPRA plans from rest to rest. A stop fixes the
speed at 0, so the pieces between stops are independent problems and this is
the same bound as one instance over the whole path gives, up to the
gridpoints TOPPRA places on the shorter path (its spacing follows the limits
of the axes that path moves). Both cores then work from the start instead of
waiting for one TOPPRA over the whole program.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ccopt.feed.grid import GridOptions
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.toppra_planner import plan_toppra
from ccopt.toolpath import ToolPath


def speed_bound(path: ExactPath, limits: AxisLimits, grid: GridOptions | None,
                s: np.ndarray, stop: np.ndarray, bmax: np.ndarray,
                origin: float = 0.0) -> np.ndarray:
    """TOPPRA's squared speed (units^2/s^2) on ``path`` at the gridpoints ``s``
    (positions on the path of which ``path`` starts at ``origin``), 0 at the
    ``stop`` gridpoints and at most the box bound ``bmax``."""
    no_jerk = AxisLimits(limits.v, limits.a, limits.tangential_acc, limits.centripetal_acc)
    upper = plan_toppra(path, no_jerk, grid=grid).speed_at(s - origin) ** 2
    return np.where(stop, 0.0, np.minimum(upper, bmax))


def stretch_path(path: ExactPath, s0: float, s1: float) -> ToolPath:
    """The tool path of ``path`` from position ``s0`` to ``s1`` (both stops or
    ends, so both at segment boundaries), with the dwells strictly inside it."""
    k0 = _boundary(path, s0)
    k1 = _boundary(path, s1)
    src = path.source_index
    i0, i1 = int(src[k0]), int(src[k1 - 1]) + 1
    tp = path.toolpath
    dwells = tuple((before - i0, seconds, blk) for before, seconds, blk in tp.dwells
                   if i0 < before < i1)
    return replace(tp, segments=tp.segments[i0:i1], dwells=dwells)


def _boundary(path: ExactPath, s: float) -> int:
    """Index of the segment boundary at ``s`` (the nearest offset: stops are
    boundaries, taken from the offsets themselves)."""
    k = int(np.searchsorted(path.offsets, s))
    if k > 0 and (k == path.offsets.size or s - path.offsets[k - 1] < path.offsets[k] - s):
        k -= 1
    return k


@dataclass(frozen=True)
class StretchBound:
    """What a worker needs to compute :func:`speed_bound` on its own stretch:
    the stretch's tool path (:func:`stretch_path`), the limits, the grid
    options and the stretch's start ``origin`` on the whole path."""

    toolpath: ToolPath
    limits: AxisLimits
    grid: GridOptions | None
    origin: float

    @classmethod
    def of(cls, path: ExactPath, limits: AxisLimits, grid: GridOptions | None,
           s0: float, s1: float) -> "StretchBound":
        return cls(stretch_path(path, s0, s1), limits, grid, float(path.offsets[_boundary(path, s0)]))

    def __call__(self, s: np.ndarray, stop: np.ndarray, bmax: np.ndarray) -> np.ndarray:
        """:func:`speed_bound` at the stretch's gridpoints ``s`` (whole-path positions)."""
        return speed_bound(ExactPath(self.toolpath), self.limits, self.grid, s, stop, bmax,
                           self.origin)
