"""Jerk-limited time-optimal feed (planner ``jerk``): a pseudo-jerk LP in windows.

The problem. Along the exact path ``q(s)`` (arc length ``s``, ``|q'| = 1``)
find ``s(t)`` from rest to rest, stopping at tangent breaks and dwells, of
least duration, under the axis limits (plane order, axis ``i``)::

    |q_i' s'|                                    <= V_i      velocity
    |q_i' s'' + q_i'' s'^2|                      <= A_i      acceleration
    |q_i''' s'^3 + 3 q_i'' s' s'' + q_i' s'''|   <= J_i      jerk
    s' <= F (programmed feed), |s''| <= a_t, |q''| s'^2 <= a_n  (optional path limits)

Formulation: squared speed ``b(s) = s'^2`` and path acceleration
``alpha(s) = s'' = b'/2`` as functions of ``s`` on gridpoints ``s_k``. The
axis acceleration is linear in ``(b, alpha)``; the jerk is
``s' * (q''' b + 3 q'' alpha + q' alpha')`` (``s''' = s' alpha'``), linear but
for the factor ``s' = sqrt(b)``. That factor is replaced by ``sqrt(bhat)``, a
bound on the speed (the *pseudo-jerk* linearisation): first ``bhat`` is the
speed of straight motion from the nearest stop under the acceleration and
jerk the axes allow along the tangent, capped by the box bound on ``b`` (axis
velocities, feed, the caps at curvature breaks), on a window from rest to
rest (:func:`~ccopt.feed.jerk.windows.rest_bound`; ``b`` is capped by the box
bound there), or on the overlapping windows of a stretch with
no stop the TOPPRA solution (acceleration-limited, so an upper bound of every
feasible speed, which also keeps a window's kept end able to brake for what
lies beyond it), then ``bhat`` is updated to the geometric mean of itself and the LP's
new ``b`` until the two agree within
:data:`~ccopt.feed.jerk.windows.BHAT_TOL` (relative, on ``b``), or the
window's duration settles (:data:`~ccopt.feed.jerk.windows.DURATION_TOL`),
at most :data:`~ccopt.feed.jerk.windows.MAX_ROUNDS` rounds; a last round
imposes ``b <= bhat`` so that ``sqrt(b) <= sqrt(bhat)`` and the jerk bound
holds exactly at the gridpoints, and that round's solution is the profile
(where HiGHS would take long over it, ``bhat`` is first raised to the last
``b`` where that rose above it: :func:`~ccopt.feed.jerk.windows.solve_rounds`).
The objective is the duration ``sum h / sqrt(b)`` linearised at ``bhat``:
maximise ``sum h b / bhat^(3/2)``. Each round is one LP solved by HiGHS's
simplex (``highspy``, ranged rows). A jerk row divided by its
``sqrt(bhat)`` is a fixed row whose bounds move, so a window's LP is built
once and each round starts from the last one's basis
(:class:`~ccopt.feed.jerk.lp.WindowLP`).

Between gridpoints the model is exact, so the profile the samples show is the
one the LP constrained:

- an interval whose ends both move has ``alpha`` linear in ``s``: ``b`` is
  quadratic, ``b_k+1 - b_k = h (alpha_k + alpha_k+1)`` (a linear equality),
  the path jerk is ``s' (alpha_k+1 - alpha_k) / h``, and the axis acceleration
  and jerk are imposed at both ends with the interval's own one-sided
  derivatives;
- an interval that starts at rest is a constant-jerk piece in time
  (``s = sigma t^3 / 6``, ``alpha`` grows like ``s^(1/3)``, which no
  polynomial in ``s`` does): with ``v1`` the speed at its other end,
  ``alpha_1 = 2 b_1 / (3 h)`` (linear), duration ``3 h / v1`` and jerk
  ``sigma = v1 * 2 b_1 / (9 h^2)``, imposed as ``sqrt(bhat_1) * 2 b_1 / (9 h^2)``;
  an interval that ends at rest is its mirror image.

On an interval whose curvature changes along it (a blend curve, a spiral)
the jerk is also imposed at a quarter, half and three quarters of its length,
where the model is linear in the unknowns too
(:func:`~ccopt.feed.jerk.lp._inner_rows`): there every factor of the jerk
varies along the interval and it bulged 0.87 % over the limit between
gridpoints that both met it. With these rows such curves need far fewer
gridpoints than TOPPRA's (:data:`JERK_GRID`).

What is checked only at gridpoints, and its margin: the axis acceleration on
curved segments (as TOPPRA's, :mod:`ccopt.feed.grid`, whose gridpoints are
used) and the speed and jerk where ``alpha`` changes sign inside a curved
interval (``b`` then peaks inside, above its ends by at most ``alpha_k^2 h /
|alpha_k+1 - alpha_k|``: second order in the grid spacing); the tests sample
at 10 kHz and hold every limit to the certificate's tolerance, 0.1 %
(:data:`ccopt.verify.limits.LIMITS_TOL`; on the bundled cases the jerk
reaches 1 + 1.9e-4 and the feed 1 + 2.8e-4). On a straight interval that
peak is covered exactly where it would break the jerk limit
(:meth:`~ccopt.feed.jerk.lp.WindowLP.peaks_over`: the row's speed factor
raised by the largest rise the row allows, and the window solved again).
On a curved interval the planner checks the axis jerk of its own solution at
seven inner points (:func:`~ccopt.feed.jerk.refine.jerk_over_inside`) and
splits every interval over the limit there by more than
:data:`~ccopt.feed.jerk.refine.REFINE_TOL` into as many pieces as the
square root of its excess over that tolerance asks (the excess is second
order in the spacing), then plans around them again: a window a little
beyond them with its ends held at the last plan's state
(:func:`~ccopt.feed.jerk.refine.replan_locally`), or their whole stretch
where no such window is feasible short of its stops (at most
:data:`~ccopt.feed.jerk.refine.MAX_PASSES` passes; ``info``
counts ``refined_intervals``, ``refine_passes`` and what is left over,
``jerk_over_inside``). Without it, the small corner arcs of bench/feed.py's
pocket went 14 % over the jerk limit between gridpoints that all met it, and
twelve tangent quarter arcs planned in windows of 100 gridpoints 0.1 %
(tests/feed/test_jerk_windows.py).

Where the loss is: inside an interval the path jerk grows with ``s'``, so a
jerk-limited stretch uses its limit only at the faster end. Near each stop the
grid is refined geometrically (:data:`STOP_RATIO`) over the first jerk phase,
where ``s'`` changes fastest relative to itself.

Curvature breaks (line into arc, arc into arc, tangent-continuous): the axis
acceleration jumps by ``(q''_right - q''_left) b`` there, an infinite jerk for
any speed above 0. Controllers that interpolate the path every ``Ts`` seconds
see that jump spread over one period, so it is bounded by
``|Delta q_i''| b <= J_i Ts`` (``ts``, default :data:`DEFAULT_TS` = 1 ms):
a speed cap at the break. The samples' jerk is the jerk inside pieces; these
steps are bounded by this rule instead.

Windows (:mod:`ccopt.feed.jerk.windows`): the path is cut at its stops
(exactly: the pieces between stops are independent), and the pieces are
gathered into windows of about :data:`~ccopt.feed.jerk.windows.BATCH_POINTS`
gridpoints, each solved as its own LP, so the cost grows linearly with the
length of the program. A stretch between two stops with more gridpoints than
that is planned in overlapping windows: a window plans
:data:`~ccopt.feed.jerk.windows.WINDOW_OVERLAP` of its size further than it
keeps, and the next starts from the kept end's ``(b, alpha)`` with the last
``bhat`` of the one before on their overlap (with a fresh ``bhat`` from
TOPPRA's speed that state can be infeasible: the jerk rows at the start
tighten); ``b`` stays under TOPPRA's speed there, so the braking it still
needs is within reach. A window that is infeasible all the same is merged
with the one before (``info["merged_windows"]``).
Windows that start at a stop are independent of those before: on a long
program they are solved in several processes (``info["workers"]``), where
each task also computes TOPPRA's bound on its own stretch, stop to stop
(:mod:`ccopt.feed.jerk.speed_bound`), rather than one TOPPRA over the whole path
running alone first; on a shorter one in threads of this process
(``info["threads"]``: HiGHS releases the GIL while it solves), as are the
refinement's re-plans, stretch by stretch. Each window is solved from the same
data either way, so the profile does not depend on how many.

Last, on every stretch between two stops the profile is the faster of the
LP's and the jerk-limited stop baseline's (an S-curve per block: feasible,
and exactly optimal on a lone straight block, where the LP loses a few 1e-3
to its grid), so the planner is never slower than that baseline.
"""
from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ccopt.feed.baselines import scurve_pieces
from ccopt.feed.errors import FeedError
from ccopt.feed.grading import Ramps
from ccopt.feed.grid import GridOptions, gridpoints
from ccopt.feed.jerk.lp import (FROM_REST, INNER_POINTS, SLINEAR, TO_REST, JerkGrid,
                                piece_times)
