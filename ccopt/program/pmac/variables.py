"""PMAC variables and the values of statements: ``{data}`` and expressions.

``P{n}`` and ``Q{n}`` are program variables (unset ones read 0), ``I{n}``
and ``M{n}`` live in the controller (reading one the file never set is an
error). Expressions are PMAC's ``( ... )`` grammar of
:mod:`ccopt.program.expr` plus the bit-by-bit operators, ``$`` hexadecimal
constants, ``P(expr)``/``Q(expr)`` indirect references and trigonometry in
degrees, or radians after ``I15=1``. The rules are in ``docs/pmac.md``
("Data and expressions", "Variables").
"""
from __future__ import annotations

import math
import re
from typing import Callable, NamedTuple

from ccopt.errors import ProgramError
from ccopt.program.expr import (ExprError, Grammar, PMAC_BINARY, PMAC_FUNCTIONS,
                                parse_bracketed, parse_expression)
from ccopt.program.pmac.lexer import (ASSIGN_RE, HEX_RE, INDIRECT_RE, NUMBER_RE, VAR_RE,
                                      hex_value, skip)

#: Highest P/Q/I/M variable number of a Turbo PMAC.
MAX_VARIABLE = 8191
#: Bits after the binary point used for the bit-by-bit operators.
_FRACTION_BITS = 48
#: |cos| below this makes TAN infinite (cos of 90 degrees in floating point is ~6e-17, not 0).
_TAN_COS_EPS = 1e-15
#: An indirect variable number P(expr) this close to an integer is it (P(10/3*3) rounds).
_INTEGER_EPS = 1e-9
#: ``I15``: 1 = trigonometry in radians, 0 = degrees.
I_RADIANS = 15


class Assigned(NamedTuple):
    """What an assignment statement set: variable kind and number, and the
    position after the statement."""

    kind: str
    number: int
    end: int


def _check_finite(value: float, pos: int) -> float:
    if not math.isfinite(value):
        raise ExprError("value is not a finite number (too large?)", pos)
    return value


def _bitwise(a: float, b: float, op: Callable[[int, int], int]) -> float:
    """PMAC bit-by-bit operators on fixed-point values (fractional bits too)."""
    scale = 1 << _FRACTION_BITS
    try:
        ia, ib = round(a * scale), round(b * scale)
    except OverflowError:
        raise ValueError("operand of a bit-by-bit operator too large") from None
    return op(ia, ib) / scale


def _variable_number(digits: str, kind: str, pos: int) -> int:
    number = int(digits)
    if number > MAX_VARIABLE:
        raise ExprError(f"{kind}{digits}: variable numbers go from 0 to {MAX_VARIABLE}", pos)
    return number


