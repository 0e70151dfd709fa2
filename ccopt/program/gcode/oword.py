"""O-word control flow (LinuxCNC ``interp_o_word.cc``).

Subroutines (``sub``/``endsub``/``call``/``return``), branches
(``if``/``elseif``/``else``/``endif``) and loops (``do``/``while``,
``while``/``endwhile``, ``repeat``/``endrepeat``, ``break``, ``continue``).
A structure is matched (nesting and labels checked) when execution first
reaches it; the match is cached. Every handler takes the 0-based line ``pc``
of the O-word and returns the line to execute next.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

from ccopt.program.expr import ExprError, parse_bracketed
from ccopt.program.gcode.parameters import (
    SUB_PARAMS,
    bind_call_arguments,
    read_value,
    restore_after_call,
)
from ccopt.program.gcode.state import (LINE_SPLIT, LOOP_LINES_PER_ITERATION, Ctrl, Frame,
                                       GCodeState)
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, Lexed, fmt, lex, olabel, skip_blanks

_OPENERS = {"sub": "endsub", "if": "endif", "do": "while", "while": "endwhile",
            "repeat": "endrepeat"}
_CLOSERS = {"endsub": "sub", "endif": "if", "endwhile": "while", "endrepeat": "repeat"}
_LOOPS = ("do", "while", "repeat")
# A repeat count beyond this runs "for ever" (the loop iteration limit stops it).
_REPEAT_LIMIT = 2**62


# ---------------------------------------------------------------------------
# Arguments and conditions
# ---------------------------------------------------------------------------
def o_args(state: GCodeState, lx: Lexed, what: str) -> list[float]:
    """Evaluate the bracketed arguments after an O-word keyword; ``what``
    tells in errors how to write them."""
    code = lx.code
    ow = lx.oword
    p = skip_blanks(code, ow.rest)
    args: list[float] = []
    while p < len(code):
        if code[p] != "[":
            raise ExprError(f"unexpected {code[p]!r} after {olabel(ow.label)} {ow.keyword}: "
                            f"{what}", p)
        value, p = parse_bracketed(code, p, state.grammar)
        if not math.isfinite(value):
            raise ExprError("value is not a finite number", p)
        args.append(value)
        p = skip_blanks(code, p)
    return args


def _condition(state: GCodeState, i: int) -> float:
    """The one bracketed condition of the O-word at line ``i`` (errors located there)."""
    lx = lex(state, i)
    saved = state.line_no
    state.line_no = i
    try:
        args = o_args(state, lx, "write one condition in brackets, e.g. [#1 LT 3]")
    except ExprError as exc:
        raise state.error(exc.message, exc.col, i) from None
    state.line_no = saved
    if len(args) != 1:
        raise state.error(f"{olabel(lx.oword.label)} {lx.oword.keyword} needs exactly one "
                          "condition in brackets, e.g. [#1 LT 3]", lx.oword.col, i)
    return args[0]


def _no_args(state: GCodeState, lx: Lexed, line: int | None = None) -> None:
    p = skip_blanks(lx.code, lx.oword.rest)
    if p < len(lx.code):
        raise state.error(f"unexpected text after {olabel(lx.oword.label)} "
                          f"{lx.oword.keyword}: it takes no argument", p, line)


# ---------------------------------------------------------------------------
# Matching a structure
# ---------------------------------------------------------------------------
def structure(state: GCodeState, i: int) -> tuple:
    """Match the structure opened at line ``i``: ``(end_line, branches)``.

    ``branches`` lists the ``elseif``/``else`` lines of an ``if``. Nesting
    must be proper and every closer must carry its opener's label.
    """
    cached = state.matched.get(i)
    if cached is not None:
        return cached
    ow = lex(state, i).oword
    kind, label = ow.keyword, ow.label
    stack: list[tuple[str, str, int]] = []
    branches: list[int] = []
    for j in range(i + 1, state.region_end(i)):
        if not state.lines[j] or ("o" not in state.lines[j] and "O" not in state.lines[j]):
            continue
        o = lex(state, j).oword
        if o is None or o.keyword is None:
            continue
        kw, lab = o.keyword, o.label
        where = f"{olabel(lab)} {kw} at line {j + 1}"
        if kw == "sub":
            if kind == "sub" or any(s[0] == "sub" for s in stack):
                raise state.error(f"{where}: subroutine definitions cannot be nested; close "
                                  f"the enclosing sub first", o.col, j)
            stack.append((kw, lab, j))
        elif kw == "while" and stack and stack[-1][0] == "do" and stack[-1][1] == lab:
            stack.pop()
        elif kw == "while" and not stack and kind == "do" and lab == label:
            state.matched[i] = (j, ())
            return state.matched[i]
        elif kw in _OPENERS:
            stack.append((kw, lab, j))
        elif kw in _CLOSERS:
            if _closes(state, stack, o, j, where, (kind, label, i)):
                state.matched[i] = (j, tuple(branches))
                return state.matched[i]
        elif kw in ("elseif", "else"):
            _branch(state, stack, o, j, where, (kind, label), branches)
    if kind == "sub":
        m99 = next((j for j in range(i + 1, state.region_end(i)) if lex(state, j).fanuc == 99),
                   None)
        if m99 is not None:
            raise state.error(f"'O{label} endsub' or 'O{label} return' must follow 'O{label} "
                              f"sub' subroutine definition, not M99", lex(state, m99).start,
                              m99)
    raise state.error(f"{olabel(label)} {kind} has no matching {olabel(label)} "
                      f"{_OPENERS[kind]}", ow.col, i)


def _closes(state: GCodeState, stack: list, o, j: int, where: str, opener: tuple) -> bool:
    """Closer ``o`` at line ``j``: pops the inner structure it closes, or is
    the closer of ``opener`` = (kind, label, line) (True); anything else is
    improper nesting."""
    kind, label, i = opener
    want = _CLOSERS[o.keyword]
    if stack:
        top = stack[-1]
        if top[0] != want or top[1] != o.label:
            raise state.error(f"{where} does not close {olabel(top[1])} {top[0]} "
                              f"at line {top[2] + 1}: close it with "
                              f"{olabel(top[1])} {_OPENERS[top[0]]} first", o.col, j)
        stack.pop()
        return False
    if want == kind and o.label == label:
        return True
    raise state.error(f"{where} does not close {olabel(label)} {kind} at line "
                      f"{i + 1}: expected {olabel(label)} {_OPENERS[kind]}", o.col, j)


def _branch(state: GCodeState, stack: list, o, j: int, where: str, opener: tuple,
            branches: list[int]) -> None:
    """An ``elseif``/``else`` at line ``j``: inside an inner ``if`` of its
    label, or a branch of ``opener`` = (kind, label) appended to ``branches``
    (nothing may follow the ``else``)."""
    kind, label = opener
    if stack:
        top = stack[-1]
        if top[0] != "if" or top[1] != o.label:
            raise state.error(f"{where} is not inside an if with label {olabel(o.label)}",
                              o.col, j)
    elif kind == "if" and o.label == label:
        if branches and lex(state, branches[-1]).oword.keyword == "else":
            raise state.error(f"{where} comes after the else of {olabel(label)} if", o.col, j)
        branches.append(j)
    else:
        raise state.error(f"{where} is not inside an if with label {olabel(o.label)}",
                          o.col, j)


# ---------------------------------------------------------------------------
# Executing O-words
# ---------------------------------------------------------------------------
def exec_oword(state: GCodeState, pc: int, lx: Lexed) -> int:
    """Execute the O-word line ``pc``; returns the next line to execute."""
    kw = lx.oword.keyword
    if kw is None:
        # a program number, or a Fanuc subprogram's head run into (fanuc.py)
        if lx.oword.label.isdigit():
            state.meta.setdefault("program_number", int(lx.oword.label))
        return pc + 1
    return _HANDLERS[kw](state, pc, lx)


def _sub(state: GCodeState, pc: int, lx: Lexed) -> int:
    """A definition reached by execution: register it and skip its body."""
    ow = lx.oword
    if len(state.frames) > 1:
        raise state.error(f"{olabel(ow.label)} sub inside a running subroutine: "
                          "subroutine definitions cannot be nested", ow.col)
    end, _ = structure(state, pc)
    _define(state, ow.label, pc, end, ow.col)
    return end + 1


def _call(state: GCodeState, pc: int, lx: Lexed) -> int:
    ow = lx.oword
    label, col = ow.label, ow.col
    if ow.computed is not None:
        label = computed_label(state, lx.code, ow.computed, col)
    args = o_args(state, lx, "write the arguments in brackets, e.g. [1] [2.5]")
    if len(args) > SUB_PARAMS:
        raise state.error(f"{olabel(label)} call with {len(args)} arguments: at most "
                          f"{SUB_PARAMS} (#1 to #{SUB_PARAMS})", col)
    return enter_sub(state, label, pc, col, args)


def enter_sub(state: GCodeState, label: str, pc: int, col: int, args: list[float]) -> int:
    """Call sub ``label`` from line ``pc`` (0-based; ``col`` locates errors)
    with ``args`` as ``#1``..: its frame pushed, the first line of its body
    returned. Also how G70-G72 run their contour's sub (lathe_cycles.py)."""
    sub = state.subs.get(label)
    if sub is None:
        sub = _define_ahead(state, pc, label, col)
    if len(state.frames) > state.max_call_depth:
        raise state.error(f"subroutine calls nested deeper than {state.max_call_depth}: "
                          "runaway recursion? check the condition that ends it", col)
    saved = bind_call_arguments(state, args)
    state.frames.append(Frame(name=label, return_pc=pc + 1, call_line=pc, saved=saved))
    return sub[0] + 1


