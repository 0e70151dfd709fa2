"""The TNC tool table ``TOOL.T``: tool number -> compensation diameter.

Format (TNC 640 User's Manual, "Tool table: Standard tool data")::

    BEGIN TOOL.T MM
    T    NAME            L          R          R2         DL       DR       ...
    0    NULLTOOL        +0         +0         +0         +0       +0
    1    MILL_D10        +50        +5         +0         +0       -0.02
    [END]

The header line names the columns; each tool line gives its values in that
order, separated by blanks (a ``NAME`` may be empty only at the end of a
line, so ccopt reads a line's words against the header's). ccopt keeps ``T``,
``R`` and ``DR``: the table's part of the compensation value ``R + DR``,
returned as a diameter ``2*(R + DR)`` in the :class:`~ccopt.program.tooltable.ToolTable`
shape the readers take (``TOOL CALL``'s own ``DR`` is added by the reader).
Every problem is a located :class:`~ccopt.errors.ProgramError`.
"""
from __future__ import annotations

import math
import re

from ccopt.errors import ProgramError
from ccopt.program.model import out_of_range
from ccopt.program.tooltable import ToolTable, _load

_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)$")


def is_tnc_table(text: str) -> bool:
    """The text starts as a TNC tool table does (``BEGIN TOOL.T``)."""
    return text.lstrip().upper().startswith("BEGIN TOOL")


def read_tnc_tool_table(path_or_text, file: str | None = None) -> ToolTable:
    """Read a TNC ``TOOL.T`` table (module docstring)."""
    text, name = _load(path_or_text)
    name = file or name
    lines = re.split(r"\r\n|\r|\n", text)
    header, table = None, ToolTable()
    for lineno, line in enumerate(lines, start=1):
        words = line.split()
        if not words or words[0].upper().startswith(("BEGIN", "[END]")):
            continue
        if header is None:
            header = [w.upper() for w in words]
            for need in ("T", "R"):
                if need not in header:
                    raise ProgramError(f"TOOL.T header without a {need} column", name, lineno, 1)
            continue
        values = dict(zip(header, words))
        if header[1:2] == ["NAME"] and len(words) == len(header) - 1:
            values = dict(zip([header[0]] + header[2:], words))   # an empty NAME
        tool = values.get("T", "")
        if not tool.isdigit():
            raise ProgramError(f"tool number {tool!r} is not a whole number", name, lineno, 1)
        radius = 0.0
        for key in ("R", "DR"):
            v = values.get(key, "0")
            if not _NUMBER.match(v) or not math.isfinite(float(v)) or out_of_range(float(v)):
                col = line.find(v) + 1 if v else 1
                raise ProgramError(f"{key} of tool {tool}: cannot read {v!r}", name, lineno, col)
            radius += float(v)
        if int(tool) in table:
            raise ProgramError(f"tool {tool} is listed twice", name, lineno, 1)
        table[int(tool)] = 2.0 * radius
    return table
