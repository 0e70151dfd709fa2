"""``compare``: every variant of one program, with the same figures.

For each variant: build its tool path (timed: ``solve_time``), certify it
with :func:`ccopt.verify.verify` against the program's contour, plan its feed
under the same limits, with TOPPRA, or with the jerk planner when the limits
carry jerk (``max_acc_ratio`` is the largest axis acceleration over its limit
in the profile sampled every 0.2 ms; the feed grid follows the turning inside
blend curves, :mod:`ccopt.feed.grid`), and measure it (:mod:`.figures`)
against the reference, PMAC's path. A variant that a controller refuses
(``refused``), that cannot be built or certified (``rejected``) or that fails
unexpectedly (``failed``) is still listed, with the reason and no figures.

The reference is planned once, whole; a variant's cycle time reuses the
reference's time on every stretch between two stops that it shares and
plans only the stretches it changed (:mod:`.timing`, where the rule and why
it is exact are). ``workers > 1`` runs the variants in that many worker
processes; the rows are the same as a serial run's (each variant starts
from the reference's stretch times alone), ``solve_time`` aside.
"""
from __future__ import annotations

import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Callable

from ccopt.compare.contract import BUILTIN_NAMES, BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.figures import max_deviation, path_figures
from ccopt.compare.leads import lead_joins
from ccopt.compare.registry import available, load
from ccopt.compensate import compensate
from ccopt.compare.timing import StretchTimes, duration_figures, planner_for, same_plan
from ccopt.errors import CcoptError
from ccopt.feed.limits import AxisLimits
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath

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
    status: str                     # ok | refused | rejected | failed
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
                "planner": planner_for(self.limits) if self.limits is not None else None,
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
    cert = certificate if certificate is not None else problem.certify(path)
    fig = path_figures(path, lead_joins(path))
    dur, acc_ratio, feed_msg = _duration(path, problem.limits, times)
    if problem.reference is not None:
        dev, dev_bound = max_deviation(path, problem.reference)
    else:  # no reference to measure against (PMAC refused the program)
        dev = dev_bound = None
    gouge = cert.check("gouge")
    fig.update(duration=dur, max_acc_ratio=acc_ratio,
               min_clearance=cert.min_clearance, certified=bool(cert.ok),
               clearance_ok=bool(gouge.ok), violations=len(cert.violations),
               max_deviation=dev, max_deviation_bound=dev_bound, solve_time=solve_time)
    return VariantResult(name, "ok", feed_msg, path, cert, fig, dict(info or {}))


def compare(program: Program, variants=None, *, limits: AxisLimits | None = None,
            delta: float | None = None, radius: float | None = None, side=None,
            options: dict | None = None, workers: int = 1,
            progress: Callable[[str], None] | None = None, ts: float | None = None,
            reference_profile: FeedProfile | None = None) -> Comparison:
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
    reference_profile: the reference's whole-path feed profile when the caller
        has planned it already (``ccopt run`` does, in its feed stage); used
        only when it is the plan this would make (:func:`.timing.same_plan`:
        PMAC's path, these limits, their planner and ``ts``), else ignored.
    """
    names = list(variants) if variants else available()
    known = set(available())
    t0 = time.perf_counter()
    reference = None
    ref_error = None
    try:
        reference = compensate(program, REFERENCE, radius=radius, side=side)
    except CcoptError as exc:
        ref_error = str(exc)
    ref_time = time.perf_counter() - t0
    opts = dict(options or {})
    problem = times = ref_row = None
    if reference is not None:
        problem = BlendProblem(program, reference, limits, delta, opts, radius, side)
        planned = reference_profile if same_plan(reference_profile, reference, limits, ts) \
            else None
        times = _reference_times(reference, limits, ts, planned)
    rows: list[VariantResult | None] = [None] * len(names)
    jobs: list[tuple[int, str, BlendProblem]] = []
    for i, name in enumerate(names):
        if name not in known:
            rows[i] = VariantResult(name, "failed", f"unknown variant {name!r}; known: "
                                    f"{', '.join(sorted(known))}")
        elif problem is None:
            if name == REFERENCE:
                rows[i] = VariantResult(name, "refused", ref_error)
            elif getattr(load(name), "compensates", False):
                # another controller style needs no reference: it may accept the program
                jobs.append((i, name, BlendProblem(program, None, limits, delta, opts, radius,
                                                   side)))
            else:
                rows[i] = VariantResult(name, "failed", f"no reference path: {ref_error}")
        elif name == REFERENCE:
            _say(progress, f"variant {i + 1}/{len(names)} {name}")
            rows[i] = ref_row = measure(name, reference, problem, ref_time, times=times)
        else:
            jobs.append((i, name, problem))
    for i, row in _run_jobs(jobs, times, len(names), workers, progress):
        rows[i] = row
    ref_duration = ref_row.figures.get("duration") if ref_row is not None else None
    if ref_duration is None and problem is not None and limits is not None:
        ref_duration = _duration(reference, limits, times)[0]
    for row in rows:
        d = row.figures.get("duration")
        if d is not None and ref_duration:
            row.figures["duration_ratio"] = d / ref_duration
    return Comparison(rows, reference, limits, program)


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


def _run_jobs(jobs, times: StretchTimes | None, total: int, workers: int, progress):
    """``(row index, VariantResult)`` of every job ``(index, name, problem)``: here,
    one after the other, or in ``workers`` processes."""
    if workers <= 1 or len(jobs) <= 1:
        for i, name, problem in jobs:
            _say(progress, f"variant {i + 1}/{total} {name}")
            local = problem if progress is None else replace(problem, progress=progress)
            yield i, _run(name, local, times.copy() if times is not None else None)
        return
    # fork where there is one: a worker then starts with ccopt and its libraries
    # loaded (spawning would import toppra, casadi and cvxpy again in each)
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context("fork" if "fork" in methods else None)
    with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=ctx) as pool:
        futures = [None] * len(jobs)
        for k, (_, name, problem) in _longest_first(jobs):
            futures[k] = pool.submit(_run, name, problem,
                                     times.copy() if times is not None else None)
        for done, ((i, name, _), fut) in enumerate(zip(jobs, futures), 1):
            row = fut.result()
            _say(progress, f"variant {i + 1}/{total} {name} done ({done}/{len(jobs)})")
            yield i, row


def _longest_first(jobs):
    """``(position, job)`` of ``jobs`` in the order to hand them to the workers:
    the plug-in blends first, the last listed first (they solve optimisation
    problems over the path: the smoother, listed last, took 17 s on
    freeform-hsm where each built-in variant took 0.5-2 s), so the longest job
    does not start last and leave the other workers idle."""
    return sorted(enumerate(jobs), key=lambda kj: (kj[1][1] in BUILTIN_NAMES, -kj[0]))


def _run(name: str, problem: BlendProblem, times: StretchTimes | None = None) -> VariantResult:
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
    return measure(name, out, problem, solve, info, cert, times)
