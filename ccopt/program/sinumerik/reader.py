"""The line loop of a SINUMERIK program: flow statements here, ordinary
blocks in :mod:`.blocks`; the runaway guards of the G-code reader."""
from __future__ import annotations

import gc
import math

from ccopt.errors import ProgramError
from ccopt.program.expr import ExprError
from ccopt.program.gcode import reader as gcode_reader
from ccopt.program.gcode import state as gcode_state
from ccopt.program.gcode.coordinates import init_coordinates
from ccopt.program.gcode.state import GCodeState, ProgramEnd
from ccopt.program.gcode.units import output_units
from ccopt.program.model import (INPUT_FILES, PLANE_CHANGES_CHECKED, TRAILING_WORDS,
                                 Program, SiemensModes)
from ccopt.program.sinumerik import corners
from ccopt.program.sinumerik.blocks import exec_block
from ccopt.program.sinumerik.calls import CallFrame, load_sub
from ccopt.program.sinumerik.flow import jump_target, match_structures
from ccopt.program.sinumerik.lexer import next_name, skip_blanks
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.values import whole

#: ``Program.meta`` key: the codes read and ignored (``G64``, ``G642``,
#: ``STOPRE``, ...) -> the first line each stands on.
IGNORED_CODES = "sinumerik_ignored"

#: The motion (G group 1, tenths) in force at program start: its reset value
#: (MD20150 ``$MC_GCODE_RESET_VALUES``), ``G1`` in Siemens' standard
#: configuration (PM Fundamentals, list of G functions: G1 "Def."), so axis
#: words before any G0-G3 move linearly at the programmed feed.
RESET_MOTION = 10


def read_sinumerik(text: str, file: str = "<string>", *,
                   tool_table: dict[int, float] | None = None, start=(0.0, 0.0, 0.0),
                   units: str | None = None, max_loop_iterations: int | None = None,
                   sub_path=()) -> Program:
    """Read a SINUMERIK 840D program into a :class:`Program` (dialect ``"sinumerik"``).

    ``tool_table`` maps tool numbers ``T`` to diameters (the radius of
    ``D1``..; a ``$TC_DP6[t, d]`` set in the program wins); ``units`` is the
    unit every length is converted to (default the program's first
    ``G70``/``G71``, mm); ``max_loop_iterations`` bounds the passes of all
    loops and backward jumps together (default the G-code reader's).
    """
    file, table, s = gcode_reader.check_inputs(file, tool_table, start)
    if not isinstance(text, str):
        raise ProgramError(f"program text must be a string, not {type(text).__name__}", file)
    if units is not None and units not in ("mm", "inch"):
        raise ProgramError(f"units must be mm or inch, not {units!r}", file)
    loops = gcode_state.MAX_LOOP_ITERATIONS if max_loop_iterations is None \
        else max_loop_iterations
    state = GCodeState(text, file, table, s, max_executed_lines=gcode_state.MAX_EXECUTED_LINES,
                       max_call_depth=gcode_state.MAX_CALL_DEPTH, max_loop_iterations=loops)
    state.out_units = units
    state.sub_path = tuple(str(p) for p in sub_path)
    state.siemens = SiemensModes()
    state.motion_mode = RESET_MOTION
    init_coordinates(state)
    paused = gc.isenabled()
    gc.disable()
    try:
        run = SinumerikRun(state, match_structures(state.lines, file))
        _run_lines(run)
    except ProgramEnd:
        pass
    except ProgramError:
        raise
    except ExprError as exc:
        raise state.error(exc.message, exc.col) from None
    except RecursionError:
        raise state.error("expression nested too deeply to read") from None
    except Exception as exc:  # a bug in this reader must still reach users located
        raise ProgramError(f"internal error of the SINUMERIK reader ({type(exc).__name__}: "
                           f"{exc}); please report it with this program", file,
                           state.line_no + 1) from exc
    finally:
        if paused:
            gc.enable()
    if run.pending_sar is not None:
        raise state.error("a smooth approach (G147/G247/G347) whose end point no later block "
                          "gives: write the contour's start in this block or a later one",
                          run.pending_sar.sar[1], run.pending_line)
    if run.pending_angle is not None:
        raise state.error("a contour definition (a line with ANG and no end point) whose "
                          "second block never comes", run.pending_angle[0].values["ANG"][2],
                          run.pending_angle[1])
    corners.at_end(run)
    state.meta[corners.NOT_INSERTED] = dict(run.not_inserted)
    state.meta[PLANE_CHANGES_CHECKED] = True
    state.meta[TRAILING_WORDS] = tuple(state.pending_words)
    state.meta[IGNORED_CODES] = dict(run.ignored)
    state.meta[INPUT_FILES] = tuple(f for _, _, f in state.sub_files)
    return Program(tuple(state.blocks), file=file, dialect="sinumerik",
                   units=output_units(state), start=state.start, meta=state.meta)


