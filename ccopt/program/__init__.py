"""Part-program readers: text -> immutable :class:`Program`.

``read_program(path)`` picks the dialect from the file suffix (``.pmc``,
``.pmac``, ``.prg`` -> PMAC motion program; ``.mpf``, ``.spf`` -> SINUMERIK
840D; ``.nc``, ``.ngc``, ``.gcode``, ``.tap``, ``.cnc``, ``.iso`` -> ISO/RS274
G-code; ``.h`` -> HEIDENHAIN Klartext) unless ``dialect=`` says otherwise.
"""
from __future__ import annotations

import os
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.gcode.ini import LinuxCncIni, read_ini
from ccopt.program.gcode.coordinates import read_var_file
from ccopt.program.heidenhain import read_heidenhain
from ccopt.program.heidenhain.tooltable import is_tnc_table, read_tnc_tool_table
from ccopt.program.model import INPUT_FILES, Block, Modal, Motion, PLANE_AXES, Program, Source
from ccopt.program.pmac import read_pmac
from ccopt.program.sinumerik import read_sinumerik
from ccopt.program.tooltable import read_tool_table

PMAC_SUFFIXES = {".pmc", ".pmac", ".prg"}
GCODE_SUFFIXES = {".nc", ".ngc", ".gcode", ".tap", ".cnc", ".iso", ".g"}
HEIDENHAIN_SUFFIXES = {".h"}
SINUMERIK_SUFFIXES = {".mpf", ".spf"}
DIALECTS = ("gcode", "pmac", "heidenhain", "sinumerik")


def dialect_of(path: str | os.PathLike) -> str:
    """The dialect a file's suffix implies; ProgramError when it implies none."""
    suffix = Path(path).suffix.lower()
    if suffix in PMAC_SUFFIXES:
        return "pmac"
    if suffix in GCODE_SUFFIXES:
        return "gcode"
    if suffix in HEIDENHAIN_SUFFIXES:
        return "heidenhain"
    if suffix in SINUMERIK_SUFFIXES:
        return "sinumerik"
    raise ProgramError(
        f"cannot tell the dialect from the suffix {suffix or '(none)'!r}; "
        f"use {sorted(PMAC_SUFFIXES)} for PMAC, {sorted(GCODE_SUFFIXES)} for G-code, "
        f"{sorted(HEIDENHAIN_SUFFIXES)} for HEIDENHAIN Klartext, "
        f"{sorted(SINUMERIK_SUFFIXES)} for SINUMERIK, "
        "or give the dialect (--dialect gcode|pmac|heidenhain|sinumerik; dialect= in Python)",
        str(path))


