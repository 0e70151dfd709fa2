"""Parameters and word values (LinuxCNC ``interp_read.cc`` values,
``interp_namedparams.cc``).

Numbered parameters ``#1``..``#5601`` read 0 when unset; ``#1``..``#30`` are
local to a subroutine call (its arguments, then 0). Named parameters
``#<name>`` are local to the sub (or main program) that sets them, unless the
name starts with ``_`` (global); reading an unset one is an error. A word's
value is a literal number, a parameter, a bracketed expression or a unary
function; expressions are evaluated by :mod:`ccopt.program.expr` with the
G-code grammar, whose variables are the parameters read here.
"""
from __future__ import annotations

import math
import re

from ccopt.program.expr import (
    GCODE_BINARY,
    GCODE_FUNCTIONS,
    ExprError,
    Grammar,
    parse_bracketed,
    parse_operand,
)
from ccopt.program.gcode.axes import extra_work
from ccopt.program.gcode.coordinates import to_work
from ccopt.program.gcode.state import MAX_PARAMETER, Frame, GCodeState
from ccopt.program.gcode.units import input_factor
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, read_number, skip_blanks

#: Positional parameters #1..#30 local to a call.
SUB_PARAMS = 30

_FUNC_NAMES = sorted(set(GCODE_FUNCTIONS) | {"ATAN", "EXISTS"}, key=len, reverse=True)


def attach_grammar(state: GCodeState) -> None:
    """Give the state its expression grammar: brackets ``[ ]``, the G-code
    operators and functions (degrees), ``ATAN[a]/[b]``, and ``#`` parameters
    as variables."""
    def variable(text: str, pos: int):
        if text[pos] == "#":
            return read_parameter(state, text, pos)
        if text[pos] in "eE" and text[pos:pos + 6].upper() == "EXISTS":
            return read_exists(state, text, pos)
        return None

    state.grammar = Grammar("[", "]", GCODE_BINARY, GCODE_FUNCTIONS, atan2_form=True,
                            variable=variable)


#: LinuxCNC's read-only parameters of the current position (X Y Z A B C U V W):
#: ``#5021``-``#5029`` and ``#<_abs_x>``... in machine coordinates (where
#: ``G53`` puts the tool), ``#5420``-``#5428`` and ``#<_x>``... in the work
#: coordinates in force (origin, ``G92``/``G52`` offset and rotation applied),
#: program units (A B C in degrees).
_AXIS_LETTERS = "xyzabcuvw"
MACHINE_POSITION = {5021 + k: k for k in range(9)}
WORK_POSITION = {5420 + k: k for k in range(9)}
_POSITION_NAMES = {**{f"_abs_{a}": (True, k) for k, a in enumerate(_AXIS_LETTERS)},
                   **{f"_{a}": (False, k) for k, a in enumerate(_AXIS_LETTERS)}}
#: ``#<_line>``: the line number of the block being executed, in its file.
LINE_NUMBER = "_line"


def read_parameter(state: GCodeState, code: str, pos: int) -> tuple[float, int]:
    """Value of the parameter reference at ``code[pos] == '#'`` and the
    position after it."""
    kind, key, end = parameter_target(state, code, pos)
    if kind == "name":
        if key == LINE_NUMBER:
            value = float(state.where(state.line_no)[1])
        elif key in _POSITION_NAMES:
            value = _position(state, *_POSITION_NAMES[key])
        else:
            value = _get_named(state, key, pos)
    elif key in MACHINE_POSITION:
        value = _position(state, True, MACHINE_POSITION[key])
    elif key in WORK_POSITION:
        value = _position(state, False, WORK_POSITION[key])
    else:
        value = state.params.get(key, 0.0)
    return value, end


def _position(state: GCodeState, machine: bool, axis: int) -> float:
    """The current position's ``axis`` (0 .. 8: X Y Z A B C U V W), machine or
    work coordinates, in the program's units in force (G20/G21; A B C in
    degrees), as LinuxCNC gives it."""
    if axis < 3:
        value = state.pos[axis] if machine else to_work(state, state.pos)[axis]
    else:
        value = (state.extra or [0.0] * 6)[axis - 3] if machine else extra_work(state)[axis - 3]
        if axis < 6:
            return float(value)                 # A B C: degrees, not lengths
    return float(value) / input_factor(state)


