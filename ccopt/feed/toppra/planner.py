"""Time-optimal feed by TOPPRA (the ``toppra`` package) on the exact path.

One TOPPRA instance runs over the whole path, on gridpoints from
:mod:`ccopt.feed.grid`, with the constraints of
:mod:`ccopt.feed.toppra.constraints` and toppra's ``seidel`` solver. Stops
(tangent breaks, dwells) are imposed as a zero speed cap at their gridpoint,
which is equivalent to planning each piece between stops from rest to rest.
The output is parametrised with constant acceleration between gridpoints
(toppra's ``ParametrizeConstAccel``; its default ``ParametrizeSpline``
overshoots the limits between gridpoints).

The axis limits hold all along the path, not only at the gridpoints:
accelerations are checked at the ends and three interior points of every
interval, against limits shrunk on curved intervals by the residual defect
between checks (:class:`IntervalAxisAccelerationConstraint`), and velocities
against each interval's largest ``|q_j'|`` (:class:`IntervalAxisVelocityConstraint`);
the derivation is in :mod:`ccopt.feed.grid`. On lines both are exact.

The gridpoints include the switch points of both baseline planners
(:func:`ccopt.feed.baselines.baseline_knot_positions`): every baseline
profile is then feasible for the discretised problem, so the TOPPRA profile,
the largest feasible speed at every gridpoint, is never slower than either
(up to toppra's own margin: its forward pass lowers each squared speed by
``1e-8``, a few ``1e-7`` of the duration at most).

Two numerical matters, both from toppra's absolute tolerances: the problem
is posed in a time unit where squared cruise speeds are about 1
(:func:`speed_scale`, :func:`build_constraints`), and
:class:`StoppingTOPPRA` puts back controllable-set ends that rounding pushed
across each other next to zero-speed gridpoints.
"""
from __future__ import annotations

import logging
import math

import numpy as np

from ccopt.feed.baselines import baseline_knot_positions, segment_budgets
from ccopt.feed.toppra.constraints import (
    AxisAccelerationConstraint,
    AxisVelocityConstraint,
    CentripetalAccelerationConstraint,
    PathSpeedConstraint,
    TangentialAccelerationConstraint,
)
from ccopt.feed.errors import FeedError
from ccopt.feed.grid import (GridOptions, interval_samples, interval_speed_peaks, refine,
                             residual_margins)
from ccopt.feed.grid import gridpoints as make_gridpoints
from ccopt.feed.junction import boundary_speed_caps
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.profile import FeedProfile
from ccopt.feed.toppra.library import TOPPRA, ParameterizationReturnCode
from ccopt.tolerances import CROSSING_TOL

#: Relative lowerings of the current squared speed tried when a forward step's
#: LP fails on rounding (0 first: most steps need none).
FORWARD_RETRY = (0.0, 1e-12, 1e-9, 1e-6)

#: The weight of the path acceleration ``u`` in the objective of toppra's
#: backward step (toppra's own constant: its step maximises ``x`` with this
#: tie-break on ``u``; the pass solves the same LPs).
BACKWARD_U_WEIGHT = 1e-9

#: toppra's own logger of the backward pass, which warns as toppra's pass does
_TOPPRA_LOG = logging.getLogger("toppra.algorithm.reachabilitybased.reachability_algorithm")


