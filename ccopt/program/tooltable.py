"""LinuxCNC tool table reader: tool number -> diameter.

Format (LinuxCNC's ``tool.tbl``, one tool per line)::

    T1 P1 D6.0 Z+0.0 ;6 mm end mill
    T2 P2 X0 Z-12.5 D10 I0 J0 Q0

Words are separated by blanks and are case-insensitive: ``T`` tool number
(required, a non-negative integer), ``P`` pocket and ``Q`` orientation
(whole numbers, also written with decimals such as ``Q0.0``), ``D`` diameter, offsets ``X Y Z A B C U V W`` and lathe angles
``I J`` (numbers). Only ``T`` and ``D`` matter to ccopt; the rest are checked
and ignored. ``;`` starts a comment; blank and comment-only lines are skipped.

Decisions: a tool without ``D`` has diameter 0 (LinuxCNC's default, so
``G41 D<n>`` with it compensates by 0); a negative diameter is kept (the
G-code reader turns it into a side flip, as LinuxCNC does); a tool listed
twice, an unknown word, a malformed or non-finite number is a located
:class:`~ccopt.errors.ProgramError`. The old column format of LinuxCNC 2.3
is not read.
"""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.program.model import MAX_PROGRAM_COORDINATE, out_of_range

__all__ = ["ToolTable", "read_tool_table"]


class ToolTable(dict):
    """``{tool number: diameter}`` (the table's units), plus ``orientation``:
    ``{tool number: Q}``, the lathe tool orientation 1..9 of the tools that
    give one (0 or absent: a mill tool)."""

    def __init__(self, diameters=(), orientation=None):
        super().__init__(diameters)
        self.orientation: dict[int, int] = dict(orientation or {})

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\Z")
_INTEGER = re.compile(r"[+-]?\d+\Z")
_REAL_WORDS = set("DXYZABCUVWIJ")
_INT_WORDS = set("TPQ")


def _load(path_or_text) -> tuple[str, str]:
    """``(text, file name)`` from a path or the table text itself."""
    if isinstance(path_or_text, os.PathLike):
        path = Path(path_or_text)
    elif isinstance(path_or_text, str):
        s = path_or_text
        if "\n" not in s and s.strip() and os.path.isfile(s):
            path = Path(s)
        elif "\n" not in s and (s.lower().endswith(".tbl") or os.sep in s) and " " not in s:
            raise ProgramError(f"tool table file not found: {s}", s)
        else:
            return s, "<tool table>"
    else:
        raise ProgramError(f"tool table must be a path or text, not {type(path_or_text).__name__}",
                           "<tool table>")
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
        return text, str(path)
    except OSError as exc:
        raise ProgramError(f"cannot read tool table: {exc.strerror or exc}", str(path)) from None


def read_tool_table(path_or_text, file: str | None = None) -> ToolTable:
    """Read a LinuxCNC tool table; return ``{tool number: diameter}`` (a
    :class:`ToolTable`, which also holds each tool's orientation ``Q``).

    ``path_or_text`` is a path (``str`` naming an existing file or
    ``os.PathLike``) or the table text. ``file`` overrides the name used in
    errors. Diameters are in the units of the table (the program's units).
    """
    text, name = _load(path_or_text)
    if file is not None:
        name = file
    table = ToolTable()
    where: dict[int, int] = {}
    for lineno, line in enumerate(re.split(r"\r\n|\r|\n", text), start=1):
        code = line.split(";", 1)[0]
        tool = None
        diameter = 0.0
        orientation = 0
        seen: set[str] = set()
        first_col = None
        for m in re.finditer(r"\S+", code):
            token, col = m.group(), m.start() + 1
            if first_col is None:
                first_col = col
            letter = token[0].upper()
            value = token[1:]
            if letter not in _REAL_WORDS and letter not in _INT_WORDS:
                if token[0].isdigit():
                    raise ProgramError("old-style tool table line (columns of numbers) is not "
                                       "supported: write T<tool> P<pocket> D<diameter>",
                                       name, lineno, col)
                raise ProgramError(f"unknown word {token!r} in tool table: use T, P, D, X, Y, Z, "
                                   "A, B, C, U, V, W, I, J, Q", name, lineno, col)
            if letter in seen:
                raise ProgramError(f"two {letter} words on one tool line", name, lineno, col)
            seen.add(letter)
            if letter in _INT_WORDS:
                # LinuxCNC writes whole numbers, other tools "Q0.0": both are read
                if not (_INTEGER.match(value) or (_NUMBER.match(value)
                                                  and float(value).is_integer())):
                    raise ProgramError(f"{letter} needs a whole number, got {value!r}",
                                       name, lineno, col)
                number = int(float(value))
                if letter == "Q":
                    if not 0 <= number <= 9:
                        raise ProgramError(f"tool orientation Q{number} must be 0 to 9",
                                           name, lineno, col)
                    orientation = number
                if letter == "T":
                    if number < 0:
                        raise ProgramError(f"tool number T{number} must not be negative",
                                           name, lineno, col)
                    tool = number
            else:
                if not _NUMBER.match(value):
                    raise ProgramError(f"{letter} needs a number, got {value!r}", name, lineno, col)
                number = float(value)
                if not math.isfinite(number):
                    raise ProgramError(f"{letter}{value} is not a finite number", name, lineno, col)
                if letter == "D":
                    if out_of_range(number):
                        raise ProgramError(f"D{value} is out of range: a diameter must lie "
                                           f"within +-{MAX_PROGRAM_COORDINATE:g}",
                                           name, lineno, col)
                    diameter = number
        if first_col is None:
            continue
        if tool is None:
            raise ProgramError("tool line without T<tool number>", name, lineno, first_col)
        if tool in table:
            raise ProgramError(f"tool T{tool} is listed twice (lines {where[tool]} and {lineno})",
                               name, lineno, first_col)
        table[tool] = diameter
        if orientation:
            table.orientation[tool] = orientation
        where[tool] = lineno
    return table
