"""Subprogram calls of a SINUMERIK program (Programming Manual Fundamentals,
"Subprograms": calling by name, ``L<number>``, program repetition ``P``).

``NAME`` or ``L123`` alone in a block (with ``P<n>``: ``n`` passes) runs the
subprogram file ``NAME.SPF`` (``L123.SPF``; also ``.spf``/``.mpf``) found in
the folders of the sub path: by default the calling program's own folder
(:func:`ccopt.program.read_program` passes it). Its lines are read after the
program's, so every error names the subprogram file and line. It returns at
``M17``, ``RET``, ``M2``/``M30`` or its end; R parameters and ``DEF``
variables are shared (ccopt reads no ``PROC`` parameters). A subprogram's
jump labels and structures are its own.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from ccopt.program.expr import ExprError
from ccopt.program.gcode.state import LINE_SPLIT, GCodeState
from ccopt.program.sinumerik.flow import Structure, match_structures

#: Suffixes a subprogram file may have, tried in this order.
SUB_SUFFIXES = (".SPF", ".spf", ".MPF", ".mpf")
#: Most passes of one call (``P``): larger counts are typing errors.
MAX_PASSES = 9999
_NAME = re.compile(r"[A-Z_][A-Z0-9_]*\Z")


@dataclass
class CallFrame:
    """A running program text: its structure, where its lines start in the
    state's ``lines``, the line to return to, the passes still to run."""

    structure: Structure
    offset: int
    return_pc: int = -1
    passes: int = 0


def find_sub(state: GCodeState, name: str) -> Path | None:
    """The subprogram file of ``name`` in the sub path, or ``None``."""
    if not _NAME.match(name):
        return None
    for folder in state.sub_path:
        for suffix in SUB_SUFFIXES:
            for stem in (name, name.lower()):
                path = Path(folder) / f"{stem}{suffix}"
                if path.is_file():
                    return path
    return None


def load_sub(state: GCodeState, loaded: dict, name: str, col: int) -> CallFrame:
    """The frame of subprogram ``name`` (its file read once)."""
    if name in loaded:
        structure, offset = loaded[name]
        return CallFrame(structure, offset)
    path = find_sub(state, name)
    if path is None:
        where = ", ".join(state.sub_path) or "(no folder: give the program as a file)"
        raise ExprError(f"{name}: no subprogram file {name}.SPF in the sub path ({where}); "
                        "ccopt reads subprograms from files beside the program", col)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ExprError(f"{name}: cannot read {path}: {exc}", col) from None
    lines = LINE_SPLIT.split(text)
    if lines and lines[-1] == "":
        lines.pop()
    offset = len(state.lines)
    state.lines.extend(lines)
    state.sub_files.append((offset, len(state.lines), str(path)))
    structure = match_structures(lines, str(path))
    loaded[name] = (structure, offset)
    return CallFrame(structure, offset)


def passes_of(value: float | None, col: int) -> int:
    """The number of passes ``P`` (default 1)."""
    if value is None:
        return 1
    n = round(value)
    if abs(value - n) > 0 or not 1 <= n <= MAX_PASSES:
        raise ExprError(f"P{value:g}: the number of passes is a whole number from 1 to "
                        f"{MAX_PASSES}", col)
    return int(n)
