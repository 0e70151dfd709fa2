"""``compare``: every variant of one program, with the same figures.

For each variant: build its tool path (timed: ``solve_time``), certify it
with :func:`ccopt.verify.verify` against the program's contour, plan its feed
under the same limits, with TOPPRA, or with the jerk planner when the limits
carry jerk (``max_acc_ratio`` is the largest axis acceleration over its limit
in the profile sampled every 0.2 ms; the feed grid follows the turning inside
blend curves, :mod:`ccopt.feed.grid`), and measure it (:mod:`.figures`)
against the reference, PMAC's path. A row is ``ok`` only when the verifier
certifies its path; a path it does not certify is ``uncertified``, with its
figures and why. A variant that a controller refuses (``refused``), that
cannot be built or certified (``rejected``) or that fails unexpectedly
(``failed``) is still listed, with the reason and no figures.

The reference is planned once, whole; a variant's cycle time reuses the
reference's time on every stretch between two stops that it shares and
plans only the stretches it changed (:mod:`.timing`, where the rule and why
it is exact are); variants that build the same tool path are timed once.
``workers > 1`` runs the variants in that many worker
processes; the rows are the same as a serial run's (each variant starts
from the reference's stretch times alone), ``solve_time`` aside.
"""
from __future__ import annotations

import os
import time
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, ThreadPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Callable

from ccopt.compare.baseline import apply_baseline, base_row, from_base
from ccopt.compare.contract import BUILTIN_NAMES, BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.figures import max_deviation, path_figures
from ccopt.compare.leads import lead_joins
from ccopt.compare.registry import available, load
from ccopt.compensate import compensate
from ccopt.compare.timing import (PartialTime, StretchTimes, duration_figures, load_planner,
                                  partial_figures, same_plan, stretch_keys)
from ccopt.errors import CcoptError
from ccopt.feed import certified_planner
from ccopt.feed.limits import AxisLimits
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath
from ccopt.workers import fork_context, kill_processes, start_child

if TYPE_CHECKING:  # pragma: no cover
    from ccopt.feed.profile import FeedProfile

REFERENCE = "pmac"

#: Figures every listed variant has (``None`` when it has no tool path).
FIGURES = ("length", "max_curvature", "max_curvature_jump", "continuity", "path_continuity",
           "tangent_breaks", "duration", "duration_ratio", "max_acc_ratio", "min_clearance",
           "certified", "max_deviation", "max_deviation_bound", "solve_time")


@dataclass
class VariantResult:
    """One row of the comparison."""

    name: str
    status: str                     # ok | uncertified | refused | rejected | failed
    message: str | None = None
    toolpath: ToolPath | None = None
    certificate: object | None = None
    figures: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)

    def __getitem__(self, key):
        return self.to_json()[key]

    def to_json(self) -> dict:
        out = {"name": self.name, "status": self.status, "message": self.message}
        for k in FIGURES:
            out[k] = self.figures.get(k)
        for k, v in self.figures.items():
            out.setdefault(k, v)
        if self.info:
            out["info"] = self.info
        return out


@dataclass
class Comparison:
    """Rows in variant order; iterable. ``reference`` is PMAC's path."""

    variants: list[VariantResult]
    reference: ToolPath | None
    limits: AxisLimits | None
    program: Program

    def __iter__(self):
        return iter(self.variants)

    def __len__(self):
        return len(self.variants)

    def __getitem__(self, name: str) -> VariantResult:
        for v in self.variants:
            if v.name == name:
                return v
        raise KeyError(name)

    def to_json(self) -> dict:
        return {"program": self.program.file,
                "radius": self.reference.radius if self.reference is not None else None,
                "units": self.program.units,
                "limits": self.limits.to_json() if self.limits is not None else None,
                "reference": REFERENCE,
                "planner": certified_planner(self.limits) if self.limits is not None else None,
                "variants": [v.to_json() for v in self.variants]}


def _duration(path: ToolPath, limits: AxisLimits | None, times: StretchTimes | None = None):
    """``(duration, max axis acceleration ratio sampled every 0.2 ms, message)``
    (:func:`ccopt.compare.timing.duration_figures`)."""
    return duration_figures(path, limits, times)


