"""SINUMERIK 840D approach families as comparison variants.

``siemens`` is the ``siemens`` style (docs/compensation.md, section 11) as
the program asks (its G450/G451, NORM/KONT and smooth approaches; the
defaults for programs of other dialects). Each other variant is the style
with one approach and retraction family forced on every lead-in and
lead-out, and the family's parameter chosen as the fastest certified member
of a small set:

* ``siemens-norm``, ``siemens-kont``: ``NORM`` / ``KONT`` (SINUMERIK rule 4),
  the outside-corner mode chosen from ``G450`` and ``G451``;
* ``siemens-g147``, ``siemens-g247``, ``siemens-g347``: the smooth approach
  and retraction on a line, a quadrant, a semicircle (SINUMERIK rule 5),
  ``DISR`` chosen from :data:`DISR_FACTORS` times the cutter radius.

"Fastest" is the cycle time under the comparison's limits (planned stretch
by stretch, the stretches the members share once:
:class:`~ccopt.compare.timing.StretchTimes`, starting from the reference's
stretches and those of the ``siemens`` path as the program asks, planned
once per process: :func:`_base_times`); without limits, the shortest path.
The row's cycle time is the chosen member's figure, read off the stretch
times it was timed with (:attr:`~ccopt.compare.contract.BlendOutcome.stretch_times`).
A member the verifier does not certify (a gouge, a gap, a side fault) is
not chosen; with none certified the variant is rejected with the reasons.
The row's ``info`` names the member chosen and every member's figure.
"""
from __future__ import annotations

import math

from ccopt.compare.contract import (SIEMENS_NAMES, Blend, BlendOutcome, BlendProblem,
                                    BlendRejected, deepest)
from ccopt.compare.leads import find_leads, outside_leads
from ccopt.compare.timing import StretchTimes, duration_figures, reference_times, stretch_keys
from ccopt.compensate import compensate
from ccopt.errors import CcoptError
from ccopt.toolpath import ToolPath

#: DISR of each smooth approach family, in cutter radii (G147: the cutter
#: edge's distance from the contour; G247/G347: the tool-centre arc's radius).
DISR_FACTORS = {"G147": (0.0, 0.5, 1.0), "G247": (0.5, 1.0, 2.0), "G347": (0.5, 1.0, 2.0)}
CORNERS = ("G450", "G451")
#: The verifier's findings that keep a member from being chosen.
_FAULTS = ("gouge", "gap", "side")
#: Base stretch times kept per process (:func:`_base_times`): a comparison
#: needs one (its limits, ``ts`` and program); a sweep's worker moves on.
_BASES_KEPT = 4
_BASES: dict = {}


def _base_times(problem: BlendProblem) -> StretchTimes:
    """A copy of the comparison reference's stretch times
    (:attr:`~ccopt.compare.contract.BlendProblem.stretch_times`, else planned
    here) with those of the ``siemens`` path as the program asks, timed as the
    comparison times that path's own row (:meth:`StretchTimes.time` from the
    reference's): planned once per process for this reference, path, limits
    and ``ts``.

    Why: the families change that path only at its leads (and NORM/KONT at
    the corners their G450/G451 member changes), so each member plans only
    the stretches it changes, and a member that leaves the path as it is
    gets the ``siemens`` row's figure exactly. The memo is keyed by both
    paths' stretch keys, the limits and ``ts``, so a family's figures do not
    depend on which families ran before it in the process (serial and
    parallel comparisons agree); each family gets a copy, so the stretches
    its own members add reach no other. Just the reference's where the style
    refuses the program or the planner its path (the members then say why)."""
    try:
        path = compensate(problem.program, "siemens", radius=problem.radius, side=problem.side)
        ref_keys = None if problem.reference is None else tuple(stretch_keys(problem.reference))
        key = (problem.limits, problem.ts, ref_keys, tuple(stretch_keys(path)))
    except CcoptError:
        return _known_times(problem).copy()
    base = _BASES.get(key)
    if base is None:
        base = _known_times(problem).copy()
        try:
            base.time(path)
        except CcoptError:
            pass
        while len(_BASES) >= _BASES_KEPT:
            del _BASES[next(iter(_BASES))]
        _BASES[key] = base
    return base.copy()


def _known_times(problem: BlendProblem) -> StretchTimes:
    """The comparison's stretch times: the problem's (the reference's, and the
    ``siemens`` row's when it has been timed: then the ``siemens`` path needs
    no plan here), else PMAC's path planned whole and cut at its stops, as
    the comparison plans it; none known without a reference or where the
    planner refuses it."""
    if problem.stretch_times is not None:
        return problem.stretch_times
    if problem.reference is not None:
        return reference_times(problem.reference, problem.limits, problem.ts)
    return StretchTimes(problem.limits, ts=problem.ts)


