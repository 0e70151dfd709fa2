"""The ``jerk`` planner's windows: the pseudo-jerk rounds on each, in parallel.

See :mod:`ccopt.feed.jerk.planner` for the formulation. Here: how the
gridpoints are cut into windows (:func:`windows`), the rounds that tighten a
window's speed bound ``bhat`` (:func:`solve_rounds`), and
:func:`plan_windows`, which solves every window and gathers ``(b, alpha)``.

Windows are grouped into *chains*: a chain starts at a stop and goes on as
long as each window starts where the last one kept its solution (a stretch
with no stop, planned in overlapping windows). Chains are independent (a stop
fixes ``b = alpha = 0`` between them), so on a long program they are solved
by :data:`WORKERS` processes (fresh interpreters fed over pipes,
:func:`ccopt.workers.run_in_interpreters`); the result does not depend on how
many.
"""
from __future__ import annotations

import multiprocessing
from dataclasses import replace

import numpy as np

from ccopt.feed.jerk.lp import JerkGrid, WindowLP
# PARENT_ENV: the variable WORKER_COMMAND's processes read (named here for them and the tests)
from ccopt.workers import (PARENT_ENV, interpreter_command, map_in_threads,  # noqa: F401
                           resolve_workers, run_in_interpreters, thread_budget)

#: Relative agreement of ``b`` and ``bhat`` that ends the pseudo-jerk rounds.
BHAT_TOL = 2e-3
#: ... or a window's duration estimate changing by less than DURATION_TOL
#: (relative) in each of SETTLED_ROUNDS rounds in a row; at most MAX_ROUNDS
#: rounds. Fewer rounds leave the pseudo-jerk bound loose (the pure-jerk
#: diagonal of test_jerk_planner further from its closed form); more wander,
#: as the LP's optimum jumps between vertices when bhat moves, and can leave
#: windows infeasible (docs/jerk.md).
DURATION_TOL = 1e-3
SETTLED_ROUNDS = 2
MAX_ROUNDS = 8
#: Simplex iterations per gridpoint the last round may take before its bound
#: is raised where the last b rose (see :func:`solve_rounds`).
FINAL_ITERATIONS = 2
#: Passes of the last round that tighten only the straight intervals where
#: the speed's inner peak breaks the jerk limit (see :func:`solve_rounds`).
PEAK_PASSES = 3
#: Largest fall of ``bhat`` in one round (a factor), see :func:`solve_rounds`.
BHAT_FALL = 0.1
#: Trust region of a round: b may rise at most this factor above bhat.
BHAT_RISE = 1.5
#: Gridpoints per LP window of stop-to-stop stretches gathered together; of a
#: stretch with no stop; and how much further such a window plans than it keeps.
#: (A window's rounds end together, and a failed window takes the S-curve on
#: all its stretches: larger batches plan slower in more CPU. On a long
#: stretch with no stop, longer windows gain little cycle time for more CPU,
#: shorter ones or a shorter overlap leave windows too short to keep their
#: solution, merged with the one before: docs/jerk.md.)
BATCH_POINTS = 200
WINDOW_POINTS = 1500
WINDOW_OVERLAP = 0.25
#: Processes or threads for the chains (None: as many as the CPUs this
#: process may use, :func:`~ccopt.workers.thread_budget`), and the fewest
#: gridpoints worth starting processes for; below it the chains are solved in
#: threads of this process. A spawned process takes about a second to import
#: ccopt and is sent its grid, where a thread needs neither; but only HiGHS's
#: solves run beside each other in threads (it releases the GIL, the LP's
#: set-up does not), so on long programs processes win: bench/feed.py times
#: both (``--jerk-threads``) on the pocket (docs/benchmarks.md).
WORKERS: int | None = None
PARALLEL_MIN_POINTS = 200_000
#: The fewest gridpoints from which each task computes the speed bound of its
#: own stretch (:func:`split`); TOPPRA over the whole path would otherwise run
#: alone before the processes start (docs/jerk.md).
SPLIT_BOUND_POINTS = 50_000
#: Gridpoints per task handed to a process (several chains each, so the
#: grid's arrays cross in few messages and the processes stay evenly loaded).
TASK_POINTS = 20_000


