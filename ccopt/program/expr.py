"""Arithmetic expressions of part programs, shared by the G-code and PMAC readers.

Both dialects write expressions inside brackets — G-code ``[ ... ]``, PMAC
``( ... )`` — with numbers, variables, unary functions and infix operators.
They differ in bracket characters, operator words, function names and how a
variable is written, so a :class:`Grammar` describes a dialect and
:func:`parse_bracketed` evaluates one bracketed expression from a position in
a line, returning the value and the position after the closing bracket.

Trigonometric functions work in **degrees** in both dialects (RS274/NGC and
PMAC with its default I15=0); results of ``ASIN``/``ACOS``/``ATAN`` are degrees.
Every problem raises :class:`ExprError` with the 0-based column, which the
readers turn into a located :class:`~ccopt.errors.ProgramError`.
"""
from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from typing import Callable


class ExprError(Exception):
    """An expression problem at 0-based column ``col`` of the line."""

    def __init__(self, message: str, col: int):
        super().__init__(message)
        self.message = message
        self.col = col


def _finite(x: float, what: str) -> float:
    if not math.isfinite(x):
        raise ValueError(f"{what} is not a finite number")
    return x


def _div(a: float, b: float) -> float:
    if b == 0:
        raise ZeroDivisionError("division by zero")
    return a / b


def _mod(a: float, b: float) -> float:
    if b == 0:
        raise ZeroDivisionError("MOD by zero")
    # RS274/NGC: the result has the sign of the divisor (like Python's %).
    return a % b


def _pow(a: float, b: float) -> float:
    if a < 0 and b != int(b):
        raise ValueError(f"{a:g} ** {b:g} has no real value")
    if a == 0 and b < 0:
        raise ZeroDivisionError("zero raised to a negative power")
    try:
        return float(a) ** float(b)
    except OverflowError:
        raise ValueError("power overflows") from None


def _sqrt(x: float) -> float:
    if x < 0:
        raise ValueError(f"SQRT of negative number {x:g}")
    return math.sqrt(x)


