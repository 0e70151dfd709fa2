"""Surface markers: the program says which compensated moves are part surface.

A comment on a move's line marks that move (the marker is not modal):

* G-code: ``(ccopt: air)`` / ``(ccopt: part)`` (also after ``;``);
* PMAC: ``; ccopt: air`` / ``; ccopt: part`` in the line's comment.

``part``: the move's programmed geometry is part surface; ``air``: it is a
lead or any other move in air (its tool path is still checked against the
part, the part is never checked against it). Letters may be in either case.
The verifier reads the marker (:attr:`ccopt.program.model.Block.surface`);
see docs/compensation.md section 8.1.
"""
from __future__ import annotations

import re

from ccopt.errors import ProgramError

SURFACE_PART, SURFACE_AIR = "part", "air"

_PATTERNS = {
    "gcode": re.compile(r"(?:\(|;)\s*ccopt\s*:\s*(air|part)\s*(?:\)|$)", re.IGNORECASE),
    "pmac": re.compile(r";.*?\bccopt\s*:\s*(air|part)\b", re.IGNORECASE),
}


def surface_marker(text: str, dialect: str, file: str, line: int) -> str | None:
    """``"part"``, ``"air"`` or ``None``: the marker in the comments of the
    program line ``text`` (1-based ``line`` of ``file``, for the error).
    Both markers on one line are a located :class:`ProgramError`."""
    if "ccopt" not in text.lower():
        return None
    found = {m.group(1).lower(): m.start() for m in _PATTERNS[dialect].finditer(text)}
    if len(found) > 1:
        raise ProgramError("both (ccopt: air) and (ccopt: part) on one line: a move is "
                           "either part surface or air; keep one", file, line,
                           max(found.values()) + 1)
    return next(iter(found), None)