def _is_tnc_table(path) -> bool:
    """``path`` names a HEIDENHAIN ``TOOL.T`` table (``BEGIN TOOL.T`` first)."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(64).decode("utf-8", errors="replace")
    except OSError:
        return False            # read_tool_table says what is wrong with it
    return is_tnc_table(head)


def read_text(text: str, file: str = "<string>", dialect: str = "gcode", *,
              tool_table: dict[int, float] | None = None,
              parameters: dict[int, float] | None = None, units: str | None = None,
              table_units: str | None = None, sub_path=(),
              max_loop_iterations: int | None = None, ini: LinuxCncIni | None = None,
              keep_going: bool = False) -> Program:
    """Read program text of the given dialect (``parameters``, ``units``,
    ``table_units``, ``sub_path``, ``max_loop_iterations``, ``ini`` and
    ``keep_going``: G-code only,
    see :func:`read_gcode`, except that SINUMERIK programs take ``units``
    and ``max_loop_iterations`` too (:func:`read_sinumerik`); PMAC programs
    have no loops ccopt runs, ``WHILE`` is refused; ``tool_table`` also gives
    HEIDENHAIN ``TOOL CALL`` radii)."""
    if dialect == "gcode":
        return read_gcode(text, file, tool_table=tool_table, parameters=parameters,
                          units=units, table_units=table_units, sub_path=sub_path,
                          max_loop_iterations=max_loop_iterations, ini=ini,
                          keep_going=keep_going)
    if keep_going:
        raise ProgramError("keep_going (go on after errors) applies to G-code programs only",
                           file)
    if ini is not None:
        raise ProgramError("a LinuxCNC INI file (--ini) applies to G-code programs only", file)
    if dialect == "pmac":
        return read_pmac(text, file)
    if dialect == "heidenhain":
        return read_heidenhain(text, file, tool_table=tool_table)
    if dialect == "sinumerik":
        return read_sinumerik(text, file, tool_table=tool_table, units=units,
                              max_loop_iterations=max_loop_iterations, sub_path=sub_path)
    raise ProgramError(f"unknown dialect {dialect!r}; choose one of {', '.join(DIALECTS)}", file)


def read_program(path: str | os.PathLike, dialect: str | None = None, *,
                 tool_table: str | os.PathLike | dict[int, float] | None = None,
                 var_file: str | os.PathLike | None = None, units: str | None = None,
                 table_units: str | None = None, sub_path=(),
                 max_loop_iterations: int | None = None,
                 ini: str | os.PathLike | None = None, keep_going: bool = False) -> Program:
    """Read a part program file.

    Parameters
    ----------
    path: program file.
    dialect: ``"gcode"``, ``"pmac"``, ``"heidenhain"`` or ``"sinumerik"``; default
        from the suffix.
    tool_table: LinuxCNC tool table or HEIDENHAIN ``TOOL.T`` (path, told apart
        by its ``BEGIN TOOL.T`` line) or ``{tool: diameter}``, for G-code
        ``G41 D<tool>``, HEIDENHAIN ``TOOL CALL <tool>`` and SINUMERIK ``T``.
    var_file: LinuxCNC parameter file (``linuxcnc.var``) whose values are in
        force at the start of a G-code program (coordinate system origins).
    units, table_units, sub_path: G-code only: the unit every length is
        converted to, the tool table's, and the folders of subroutine files
        (see :func:`~ccopt.program.gcode.read_gcode`).
    max_loop_iterations: most O-word loop iterations of a G-code program, all
        loops together (``None``: ``ccopt.program.gcode.MAX_LOOP_ITERATIONS``).
    ini: G-code only: the machine's LinuxCNC INI file
        (:mod:`ccopt.program.gcode.ini`), which gives the tool table, its
        units, the parameter file and the subroutine folders where the
        arguments above do not (a folder given comes first), and the values
        of ``#<_ini[SECTION]NAME>``.
    keep_going: G-code only: go on after an error, as LinuxCNC's ``rs274 -n 0``
        (see :func:`~ccopt.program.gcode.read_gcode`).
    """
    file = str(path)
    dialect = dialect or dialect_of(path)
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise ProgramError(f"cannot read program: {exc.strerror or exc}", file) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise ProgramError("not UTF-8/ASCII text (a binary file?)", file, line) from None
    cfg = None
    if ini is not None:
        if dialect != "gcode":
            raise ProgramError("a LinuxCNC INI file (--ini) applies to G-code programs only",
                               file)
        cfg = read_ini(ini)
        tool_table = tool_table if tool_table is not None else cfg.tool_table
        var_file = var_file if var_file is not None else cfg.var_file
        table_units = table_units or cfg.table_units
        sub_path = (*sub_path, *cfg.sub_path)
    table = tool_table
    if tool_table is not None and not isinstance(tool_table, dict):
        table = (read_tnc_tool_table(tool_table) if _is_tnc_table(tool_table)
                 else read_tool_table(tool_table))
    parameters = read_var_file(var_file) if var_file is not None else None
    if dialect != "gcode":
        for given, what in ((parameters, "a LinuxCNC parameter file (--var-file)"),
                            (units if dialect != "sinumerik" else None, "--units"),
                            (table_units, "--table-units"),
                            ((sub_path or None) if dialect != "sinumerik" else None, "--sub-path")):
            if given is not None:
                raise ProgramError(f"{what} applies to G-code programs only", file)
    if dialect == "sinumerik":
        # SINUMERIK subprograms (NAME.SPF) are looked for beside the program first
        sub_path = (str(Path(path).resolve().parent), *sub_path)
    prog = read_text(text, file, dialect, tool_table=table, parameters=parameters, units=units,
                     table_units=table_units, sub_path=sub_path,
                     max_loop_iterations=max_loop_iterations, ini=cfg, keep_going=keep_going)
    # every file it was read from: what no output may replace (ccopt.export)
    read_from = [file, *prog.meta.get(INPUT_FILES, ()), *(b.source.file for b in prog.blocks),
                 *(str(f) for f in (tool_table, var_file, ini)
                   if isinstance(f, (str, os.PathLike)) and os.path.isfile(f))]
    prog.meta[INPUT_FILES] = tuple(dict.fromkeys(read_from))
    return prog


__all__ = ["Block", "Modal", "Motion", "PLANE_AXES", "Program", "ProgramError", "Source",
           "dialect_of", "read_program", "read_text"]
