"""``read_pmac``: a PMAC download file or program body -> :class:`Program`.

Reading order: cut the text into lines (:mod:`.lexer`) and buffers
(:mod:`.buffers`), run the on-line commands outside the buffers (variable
assignments, ``&n``, recorded definitions), then execute the selected PROG
buffer statement by statement (:mod:`.statements`).
"""
from __future__ import annotations

import gc
import math

from ccopt.errors import ProgramError
from ccopt.program.markers import surface_marker
from ccopt.program.model import Program, Vec3
from ccopt.program.pmac import buffers
from ccopt.program.pmac.lexer import skip, split_lines, word
from ccopt.program.pmac.statements import Interpreter

#: On-line commands recorded in ``meta["online"]`` and otherwise ignored.
_RECORDED_ONLINE = ("UNDEFINE", "DELETE", "DEFINE")


def read_pmac(text: str, file: str = "<string>", *, start: Vec3 = (0.0, 0.0, 0.0),
              program: int | None = None) -> Program:
    """Read PMAC / Turbo PMAC motion-program text.

    Parameters
    ----------
    text: the download file or bare program body.
    file: name used in error messages and :attr:`Program.file`.
    start: machine position ``(x, y, z)`` before the first move.
    program: number of the ``OPEN PROG`` buffer to read; default the first
        one in the file (``None`` for a file without ``OPEN``).

    Returns
    -------
    Program with ``dialect="pmac"``; see ``docs/pmac.md`` for the rules.

    Raises
    ------
    ProgramError: for any problem in the text, located by line and column.
    """
    try:
        start_t = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ProgramError(f"start must be three numbers (x, y, z), got {start!r}", file) from None
    if len(start_t) != 3 or not all(math.isfinite(v) for v in start_t):
        raise ProgramError(f"start must be three finite numbers (x, y, z), got {start!r}", file)
    # The cyclic garbage collector is paused meanwhile (as verify does): reading
    # makes blocks, tuples and strings, no reference cycles, and each automatic
    # full collection would walk every block made so far (measured: 40 % of
    # the time of reading 100,000 lines).
    paused = gc.isenabled()
    gc.disable()
    try:
        return _read(text, file, start_t, program)  # type: ignore[arg-type]
    finally:
        if paused:
            gc.enable()


def _read(text: str, file: str, start: Vec3, program: int | None) -> Program:
    meta: dict = {"i_variables": {}, "m_variables": {}, "delay_blocks": [],
                  "ignored": [], "online": [], "skipped_buffers": []}
    run = Interpreter(file, start, meta)
    lines = split_lines(text, file)
    if "ccopt" in text.lower():
        # comments are cut by split_lines: the surface markers are read from the raw text
        for n, raw in enumerate(text.split("\n"), start=1):
            mark = surface_marker(raw, "pmac", file, n)
            if mark is not None:
                run.markers[n] = mark
    download = buffers.split_buffers(lines, file)
    meta["skipped_buffers"] = download.skipped if download else []
    meta["programs"] = download.order if download else []
    if download is None:
        if program is not None:
            raise ProgramError(f"program={program} was asked for, but the file has no "
                               "OPEN PROG ... CLOSE buffer (it is read as a bare program body)",
                               file, None)
        body = lines
        meta["program"] = None
    else:
        for lineno, line in download.outside:
            _online_line(run, lineno, line)
        meta["program"], body = buffers.select_program(download, lines, program, file)
    run.apply_coordinate_system_defaults()
    run.in_body = True
    run.run_lines(body)
    return Program(blocks=tuple(run.blocks), file=file, dialect="pmac", units="mm",
                   start=start, meta=meta)


def _online_line(run: Interpreter, line: int, text: str) -> None:
    """Execute one on-line command line of a download file (outside the buffers)."""
    pos = 0
    while True:
        pos = skip(text, pos)
        if pos >= len(text):
            return
        end = run.assignment(line, text, pos)
        if end is not None:
            pos = end
            continue
        ch = text[pos]
        if ch == "&":
            run.coord_system, command, pos = buffers.coordinate_system(text, pos, file=run.file,
                                                                       line=line)
            run.meta["online"].append({"line": line, "text": command})
            continue
        name = word(text, pos)
        if ch == "#" or name in _RECORDED_ONLINE:
            rest = text[pos:].strip()
            ccbuf = buffers.ccbuf_number(rest)
            if ccbuf is not None:
                run.meta["ccbuf"] = ccbuf
            run.meta["online"].append({"line": line, "text": rest})
            return
        raise ProgramError(
            f"unexpected {name or ch!r} outside OPEN PROG ... CLOSE: only variable "
            "assignments, &n, #n->..., UNDEFINE, DELETE and DEFINE may stand outside a "
            "program buffer", run.file, line, pos + 1)