def _run_lines(run: SinumerikRun) -> None:
    """The blocks in order, into subprograms and back (:mod:`.calls`)."""
    state = run.state
    frames = [CallFrame(run.structure, 0)]
    pc = 0
    while True:
        st = run.structure
        if pc >= len(st.lines):
            if len(frames) == 1:
                return
            pc = _return(run, frames)
            continue
        state.line_no = run.offset + pc
        state.executed += 1
        if state.executed > state.max_executed_lines:
            raise state.error(f"more than {state.max_executed_lines} blocks executed: endless "
                              "loop? check the loop conditions and jumps")
        try:
            kind = st.kinds[pc]
            if kind is not None:
                pc = _flow(run, pc, kind)
                continue
            try:
                call = exec_block(run, st.lines[pc])
            except ProgramEnd:
                if len(frames) == 1:
                    raise
                pc = _return(run, frames)     # M17, RET, M2, M30 end a subprogram
                continue
            pc = pc + 1 if call is None else _enter(run, frames, call, pc)
        except ExprError as exc:
            raise state.error(exc.message, exc.col) from None


def _enter(run: SinumerikRun, frames: list, call: tuple, pc: int) -> int:
    """Run subprogram ``call = (name, passes, col)`` called from line ``pc``."""
    name, passes, col = call
    if len(frames) > run.state.max_call_depth:
        raise ExprError(f"subprogram calls nested deeper than {run.state.max_call_depth}: "
                        "runaway recursion?", col)
    frame = load_sub(run.state, run.loaded, name, col)
    frames[-1].return_pc = pc + 1
    frame.passes = passes - 1
    frames.append(frame)
    _count_pass(run, col)
    run.structure, run.offset = frame.structure, frame.offset
    return 0


def _return(run: SinumerikRun, frames: list) -> int:
    """The end of a subprogram pass: the next pass, or back to the caller."""
    frame = frames[-1]
    if frame.passes > 0:
        frame.passes -= 1
        _count_pass(run, 0)
        return 0
    frames.pop()
    caller = frames[-1]
    run.structure, run.offset = caller.structure, caller.offset
    return caller.return_pc


def _count_pass(run: SinumerikRun, col: int) -> None:
    state = run.state
    state.loop_iterations += 1
    if state.loop_iterations > state.max_loop_iterations:
        raise ExprError(f"more than {state.max_loop_iterations} loop passes and backward "
                        "jumps: endless loop? (raise the limit with --max-loop-iterations N)",
                        col)


def _condition(run: SinumerikRun, code: str, p: int) -> tuple[bool, int]:
    value, end = run.variables.evaluate(code, p)
    return value != 0, end


def _rest_empty(code: str, p: int, what: str) -> None:
    p = skip_blanks(code, p)
    if p < len(code):
        raise ExprError(f"unexpected {code[p]!r} after {what}", p)


