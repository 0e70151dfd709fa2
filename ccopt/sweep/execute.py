"""One task: its job through :func:`ccopt.pipeline.pipeline` on one program.

:func:`run_task` is what a Dask worker runs; it never raises: a bad program,
a refused setting, a solver failure or a timeout is the row's ``error``.
Its figures are exactly those of ``ccopt run``, ``ccopt compare`` and the
public API on the same job (the same pipeline), e.g. with no variant::

    path = ccopt.compensate(prog, style=job.style, radius=job.radius, side=job.side)
    prof = ccopt.plan_feed(path, job.limits(), planner=p)
    cert = ccopt.verify(path, prog, profile=prof, radius=job.radius, side=job.side)

With a ``variant`` the path is that variant's from
:func:`ccopt.compare.compare` (its ``max_deviation`` from PMAC's path is the
row's ``deviation``), then planned and verified the same way.

Row figures (units: program units, seconds): ``cycle_time`` (the certified
planner's duration: the first of the spec's ``planners``, else the jerk
planner's with jerk limits, else TOPPRA's) and ``cycle_time_<planner>``,
``min_clearance`` (certified), ``ok`` (every check), ``geometry_ok`` (every
check but ``limits``), ``verdict`` (the certificate's: ``ok``, ``ok within
tolerance`` or ``failed``), ``limits_ok`` (the feed limits check on the certified
profile) and ``limits_ratio`` (its figure: the largest |value| / limit
sampled), ``limits_from`` (where the axis limits came from, :attr:`ccopt.cases.Job.limits_from`),
``cutter_radius``, ``path_length``, ``max_curvature`` (1/units,
largest |curvature| of the moves that cut, rapids excluded), ``deviation``,
``solve_time`` (building the path), ``feed_time`` (every planner),
``verify_time``, ``task_time`` (the whole task), ``worker`` (host:pid
that ran it), ``error``.
"""
from __future__ import annotations

import os
import socket
import threading
import time

import numpy as np

from ccopt.cases import Job
from ccopt.errors import CcoptError
from ccopt.pipeline import pipeline
from ccopt.program.model import Program
from ccopt.toolpath import Role

#: Curvature samples per spiral or blend curve (lines and arcs are exact at any count).
CURVATURE_SAMPLES = 257

#: Result columns every row has, in table order (``cycle_time_<planner>`` follow ``cycle_time``).
FIGURES = ("error", "ok", "verdict", "geometry_ok", "limits_ok", "limits_ratio", "limits_from",
           "cycle_time",
           "min_clearance", "cutter_radius", "path_length", "max_curvature", "deviation",
           "solve_time", "feed_time", "verify_time", "task_time", "worker")


class TaskTimeout(Exception):
    """The task ran past its time budget."""


def _check_time(deadline: float | None, stage: str) -> None:
    if deadline is not None and time.monotonic() > deadline:
        raise TaskTimeout(f"timeout before {stage}")


def max_curvature(path) -> float:
    """Largest |curvature| (1/units) over the segments that are not rapids."""
    worst = 0.0
    for seg in path.segments:
        if seg.role is Role.RAPID or seg.length <= 0:
            continue
        if seg.kind == "line":
            continue
        if seg.kind == "arc":
            k = 1.0 / seg.geom.radius
        else:
            s = np.linspace(0.0, seg.geom.length, CURVATURE_SAMPLES)
            k = float(np.max(np.abs(np.asarray(seg.geom.curvature(s), float))))
        worst = max(worst, k)
    return worst


def _verdicts(cert) -> dict:
    limits = [c for c in cert.checks if c.name == "limits"]
    geometry = [c for c in cert.checks if c.name != "limits"]
    limits_ok = ratio = None
    if limits and limits[0].basis != "not-run":
        limits_ok, ratio = bool(limits[0].ok), limits[0].figure
    return {"ok": bool(cert.ok), "verdict": cert.verdict,
            "geometry_ok": all(bool(c.ok) for c in geometry),
            "limits_ok": limits_ok, "limits_ratio": ratio, "min_clearance": cert.min_clearance}


def figures(program: Program, job: Job, deadline: float | None = None) -> dict:
    """The task's figures (see the module docstring); raises on failure."""
    def checkpoint(step: str) -> None:
        _check_time(deadline, step)

    done = pipeline(job, program=program, checkpoint=checkpoint).result()
    path = done.path
    row: dict = {"cutter_radius": path.radius, "path_length": path.length,
                 "max_curvature": max_curvature(path), "deviation": done.deviation,
                 "solve_time": done.solve_time}
    for planner, profile in done.profiles.items():
        row[f"cycle_time_{planner}"] = profile.duration
    row["feed_time"] = done.seconds.get("feed")
    row["cycle_time"] = done.duration
    # where the task's axis limits came from (Job.limits_from: case, default, ...)
    row["limits_from"] = job.limits_from
    row["verify_time"] = done.seconds.get("verify")
    row.update(_verdicts(done.certificate))
    return row


def _guarded(program: Program, job: Job, deadline: float | None) -> dict:
    """:func:`figures`, with any failure as the row's ``error``."""
    try:
        return figures(program, job, deadline)
    except TaskTimeout as exc:
        return {"error": f"timeout: {exc}"}
    except CcoptError as exc:
        return {"error": f"{type(exc).__name__}: {exc}"}
    except Exception as exc:  # a solver's or plug-in's failure must not end the sweep
        return {"error": f"{type(exc).__name__}: {exc}"}


def run_task(program, job: Job, timeout: float | None = None) -> dict:
    """Figures of one task; never raises.

    ``program``: a :class:`~ccopt.program.model.Program`, or the exception
    met reading it (the row then carries it). ``timeout`` (seconds): the
    task runs in a thread; past the timeout the row says so and the thread,
    which Python cannot kill, stops at its next stage (planner, verify).
    """
    t0 = time.perf_counter()
    if isinstance(program, BaseException):
        row = {"error": f"{type(program).__name__}: {program}"}
    elif timeout is None:
        row = _guarded(program, job, None)
    else:
        box: dict = {}
        deadline = time.monotonic() + timeout
        worker = threading.Thread(target=lambda: box.update(_guarded(program, job, deadline)),
                                  name="ccopt-sweep-task", daemon=True)
        worker.start()
        worker.join(timeout)
        row = dict(box) if not worker.is_alive() else {
            "error": f"timeout: still running after {timeout:g} s"}
    row["task_time"] = time.perf_counter() - t0
    row["worker"] = f"{socket.gethostname()}:{os.getpid()}"
    return row
