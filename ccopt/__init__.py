"""ccopt: cutter radius compensation as a controller does it, then planned,
verified, compared and exported.

The pipeline (see DESIGN.md)::

    prog = ccopt.read_program("part.pmc")
    path = ccopt.compensate(prog, style="pmac")

Units: lengths in program units (mm or inch), time in seconds, angles in
radians inside ccopt.
"""
from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version as _version

from ccopt.compensate import compensate
from ccopt.errors import CcoptError, CompensationError, ProgramError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program import read_program, read_text
from ccopt.program.model import Block, Modal, Motion, Program, Source
# ccopt.sweep imports Dask, pandas and pyarrow only when a sweep runs.
from ccopt.sweep import sweep
from ccopt.toolpath import PathSegment, Role, ToolPath, programmed_path
from ccopt.verify import Certificate, verify

try:
    __version__ = _version("ccopt")
except PackageNotFoundError:  # running from a source tree without install
    __version__ = "0.0.0+unknown"

__all__ = [
    "Certificate", "verify",
    "AxisLimits", "plan_feed",
    "Block", "CcoptError", "CompensationError", "Modal", "Motion", "PathSegment", "Program",
    "ProgramError", "Role", "Source", "ToolPath", "compensate", "programmed_path", "read_program",
    "read_text", "sweep", "__version__",
]
