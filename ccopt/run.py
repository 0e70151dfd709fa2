"""The main job: for each case or program, compensate, plan the feed, verify,
compare blend variants, export, and write one HTML report.

Used by ``ccopt run``. Every input comes as a :class:`ccopt.cases.Job`, its
settings resolved once by :func:`ccopt.cases.resolve_input`: a case's
``case.toml`` gives its style, radius, expected verdict (``ok``, ``gouge``,
``error``) and axis limits; a bare program uses the command line's values or
:data:`DEFAULT_LIMITS`.
"""
from __future__ import annotations

import inspect
import json
import os
import time
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Protocol

# DEFAULT_LIMITS: the axis limits of an input with none (ccopt.cases defines them)
from ccopt.cases import DEFAULT_LIMITS, Job  # noqa: F401 - re-exported for ccopt run
from ccopt.compare import compare
from ccopt.errors import CcoptError, ProgramError
from ccopt.export import export
from ccopt.atomic import write_text_atomic
from ccopt import feed as feed_planning
from ccopt.feed import AxisLimits, certified_planner, plan_feed
from ccopt.program.model import Program
from ccopt.report.html import render
from ccopt.report.plots import feed_plot, path_plot, speed_time_plot
from ccopt.toolpath import ToolPath, programmed_path
from ccopt.verify import Certificate, verify
from ccopt.workers import run_in_workers

if TYPE_CHECKING:  # pragma: no cover - importing it loads toppra (see ccopt.feed)
    from ccopt.feed.profile import FeedProfile


#: the planners of every run (``jerk`` joins them when the limits carry jerk)
PLANNERS = ("toppra", "stop", "junction")

#: the parameters the installed :func:`ccopt.compare.compare` takes
COMPARE_PARAMETERS = frozenset(inspect.signature(compare).parameters)

#: Sampling step of the feed figures and the feed CSV, seconds (fine enough to
#: show a millisecond-scale acceleration phase; longer paths get a coarser one,
#: :meth:`FeedProfile.affordable_dt`).
SAMPLE_DT = 1e-3


@dataclass
class RunOptions:
    """What the command line can change for the whole run (the per-input
    settings are in each :class:`Job`)."""

    compare: bool = True
    variants: list[str] | None = None     # blend variants compared (None: every available one)
    compare_workers: int = 1              # worker processes of each comparison


class StageClock:
    """The stages of one input (read, compensate, feed, verify, compare,
    export), each announced to ``progress`` as it starts and its wall time
    (s) kept in ``seconds``."""

    def __init__(self, progress: Callable[[str], None] | None = None):
        self.progress = progress
        self.seconds: dict[str, float] = {}
        self._stage: str | None = None
        self._t0 = 0.0

    def __call__(self, stage: str) -> None:
        """``stage`` starts now (the previous one ends)."""
        self.stop()
        self._stage, self._t0 = stage, time.perf_counter()
        self.say(stage)

    def say(self, text: str) -> None:
        if self.progress is not None:
            self.progress(text)

    def stop(self) -> None:
        if self._stage is not None:
            self.seconds[self._stage] = self.seconds.get(self._stage, 0.0) + \
                time.perf_counter() - self._t0
            self._stage = None


def run_one(job: Job, out: Path | None, opts: RunOptions,
            progress: Callable[[str], None] | None = None) -> dict:
    """Everything for one input; returns the row the report and summary use.

    ``status``: ``ok``; ``error (expected)``/``gouge (expected)`` when the case
    says so; ``error``/``FAILED``/``UNEXPECTED PASS`` otherwise. Bad input is
    reported in the row (``message``), never raised, so other inputs still run.
    ``progress(text)`` hears each stage as it starts (and the comparison's
    variants); ``row["stage_seconds"]`` is each stage's wall time.
    """
    clock = StageClock(progress)
    row: dict = {"name": job.label, "program": str(job.program), "expect": job.expect,
                 "title": job.title, "source": job.source}
    try:
        _run_stages(job, out, opts, row, clock)
    except CcoptError as exc:
        failed = "error (expected)" if job.expect == "error" and "style" not in row else "error"
        row.update(status=failed, message=str(exc))
    finally:
        clock.stop()
        row["stage_seconds"] = clock.seconds
    return row