class StoppingTOPPRA(TOPPRA):
    """toppra's TOPPRA with one numerical guard for paths that stop on the way.

    At a gridpoint whose speed is pinned to 0 the controllable set is
    ``[0, 0]``, and the one-step LPs next to it come out at rounding level
    on the wrong side: an upper end of ``-1e-14`` (the forward pass then takes
    the square root of a negative ``x`` and fails with ``ErrUnknown``) or a
    lower end a few ``1e-14`` above the upper one (toppra then reports the
    instance as not controllable, ``FailUncontrollable``). Ends off by no
    more than rounding (:data:`CROSSING_TOL` relative) are put back: the
    upper end to 0, the lower end to the upper one. Nothing else of the
    algorithm changes.
    """

    def compute_controllable_sets(self, sdmin: float, sdmax: float) -> np.ndarray:
        """toppra's backward pass (``TOPPRA.compute_controllable_sets``) with
        :meth:`_one_step`'s guard (:func:`_uncrossed`): the same two LPs per
        gridpoint with the same numbers, in the same order (the solver warm
        starts each from the last), without the arrays toppra's step makes and
        checks each time (most of the pass's time: each LP takes microseconds).
        ``sdmin``, ``sdmax``: the final path speed's bounds (time unit of the
        problem); returns ``K``, shape ``(N + 1, 2)``, squared speeds."""
        assert sdmin <= sdmax and 0 <= sdmin
        N = self._N
        K = np.zeros((N + 1, 2))
        K[N] = [sdmin ** 2, sdmax ** 2]
        wrapper = self.solver_wrapper
        solve = wrapper.solve_stagewise_optim
        upper = np.zeros(wrapper.get_no_vars())
        upper[0], upper[1] = BACKWARD_U_WEIGHT, -1
        lower = -upper
        lo_next, hi_next = K[N].tolist()
        wrapper.setup_solver()
        for i in range(N - 1, -1, -1):
            if math.isnan(lo_next) or math.isnan(hi_next):
                lo = hi = math.nan
            else:
                hi = solve(i, None, upper, math.nan, math.nan, lo_next, hi_next)[1]
                lo = solve(i, None, lower, math.nan, math.nan, lo_next, hi_next)[1]
                if hi < 0.0 or lo > hi:  # rare: only then pay for the checks
                    lo, hi = _uncrossed(lo, hi, hi_next)
            if lo < 0:
                lo = 0.0
            K[i, 0], K[i, 1] = lo, hi
            if math.isnan(lo) or math.isnan(hi):
                _TOPPRA_LOG.warning("A numerical error occurs: The controllable set at step "
                                    "[%d / %d] can't be computed.", i, N + 1)
                return K
            lo_next, hi_next = lo, hi
        wrapper.close_solver()
        return K

    def forward_without_margin(self, x_start: float, K: np.ndarray) -> np.ndarray | None:
        """The greedy forward pass again, on toppra's controllable sets ``K``,
        without toppra's safety margin.

        toppra lowers every next squared speed to ``max(x - 1e-8, 0.9999 x)``
        so rounding cannot push it out of the controllable set; near stops,
        where ``x`` is small, that is 0.01 % per gridpoint and adds up to a
        measurable loss of time (1.3e-6 of the cycle on a random contour,
        enough to be slower than a stop-per-block trapezoid that is exactly
        optimal there). Here the next speed is only clamped into
        ``K[i+1]``; a step whose LP fails is retried from a speed lowered by
        :data:`FORWARD_RETRY` (relative). Returns the squared speeds, or
        ``None`` when a step cannot be solved (the caller keeps toppra's).

        Each step is the LP of toppra's ``_forward_step`` (objective
        ``(-2 delta_i, -1)``), solved with the same numbers as Python floats,
        not through the arrays toppra's step makes each time.
        """
        N = self.solver_wrapper.get_no_stages()
        deltas = self.solver_wrapper.get_deltas()
        solve = self.solver_wrapper.solve_stagewise_optim
        objective = np.zeros((N, self.solver_wrapper.get_no_vars()))
        objective[:, 0] = -2 * deltas[:N]
        objective[:, 1] = -1
        step = (2.0 * deltas[:N]).tolist()
        bounds = K.tolist()
        xs = [float(x_start)] + [0.0] * N
        self.solver_wrapper.setup_solver()
        try:
            for i in range(N):
                lo_next, hi_next = bounds[i + 1]
                for shrink in FORWARD_RETRY:
                    x = xs[i] * (1.0 - shrink)
                    u = math.nan if math.isnan(x) else \
                        solve(i, None, objective[i], x, x, lo_next, hi_next)[0]
                    if not math.isnan(u):
                        xs[i] = x
                        break
                else:
                    return None
                xs[i + 1] = min(hi_next, max(lo_next, xs[i] + step[i] * u))
        finally:
            self.solver_wrapper.close_solver()
        return np.array(xs)


def _uncrossed(lo, hi, hi_next: float):
    """``(lo, hi)``, a controllable set's ends, put back where rounding pushed
    them across (:class:`StoppingTOPPRA`): an upper end below 0 by no more than
    :data:`CROSSING_TOL` relative to ``hi_next`` (the next set's upper end) to
    0, then a lower end above the upper one by no more than that to it."""
    tol = CROSSING_TOL * max(1.0, abs(hi_next))
    if -tol <= hi < 0.0:
        hi = 0.0
    if hi < lo <= hi + tol:
        lo = hi
    return lo, hi


