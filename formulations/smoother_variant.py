"""The ``smooth`` variant of ``ccopt compare``: the smoother, and the path it starts from.

The comparison hands each plug-in blend the fastest certified controller
variant's path (:attr:`~ccopt.compare.contract.BlendProblem.reference`). The
smoother keeps a path within its band (:func:`ccopt_formulations.smoother.smooth`),
so what it gains depends on where the path meets the contour as much as on
its corners: it cannot move a lead's join along the contour by more than the
band. The controller styles meet it two ways. PMAC, Fagor, HEIDENHAIN and
SINUMERIK reach the offset of the contour's first element at its start (at
right angles for a perpendicular lead) and leave the last one at its end;
LinuxCNC ends the entry move beside the programmed point, offset at right
angles to the entry move, and joins the contour as at any corner, at a
concave turn where the offsets meet (docs/compensation.md, LinuxCNC rules 1
and 2), and leaves likewise, so its path can run up to a cutter radius less
of the contour at each end (a closed contour is cut there on the way round)
and turn through less where the lead meets it. Smoothed, that path is often
the faster although its own cycle time is not (docs/benchmarks.md, blend
gains). So this variant smooths the path it is given and, where the
comparison offers it (:attr:`~ccopt.compare.contract.BlendProblem.alternatives`),
LinuxCNC's, and keeps the faster of the certified results. Each is timed
by stretches from the comparison's stretch times, as the comparison times
its rows, and the row's cycle time is read off them
(:attr:`~ccopt.compare.contract.BlendOutcome.stretch_times`). Without limits
(no cycle time) or the comparison's stretch times, the given path alone is
smoothed.
"""
from __future__ import annotations

from dataclasses import replace

from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.timing import duration_figures, stretch_keys
from ccopt.stand_ins import import_cvxpy
from ccopt_formulations.smoother import smooth

#: The controller variant whose path is smoothed too, when the comparison
#: offers it: the one whose entry and exit meet the contour as at a corner
#: (module docstring).
OTHER_START = "linuxcnc"


def smooth_variant(problem: BlendProblem) -> BlendOutcome:
    """Entry point ``smooth`` (group ``ccopt.blends``): the smoother at ``problem.band``
    from the path given and, where offered, LinuxCNC's (module docstring).
    Option ``conic_solver``: the CVXPY solver name (default ``"CLARABEL"``)."""
    starts = [(None, problem)]
    if problem.limits is not None and problem.stretch_times is not None:
        starts += [(name, replace(problem, reference=path, reference_certificate=cert))
                   for name, path, cert in problem.alternatives if name == OTHER_START]
    if len(starts) == 1:
        return BlendOutcome(*_smoothed(problem))
    best, why, tried = None, [], {}
    for name, start in starts:
        try:
            path, info = _smoothed(start)
        except BlendRejected as exc:
            why.append(str(exc) if name is None else f"from {name}'s path: {exc}")
            continue
        duration, own = _timed(path, problem)
        tried["given" if name is None else name] = duration
        if not info["certificate"].ok or duration is None:
            whose = "the given" if name is None else f"{name}'s"
            why.append(f"from {whose} path: not certified or not timed")
            continue
        if best is None or duration < best[0]:
            best = (duration, name, path, info, own)
    if best is None:
        raise BlendRejected("; ".join(why))
    _, name, path, info, own = best
    info["starts"] = tried
    if name is not None:
        info["started_from"] = name
    return BlendOutcome(path, info, stretch_times=own)


def _smoothed(problem: BlendProblem):
    """The smoother's path and info from ``problem.reference``."""
    path, info = smooth(problem, solver=str(problem.options.get("conic_solver", "CLARABEL")),
                        deviation=False, certifiable=True)
    for key in ("max_deviation", "max_deviation_bound"):
        info.pop(key)
    if info["joins_found"] and not info["joins_blended"]:
        raise BlendRejected("no join could be blended within the band")
    return path, info


def _timed(path, problem: BlendProblem):
    """``(cycle time, stretch times of path)`` as the comparison times a row:
    by stretches from its stretch times (a copy; ``(None, None)`` when the
    planner refuses the path)."""
    times = problem.stretch_times.copy()
    duration = duration_figures(path, problem.limits, times)[0]
    if duration is None:
        return None, None
    return duration, {k: times.known[k] for k in stretch_keys(path)
                      if k is not None and k in times.known}


#: what the blend imports only when it runs (:data:`ccopt.compare.contract.Blend`)
smooth_variant.imports = import_cvxpy