def computed_label(state: GCodeState, code: str, p: int, col: int) -> str:
    """The number a parameter or expression label evaluates to, as a label."""
    value, _ = read_value(state, code, p, "O", col)
    if abs(value - round(value)) > WHOLE_NUMBER_TOL or value < 0:
        raise state.error(f"O-word label {fmt(value)} is not a whole number >= 0", p)
    return str(int(round(value)))


def _define_ahead(state: GCodeState, pc: int, label: str, col: int) -> tuple[int, int]:
    """A sub not seen yet: LinuxCNC skips forward from the call to find it."""
    found = _find_sub(state, label, pc + 1, state.region_end(pc))
    if found is not None:
        return found
    if state.sub_path and not label.isdigit():
        return load_sub_file(state, label, col)
    for j in range(state.first_line, state.end_line):
        o = lex(state, j).oword if ("o" in state.lines[j] or "O" in state.lines[j]) else None
        if o is not None and o.keyword is None and o.label == label and j != state.first_line:
            raise state.error(f"Fanuc 'O{label}' subroutine must be called with 'M98 P{label}' "
                              f"(line {j + 1} is its head), not {olabel(label)} call", col)
    where = "" if label.isdigit() else f", or give the folder of {label}.ngc with --sub-path"
    raise state.error(f"{olabel(label)} call: no subroutine {olabel(label)} is "
                      f"defined; define it with {olabel(label)} sub ... "
                      f"{olabel(label)} endsub{where}", col)