class IntervalAxisVelocityConstraint(AxisVelocityConstraint):
    """Per-axis velocity limits ``v`` held all along each grid interval, not
    only at its ends: ``x`` at a gridpoint at most ``v_j^2 / G_j^2`` with
    ``G_j`` the largest ``|q_j'|`` of both intervals around it
    (:func:`ccopt.feed.grid.interval_speed_peaks`; ``x`` is linear between
    gridpoints). On lines the same as :class:`AxisVelocityConstraint`."""

    samples = None   # IntervalSamples of the planner's grid, shared with the acceleration rows

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        out = list(super().compute_constraint_params(path, gridpoints, *args, **kwargs))
        peak = interval_speed_peaks(_samples(self.samples, path, gridpoints))
        with np.errstate(divide="ignore"):
            x = np.where(peak > 0, (self.v / np.where(peak > 0, peak, 1.0)) ** 2, np.inf).min(axis=1)
        upper = out[6][:, 1].copy()
        upper[:-1] = np.minimum(upper[:-1], x)
        upper[1:] = np.minimum(upper[1:], x)
        out[6] = np.column_stack([np.zeros_like(upper), upper])
        return tuple(out)


class IntervalAxisAccelerationConstraint(AxisAccelerationConstraint):
    """Per-axis acceleration limits ``a`` held all along each grid interval.

    For stage ``i`` the rows are ``|P(tau) u_i + Q(tau) x_i| <= a (1 - m_i)``
    at both ends and at :data:`ccopt.feed.grid.INTERIOR_CHECKS` of the
    interval (``P``, ``Q``: :attr:`ccopt.feed.grid.IntervalSamples.accel_rows`),
    ``m_i`` the residual margin of :func:`ccopt.feed.grid.residual_margins`
    (0 on lines), which bounds the excess between the checks. ``x_cap``: the
    squared speed caps at the gridpoints (programmed feed), in the
    constraint's units, which with the axis velocities bound ``x_i`` there.
    """

    samples = None   # as IntervalAxisVelocityConstraint.samples

    def __init__(self, a, v, cap):
        super().__init__(a)
        self.v = np.asarray(v, dtype=float)
        self.cap = np.asarray(cap, dtype=float)

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        gridpoints = np.asarray(gridpoints, dtype=float)
        smp = _samples(self.samples, path, gridpoints)
        q1 = path.eval_sided(gridpoints, 1, "right")
        with np.errstate(divide="ignore"):
            x_vel = np.where(np.abs(q1) > 0, (self.v / np.where(np.abs(q1) > 0, np.abs(q1), 1.0))
                             ** 2, np.inf).min(axis=1)
        margin = residual_margins(smp, self.a, np.minimum(np.square(self.cap), x_vel))
        P, Q = smp.accel_rows
        scale = (1.0 / (1.0 - margin))[:, None, :]
        n, d, k = gridpoints.size, self.dof, smp.checks.size
        a = np.empty((n, k * d))
        b = np.empty((n, k * d))
        a[:-1] = (P[:, smp.checks] * scale).reshape(n - 1, k * d)
        b[:-1] = (Q[:, smp.checks] * scale).reshape(n - 1, k * d)
        # the last gridpoint has no stage: its rows repeat its own point
        a[-1] = np.tile(path.eval_sided(gridpoints[-1:], 1, "left")[0], k)
        b[-1] = np.tile(path.eval_sided(gridpoints[-1:], 2, "left")[0], k)
        eye = np.eye(k * d)
        F = np.vstack([eye, -eye])
        g = np.tile(self.a, 2 * k)
        return a, b, np.zeros_like(a), F, g, None, None


def _samples(given, path, gridpoints):
    """The :class:`~ccopt.feed.grid.IntervalSamples` of ``gridpoints``: from
    ``given`` (``(gridpoints, samples)`` computed once by the planner for both
    constraints) when it is of the same gridpoints, else computed here."""
    gp = np.asarray(gridpoints, dtype=float)
    if given is not None and np.array_equal(given[0], gp):
        return given[1]
    return interval_samples(path, gp)


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


def speed_scale(path: ExactPath, v_caps: np.ndarray) -> float:
    """Reference speed (units/s) for :func:`build_constraints`: the largest
    budget speed (:func:`ccopt.feed.baselines.segment_budgets`) of the feed
    moves, a cruise speed the cut really reaches (of the rapids only when
    there is nothing else): cutting, where the time goes, then runs at
    squared speeds of order 1."""
    ok = np.isfinite(v_caps) & (v_caps > 0)
    feed = ok & np.isfinite(path.feeds)
    pick = v_caps[feed] if feed.any() else v_caps[ok]
    return float(pick.max()) if pick.size else 1.0


