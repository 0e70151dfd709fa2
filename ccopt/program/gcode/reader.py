"""Running a program text line by line (LinuxCNC ``rs274ngc_pre.cc``).

:func:`open_program` builds the state (lines, expression grammar, the span
of lines ``%`` delimits); :func:`run` executes lines in order, handing
O-word lines to :mod:`.oword` (which returns the next line) and ordinary
lines to :mod:`.codes` and :mod:`.execute`, until the program ends. Runs of
plain straight move lines go to :mod:`.plain` first, which executes those
it is sure to execute as this loop does and leaves it the rest.
"""
from __future__ import annotations

import gc
import math

from ccopt.errors import ProgramError
from ccopt.program.expr import ExprError
from ccopt.program.gcode.codes import read_words
from ccopt.program.gcode.coordinates import init_coordinates
from ccopt.program.gcode.execute import execute_words
from ccopt.program.gcode.fanuc import exec_fanuc, runs_as_fanuc
from ccopt.program.gcode.oword import count_line, exec_oword, innermost_loop
from ccopt.program.gcode.parameters import (MAX_PARAMETER, attach_grammar, message_text,
                                             restore_after_call, set_parameter)
from ccopt.program.gcode.plain import run_plain
from ccopt.program.gcode.state import GCodeState, ProgramEnd
from ccopt.program.gcode.units import output_units
from ccopt.program.gcode.words import Lexed, lex, olabel, program_span
from ccopt.program.model import (ERRORS_PASSED, INPUT_FILES, MESSAGES, PLANE_CHANGES_CHECKED,
                                 START_PARAMETERS, TRAILING_WORDS, Program)
from ccopt.program.tooltable import ToolTable


def check_inputs(file, tool_table, start) -> tuple[str, dict[int, float] | None,
                                                   tuple[float, float, float]]:
    """``read_gcode``'s arguments checked and normalised: the file name as a
    string, the tool table as ``{int: float}``, the start as three floats."""
    if not isinstance(file, str):
        file = str(file)
    try:
        s = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ProgramError(f"start must be three numbers (x, y, z), got {start!r}", file) from None
    if len(s) != 3 or not all(math.isfinite(v) for v in s):
        raise ProgramError(f"start must be three finite numbers (x, y, z), got {start!r}", file)
    table = None
    if tool_table is not None:
        table = ToolTable(orientation=getattr(tool_table, "orientation", None))
        try:
            for k, v in dict(tool_table).items():
                table[int(k)] = float(v)
        except (TypeError, ValueError):
            raise ProgramError("tool_table must map tool numbers to diameters", file) from None
    return file, table, s


def open_program(text: str, file: str, tool_table: dict[int, float] | None,
                 start: tuple[float, float, float], *, max_executed_lines: int,
                 max_call_depth: int, max_loop_iterations: int,
                 parameters: dict[int, float] | None = None) -> GCodeState:
    """The state to run ``text`` with (its ``%`` span already found), its
    numbered parameters and coordinate systems set from ``parameters``."""
    state = GCodeState(text, file, tool_table, start, max_executed_lines=max_executed_lines,
                       max_call_depth=max_call_depth, max_loop_iterations=max_loop_iterations)
    for number, value in (parameters or {}).items():
        if not (isinstance(number, int) and 1 <= number <= MAX_PARAMETER
                and math.isfinite(float(value))):
            raise ProgramError(f"parameter #{number} = {value!r}: numbers run from 1 to "
                               f"{MAX_PARAMETER} and values must be finite", file)
        state.params[number] = float(value)
    state.meta[START_PARAMETERS] = dict(state.params)
    init_coordinates(state)
    attach_grammar(state)
    state.first_line, state.end_line = program_span(state)
    return state


def run(state: GCodeState) -> Program:
    """Execute the program; the blocks it made as a :class:`Program`.

    Errors raised inside a subroutine name the call that ran it.
    """
    # The cyclic garbage collector is paused meanwhile (as verify does): the
    # lines make blocks, tuples and cached words, no reference cycles, and each
    # automatic full collection would walk every object made so far (measured:
    # 40 % of the time of reading 20,000 lines).
    paused = gc.isenabled()
    gc.disable()
    try:
        _run_lines(state)
    except ProgramEnd:
        pass
    except ProgramError as exc:
        if len(state.frames) > 1 and exc.line is not None:
            f = state.frames[-1]
            exc.message += (f" (in subroutine {olabel(f.name)} called from line "
                            f"{f.call_line + 1})")
        exc.read_before = Program(tuple(state.blocks), file=state.file, dialect="gcode",
                                  units=output_units(state), start=state.start,
                                  meta=state.meta)
        raise
    finally:
        # the state is held in a reference cycle (its expression grammar reads
        # it), so it waits for a collection: free its per-line caches now
        state.lexed.clear()
        state.constant.clear()
        state.matched.clear()
        if paused:
            gc.enable()
    units = output_units(state)
    state.meta[PLANE_CHANGES_CHECKED] = True     # execute._set_modes refuses them
    state.meta[TRAILING_WORDS] = tuple(state.pending_words)
    # the subroutine files read from the sub path, called or not: inputs too
    state.meta[INPUT_FILES] = tuple(dict.fromkeys(f for _, _, f in state.sub_files))
    return Program(tuple(state.blocks), file=state.file, dialect="gcode", units=units,
                   start=state.start, meta=state.meta)