def _figure(path: ToolPath, problem: BlendProblem, times: StretchTimes | None) -> float | None:
    """The member's figure to minimise: cycle time, else length (``None``:
    the planner refused it). ``times`` holds the stretches planned for the
    members so far: the members differ only at their leads or corners, so
    the stretches between are planned once (:mod:`.timing`)."""
    if times is None:
        return float(sum(s.geom.length for s in path.segments))
    duration = duration_figures(path, problem.limits, times)[0]
    return None if duration is None else float(duration)


def _cutter_radius(problem: BlendProblem) -> float:
    """The cutter radius: the reference's, else (PMAC refused the program) the
    one the siemens style compensates with."""
    if problem.reference is not None:
        return problem.cutter_radius
    return float(compensate(problem.program, "siemens", radius=problem.radius,
                            side=problem.side).radius)


def _fastest(problem: BlendProblem, members: dict[str, dict], label: str,
             leads_only: bool = False) -> BlendOutcome:
    """Compensate with each member's options, certify, and keep the fastest.
    ``leads_only``: the members differ only at their leads (the smooth approach
    families), so a fault outside every lead of one (:func:`.leads.outside_leads`)
    is every member's: the family is rejected there, its other members not tried."""
    best, tried, refusals = None, {}, []
    times = None if problem.limits is None else _base_times(problem)
    for key, options in members.items():
        try:
            path = compensate(problem.program, "siemens", radius=problem.radius,
                              side=problem.side, **options)
        except CcoptError as exc:
            tried[key] = f"refused: {exc}"
            refusals.append(exc)
            continue
        cert = problem.certify(path)
        faults = [v for v in cert.violations if v.kind in _FAULTS]
        if faults and leads_only:
            shared = outside_leads(faults, find_leads(path))
            if shared:
                raise BlendRejected(f"{label}: no member can be certified: {key} has "
                                    f"{len(shared)} fault(s) away from its leads, which every "
                                    f"member shares ({deepest(shared)})")
        if faults:
            tried[key] = f"not certified: {faults[0].kind} of depth {faults[0].depth:.3g}"
            continue
        figure = _figure(path, problem, times)
        if figure is None:
            tried[key] = "the feed planner refused it"
            continue
        tried[key] = figure
        if best is None or figure < best[0]:
            best = (figure, key, path, cert)
    if best is None and len(refusals) == len(members):
        raise refusals[0]          # the controller refuses the program: the row says why
    if best is None:
        raise BlendRejected(f"{label}: no member certified ("
                            + "; ".join(f"{k}: {v}" for k, v in tried.items()) + ")")
    _, key, path, cert = best
    # the row's cycle time is the figure the member was chosen by: every
    # stretch of its path as it was timed here (none without limits)
    own = None if times is None else {k: times.known[k] for k in stretch_keys(path)
                                      if k is not None and k in times.known}
    return BlendOutcome(path, {"chosen": key, "members": tried, "certificate": cert}, own)


def _approach(mode: str) -> Blend:
    def run(problem: BlendProblem) -> BlendOutcome:
        members = {c: {"approach": mode, "corner": c} for c in CORNERS}
        return _fastest(problem, members, f"siemens {mode}")
    run.__doc__ = f"SINUMERIK {mode} approach and retraction, G450 or G451 (the faster)"
    run.compensates = True  # a controller style: refusals are the controller's
    return run


def _smooth(kind: str) -> Blend:
    def run(problem: BlendProblem) -> BlendOutcome:
        r = _cutter_radius(problem)
        members = {}
        for f in DISR_FACTORS[kind]:
            disr = f * r
            if disr <= 0 and kind != "G147" or not math.isfinite(disr):
                continue
            members[f"DISR={disr:g}"] = {"sar": kind, "disr": disr}
        if not members:
            raise BlendRejected(f"{kind}: no DISR to try with cutter radius {r:g}")
        return _fastest(problem, members, f"siemens {kind}", leads_only=True)
    run.__doc__ = (f"SINUMERIK smooth approach/retraction {kind}/{kind[:3]}8, DISR the "
                   "fastest certified of " + ", ".join(f"{f:g}r" for f in DISR_FACTORS[kind]))
    run.compensates = True
    return run


def _as_programmed() -> Blend:
    def run(problem: BlendProblem) -> ToolPath:
        return compensate(problem.program, "siemens", radius=problem.radius, side=problem.side)
    run.__doc__ = "the SINUMERIK 840D style with the program's own modes"
    run.compensates = True
    return run


def siemens_variants() -> dict[str, Blend]:
    """The SINUMERIK variants by name."""
    made = {"siemens": _as_programmed(),
            "siemens-norm": _approach("NORM"), "siemens-kont": _approach("KONT"),
            "siemens-g147": _smooth("G147"), "siemens-g247": _smooth("G247"),
            "siemens-g347": _smooth("G347")}
    return {name: made[name] for name in SIEMENS_NAMES}

