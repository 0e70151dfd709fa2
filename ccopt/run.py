"""The main job: for each case or program, compensate, plan the feed, verify,
compare blend variants, export, and write one HTML report.

Used by ``ccopt run``. Every input comes as a :class:`ccopt.cases.Job`, its
settings resolved once by :func:`ccopt.cases.resolve_input` (a case's
``case.toml`` gives its style, radius, expected verdict ``ok``, ``gouge`` or
``error``, and axis limits; a bare program uses the command line's values or
:data:`DEFAULT_LIMITS`), and runs through :func:`ccopt.pipeline.pipeline`, the
stages every command shares; this module adds the report's own files.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Protocol

# DEFAULT_LIMITS: the axis limits of an input with none (ccopt.cases defines them)
from ccopt.cases import DEFAULT_LIMITS, Job  # noqa: F401 - re-exported for ccopt run
from ccopt.compare.registry import available
from ccopt.errors import CcoptError, ProgramError
from ccopt.atomic import job_inputs, refuse_overwriting_inputs, write_text_atomic
from ccopt.export import refuse_foreign_files
from ccopt.pipeline import Outcome, StageClock, Target, pipeline
from ccopt.program.model import Program
from ccopt.report.html import PAGE_SUFFIX, render
from ccopt.report.plots import feed_plot, path_plot, speed_time_plot
from ccopt.toolpath import ToolPath, programmed_path
from ccopt.verify import Certificate
from ccopt.workers import run_in_workers

if TYPE_CHECKING:  # pragma: no cover - importing it loads toppra (see ccopt.feed)
    from ccopt.feed.profile import FeedProfile


#: the planners of every run: every one the limits allow (``jerk`` when they carry
#: jerk), resolved into each job (:meth:`ccopt.cases.Job.planners_for`)
PLANNERS = ("all",)

#: Sampling step of the feed figures and the feed CSV, seconds (fine enough to
#: show a millisecond-scale acceleration phase; longer paths get a coarser one,
#: :meth:`FeedProfile.affordable_dt`).
SAMPLE_DT = 1e-3

#: the exported programs of each input, in the order they are written
EXPORTS = (".nc", ".pmc", ".svg")


@dataclass
class RunOptions:
    """What the command line can change for the whole run (the per-input
    settings, the compared variants among them, are in each :class:`Job`)."""

    compare: bool = True
    compare_workers: int = 1              # worker processes of each comparison


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
    files: dict[str, str] = {}
    targets = [Target(f"{out / job.label}{suffix}", title=job.label if suffix == ".svg" else None)
               for suffix in EXPORTS] if out is not None else []
    done = pipeline(job, compare=opts.compare, export=targets, workers=opts.compare_workers,
                    clock=clock)
    _fill(row, done, files)
    # a program with no moves: nothing to plot or certify (issue 29)
    nothing = done.program.nothing_to_verify() if done.program is not None else None
    if done.error is None and out is not None and not nothing:
        try:
            clock("export")
            _write_files(out / job.label, done, row, files)
            row["plots"] = _plots(done.path, done.program, done.certificate, done.profiles,
                                  job.label, done.planner)
        except CcoptError as exc:
            done.error = exc
        finally:
            clock.stop()
    if done.error is not None:
        compensated = done.path is not None
        failed = "error (expected)" if job.expect == "error" and not compensated else "error"
        row.update(status=failed, message=str(done.error))
    elif nothing:
        # said in so many words, not "ok" over no checks (issue 29); exit 0
        row.update(status="nothing to verify", message=f"{done.program.file}: {nothing}")
    else:
        row["status"] = _status(job.expect, done.certificate.ok)
    row["stage_seconds"] = clock.seconds
    return row


def _fill(row: dict, done: Outcome, files: dict[str, str]) -> None:
    """``row`` with what the pipeline made (as far as it got)."""
    path = done.path
    if path is not None:
        row.update(style=path.style, radius=path.radius, units=path.units,
                   segments=len(path.segments), length=path.length)
        row["files"] = files
    if done.limits is not None:
        row.update(limits=done.limits.to_json(), limits_from=done.job.limits_from)
    if done.profiles:
        row["feed"] = {p: prof.summary(prof.affordable_dt(SAMPLE_DT))
                       for p, prof in done.profiles.items()}
        # the cycle time is the certified planner's: the jerk planner's when the
        # limits carry jerk (TOPPRA's profile would break them), else TOPPRA's
        row["planner"] = done.planner
        row["duration"] = done.duration
    cert = done.certificate
    if cert is not None:
        row["certificate"] = cert.to_json()
        row["certificate_text"] = cert.summary()
        row["verified"] = bool(cert.ok)
        row["verdict"] = cert.verdict          # ok, ok within tolerance or failed
        row["min_clearance"] = cert.min_clearance
    if done.comparison is not None:
        row["compare"] = [v.to_json() for v in done.comparison]
        # what this run left to be asked for (the lead families and opt-cvxpy by default)
        compared = {v["name"] for v in row["compare"]}
        row["not_compared"] = [n for n in available() if n not in compared]
    for res in done.exports:
        files[Path(res.file).suffix[1:]] = Path(res.file).name


def _write_files(stem: Path, done: Outcome, row: dict, files: dict[str, str]) -> None:
    """The feed CSV, certificate and tool path of one input beside its exported
    programs, named ``stem.*``; ``files`` maps what each is to its file name as
    they are written (so a failure still lists the ones that were)."""
    label = done.job.label
    best = done.profile
    best.to_csv(f"{stem}.feed.csv", best.affordable_dt(SAMPLE_DT))
    files["feed csv"] = f"{label}.feed.csv"
    write_text_atomic(f"{stem}.certificate.json", json.dumps(row["certificate"]) + "\n")
    files["certificate"] = f"{label}.certificate.json"
    write_text_atomic(f"{stem}.toolpath.json", json.dumps(done.path.to_json()) + "\n")
    files["tool path"] = f"{label}.toolpath.json"


def _status(expect: str, verified: bool) -> str:
    """The row's status once everything ran: the verdict against the case's ``expect``."""
    if expect == "error":
        return "UNEXPECTED PASS"
    if verified:
        return "ok" if expect == "ok" else "UNEXPECTED PASS"
    return "gouge (expected)" if expect == "gouge" else "FAILED"


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


#: the files of each input beside its exported programs (:func:`_write_files`)
FILES_PER_INPUT = (".feed.csv", ".certificate.json", ".toolpath.json")


def distinct_labels(jobs: list[Job]) -> list[Job]:
    """``jobs`` with labels no two of them share, as their files are named
    ``LABEL.*`` in one folder: a label two or more inputs share (``part.mpf``
    and ``part.h``, or two folders' ``part.nc``) becomes the program's file
    name with its suffix as a word (``part-mpf``, ``part-h``), then, where
    still shared, gets ``-2``, ``-3`` ... in the order given (the first keeps it)."""
    def shared(labels):
        return {a for a in labels if labels.count(a) > 1}

    labels = [j.label for j in jobs]
    twice = shared(labels)
    labels = [f"{j.program.stem}-{j.program.suffix.lstrip('.').lower()}"
              if a in twice and j.case is None and j.program.suffix else a
              for a, j in zip(labels, jobs)]
    seen: dict[str, int] = {}
    taken = set(labels)
    out = []
    for a, j in zip(labels, jobs):
        seen[a] = seen.get(a, 0) + 1
        label, k = a, seen[a]
        while k > 1 and label in taken:
            label = f"{a}-{k}"
            k += 1
        taken.add(label)
        out.append(j if label == j.label else replace(j, label=label))
    return out


def planned_files(jobs: list[Job], out: Path) -> list[Path]:
    """Every file :func:`run_all` writes into ``out`` (the report and each
    input's ``LABEL.*``): none of them may be an input."""
    return [out / "index.html", out / "summary.json",
            *(out / f"{job.label}{suffix}" for job in jobs
              for suffix in (*EXPORTS, *FILES_PER_INPUT, PAGE_SUFFIX))]


def run_all(jobs: list[Job], out: Path | None, opts: RunOptions,
            workers: int | None = None, progress: RunProgress | None = None) -> list[dict]:
    """Run every input, write the report into ``out`` (if given).

    ``workers``: ``None`` runs the inputs one after the other in this process;
    a number runs them in that many worker processes (:mod:`ccopt.workers`;
    1: one after the other, in one), which a Ctrl-C stops at once. The rows
    are the same either way, in the order of ``jobs``. ``progress`` hears
    each stage of each input and each input done.
    A :class:`ProgramError`, nothing written, when one of the files it would
    write (:func:`planned_files`) is one of the inputs (``-o .`` beside them),
    or a program there ccopt did not write (:func:`ccopt.export.refuse_foreign_files`).
    """
    labels = [j.label for j in jobs]
    if len(set(labels)) < len(labels):
        twice = sorted({a for a in labels if labels.count(a) > 1})
        raise ProgramError(f"two inputs share the label {twice[0]!r}: their files would "
                           "overwrite each other; give them distinct labels "
                           "(ccopt.run.distinct_labels)", twice[0])
    if out is not None:
        refuse_overwriting_inputs(planned_files(jobs, out), job_inputs(*jobs))
        # nor a program (or index.html) of the user's under a name run chooses
        refuse_foreign_files(planned_files(jobs, out))
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
        for name, page in render(rows).items():
            write_text_atomic(out / name, page)
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
