"""What no planner can beat on a path: the feed-limited time.

A smoother or a blend changes the path a little; how much cycle time it can
buy is bounded by the time the path takes with no acceleration limit at all.
On each segment the machine can move no faster than

- its programmed feed ``F`` along the path (tangential speed cap, units/s;
  rapids have none), so the segment takes at least ``S / F`` for its 3-D
  length ``S = hypot(L, dw)`` (``w`` linear in the in-plane length ``L``);
- each axis's velocity limit ``V_i``, so at least ``|d_i| / V_i`` for the
  axis's net displacement ``d_i`` (the displacement is at most the integral
  of the axis speed);

and a dwell takes its seconds. The sum of the larger of these per segment is
a lower bound of every planner's duration (TOPPRA's, the baselines') under
the same limits; how far above it a planner lands is the time lost to
acceleration, at corners, stops and the ends.
"""
from __future__ import annotations

import math

from ccopt.feed.limits import AxisLimits
from ccopt.toolpath import Role, ToolPath


def feed_limited_time(toolpath: ToolPath, limits: AxisLimits) -> float:
    """Lower bound (seconds) of the cycle time of ``toolpath`` under ``limits``.

    See the module docstring. ``ValueError`` when the path moves an axis the
    limits do not give (as :meth:`AxisLimits.in_plane`).
    """
    moves_w = any(s.w1 != s.w0 for s in toolpath.segments)
    v_axis, _ = limits.in_plane(toolpath.plane, 3 if moves_w else 2)
    t = sum(seconds for _, seconds, _ in toolpath.dwells)
    for s in toolpath.segments:
        (u0, v0), (u1, v1) = s.start, s.end
        disp = (u1 - u0, v1 - v0, s.w1 - s.w0)[: len(v_axis)]
        t_axes = max(abs(d) / float(vmax) for d, vmax in zip(disp, v_axis))
        t_feed = 0.0
        if s.feed is not None and s.role is not Role.RAPID:
            t_feed = math.hypot(s.length, s.w1 - s.w0) / s.feed
        t += max(t_axes, t_feed)
    return t
