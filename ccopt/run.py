"""The main job: for each case or program, compensate, plan the feed, verify,
compare blend variants, export, and write one HTML report.

Used by ``ccopt run``. A case's ``case.toml`` gives its style, radius,
expected verdict (``ok``, ``gouge``, ``error``) and axis limits; a bare
program uses the command line's values or :data:`DEFAULT_LIMITS`.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ccopt.cases import Case
from ccopt.errors import CcoptError, ProgramError
from ccopt.export import export
from ccopt.export.atomic import write_text_atomic
from ccopt.program import read_program
from ccopt.toolpath import ToolPath, programmed_path

#: Axis limits for a program that is not a case and gets none on the command
#: line: 100 units/s and 1000 units/s^2 on every axis (a small mill in mm).
DEFAULT_LIMITS = {"v": (100.0, 100.0, 100.0), "a": (1000.0, 1000.0, 1000.0)}

PLANNERS = ("toppra", "stop", "junction")


@dataclass
class RunOptions:
    """What the command line can change for every input."""

    style: str | None = None
    radius: float | None = None
    side: str | None = None
    dialect: str | None = None
    tool_table: str | os.PathLike | None = None
    vmax: tuple[float, ...] | None = None
    amax: tuple[float, ...] | None = None
    compare: bool = True
    variants: list[str] | None = None     # blend variants compared (None: every available one)
    style_options: dict = field(default_factory=dict)


def _limits(case: Case | None, opts: RunOptions):
    from ccopt.feed import AxisLimits
    v = opts.vmax or (case.vmax if case and case.vmax else None) or DEFAULT_LIMITS["v"]
    a = opts.amax or (case.amax if case and case.amax else None) or DEFAULT_LIMITS["a"]
    return AxisLimits(v=list(v), a=list(a))


def run_one(label: str, program_file: Path, case: Case | None, out: Path | None,
            opts: RunOptions) -> dict:
    """Everything for one input; returns the row the report and summary use.

    ``status``: ``ok``; ``error (expected)``/``gouge (expected)`` when the case
    says so; ``error``/``FAILED``/``UNEXPECTED PASS`` otherwise. Bad input is
    reported in the row (``message``), never raised, so other inputs still run.
    """
    from ccopt.compensate import compensate
    expect = case.expect if case else "ok"
    row: dict = {"name": label, "program": str(program_file), "expect": expect,
                 "title": case.title if case else "", "source": case.source if case else ""}
    try:
        prog = read_program(program_file, opts.dialect, tool_table=opts.tool_table)
        style = opts.style or (case.style if case else "pmac")
        radius = opts.radius if opts.radius is not None else (case.radius if case else None)
        path = compensate(prog, style=style, radius=radius, side=opts.side, **opts.style_options)
    except CcoptError as exc:
        row.update(status="error (expected)" if expect == "error" else "error", message=str(exc))
        return row
    row.update(style=path.style, radius=path.radius, units=path.units,
               segments=len(path.segments), length=path.length)
    files: dict[str, str] = {}
    try:
        limits = _limits(case, opts)
        from ccopt.feed import ExactPath, plan_feed
        exact = ExactPath(path)
        profiles = {p: plan_feed(exact, limits, planner=p) for p in PLANNERS}
        row["feed"] = {p: prof.summary(prof.affordable_dt(1e-3)) for p, prof in profiles.items()}
        row["duration"] = profiles["toppra"].duration
        from ccopt.verify import verify
        cert = verify(path, prog, profile=profiles["toppra"])
        row["certificate"] = cert.to_json()
        row["verified"] = bool(cert.ok)
        row["min_clearance"] = cert.min_clearance
        if opts.compare:
            row["compare"] = _compare(prog, limits, radius, opts.side, opts.variants)
        if out is not None:
            stem = out / label
            for suffix in (".nc", ".pmc"):
                res = export(path, f"{stem}{suffix}", program=prog, title=row["title"] or label)
                files[suffix[1:]] = Path(res.file).name
            export(path, f"{stem}.svg", program=prog, title=label)
            files["svg"] = f"{label}.svg"
            best = profiles["toppra"]
            best.to_csv(f"{stem}.feed.csv", best.affordable_dt(1e-3))
            files["feed csv"] = f"{label}.feed.csv"
            write_text_atomic(f"{stem}.certificate.json", json.dumps(row["certificate"]) + "\n")
            files["certificate"] = f"{label}.certificate.json"
            write_text_atomic(f"{stem}.toolpath.json", json.dumps(path.to_json()) + "\n")
            files["tool path"] = f"{label}.toolpath.json"
            row["plots"] = _plots(path, prog, cert, profiles, label)
    except CcoptError as exc:
        row.update(status="error", message=str(exc), files=files)
        return row
    row["files"] = files
    if expect == "error":
        row["status"] = "UNEXPECTED PASS"
    elif cert.ok:
        row["status"] = "ok" if expect == "ok" else "UNEXPECTED PASS"
    else:
        row["status"] = "gouge (expected)" if expect == "gouge" else "FAILED"
    return row


def _compare(prog, limits, radius: float | None, side: str | None,
             variants: list[str] | None) -> list[dict]:
    """The blend comparison, with the same compensation overrides as the run
    (a case's radius, ``--radius``, ``--side``), so a program that names no
    radius (e.g. ``G41`` without ``D``) is compared, not refused."""
    from ccopt.compare import compare
    return [v.to_json() for v in compare(prog, variants, limits=limits, radius=radius, side=side)]


def _plots(path: ToolPath, prog, cert, profiles, label: str) -> dict:
    from ccopt.report.plots import feed_plot, path_plot, speed_time_plot
    contour = programmed_path(prog)
    viol = cert.to_json().get("violations", [])
    return {
        "tool path": path_plot(path, contour, path.radius, viol, f"{label}: programmed vs tool path"),
        "feed": feed_plot(profiles["toppra"], f"{label}: TOPPRA feed along the path"),
        "speed": speed_time_plot(profiles, f"{label}: speed against time"),
    }


def run_all(inputs: list[tuple[str, Path, Case | None]], out: Path | None, opts: RunOptions,
            progress: Callable[[int, int, str], None] | None = None) -> list[dict]:
    """Run every input, write the report into ``out`` (if given)."""
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ProgramError(f"cannot create output folder: {exc.strerror or exc}",
                               str(out)) from None
    rows = []
    for k, (label, program_file, case) in enumerate(inputs):
        if progress:
            progress(k, len(inputs), label)
        rows.append(run_one(label, program_file, case, out, opts))
    if progress:
        progress(len(inputs), len(inputs), "")
    if out is not None:
        from ccopt.report.html import render
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
