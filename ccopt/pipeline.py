"""One pipeline for every entry point: a :class:`~ccopt.cases.Job` through
compensate -> feed -> verify -> compare -> export, as asked.

``ccopt run``, ``ccopt compare``, ``verify``, ``feed``, ``compensate``,
``export``, the sweep's tasks and the Python API all call :func:`pipeline`
with a job resolved once (:func:`ccopt.cases.resolve_input`); none orders the
stages or works out a setting by itself, so the same job gives the same
figures bit for bit whichever way it came in::

    job = ccopt.make_job("cases/pocket", vmax=(50, 50), amax=(500, 500))
    out = ccopt.pipeline(job).result()      # raises the error that stopped it, if any
    out.duration, out.certificate.ok, out.certificate.min_clearance

The stages:

- *compensate*: the job's style, radius, side and style options
  (:meth:`~ccopt.cases.Job.compensate`); or the job's ``variant``'s path from
  the comparison (:func:`ccopt.compare.compare`), or the tool path file it
  names (``toolpath``, verified as given).
- *feed*: every planner of :meth:`~ccopt.cases.Job.planners_for` under the
  job's limits, on one :class:`~ccopt.feed.ExactPath`; the certified one
  (:meth:`~ccopt.cases.Job.planner_for`) gives the cycle time.
- *verify*: :func:`ccopt.verify.verify` with the certified profile and the
  job's overrides and tolerances (:meth:`~ccopt.cases.Job.verify_options`).
- *compare*: the blend variants; when the job's own path is PMAC's (the
  comparison's reference), the comparison takes it and its plan
  (:class:`ccopt.compare.GivenReference`) instead of compensating again.
- *export*: the path written to each target (read back and verified,
  :func:`ccopt.export.export`).

Units: program units, seconds.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Sequence

from ccopt import feed as feed_planning
from ccopt.cases import Job
from ccopt.compare import REFERENCE, Comparison, GivenReference, compare
from ccopt.errors import CcoptError
from ccopt.export import ExportResult, export
from ccopt.feed import AxisLimits, certified_planner, plan_feed
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath
from ccopt.toolpath_json import read_toolpath_json
from ccopt.verify import Certificate, verify

if TYPE_CHECKING:  # pragma: no cover - importing it loads toppra (see ccopt.feed)
    from ccopt.feed.profile import FeedProfile


class StageClock:
    """The stages of one job (read, compensate, feed, verify, compare,
    export), each announced to ``progress`` as it starts and its wall time
    (s) kept in ``seconds``."""

    def __init__(self, progress: Callable[[str], None] | None = None):
        self.progress = progress
        self.seconds: dict[str, float] = {}
        self.stage: str | None = None
        self._t0 = 0.0

    def __call__(self, stage: str) -> None:
        """``stage`` starts now (the previous one ends)."""
        self.stop()
        self.stage, self._t0 = stage, time.perf_counter()
        self.say(stage)

    def say(self, text: str) -> None:
        if self.progress is not None:
            self.progress(text)

    def stop(self) -> None:
        if self.stage is not None:
            self.seconds[self.stage] = self.seconds.get(self.stage, 0.0) + \
                time.perf_counter() - self._t0
            self.stage = None


@dataclass(frozen=True)
class Target:
    """An export of the job's path: the ``file`` (its suffix names the format),
    the ``title`` in its header (``None``: the case's title, else the job's
    label; ``""``: none) and the arc-fit tolerance ``tol`` (program units; ``None``: the
    writer's default)."""

    file: str | Path
    title: str | None = None
    tol: float | None = None


@dataclass
class Outcome:
    """What :func:`pipeline` made of a job, as far as it got.

    ``path``: the job's tool path; ``style_from``: where its style comes from;
    ``limits``: the axis limits planned under; ``profiles``: planner name ->
    :class:`~ccopt.feed.FeedProfile`; ``planner``: the certified one;
    ``certificate``, ``comparison``, ``exports``: the later stages' results;
    ``deviation`` (program units) and ``solve_time`` (s): a variant's from the
    comparison, else ``None`` and the compensation's time; ``seconds``: each
    stage's wall time (s). ``error``: the :class:`~ccopt.errors.CcoptError`
    that stopped the pipeline in ``stage`` (``None``: it ran through).
    """

    job: Job
    program: Program | None = None
    path: ToolPath | None = None
    style_from: str | None = None
    limits: AxisLimits | None = None
    planner: str | None = None
    profiles: dict[str, FeedProfile] = field(default_factory=dict)
    certificate: Certificate | None = None
    comparison: Comparison | None = None
    exports: list[ExportResult] = field(default_factory=list)
    deviation: float | None = None
    solve_time: float | None = None
    seconds: dict[str, float] = field(default_factory=dict)
    error: CcoptError | None = None
    stage: str | None = None

    @property
    def profile(self) -> FeedProfile | None:
        """The certified planner's profile (``None`` when nothing was planned)."""
        return self.profiles.get(self.planner) if self.planner else None

    @property
    def duration(self) -> float | None:
        """The cycle time, s: the certified planner's duration."""
        return self.profile.duration if self.profile is not None else None

    def result(self) -> "Outcome":
        """This outcome, or the error that stopped the pipeline raised."""
        if self.error is not None:
            raise self.error
        return self


def pipeline(job: Job, *, program: Program | None = None, compensate: bool = True,
             feed: bool = True, verify: bool = True, compare: bool = False,
             export: Sequence[Target | str | Path] = (), workers: int = 1,
             progress: Callable[[str], None] | None = None,
             clock: StageClock | None = None,
             checkpoint: Callable[[str], None] | None = None) -> Outcome:
    """Run ``job`` through the stages asked for; never raises a
    :class:`~ccopt.errors.CcoptError` (it is the outcome's ``error``, with the
    stage it stopped in: :meth:`Outcome.result` raises it).

    ``program``: the job's program when the caller has read it (the sweep
    reads each once); ``compensate``: build the job's own path (implied by
    ``feed``, ``verify`` and ``export``; a comparison alone makes its own);
    ``workers``: the comparison's worker processes; ``progress(text)``: each
    stage as it starts and the comparison's variants (``clock``: the
    caller's :class:`StageClock`, which then also times them);
    ``checkpoint(step)``: called before each stage and each planner (the
    sweep's task timeout raises from it).
    """
    clock = clock if clock is not None else StageClock(progress)
    out = Outcome(job)
    try:
        _run(out, program, clock, checkpoint or (lambda _step: None),
             compensate or feed or verify or bool(export), feed, verify, compare, export,
             workers)
    except CcoptError as exc:
        out.error, out.stage = exc, clock.stage
    finally:
        clock.stop()
        out.seconds = dict(clock.seconds)
    return out


def _run(out: Outcome, program, clock: StageClock, checkpoint, build: bool, feed: bool,
         check: bool, comparing: bool, targets, workers: int) -> None:
    """The stages of :func:`pipeline`, filling ``out``; a CcoptError stops them."""
    job = out.job
    clock("read")
    out.program = program if program is not None else job.read()
    if build:
        checkpoint("compensate")
        clock("compensate")
        _build(out, clock)
    if feed or comparing:
        out.limits = job.limits()
    if feed:
        clock("feed")
        _plan(out, checkpoint)
    if check:
        checkpoint("verify")
        clock("verify")
        out.certificate = verify(out.path, out.program, profile=out.profile,
                                 **job.verify_options())
    if comparing:
        checkpoint("compare")
        clock("compare")
        out.comparison = _compare(out, clock, workers)
    if targets:
        checkpoint("export")
        clock("export")
        for target in targets:
            target = target if isinstance(target, Target) else Target(target)
            out.exports.append(export(out.path, target.file, program=out.program,
                                      tol=target.tol,
                                      title=job.title or job.label if target.title is None
                                      else target.title))


def _build(out: Outcome, clock: StageClock) -> None:
    """The job's tool path: a variant's, a tool path file's or the style's."""
    job, prog = out.job, out.program
    if job.toolpath is not None:
        out.path, out.style_from = read_toolpath_json(job.toolpath, prog), "a tool path file"
        return
    if job.variant is not None:
        # the variant's path from the comparison, limits and all, as `ccopt compare` makes it
        row = compare(prog, [job.variant], limits=job.limits(), delta=job.delta,
                      radius=job.radius, side=job.side, options=job.blend_options,
                      ts=job.ts, tolerance=job.tolerance)[job.variant]
        if row.toolpath is None:
            raise CcoptError(f"variant {job.variant} {row.status}: {row.message}")
        out.path, out.style_from = row.toolpath, "the variant's"
        out.deviation = row.figures.get("max_deviation")
        out.solve_time = row.figures.get("solve_time")
        return
    t0 = time.perf_counter()
    out.style_from = job.style_for(prog)[1]
    out.path = job.compensate(prog)
    out.solve_time = time.perf_counter() - t0


def _plan(out: Outcome, checkpoint) -> None:
    """Every planner of the job on one exact path; the certified one named."""
    job = out.job
    # ccopt.feed loads ExactPath (and toppra) on first use, so `ccopt show` stays fast
    exact = feed_planning.ExactPath(out.path)
    out.planner = job.planner_for(out.limits)
    for name in job.planners_for(out.limits):
        checkpoint(f"planner {name}")
        out.profiles[name] = plan_feed(exact, out.limits, planner=name, ts=job.ts,
                                       junction_deviation=job.junction_deviation)


def _compare(out: Outcome, clock: StageClock, workers: int) -> Comparison:
    """The blend comparison with the job's settings; PMAC's path and plan given
    when the job's own path is PMAC's (:func:`_own_reference`)."""
    job = out.job
    return compare(out.program, job.variants, limits=out.limits, delta=job.delta,
                   radius=job.radius, side=job.side, options=job.blend_options,
                   workers=workers, progress=lambda text: clock.say(f"compare: {text}"),
                   ts=job.ts, reference=_own_reference(out), tolerance=job.tolerance)


def _own_reference(out: Outcome) -> GivenReference | None:
    """The job's path as the comparison's reference, when it is the path the
    comparison would make: PMAC's style with no style option of its own, not
    a variant's or a file's (its plan with it, when the certified planner's
    is the comparison's)."""
    job = out.job
    if out.path is None or out.path.style != REFERENCE or job.style_options \
            or job.variant is not None or job.toolpath is not None:
        return None
    profile = out.profiles.get(certified_planner(out.limits)) if out.limits else None
    return GivenReference(out.path, out.solve_time or 0.0, profile)