def _find_sub(state: GCodeState, label: str, first: int, end: int) -> tuple[int, int] | None:
    """Define ``label``'s sub from its ``sub`` line in ``lines[first:end]``."""
    for j in range(first, end):
        if "o" not in state.lines[j] and "O" not in state.lines[j]:
            continue
        o = lex(state, j).oword
        if o is not None and o.keyword == "sub" and o.label == label:
            end, _ = structure(state, j)
            _define(state, label, j, end, o.col)
            return state.subs[label]
    return None


def load_sub_file(state: GCodeState, label: str, col: int) -> tuple[int, int]:
    """``o<name> call`` of a sub the program does not define: ``name.ngc`` from
    the first folder of the sub path that has it (LinuxCNC's SUBROUTINE_PATH),
    read after the program's lines; it must define ``o<name> sub``."""
    if any(sep in label for sep in ("/", "\\", os.sep)) or label in (".", ".."):
        raise state.error(f"{olabel(label)} call: a subroutine name cannot hold a path; "
                          "put its folder in the sub path instead", col)
    for folder in state.sub_path:
        path = Path(folder) / f"{label}.ngc"
        if path.is_file():
            break
    else:
        raise state.error(f"{olabel(label)} call: no subroutine {olabel(label)} in the program "
                          f"and no {label}.ngc in the sub path ({', '.join(state.sub_path)})",
                          col)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise state.error(f"{olabel(label)} call: cannot read {path}: {exc}", col) from None
    first = len(state.lines)
    state.lines.extend(LINE_SPLIT.split(text))
    state.sub_files.append((first, len(state.lines), str(path)))
    found = _find_sub(state, label, first, len(state.lines))
    if found is None:
        raise state.error(f"{path} does not define {olabel(label)} sub ... {olabel(label)} "
                          "endsub", col)
    # LinuxCNC reads such a file no further than the sub's endsub: a sub written
    # after it is not defined (tests/interp/nested-sub-in-file-error)
    state.sub_files[-1] = (first, found[1] + 1, str(path))
    return found


