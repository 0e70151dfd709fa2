"""A toy blend for the registry test: PMAC's path with its lead-in replaced by a
straight line from the approach point to the host's start (for an inside
lead-in that is exactly PMAC's own diagonal)."""
from ccopt.compare import BlendOutcome
from ccopt.compare.leads import Line, find_leads, splice


def toy(problem):
    path = problem.reference
    ld = find_leads(path)[0]
    lg = ld.geometry(path)
    out = splice(path, ld, [Line(lg.approach, lg.host.start)], 0.0, style="toy")
    return BlendOutcome(out, {"toy": True})
