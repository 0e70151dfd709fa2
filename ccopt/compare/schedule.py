"""How the comparison's work is run: in this process, or in worker processes.

Each variant is two jobs: its blend and what needs no feed plan
(:func:`.variant.solve`), then its cycle time (:func:`_duration`) under the
reference's stretch times. :func:`run_jobs` does them one after the other
here, or hands them to ``workers`` processes (:func:`ccopt.workers.process_pool`)
as they free up, while a thread of this process plans the reference; either
way the rows are the same (:mod:`.core` states the comparison itself, and
:mod:`.timing` why a cycle time planned before the reference is the same).

``ref``, below, is the comparison's reference (:class:`.core._Reference`):
its ``path``, ``limits`` and ``ts``, its stretch times (``ref.times()``,
planned when first asked) and stretch keys (``ref.keys()``).
"""
from __future__ import annotations

from collections import deque
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from contextlib import contextmanager
from typing import Callable
from dataclasses import replace

from ccopt.compare.contract import BUILTIN_NAMES
from ccopt.compare.registry import load
from ccopt.compare.timing import (PartialTime, StretchTimes, duration_figures, load_planner,
                                  partial_figures, same_timing_message, timed_alike)
from ccopt.compare.variant import VariantResult, gets_cycle_time, solve, with_duration
from ccopt.feed.limits import AxisLimits
from ccopt.toolpath import ToolPath
from ccopt.workers import process_pool

def _duration(path: ToolPath, limits: AxisLimits | None, times: StretchTimes | None = None):
    """A path's cycle time: ``(duration, max axis acceleration ratio sampled
    every 0.2 ms, message)`` (:func:`ccopt.compare.timing.duration_figures`),
    in this process or a worker."""
    return duration_figures(path, limits, times)


def _timed(path: ToolPath, limits: AxisLimits | None, times: StretchTimes | None = None):
    """:func:`_duration` and, as a fourth item, the stretch times planned for it
    (those ``times`` did not know; :attr:`.variant.VariantResult.stretch_times`)."""
    before = set(times.known) if times is not None else set()
    figures = _duration(path, limits, times)
    learned = {} if times is None else {k: v for k, v in times.known.items() if k not in before}
    return (*figures, learned)


def _read_off(row: VariantResult, problem):
    """The cycle-time figures of a row whose blend timed its path by stretches
    (:attr:`.variant.VariantResult.timed_by_blend`): read off those stretch
    times, nothing planned, so the row shows the figure the blend chose by."""
    times = StretchTimes(problem.limits, dict(row.stretch_times), problem.ts)
    return (*_duration(row.toolpath, problem.limits, times), row.stretch_times)


def say(progress, line: str) -> None:
    if progress is not None:
        progress(line)


def run_jobs(jobs, ref, reference_row, total: int, workers: int, progress, refs=None,
             memo: dict | None = None, prepare: Callable[[], None] | None = None):
    """``(row index, VariantResult)`` of the reference (``reference_row(times)``)
    and of every job ``(index, name, problem)``: here, one after the other, or
    in ``workers`` processes (:func:`_run_in_processes`).

    A job is done in two parts: the blend and what needs no feed plan
    (:func:`solve`), then the cycle time (:func:`_duration`) under the
    reference's stretch times (``ref.times()``). A variant whose
    tool path is another's takes that one's cycle time, planned once: here
    any path the planners time alike (:func:`_timed_twin`, whatever style
    made it), in workers an equal one (:func:`_of_path`); the figures are
    the same either way.

    ``refs``: job index -> the reference whose stretch times that job's cycle
    time starts from, where it is not ``ref`` (planned already: the plug-in
    blends' base path, :func:`.core.compare`); twins share a cycle time only
    under one reference. ``memo``: the paths timed so far, kept across calls
    (a comparison's later jobs take an earlier one's twin), and the count of
    jobs done (``"done"``) of all of them (``"jobs"``), for the progress lines.
    ``prepare``: work for this process, done when this returns (while
    workers run the jobs: in the thread that plans the reference, after it;
    else after the jobs): the imports the next call's jobs declare
    (:func:`.registry.preload`), so that its workers start with them."""
    refs = {} if refs is None else refs
    memo = {} if memo is None else memo
    if workers > 1 and len(jobs) > 1:
        yield from _run_in_processes(jobs, ref, reference_row, total, workers, progress, refs,
                                     memo, prepare)
        return
    yield from reference_row(ref.times())
    for i, name, problem in jobs:
        say(progress, f"variant {i + 1}/{total} {name}")
        local = problem if progress is None else replace(problem, progress=progress)
        # the rows measured under this problem: a path two variants leave is measured once
        row = solve(name, local, memo.setdefault(("measured", id(problem)), []))
        if gets_cycle_time(row) and row.timed_by_blend:
            row = with_duration(row, _read_off(row, problem))
        elif gets_cycle_time(row):
            by = refs.get(i, ref)
            alike = memo.setdefault(("here", id(by)), [])
            got = _timed_twin(alike, row.toolpath)
            if got is None:
                times = by.times()
                got = _timed(row.toolpath, problem.limits,
                             times.copy() if times is not None else None)
                alike.append((row.toolpath, got))
            row = with_duration(row, got)
        memo["done"] = memo.get("done", 0) + 1
        yield i, row
    if prepare is not None:
        prepare()