def windows(g: JerkGrid) -> list[tuple[int, int, int]]:
    """``(i0, i1, keep)`` windows: stop-to-stop stretches gathered up to
    :data:`BATCH_POINTS` gridpoints (fewer, larger LPs: less overhead per
    gridpoint); a stretch of up to :data:`WINDOW_POINTS` alone; a longer one
    in overlapping windows that plan to ``i1`` and keep ``i0..keep``; none
    on a stretch that is a lone straight segment (``g.lone``)."""
    stops = np.flatnonzero(g.stop)
    out: list[tuple[int, int, int]] = []
    i0 = int(stops[0])
    for a, b in zip(stops[:-1], stops[1:]):
        a, b = int(a), int(b)
        if g.lone is not None and g.lone[a]:
            # a lone straight segment: its S-curve is exact, no window (planner.lone_lines)
            if a > i0:
                out.append((i0, a, a))
            i0 = b
            continue
        if b - i0 <= BATCH_POINTS:
            continue
        if a > i0:
            out.append((i0, a, a))
            i0 = a
        while b - i0 > WINDOW_POINTS:
            end = min(b, i0 + int(WINDOW_POINTS * (1 + WINDOW_OVERLAP)))
            keep = i0 + WINDOW_POINTS if end < b else b
            out.append((i0, end, keep))
            i0 = keep
        if b - i0 > BATCH_POINTS:
            out.append((i0, b, b))
            i0 = b
    if int(stops[-1]) > i0:
        out.append((i0, int(stops[-1]), int(stops[-1])))
    return out


def solve_rounds(g: JerkGrid, i0: int, i1: int, cap: np.ndarray, start, scale: float,
                 bhat0: np.ndarray | None = None):
    """The pseudo-jerk rounds on one window (see :mod:`ccopt.feed.jerk.planner`):
    ``(b, alpha, rounds, bhat)`` scaled, or None when an LP is infeasible.

    ``bhat`` starts at ``cap`` (TOPPRA's speed, scaled), or on the first
    ``bhat0.size`` gridpoints at ``bhat0`` (the previous window's last bound
    on the overlap, when the window starts from that one's state), and the
    result's fourth item is the last ``bhat``. The rounds end when
    ``b`` and ``bhat`` agree within :data:`BHAT_TOL`, or when the window's
    duration (estimated from the speeds at the gridpoints) has changed by less
    than :data:`DURATION_TOL` in each of the last :data:`SETTLED_ROUNDS`
    rounds, or after :data:`MAX_ROUNDS` rounds; then one more round with
    ``b <= bhat`` gives the profile (``bhat`` first raised to the last ``b``
    where that rose above it, on a window that is part of a chain: see the
    comment below)."""
    bhat = cap.copy()
    if bhat0 is not None:
        bhat[:bhat0.size] = np.minimum(bhat0, cap[:bhat0.size])
    lp = WindowLP(g, i0, i1, cap, start, scale)
    h = np.diff(g.s[i0:i1 + 1])
    durations: list[float] = []
    rounds = 0
    for rounds in range(1, MAX_ROUNDS + 1):
        out = lp.solve(bhat, np.minimum(cap, BHAT_RISE * bhat))
        if out is None:
            return None
        b = out[0]
        big = b > BHAT_TOL * max(float(b.max(initial=0.0)), np.finfo(float).tiny)
        rel = np.abs(b[big] - bhat[big]) / np.maximum(bhat[big], b[big])
        # geometric mean, and never below a tenth of the last bound: a point the
        # LP left at 0 would otherwise pin the next rounds' cap there
        bhat = np.sqrt(np.maximum(b, BHAT_FALL * bhat) * bhat)
        v = np.sqrt(b)
        with np.errstate(divide="ignore"):
            durations.append(float(np.sum(2.0 * h / (v[1:] + v[:-1]))))
        if rel.max(initial=0.0) < BHAT_TOL or _settled(durations):
            break
    # the last round: b <= bhat. From the last round's basis HiGHS's simplex
    # needs well under one iteration per gridpoint on rest-to-rest windows, but
    # tens of thousands on the chained windows of a smoothed path (blend
    # curves, rows at every gridpoint). There, and past FINAL_ITERATIONS per
    # gridpoint elsewhere, the bound is raised to the last b where b rose
    # above it instead: the last solution then breaks only those points' jerk
    # rows (by at most sqrt(BHAT_RISE)) and is repaired in a few hundred
    # iterations. Exact either way (b <= bhat and the jerk rows at that bhat).
    # Capped, rest-to-rest windows plan faster; raised, chained windows plan
    # as fast in less CPU (docs/jerk.md).
    in_chain = start is not None or not g.stop[i1]        # see chained()
    out = None if in_chain else lp.solve(bhat, np.minimum(cap, bhat),
                                         max_iterations=int(FINAL_ITERATIONS * bhat.size))
    if out is None:
        bhat = np.maximum(bhat, b)
        out = lp.solve(bhat, np.minimum(cap, bhat))
    out = cover_peaks(lp, bhat, np.minimum(cap, bhat), out)
    if out is None:
        return None
    return out[0], out[1], rounds + 1, bhat


