"""One task: compensate -> feed -> verify (-> compare) on one program, one setting.

:func:`run_task` is what a Dask worker runs; it never raises: a bad program,
a refused setting, a solver failure or a timeout is the row's ``error``.
Its figures are exactly those of the public API called by hand::

    path = ccopt.compensate(prog, style=s.style, radius=s.radius, side=s.side)
    prof = ccopt.plan_feed(path, ccopt.AxisLimits(**s.limits), planner=p)
    cert = ccopt.verify(path, prog, profile=prof, radius=s.radius, side=s.side)

With a ``variant`` the path is that variant's from
:func:`ccopt.compare.compare` (its ``max_deviation`` from PMAC's path is the
row's ``deviation``), then planned and verified the same way.

Row figures (units: program units, seconds): ``cycle_time`` (the first
planner's duration) and ``cycle_time_<planner>``, ``min_clearance``
(certified), ``ok`` (every check), ``geometry_ok`` (every check but
``limits``), ``limits_ok`` (the feed limits check on the first planner's
profile) and ``limits_ratio`` (its figure: the largest |value| / limit
sampled), ``cutter_radius``, ``path_length``, ``max_curvature`` (1/units,
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

from ccopt.compare import compare
from ccopt.compensate import compensate
from ccopt.errors import CcoptError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program.model import Program
from ccopt.sweep.tasks import Setting
from ccopt.toolpath import Role
from ccopt.verify import verify

#: Curvature samples per spiral or blend curve (lines and arcs are exact at any count).
CURVATURE_SAMPLES = 257

#: Result columns every row has, in table order (``cycle_time_<planner>`` follow ``cycle_time``).
FIGURES = ("error", "ok", "geometry_ok", "limits_ok", "limits_ratio", "cycle_time",
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


def build_path(program: Program, s: Setting):
    """``(tool path, deviation from PMAC's path or None, seconds to build it)``."""
    t0 = time.perf_counter()
    if s.variant is None:
        path = compensate(program, style=s.style, radius=s.radius, side=s.side)
        return path, None, time.perf_counter() - t0
    cmp = compare(program, [s.variant], limits=AxisLimits(**s.limits), delta=s.delta,
                  radius=s.radius, side=s.side)
    row = cmp[s.variant]
    if row.status != "ok" or row.toolpath is None:
        raise CcoptError(f"variant {s.variant} {row.status}: {row.message}")
    return row.toolpath, row.figures.get("max_deviation"), row.figures.get("solve_time")


def _verdicts(cert) -> dict:
    limits = [c for c in cert.checks if c.name == "limits"]
    geometry = [c for c in cert.checks if c.name != "limits"]
    limits_ok = ratio = None
    if limits and limits[0].basis != "not-run":
        limits_ok, ratio = bool(limits[0].ok), limits[0].figure
    return {"ok": bool(cert.ok), "geometry_ok": all(bool(c.ok) for c in geometry),
            "limits_ok": limits_ok, "limits_ratio": ratio, "min_clearance": cert.min_clearance}


def pipeline(program: Program, s: Setting, deadline: float | None = None) -> dict:
    """The task's figures (see the module docstring); raises on failure."""
    path, deviation, solve_time = build_path(program, s)
    row: dict = {"cutter_radius": path.radius, "path_length": path.length,
                 "max_curvature": max_curvature(path), "deviation": deviation,
                 "solve_time": solve_time}
    limits = AxisLimits(**s.limits)
    profiles = {}
    t0 = time.perf_counter()
    for planner in s.planners:
        _check_time(deadline, f"planner {planner}")
        profiles[planner] = plan_feed(path, limits, planner=planner)
        row[f"cycle_time_{planner}"] = profiles[planner].duration
    row["feed_time"] = time.perf_counter() - t0
    row["cycle_time"] = profiles[s.planners[0]].duration
    _check_time(deadline, "verify")
    t0 = time.perf_counter()
    cert = verify(path, program, profile=profiles[s.planners[0]], radius=s.radius, side=s.side)
    row["verify_time"] = time.perf_counter() - t0
    row.update(_verdicts(cert))
    return row


def _guarded(program: Program, s: Setting, deadline: float | None) -> dict:
    """:func:`pipeline`, with any failure as the row's ``error``."""
    try:
        return pipeline(program, s, deadline)
    except TaskTimeout as exc:
        return {"error": f"timeout: {exc}"}
    except CcoptError as exc:
        return {"error": f"{type(exc).__name__}: {exc}"}
    except Exception as exc:  # a solver's or plug-in's failure must not end the sweep
        return {"error": f"{type(exc).__name__}: {exc}"}


def run_task(program, s: Setting, timeout: float | None = None) -> dict:
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
        row = _guarded(program, s, None)
    else:
        box: dict = {}
        deadline = time.monotonic() + timeout
        worker = threading.Thread(target=lambda: box.update(_guarded(program, s, deadline)),
                                  name="ccopt-sweep-task", daemon=True)
        worker.start()
        worker.join(timeout)
        row = dict(box) if not worker.is_alive() else {
            "error": f"timeout: still running after {timeout:g} s"}
    row["task_time"] = time.perf_counter() - t0
    row["worker"] = f"{socket.gethostname()}:{os.getpid()}"
    return row