def _asin(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise ValueError(f"ASIN argument {x:g} outside [-1, 1]")
    return math.degrees(math.asin(x))


def _acos(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise ValueError(f"ACOS argument {x:g} outside [-1, 1]")
    return math.degrees(math.acos(x))


def _ln(x: float) -> float:
    if x <= 0:
        raise ValueError(f"LN of non-positive number {x:g}")
    return math.log(x)


def _exp(x: float) -> float:
    try:
        return math.exp(x)
    except OverflowError:
        raise ValueError(f"EXP[{x:g}] overflows") from None


#: TAN is infinite this close (degrees) to an odd multiple of 90 (math.tan gives ~1e16 there).
_TAN_POLE_DEG = 1e-12


def _tan(x: float) -> float:
    if math.isclose(math.fmod(abs(x), 180.0), 90.0, abs_tol=_TAN_POLE_DEG):
        raise ValueError(f"TAN of {x:g} degrees is infinite")
    return math.tan(math.radians(x))


def _round_half_away(x: float) -> float:
    return float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0)


#: Unary functions both dialects know (degrees for trigonometry).
COMMON_FUNCTIONS: dict[str, Callable[[float], float]] = {
    "SIN": lambda x: math.sin(math.radians(x)),
    "COS": lambda x: math.cos(math.radians(x)),
    "TAN": _tan,
    "ASIN": _asin,
    "ACOS": _acos,
    "ATAN": lambda x: math.degrees(math.atan(x)),
    "SQRT": _sqrt,
    "ABS": abs,
    "EXP": _exp,
    "LN": _ln,
}


def _bool(x: bool) -> float:
    return 1.0 if x else 0.0


@dataclass(frozen=True)
class Grammar:
    """How a dialect writes expressions.

    Attributes
    ----------
    open, close: bracket characters.
    binary: operator spelling (upper case) -> (precedence, function); higher
        precedence binds tighter. Spellings are matched longest first.
    functions: unary function names (upper case) -> function of the value.
    atan2_form: G-code writes two-argument arctangent as ``ATAN[a]/[b]``.
    variable: callback ``(text, pos) -> (value, new_pos) | None`` reading a
        variable reference at ``pos`` (e.g. ``#12`` or ``P12``); ``None`` when
        no variable starts there.
    """

    open: str
    close: str
    binary: dict[str, tuple[int, Callable[[float, float], float]]]
    functions: dict[str, Callable[[float], float]]
    atan2_form: bool = False
    variable: Callable[[str, int], tuple[float, int] | None] | None = field(default=None)


GCODE_BINARY: dict[str, tuple[int, Callable[[float, float], float]]] = {
    "**": (4, _pow),
    "*": (3, operator.mul),
    "/": (3, _div),
    "MOD": (3, _mod),
    "+": (2, operator.add),
    "-": (2, operator.sub),
    "EQ": (1, lambda a, b: _bool(a == b)),
    "NE": (1, lambda a, b: _bool(a != b)),
    "GT": (1, lambda a, b: _bool(a > b)),
    "GE": (1, lambda a, b: _bool(a >= b)),
    "LT": (1, lambda a, b: _bool(a < b)),
    "LE": (1, lambda a, b: _bool(a <= b)),
    "AND": (0, lambda a, b: _bool(a != 0 and b != 0)),
    "OR": (0, lambda a, b: _bool(a != 0 or b != 0)),
    "XOR": (0, lambda a, b: _bool((a != 0) != (b != 0))),
}

GCODE_FUNCTIONS: dict[str, Callable[[float], float]] = {
    **COMMON_FUNCTIONS,
    "FIX": lambda x: float(math.floor(x)),
    "FUP": lambda x: float(math.ceil(x)),
    "ROUND": _round_half_away,
}

PMAC_BINARY: dict[str, tuple[int, Callable[[float, float], float]]] = {
    "*": (3, operator.mul),
    "/": (3, _div),
    "%": (3, _mod),
    "+": (2, operator.add),
    "-": (2, operator.sub),
}

PMAC_FUNCTIONS: dict[str, Callable[[float], float]] = {
    **COMMON_FUNCTIONS,
    "INT": lambda x: float(math.floor(x)),
}


_DIGITS = frozenset("0123456789")

#: Deepest bracket/operator nesting accepted (deeper is an error, not a crash).
MAX_DEPTH = 200


class _Parser:
    def __init__(self, text: str, grammar: Grammar):
        self.depth = 0
        self.text = text
        self.upper = text.upper()
        self.g = grammar
        self._ops = sorted(grammar.binary, key=len, reverse=True)
        self._funcs = sorted(grammar.functions, key=len, reverse=True)
        if grammar.atan2_form:
            self._funcs = sorted(set(self._funcs) | {"ATAN"}, key=len, reverse=True)

    # -- low level ------------------------------------------------------
    def skip(self, pos: int) -> int:
        while pos < len(self.text) and self.text[pos] in " \t":
            pos += 1
        return pos

    def expect(self, pos: int, ch: str) -> int:
        pos = self.skip(pos)
        if pos >= len(self.text) or self.text[pos] != ch:
            found = "end of line" if pos >= len(self.text) else repr(self.text[pos])
            raise ExprError(f"expected {ch!r}, found {found}", pos)
        return pos + 1

    def number(self, pos: int) -> tuple[float, int] | None:
        # ASCII digits only: str.isdigit() also accepts "²" and other digits
        # float() refuses.
        start = pos
        digits = False
        while pos < len(self.text) and self.text[pos] in _DIGITS:
            pos += 1
            digits = True
        if pos < len(self.text) and self.text[pos] == ".":
            pos += 1
            while pos < len(self.text) and self.text[pos] in _DIGITS:
                pos += 1
                digits = True
        if not digits:
            return None
        value = float(self.text[start:pos])
        if not math.isfinite(value):
            raise ExprError("number is not finite (too large)", start)
        return value, pos

    # -- grammar --------------------------------------------------------
    def bracketed(self, pos: int) -> tuple[float, int]:
        pos = self.expect(pos, self.g.open)
        value, pos = self.expression(pos, 0)
        pos = self.expect(pos, self.g.close)
        return value, pos

    def expression(self, pos: int, min_prec: int) -> tuple[float, int]:
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                raise ExprError(f"expression nested too deeply (more than {MAX_DEPTH} levels)", pos)
            return self._expression(pos, min_prec)
        finally:
            self.depth -= 1

    def _expression(self, pos: int, min_prec: int) -> tuple[float, int]:
        left, pos = self.operand(pos)
        while True:
            p = self.skip(pos)
            op = self.match_operator(p)
            if op is None:
                return left, p
            prec, fn = self.g.binary[op]
            if prec < min_prec:
                return left, p
            # RS274/NGC evaluates equal precedence left to right (power too),
            # so the right operand only takes tighter-binding operators.
            right, pos = self.expression(p + len(op), prec + 1)
            left = self.apply(fn, p, left, right)

    def match_operator(self, pos: int) -> str | None:
        for op in self._ops:
            if self.upper.startswith(op, pos):
                if op[0].isalpha():
                    # A word operator must not be the prefix of a longer word,
                    # unless that word is a function (``1ANDABS[2]``).
                    end = pos + len(op)
                    if end < len(self.upper) and self.upper[end].isalpha() and not any(
                            self.upper.startswith(f, end) for f in self._funcs):
                        continue
                return op
        return None

    def apply(self, fn, col: int, *args: float) -> float:
        try:
            return _finite(float(fn(*args)), "result")
        except (ValueError, ZeroDivisionError, OverflowError) as exc:
            raise ExprError(str(exc), col) from None

    def operand(self, pos: int) -> tuple[float, int]:
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                raise ExprError(f"expression nested too deeply (more than {MAX_DEPTH} levels)", pos)
            return self._operand(pos)
        finally:
            self.depth -= 1

    def _operand(self, pos: int) -> tuple[float, int]:
        pos = self.skip(pos)
        if pos >= len(self.text):
            raise ExprError("expression ends too early", pos)
        ch = self.text[pos]
        if ch in "+-":
            value, end = self.operand(pos + 1)
            return (-value if ch == "-" else value), end
        if ch == self.g.open:
            return self.bracketed(pos)
        num = self.number(pos)
        if num is not None:
            return num
        if self.g.variable is not None:
            var = self.g.variable(self.text, pos)
            if var is not None:
                return var
        for name in self._funcs:
            if self.upper.startswith(name, pos):
                after = self.skip(pos + len(name))
                if after < len(self.text) and self.text[after] == self.g.open:
                    arg, end = self.bracketed(after)
                    if name == "ATAN" and self.g.atan2_form:
                        slash = self.skip(end)
                        if slash < len(self.text) and self.text[slash] == "/":
                            nxt = self.skip(slash + 1)
                            if nxt < len(self.text) and self.text[nxt] == self.g.open:
                                x, end = self.bracketed(nxt)
                                return self.apply(
                                    lambda a, b: math.degrees(math.atan2(a, b)), pos, arg, x), end
                    return self.apply(self.g.functions[name], pos, arg), end
        raise ExprError(f"unexpected {ch!r} in expression", pos)


def parse_bracketed(text: str, pos: int, grammar: Grammar) -> tuple[float, int]:
    """Evaluate the bracketed expression starting at ``text[pos]``.

    Returns ``(value, position after the closing bracket)``. Raises
    :class:`ExprError` with the column of the problem.
    """
    return _Parser(text, grammar).bracketed(pos)


def parse_operand(text: str, pos: int, grammar: Grammar) -> tuple[float, int]:
    """Evaluate one operand (number, variable, function or bracketed expression)."""
    return _Parser(text, grammar).operand(pos)


def parse_expression(text: str, pos: int, grammar: Grammar) -> tuple[float, int]:
    """Evaluate an unbracketed expression starting at ``text[pos]`` (e.g. the
    right-hand side of a PMAC ``P1=P2*2+1``); stops at the first character
    that cannot continue it. Returns ``(value, position after it)``."""
    return _Parser(text, grammar).expression(pos, 0)