def measure(name: str, path: ToolPath, problem: BlendProblem, solve_time: float,
            info: dict | None = None, certificate=None,
            times: StretchTimes | None = None) -> VariantResult:
    """Certify, time and measure one variant's tool path (``times``: the
    reference's stretch times, :mod:`.timing`; ``None`` plans the whole path)."""
    row = _measure_shape(name, path, problem, solve_time, info, certificate)
    return _with_duration(row, _duration(path, problem.limits, times))


def _measure_shape(name: str, path: ToolPath, problem: BlendProblem, solve_time: float,
                   info: dict | None = None, certificate=None) -> VariantResult:
    """:func:`measure` but the cycle time: certificate, path figures, deviation
    from the reference (what needs no feed plan)."""
    cert = certificate if certificate is not None else problem.certify(path)
    fig = path_figures(path, lead_joins(path))
    if problem.reference is not None:
        dev, dev_bound = max_deviation(path, problem.reference)
    else:  # no reference to measure against (PMAC refused the program)
        dev = dev_bound = None
    gouge = cert.check("gouge")
    fig.update(min_clearance=cert.min_clearance, certified=bool(cert.ok),
               verdict=cert.verdict,
               clearance_ok=bool(gouge.ok), violations=len(cert.violations),
               max_deviation=dev, max_deviation_bound=dev_bound, solve_time=solve_time)
    status, message = ("ok", _warnings_note(cert)) if cert.ok else \
        ("uncertified", uncertified_reason(cert))
    return VariantResult(name, status, message, path, cert, fig, dict(info or {}))


def _warnings_note(cert) -> str | None:
    """``ok within tolerance: ...`` for a certified path with shallow violations
    the verifier lists as warnings (program units), else ``None``."""
    if not cert.warnings:
        return None
    v = max(cert.warnings, key=lambda v: v.depth)
    line = f" at line {v.tool_block}" if v.tool_block is not None else ""
    return (f"ok within tolerance: {len(cert.warnings)} warning(s), deepest {v.kind} "
            f"{v.depth:.3g}{line}")


def uncertified_reason(cert) -> str:
    """Why a row whose path the verifier did not certify is not ``ok``: the
    checks that failed and the deepest violation (program units for a
    gouge, side or gap; a ratio over the limit for the feed limits)."""
    failed = [c.name for c in cert.checks if not c.ok]
    text = f"not certified: {', '.join(failed) or 'a check'} failed"
    if cert.violations:
        v = max(cert.violations, key=lambda v: v.depth)
        line = f" at line {v.tool_block}" if v.tool_block is not None else ""
        text += f" (deepest: {v.kind} {v.depth:.3g}{line}, {len(cert.violations)} violation(s))"
    return text


def _timed(row: VariantResult) -> bool:
    """Whether ``row`` gets a cycle time: it has a tool path (``ok`` or
    ``uncertified``; the time of an uncertified path is still a figure)."""
    return row.status in ("ok", "uncertified") and row.toolpath is not None


def _with_duration(row: VariantResult, duration) -> VariantResult:
    """``row`` with :func:`_duration`'s ``(duration, max_acc_ratio, message)``
    (the planner's refusal joins the row's own message, if any)."""
    dur, acc_ratio, feed_msg = duration
    row.figures.update(duration=dur, max_acc_ratio=acc_ratio)
    if feed_msg:
        row.message = feed_msg if row.message is None else f"{row.message}; {feed_msg}"
    return row


@dataclass(frozen=True)
class GivenReference:
    """PMAC's path of the program as the caller made it (``ccopt run``'s
    pipeline, when the job's own path is PMAC's): ``path``, the ``seconds``
    compensating it took, and ``profile``, its whole-path feed plan under the
    comparison's limits and :func:`~ccopt.feed.certified_planner` when the
    caller has one (``None``: planned here). The comparison takes it as its
    reference instead of compensating the program again."""

    path: ToolPath
    seconds: float = 0.0
    profile: FeedProfile | None = None