from ccopt.feed.jerk.profile import CUBIC, JerkProfile, slinear_time
from ccopt.feed.jerk.refine import (MAX_PASSES, jerk_over_inside, profile_at, replan_locally,
                                   split_points)
from ccopt.feed.jerk.profile import SLINEAR as PIECE_SLINEAR
from ccopt.feed.jerk.speed_bound import StretchBound, speed_bound
from ccopt.feed.jerk.windows import grid_slice, any_chained, plan_windows, split
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.feed.planners import DEFAULT_TS
from ccopt.geometry import Line

#: The gridpoints of the LP when the caller gives none: TOPPRA's default grid
#: (:class:`~ccopt.feed.grid.GridOptions`) with 8x its budgets of curvature
#: change and bend, so blend curves and spirals get far fewer gridpoints
#: (lines and arcs, spaced by braking distance and turning angle, keep
#: theirs, but that a line with no curvature jump at its ends takes its
#: stretch's length for its braking spacing:
#: :attr:`~ccopt.feed.grid.GridOptions.stretch_lines`); the jerk inside their
#: intervals is imposed at three inner points
#: instead (:data:`~ccopt.feed.jerk.lp.INNER_POINTS`). 8x: a smoothed path's
#: cycle time a fraction of a percent above the finest grid's in a small share
#: of its time (ccopt compare and ccopt run plan it for every comparison),
#: with the jerk between gridpoints within the certificate's tolerance; fewer
#: budgets gain little time, more lose cycle time (docs/jerk.md).
JERK_GRID = GridOptions(max_curvature_change=0.4, max_curvature_bend=0.4, stretch_lines=True)
#: Whether lines and arcs are graded as TOPPRA grades them
#: (:func:`ccopt.feed.grid.gridpoints` with :class:`~ccopt.feed.grading.Ramps`,
#: their ramp zones S-curves', :func:`~ccopt.feed.grading.scurve_ramp` and
#: :func:`~ccopt.feed.grading.curved_ramp`): the even grid's spacing within
#: those zones at both ends, where the speed can change, growing
#: geometrically in between, where it is at its cap and any gridding
#: represents it exactly. bench/jerk_grid.py measures graded against even.
#: Arcs were kept even once because the axis jerk between an arc's gridpoints
#: went 0.21 % over (seed 134 of tests/feed/test_jerk_generated.py); the
#: planner now checks and splits such intervals itself (ccopt.feed.jerk.refine).
#: Lines alone gained little on generated CAM plates (their arcs, at the
#: feed, kept the even grid), and a window of seed 104 of
#: tests/feed/test_jerk_generated.py stalled (gridpoints 3.8e-9 mm from a
#: stop, now dropped: :func:`_clear_of_stops`). False: every line and arc evenly.
GRADED = True
#: Ratio of consecutive interval lengths in the geometric refinement at stops:
#: a finer ratio plans a program with many stops a few tenths of a percent
#: faster in more CPU, a coarser one slower for little saved (docs/jerk.md).
STOP_RATIO = 1.1
#: First interval at a stop, as a share of the first jerk phase's length.
STOP_FIRST = 0.02