def build_constraints(path: ExactPath, limits: AxisLimits, cap: np.ndarray,
                      scale: float = 1.0) -> list:
    """The toppra constraint list for ``path`` under ``limits`` and speed caps ``cap``.

    With ``scale`` the problem is posed in time units of ``1/scale`` seconds:
    speeds divided by ``scale``, accelerations by ``scale^2``, so squared path
    speeds are at most about 1. toppra's seidel solver works with absolute
    tolerances (``1e-10`` on coefficients, ``1e-8`` on feasibility) that
    suit squared speeds of order 1, not the ``1e4`` of mm/s; the solution
    ``sd`` is then in units of ``scale``. (Squared speeds much below 1 are
    not wanted either: toppra's forward pass lowers each one by ``1e-8`` as
    a safety margin, which costs ``1e-8 / x`` of the time spent at ``x``.)
    """
    v, a = limits.in_plane(path.frame, path.dof)
    s2 = scale * scale
    out = [IntervalAxisVelocityConstraint(v / scale),
           IntervalAxisAccelerationConstraint(a / s2, v / scale, cap / scale),
           PathSpeedConstraint(cap / scale, path.dof)]
    if limits.tangential_acc is not None:
        out.append(TangentialAccelerationConstraint(limits.tangential_acc / s2, path.dof))
    if limits.centripetal_acc is not None:
        out.append(CentripetalAccelerationConstraint(limits.centripetal_acc / s2, path.dof))
    return out


def plan_toppra(path: ExactPath, limits: AxisLimits, *, junction_deviation: float | None = None,
                grid: GridOptions | None = None) -> FeedProfile:
    """Time-optimal profile of ``path`` under ``limits`` (see the module docstring).

    Raises :class:`FeedError` naming the block where TOPPRA failed when its
    return code is not ``Ok``.
    """
    grid = GridOptions() if grid is None else grid
    if not path.segments:
        return FeedProfile.empty(path, limits, "toppra")
    v, a = limits.in_plane(path.frame, path.dof)
    budgets = segment_budgets(path, limits)
    gp = make_gridpoints(path, v, a, grid, (limits.tangential_acc, limits.centripetal_acc))
    if grid.baseline_knots:
        gp = refine(gp, baseline_knot_positions(path, limits, junction_deviation, budgets),
                    grid.min_spacing)
    cap = speed_caps(path, gp, a, junction_deviation)
    scale = speed_scale(path, budgets[0])
    constraints = build_constraints(path, limits, cap, scale)
    shared = (gp, interval_samples(path, gp))
    for c in constraints[:2]:
        c.samples = shared
    algo = StoppingTOPPRA(constraints, path, gridpoints=gp,
                          solver_wrapper="seidel", parametrizer="ParametrizeConstAccel")
    # toppra's controllable sets, then the greedy pass from rest without its
    # margin (forward_without_margin), which dominates toppra's own pass at
    # every gridpoint: toppra's pass (as long again) is run only where ours
    # cannot step, and then its profile is the one kept, as before
    K = algo.compute_controllable_sets(0.0, 0.0)
    xs = None
    if not np.isnan(K).any() and K[0, 0] <= 0.0 <= K[0, 1]:
        xs = algo.forward_without_margin(0.0, K)
    if xs is not None:
        sd = np.sqrt(np.maximum(xs, 0.0))
    else:
        _, sd, _, K = algo.compute_parameterization(0.0, 0.0, return_data=True)
        code = algo.problem_data.return_code
        if code != ParameterizationReturnCode.Ok or sd is None or np.isnan(sd).any():
            where = _failure_position(gp, sd, K)
            raise FeedError(f"TOPPRA failed ({code.value}) near s = {where:.6g} of "
                            f"{path.length:.6g}", path.source_file, path.block_line(where))
    # Where a stop was imposed (cap 0) the speed is 0, not the square root of
    # a rounding residue of toppra's squared speed.
    sd = np.where(cap == 0.0, 0.0, sd * scale)
    info = {"gridpoints": int(gp.size), "return_code": ParameterizationReturnCode.Ok.name,
            "time_scale": scale,
            "junction_deviation": junction_deviation if junction_deviation else 0.0}
    return FeedProfile.from_path_velocity(path, limits, "toppra", gp, sd, info)


def _failure_position(gp, sd, K) -> float:
    if K is not None and np.isnan(K).any():
        return float(gp[int(np.flatnonzero(np.isnan(K).any(axis=1)).max())])
    if sd is not None and np.isnan(sd).any():
        return float(gp[int(np.flatnonzero(np.isnan(sd))[0])])
    return float(gp[0])
