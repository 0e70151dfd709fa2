"""``plan_feed``: one entry to every planner of :data:`~ccopt.feed.planners.PLANNERS`.

Imports toppra (through :mod:`.path`); :func:`ccopt.feed.plan_feed` loads this
module on first use so that ``import ccopt`` stays fast.
"""
from __future__ import annotations

from ccopt.feed.errors import FeedError
from ccopt.feed.grid import GridOptions
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.planners import planner_function
from ccopt.feed.profile import FeedProfile
from ccopt.toolpath import ToolPath


def plan_feed(toolpath: ToolPath | ExactPath, limits: AxisLimits, *, planner: str = "toppra",
              junction_deviation: float | None = None,
              grid: GridOptions | None = None, ts: float | None = None) -> FeedProfile:
    """Feed profile of ``toolpath`` under ``limits`` (see :func:`ccopt.feed.plan_feed`)."""
    func = planner_function(planner)
    if not isinstance(limits, AxisLimits):
        raise TypeError("limits must be an AxisLimits")
    if junction_deviation is not None and not junction_deviation >= 0:
        raise ValueError(f"junction_deviation must be >= 0, got {junction_deviation!r}")
    path = toolpath if isinstance(toolpath, ExactPath) else ExactPath(toolpath)
    try:
        limits.in_plane(path.frame, path.dof)
        limits.jerk_in_plane(path.frame, path.dof)
    except ValueError as exc:
        raise FeedError(str(exc), path.source_file) from None
    kwargs: dict = {"junction_deviation": junction_deviation}
    if planner == "toppra":
        kwargs["grid"] = grid if grid is not None else GridOptions()
    elif planner == "jerk":
        kwargs["grid"] = grid           # None: the jerk planner's own default (JERK_GRID)
    if planner in ("jerk", "junction") and ts is not None:
        # the interpolation period caps curvature-break speeds under jerk limits
        kwargs["ts"] = ts
    return func(path, limits, **kwargs)


__all__ = ["plan_feed"]