def _run_in_processes(jobs, ref, reference_row, total: int, workers: int,
                      progress, refs: dict, memo: dict, prepare=None):
    """:func:`run_jobs` in ``workers`` processes: at most one task per worker,
    a cycle time before a blend (a long blend's plan, the smoother's, starts
    as soon as its path is there), the blends in :func:`_longest_first`
    order. This process plans the reference in a thread meanwhile, handing
    out work as workers free up: a cycle time asked before the reference is
    planned plans the stretches it does not share with the reference
    (:func:`.timing.partial_figures`) and takes the shared ones from the
    reference's plan when it is there (:meth:`.timing.PartialTime.finish`),
    the same figures as a serial run. A job timed under another reference
    (``refs``) is timed under its stretch times, planned already."""
    n_workers = min(workers, len(jobs))
    if ref.limits is not None:
        load_planner(ref.limits)
    to_solve = deque(job for _, job in _longest_first(jobs))
    # ``by`` below: the reference a path is timed under (``refs``, else ``ref``)
    to_time: deque = deque()          # [path, limits, rows waiting for its time, by]
    running: dict = {}                # future -> (job, rows waiting for it, path, limits, by)
    partial: list = []                # (PartialTime, rows, path, limits, by): the reference's
                                      # part to come
    known: list = []                          # [the reference's stretch times], once planned

    def timed(by):
        """``(path, its cycle-time future)`` of the paths timed under ``by``."""
        return memo.setdefault(("workers", id(by)), [])

    with _pools(n_workers) as (pool, planner):

        def refill():
            while len(running) < n_workers and (to_time or to_solve):
                if to_time:
                    path, limits, rows, by = to_time.popleft()
                    if by is not ref or known or limits is None or ref.path is None:
                        times = by.times()
                        fut = pool.submit(_timed, path, limits,
                                          times.copy() if times is not None else None)
                    else:
                        fut = pool.submit(partial_figures, path, limits, ref.ts, ref.keys())
                    timed(by).append((path, fut))
                    running[fut] = (None, rows, path, limits, by)
                else:
                    job = to_solve.popleft()
                    running[pool.submit(solve, job[1], job[2])] = (job, None, None, None,
                                                                    refs.get(job[0], ref))

        refill()
        ref.keys()          # here, before the thread plans the same geometry
        reference = None
        if ref.planned():
            known.append(ref.times())
            yield from reference_row(known[0])
        else:
            reference = planner.submit(ref.times)
        if prepare is not None:     # the workers are forked by now (the first refill)
            planner.submit(prepare)
        while running or not known:
            finished, _ = wait(set(running) | ({reference} if not known else set()),
                               return_when=FIRST_COMPLETED)
            ready = []
            now_known = reference is not None and reference in finished
            if now_known:
                known.append(reference.result())
            for fut in finished - {reference}:
                job, rows, path, limits, by = running.pop(fut)
                if job is None:               # a cycle time: to every row that waits for it
                    partial.append((fut.result(), rows, path, limits, by))
                else:
                    ready.extend(_timed_or_queued(job, fut.result(), timed(by), to_time, running,
                                                  partial, known, by))
            ready.extend(_finish_partial(partial, known, to_time))
            refill()
            if now_known:
                yield from reference_row(ref.times())
            for i, name, row in sorted(ready, key=lambda r: r[0]):
                memo["done"] = memo.get("done", 0) + 1
                # one counter: the variants done of the comparison's jobs
                say(progress, f"variants {memo['done']}/{memo.get('jobs', len(jobs))} done: "
                              f"{name}")
                yield i, row


@contextmanager
def _pools(n_workers: int):
    """``(pool, planner)``: ``n_workers`` worker processes
    (:func:`ccopt.workers.process_pool`) and a thread for the reference's
    plan. Left normally, after both are done; on a Ctrl-C or an error, at
    once: the workers killed and the thread not waited for."""
    with process_pool(n_workers) as pool:
        planner = ThreadPoolExecutor(max_workers=1)
        done = False
        try:
            yield pool, planner
            done = True
        finally:
            planner.shutdown(wait=done, cancel_futures=True)