def _stop_refinement(path: ExactPath, stops: np.ndarray, a: np.ndarray, j: np.ndarray,
                     base: np.ndarray) -> np.ndarray:
    """Extra gridpoints on both sides of every stop, at distances growing
    geometrically (ratio :data:`STOP_RATIO`) from :data:`STOP_FIRST` of the
    first jerk phase's length ``A^3 / (6 J^2)`` (largest ``A``, smallest ``J``
    of the axes, so it is long enough on every axis) to twice that length, up
    to half way to the neighbouring stops."""
    reach = 2.0 * float(a.max()) ** 3 / (6.0 * float(j.min()) ** 2)
    first = STOP_FIRST * reach / 2.0
    m = max(1, math.ceil(math.log(reach / first) / math.log(STOP_RATIO)))
    offs = first * STOP_RATIO ** np.arange(m + 1)     # so s_k+1 / s_k = STOP_RATIO
    offs = offs[offs < reach]
    pts = []
    for i, s in enumerate(stops):
        # up to half way to the neighbouring stops
        left = 0.5 * (s + stops[i - 1]) if i > 0 else s
        right = 0.5 * (s + stops[i + 1]) if i + 1 < stops.size else s
        pts.append(s - offs[s - offs > left])
        pts.append(s + offs[s + offs < right])
    extra = np.concatenate(pts) if pts else np.zeros(0)
    return np.union1d(base, extra)