def _define(state: GCodeState, label: str, line: int, end: int, col: int) -> None:
    known = state.subs.get(label)
    if known is not None and known[0] != line:
        raise state.error(f"subroutine {olabel(label)} is defined twice (lines {known[0] + 1} "
                          f"and {line + 1}): rename one of them", col, line)
    state.subs[label] = (line, end)


def _return(state: GCodeState, pc: int, lx: Lexed) -> int:
    """``endsub [v]`` or ``return [v]``: back to the caller."""
    ow = lx.oword
    kw, label = ow.keyword, ow.label
    args = o_args(state, lx, "write an optional return value in brackets")
    if len(args) > 1:
        raise state.error(f"{olabel(label)} {kw} takes at most one value", ow.col)
    if len(state.frames) == 1:
        raise state.error(f"{olabel(label)} {kw} outside a subroutine: there is no "
                          f"matching {olabel(label)} sub being called", ow.col)
    frame = state.frames[-1]
    if frame.fanuc:
        raise state.error(f"Fanuc 'O{frame.name}' subroutine definition must end with 'M99', "
                          f"not {olabel(label)} {kw}", ow.col)
    if frame.name != label and kw == "endsub":
        raise state.error(f"{olabel(label)} {kw} inside subroutine {olabel(frame.name)}: "
                          "use the label of the subroutine", ow.col)
    # a return under another label (o1010 return inside o1010 if) returns
    # from the running subroutine, as LinuxCNC's execute_return does
    state.frames.pop()
    restore_after_call(state, frame, args[0] if args else None)
    return frame.return_pc


def _if(state: GCodeState, pc: int, lx: Lexed) -> int:
    """Run the first branch whose condition holds (or the ``else``)."""
    label = lx.oword.label
    frame = state.frames[-1]
    end, branches = structure(state, pc)
    if _condition(state, pc) != 0.0:
        frame.ctrl.append(Ctrl("if", label, pc, end))
        return pc + 1
    for b in branches:
        blx = lex(state, b)
        if blx.oword.keyword == "else":
            _no_args(state, blx, b)
            frame.ctrl.append(Ctrl("if", label, pc, end))
            return b + 1
        if _condition(state, b) != 0.0:
            frame.ctrl.append(Ctrl("if", label, pc, end))
            return b + 1
    return end + 1


def _end_of_branch(state: GCodeState, pc: int, lx: Lexed) -> int:
    """``elseif``/``else`` reached from the branch above it (skip to after
    the ``endif``), or ``endif``."""
    ow = lx.oword
    kw, label = ow.keyword, ow.label
    if kw == "endif":
        _no_args(state, lx)
    frame = state.frames[-1]
    top = frame.ctrl[-1] if frame.ctrl else None
    if top is None or top.kind != "if" or top.label != label:
        raise state.error(f"{olabel(label)} {kw} without a matching {olabel(label)} if",
                          ow.col)
    frame.ctrl.pop()
    return top.end + 1 if kw != "endif" else pc + 1


def _do(state: GCodeState, pc: int, lx: Lexed) -> int:
    _no_args(state, lx)
    end, _ = structure(state, pc)
    loop = Ctrl("do", lx.oword.label, pc, end)
    _next_pass(state, loop)
    state.frames[-1].ctrl.append(loop)
    return pc + 1


def _while(state: GCodeState, pc: int, lx: Lexed) -> int:
    """The ``while`` closing a ``do`` (loop back while true), or a ``while`` loop's head."""
    frame = state.frames[-1]
    top = frame.ctrl[-1] if frame.ctrl else None
    if top is not None and top.kind == "do" and top.end == pc:
        if _condition(state, pc) != 0.0:
            _next_pass(state, top)
            return top.start + 1
        frame.ctrl.pop()
        return pc + 1
    end, _ = structure(state, pc)
    if _condition(state, pc) != 0.0:
        loop = Ctrl("while", lx.oword.label, pc, end)
        _next_pass(state, loop)
        frame.ctrl.append(loop)
        return pc + 1
    return end + 1


def _endwhile(state: GCodeState, pc: int, lx: Lexed) -> int:
    ow = lx.oword
    _no_args(state, lx)
    frame = state.frames[-1]
    top = frame.ctrl[-1] if frame.ctrl else None
    if top is None or top.kind != "while" or top.end != pc:
        raise state.error(f"{olabel(ow.label)} endwhile without a matching "
                          f"{olabel(ow.label)} while", ow.col)
    frame.ctrl.pop()
    return top.start  # the while line tests the condition and counts the pass


