"""ccopt: cutter radius compensation as a controller does it, then planned,
verified, compared and exported.

The pipeline (see DESIGN.md)::

    prog = ccopt.read_program("part.pmc")
    path = ccopt.compensate(prog, style="pmac")
    cert = ccopt.verify(path, prog)
    ccopt.export(path, "part.nc", program=prog)

or, every stage with its settings resolved once as every command resolves them::

    job = ccopt.make_job("part.pmc", vmax=(100, 100), amax=(1000, 1000), tolerance=1e-3)
    out = ccopt.pipeline(job).result()       # out.path, out.duration, out.certificate

Units: lengths in program units (mm or inch), time in seconds, angles in
radians inside ccopt.
"""
from __future__ import annotations


from ccopt.cases import Job, make_job
from ccopt.compensate import compensate
from ccopt.errors import CcoptError, CompensationError, ProgramError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program import read_program, read_text
from ccopt.program.model import Block, Modal, Motion, Program, Source
# ccopt.sweep imports Dask, pandas and pyarrow only when a sweep runs.
from ccopt.sweep import sweep
from ccopt.toolpath import PathSegment, Role, ToolPath, programmed_path
from ccopt.verify import Certificate, verify
from ccopt.version import __version__

# Bound last: the name ``ccopt.export`` is the function, as ``ccopt.verify``
# is (the modules stay importable: ``from ccopt.export import export``,
# ``from ccopt.export.arcfit import ...``).
from ccopt.export import ExportResult, export
# the one pipeline every command runs a Job through (after export: it uses the function)
from ccopt.pipeline import Outcome, pipeline


__all__ = [
    "Certificate", "verify",
    "ExportResult", "export",
    "AxisLimits", "plan_feed",
    "Job", "Outcome", "make_job", "pipeline",
    "Block", "CcoptError", "CompensationError", "Modal", "Motion", "PathSegment", "Program",
    "ProgramError", "Role", "Source", "ToolPath", "compensate", "programmed_path", "read_program",
    "read_text", "sweep", "__version__",
]