def build_grid(path: ExactPath, limits: AxisLimits, ts: float,
               grid: GridOptions | None = None, extra: np.ndarray | None = None,
               previous: JerkGrid | None = None) -> JerkGrid:
    """The gridpoints and their data (see :class:`~ccopt.feed.jerk.lp.JerkGrid`);
    ``extra``: further gridpoints (path positions strictly inside intervals);
    ``previous``: a grid of the same path holding some of these gridpoints
    (the last refinement pass's), whose derivatives at them, and inside its
    intervals that are still intervals, are copied instead of evaluated again
    (the same numbers: each is evaluated at its own position alone)."""
    plane = path.frame
    v, a = limits.in_plane(plane, path.dof)
    j = limits.jerk_in_plane(plane, path.dof)
    ramps = Ramps(limits.tangential_acc, limits.centripetal_acc, j) if GRADED else None
    base = gridpoints(path, v, a, JERK_GRID if grid is None else grid, ramps)
    stop_s = np.concatenate([[0.0], path.stop_positions, [path.length]])
    s = _stop_refinement(path, stop_s, a, j, base)
    if extra is not None and extra.size:
        s = np.union1d(s, extra)
    s = _clear_of_stops(s, stop_s, (JERK_GRID if grid is None else grid).min_spacing)
    q, kept = _sided_derivatives(path, s, previous)
    stop = np.isin(s, stop_s)
    bmax = _speed_caps(path, limits, s, q, v, j, ts)
    kind = np.full(s.size - 1, SLINEAR)
    kind[stop[:-1]] = FROM_REST
    kind[stop[1:]] = TO_REST
    lone = lone_lines(path, s, stop)
    # a stretch of one interval (a segment shorter than twice the grid's least
    # spacing between two stops: a 8.1e-8 mm corner line of the Fagor G137
    # style at a near-tangent join of a 6-decimal program) has no gridpoint to
    # plan; on a straight segment the S-curve stands in, exact (lone_lines)
    if np.any(stop[:-1] & stop[1:] & ~lone):
        i = int(np.flatnonzero(stop[:-1] & stop[1:] & ~lone)[0])
        raise FeedError(f"two stops one grid interval apart at s = {s[i]:.6g}",
                        path.source_file, path.block_line(s[i]))
    a_t = limits.tangential_acc if limits.tangential_acc is not None else np.inf
    m = _inner_derivatives(path, s, previous, kept)
    return JerkGrid(s, q[0], q[1], q[2], kind, stop, bmax, a_t, a, j, *m, lone=lone)


