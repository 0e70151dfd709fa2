"""The main job: for each case or program, compensate, plan the feed, verify,
compare blend variants, export, and write one HTML report.

Used by ``ccopt run``. Every input comes as a :class:`ccopt.cases.Job`, its
settings resolved once by :func:`ccopt.cases.resolve_input`: a case's
``case.toml`` gives its style, radius, expected verdict (``ok``, ``gouge``,
``error``) and axis limits; a bare program uses the command line's values or
:data:`DEFAULT_LIMITS`.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable

from ccopt.cases import Job
from ccopt.compare import compare
from ccopt.errors import CcoptError, ProgramError
from ccopt.export import export
from ccopt.atomic import write_text_atomic
from ccopt import feed as feed_planning
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program.model import Program
from ccopt.report.html import render
from ccopt.report.plots import feed_plot, path_plot, speed_time_plot
from ccopt.toolpath import ToolPath, programmed_path
from ccopt.verify import Certificate, verify

if TYPE_CHECKING:  # pragma: no cover - importing it loads toppra (see ccopt.feed)
    from ccopt.feed.profile import FeedProfile

#: Axis limits for a program that is not a case and gets none on the command
#: line: 100 units/s and 1000 units/s^2 on every axis (a small mill in mm).
DEFAULT_LIMITS = {"v": (100.0, 100.0, 100.0), "a": (1000.0, 1000.0, 1000.0)}

PLANNERS = ("toppra", "stop", "junction")

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


def run_one(job: Job, out: Path | None, opts: RunOptions) -> dict:
    """Everything for one input; returns the row the report and summary use.

    ``status``: ``ok``; ``error (expected)``/``gouge (expected)`` when the case
    says so; ``error``/``FAILED``/``UNEXPECTED PASS`` otherwise. Bad input is
    reported in the row (``message``), never raised, so other inputs still run.
    """
    expect = job.expect
    row: dict = {"name": job.label, "program": str(job.program), "expect": expect,
                 "title": job.title, "source": job.source}
    try:
        prog = job.read()
        path = job.compensate(prog)
    except CcoptError as exc:
        row.update(status="error (expected)" if expect == "error" else "error", message=str(exc))
        return row
    row.update(style=path.style, radius=path.radius, units=path.units,
               segments=len(path.segments), length=path.length)
    files: dict[str, str] = {}
    try:
        limits = job.limits()
        profiles = _plan(path, limits, row)
        cert = verify(path, prog, profile=profiles["toppra"])
        row["certificate"] = cert.to_json()
        row["verified"] = bool(cert.ok)
        row["min_clearance"] = cert.min_clearance
        if opts.compare:
            row["compare"] = _compare(prog, limits, job, opts.variants)
        if out is not None:
            _write_files(out / job.label, job, path, prog, profiles, row, files)
            row["plots"] = _plots(path, prog, cert, profiles, job.label)
    except CcoptError as exc:
        row.update(status="error", message=str(exc), files=files)
        return row
    row["files"] = files
    row["status"] = _status(expect, cert.ok)
    return row


def _plan(path: ToolPath, limits: AxisLimits, row: dict) -> dict[str, FeedProfile]:
    """Every planner's feed profile of ``path``; their summaries and the
    TOPPRA cycle time (s) go into ``row``."""
    # ccopt.feed loads ExactPath (and toppra, ~2 s) on first use, so `ccopt show` stays fast
    exact = feed_planning.ExactPath(path)
    profiles = {p: plan_feed(exact, limits, planner=p) for p in PLANNERS}
    row["feed"] = {p: prof.summary(prof.affordable_dt(SAMPLE_DT)) for p, prof in profiles.items()}
    row["duration"] = profiles["toppra"].duration
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
    best = profiles["toppra"]
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


def _compare(prog: Program, limits: AxisLimits, job: Job,
             variants: list[str] | None) -> list[dict]:
    """The blend comparison, with the same compensation overrides as the run
    (a case's radius, ``--radius``, ``--side``), so a program that names no
    radius (e.g. ``G41`` without ``D``) is compared, not refused."""
    return [v.to_json() for v in compare(prog, variants, limits=limits, radius=job.radius,
                                         side=job.side)]


def _plots(path: ToolPath, prog: Program, cert: Certificate, profiles: dict[str, FeedProfile],
           label: str) -> dict:
    contour = programmed_path(prog)
    viol = cert.to_json().get("violations", [])
    return {
        "tool path": path_plot(path, contour, path.radius, viol, f"{label}: programmed vs tool path"),
        "feed": feed_plot(profiles["toppra"], f"{label}: TOPPRA feed along the path"),
        "speed": speed_time_plot(profiles, f"{label}: speed against time"),
    }


def run_all(jobs: list[Job], out: Path | None, opts: RunOptions,
            progress: Callable[[int, int, str], None] | None = None) -> list[dict]:
    """Run every input, write the report into ``out`` (if given)."""
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ProgramError(f"cannot create output folder: {exc.strerror or exc}",
                               str(out)) from None
    rows = []
    for k, job in enumerate(jobs):
        if progress:
            progress(k, len(jobs), job.label)
        rows.append(run_one(job, out, opts))
    if progress:
        progress(len(jobs), len(jobs), "")
    if out is not None:
        write_text_atomic(out / "index.html", render(rows, "ccopt run"))
        summary = [{k: v for k, v in r.items() if k not in ("plots",)} for r in rows]
        write_text_atomic(out / "summary.json", json.dumps({"cases": summary}, default=str) + "\n")
    return rows


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
