"""Research sweeps: many programs times many settings, on Dask.

::

    import ccopt
    table = ccopt.sweep("sweeps/styles-radii.toml")   # a local cluster, one worker per core
    table = ccopt.sweep(spec, client=my_dask_client, out="sweep-out")

The spec (:mod:`.spec`) names programs and axes; the sweep is the product
of the axes (:mod:`.tasks`); each task runs compensate -> feed -> verify
(-> compare) on one program (:mod:`.execute`) on a Dask worker
(:mod:`.engine`); the rows land in a resumable results folder
(:mod:`.results`) with a summary page (:mod:`.summary`). ``ccopt sweep`` is
:mod:`ccopt.cli.sweep`.

Importing this package imports neither Dask nor pandas nor pyarrow: they
load when a sweep runs, so ``import ccopt`` stays light.
"""
from __future__ import annotations

import os
import sys
import time
from datetime import datetime, timezone
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Callable

from ccopt.errors import CcoptError
from ccopt.program import read_program
from ccopt.sweep.engine import Progress, open_client, run_serial, run_tasks
from ccopt.sweep.results import (Flusher, columns, load_done, make_folder, write_meta,
                                 write_spec_copy)
from ccopt.sweep.spec import Spec, load_spec
from ccopt.sweep.summary import write_summary
from ccopt.sweep.tasks import ProgramInput, Task, expand, planned, resolve_programs
from ccopt.version import __version__


def _version(dist: str) -> str | None:
    try:
        return version(dist)
    except PackageNotFoundError:
        return None


def _read(programs: list[ProgramInput], labels: set[str]) -> dict:
    """label -> Program, or the error met reading it (the tasks' rows carry it)."""
    out = {}
    for p in programs:
        if p.label in labels:
            try:
                out[p.label] = read_program(p.file)
            except (CcoptError, OSError, UnicodeDecodeError) as exc:
                out[p.label] = exc
    return out


def _execute(todo: list[Task], programs: dict, run: int, flusher: Flusher, options: dict,
             log: Callable[[str], None]) -> None:
    progress = Progress(len(todo), options.get("progress"))
    try:
        def on_row(row: dict) -> None:
            flusher.add(row)
            progress.update(row)
        timeout = options.get("task_timeout")
        if options.get("serial"):
            run_serial(programs, todo, run, timeout, on_row)
            return
        session = open_client(options.get("client"), options.get("scheduler"),
                              options.get("workers"))
        try:
            if session.dashboard:
                log(f"Dask dashboard: {session.dashboard}")
            run_tasks(session, programs, todo, run, timeout, on_row)
        finally:
            session.close()
    finally:
        progress.close()


def _finish(out: Path | None, spec: Spec, table, meta: dict) -> None:
    if out is None:
        return
    meta["spec_copy"] = write_spec_copy(out, spec)
    write_meta(out, meta)
    write_summary(out, table, spec.title)


def sweep(spec, client=None, *, out: str | os.PathLike | None = None,
          scheduler: str | None = None, workers: int | None = None,
          task_timeout: float | None = None, progress: bool | None = None,
          serial: bool = False, log: Callable[[str], None] | None = None):
    """Run the sweep ``spec``; returns a pandas DataFrame, one row per task.

    Parameters
    ----------
    spec: a spec file (TOML, :mod:`.spec`), a dict written like one, or a :class:`Spec`.
    client: the user's ``distributed.Client`` (left open); default: a new
        ``LocalCluster`` of ``workers`` processes (one per core), or a client
        of ``scheduler`` (``tcp://host:8786``).
    out: results folder; when it holds results of this spec, only the
        missing tasks run (resume). ``None``: nothing is written.
    task_timeout: seconds per task; a task past it is a row with a timeout error.
    progress: a live bar on stderr (default: when stderr is a terminal).
    serial: run the tasks here, one after another, without Dask.
    log: where notes go (the dashboard's address); default: nowhere.

    ``table.attrs``: ``computed`` (tasks run now), ``total``, ``out``.
    """
    started = time.time()
    spec = load_spec(spec)
    programs = resolve_programs(spec)
    tasks = expand(spec, programs)
    folder = make_folder(out) if out is not None else None
    done = load_done(folder) if folder is not None else None
    have = set(done["task_id"]) if done is not None else set()
    todo = [t for t in tasks if t.id not in have]
    last = int(done["run"].max()) if done is not None and len(done) else 0
    run = last + 1 if todo else last  # a run that computes nothing is no new run
    flusher = Flusher(folder, done, [t.id for t in tasks], columns(spec, planned(spec, tasks)))
    options = {"client": client, "scheduler": scheduler, "workers": workers,
               "task_timeout": task_timeout, "progress": progress, "serial": serial}
    try:
        if todo:
            loaded = _read(programs, {t.program for t in todo})
            _execute(todo, loaded, run, flusher, options, log or (lambda _msg: None))
    finally:
        table = flusher.flush()
    meta = {"ccopt_version": __version__, "dask_version": _version("distributed"),
            "python": sys.version.split()[0], "title": spec.title, "tasks": len(tasks),
            "computed": len(todo), "failed": int(table["error"].notna().sum()), "run": run,
            "started": datetime.fromtimestamp(started, timezone.utc).isoformat(timespec="seconds"),
            "seconds": round(time.time() - started, 3)}
    _finish(folder, spec, table, meta)
    table.attrs.update(computed=len(todo), total=len(tasks),
                       out=str(folder) if folder is not None else None)
    return table


__all__ = ["Spec", "load_spec", "sweep"]