def _sided_derivatives(path: ExactPath, s: np.ndarray, previous: JerkGrid | None):
    """``(q, kept)``: ``q`` the first three derivatives, each ``(2, N, dof)``,
    their left and right limits at the gridpoints ``s``, those ``previous``
    has copied from it; ``kept = (at, had)``, each gridpoint's index there
    and whether it is one of its gridpoints (None without ``previous``)."""
    if previous is None:
        left, right = (path.eval_sided_orders(s, (1, 2, 3), side) for side in ("left", "right"))
        return [np.stack([lo, hi]) for lo, hi in zip(left, right)], None
    at = np.minimum(np.searchsorted(previous.s, s), previous.s.size - 1)
    had = previous.s[at] == s
    q = [np.empty((2, s.size, path.dof)) for _ in range(3)]
    for qq, old in zip(q, (previous.q1, previous.q2, previous.q3)):
        qq[:, had] = old[:, at[had]]
    new = ~had
    if new.any():
        for side, name in enumerate(("left", "right")):
            for qq, got in zip(q, path.eval_sided_orders(s[new], (1, 2, 3), name)):
                qq[side, new] = got
    return q, (at, had)


def _inner_derivatives(path: ExactPath, s: np.ndarray, previous: JerkGrid | None, kept):
    """The first three derivatives at the fractions :data:`INNER_POINTS` of
    every interval of ``s``, ``(T, N, dof)`` each; an interval ``previous``
    has too (both ends its gridpoints, next to each other there) copied."""
    inner = np.asarray(INNER_POINTS)[:, None]
    if previous is None:
        x = (s[:-1] + inner * np.diff(s)).ravel()
        return [d.reshape(inner.size, s.size - 1, -1)
                for d in path.eval_sided_orders(x, (1, 2, 3), "right")]
    at, had = kept
    same = had[:-1] & had[1:] & (at[1:] == at[:-1] + 1)
    m = [np.empty((inner.size, s.size - 1, path.dof)) for _ in range(3)]
    for mm, old in zip(m, (previous.m1, previous.m2, previous.m3)):
        mm[:, same] = old[:, at[:-1][same]]
    fresh = ~same
    if fresh.any():
        x = (s[:-1][fresh] + inner * np.diff(s)[fresh]).ravel()
        for mm, got in zip(m, path.eval_sided_orders(x, (1, 2, 3), "right")):
            mm[:, fresh] = got.reshape(inner.size, int(fresh.sum()), -1)
    return m


def _clear_of_stops(s: np.ndarray, stops: np.ndarray, min_spacing: float) -> np.ndarray:
    """``s`` without the gridpoints closer than ``min_spacing`` to a stop
    (``stops``, themselves kept; units). The interval from rest to such a point
    is below what the LP resolves: the speed there (pure jerk from rest,
    ``b ~ (J d)^(4/3)``) is under HiGHS's tolerance even in the ``b`` column's
    own unit, and a squared speed of 0 away from a stop, which the LP may
    then give (its objective weight there is as small as the interval), is a
    stall. Such points come from a segment shorter than ``min_spacing`` next
    to a stop (a corner arc of sweep 6.5e-8 rad, a generated CAM plate, seed
    104 of tests/feed/test_jerk_generated.py: the segment's own 16 intervals of
    3.8e-9 mm). The interval from the stop then reaches past that segment's
    curvature break, a distance the tool covers at under 1e-3 of its speed."""
    k = np.searchsorted(stops, s)
    near = np.minimum(np.abs(s - stops[np.clip(k - 1, 0, stops.size - 1)]),
                      np.abs(stops[np.clip(k, 0, stops.size - 1)] - s))
    return s[(near >= min_spacing) | np.isin(s, stops)]