def _finish_partial(partial: list, known: list, to_time) -> list:
    """The rows whose cycle time is complete: each ``(figures, rows, path,
    limits)`` of ``partial`` (emptied of them) whose figures are ``(duration,
    max_acc_ratio, message)`` or, once the reference is planned (``known``), a
    :class:`~.timing.PartialTime` finished with its stretch times; a path the
    reference's times cannot finish is queued to be timed with them, and so
    is a twin's row whose path the planner's message would not name
    (:func:`_shares`)."""
    ready, waiting = [], []
    for fig, rows, path, limits, by in partial:
        if isinstance(fig, PartialTime):
            if not known:
                waiting.append((fig, rows, path, limits, by))
                continue
            whole = fig.finish(known[0])
            if whole is None:
                to_time.append((path, limits, rows, by))
                continue
            fig = (*whole, None, fig.learned)
        for entry in rows:
            if _shares(fig, path, entry[2].toolpath):
                ready.append((entry[0], entry[1], with_duration(entry[2], fig)))
            else:
                to_time.append((entry[2].toolpath, limits, [entry], by))
    partial[:] = waiting
    return ready


def _shares(fig, path: ToolPath, twin: ToolPath) -> bool:
    """Whether the cycle-time figures ``fig`` (``(duration, max_acc_ratio,
    message, ...)``) of ``path`` are also those of ``twin``, a path the
    planners time alike (:func:`_of_path`): always but for a planner's
    refusal, whose message names program lines
    (:func:`~.timing.same_timing_message`)."""
    return twin == path or not fig[2] or same_timing_message(path, twin)


def _timed_or_queued(job, row: VariantResult, timed, to_time, running, partial,
                     known, by) -> list:
    """The rows ready now for a solved ``job``: the row itself when it has no
    path to time, or with the cycle time of the same path planned already
    under its reference ``by`` (``timed``: those paths and their futures);
    else none, the row waiting for a plan of its path (running, waiting for
    the reference's, queued, or queued here)."""
    i, name, problem = job
    entry = (i, name, row)
    if not gets_cycle_time(row):
        return [entry]
    if row.timed_by_blend:
        return [(i, name, with_duration(row, _read_off(row, problem)))]
    twin = _of_path(timed, row.toolpath)
    if twin is not None and twin in running:
        running[twin][1].append(entry)
        return []
    if twin is not None:
        fig = twin.result()
        if isinstance(fig, PartialTime):
            held = _of_path(((p[2], p) for p in partial if p[4] is by), row.toolpath)
            if held is not None:
                held[1].append(entry)
                return []
            whole = fig.finish(known[0]) if known else None
            fig = None if whole is None else (*whole, None, fig.learned)
        timed_path = next(p for p, f in timed if f is twin)
        if fig is not None and _shares(fig, timed_path, row.toolpath):
            return [(i, name, with_duration(row, fig))]
    waiting = _of_path(((w[0], w) for w in to_time if w[3] is by), row.toolpath)
    if waiting is not None:
        waiting[2].append(entry)
    else:
        to_time.append((row.toolpath, problem.limits, [entry], by))
    return []


def _of_path(pairs, path: ToolPath):
    """The value paired in ``(path, value)`` ``pairs`` with a tool path equal
    to ``path``, else with one the planners time alike
    (:func:`~.timing.timed_alike`: another style's path of the same
    geometry, as the serial run's :func:`_timed_twin` finds), or None. The
    figures of a path timed in a worker arrive later, a planner's refusal
    with them, so a twin that is not equal takes them only where that
    refusal would read the same for it (:func:`_shares`, when they arrive)."""
    pairs = list(pairs)
    return next((value for p, value in pairs if p == path),
                next((value for p, value in pairs if timed_alike(p, path)), None))


def _timed_twin(timed, path: ToolPath):
    """The cycle-time figures of a path of ``timed`` (``(path, figures)``)
    the planners time as ``path`` (:func:`~.timing.timed_alike`), or None;
    not when they carry a refusal naming other lines than ``path``'s would
    (:func:`~.timing.same_timing_message`)."""
    for p, got in timed:
        if timed_alike(p, path) and _shares(got, p, path):
            return got
    return None


def _longest_first(jobs):
    """``(position, job)`` of ``jobs`` in the order to hand them to the workers,
    longest first so that none starts last and leaves the other workers idle:
    the plug-in blends, the last listed first (they solve optimisation
    problems over the path: on freeform-hsm the smoother, listed last, took
    8 s, the optimised leads 1.5-2.5 s each), then the other controller
    styles (they change every stretch of the path, all planned again: 0.8-1.2 s
    each there), then the geometric leads (only the leads: 0.2 s)."""
    def rank(kj):
        name = kj[1][1]
        if name not in BUILTIN_NAMES:
            return (0, -kj[0])
        return (1 if getattr(load(name), "compensates", False) else 2, kj[0])

    return sorted(enumerate(jobs), key=rank)