def cover_peaks(lp: WindowLP, bhat: np.ndarray, cap: np.ndarray, out):
    """``out`` (a solution of ``lp`` under ``bhat`` and ``cap``, or None) once
    the speed's peaks inside straight intervals are covered: their rows
    tightened where the profile breaks the jerk limit there, and solved again
    (each pass from the last basis); after :data:`PEAK_PASSES`, all of them
    (exact whatever comes). None when a solve fails."""
    for k in range(PEAK_PASSES + 1):
        if out is None:
            return None
        over = lp.peaks_over(*out)
        if not over.any():
            break
        lp.peaked |= over if k < PEAK_PASSES else lp.rise > 0.0
        out = lp.solve(bhat, cap)
    return out


def _settled(durations: list[float]) -> bool:
    """Whether each of the last :data:`SETTLED_ROUNDS` changes of the duration
    estimate is within :data:`DURATION_TOL` (relative)."""
    if len(durations) <= SETTLED_ROUNDS:
        return False
    d = np.asarray(durations[-SETTLED_ROUNDS - 1:])
    if not np.all(np.isfinite(d)):
        return False                 # a speed of 0 away from a stop: not settled
    return bool(np.all(np.abs(np.diff(d)) <= DURATION_TOL * d[1:]))


def _chains(wins: list[tuple[int, int, int]], stop: np.ndarray) -> list[list[tuple[int, int, int]]]:
    """The windows in chains, each starting at a stop (see the module docstring)."""
    chains: list[list[tuple[int, int, int]]] = []
    for w in wins:
        if stop[w[0]] or not chains:
            chains.append([w])
        else:
            chains[-1].append(w)
    return chains


def grid_slice(g: JerkGrid, i0: int, i1: int) -> JerkGrid:
    """The gridpoints ``i0..i1`` of ``g`` (its intervals between them)."""
    sl = slice(i0, i1 + 1)
    return replace(g, s=g.s[sl], q1=g.q1[:, sl], q2=g.q2[:, sl], q3=g.q3[:, sl],
                   kind=g.kind[i0:i1], stop=g.stop[sl], bmax=g.bmax[sl],
                   m1=g.m1[:, i0:i1], m2=g.m2[:, i0:i1], m3=g.m3[:, i0:i1],
                   lone=None if g.lone is None else g.lone[i0:i1])