def _run_stages(job: Job, out: Path | None, opts: RunOptions, row: dict,
                clock: StageClock) -> None:
    """The stages of :func:`run_one`, filling ``row``; a CcoptError stops them."""
    clock("read")
    prog = job.read()
    clock("compensate")
    path = job.compensate(prog)
    row.update(style=path.style, radius=path.radius, units=path.units,
               segments=len(path.segments), length=path.length)
    files: dict[str, str] = {}
    row["files"] = files
    limits = job.limits()
    row.update(limits=limits.to_json(), limits_from=job.limits_from)
    clock("feed")
    profiles = _plan(path, limits, row, job.ts)
    clock("verify")
    cert = verify(path, prog, profile=profiles[row["planner"]])
    row["certificate"] = cert.to_json()
    row["certificate_text"] = cert.summary()
    row["verified"] = bool(cert.ok)
    row["min_clearance"] = cert.min_clearance
    if opts.compare:
        clock("compare")
        row["compare"] = _compare(prog, limits, job, opts, clock.say, profiles[row["planner"]])
    if out is not None:
        clock("export")
        _write_files(out / job.label, job, path, prog, profiles, row, files)
        row["plots"] = _plots(path, prog, cert, profiles, job.label, row["planner"])
    row["status"] = _status(job.expect, cert.ok)


def _plan(path: ToolPath, limits: AxisLimits, row: dict,
          ts: float | None = None) -> dict[str, FeedProfile]:
    """Every planner's feed profile of ``path`` (``ts``: the interpolation
    period of the jerk-limited planners, s; ``None``: their default); their
    summaries and the TOPPRA cycle time (s) go into ``row``."""
    # ccopt.feed loads ExactPath (and toppra, ~2 s) on first use, so `ccopt show` stays fast
    exact = feed_planning.ExactPath(path)
    planners = PLANNERS + (("jerk",) if limits.j is not None else ())
    profiles = {p: plan_feed(exact, limits, planner=p, ts=ts) for p in planners}
    row["feed"] = {p: prof.summary(prof.affordable_dt(SAMPLE_DT)) for p, prof in profiles.items()}
    # the cycle time is the certified planner's: the jerk planner's when the
    # limits carry jerk (TOPPRA's profile would break them), else TOPPRA's
    row["planner"] = certified_planner(limits)
    row["duration"] = profiles[row["planner"]].duration
    return profiles


def _write_files(stem: Path, job: Job, path: ToolPath, prog: Program,
                 profiles: dict[str, FeedProfile], row: dict, files: dict[str, str]) -> None:
    """The exported programs, SVG, feed CSV, certificate and tool path of one
    input, named ``stem.*``; ``files`` maps what each is to its file name as
    they are written (so a failure still lists the ones that were)."""
    label = job.label
    for suffix in (".nc", ".pmc"):
        res = export(path, f"{stem}{suffix}", program=prog, title=row["title"] or label)
        files[suffix[1:]] = Path(res.file).name
    export(path, f"{stem}.svg", program=prog, title=label)
    files["svg"] = f"{label}.svg"
    best = profiles[row["planner"]]
    best.to_csv(f"{stem}.feed.csv", best.affordable_dt(SAMPLE_DT))
    files["feed csv"] = f"{label}.feed.csv"
    write_text_atomic(f"{stem}.certificate.json", json.dumps(row["certificate"]) + "\n")
    files["certificate"] = f"{label}.certificate.json"
    write_text_atomic(f"{stem}.toolpath.json", json.dumps(path.to_json()) + "\n")
    files["tool path"] = f"{label}.toolpath.json"


def _status(expect: str, verified: bool) -> str:
    """The row's status once everything ran: the verdict against the case's ``expect``."""
    if expect == "error":
        return "UNEXPECTED PASS"
    if verified:
        return "ok" if expect == "ok" else "UNEXPECTED PASS"
    return "gouge (expected)" if expect == "gouge" else "FAILED"


def _compare(prog: Program, limits: AxisLimits, job: Job, opts: RunOptions,
             say: Callable[[str], None], reference_profile: FeedProfile | None = None) -> list[dict]:
    """The blend comparison, with the same compensation overrides as the run
    (a case's radius, ``--radius``, ``--side``), so a program that names no
    radius (e.g. ``G41`` without ``D``) is compared, not refused.
    ``reference_profile``: the run's certified plan of its own path, which
    the comparison reuses for PMAC's path when that is the path it planned
    (not on a Fagor or LinuxCNC case)."""
    extra = compare_extras(lambda text: say(f"compare: {text}"), opts.compare_workers, job.ts,
                           reference_profile)
    return [v.to_json() for v in compare(prog, opts.variants, limits=limits, radius=job.radius,
                                         side=job.side, **extra)]