def compare(program: Program, variants=None, *, limits: AxisLimits | None = None,
            delta: float | None = None, radius: float | None = None, side=None,
            options: dict | None = None, workers: int = 1,
            progress: Callable[[str], None] | None = None, ts: float | None = None,
            reference: GivenReference | None = None,
            tolerance: float | None = None) -> Comparison:
    """Compare lead-in/lead-out/corner variants of ``program``.

    Parameters
    ----------
    variants: names (default: every available one, :func:`available`).
    limits: machine limits for the cycle time (``None``: no durations); with
        jerk limits (``limits.j``) cycle times are the jerk planner's.
    delta: the smoother's tolerance band (default 1 % of the cutter radius).
    radius, side: compensation overrides, as for :func:`ccopt.compensate`.
    options: blend options (e.g. ``lead_radius`` for the geometric leads).
    workers: worker processes for the variants (1: all in this process); the
        rows are the same either way, ``solve_time`` aside.
    progress: called with a short line as the work goes ("variant 3/10
        opt-casadi"; in this process also "opt-casadi: blend 2/6").
    ts: the jerk planner's interpolation period (s; None: its default, 1 ms).
    reference: PMAC's path (and its plan) when the caller has made it already
        (:class:`GivenReference`; it must be PMAC's path of ``program`` with
        ``radius`` and ``side``); its plan is used only when it is the plan
        this would make (:func:`.timing.same_plan`: these limits, their
        planner and ``ts``), else the path is planned here.
    tolerance: the verifier's gouge tolerance (program units; ``None``: its
        default), as for :func:`ccopt.verify.verify`.

    A row is ``ok`` only when its path is certified; a path the verifier does
    not certify is ``uncertified``, with its figures and why (``message``).
    """
    names = list(variants) if variants else available()
    ref = _Reference.of(program, radius, side, limits, ts, reference)
    settings = (limits, delta, dict(options or {}), radius, side, None, tolerance, ts)
    problem = BlendProblem(program, ref.path, *settings) if ref.path is not None else None
    rows, jobs, ref_index = _jobs(names, program, problem, ref.error, settings)

    def reference_row(times: StretchTimes | None):
        """The reference's row (it is the first variant that reports)."""
        if ref_index is None:
            return []
        _say(progress, f"variant {ref_index + 1}/{len(names)} {REFERENCE}")
        return [(ref_index, measure(REFERENCE, ref.path, problem, ref.seconds, times=times))]

    # the controllers and built-in leads first; the plug-in blends then start
    # from the fastest certified controller variant's path (issue 30)
    first = [job for job in jobs if job[1] in BUILTIN_NAMES]
    for i, row in _run_jobs(first, ref, reference_row, len(names), workers, progress):
        rows[i] = row
    later = [job for job in jobs if job[1] not in BUILTIN_NAMES]
    base = base_row(rows, REFERENCE) if limits is not None and problem is not None else None
    if base is not None:
        later = [(i, name, replace(problem, reference=base.toolpath)) for i, name, _ in later]
    for i, row in _run_jobs(later, ref, lambda _: [], len(names), workers, progress):
        rows[i] = row if base is None else from_base(row, base.name, problem.reference)
    ref_duration = rows[ref_index].figures.get("duration") if ref_index is not None else None
    if ref_duration is None and problem is not None and limits is not None:
        ref_duration = _duration(ref.path, limits, ref.times())[0]
    for row in rows:
        d = row.figures.get("duration")
        if d is not None and ref_duration:
            row.figures["duration_ratio"] = d / ref_duration
    if limits is not None and problem is not None:
        apply_baseline(rows, REFERENCE)
    return Comparison(rows, ref.path, limits, program)


