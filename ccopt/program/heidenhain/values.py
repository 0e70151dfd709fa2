"""Numbers and Q parameters of a Klartext program.

A value is written after its address: ``X+10``, ``X-.5``, ``X10``, ``X+Q5``
(the value of Q5), ``X-Q5`` (its negative), also ``QL``/``QR`` parameters.
Q parameters are set by ``FN 0`` .. ``FN 8`` and ``FN 13`` (``FN 1: Q1 = +Q2 +
+5``) and by formulas (``Q1 = Q2 * 3 + SIN ( 30 )``); conditional jumps are
``FN 9`` .. ``FN 12`` (``FN 9: IF +Q1 EQU +5 GOTO LBL 2``). Trigonometry is in
degrees. A parameter never set reads 0.
"""
from __future__ import annotations

import math
import operator
import re

from ccopt.errors import ProgramError
from ccopt.program.expr import COMMON_FUNCTIONS, ExprError, Grammar, parse_expression
from ccopt.program.heidenhain.lexer import Statement, Word
from ccopt.program.model import out_of_range

#: A Q parameter reference: ``Q12``, ``QL3``, ``QR40``.
Q_RE = re.compile(r"(Q[LR]?)(\d+)")
_NUMBER_RE = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)$")
_QREF_RE = re.compile(r"([+-]?)(Q[LR]?\d+)$")


def _pow(a: float, b: float) -> float:
    return float(a) ** float(b)


def _div(a: float, b: float) -> float:
    if b == 0:
        raise ValueError("division by zero")
    return a / b


def _frac(x: float) -> float:
    return x - math.trunc(x)


FUNCTIONS = {**COMMON_FUNCTIONS, "SQ": lambda x: x * x, "INT": lambda x: float(math.trunc(x)),
             "NEG": lambda x: -x, "FRAC": _frac, "LOG": math.log10,
             "SGN": lambda x: float((x > 0) - (x < 0))}
BINARY = {"^": (4, _pow), "*": (3, operator.mul), "/": (3, _div), "+": (2, operator.add),
          "-": (2, operator.sub)}


