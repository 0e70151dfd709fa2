"""Time-optimal feed by TOPPRA (the ``toppra`` package) on the exact path.

One TOPPRA instance runs over the whole path, on gridpoints from
:mod:`ccopt.feed.grid`, with the constraints of
:mod:`ccopt.feed.constraints` and toppra's ``seidel`` solver. Stops
(tangent breaks, dwells) are imposed as a zero speed cap at their gridpoint,
which is equivalent to planning each piece between stops from rest to rest.
The output is parametrised with constant acceleration between gridpoints
(toppra's ``ParametrizeConstAccel``; its default ``ParametrizeSpline``
overshoots the limits between gridpoints).

The gridpoints include the switch points of both baseline planners
(:func:`ccopt.feed.baselines.baseline_knot_positions`): every baseline
profile is then feasible for the discretised problem, so the TOPPRA profile,
the largest feasible speed at every gridpoint, is never slower than either.
"""
from __future__ import annotations

import logging

import numpy as np
from toppra.algorithm import TOPPRA
from toppra.algorithm.algorithm import ParameterizationReturnCode

from ccopt.feed.constraints import (
    AxisAccelerationConstraint, AxisVelocityConstraint, CentripetalAccelerationConstraint,
    PathSpeedConstraint, TangentialAccelerationConstraint,
)
from ccopt.feed.errors import FeedError
from ccopt.feed.baselines import baseline_knot_positions
from ccopt.feed.grid import GridOptions, gridpoints as make_gridpoints, refine
from ccopt.feed.junction import boundary_speed_caps
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.profile import FeedProfile

logger = logging.getLogger(__name__)


def speed_caps(path: ExactPath, gridpoints: np.ndarray, a_axis,
               junction_deviation: float | None = None) -> np.ndarray:
    """Path speed cap (units/s) at each gridpoint: the programmed feed of both
    sides (``inf`` on rapids), and the boundary caps of
    :func:`ccopt.feed.junction.boundary_speed_caps` where a gridpoint is a
    segment boundary."""
    cap = np.minimum(path.feeds[path.locate(gridpoints, "left")],
                     path.feeds[path.locate(gridpoints, "right")])
    b = np.searchsorted(gridpoints, path.offsets)
    on = (b < gridpoints.size) & (gridpoints[np.minimum(b, gridpoints.size - 1)] == path.offsets)
    if not np.all(on):
        raise AssertionError("a segment boundary is not a gridpoint")
    cap[b] = np.minimum(cap[b], boundary_speed_caps(path, a_axis, junction_deviation))
    return cap


def build_constraints(path: ExactPath, limits: AxisLimits, cap: np.ndarray) -> list:
    """The toppra constraint list for ``path`` under ``limits`` and speed caps ``cap``."""
    v, a = limits.in_plane(path.toolpath.plane, path.dof)
    out = [AxisVelocityConstraint(v), AxisAccelerationConstraint(a),
           PathSpeedConstraint(cap, path.dof)]
    if limits.tangential_acc is not None:
        out.append(TangentialAccelerationConstraint(limits.tangential_acc, path.dof))
    if limits.centripetal_acc is not None:
        out.append(CentripetalAccelerationConstraint(limits.centripetal_acc, path.dof))
    return out


def plan_toppra(path: ExactPath, limits: AxisLimits, *, junction_deviation: float | None = None,
                grid: GridOptions = GridOptions()) -> FeedProfile:
    """Time-optimal profile of ``path`` under ``limits`` (see the module docstring).

    Raises :class:`FeedError` naming the block where TOPPRA failed when its
    return code is not ``Ok``.
    """
    if not path.segments:
        return FeedProfile.empty(path, limits, "toppra")
    v, a = limits.in_plane(path.toolpath.plane, path.dof)
    gp = make_gridpoints(path, v, a, grid)
    if grid.baseline_knots:
        gp = refine(gp, baseline_knot_positions(path, limits, junction_deviation), grid.min_spacing)
    cap = speed_caps(path, gp, a, junction_deviation)
    algo = TOPPRA(build_constraints(path, limits, cap), path, gridpoints=gp,
                  solver_wrapper="seidel", parametrizer="ParametrizeConstAccel")
    _, sd, _, K = algo.compute_parameterization(0.0, 0.0, return_data=True)
    code = algo.problem_data.return_code
    if code != ParameterizationReturnCode.Ok or sd is None or np.isnan(sd).any():
        where = _failure_position(gp, sd, K)
        raise FeedError(f"TOPPRA failed ({code.value}) near s = {where:.6g} of "
                        f"{path.length:.6g}", path.source_file, path.block_line(where))
    info = {"gridpoints": int(gp.size), "return_code": code.name,
            "junction_deviation": junction_deviation if junction_deviation else 0.0}
    return FeedProfile.from_path_velocity(path, limits, "toppra", gp, sd, info)


def _failure_position(gp, sd, K) -> float:
    if K is not None and np.isnan(K).any():
        return float(gp[int(np.flatnonzero(np.isnan(K).any(axis=1)).max())])
    if sd is not None and np.isnan(sd).any():
        return float(gp[int(np.flatnonzero(np.isnan(sd))[0])])
    return float(gp[0])
