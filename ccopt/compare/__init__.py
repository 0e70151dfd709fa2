"""Compare lead-in, lead-out and corner blends of one program, certified and timed.

::

    from ccopt.compare import compare
    cmp = compare(prog, limits=ccopt.AxisLimits(v=[100, 100, 30], a=[1000, 1000, 300]))
    for row in cmp:
        print(row.name, row.figures["duration"], row.figures["continuity"])
    cmp.to_json()   # {"variants": [{"name", "duration", "min_clearance", ...}, ...]}

Variants are the controller styles and geometric leads built in
(:mod:`.registry`) plus every ``ccopt.blends`` entry point (the optimised
blends and the smoother of :mod:`formulations` register there). A blend is
``blend(problem: BlendProblem) -> ToolPath | BlendOutcome`` (:mod:`.contract`);
leads are found and replaced with :mod:`.leads`; figures are in
:mod:`.figures` and cycle times in :mod:`.timing`. :mod:`.core` is the
comparison itself, :mod:`.variant` one variant's row, and :mod:`.schedule`
runs the variants here or in worker processes.
"""
from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.core import REFERENCE, Comparison, GivenReference, compare
from ccopt.compare.variant import FIGURES, VariantResult, measure
from ccopt.compare.contract import ENTRY_POINT_GROUP
from ccopt.compare.registry import available, load

__all__ = ["BlendOutcome", "BlendProblem", "BlendRejected", "Comparison", "ENTRY_POINT_GROUP",
           "FIGURES", "GivenReference", "REFERENCE", "VariantResult", "available", "compare", "load", "measure"]
