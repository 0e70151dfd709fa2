"""ISO/RS274NGC G-code reader (LinuxCNC dialect, plus Fagor G136-G139).

:func:`read_gcode` runs a part program the way LinuxCNC's interpreter reads
it and returns an immutable :class:`~ccopt.program.model.Program`: one
:class:`~ccopt.program.model.Block` per executed move or dwell, in execution
order, with O-word subroutines, branches and loops expanded. Coordinates are
absolute program units; feeds are program units per second; ``G2`` is
clockwise seen down the plane normal; side +1 is ``G41`` (left).

The dialect (words, codes, O-words, units and signs) and every decision the
reader takes are described in ``docs/gcode.md``. The stages follow LinuxCNC's
interpreter: :mod:`.words` (``interp_read.cc``, lexing), :mod:`.parameters`
(parameters and expression values), :mod:`.codes` (a line's words and code
checks), :mod:`.oword` (``interp_o_word.cc``), :mod:`.execute`
(``interp_convert.cc``), :mod:`.arcs` (``interp_arc.cc``) and :mod:`.reader`
(the line loop), all passing one :class:`~.state.GCodeState`.
"""
from __future__ import annotations

from ccopt.errors import ProgramError
# The limits the single-module reader exposed stay importable from here.
from ccopt.program.gcode.arcs import MAX_ARC_TURNS  # noqa: F401
from ccopt.program.gcode.ini import LinuxCncIni, read_ini  # noqa: F401 - read_ini exported
from ccopt.program.gcode.parameters import MAX_PARAMETER, SUB_PARAMS  # noqa: F401
from ccopt.program.gcode.reader import check_inputs, open_program, run
# read_gcode reads the three MAX_ limits at each call, so setting them here
# (as the runaway tests do) changes the guards; LOOP_LINES_PER_ITERATION is
# exported for reference only.
from ccopt.program.gcode.state import (  # noqa: F401 - LOOP_LINES_PER_ITERATION exported
    LOOP_LINES_PER_ITERATION,
    MAX_CALL_DEPTH,
    MAX_EXECUTED_LINES,
    MAX_LOOP_ITERATIONS,
)
from ccopt.program.gcode.units import MM_PER_INCH, UNITS  # noqa: F401
from ccopt.program.model import Program

__all__ = ["read_gcode", "MAX_EXECUTED_LINES", "MAX_CALL_DEPTH", "MAX_LOOP_ITERATIONS"]


def read_gcode(text: str, file: str = "<string>", *, tool_table: dict[int, float] | None = None,
               start=(0.0, 0.0, 0.0), parameters: dict[int, float] | None = None,
               units: str | None = None, table_units: str | None = None,
               sub_path=(), max_loop_iterations: int | None = None,
               ini: LinuxCncIni | None = None, keep_going: bool = False) -> Program:
    """Read RS274NGC/LinuxCNC G-code into a :class:`Program` (dialect ``"gcode"``).

    Parameters
    ----------
    text, file:
        The program text; the name used in :class:`~ccopt.program.model.Source` and errors.
    tool_table:
        Tool number -> DIAMETER (program units, e.g. :func:`~ccopt.program.tooltable.
        read_tool_table`), for ``G41``/``G42 D<tool>`` or a loaded tool (``T<n> M6``).
    start: machine position ``(x, y, z)`` before the first block, program units.
    parameters:
        Numbered parameters in force at the start (e.g. from a LinuxCNC
        parameter file, :func:`~ccopt.program.gcode.coordinates.read_var_file`):
        the coordinate system origins ``#5221``..., the active system
        ``#5220`` and the G92 offset ``#5210``-``#5213`` among them, in the
        output units.
    units:
        ``"mm"`` or ``"inch"``: every length of the program is converted to
        it; default the program's first ``G20``/``G21`` (mm if it moves
        before saying). ``G20``/``G21`` may change anywhere.
    table_units:
        The tool table's units (LinuxCNC's are the machine's); default the
        output units.
    sub_path:
        Folders, in order, where ``o<name> call`` of a subroutine the program
        does not define finds ``name.ngc`` (LinuxCNC's SUBROUTINE_PATH);
        nowhere else. A name holding a path is refused.
    max_loop_iterations:
        Most loop iterations (passes of every O-word ``do``/``while``/
        ``repeat`` loop of the program, together) before the reader stops
        with an error located at the loop's first line; ``None``:
        :data:`MAX_LOOP_ITERATIONS`. The loops may also execute at most
        :data:`LOOP_LINES_PER_ITERATION` times as many lines (bodies,
        nested loops and the subroutines they call, all together), so a
        long body stops as soon as a short one.

    ini:
        The machine's INI file (:func:`~.ini.read_ini`) for ``#<_ini[SECTION]NAME>``.
    keep_going:
        LinuxCNC's ``rs274 -n 0``: an error is recorded (``meta["errors_passed"]``)
        and reading goes on after it, the calls in progress unwound.

    The runaway guards are this module's :data:`MAX_EXECUTED_LINES`,
    :data:`MAX_CALL_DEPTH` and :data:`MAX_LOOP_ITERATIONS`, read at each call.

    Raises
    ------
    ProgramError
        For anything wrong with the text, located by file, line and column.
    """
    file, table, s = check_inputs(file, tool_table, start)
    loops = _check_options(file, text, units, table_units, max_loop_iterations)
    if ini is not None:
        parameters = ini.start_parameters(parameters)
    state = None
    try:
        state = open_program(text, file, table, s, max_executed_lines=MAX_EXECUTED_LINES,
                             max_call_depth=MAX_CALL_DEPTH, max_loop_iterations=loops,
                             parameters=parameters)
        state.out_units, state.table_units = units, table_units
        state.sub_path = tuple(str(p) for p in sub_path)
        state.ini, state.keep_going = ini, keep_going
        return run(state)
    except ProgramError:
        raise
    except RecursionError:
        line = state.line_no + 1 if state is not None else None
        raise ProgramError("program nested too deeply to read", file, line) from None
    except Exception as exc:  # a bug in this reader must still reach users located
        line = state.line_no + 1 if state is not None else None
        raise ProgramError(f"internal error of the G-code reader ({type(exc).__name__}: {exc}); "
                           "please report it with this program", file, line) from exc


def _check_options(file: str, text, units, table_units, max_loop_iterations) -> int:
    """:func:`read_gcode`'s option checks; the loop iteration bound in force."""
    for name, value in (("units", units), ("table_units", table_units)):
        if value is not None and value not in UNITS:
            raise ProgramError(f"{name} must be one of {', '.join(UNITS)}, not {value!r}", file)
    if not isinstance(text, str):
        raise ProgramError(f"program text must be a string, not {type(text).__name__}", file)
    loops = MAX_LOOP_ITERATIONS if max_loop_iterations is None else max_loop_iterations
    if isinstance(loops, bool) or not isinstance(loops, int) or loops < 0:
        raise ProgramError(f"max_loop_iterations must be a whole number >= 0, got {loops!r}",
                           file)
    return loops