def _solve_chain(g: JerkGrid, cap: np.ndarray, chain, scale: float,
                 first: np.ndarray | None = None) -> list[tuple]:
    """:func:`_solve_chain_in` in the chain's own scale: the largest finite
    squared speed bound ``cap * scale`` on its gridpoints, its results
    brought back to ``scale``. HiGHS's tolerances are absolute, so in the
    whole path's scale (the fastest move anywhere, a rapid's) a chain's plan
    depended on what else the path holds: a stretch planned alone, as
    ``compare`` times a variant's, came out up to 6e-6 from the same stretch
    in the whole path's plan (a generated CAM plate with a plunge, seed 38 of
    tests/compare/test_stretch_axes.py); in its own scale, 1e-14."""
    lo, hi = chain[0][0], chain[-1][1]
    # the chain's own gridpoints only: scaling the whole task's bounds for
    # each of its chains cost time in proportion to chains times gridpoints
    cap = cap[lo:hi + 1]
    first = None if first is None else first[lo:hi + 1]
    local = [(i0 - lo, i1 - lo, keep - lo) for i0, i1, keep in chain]
    own = float(np.max(cap[np.isfinite(cap)] * scale, initial=0.0))
    f = scale / own if own > 0.0 else 1.0
    out = _solve_chain_in(grid_slice(g, lo, hi), cap * f, local, own if own > 0.0 else scale,
                          None if first is None else first * f)
    return [(i0 + lo, i1 + lo, keep + lo, b, alpha, n) if b is None else
            (i0 + lo, i1 + lo, keep + lo, b / f, alpha / f, n)
            for i0, i1, keep, b, alpha, n in out]


def _solve_chain_in(g: JerkGrid, cap: np.ndarray, chain, scale: float,
                    first: np.ndarray | None = None) -> list[tuple]:
    """Every window of a chain in turn, each starting from the last one's
    kept end: per window ``(i0, i1, keep, b, alpha, rounds)`` (``b, alpha``
    scaled, on ``i0..keep``), or ``(i0, i1, keep, None, rest_to_rest, 0)`` for
    a window whose LP failed (the chain stops there).

    A window starts with the previous one's last speed bound ``bhat`` on
    their overlap (the bound its kept state was planned against). It can
    still be infeasible where the whole stretch is not: it is then merged with the
    previous window and the two planned again as one, back to the chain's
    first window (from rest) if need be: one window over the stretch is the
    planner's exact model. ``first``: the first window's first ``bhat``
    (scaled, at every gridpoint of ``g``) when not ``cap``."""
    out: list[tuple] = []
    carry: list[np.ndarray] = []          # each kept window's last bhat beyond its keep
    chain = list(chain)
    k = 0
    while k < len(chain):
        i0, i1, keep = chain[k]
        start = None if g.stop[i0] or not out else (float(out[-1][3][-1]),
                                                     float(out[-1][4][-1]))
        res = solve_rounds(g, i0, i1, cap[i0:i1 + 1], start, scale,
                           carry[-1] if start is not None else
                           None if first is None else first[i0:i1 + 1])
        rest_to_rest = start is None and bool(g.stop[i1])
        if res is not None and rest_to_rest and np.any(res[0][~g.stop[i0:i1 + 1]] <= 0.0):
            res = None        # a stall (speed 0 away from a stop): as a failed LP
        if res is None and out:
            chain[k - 1:k + 1] = [(chain[k - 1][0], i1, keep)]
            out.pop()
            carry.pop()
            k -= 1
            continue
        if res is None:
            out.append((i0, i1, keep, None, rest_to_rest, 0))
            break
        n = keep - i0 + 1
        out.append((i0, i1, keep, res[0][:n], res[1][:n], res[2]))
        carry.append(res[3][n - 1:])
        k += 1
    return out


def chained(chain, stop: np.ndarray) -> bool:
    """Whether ``chain`` plans a stop-free stretch in overlapping windows (more
    than one window, or one that does not end at a stop), rather than one
    window from rest to rest."""
    return len(chain) > 1 or not stop[chain[0][1]]


def any_chained(g: JerkGrid) -> bool:
    """Whether any stretch of ``g`` is planned in overlapping windows (:func:`chained`)."""
    return any(chained(c, g.stop) for c in _chains(windows(g), g.stop))


