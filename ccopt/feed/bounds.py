"""What no planner can beat on a path: the feed-limited time.

A smoother or a blend changes the path a little; how much cycle time it can
buy is bounded by the time the path takes with no acceleration limit at all.
On each segment the machine can move no faster than

- its programmed feed ``F`` along the path (tangential speed cap, units/s;
  rapids have none), so the segment takes at least ``S / F`` for its 3-D
  length ``S = hypot(L, dw)`` (``w`` linear in the in-plane length ``L``);
- each axis's velocity limit ``V_i``, so at least ``T_i / V_i`` for the
  axis's travel ``T_i`` along the segment (the integral of the axis speed):
  exact on lines and arcs (an arc's ``u`` travel is ``R`` times the total
  variation of ``cos`` over its sweep, e.g. ``4 R`` on a full circle), the
  net displacement on other curves (a lower bound of their travel);

and a dwell takes its seconds. The sum of the larger of these per segment is
the least time of the exact, continuous problem under the same limits; how
far above it a planner lands is the time lost to acceleration, at corners,
stops and the ends.

The planners impose the feed exactly (their speed is monotone between
gridpoints, and a gridpoint on a segment boundary takes the smaller cap), so
no planner beats the feed term. TOPPRA imposes the axis velocity limits at
its gridpoints only and may exceed them between by the grid's stated margin
(:mod:`ccopt.feed.grid`: at most ~5e-3, seen ~2e-4): on a stretch where an
axis runs at its limit throughout, a long chain of arcs, TOPPRA can finish
that fraction below the axis term.

Segments shorter than :data:`~ccopt.tolerances.POINT_EPS` in 3-D are left
out, as :class:`~ccopt.feed.path.ExactPath` leaves them out.
"""
from __future__ import annotations

import math

from ccopt.feed.limits import AxisLimits
from ccopt.geometry import Arc
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role, ToolPath


def _travel_cos(theta0: float, sweep: float) -> float:
    """Total variation of ``cos`` over ``[theta0, theta0 + sweep]`` (radians, either sign)."""
    a, b = sorted((theta0, theta0 + sweep))
    # cos is monotone between consecutive multiples of pi
    k0, k1 = math.floor(a / math.pi) + 1, math.ceil(b / math.pi) - 1
    stops = [a] + [k * math.pi for k in range(k0, k1 + 1)] + [b]
    return sum(abs(math.cos(y) - math.cos(x)) for x, y in zip(stops[:-1], stops[1:]))


def axis_travel(geom) -> tuple[float, float]:
    """In-plane ``(u, v)`` travel of a segment's geometry (program units): exact
    for :class:`Line` and :class:`Arc`, the net displacement otherwise."""
    if isinstance(geom, Arc):
        R = geom.radius
        return (R * _travel_cos(geom.theta0, geom.sweep),
                R * _travel_cos(geom.theta0 - 0.5 * math.pi, geom.sweep))   # sin = cos(. - pi/2)
    (u0, v0), (u1, v1) = geom.start, geom.end
    return abs(u1 - u0), abs(v1 - v0)


def feed_limited_time(toolpath: ToolPath, limits: AxisLimits) -> float:
    """The feed-limited time of ``toolpath`` under ``limits`` (seconds).

    See the module docstring for what it bounds. ``ValueError`` when the path
    moves an axis the limits do not give (as :meth:`AxisLimits.in_plane`).
    """
    segs = [s for s in toolpath.segments if math.hypot(s.length, s.w1 - s.w0) > POINT_EPS]
    several = len({s.plane for s in segs}) > 1     # then every section moves its w axis
    moves_w = several or any(s.w1 != s.w0 for s in segs)
    v_axes = {p: limits.in_plane(p, 3 if moves_w else 2)[0] for p in {s.plane for s in segs}}
    t = float(sum(seconds for _, seconds, _ in toolpath.dwells))
    for s in segs:
        v_axis = v_axes[s.plane]            # the limits of the axes this segment moves
        travel = (*axis_travel(s.geom), abs(s.w1 - s.w0))[: len(v_axis)]
        t_axes = max(d / float(vmax) for d, vmax in zip(travel, v_axis))
        t_feed = 0.0
        if s.feed is not None and s.role is not Role.RAPID:
            t_feed = math.hypot(s.length, s.w1 - s.w0) / s.feed
        t += max(t_axes, t_feed)
    return t


__all__ = ["axis_travel", "feed_limited_time"]
