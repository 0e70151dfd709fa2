"""Buffers of a PMAC download file: ``OPEN PROG n [CLEAR]`` ... ``CLOSE``.

A file with at least one ``OPEN`` is a download file: its ``PROG`` buffers
hold motion programs, other buffers (``PLC``, ``ROT``, kinematics ...) are
skipped, and the lines outside every buffer are on-line commands that run
before the program. A file without ``OPEN`` is a bare program body. The rules
and decisions are in ``docs/pmac.md`` ("Buffers").
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

from ccopt.errors import ProgramError

_OPEN_RE = re.compile(r"OPEN[ \t]*([A-Z]*)[ \t]*(\d*)[ \t]*(CLEAR)?[ \t]*$")
_COORD_RE = re.compile(r"&[ \t]*(\d+)")
_CCBUF_RE = re.compile(r"DEFINE[ \t]*CCBUF[ \t]*(\d+)")
#: Coordinate systems of a Turbo PMAC: ``&1`` .. ``&16``.
MAX_COORDINATE_SYSTEM = 16

Lines = list[tuple[int, str]]


@dataclass
class Download:
    """A download file cut into its buffers.

    Attributes
    ----------
    programs: PROG number -> its ``(line number, text)`` lines.
    order: PROG numbers in the order the file first opens them.
    outside: lines outside every buffer (on-line commands).
    skipped: the other buffers, e.g. ``"PLC 1"``.
    """

    programs: dict[int, Lines] = field(default_factory=dict)
    order: list[int] = field(default_factory=list)
    outside: Lines = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)


def split_buffers(lines: Lines, file: str) -> Download | None:
    """Cut the file into PROG buffers and on-line text; ``None`` for a file
    without any ``OPEN`` (a bare program body, where ``CLOSE`` is an error)."""
    if not any("OPEN" in line and line.lstrip().startswith("OPEN") for _, line in lines):
        for n, line in lines:
            if line.strip() == "CLOSE":
                raise ProgramError("CLOSE without OPEN (a file without OPEN is read as a "
                                   "bare program body)", file, n, line.index("CLOSE") + 1)
        return None
    out = Download()
    current: int | None = None      # PROG number being filled
    skipping: str | None = None     # other buffer being skipped
    opened_at = 0
    for item in lines:
        n, line = item
        if "OPEN" not in line and "CL" not in line:
            # neither OPEN, CLOSE nor CLEAR: the common line, in one test
            if skipping is None:
                (out.outside if current is None else out.programs[current]).append(item)
            continue
        stripped = line.strip()
        if stripped.startswith("OPEN"):
            col = len(line) - len(line.lstrip()) + 1
            if current is not None or skipping is not None:
                raise ProgramError("OPEN inside an open buffer: CLOSE the buffer opened at "
                                   f"line {opened_at} first", file, n, col)
            current, skipping = _open(out, stripped, file, n, col)
            opened_at = n
        elif stripped == "CLOSE":
            current = None
            skipping = None
        elif skipping is not None:
            continue
        elif current is None:
            out.outside.append((n, line))
        elif stripped == "CLEAR":
            out.programs[current] = []
        else:
            out.programs[current].append((n, line))
    if current is not None or skipping is not None:
        what = f"PROG {current}" if current is not None else skipping
        raise ProgramError(f"OPEN {what} is never closed: add CLOSE at the end of the buffer",
                           file, opened_at, 1)
    return out


def _open(out: Download, stripped: str, file: str, n: int,
          col: int) -> tuple[int | None, str | None]:
    """Open the buffer of an ``OPEN`` line: ``(PROG number, None)`` or
    ``(None, name of the skipped buffer)``."""
    m = _OPEN_RE.match(stripped)
    if not m or not m.group(1):
        raise ProgramError("expected OPEN PROG {number} [CLEAR] alone on its line", file, n, col)
    kind, number, clear = m.groups()
    if kind != "PROG":
        name = f"{kind} {number}".strip()
        out.skipped.append(name)
        return None, name
    if not number:
        raise ProgramError("OPEN PROG needs a program number", file, n, col)
    prog = int(number)
    if prog not in out.programs:
        out.programs[prog] = []
        out.order.append(prog)
    if clear:
        out.programs[prog] = []
    return prog, None


def select_program(download: Download, lines: Lines, program: int | None,
                   file: str) -> tuple[int, Lines]:
    """The PROG buffer to execute: ``program``, default the first one opened."""
    if program is None:
        if not download.order:
            first_open = next(n for n, line in lines if line.lstrip().startswith("OPEN"))
            raise ProgramError("the file opens no PROG buffer (only "
                               + ", ".join(download.skipped) + ")", file, first_open, 1)
        program = download.order[0]
    if program not in download.programs:
        have = ", ".join(f"PROG {n}" for n in download.order) or "none"
        raise ProgramError(f"program {program} is not in the file (it has: {have})", file, None)
    return program, download.programs[program]


def coordinate_system(text: str, pos: int, file: str, line: int) -> tuple[int, str, int]:
    """Read the on-line ``&n`` at ``pos``: ``(n, its text, position after it)``."""
    m = _COORD_RE.match(text, pos)
    if not m or not 1 <= int(m.group(1)) <= MAX_COORDINATE_SYSTEM:
        raise ProgramError(f"'&' needs a coordinate-system number 1..{MAX_COORDINATE_SYSTEM}",
                           file, line, pos + 1)
    return int(m.group(1)), m.group(0), m.end()


def ccbuf_number(command: str) -> int | None:
    """``n`` of the on-line ``DEFINE CCBUF n`` (the compensation look-ahead
    buffer), ``None`` for any other command."""
    m = _CCBUF_RE.fullmatch(command)
    return int(m.group(1)) if m else None