@dataclass
class _Reference:
    """PMAC's path of the program (``None`` with the ``error`` when PMAC refuses
    it), the seconds its compensation took, and its stretch times, planned
    when first asked (:meth:`times`): in a parallel comparison while the
    workers solve the blends (freeform-hsm's reference takes about 2 s)."""

    path: ToolPath | None
    error: str | None
    seconds: float
    limits: AxisLimits | None
    ts: float | None
    profile: FeedProfile | None           # the caller's plan of it, if any
    _times: list = field(default_factory=list)
    _keys: list = field(default_factory=list)   # [its stretch keys], once asked

    @classmethod
    def of(cls, program: Program, radius, side, limits, ts,
           given: GivenReference | None = None) -> "_Reference":
        """PMAC's path of ``program``: the caller's (``given``) or compensated here."""
        if given is not None:
            return cls(given.path, None, given.seconds, limits, ts, given.profile)
        t0 = time.perf_counter()
        try:
            path, error = compensate(program, REFERENCE, radius=radius, side=side), None
        except CcoptError as exc:
            path, error = None, str(exc)
        return cls(path, error, time.perf_counter() - t0, limits, ts, None)

    def times(self) -> StretchTimes | None:
        """:func:`_reference_times`, once; with no reference (refused) an empty
        :class:`StretchTimes`, so each path is planned whole with ``ts``."""
        if not self._times:
            if self.path is None:
                self._times.append(None if self.limits is None
                                   else StretchTimes(self.limits, ts=self.ts))
            else:
                planned = self.profile if same_plan(self.profile, self.path, self.limits,
                                                    self.ts) else None
                self._times.append(_reference_times(self.path, self.limits, self.ts, planned))
        return self._times[0]

    def keys(self) -> frozenset:
        """The reference's stretch keys (:func:`.timing.stretch_keys`; none
        without a reference or limits): a cycle time planned before the
        reference leaves these stretches to its plan."""
        if not self._keys:
            self._keys.append(frozenset() if self.path is None or self.limits is None
                              else frozenset(stretch_keys(self.path)) - {None})
        return self._keys[0]


def _jobs(names: list[str], program: Program, problem: BlendProblem | None,
          ref_error: str | None, settings: tuple):
    """``(rows, jobs, ref_index)``: the rows known without work (unknown names,
    refusals for want of a reference), the jobs ``(index, name, problem)`` and
    the reference's index in ``names`` (None when absent or refused).
    ``settings``: ``(limits, delta, options, radius, side, progress, tolerance)``
    of a problem without reference."""
    known = set(available())
    rows: list[VariantResult | None] = [None] * len(names)
    jobs: list[tuple[int, str, BlendProblem]] = []
    ref_index = None
    for i, name in enumerate(names):
        if name not in known:
            rows[i] = VariantResult(name, "failed", f"unknown variant {name!r}; known: "
                                    f"{', '.join(sorted(known))}")
        elif problem is None:
            if name == REFERENCE:
                rows[i] = VariantResult(name, "refused", ref_error)
            elif getattr(load(name), "compensates", False):
                # another controller style needs no reference: it may accept the program
                jobs.append((i, name, BlendProblem(program, None, *settings)))
            else:
                rows[i] = VariantResult(name, "failed", f"no reference path: {ref_error}")
        elif name == REFERENCE:
            ref_index = i
        else:
            jobs.append((i, name, problem))
    return rows, jobs, ref_index


def _say(progress, line: str) -> None:
    if progress is not None:
        progress(line)


def _reference_times(reference: ToolPath, limits: AxisLimits | None, ts: float | None = None,
                     profile: FeedProfile | None = None) -> StretchTimes | None:
    """The reference planned whole (or its ``profile``) and cut at its stops
    (``None`` without limits; none known when the planner refuses the
    reference: each variant is then planned whole and says why)."""
    if limits is None:
        return None
    try:
        return StretchTimes.from_reference(reference, limits, ts, profile)[0]
    except CcoptError:
        return StretchTimes(limits, ts=ts)