def rest_bound(s: np.ndarray, stop: np.ndarray, q1: np.ndarray, a: np.ndarray, j: np.ndarray,
               bmax: np.ndarray) -> np.ndarray:
    """A first speed bound (squared, units^2/s^2) for a window from rest to
    rest, at the gridpoints ``s``: at distance ``d`` from the nearest of the
    ``stop`` gridpoints, the squared speed of straight motion from rest under
    the path acceleration and jerk ``A``, ``J`` the axes allow along the
    tangent (``min_i A_i / |q_i'|``; ``q1``: ``(2, N, dof)`` one-sided
    ``q'``), ``min(2 A d, J^(2/3) (6 d)^(4/3) / 4)`` (the acceleration-limited
    motion, and the constant-jerk start ``s = J t^3 / 6``, ``v = J t^2 / 2``),
    and at most ``bmax``.

    A start for the pseudo-jerk rounds, not a bound they rely on (``b`` is
    capped by ``bmax`` and the LP's own rows): where it is low the rounds
    raise it (by at most :data:`~ccopt.feed.jerk.windows.BHAT_RISE` a
    round), where high they lower it. It replaces TOPPRA's speed there at no
    cost, and starts closer on jerk-limited stretches."""
    at = np.flatnonzero(stop)
    k = np.clip(np.searchsorted(s[at], s), 1, at.size - 1) if at.size > 1 else np.zeros(s.size, int)
    d = np.abs(s - s[at[k]]) if at.size else np.full(s.size, np.inf)
    if at.size > 1:
        d = np.minimum(d, np.abs(s - s[at[k - 1]]))
    t = np.abs(q1).max(axis=0)                       # (N, dof), both sides
    with np.errstate(divide="ignore"):
        A = np.min(np.where(t > 0, a / np.where(t > 0, t, 1.0), np.inf), axis=1)
        J = np.min(np.where(t > 0, j / np.where(t > 0, t, 1.0), np.inf), axis=1)
    out = np.minimum(2.0 * A * d, 0.25 * J ** (2.0 / 3.0) * (6.0 * d) ** (4.0 / 3.0))
    return np.where(stop, 0.0, np.minimum(out, bmax))


def _solve_task(g: JerkGrid, cap: np.ndarray | None, chains, scale: float,
                bound=None) -> list[tuple]:
    """:func:`_solve_chain` on each of ``chains`` (indices local to ``g``).

    A window from rest to rest is capped by the box bound ``g.bmax`` (0 at
    stops) and starts from :func:`rest_bound`; a chain of overlapping
    windows is capped by and starts from ``cap``, TOPPRA's speed (see
    :mod:`ccopt.feed.jerk.planner`), or with ``cap`` None from ``bound(s,
    stop, bmax) / scale`` (the speed bound of the task's own stretch,
    :class:`~ccopt.feed.jerk.speed_bound.StretchBound`), computed only when the
    task has such a chain."""
    solve = _chain_solver(g, cap, chains, scale, bound)
    return [r for chain in chains for r in solve(chain)]


def _chain_solver(g: JerkGrid, cap: np.ndarray | None, chains, scale: float, bound=None):
    """``solve(chain)``: :func:`_solve_chain` of one of ``chains`` with the
    bounds :func:`_solve_task` gives it (each computed once, here, for all)."""
    in_chain = [chained(c, g.stop) for c in chains]
    if cap is None and any(in_chain):
        cap = bound(g.s, g.stop, g.bmax) / scale
    box = first = None
    if not all(in_chain):
        box = np.where(g.stop, 0.0, g.bmax) / scale
        first = rest_bound(g.s, g.stop, g.q1, g.a, g.j, g.bmax) / scale

    def solve(chain):
        if chained(chain, g.stop):
            return _solve_chain(g, cap, chain, scale)
        return _solve_chain(g, box, chain, scale, first)
    return solve


def _tasks(g: JerkGrid, cap: np.ndarray | None, chains, scale: float, bound_of=None):
    """Chains gathered into tasks of about :data:`TASK_POINTS` gridpoints, each
    with its own slice of the grid: ``(offset, args of _solve_task)``; with
    ``cap`` None, each with ``bound_of(i0, i1)``, the speed bound of its
    gridpoints ``i0..i1`` instead of a slice of ``cap``."""
    if not chains:
        return                      # every stretch a lone line (no window at all)
    groups: list[list] = [[]]
    size = 0
    for chain in chains:
        if size >= TASK_POINTS:
            groups.append([])
            size = 0
        groups[-1].append(chain)
        size += chain[-1][1] - chain[0][0]
    for group in groups:
        lo, hi = group[0][0][0], group[-1][-1][1]
        local = [[(i0 - lo, i1 - lo, keep - lo) for i0, i1, keep in chain] for chain in group]
        if cap is None:
            bound = bound_of(lo, hi) if bound_of is not None else None
            yield lo, (grid_slice(g, lo, hi), None, local, scale, bound)
        else:
            yield lo, (grid_slice(g, lo, hi), cap[lo:hi + 1], local, scale)