class Parameters:
    """The Q, QL and QR parameters of a run."""

    def __init__(self, file: str):
        self.file = file
        self.values: dict[str, float] = {}
        self.grammar = Grammar("(", ")", BINARY, FUNCTIONS, variable=self._variable)

    def _variable(self, text: str, pos: int):
        upper = text.upper()
        if upper.startswith("PI", pos) and not upper[pos + 2: pos + 3].isalnum():
            return math.pi, pos + 2
        m = Q_RE.match(upper, pos)
        if m is None:
            return None
        return self.get(m.group(0)), m.end()

    def get(self, name: str) -> float:
        return self.values.get(name, 0.0)

    def set(self, name: str, value: float, line: int, col: int) -> None:
        if not math.isfinite(value) or out_of_range(value):
            raise ProgramError(f"{name} = {value:g} is out of range", self.file, line, col)
        self.values[name] = float(value)

    def number(self, text: str, line: int, col: int, what: str) -> float:
        """The value written as ``text`` (a number or a signed Q reference)."""
        if _NUMBER_RE.match(text):
            value = float(text)
        else:
            m = _QREF_RE.match(text)
            if m is None:
                raise ProgramError(f"{what}: cannot read the value {text!r} (a number such as "
                                   "+10.5 or a parameter such as +Q5 is expected)",
                                   self.file, line, col)
            value = self.get(m.group(2)) * (-1.0 if m.group(1) == "-" else 1.0)
        if out_of_range(value):
            raise ProgramError(f"{what}{text} is out of range: check the value",
                               self.file, line, col)
        return value

    def formula(self, text: str, line: int, col: int) -> float:
        """The value of a formula (the right-hand side of ``Q1 = ...``)."""
        try:
            value, end = parse_expression(text, 0, self.grammar)
        except ExprError as exc:
            raise ProgramError(f"formula: {exc.message}", self.file, line,
                               col + exc.col) from None
        if text[end:].strip():
            raise ProgramError(f"formula: cannot read {text[end:].strip()!r}", self.file, line,
                               col + end)
        return value

    # -- statements -------------------------------------------------------------
    def assignment(self, st: Statement) -> None:
        """``Q1 = <formula>`` (the whole statement)."""
        target = st.words[0]
        name, eq, text = " ".join(w.text for w in st.words).partition("=")
        name = name.strip()
        if not Q_RE.fullmatch(name):
            raise ProgramError(f"cannot assign to {name!r}", self.file, st.line, target.col)
        if not eq:
            raise ProgramError(f"expected '=' after {name}", self.file, st.line, target.col)
        self.set(name, self.formula(text, st.line, target.col), st.line, target.col)

    def fn(self, st: Statement) -> tuple[str, float, str] | None:
        """An ``FN`` statement. Arithmetic ones set their parameter and return
        ``None``; a conditional jump returns ``("jump", 1.0|0.0, label)``."""
        words = st.words
        if len(words) < 2:
            raise ProgramError("FN without a number", self.file, st.line, words[0].col)
        number = words[1].text.rstrip(":")
        if not number.isdigit():
            raise ProgramError(f"FN {words[1].text}: expected a function number",
                               self.file, st.line, words[1].col)
        n = int(number)
        rest = words[2:]
        if 9 <= n <= 12:
            return self._jump(n, rest, st)
        if not (0 <= n <= 8 or n == 13):
            raise ProgramError(f"FN {n} is not read by ccopt (FN 0-13 are)", self.file, st.line,
                               words[0].col)
        text = " ".join(w.text for w in rest)
        name, eq, rhs = text.partition("=")
        name = name.strip()
        if not eq or not Q_RE.fullmatch(name):
            raise ProgramError(f"FN {n}: expected 'Q<n> = ...'", self.file, st.line,
                               words[0].col)
        col = rest[0].col
        args = [t for t in rhs.split() if t not in ("DIV", "+", "-", "*", "/", "ANGLE", "ROOT",
                                                   "SQRT", "SIN", "COS", "LEN")]
        vals = [self.number(t, st.line, col, f"FN {n}") for t in args]
        value = self._arith(n, vals, st, words[0])
        self.set(name, value, st.line, col)
        return None

    def _arith(self, n: int, v: list[float], st: Statement, w: Word) -> float:
        need = 1 if n in (0, 5, 6, 7) else 2
        if len(v) != need:
            raise ProgramError(f"FN {n}: expected {need} value(s), found {len(v)}",
                               self.file, st.line, w.col)
        try:
            return [lambda: v[0], lambda: v[0] + v[1], lambda: v[0] - v[1],
                    lambda: v[0] * v[1], lambda: _div(v[0], v[1]),
                    lambda: FUNCTIONS["SQRT"](v[0]), lambda: FUNCTIONS["SIN"](v[0]),
                    lambda: FUNCTIONS["COS"](v[0]), lambda: math.hypot(v[0], v[1]),
                    None, None, None, None,
                    lambda: math.degrees(math.atan2(v[1], v[0]))][n]()
        except ValueError as exc:
            raise ProgramError(f"FN {n}: {exc}", self.file, st.line, w.col) from None

    def _jump(self, n: int, rest: list[Word], st: Statement) -> tuple[str, float, str]:
        texts = [w.text for w in rest]
        try:
            i_goto = texts.index("GOTO")
        except ValueError:
            raise ProgramError(f"FN {n}: expected 'IF a <op> b GOTO LBL n'", self.file,
                               st.line, st.words[0].col) from None
        vals = [w for w in rest[:i_goto] if w.text not in ("IF", "EQU", "NE", "GT", "LT")]
        if len(vals) != 2 or texts[i_goto + 1: i_goto + 2] != ["LBL"] or len(texts) < i_goto + 3:
            raise ProgramError(f"FN {n}: expected 'IF a <op> b GOTO LBL n'", self.file,
                               st.line, st.words[0].col)
        a, b = (self.number(w.text, st.line, w.col, f"FN {n}") for w in vals)
        holds = [a == b, a != b, a > b, a < b][n - 9]
        return ("jump", 1.0 if holds else 0.0, texts[i_goto + 2])