def _run_lines(state: GCodeState) -> None:
    """The line loop, with the runaway guard; expression errors are located
    on the line being executed."""
    pc = state.first_line
    # the program's lines, or a sub file's while a call runs there
    while (pc < state.end_line and not state.in_sub_file(pc)) or (
            len(state.frames) > 1 and state.in_sub_file(pc)):
        # a run of plain move lines in one loop (plain.py), which leaves any
        # line it is not sure of to this loop
        after = run_plain(state, pc)
        if after != pc:
            pc = after
            continue
        count_line(state, pc)
        try:
            lx = lex(state, pc)
            if lx.oword is not None:
                pc = exec_oword(state, pc, lx)
                state.in_loop = innermost_loop(state) is not None
            elif lx.fanuc is not None and runs_as_fanuc(state, lx):
                pc = exec_fanuc(state, pc, lx)
                state.in_loop = innermost_loop(state) is not None
            else:
                if lx.message is not None:
                    _message(state, *lx.message)
                if lx.abort is not None:
                    col, text = lx.abort
                    raise state.error(f"(abort) {message_text(state, text).strip()}: the "
                                      "program stops here, as LinuxCNC's does", col)
                if lx.first is not None:
                    _exec_line(state, lx)
                pc += 1
        except (ExprError, ProgramError) as exc:
            err = state.error(exc.message, exc.col) if isinstance(exc, ExprError) else exc
            if not state.keep_going:
                raise err from None
            pc = _go_on_after(state, pc, err)
        except RecursionError:
            raise state.error("expression or parameter reference nested too deeply") from None


#: ``#5599``: LinuxCNC shows ``(debug, ...)`` messages while it is > 0 (1 at start).
DEBUG_MESSAGES = 5599


def _go_on_after(state: GCodeState, pc: int, err: ProgramError) -> int:
    """LinuxCNC's ``rs274 -n 0``: the error ``err`` met at line ``pc`` is
    recorded (``Program.meta[ERRORS_PASSED]``, located) and reading goes on:
    the subroutine calls in progress unwound (``Interp::unwind_call``: each
    caller's ``#1``-``#30`` given back, except over an ``M98``) to the line
    after the outermost call, or else at the next line."""
    state.meta.setdefault(ERRORS_PASSED, []).append(str(err))
    if len(state.frames) == 1:
        return pc + 1
    for frame in reversed(state.frames[1:]):
        if not frame.fanuc:
            restore_after_call(state, frame, None)
    pc = state.frames[1].return_pc
    del state.frames[1:]
    state.in_loop = innermost_loop(state) is not None
    return pc


def _message(state: GCodeState, kind: str, text: str) -> None:
    """A ``(debug, ...)``, ``(msg, ...)`` or ``(print, ...)`` comment's message,
    recorded in order (``Program.meta[MESSAGES]``: ``{"file", "line", "text",
    "kind"}``), debug and print with their parameters' values. LinuxCNC shows
    msg and debug as MESSAGE (debug only while ``#5599`` > 0) and prints print
    on its standard output."""
    if kind == "debug" and not state.params.get(DEBUG_MESSAGES, 1.0) > 0.0:
        return
    file, line = state.where(state.line_no)
    shown = text if kind == "msg" else message_text(state, text)
    state.meta.setdefault(MESSAGES, []).append({"file": file, "line": line, "text": shown,
                                                "kind": kind})


def _exec_line(state: GCodeState, lx: Lexed) -> None:
    """An ordinary line: its parameter settings (after all its words are
    read), then its words."""
    words = state.constant.get(state.line_no)
    if words is None:
        words, settings = read_words(state, lx)
        for kind, key, value in settings:
            set_parameter(state, kind, key, value)
        if not settings and "#" not in lx.code and "[" not in lx.code:
            # No parameter or expression: the words are the same every time.
            state.constant[state.line_no] = words
    if words.letters or words.g or words.m:
        execute_words(state, words)