def _run_jobs(jobs, ref: "_Reference", reference_row, total: int, workers: int, progress):
    """``(row index, VariantResult)`` of the reference (``reference_row(times)``)
    and of every job ``(index, name, problem)``: here, one after the other, or
    in ``workers`` processes (:func:`_run_in_processes`).

    A job is done in two parts: the blend and what needs no feed plan
    (:func:`_solve`), then the cycle time (:func:`_duration`) under the
    reference's stretch times (``ref.times()``). A variant whose
    tool path is another's takes that one's cycle time, planned once (Fagor's
    G138 and G139 with G136 leave the same path on 15 of the 27 bundled
    cases, all three Fagor styles on 7)."""
    if workers > 1 and len(jobs) > 1:
        yield from _run_in_processes(jobs, ref, reference_row, total, workers, progress)
        return
    times = ref.times()
    yield from reference_row(times)
    timed: list[tuple[ToolPath, tuple]] = []
    for i, name, problem in jobs:
        _say(progress, f"variant {i + 1}/{total} {name}")
        local = problem if progress is None else replace(problem, progress=progress)
        row = _solve(name, local)
        if _timed(row):
            got = _of_path(timed, row.toolpath)
            if got is None:
                got = _duration(row.toolpath, problem.limits,
                                times.copy() if times is not None else None)
                timed.append((row.toolpath, got))
            row = _with_duration(row, got)
        yield i, row


def _run_in_processes(jobs, ref: "_Reference", reference_row, total: int, workers: int,
                      progress):
    """:func:`_run_jobs` in ``workers`` processes: at most one task per worker,
    a cycle time before a blend (a long blend's plan, the smoother's, starts
    as soon as its path is there), the blends in :func:`_longest_first`
    order. This process plans the reference in a thread meanwhile, handing
    out work as workers free up: a cycle time asked before the reference is
    planned plans the stretches it does not share with the reference
    (:func:`.timing.partial_figures`) and takes the shared ones from the
    reference's plan when it is there (:meth:`.timing.PartialTime.finish`),
    the same figures as a serial run."""
    n_workers = min(workers, len(jobs))
    if ref.limits is not None:
        load_planner(ref.limits)
    to_solve = deque(job for _, job in _longest_first(jobs))
    to_time: deque = deque()                  # [path, limits, rows waiting for its time]
    timed: list[tuple[ToolPath, object]] = []   # path, its cycle-time future
    running: dict = {}                        # future -> (job, rows waiting for it)
    partial: list = []                        # (PartialTime, rows): the reference's part to come
    known: list = []                          # [the reference's stretch times], once planned
    done = 0
    with _pools(n_workers) as (pool, planner):

        def refill():
            while len(running) < n_workers and (to_time or to_solve):
                if to_time:
                    path, limits, rows = to_time.popleft()
                    if known or limits is None or ref.path is None:
                        times = ref.times()
                        fut = pool.submit(_duration, path, limits,
                                          times.copy() if times is not None else None)
                    else:
                        fut = pool.submit(partial_figures, path, limits, ref.ts, ref.keys())
                    timed.append((path, fut))
                    running[fut] = (None, rows, path, limits)
                else:
                    job = to_solve.popleft()
                    running[pool.submit(_solve, job[1], job[2])] = (job, None, None, None)

        refill()
        ref.keys()          # here, before the thread plans the same geometry
        reference = planner.submit(ref.times)
        while running or not known:
            finished, _ = wait(set(running) | ({reference} if not known else set()),
                               return_when=FIRST_COMPLETED)
            ready = []
            now_known = reference in finished
            if now_known:
                known.append(reference.result())
            for fut in finished - {reference}:
                job, rows, path, limits = running.pop(fut)
                if job is None:               # a cycle time: to every row that waits for it
                    partial.append((fut.result(), rows, path, limits))
                else:
                    ready.extend(_timed_or_queued(job, fut.result(), timed, to_time, running,
                                                  partial, known))
            ready.extend(_finish_partial(partial, known, to_time))
            refill()
            if now_known:
                yield from reference_row(ref.times())
            for i, name, row in sorted(ready, key=lambda r: r[0]):
                done += 1
                _say(progress, f"variant {i + 1}/{total} {name} done ({done}/{len(jobs)})")
                yield i, row