def read_exists(state: GCodeState, code: str, pos: int) -> tuple[float, int]:
    """``EXISTS[#<name>]``: 1 when the named parameter is set where it is read
    (the running sub's own or a global one), else 0; ``EXISTS[#n]``: 1 when
    ``n`` is a parameter number (1 .. 5601), as LinuxCNC's ``read_parameter``
    with ``check_exists``. The value after the closing bracket."""
    p = skip_blanks(code, pos + 6)
    if p >= len(code) or code[p] != "[":
        raise ExprError("EXISTS needs a parameter in brackets, e.g. EXISTS[#<depth>]", pos)
    q = skip_blanks(code, p + 1)
    if q >= len(code) or code[q] != "#":
        raise ExprError("Expected # reading parameter: EXISTS takes one parameter, e.g. "
                        "EXISTS[#<depth>]", q)
    r = skip_blanks(code, q + 1)
    if r < len(code) and code[r] == "<":
        _, name, end = parameter_target(state, code, q)
        local = name in state.frames[-1].named if not name.startswith("_") else False
        value = 1.0 if local or (name.startswith("_") and name in state.globals) else 0.0
    else:
        number, end = _parameter_number(state, code, r, q)
        value = 1.0 if math.isfinite(number) and 1 <= round(number) <= MAX_PARAMETER else 0.0
    end = skip_blanks(code, end)
    if end >= len(code) or code[end] != "]":
        raise ExprError("Expected ] reading bracketed parameter", end)
    return value, end + 1


def _parameter_number(state: GCodeState, code: str, p: int, pos: int) -> tuple[float, int]:
    """The number after a ``#`` (literal, ``[expr]``, ``#n`` or a function
    such as ``ATAN[1]/[1]``) and the position after it."""
    n = len(code)
    ch = code[p] if p < n else ""
    if ch.isdigit() or ch == ".":
        return read_number(state, code, p, "#")
    if ch == "[":
        return parse_bracketed(code, p, state.grammar)
    if ch == "#":
        return read_parameter(state, code, p)
    if ch.isalpha() and any(code[p:p + 6].upper().startswith(f) for f in _FUNC_NAMES):
        return parse_operand(code, p, state.grammar)
    raise ExprError("'#' needs a parameter number or <name>, e.g. #1 or #<depth>", pos)


def parameter_target(state: GCodeState, code: str, pos: int) -> tuple[str, object, int]:
    """Parse ``#n``, ``#[expr]``, ``##n`` or ``#<name>`` at ``pos``.

    Returns ``("name", lower-case name, end)`` or ``("index", n, end)``.
    """
    p = skip_blanks(code, pos + 1)
    n = len(code)
    if p >= n:
        raise ExprError("'#' needs a parameter number or <name>, e.g. #1 or #<depth>", pos)
    ch = code[p]
    if ch == "<":
        end = code.find(">", p)
        if end < 0:
            raise ExprError("parameter name has no closing '>'", p)
        name = "".join(code[p + 1:end].split()).lower()
        if not name:
            raise ExprError("empty parameter name '#<>'", p)
        return "name", name, end + 1
    value, end = _parameter_number(state, code, p, pos)
    if not math.isfinite(value) or abs(value - round(value)) > WHOLE_NUMBER_TOL:
        raise ExprError(f"parameter number {fmt(value)} is not an integer", pos)
    index = int(round(value))
    if not 1 <= index <= MAX_PARAMETER:
        raise ExprError(f"parameter number #{index} out of range: use #1 to #{MAX_PARAMETER}",
                        pos)
    return "index", index, end


#: ``#<_ini[SECTION]NAME>`` (the name as the reader keeps it, lower case).
_INI_NAME = re.compile(r"_ini\[([^\]]*)\](.+)")


def is_position_name(name: str) -> bool:
    """Whether the (lower-case) parameter name is a position's (``_x``,
    ``_abs_x``, ...) or ``_line``: read-only."""
    return name in _POSITION_NAMES or name == LINE_NUMBER


def is_ini_name(name: str) -> bool:
    """Whether the (lower-case) parameter name is ``_ini[SECTION]NAME``: read-only."""
    return _INI_NAME.fullmatch(name) is not None


def _get_named(state: GCodeState, name: str, col: int) -> float:
    m = _INI_NAME.fullmatch(name)
    if m is not None:
        return _ini_value(state, m.group(1), m.group(2), name, col)
    if not name.startswith("_"):
        local = state.frames[-1].named
        if name in local:
            return local[name]
    elif name in state.globals:
        return state.globals[name]
    raise ExprError(f"named parameter #<{name}> is not set: assign it first "
                    f"(#<{name}> = ...)", col)


def _ini_value(state: GCodeState, section: str, key: str, name: str, col: int) -> float:
    """``#<_ini[section]key>``: the machine INI file's entry (``--ini``)."""
    ini = state.ini
    if ini is None:
        raise ExprError(f"named parameter #<{name}> not defined: it reads the machine's INI "
                        "file, and none was given (--ini FILE)", col)
    try:
        value = ini.number(section, key)
    except ValueError as exc:
        raise ExprError(f"#<{name}>: {exc}", col) from None
    if value is None:
        why = (f"no [{section.upper()}] {key.upper()} in {ini.file}" if ini.ini_vars
               else f"{ini.file} says [RS274NGC] INI_VARS = 0")
        raise ExprError(f"named parameter #<{name}> not defined: {why}", col)
    return value