class Variables:
    """The P, Q, I and M variables of one read, and the expressions reading them.

    ``meta`` is the program's ``meta`` dict: I- and M-variable assignments are
    recorded in ``meta["i_variables"]`` / ``meta["m_variables"]``, M-variable
    definitions in ``meta["ignored"]``.
    """

    def __init__(self, file: str, meta: dict):
        self.file = file
        self.meta = meta
        self.p: dict[int, float] = {}
        self.q: dict[int, float] = {}
        self.i: dict[int, float] = {}
        self.i_line: dict[int, int] = {}      # line of the last assignment of each I-variable
        self.m: dict[int, float] = {}
        self.radians = False
        self.grammar = self._grammar()

    def error(self, message: str, line: int | None, col: int | None = None) -> ProgramError:
        return ProgramError(message, self.file, line, col)

    # -- grammar ------------------------------------------------------------
    def _grammar(self) -> Grammar:
        """PMAC's expression grammar; trigonometry follows ``I15`` when evaluated."""
        def to_rad(x: float) -> float:
            return x if self.radians else math.radians(x)

        def from_rad(x: float) -> float:
            return x if self.radians else math.degrees(x)

        def asin(x: float) -> float:
            if not -1.0 <= x <= 1.0:
                raise ValueError(f"ASIN argument {x:g} outside [-1, 1]")
            return from_rad(math.asin(x))

        def acos(x: float) -> float:
            if not -1.0 <= x <= 1.0:
                raise ValueError(f"ACOS argument {x:g} outside [-1, 1]")
            return from_rad(math.acos(x))

        def tan(x: float) -> float:
            c = math.cos(to_rad(x))
            if abs(c) < _TAN_COS_EPS:
                raise ValueError(f"TAN of {x:g} is infinite")
            return math.sin(to_rad(x)) / c

        functions = dict(PMAC_FUNCTIONS)
        functions.update({
            "SIN": lambda x: math.sin(to_rad(x)),
            "COS": lambda x: math.cos(to_rad(x)),
            "TAN": tan,
            "ASIN": asin,
            "ACOS": acos,
            "ATAN": lambda x: from_rad(math.atan(x)),
            # Turbo PMAC: the cosine argument of ATAN2 is Q0.
            "ATAN2": lambda x: from_rad(math.atan2(x, self.q.get(0, 0.0))),
        })
        binary = dict(PMAC_BINARY)
        binary.update({
            "&": (3, lambda a, b: _bitwise(a, b, lambda x, y: x & y)),
            "|": (2, lambda a, b: _bitwise(a, b, lambda x, y: x | y)),
            "^": (2, lambda a, b: _bitwise(a, b, lambda x, y: x ^ y)),
        })
        return Grammar("(", ")", binary, functions, variable=self._variable)

    def _variable(self, text: str, pos: int) -> tuple[float, int] | None:
        """Read ``P12``, ``Q(P1+1)``, ``I15``, ``M7`` or a ``$hex`` constant."""
        m = HEX_RE.match(text, pos)
        if m:
            return hex_value(m.group(1), pos), m.end()
        m = INDIRECT_RE.match(text, pos)
        if m:
            number, end = self._indirect_number(text, pos, m)
            table = self.p if m.group(1) == "P" else self.q
            return table.get(number, 0.0), end
        m = VAR_RE.match(text, pos)
        if not m:
            return None
        kind, number = m.group(1), _variable_number(m.group(2), m.group(1), pos)
        if kind == "P":
            return self.p.get(number, 0.0), m.end()
        if kind == "Q":
            return self.q.get(number, 0.0), m.end()
        table = self.i if kind == "I" else self.m
        if number not in table:
            raise ExprError(f"{kind}{number} is read but never set in the file: its value lives "
                            "in the controller, which ccopt cannot see", pos)
        return table[number], m.end()

    def _indirect_number(self, text: str, pos: int, m: re.Match) -> tuple[int, int]:
        """Number of the variable ``P(expr)``/``Q(expr)`` whose ``P(`` is ``m``."""
        value, end = parse_bracketed(text, m.end() - 1, self.grammar)
        value = _check_finite(value, pos)
        if abs(value - round(value)) > _INTEGER_EPS or not 0 <= round(value) <= MAX_VARIABLE:
            raise ExprError(f"{m.group(1)}({value:g}): the variable number must be an integer "
                            f"0..{MAX_VARIABLE}", pos)
        return int(round(value)), end

    # -- values -------------------------------------------------------------
    def expression(self, line: int, text: str, pos: int, *, bare: bool) -> tuple[float, int]:
        """Evaluate an expression at ``pos``; ``bare`` allows no outer parentheses."""
        try:
            if bare:
                # The shared evaluator only exposes bracketed expressions; an
                # assignment's right-hand side may be unbracketed.
                value, end = parse_expression(text, pos, self.grammar)
            else:
                value, end = parse_bracketed(text, pos, self.grammar)
            return _check_finite(value, pos), end
        except ExprError as exc:
            raise self.error(exc.message, line, exc.col + 1) from None
        except RecursionError:
            raise self.error("expression nested too deeply", line, pos + 1) from None

    def data(self, line: int, text: str, pos: int, what: str) -> tuple[float, int]:
        """``{data}``: a constant (optionally signed, ``$hex`` too) or ``(expression)``."""
        p = skip(text, pos)
        sign = 1.0
        if p < len(text) and text[p] in "+-":
            sign = -1.0 if text[p] == "-" else 1.0
            p = skip(text, p + 1)
        if p < len(text) and text[p] == "(":
            value, end = self.expression(line, text, p, bare=False)
            return sign * value, end
        m = NUMBER_RE.match(text, p) or HEX_RE.match(text, p)
        if not m:
            found = "end of line" if p >= len(text) else repr(text[p])
            raise self.error(f"{what} needs a value (a number or a (expression)), found {found}",
                             line, min(p, len(text)) + 1)
        try:
            value = float(m.group(1)) if m.re is NUMBER_RE else hex_value(m.group(1), p)
        except ExprError as exc:
            raise self.error(exc.message, line, p + 1) from None
        if not math.isfinite(value):
            raise self.error(f"{what}: number too large", line, p + 1)
        return sign * value, m.end()

    # -- assignments ----------------------------------------------------------
    def assignment(self, line: int, text: str, pos: int) -> Assigned | None:
        """Execute ``P1=...``/``Q(P2)=...``/``I15=...``/``M1==...`` at ``pos``;
        ``None`` when no assignment starts there."""
        m = ASSIGN_RE.match(text, pos)
        if m:
            return self._direct(line, text, pos, m)
        m = INDIRECT_RE.match(text, pos)
        if m:
            return self._indirect(line, text, pos, m)
        return None

    def _direct(self, line: int, text: str, pos: int, m: re.Match) -> Assigned:
        """``P1=``, ``I15=``, ``M1==`` (synchronous) or ``M1->`` (a definition, ignored)."""
        kind, op = m.group(1), m.group(3)
        try:
            number = _variable_number(m.group(2), kind, pos)
        except ExprError as exc:
            raise self.error(exc.message, line, pos + 1) from None
        if op == "->":
            if kind != "M":
                raise self.error(f"{kind}{number}->: only M-variables take a definition",
                                 line, pos + 1)
            self.meta["ignored"].append({"line": line, "text": text[pos:].strip(),
                                         "why": "M-variable definition"})
            return Assigned(kind, number, len(text))
        if op == "==" and kind != "M":
            raise self.error(f"'==' (synchronous assignment) is for M-variables, not "
                             f"{kind}{number}", line, m.start(3) + 1)
        value, end = self.expression(line, text, m.end(), bare=True)
        self.store(kind, number, value, line)
        return Assigned(kind, number, end)

    def _indirect(self, line: int, text: str, pos: int, m: re.Match) -> Assigned:
        """``P(expr)=`` / ``Q(expr)=``."""
        try:
            number, end = self._indirect_number(text, pos, m)
        except ExprError as exc:
            raise self.error(exc.message, line, exc.col + 1) from None
        except RecursionError:
            raise self.error("expression nested too deeply", line, pos + 1) from None
        eq = skip(text, end)
        if eq >= len(text) or text[eq] != "=" or text.startswith("==", eq):
            raise self.error(f"{m.group(1)}(...) must be followed by '=' and a value",
                             line, eq + 1)
        value, end = self.expression(line, text, eq + 1, bare=True)
        self.store(m.group(1), number, value, line)
        return Assigned(m.group(1), number, end)

    def store(self, kind: str, number: int, value: float, line: int) -> None:
        """Set variable ``kind``/``number`` to ``value`` (assigned on ``line``)."""
        if kind == "P":
            self.p[number] = value
        elif kind == "Q":
            self.q[number] = value
        elif kind == "M":
            self.m[number] = value
            self.meta["m_variables"][number] = value
        else:
            self.i[number] = value
            self.i_line[number] = line
            self.meta["i_variables"][number] = value
            if number == I_RADIANS:
                self.radians = value != 0