@contextmanager
def _pools(n_workers: int):
    """``(pool, planner)``: ``n_workers`` worker processes (forked where the
    platform can: they start with ccopt and its libraries loaded) and a
    thread for the reference's plan. Left normally, after both are done; on a
    Ctrl-C or an error, at once: the workers killed (a library pool lets
    each finish its task first, seconds on a long plan) and the thread not
    waited for."""
    pool = ProcessPoolExecutor(max_workers=n_workers, mp_context=fork_context(),
                               initializer=start_child, initargs=(os.getpid(),))
    planner = ThreadPoolExecutor(max_workers=1)
    done = False
    try:
        yield pool, planner
        done = True
    finally:
        if not done:
            kill_processes(list((getattr(pool, "_processes", None) or {}).values()))
        planner.shutdown(wait=done, cancel_futures=True)
        pool.shutdown(wait=done, cancel_futures=True)


def _finish_partial(partial: list, known: list, to_time) -> list:
    """The rows whose cycle time is complete: each ``(figures, rows, path,
    limits)`` of ``partial`` (emptied of them) whose figures are ``(duration,
    max_acc_ratio, message)`` or, once the reference is planned (``known``), a
    :class:`~.timing.PartialTime` finished with its stretch times; a path the
    reference's times cannot finish is queued to be timed with them."""
    ready, waiting = [], []
    for fig, rows, path, limits in partial:
        if isinstance(fig, PartialTime):
            if not known:
                waiting.append((fig, rows, path, limits))
                continue
            whole = fig.finish(known[0])
            if whole is None:
                to_time.append((path, limits, rows))
                continue
            fig = (*whole, None)
        ready.extend((i, name, _with_duration(row, fig)) for i, name, row in rows)
    partial[:] = waiting
    return ready


def _timed_or_queued(job, row: VariantResult, timed, to_time, running, partial,
                     known) -> list:
    """The rows ready now for a solved ``job``: the row itself when it has no
    path to time, or with the cycle time of the same path planned already;
    else none, the row waiting for a plan of its path (running, waiting for
    the reference's, queued, or queued here)."""
    i, name, problem = job
    entry = (i, name, row)
    if not _timed(row):
        return [entry]
    twin = _of_path(timed, row.toolpath)
    if twin is not None and twin in running:
        running[twin][1].append(entry)
        return []
    if twin is not None:
        fig = twin.result()
        if isinstance(fig, PartialTime):
            held = _of_path(((p[2], p) for p in partial), row.toolpath)
            if held is not None:
                held[1].append(entry)
                return []
            whole = fig.finish(known[0]) if known else None
            fig = None if whole is None else (*whole, None)
        if fig is not None:
            return [(i, name, _with_duration(row, fig))]
    waiting = _of_path(((w[0], w) for w in to_time), row.toolpath)
    if waiting is not None:
        waiting[2].append(entry)
    else:
        to_time.append((row.toolpath, problem.limits, [entry]))
    return []


def _of_path(pairs, path: ToolPath):
    """The value paired with a tool path equal to ``path`` in ``(path, value)``
    ``pairs``, or None."""
    return next((value for p, value in pairs if p == path), None)


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


def _solve(name: str, problem: BlendProblem) -> VariantResult:
    """The blend ``name`` on ``problem``, certified and measured but for its cycle
    time (:func:`_measure_shape`); a blend that is refused, rejected or fails
    gives its row with the reason."""
    t0 = time.perf_counter()
    try:
        blend = load(name)
        out = blend(problem)
    except BlendRejected as exc:
        return VariantResult(name, "rejected", str(exc),
                             figures={"solve_time": time.perf_counter() - t0})
    except CcoptError as exc:
        return VariantResult(name, "refused", str(exc),
                             figures={"solve_time": time.perf_counter() - t0})
    except Exception as exc:  # a plug-in's bug must not hide the other variants
        return VariantResult(name, "failed", f"{type(exc).__name__}: {exc}",
                             figures={"solve_time": time.perf_counter() - t0})
    solve = time.perf_counter() - t0
    info: dict = {}
    cert = None
    if isinstance(out, BlendOutcome):
        info = dict(out.info)
        cert = info.pop("certificate", None)
        out = out.toolpath
    if not isinstance(out, ToolPath):
        return VariantResult(name, "failed", f"blend returned {type(out).__name__}, "
                             "not a ToolPath or BlendOutcome", figures={"solve_time": solve})
    return _measure_shape(name, out, problem, solve, info, cert)
