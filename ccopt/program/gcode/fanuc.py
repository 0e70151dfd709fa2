"""Fanuc-style subprograms, as LinuxCNC reads them (``read_o`` in
``interp_read.cc``, ``execute_call``/``execute_return`` in
``interp_o_word.cc``).

- A subprogram starts at a bare O-word line, ``O<number>`` (or
  ``O<name>``), and ends at its ``M99``; it is defined anywhere in the
  program, before or after the main program. ``O0002`` and ``O2`` are the
  same number: the first definition is called.
- ``M98 P<number> [L<count>]`` as the first word of its line (after ``N``)
  calls it ``L`` times (once without ``L``; ``L0`` not at all). ``P`` may be
  a parameter or an expression. Parameters are not local: the subprogram
  reads and sets the caller's ``#1``-``#30`` (unlike ``o.. call``).
- ``M99`` as the first word of a line in a subprogram returns to the line
  after the ``M98`` (or runs the next repeat); ``#<_value>`` and
  ``#<_value_returned>`` become 0. ``M99`` in the main program ends it:
  LinuxCNC's stand-alone interpreter stops there and its task would run the
  program again from the start for ever (an endless program); ccopt reads
  one pass, as the stand-alone interpreter does, and records where in
  ``Program.meta[ENDLESS_MAIN]`` (:mod:`ccopt.program.model`).
- Mixing styles is refused as LinuxCNC refuses it: ``M98`` of an
  ``O.. sub``, ``endsub``/``return`` in a Fanuc subprogram, ``M99`` in an
  ``O.. sub``.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.codes import read_words
from ccopt.program.gcode.state import Frame, GCodeState
from ccopt.program.gcode.words import FANUC_CALL, Lexed, fmt, lex, skip_blanks

_INTEGER_TOL = 1e-4   # LinuxCNC's read_o: P within 0.0001 of an integer


def runs_as_fanuc(state: GCodeState, lx: Lexed) -> bool:
    """Line ``lx`` is an ``M98`` call or a subprogram's ``M99`` return."""
    return lx.fanuc == 98 or (lx.fanuc == 99 and len(state.frames) > 1)


def exec_fanuc(state: GCodeState, pc: int, lx: Lexed) -> int:
    """Execute the ``M98``/``M99`` line ``pc``; the next line to execute."""
    return _m98(state, pc, lx) if lx.fanuc == 98 else _m99(state, pc, lx)


def check_fanuc_style(state: GCodeState, m: int, col: int) -> None:
    """``M98`` and a subprogram's ``M99`` are refused when the machine's INI says
    ``[RS274NGC] DISABLE_FANUC_STYLE_SUB`` (LinuxCNC's read_o_word message; the
    main program's ``M99`` is read_m's, which does not check)."""
    if state.ini is not None and state.ini.fanuc_subs_disabled:
        raise state.error(f"DISABLE_FANUC_STYLE_SUB set in INI file, but found m{m}", col)


def _m98(state: GCodeState, pc: int, lx: Lexed) -> int:
    col = lx.start
    check_fanuc_style(state, 98, col)
    words, settings = read_words(state, lx)
    others = [c for _, c in words.g] + [c for v, c in words.m[1:]] + \
        [c for k, (_, c) in words.letters.items() if k not in "PL"]
    if others or settings:
        raise state.error("M98 takes only P (the subprogram) and L (the repeats) on its "
                          "line: put other words on a line of their own",
                          min(others) if others else col)
    if "P" not in words.letters:
        raise state.error("Found 'm98' code with no P-word: M98 P<subprogram number>", col)
    p, pcol = words.letters["P"]
    n = math.floor(p)
    if p - n > 1.0 - _INTEGER_TOL:
        n += 1
    elif p - n > _INTEGER_TOL or n < 0:
        raise state.error(f"M98 P{fmt(p)}: P must be a whole number >= 0", pcol)
    label = str(int(n))
    times = 1
    if "L" in words.letters:
        times = int(math.floor(words.letters["L"][0] + 0.5))
        if times == 0:
            return pc + 1          # M98 L0: no call (LinuxCNC execute_call)
    start = _subprogram(state, label, pcol)
    if len(state.frames) > state.max_call_depth:
        raise state.error(f"subroutine calls nested deeper than {state.max_call_depth}: "
                          "runaway recursion? check the subprograms' M98 calls", col)
    _count_pass(state, pc, col)
    state.frames.append(Frame(name=label, return_pc=pc + 1, call_line=pc, fanuc=True,
                              repeats=max(times, 1) - 1, start=start))
    return start + 1


def _subprogram(state: GCodeState, label: str, col: int) -> int:
    """The line of subprogram ``O<label>``'s head (the first in the program)."""
    known = state.fanuc_subs.get(label)
    if known is not None:
        return known
    for j in range(state.first_line, state.end_line):
        line = state.lines[j]
        if "o" not in line and "O" not in line:
            continue
        o = lex(state, j).oword
        if o is None or o.label != label or o.keyword not in (None, "sub"):
            continue
        if o.keyword == "sub":
            raise state.error(f"'O{label} sub' subroutine must be called with 'O{label} "
                              f"call', not M98 (LinuxCNC refuses mixing the styles)", col)
        state.fanuc_subs[label] = j
        return j
    raise state.error(f"M98 P{label}: no subprogram O{label} in the program (define it "
                      f"with a line O{label}, its body and M99)", col)


def _m99(state: GCodeState, pc: int, lx: Lexed) -> int:
    check_fanuc_style(state, 99, lx.start)
    code = lx.code
    end = skip_blanks(code, FANUC_CALL.match(code, lx.start).end())
    if end < len(code):
        raise state.error("Unexpected character after M99: it returns from the subprogram "
                          "and takes no word", end)
    frame = state.frames[-1]
    if not frame.fanuc:
        raise state.error(f"'O{frame.name} endsub' or 'O{frame.name} return' must follow "
                          f"'O{frame.name} sub' subroutine definition, not M99", lx.start)
    state.globals["_value"] = 0.0
    state.globals["_value_returned"] = 0.0
    if frame.repeats > 0:
        _count_pass(state, frame.call_line, None)
        frame.repeats -= 1
        frame.ctrl.clear()
        frame.named.clear()
        return frame.start + 1
    state.frames.pop()
    return frame.return_pc


def _count_pass(state: GCodeState, call_line: int, col: int | None) -> None:
    """A pass of a subprogram counts against the program's loop iterations."""
    state.loop_iterations += 1
    if state.loop_iterations > state.max_loop_iterations:
        raise state.error(f"M98: more than {state.max_loop_iterations} loop iterations (all "
                          "loops and subprogram repeats of the program together): raise the "
                          "limit (--max-loop-iterations N)", col, call_line)