def lone_lines(path: ExactPath, s: np.ndarray, stop: np.ndarray) -> np.ndarray:
    """Which grid intervals lie on a stretch between two stops that is a single
    straight segment (a line, or a rapid). There the S-curve from rest to rest
    under the segment's speed, acceleration and jerk budgets (the axes' limits
    along its fixed direction, the feed, the tangential limit) is the exact
    optimum, which the planner takes per stretch anyway
    (:func:`_best_per_stretch`; the LP there loses a few 1e-3 to its grid), so
    such stretches get no LP window: on a chord program whose every vertex is
    a tangent break (LinuxCNC's path of freeform-hsm, 306 of them) no LP at all."""
    seg = path.locate(0.5 * (s[:-1] + s[1:]))
    starts = np.flatnonzero(stop[:-1])                      # each stretch's first interval
    first = np.minimum.reduceat(seg, starts)
    last = np.maximum.reduceat(seg, starts)
    line = np.array([isinstance(path.segments[k].geom, Line) for k in first], bool)
    lone = (first == last) & line
    return np.repeat(lone, np.diff(np.r_[starts, seg.size]))


def _speed_caps(path, limits, s, q, v, j, ts) -> np.ndarray:
    """Box bound on ``b`` at each gridpoint: axis velocities and feed on both
    sides, the centripetal limit, and ``|Delta q''| b <= J Ts`` at curvature breaks."""
    q1, q2 = q[0], q[1]
    with np.errstate(divide="ignore"):
        vb = np.where(np.abs(q1) > 0, (v / np.where(np.abs(q1) > 0, np.abs(q1), 1.0)) ** 2,
                      np.inf).min(axis=(0, 2))
        feed = np.minimum(path.feeds[path.locate(s, "left")], path.feeds[path.locate(s, "right")])
        cap = np.minimum(vb, feed ** 2)
        jump = np.abs(q2[1] - q2[0])
        cap = np.minimum(cap, np.where(jump > 0, j * ts / np.where(jump > 0, jump, 1.0),
                                       np.inf).min(axis=1))
        if limits.centripetal_acc is not None:
            kap = np.linalg.norm(q2, axis=2).max(axis=0)
            cap = np.minimum(cap, np.where(kap > 0, limits.centripetal_acc
                                           / np.where(kap > 0, kap, 1.0), np.inf))
    return cap


def plan_jerk(path: ExactPath, limits: AxisLimits, *, ts: float = DEFAULT_TS,
              grid: GridOptions | None = None, junction_deviation: float | None = None,
              **_ignored) -> JerkProfile:
    """Jerk-limited time-optimal profile of ``path`` (see the module docstring).

    ``limits.j`` is required. ``junction_deviation`` is not used: the planner
    stops at every tangent break. A window from rest to rest whose LP HiGHS
    does not solve, or whose solution stalls (speed 0 away from a stop), takes
    the S-curve per block (``info["lp_failed_windows"]``);
    raises :class:`FeedError` when any other window's LP fails.
    """
    if limits.j is None:
        raise FeedError("the jerk planner needs jerk limits (--jmax, or j in the case's "
                        "[limits])", path.source_file)
    if not ts > 0:
        raise ValueError(f"ts must be > 0, got {ts!r}")
    if not path.segments:
        return JerkProfile.empty(path, limits, "jerk")
    # TOPPRA's bound (below) on the LP's grid options too: on TOPPRA's finer
    # default grid it cost several times more and planned the same within 2e-6
    # (docs/jerk.md)
    grid = JERK_GRID if grid is None else grid
    j = limits.jerk_in_plane(path.frame, path.dof)
    g = build_grid(path, limits, ts, grid)
    b, alpha, info, scurve = _plan_grid(path, limits, g, grid, None)
    extra = np.zeros(0)
    refined = passes = 0
    # split the curved intervals whose axis jerk goes over the limit between
    # their gridpoints (ccopt.feed.jerk.refine) and plan around them again
    checked = None                    # every interval on the first pass
    while True:
        over, excess = jerk_over_inside(path, g, b, alpha, j, checked)
        if not over.any() or passes == MAX_PASSES:
            break
        passes += 1
        new = split_points(g.s, over, excess)
        extra = np.union1d(extra, new)
        refined += int(np.count_nonzero(over))
        finer = build_grid(path, limits, ts, grid, extra, previous=g)
        b, alpha = profile_at(g.s, b, alpha, finer.s)
        b, alpha, failed, replanned = replan_locally(finer, b, alpha, new, _scale(finer.bmax))
        for lo, hi in failed:
            b[lo:hi + 1], alpha[lo:hi + 1], _, _ = _plan_grid(path, limits,
                                                              grid_slice(finer, lo, hi),
                                                              grid, scurve)
        # the next pass checks only what was planned again: every other interval
        # is one of the last grid's, with the profile it had, so within the limit
        # (each interval over it was split, and its new points lie in a window)
        checked = np.zeros(finer.kind.size, bool)
        for lo, hi in (*replanned, *failed):
            checked[lo:hi] = True
        g = finer
    info.update(ts=ts, gridpoints=int(g.s.size), refined_intervals=refined, refine_passes=passes,
                jerk_over_inside=int(np.count_nonzero(over)))
    return _profile(path, limits, g, b, alpha, info, scurve)


