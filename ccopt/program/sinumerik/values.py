"""Arithmetic parameters, user variables and expressions of a SINUMERIK
program (Programming Manual Fundamentals, "Arithmetic parameters (R)",
"Arithmetic operations", "Comparison and logic operations"; Job Planning
"User-defined variables (DEF)").

* ``R0`` .. ``R999`` read 0 until set; ``R[expr]`` indexes them.
* ``DEF REAL|INT|BOOL NAME[=value], ...`` declares user variables (0 until
  set); reading a name that was never declared is an error.
* Expressions are written without brackets after ``=`` (``X=R1+2*R2``) with
  ``( )`` for grouping; operators ``* / DIV MOD + -``, comparisons
  ``== <> > < >= <=``, ``AND OR XOR`` and ``NOT``; functions ``SIN COS TAN
  ASIN ACOS ATAN2(y, x) SQRT POT ABS TRUNC ROUND LN EXP`` (degrees).
* ``$TC_DP6[t, d]`` is the radius of cutting edge ``d`` of tool ``t``
  (``$TC_DP1``..``$TC_DP25`` may be set; only the radius is used).
"""
from __future__ import annotations

import math
import operator

from ccopt.program.expr import COMMON_FUNCTIONS, ExprError, Grammar, parse_expression

#: Highest R parameter number (MD28050 sets how many exist; 1000 is the largest).
MAX_R = 999
#: A value within this of a whole number counts as that number (an index, a tool number).
WHOLE_TOL = 1e-6
#: The tool data words ``$TC_DP1`` .. ``$TC_DP25`` that may be set.
TOOL_PARAMETERS = 25
#: ``$TC_DP6``: the radius of a cutting edge.
RADIUS_PARAMETER = 6


def _bool(x: bool) -> float:
    return 1.0 if x else 0.0


def _div(a: float, b: float) -> float:
    if b == 0:
        raise ZeroDivisionError("division by zero")
    return a / b


def _int_div(a: float, b: float) -> float:
    if b == 0:
        raise ZeroDivisionError("DIV by zero")
    return float(math.trunc(a / b))


def _mod(a: float, b: float) -> float:
    if b == 0:
        raise ZeroDivisionError("MOD by zero")
    return math.fmod(a, b)


BINARY = {
    "*": (4, operator.mul), "/": (4, _div), "DIV": (4, _int_div), "MOD": (4, _mod),
    "+": (3, operator.add), "-": (3, operator.sub),
    "==": (2, lambda a, b: _bool(a == b)), "<>": (2, lambda a, b: _bool(a != b)),
    ">=": (2, lambda a, b: _bool(a >= b)), "<=": (2, lambda a, b: _bool(a <= b)),
    ">": (2, lambda a, b: _bool(a > b)), "<": (2, lambda a, b: _bool(a < b)),
    "AND": (1, lambda a, b: _bool(a != 0 and b != 0)),
    "XOR": (0, lambda a, b: _bool((a != 0) != (b != 0))),
    "OR": (0, lambda a, b: _bool(a != 0 or b != 0)),
}


def _pot(x: float) -> float:
    return x * x


FUNCTIONS = {
    **COMMON_FUNCTIONS,
    "POT": _pot,
    "TRUNC": lambda x: float(math.trunc(x)),
    "ROUND": lambda x: float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0),
}
_NAME_CHARS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_$")


class Variables:
    """R parameters, user variables and tool radii of one program run."""

    def __init__(self) -> None:
        self.r: dict[int, float] = {}
        self.user: dict[str, float] = {}
        self.tool_radius: dict[tuple[int, int], float] = {}
        self.grammar = Grammar("(", ")", BINARY, FUNCTIONS, variable=self._variable)

    # -- evaluation -----------------------------------------------------------
    def evaluate(self, code: str, p: int) -> tuple[float, int]:
        """The expression at ``p`` and the position after it."""
        value, end = parse_expression(code, p, self.grammar)
        if not math.isfinite(value):
            raise ExprError("the value is not a finite number", p)
        return value, end

    def _variable(self, text: str, pos: int):
        if not (text[pos].isalpha() or text[pos] in "_$"):
            return None
        q = pos
        while q < len(text) and text[q] in _NAME_CHARS:
            q += 1
        name = text[pos:q]
        if name == "ATAN2":
            return self._atan2(text, q)
        if name == "NOT":
            value, end = parse_expression(text, q, self.grammar)
            return _bool(value == 0), end
        if name == "R" and q < len(text) and text[q] == "[":
            index, end = self._index(text, q)
            return self.r_value(index, pos), end
        if len(name) > 1 and name[0] == "R" and name[1:].isdigit():
            return self.r_value(int(name[1:]), pos), q
        if name in self.user:
            return self.user[name], q
        if name == "$TC_DP6" and q < len(text) and text[q] == "[":
            (t, d), end = self.tool_index(text, q)
            return self.tool_radius.get((t, d), 0.0), end
        if name in FUNCTIONS:
            return None
        if name.startswith("$"):
            raise ExprError(f"system variable {name} is not read by ccopt (only $TC_DP6, the "
                            "cutting edge radius)", pos)
        raise ExprError(f"unknown variable {name}: declare it with DEF REAL {name} or use an "
                        "R parameter", pos)

    def _atan2(self, text: str, q: int) -> tuple[float, int]:
        if q >= len(text) or text[q] != "(":
            raise ExprError("ATAN2 needs two arguments: ATAN2(y, x)", q)
        y, p = self.evaluate(text, q + 1)
        if p >= len(text) or text[p] != ",":
            raise ExprError("ATAN2 needs two arguments separated by ',': ATAN2(y, x)", p)
        x, p = self.evaluate(text, p + 1)
        if p >= len(text) or text[p] != ")":
            raise ExprError("expected ')' closing ATAN2", p)
        return math.degrees(math.atan2(y, x)), p + 1

    def _index(self, text: str, q: int) -> tuple[int, int]:
        """``[expr]`` at ``q``: a whole number and the position after ']'."""
        value, p = self.evaluate(text, q + 1)
        if p >= len(text) or text[p] != "]":
            raise ExprError("expected ']'", p)
        return whole(value, q), p + 1

    def tool_index(self, text: str, q: int) -> tuple[tuple[int, int], int]:
        """``[t, d]`` at ``q``: tool and cutting edge numbers, position after ']'."""
        t, p = self.evaluate(text, q + 1)
        if p >= len(text) or text[p] != ",":
            raise ExprError("tool data take [tool, cutting edge], e.g. $TC_DP6[1,1]", p)
        d, p = self.evaluate(text, p + 1)
        if p >= len(text) or text[p] != "]":
            raise ExprError("expected ']'", p)
        return (whole(t, q), whole(d, q)), p + 1

    def r_value(self, n: int, col: int) -> float:
        check_r(n, col)
        return self.r.get(n, 0.0)


def check_r(n: int, col: int) -> None:
    if not 0 <= n <= MAX_R:
        raise ExprError(f"R{n}: arithmetic parameters run from R0 to R{MAX_R}", col)


def whole(value: float, col: int) -> int:
    """``value`` as a whole number (an index); ExprError otherwise."""
    n = round(value)
    if abs(value - n) > WHOLE_TOL:
        raise ExprError(f"{value:g} is not a whole number", col)
    return int(n)
