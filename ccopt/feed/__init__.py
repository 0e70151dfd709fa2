"""Feed planning: how fast the machine can run a compensated tool path.

``feed`` consumes a :class:`~ccopt.toolpath.ToolPath` and never compensates.
One concept per module, after toppra's layout; one subpackage per planner:

- :mod:`.limits`: :class:`AxisLimits` (per-axis velocity and acceleration,
  optional tangential and centripetal limits);
- :mod:`.path`: :class:`ExactPath`, the tool path as a toppra
  ``AbstractGeometricPath`` parameterised by arc length, exact derivatives;
- :mod:`.grid`: gridpoints (every segment boundary, per-segment density);
- :mod:`.junction`: corner speeds (stop, or grbl's junction deviation);
- :mod:`.toppra`: the time-optimal planner (TOPPRA): :mod:`.toppra.planner`,
  the limits as small toppra constraint objects (:mod:`.toppra.constraints`)
  and toppra itself, imported lightly (:mod:`.toppra.library`);
- :mod:`.baselines`: stop-per-block and grbl-style junction planners;
- :mod:`.jerk`: the jerk-limited time-optimal planner (:mod:`.jerk.planner`)
  over its window LPs (:mod:`.jerk.lp`, :mod:`.jerk.windows`) and their speed
  bound (:mod:`.jerk.speed_bound`); its profiles (:mod:`.jerk.profile`) and
  the 7-phase S-curve (:mod:`.jerk.scurve`);
- :mod:`.bounds`: :func:`feed_limited_time`, the time no planner can beat;
- :mod:`.profile`: :class:`FeedProfile`, its samples and CSV;
- :mod:`.planners`: the planner registry; :mod:`.plan`: :func:`plan_feed` itself.

Example::

    prof = ccopt.plan_feed(path, ccopt.AxisLimits(v=[100, 100, 30], a=[1000, 1000, 300]))
    prof.duration, prof.sample(1e-3).feed
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from ccopt.feed.errors import FeedError
from ccopt.feed.limits import AxisLimits
from ccopt.feed.planners import PLANNERS, planner_function

if TYPE_CHECKING:  # pragma: no cover
    from ccopt.feed.grid import GridOptions
    from ccopt.feed.path import ExactPath
    from ccopt.feed.profile import FeedProfile
    from ccopt.toolpath import ToolPath

# Names importing toppra (which imports scipy.interpolate and matplotlib, ~2 s)
# load on first use, so ``import ccopt`` stays fast.
_LAZY = {
    "ExactPath": "ccopt.feed.path",
    "FeedProfile": "ccopt.feed.profile",
    "FeedSamples": "ccopt.feed.profile",
    "GridOptions": "ccopt.feed.grid",
    "plan_toppra": "ccopt.feed.toppra.planner",
    "plan_stop_per_block": "ccopt.feed.baselines",
    "plan_junction": "ccopt.feed.baselines",
    "plan_jerk": "ccopt.feed.jerk.planner",
    "JerkProfile": "ccopt.feed.jerk.profile",
    "feed_limited_time": "ccopt.feed.bounds",
}


def __getattr__(name):
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def certified_planner(limits: AxisLimits) -> str:
    """The planner whose profile is certified and whose time is the cycle time,
    for every command, the sweep and the comparison alike: ``"jerk"`` when
    ``limits`` carry jerk (TOPPRA's profile would break them; blends are judged
    where they pay, issue 18), else ``"toppra"``. The one place this choice is
    made (:meth:`ccopt.cases.Job.planner_for` applies a job's own choice over it)."""
    return "jerk" if limits.j is not None else "toppra"


def plan_feed(toolpath: ToolPath | ExactPath, limits: AxisLimits, *, planner: str = "toppra",
              junction_deviation: float | None = None,
              grid: GridOptions | None = None, ts: float | None = None) -> FeedProfile:
    """Feed profile of ``toolpath`` under ``limits``.

    Parameters
    ----------
    toolpath: the exact tool path (or an :class:`ExactPath` built from one,
        to share it between planners).
    limits: :class:`AxisLimits` in machine axis order X, Y[, Z].
    planner: ``"toppra"`` (time-optimal, default), ``"stop"`` (stop after
        every block; an S-curve per block when ``limits.j`` is given),
        ``"junction"`` (grbl-style look-ahead) or ``"jerk"`` (jerk-limited
        time-optimal, needs ``limits.j``; :mod:`ccopt.feed.jerk.planner`).
    junction_deviation: ``None`` (default) stops at every tangent
        discontinuity; a length ``delta > 0`` (program units) allows grbl's
        corner speed there instead (an approximation, see
        :mod:`ccopt.feed.junction`). Used by ``toppra`` and ``junction``.
    grid: gridpoint options for TOPPRA and the jerk planner (:class:`GridOptions`;
        ``None``: TOPPRA's default, and for the jerk planner
        :data:`~ccopt.feed.jerk.planner.JERK_GRID`, coarser on curves).
    ts: the interpolation period (s) of the ``"jerk"`` planner and of the
        jerk-limited ``"junction"`` baseline, which bounds the acceleration
        step at a curvature break by ``jmax * ts`` (default 1 ms).

    Raises :class:`FeedError` (a located :class:`~ccopt.errors.ProgramError`)
    when the limits do not fit the path or TOPPRA fails.
    """
    # The planners import toppra (~2 s with scipy.interpolate and matplotlib):
    # ccopt.feed.plan loads on the first plan, as the names in _LAZY do.
    plan = importlib.import_module("ccopt.feed.plan").plan_feed
    return plan(toolpath, limits, planner=planner, junction_deviation=junction_deviation,
                grid=grid, ts=ts)


__all__ = [
    "PLANNERS",
    "AxisLimits",
    "ExactPath",
    "certified_planner",
    "FeedError",
    "FeedProfile",
    "FeedSamples",
    "GridOptions",
    "JerkProfile",
    "feed_limited_time",
    "plan_feed",
    "plan_jerk",
    "plan_junction",
    "plan_stop_per_block",
    "plan_toppra",
    "planner_function",
]