def _flow(run: SinumerikRun, pc: int, kind: str) -> int:
    """Execute the flow statement on line ``pc``; the next line."""
    st = run.structure
    line = st.lines[pc]
    code = line.code
    _, p = next_name(code, line.start)
    if kind in ("IF", "WHILE", "UNTIL"):
        holds, end = _condition(run, code, p)
        _rest_empty(code, end, kind)
        if kind == "IF":
            return pc + 1 if holds else st.else_of.get(pc, st.match[pc]) + 1
        if kind == "WHILE":
            if holds:
                _count_pass(run, line.start)
                return pc + 1
            return st.match[pc] + 1
        if holds:
            return pc + 1
        _count_pass(run, line.start)
        return st.match[pc] + 1
    if kind == "IFGOTO":
        holds, end = _condition(run, code, p)
        return _jump(run, pc, code, end) if holds else pc + 1
    if kind in ("GOTOF", "GOTOB", "GOTO", "GOTOC"):
        return _jump(run, pc, code, line.start)
    if kind == "ELSE":
        return st.match[_if_of(st, pc)] + 1
    if kind in ("ENDWHILE",):
        return st.match[pc]
    if kind == "ENDLOOP":
        _count_pass(run, line.start)
        return st.match[pc] + 1
    if kind == "FOR":
        return _for(run, pc, code, p)
    if kind == "ENDFOR":
        return _endfor(run, pc)
    _rest_empty(code, p, kind)
    return pc + 1          # ENDIF, LOOP, REPEAT


def _if_of(st, else_line: int) -> int:
    return next(i for i, e in st.else_of.items() if e == else_line)


def _jump(run: SinumerikRun, pc: int, code: str, p: int) -> int:
    """``GOTOF``/``GOTOB``/``GOTO``/``GOTOC label`` at ``p``."""
    q = skip_blanks(code, p)
    keyword, q = next_name(code, q)
    if keyword not in ("GOTOF", "GOTOB", "GOTO", "GOTOC"):
        raise ExprError("expected GOTOF, GOTOB, GOTO or GOTOC and a jump label", p)
    start = skip_blanks(code, q)
    end = start
    while end < len(code) and (code[end].isalnum() or code[end] == "_"):
        end += 1
    target = code[start:end]
    if not target:
        raise ExprError(f"{keyword} needs a jump label or block number", start)
    _rest_empty(code, end, f"{keyword} {target}")
    to = jump_target(run.structure, keyword, target, pc)
    if to is None:
        if keyword == "GOTOC":
            return pc + 1
        where = {"GOTOF": " after this block", "GOTOB": " before this block"}.get(keyword, "")
        raise ExprError(f"{keyword} {target}: no jump label {target}:{where}", start)
    if to <= pc:
        _count_pass(run, start)
    return to


def _for(run: SinumerikRun, pc: int, code: str, p: int) -> int:
    """``FOR var = start TO end``: var is an R parameter or a DEF variable."""
    q = skip_blanks(code, p)
    name, r = next_name(code, q)
    digits = ""
    while r < len(code) and code[r].isdigit():
        digits += code[r]
        r += 1
    key = ("r", int(digits)) if name == "R" and digits else ("user", name)
    if key[0] == "user" and (digits or name not in run.variables.user):
        raise ExprError("FOR counts an R parameter or a DEF INT variable: FOR R1=1 TO 10", q)
    r = skip_blanks(code, r)
    if r >= len(code) or code[r] != "=":
        raise ExprError("FOR needs '=': FOR R1=1 TO 10", r)
    first, r = run.variables.evaluate(code, r + 1)
    word, r = next_name(code, skip_blanks(code, r))
    if word != "TO":
        raise ExprError("FOR needs TO: FOR R1=1 TO 10", r)
    last, r = run.variables.evaluate(code, r)
    _rest_empty(code, r, "FOR")
    first, last = whole(first, q), whole(last, r)
    _store(run, key, float(first))
    run.for_loops[pc] = (key, last)
    if first > last:
        return run.structure.match[pc] + 1
    _count_pass(run, q)
    return pc + 1


def _endfor(run: SinumerikRun, pc: int) -> int:
    start = run.structure.match[pc]
    key, last = run.for_loops[start]
    value = (run.variables.r.get(key[1], 0.0) if key[0] == "r"
             else run.variables.user.get(key[1], 0.0)) + 1.0
    _store(run, key, value)
    if not math.isfinite(value) or value > last:
        return pc + 1
    _count_pass(run, 0)
    return start + 1


def _store(run: SinumerikRun, key: tuple, value: float) -> None:
    if key[0] == "r":
        run.variables.r[key[1]] = value
    else:
        run.variables.user[key[1]] = value
