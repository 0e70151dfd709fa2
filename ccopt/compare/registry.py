"""The variants ``ccopt compare`` knows: built in, and found as entry points.

Built in (the core works without :mod:`formulations`): the controller styles
``pmac`` (the reference), ``linuxcnc``, ``fagor-g138`` (direct start and end,
the program's G136/G137), ``fagor-g139-g136`` and ``fagor-g139-g137``
(contouring start and end with circular or linear transitions, forced with
the Fagor style's ``start_end``/``corner`` options), and the geometric leads
``tangent-arc`` and ``line-arc`` (:mod:`.geometric`).

Any package adds a blend with one entry point in the group
:data:`ENTRY_POINT_GROUP`::

    [project.entry-points."ccopt.blends"]
    my-blend = "my_package.my_module:my_blend"

where ``my_blend(problem: BlendProblem) -> ToolPath | BlendOutcome``
(:mod:`.blend`). An entry point may not take a built-in name.
"""
from __future__ import annotations

from importlib.metadata import EntryPoint, entry_points
from typing import Callable

from ccopt.compare.blend import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.leads import find_leads, splice
from ccopt.toolpath import ToolPath

ENTRY_POINT_GROUP = "ccopt.blends"

Blend = Callable[[BlendProblem], "ToolPath | BlendOutcome"]


def _style(style: str, **options) -> Blend:
    def run(problem: BlendProblem) -> ToolPath:
        from ccopt.compensate import compensate
        return compensate(problem.program, style, radius=problem.radius, side=problem.side,
                          **options)
    run.__doc__ = f"compensate with style {style!r} {options or ''}".strip()
    run.compensates = True  # a controller style: refusals are the controller's
    return run


def _geometric(build, name: str) -> Blend:
    def run(problem: BlendProblem) -> BlendOutcome:
        from ccopt.compare.geometric import ConstructionError
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
    from ccopt.compare.geometric import line_arc, tangent_arc
    return {
        "pmac": _style("pmac"),
        "linuxcnc": _style("linuxcnc"),
        "fagor-g138": _style("fagor", start_end="direct"),
        "fagor-g139-g136": _style("fagor", start_end="contour", corner="circular"),
        "fagor-g139-g137": _style("fagor", start_end="contour", corner="linear"),
        "tangent-arc": _geometric(tangent_arc, "tangent-arc"),
        "line-arc": _geometric(line_arc, "line-arc"),
    }


BUILTIN_NAMES = ("pmac", "linuxcnc", "fagor-g138", "fagor-g139-g136", "fagor-g139-g137",
                 "tangent-arc", "line-arc")

#: Entry-point blends listed first, in this order, when installed.
PREFERRED_ORDER = ("opt-casadi", "opt-cvxpy", "smooth")


def blend_entry_points() -> dict[str, EntryPoint]:
    """Entry points of group ``ccopt.blends`` by name (the first of a name wins)."""
    out: dict[str, EntryPoint] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name not in BUILTIN_NAMES:
            out.setdefault(ep.name, ep)
    return out


def available() -> list[str]:
    """Every variant name: built-ins, then entry points (preferred ones first)."""
    eps = blend_entry_points()
    pref = [n for n in PREFERRED_ORDER if n in eps]
    rest = sorted(n for n in eps if n not in PREFERRED_ORDER)
    return list(BUILTIN_NAMES) + pref + rest


def require_known(names, source: str) -> None:
    """Raise a :class:`~ccopt.errors.ProgramError` (at ``source``, e.g. the
    program the names were given for) naming every unknown variant in
    ``names`` and the available ones."""
    known = available()
    unknown = [n for n in names if n not in known]
    if unknown:
        from ccopt.errors import ProgramError
        raise ProgramError(f"unknown variant(s) {', '.join(unknown)}; available: "
                           f"{', '.join(known)}", source)


def load(name: str) -> Blend:
    """The blend callable registered as ``name`` (``KeyError`` if none)."""
    if name in BUILTIN_NAMES:
        return _builtins()[name]
    eps = blend_entry_points()
    if name not in eps:
        raise KeyError(name)
    return eps[name].load()