#: A parameter in a message comment: ``#<name>`` or ``#n``.
_MESSAGE_PARAMETER = re.compile(r"#<[^>]*>|#\d+")


#: LinuxCNC's TOLERANCE_EQUAL: a message shows a value this close to 0 as 0.
_ZERO_IN_MESSAGES = 0.0001


def message_text(state: GCodeState, text: str) -> str:
    """A message comment's text (``(debug, ...)``, ``(print, ...)``,
    ``(abort, ...)``) as LinuxCNC's ``convert_param_comment`` expands it: each
    ``#<name>`` and ``#n`` replaced by its value (``%f``, six decimals; a value
    within 1e-4 of 0 as 0), ``######`` where it has none; ``%d``, ``%f`` and
    ``%.Nf`` set the format of the values that follow (none, 4 and N
    decimals) and are not shown."""
    out: list[str] = []
    decimals = 6
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "%":
            nxt = text[i + 1:i + 2]
            if nxt in ("d", "f"):
                decimals, i = (0 if nxt == "d" else 4), i + 2
            elif nxt == "." and text[i + 2:i + 3].isdigit() and text[i + 3:i + 4] == "f":
                decimals, i = int(text[i + 2]), i + 4
            elif nxt == ".":
                out.append(".")                 # LinuxCNC drops the % here
                i += 2
            else:
                out.append("%")
                i += 1
            continue
        m = _MESSAGE_PARAMETER.match(text, i) if c == "#" else None
        if m is None:
            out.append(c)
            i += 1
            continue
        try:
            value = read_parameter(state, m.group(), 0)[0]
            out.append(f"{0.0 if abs(value) < _ZERO_IN_MESSAGES else value:.{decimals}f}")
        except ExprError:
            out.append("######")
        i = m.end()
    return "".join(out)


def set_parameter(state: GCodeState, kind: str, key, value: float) -> None:
    """Set the parameter :func:`parameter_target` parsed (a named one in
    the running frame unless global)."""
    if kind == "name":
        if key.startswith("_"):
            state.globals[key] = value
        else:
            state.frames[-1].named[key] = value
    else:
        state.params[key] = value


def read_value(state: GCodeState, code: str, p: int, letter: str,
               letter_col: int) -> tuple[float, int]:
    """A word value at ``p`` (number, parameter, [expression] or unary
    function, after any signs) and the position after it."""
    n = len(code)
    negate = False
    p = skip_blanks(code, p)
    while p < n and code[p] in "+-":
        q = skip_blanks(code, p + 1)
        if q < n and (code[q].isdigit() or code[q] == "."):
            break
        if code[p] == "-":
            negate = not negate
        p = q
    if p >= n:
        raise ExprError(f"{letter} word has no value: write a number after {letter}",
                        letter_col)
    ch = code[p]
    if ch.isdigit() or ch in ".+-":
        value, end = read_number(state, code, p, letter)
    elif ch == "[" or ch == "#":
        value, end = parse_operand(code, p, state.grammar)
    elif ch.isalpha() and any(code[p:p + 6].upper().startswith(f) for f in _FUNC_NAMES):
        value, end = parse_operand(code, p, state.grammar)
    else:
        raise ExprError(f"{letter} word has no value (found {ch!r}): write a number, "
                        "#parameter or [expression] after it", letter_col)
    if not math.isfinite(value):
        raise ExprError(f"value of {letter} is not a finite number", p)
    return (-value if negate else value), end


def bind_call_arguments(state: GCodeState, args: list[float]) -> dict[int, float]:
    """Make ``args`` the call's ``#1``.. (the rest of ``#1..#30`` unset, so
    0) and reset ``#<_value>``/``#<_value_returned>``; returns the caller's
    ``#1..#30`` to restore on return."""
    saved = {k: state.params[k] for k in range(1, SUB_PARAMS + 1) if k in state.params}
    for k in range(1, SUB_PARAMS + 1):
        state.params.pop(k, None)
    for k, v in enumerate(args, start=1):
        state.params[k] = v
    state.globals["_value"] = 0.0
    state.globals["_value_returned"] = 0.0
    return saved


def restore_after_call(state: GCodeState, frame: Frame, value: float | None) -> None:
    """Give the caller back its ``#1..#30``; a returned ``value`` sets
    ``#<_value>`` and ``#<_value_returned>`` = 1."""
    for k in range(1, SUB_PARAMS + 1):
        state.params.pop(k, None)
    state.params.update(frame.saved)
    if value is not None:
        state.globals["_value"] = value
        state.globals["_value_returned"] = 1.0
