"""The variants ``ccopt compare`` knows: built in, and found as entry points.

Built in (the core works without :mod:`formulations`): the controller styles
``pmac`` (the reference), ``linuxcnc``, ``fagor-g138`` (direct start and end,
the program's G136/G137), ``fagor-g139-g136`` and ``fagor-g139-g137``
(contouring start and end with circular or linear transitions, forced with
the Fagor style's ``start_end``/``corner`` options), ``heidenhain`` (the TNC
style), the geometric leads ``tangent-arc`` and ``line-arc``
(:mod:`.geometric`), HEIDENHAIN's approach/departure leads
``heidenhain-lt``, ``-ln``, ``-ct``, ``-lct`` (:mod:`.tnc_leads`), and the
SINUMERIK 840D style as programmed, ``siemens``, with its approach families
``siemens-norm``, ``siemens-kont``, ``siemens-g147``, ``siemens-g247``,
``siemens-g347`` (:mod:`.siemens_leads`).

Every other variant is a plug-in blend registered as an entry point of group
``ccopt.blends``; what it implements and how it registers is
:mod:`ccopt.compare.contract`.
"""
from __future__ import annotations

from ccopt.compare.contract import (
    BUILTIN_NAMES, LEAD_FAMILY_NAMES, Blend, BlendOutcome, BlendProblem, BlendRejected, blend_entry_points,
)
from ccopt.compare.geometric import ConstructionError, line_arc, tangent_arc
from ccopt.compare.leads import find_leads, splice
from ccopt.compare.siemens_leads import siemens_variants
from ccopt.compare.tnc_leads import KINDS as TNC_LEADS, tnc_lead
from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.toolpath import ToolPath


def _style(style: str, **options) -> Blend:
    def run(problem: BlendProblem) -> ToolPath:
        return compensate(problem.program, style, radius=problem.radius, side=problem.side,
                          **options)
    run.__doc__ = f"compensate with style {style!r} {options or ''}".strip()
    run.compensates = True  # a controller style: refusals are the controller's
    return run


def _geometric(build, name: str) -> Blend:
    def run(problem: BlendProblem) -> BlendOutcome:
        rho = float(problem.options.get("lead_radius", problem.cutter_radius))
        path = problem.reference
        leads = find_leads(path)
        if not leads:
            raise BlendRejected("the reference path has no lead-in or lead-out to replace")
        for ld in reversed(leads):  # from the end, so earlier indices stay valid
            try:
                geoms = build(ld.geometry(path), rho)
            except ConstructionError as exc:
                raise BlendRejected(f"{ld.kind}: {exc}") from None
            path = splice(path, ld, geoms, 0.0, style=name)
        return BlendOutcome(path, {"lead_radius": rho})
    run.__doc__ = f"{name} lead-in and lead-out on PMAC's path"
    return run


def _builtins() -> dict[str, Blend]:
    return {
        "pmac": _style("pmac"),
        "linuxcnc": _style("linuxcnc"),
        "fagor-g138": _style("fagor", start_end="direct"),
        "fagor-g139-g136": _style("fagor", start_end="contour", corner="circular"),
        "fagor-g139-g137": _style("fagor", start_end="contour", corner="linear"),
        "heidenhain": _style("heidenhain"),
        "tangent-arc": _geometric(tangent_arc, "tangent-arc"),
        "line-arc": _geometric(line_arc, "line-arc"),
        **{name: tnc_lead(name) for name in TNC_LEADS},
        **siemens_variants(),
    }


#: Entry-point blends listed first, in this order, when installed.
PREFERRED_ORDER = ("opt-casadi", "opt-cvxpy", "smooth")


def available() -> list[str]:
    """Every variant name: built-ins, then entry points (preferred ones first)."""
    eps = blend_entry_points()
    pref = [n for n in PREFERRED_ORDER if n in eps]
    rest = sorted(n for n in eps if n not in PREFERRED_ORDER)
    return list(BUILTIN_NAMES) + pref + rest


#: The name that stands for every available variant in ``--variants``.
ALL = "all"


#: Plug-in blends the main job runs on demand only, as the lead families:
#: ``opt-cvxpy`` solves a conic subproblem per iteration of its sequential
#: convex programme, a dozen or more per lead and curvature weight, and is
#: the costliest variant per lead (docs/benchmarks.md, the main job's
#: compare stage). ``opt-casadi`` optimises the same leads and stays, so
#: the main job's report still has an optimised lead beside the smoother.
MAIN_JOB_ON_DEMAND = ("opt-cvxpy",)


def main_job_variants() -> list[str]:
    """The variants the main job (``ccopt run``) compares by default: every
    available one but the lead families (:data:`~.contract.LEAD_FAMILY_NAMES`),
    which search a parameter set each (every member compensated, certified
    and timed), and :data:`MAIN_JOB_ON_DEMAND`; ``--variants all`` (or
    their names) brings them in, and ``ccopt compare`` runs them all."""
    return [n for n in available() if n not in LEAD_FAMILY_NAMES + MAIN_JOB_ON_DEMAND]


def expand(names) -> list[str]:
    """``names`` with :data:`ALL` replaced by every available variant (once each,
    in order)."""
    out: list[str] = []
    for n in names:
        for m in (available() if n == ALL else [n]):
            if m not in out:
                out.append(m)
    return out


def require_known(names, source: str) -> None:
    """Raise a :class:`~ccopt.errors.ProgramError` (at ``source``, e.g. the
    program the names were given for) naming every unknown variant in
    ``names`` and the available ones."""
    known = available()
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ProgramError(f"unknown variant(s) {', '.join(unknown)}; available: "
                           f"{', '.join(known)}", source)


def preload(names) -> None:
    """Call the ``imports`` (:data:`~.contract.Blend`) of the blends ``names``,
    each once. A blend that cannot be loaded, or whose imports fail, is left as
    it is: it meets the same error when it runs, and its row says so
    (:func:`.variant.solve`)."""
    done = []
    for name in names:
        try:
            imports = getattr(load(name), "imports", None)
            if imports is not None and imports not in done:
                done.append(imports)
                imports()
        except Exception:   # noqa: BLE001  (a plug-in's bug shows in its own row)
            continue


def load(name: str) -> Blend:
    """The blend callable registered as ``name`` (``KeyError`` if none)."""
    if name in BUILTIN_NAMES:
        return _builtins()[name]
    eps = blend_entry_points()
    if name not in eps:
        raise KeyError(name)
    return eps[name].load()
