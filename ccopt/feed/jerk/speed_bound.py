"""The speed bound of the ``jerk`` planner: TOPPRA's acceleration-limited speed.

See :mod:`ccopt.feed.jerk.planner`: on a stretch with no stop, planned in
overlapping windows, the pseudo-jerk rounds start from the squared speed of
the time-optimal profile under the velocity and acceleration limits alone
(TOPPRA), an upper bound of every jerk-limited speed, and never let ``b``
rise above it (a window from rest to rest needs none of this: it starts from
:func:`ccopt.feed.jerk.windows.rest_bound`).

On a program planned in worker processes (:mod:`ccopt.feed.jerk.windows`)
TOPPRA runs in the workers too, one instance per task: a task's gridpoints
go from a stop to a stop, and the path between them is a path of its own
(:meth:`~ccopt.feed.path.ExactPath.stretch`) that TOPPRA plans from rest to
rest. A stop fixes the speed at 0, so the pieces between stops are independent problems and this is
the same bound as one instance over the whole path gives, up to the
gridpoints TOPPRA places on the shorter path (its spacing follows the limits
of the axes that path moves). Both cores then work from the start instead of
waiting for one TOPPRA over the whole program.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ccopt.feed.grid import GridOptions
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.toppra.planner import plan_toppra
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


@dataclass(frozen=True)
class StretchBound:
    """What a worker needs to compute :func:`speed_bound` on its own stretch:
    the stretch's tool path (:meth:`ExactPath.stretch`), the limits, the grid
    options, the stretch's start ``origin`` on the whole path and the whole
    path's coordinates ``axes`` (:attr:`ExactPath.axes`: TOPPRA grids the
    stretch as within the whole path)."""

    toolpath: ToolPath
    limits: AxisLimits
    grid: GridOptions | None
    origin: float
    axes: tuple[bool, int] | None = None

    @classmethod
    def of(cls, path: ExactPath, limits: AxisLimits, grid: GridOptions | None,
           s0: float, s1: float) -> "StretchBound":
        return cls(path.stretch(s0, s1), limits, grid, float(path.offsets[path.boundary(s0)]),
                   path.axes)

    def __call__(self, s: np.ndarray, stop: np.ndarray, bmax: np.ndarray) -> np.ndarray:
        """:func:`speed_bound` at the stretch's gridpoints ``s`` (whole-path positions)."""
        return speed_bound(ExactPath(self.toolpath, self.axes), self.limits, self.grid, s, stop,
                           bmax, self.origin)