def _plan_grid(path: ExactPath, limits: AxisLimits, g: JerkGrid, grid: GridOptions,
               scurve: dict | None):
    """``(b, alpha, info, scurve)``: every window of ``g`` planned (units of the
    path; NaN where no LP planned: a lone line, a failed window) and the
    S-curve per block's pieces (``scurve`` when given)."""
    if not any_chained(g):
        # every window from rest to rest: no TOPPRA bound needed (a large
        # share of the CPU on a program with many stops, and the rounds plan
        # faster from windows.rest_bound: docs/jerk.md)
        scale, cap, bound_of = _scale(g.bmax), None, None
    elif split(g):
        # each task computes its stretch's bound (speed_bound): scale from the box bound
        scale, cap = _scale(g.bmax), None

        def bound_of(i0, i1):
            return StretchBound.of(path, limits, grid, g.s[i0], g.s[i1])
    else:
        if g.s[0] == 0.0 and g.s[-1] == path.length:
            upper = speed_bound(path, limits, grid, g.s, g.stop, g.bmax)
        else:                           # a stretch planned again after refinement
            upper = StretchBound.of(path, limits, grid, g.s[0], g.s[-1])(g.s, g.stop, g.bmax)
        scale, bound_of = _scale(upper), None
        cap = upper / scale
    b = np.zeros(g.s.size)
    # a lone line's stretch has no window: no LP figure there, the S-curve stands in
    inside_lone = np.zeros(g.s.size, bool)
    inside_lone[1:-1] = g.lone[:-1] & g.lone[1:] & ~g.stop[1:-1]
    b[inside_lone] = np.nan
    alpha = np.zeros(g.s.size)
    total_rounds = failed = 0
    with ThreadPoolExecutor(1) as pool:
        # the S-curve per block (for _best_per_stretch) while the worker
        # processes solve the windows, instead of after them
        pending = (pool.submit(scurve_pieces, path, limits)
                   if cap is None and scurve is None else None)
        results, n_windows, workers, n_threads = plan_windows(g, cap, scale, bound_of)
        if scurve is None:
            scurve = scurve_pieces(path, limits) if pending is None else pending.result()
    for i0, i1, keep, bw, aw, rounds in results:
        if bw is None and aw:
            # rest to rest: the S-curve per block stands in (see _best_per_stretch)
            b[i0 + 1:i1] = np.nan
            failed += 1
            continue
        if bw is None:
            raise FeedError(f"jerk planner: the LP of the window from s = {g.s[i0]:.6g} to "
                            f"{g.s[i1]:.6g} is infeasible", path.source_file,
                            path.block_line(g.s[i0]))
        total_rounds += rounds
        b[i0:keep + 1] = bw * scale
        alpha[i0:keep + 1] = aw * scale
    info = {"gridpoints": int(g.s.size), "windows": n_windows, "lp_rounds": total_rounds,
            "lp_failed_windows": failed, "workers": workers, "threads": n_threads,
            "merged_windows": n_windows - len(results),
            "lone_lines": int(np.count_nonzero(g.lone[g.stop[:-1]]))}
    return b, alpha, info, scurve


