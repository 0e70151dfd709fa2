"""HEIDENHAIN's approach and departure paths as lead variants of ``compare``.

``heidenhain-lt``, ``heidenhain-ln``, ``heidenhain-ct`` and ``heidenhain-lct``
replace every lead-in and lead-out of PMAC's path (:mod:`.leads`) by the
TNC's ``APPR``/``DEP`` path of that kind (docs/compensation.md, HEIDENHAIN
rule 5), built on the tool centre from the approach point to the host's
start ``J`` on the free side (a lead-out as the mirrored lead-in, which is
the ``DEP`` path of the same kind): LT and LN by
:func:`ccopt.program.heidenhain.contour.approach`, the Klartext reader's
construction; CT and LCT by the geometric leads' (:func:`build`).

Each kind has one parameter (``LEN`` for LT and LN, ``R`` for CT, with
``CCA`` 90 degrees, and LCT), tried at :data:`PARAMETER_FACTORS` times the
cutter radius; for each lead the variant keeps the fastest member the
verifier certifies (:meth:`BlendProblem.check`). "Fastest": the shortest
time, under the comparison's limits and certified planner, of the lead's
segments and its host run from rest to rest (only they differ between the
members); without limits, the shortest length. The chosen parameters are
reported (``info["parameters"]``).
"""
from __future__ import annotations

from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.geometric import ConstructionError, line_arc, tangent_arc
from ccopt.compare.leads import Lead, LeadGeometry, find_leads, splice, straight_line
from ccopt.compare.timing import plan_whole
from ccopt.errors import CcoptError
from ccopt.geometry import Line
from ccopt.program.heidenhain import contour
from ccopt.toolpath import ToolPath

#: The members of each kind's parameter set, as multiples of the cutter radius.
PARAMETER_FACTORS = (1.0, 2.0, 4.0)
KINDS = {"heidenhain-lt": "LT", "heidenhain-ln": "LN", "heidenhain-ct": "CT",
         "heidenhain-lct": "LCT"}


def build(kind: str, lg: LeadGeometry, value: float) -> list:
    """The APPR path of ``kind`` with parameter ``value`` onto ``lg``'s host.

    CT (with CCA 90 degrees: a quarter circle, the manuals' example) and LCT are the constructions of the geometric
    leads ``tangent-arc`` and ``line-arc`` (:mod:`.geometric`) at radius
    ``R``, made by them: the same path to the last bit where the members'
    radius is theirs, so a comparison times it once (the tests hold both to
    the TNC's own construction)."""
    if kind == "CT":
        return tangent_arc(lg, value)
    if kind == "LCT":
        return line_arc(lg, value)
    J = tuple(float(v) for v in lg.host.start)
    t = tuple(float(v) for v in lg.host.start_tangent)
    ps = (float(lg.approach[0]), float(lg.approach[1]))
    ph, pieces = contour.approach(kind, ps, J, t, lg.side, 0.0, value, None, None)
    return [straight_line(ps, ph)] + [Line(p[1], p[2]) for p in pieces]   # lines only


def _made(lead: Lead, path: ToolPath, new: ToolPath) -> list[int]:
    """Indices in ``new`` of the segments the splice made (and the host)."""
    grown = len(new.segments) - len(path.segments)
    if lead.kind == "in":
        return list(range(lead.first, lead.host + 1 + grown))
    return list(range(lead.host, lead.last + 1 + grown))


def _lead_time(new: ToolPath, made: list[int], problem: BlendProblem) -> float:
    segs = tuple(new.segments[i] for i in made)
    if problem.limits is None:
        return float(sum(s.length for s in segs))
    part = ToolPath(segs, plane=new.plane, style=new.style, radius=new.radius,
                    units=new.units)
    prof, _ = plan_whole(part, problem.limits, problem.ts)
    return float(prof.duration)


def _best(kind: str, name: str, lead: Lead, path: ToolPath, problem: BlendProblem):
    """``(time, value, path)`` of the fastest certified member for ``lead``, or
    the reasons none was."""
    lg = lead.geometry(path)
    best, why = None, []
    for f in PARAMETER_FACTORS:
        value = f * problem.cutter_radius
        try:
            new = splice(path, lead, build(kind, lg, value), 0.0, style=name)
            made = _made(lead, path, new)
            problem.check(new, made)
            t = _lead_time(new, made, problem)
        except (contour.GeometryError, ConstructionError, BlendRejected, CcoptError) as exc:
            why.append(f"{value:g}: {exc}")
            continue
        if best is None or t < best[0]:
            best = (t, value, new)
    return best, why


def tnc_lead(name: str):
    """The blend of variant ``name`` (one of :data:`KINDS`)."""
    kind = KINDS[name]

    def run(problem: BlendProblem) -> BlendOutcome:
        path = problem.reference
        leads = find_leads(path)
        if not leads:
            raise BlendRejected("the reference path has no lead-in or lead-out to replace")
        chosen = []
        for ld in reversed(leads):  # from the end, so earlier indices stay valid
            best, why = _best(kind, name, ld, path, problem)
            if best is None:
                raise BlendRejected(f"{ld.kind}: no {kind} lead certified ({'; '.join(why)})")
            path = best[2]
            chosen.append({"lead": ld.kind, "parameter": best[1]})
        key = "LEN" if kind in ("LT", "LN") else "R"
        return BlendOutcome(path, {"parameters": [{**c, "name": key} for c in reversed(chosen)]})

    run.__doc__ = f"HEIDENHAIN APPR/DEP {kind} leads on PMAC's path"
    return run
