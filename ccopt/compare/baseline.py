"""Optimised blends never lose to a controller: the gains and the fallback.

A researcher quotes an optimised blend against what the machines already
do. The plug-in blends are solved after the controllers, from the fastest
certified controller variant's path (its leads their starting point;
:func:`ccopt.compare.compare`), and every row gets its **gain** against PMAC
(the reference) and against that fastest certified controller variant
(:data:`~ccopt.compare.contract.CONTROLLER_NAMES`): ``gain = 1 - t / t_base``,
positive when the row is faster. A plug-in blend (opt-casadi, opt-cvxpy, the
smoother: neither a controller's path nor a built-in geometric lead) that
made a path is only reported when it is a **certified improvement**: one
that is not certified, or slower than that controller variant by more than
:data:`SAME_TIME_REL`, is replaced by the controller's path, its row saying
"no faster certified blend" and keeping what the optimiser found in
``info["optimised"]`` (status, cycle time, message, figures), so the table
never shows a slower blend as the optimised answer. A plug-in that found no
blend at all (``rejected``: no lead could be replaced within its constraints)
is the same answer, "no faster certified blend", with its reason; one that
crashed (``failed``) or was refused keeps its row, so that the fault shows.
"""
from __future__ import annotations

from dataclasses import replace

from ccopt.compare.contract import BUILTIN_NAMES, CONTROLLER_NAMES

#: Two cycle times within this relative difference are the same time (the
#: planners' own rounding is far below it).
SAME_TIME_REL = 1e-9

#: Status of a plug-in row that kept the fastest controller variant's path.
NO_FASTER = "no faster certified blend"


def fastest_controller(rows) -> object | None:
    """The certified controller row with the shortest cycle time (``None``
    when no controller variant is certified and timed)."""
    timed = [r for r in rows if r.name in CONTROLLER_NAMES and r.status == "ok"
             and r.figures.get("duration") is not None]
    return min(timed, key=lambda r: r.figures["duration"], default=None)


def base_row(rows, reference_name: str):
    """The fastest certified controller variant's row when it is not the
    reference's (the plug-in blends then start from its path), else ``None``."""
    best = fastest_controller([r for r in rows if r is not None])
    return best if best is not None and best.name != reference_name else None


def from_base(row, base: str):
    """A plug-in ``row`` solved from controller ``base``'s path, saying where it
    started (``info["base"]``; its deviation is measured from the reference
    path as every row's, :attr:`~ccopt.compare.contract.BlendProblem.deviation_from`)."""
    own = row.info.get("started_from")
    if own is not None and own != base:     # the blend started from another one
        row.info["base"] = own
        note = (f"started from {own}'s path (a certified controller variant; the fastest "
                f"is {base}'s)")
    else:
        row.info["base"] = base
        note = f"started from {base}'s path (the fastest certified controller variant)"
    row.message = note if row.message is None else f"{note}; {row.message}"
    return row


def apply_baseline(rows, reference_name: str) -> None:
    """Gains on every timed row, and the fallback of every plug-in row that is
    no certified improvement (in place; see the module docstring)."""
    best = fastest_controller(rows)
    ref = next((r for r in rows if r.name == reference_name and r.status == "ok"), None)
    if best is not None:
        t_best = best.figures["duration"]
        for i, row in enumerate(rows):
            if row.name in BUILTIN_NAMES or (row.toolpath is None and row.status != "rejected"):
                continue            # a controller's or geometric lead's, or a fault
            t = row.figures.get("duration")
            improved = row.status == "ok" and t is not None \
                and t <= t_best * (1.0 + SAME_TIME_REL)
            if not improved:
                rows[i] = _kept(row, best)
    t_ref = ref.figures.get("duration") if ref is not None else None
    t_best = best.figures["duration"] if best is not None else None
    for row in rows:
        t = row.figures.get("duration")
        row.figures["gain_vs_pmac"] = None if t is None or not t_ref else 1.0 - t / t_ref
        row.figures["gain_vs_fastest_controller"] = \
            None if t is None or not t_best else 1.0 - t / t_best
        if best is not None:
            row.figures["fastest_controller"] = best.name


def _kept(row, best):
    """``row`` carrying ``best``'s path and figures, and its own in ``info``."""
    own = {"status": row.status, "duration": row.figures.get("duration"),
           "message": row.message, "certified": row.figures.get("certified"),
           "figures": dict(row.figures)}
    t = own["duration"]
    why = (f"none found: {row.message}" if row.status == "rejected" else
           "it is not certified" if row.status != "ok" else
           "it has no cycle time" if t is None else
           f"{t:.6g} s is slower than {best.name}'s {best.figures['duration']:.6g} s")
    message = f"{NO_FASTER}: {best.name}'s path kept ({row.name}'s own blend: {why})"
    info = {**row.info, "optimised": own, "baseline": best.name}
    figures = {**best.figures, "solve_time": row.figures.get("solve_time")}
    return replace(row, status="ok", message=message, toolpath=best.toolpath,
                   certificate=best.certificate, figures=figures, info=info)