def _scale(upper: np.ndarray) -> float:
    """The squared speed the LPs are scaled by: the largest finite of ``upper``."""
    return float(np.max(upper[np.isfinite(upper)], initial=1.0)) or 1.0


def _profile(path, limits, g: JerkGrid, b, alpha, info, scurve: dict) -> JerkProfile:
    """The :class:`JerkProfile` of the LP's ``(b, alpha)`` at the gridpoints
    (``scurve``: the S-curve per block's pieces, :func:`scurve_pieces`)."""
    b = np.where(g.stop, 0.0, b)
    moving = ~g.stop
    if np.any(b[moving] <= 0.0):
        i = int(np.flatnonzero(moving & (b <= 0.0))[0])
        raise FeedError(f"jerk planner stalled: zero speed at s = {g.s[i]:.6g} away from a stop",
                        path.source_file, path.block_line(g.s[i]))
    alpha = np.where(g.stop, 0.0, alpha)
    dt = piece_times(g.s, g.kind, b, alpha, slinear_time)
    v = np.sqrt(b)
    h = np.diff(g.s)
    rest = g.kind != SLINEAR
    # a rest piece's constant jerk: sigma = v_m * 2 b_m / (9 h^2) at its moving end m
    vm = np.where(g.kind == FROM_REST, v[1:], v[:-1])
    sigma = np.where(rest, 2.0 * b_moving(b, g.kind) * vm / (9.0 * h * h), 0.0)
    a0 = alpha[:-1].copy()
    a0[g.kind == TO_REST] = -2.0 * b[:-1][g.kind == TO_REST] / (3.0 * h[g.kind == TO_REST])
    pieces = {"kind": np.where(rest, CUBIC, PIECE_SLINEAR), "s0": g.s[:-1], "h": h,
              "v0": v[:-1], "v1": v[1:], "a0": a0, "a1": alpha[1:], "j": sigma, "dt": dt,
              "segment": path.locate(0.5 * (g.s[:-1] + g.s[1:]))}
    pieces, info["scurve_stretches"] = _best_per_stretch(pieces, scurve,
                                                         g.s[g.stop])
    return JerkProfile.from_pieces(path, limits, "jerk", pieces, info)


def _best_per_stretch(mine: dict, scurve: dict, stops: np.ndarray) -> tuple[dict, int]:
    """Between every two consecutive stops, the faster of the LP's pieces and
    the S-curve per block's (both feasible, rest to rest there): the S-curve is
    exactly optimal on a stretch of one straight block, where the LP loses a
    few 1e-3 to its grid. Returns the pieces and how many stretches took the S-curve."""
    def stretch(p):
        return np.clip(np.searchsorted(stops, p["s0"], side="right") - 1, 0, stops.size - 2)

    k_mine, k_sc = stretch(mine), stretch(scurve)
    n = stops.size - 1
    t_mine = np.bincount(k_mine, weights=mine["dt"], minlength=n)
    t_sc = np.bincount(k_sc, weights=scurve["dt"], minlength=n)
    use_sc = ~(t_mine <= t_sc)        # also where the LP failed (NaN)
    keep_mine, keep_sc = ~use_sc[k_mine], use_sc[k_sc]
    out = {}
    for key in mine:
        out[key] = np.concatenate([np.asarray(mine[key])[keep_mine],
                                   np.asarray(scurve[key])[keep_sc]])
    order = np.argsort(out["s0"], kind="stable")
    return {key: val[order] for key, val in out.items()}, int(use_sc.sum())


def b_moving(b: np.ndarray, kind: np.ndarray) -> np.ndarray:
    """``b`` at the moving end of each interval (the far end of a rest piece)."""
    return np.where(kind == FROM_REST, b[1:], b[:-1])