def split(g: JerkGrid) -> bool:
    """Whether the speed bound of ``g`` is computed per task
    (:class:`~ccopt.feed.jerk.speed_bound.StretchBound`, in the processes that solve
    the tasks' windows): a program of :data:`SPLIT_BOUND_POINTS` gridpoints or
    more, with more than one chain. A decision on the program alone: the
    result never depends on how many processes solve it."""
    return g.s.size >= SPLIT_BOUND_POINTS and len(_chains(windows(g), g.stop)) >= 2


def _workers(points: int, n_chains: int) -> int:
    """How many processes to use (1: this one)."""
    if points < PARALLEL_MIN_POINTS or n_chains < 2:
        return 1
    if multiprocessing.current_process().daemon:
        return 1                      # a daemonic process (a Dask worker) may not have children
    return max(1, min(resolve_workers(WORKERS), thread_budget(), n_chains))


def threads(n_tasks: int) -> int:
    """How many threads of this process solve ``n_tasks`` independent tasks
    (chains, or the stretches a refinement pass plans again): as many as
    :data:`WORKERS` and this process's share of the cores allow
    (:func:`~ccopt.workers.thread_budget`). HiGHS releases the GIL while it
    solves, most of a window's time, so threads need no process started and
    no grid sent; the tasks are independent, so the result is the same."""
    return max(1, min(resolve_workers(WORKERS), thread_budget(), n_tasks))


def plan_windows(g: JerkGrid, cap: np.ndarray | None, scale: float, bound_of=None):
    """Every window of ``g`` solved (see the module docstring): ``(results,
    n_windows, workers, threads)``, ``results`` as :func:`_solve_chain`'s, with
    global gridpoint indices, in order along the path; ``workers`` the
    processes that solved them, ``threads`` the threads of this one.

    ``cap``: the scaled speed bound at every gridpoint, or None on a
    :func:`split` program: then ``bound_of(i0, i1)`` gives each task the
    callable that computes it on the task's gridpoints ``i0..i1``; both None
    when no window is chained (every window is then capped by the box bound
    and starts from :func:`rest_bound`, see :func:`_solve_task`)."""
    wins = windows(g)
    chains = _chains(wins, g.stop)
    workers = _workers(g.s.size, len(chains))
    if workers == 1 and (cap is not None or bound_of is None):
        # in this process, chain by chain, in threads where the cores allow
        n = threads(len(chains))
        parts = map_in_threads(_chain_solver(g, cap, chains, scale), chains, n)
        return [r for part in parts for r in part], len(wins), 1, n
    tasks = list(_tasks(g, cap, chains, scale, bound_of))
    workers = max(1, min(workers, len(tasks)))     # 1: this process (or no LP at all)
    n = threads(len(tasks)) if workers == 1 else 1
    if workers == 1:
        parts = map_in_threads(lambda args: _solve_task(*args), [args for _, args in tasks], n)
    else:
        parts = run_in_interpreters(__name__, "_solve_task", [args for _, args in tasks], workers)
    results: list[tuple] = []
    for (lo, _), part in zip(tasks, parts):
        results.extend((i0 + lo, i1 + lo, keep + lo, *rest) for i0, i1, keep, *rest in part)
    return results, len(wins), workers, n


#: What a worker process runs (:func:`ccopt.workers.run_in_interpreters`):
#: :func:`_solve_task` on each task it is sent; it knows its parent by the
#: environment variable ``PARENT_ENV`` (:data:`ccopt.workers.PARENT_ENV`).
WORKER_COMMAND = interpreter_command(__name__, "_solve_task")