def _repeat(state: GCodeState, pc: int, lx: Lexed) -> int:
    end, _ = structure(state, pc)
    count = _condition(state, pc)
    if abs(count) < _REPEAT_LIMIT:
        times = int(round(count))
    else:
        times = _REPEAT_LIMIT if count > 0 else 0
    if times <= 0:
        return end + 1
    loop = Ctrl("repeat", lx.oword.label, pc, end, times - 1)
    _next_pass(state, loop)
    state.frames[-1].ctrl.append(loop)
    return pc + 1


def _endrepeat(state: GCodeState, pc: int, lx: Lexed) -> int:
    ow = lx.oword
    _no_args(state, lx)
    frame = state.frames[-1]
    top = frame.ctrl[-1] if frame.ctrl else None
    if top is None or top.kind != "repeat" or top.end != pc:
        raise state.error(f"{olabel(ow.label)} endrepeat without a matching "
                          f"{olabel(ow.label)} repeat", ow.col)
    if top.remaining > 0:
        _next_pass(state, top)
        top.remaining -= 1
        return top.start + 1
    frame.ctrl.pop()
    return pc + 1


def _break_or_continue(state: GCodeState, pc: int, lx: Lexed) -> int:
    """Leave the innermost loop of this label, or go to its next pass
    (``do``: test the ``while``; ``repeat``: count down; ``while``: re-test)."""
    ow = lx.oword
    kw, label = ow.keyword, ow.label
    _no_args(state, lx)
    ctrl = state.frames[-1].ctrl
    k = len(ctrl) - 1
    while k >= 0 and not (ctrl[k].kind in _LOOPS and ctrl[k].label == label):
        k -= 1
    if k < 0:
        raise state.error(f"{olabel(label)} {kw} outside a loop labelled {olabel(label)}: "
                          f"use the label of the enclosing do, while or repeat", ow.col)
    loop = ctrl[k]
    del ctrl[k + 1:]
    if kw == "break":
        ctrl.pop()
        return loop.end + 1
    if loop.kind == "while":
        ctrl.pop()
        return loop.start
    return loop.end  # do: test the while condition; repeat: count down


def innermost_loop(state: GCodeState) -> Ctrl | None:
    """The innermost loop open in any frame (a subroutine's, else its caller's), or None."""
    for frame in reversed(state.frames):
        for c in reversed(frame.ctrl):
            if c.kind in _LOOPS:
                return c
    return None


def count_line(state: GCodeState, pc: int) -> None:
    """Line ``pc`` is about to execute: the runaway guards (every executed line
    against ``max_executed_lines``, a line inside a loop against the loops'
    line budget), for the reader's line loop and the lathe cycles' contour."""
    state.line_no = pc
    state.executed += 1
    if state.executed > state.max_executed_lines:
        raise state.error(f"more than {state.max_executed_lines} lines executed: endless "
                          "loop or runaway recursion? check the loop conditions")
    if state.in_loop:
        state.loop_lines += 1
        if state.loop_lines > state.max_loop_lines:
            raise loop_lines_error(state)


def loop_lines_error(state: GCodeState):
    """The error when the loops executed more than their line budget,
    located at the innermost open loop's first line."""
    loop = innermost_loop(state)
    col = lex(state, loop.start).oword.col
    return state.error(f"{olabel(loop.label)} {loop.kind}: loops executed more than "
                       f"{state.max_loop_lines} lines (all loops of the program together, "
                       f"{LOOP_LINES_PER_ITERATION} per allowed loop iteration): endless loop? check its condition, or raise "
                       "the limit (--max-loop-iterations N)", col, loop.start)


def _next_pass(state: GCodeState, loop: Ctrl) -> None:
    """``loop`` starts a pass of its body: count it against the program's
    iteration limit, which stops a runaway loop located at its opener."""
    state.loop_iterations += 1
    if state.loop_iterations > state.max_loop_iterations:
        col = lex(state, loop.start).oword.col
        raise state.error(f"{olabel(loop.label)} {loop.kind}: more than "
                          f"{state.max_loop_iterations} loop iterations (all loops of the "
                          "program together): endless loop? check its condition, or raise "
                          "the limit (--max-loop-iterations N)", col, loop.start)


_HANDLERS = {
    "sub": _sub, "call": _call, "endsub": _return, "return": _return,
    "if": _if, "elseif": _end_of_branch, "else": _end_of_branch, "endif": _end_of_branch,
    "do": _do, "while": _while, "endwhile": _endwhile,
    "repeat": _repeat, "endrepeat": _endrepeat,
    "break": _break_or_continue, "continue": _break_or_continue,
}