def compare_extras(progress: Callable[[str], None] | None, workers: int,
                   ts: float | None = None, reference_profile: FeedProfile | None = None) -> dict:
    """The ``progress``, ``workers``, ``ts`` and ``reference_profile``
    arguments for :func:`ccopt.compare.compare`, as far as the installed one
    takes them (they came with issue 17; an older one is called without them,
    one at a time)."""
    given = {"progress": progress, "workers": workers, "reference_profile": reference_profile}
    if ts is not None:
        given["ts"] = ts
    return {k: v for k, v in given.items() if k in COMPARE_PARAMETERS}


def _plots(path: ToolPath, prog: Program, cert: Certificate, profiles: dict[str, FeedProfile],
           label: str, planner: str = "toppra") -> dict:
    contour = programmed_path(prog)
    name = "jerk-limited" if planner == "jerk" else "TOPPRA"
    viol = cert.to_json().get("violations", [])
    return {
        "tool path": path_plot(path, contour, path.radius, viol, f"{label}: programmed vs tool path"),
        "feed": feed_plot(profiles[planner], f"{label}: {name} feed along the path"),
        "speed": speed_time_plot(profiles, f"{label}: speed against time"),
    }


def run_all(jobs: list[Job], out: Path | None, opts: RunOptions,
            workers: int | None = None, progress: RunProgress | None = None) -> list[dict]:
    """Run every input, write the report into ``out`` (if given).

    ``workers``: ``None`` runs the inputs one after the other in this process;
    a number runs them in that many worker processes (:mod:`ccopt.workers`;
    1: one after the other, in one), which a Ctrl-C stops at once. The rows
    are the same either way, in the order of ``jobs``. ``progress`` hears
    each stage of each input and each input done.
    """
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ProgramError(f"cannot create output folder: {exc.strerror or exc}",
                               str(out)) from None
    work = partial(_run_job, out=out, opts=opts)
    if workers is None:
        rows = []
        for k, job in enumerate(jobs):
            rows.append(work(job, partial(progress.stage, k) if progress else None))
            if progress:
                progress.done(k, rows[-1])
    else:
        rows = run_in_workers(work, jobs, workers,
                              on_progress=progress.stage if progress else None,
                              on_done=progress.done if progress else None,
                              temp_folders=[out] if out is not None else [],
                              order=longest_first(jobs))
    if out is not None:
        write_text_atomic(out / "index.html", render(rows, "ccopt run"))
        summary = [{k: v for k, v in r.items() if k not in ("plots",)} for r in rows]
        write_text_atomic(out / "summary.json", json.dumps({"cases": summary}, default=str) + "\n")
    return rows


def longest_first(jobs: list[Job]) -> list[int]:
    """The indices of ``jobs``, the largest program first: a program's size
    (bytes) is the cheap guess of its work (blocks to compensate, corners to
    blend, stretches to plan); one gone since it was resolved goes last (its
    row then says why)."""
    def size(k: int) -> int:
        try:
            return os.path.getsize(jobs[k].program)
        except OSError:
            return -1
    return sorted(range(len(jobs)), key=lambda k: -size(k))


def _run_job(job: Job, progress: Callable[[str], None] | None, out: Path | None,
             opts: RunOptions) -> dict:
    """:func:`run_one` with the worker's progress (the signature :func:`run_in_workers` calls)."""
    return run_one(job, out, opts, progress)


class RunProgress(Protocol):
    """What :func:`run_all` tells as it goes: input ``index`` is at ``text``
    (a stage, or a comparison's variant), input ``index`` is done (its row)."""

    def stage(self, index: int, text: str) -> None: ...

    def done(self, index: int, row: dict) -> None: ...


def exit_code(rows: list[dict]) -> int:
    """0 when every input did what it should, 1 when a verification failed,
    2 when an input could not be read or compensated (and was not expected to)."""
    if any(r["status"] == "error" for r in rows):
        return 2
    if any(r["status"] in ("FAILED", "UNEXPECTED PASS") for r in rows):
        return 1
    return 0


def default_out() -> Path:
    return Path(os.environ.get("CCOPT_OUT", "ccopt-out"))
