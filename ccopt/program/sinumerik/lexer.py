"""Reading the text of a SINUMERIK block (Programming Manual Fundamentals,
6FC5398-2EP40, chapter 1 "Fundamentals of NC programming": block structure,
addresses and comments).

A block is one line: an optional block number ``N10`` (or main block
``:10``), an optional jump label ``NAME:``, then words; ``;`` starts a
comment to the end of the line (outside a ``"string"``). A word is an
address and a value: ``X10``, ``G1``, or with ``=`` an expression
``X=R1+5``, ``CR=12``, ``R3=2*R1``, ``DISR=5``; an address of several
letters always takes ``=``. Keywords without a value (``NORM``, ``KONT``,
``CIP``, ``CT``, ``CDON``) stand alone. The code is upper-cased here (the
language is case-insensitive), columns are kept (0-based).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ccopt.program.expr import ExprError

_BLOCK_NUMBER = re.compile(r"[ \t]*(?:[Nn][ \t]*\d+|:[ \t]*\d+)")
# A jump label: a name of letters, digits and underscores starting with a
# letter or underscore, followed by a colon.
_LABEL = re.compile(r"[ \t]*([A-Za-z_][A-Za-z0-9_]*)[ \t]*:(?!=)")
_LETTERS = re.compile(r"[A-Z_$][A-Z_$]*")
_DIGITS = re.compile(r"\d+")
_NUMBER = re.compile(r"[+-]?[ \t]*(?:\d+\.?\d*|\.\d+)")
_BLANKS = re.compile(r"[ \t]*")
_SYSTEM_NAME = re.compile(r"[A-Z0-9_$]*")
#: Single-letter addresses that take a number directly (``X10``, ``G1``).
NUMBER_ADDRESSES = set("ABCDEFGHIJKLMPSTXYZ")  # and L<n>, a subprogram call
#: Letters that, with digits, name an extended address set with ``=``
#: (``R1=``, ``I1=`` of CIP, ``L123`` calls are refused elsewhere).
EXTENDED_ADDRESSES = set("RIJKXYZ")


@dataclass(slots=True)
class Line:
    """A block's text after the block number and label."""

    code: str            # upper-cased, comments blanked (columns kept)
    start: int           # first column after the block number and label
    label: str | None    # the jump label defined on this line
    number: str | None   # the block number ``N..`` as written (upper-cased)


@dataclass(slots=True)
class Word:
    """One word: ``name`` (``"X"``, ``"G"``, ``"CR"``, ``"R1"``, ``"NORM"``),
    ``literal`` its number when written directly (``X10``), else ``None``
    and ``expr`` the column of the expression after ``=`` (``None`` for a
    keyword); ``col`` the word's column."""

    name: str
    col: int
    literal: float | None = None
    expr: int | None = None
    index: int | None = None   # column of ``[`` for ``R[..]=`` / ``$TC_DP6[..]=``


def skip_blanks(code: str, p: int) -> int:
    return _BLANKS.match(code, p).end()


def blank_comment(text: str) -> str:
    """``text`` with its ``;`` comment blanked (not inside a string)."""
    quoted = False
    for i, ch in enumerate(text):
        if ch == '"':
            quoted = not quoted
        elif ch == ";" and not quoted:
            return text[:i] + " " * (len(text) - i)
    return text


def split_line(text: str) -> Line:
    """The block number, label and code of one line."""
    code = blank_comment(text)
    code = code.upper() if '"' not in code else _upper_outside_strings(code)
    number = None
    p = 0
    m = _BLOCK_NUMBER.match(code, p)
    if m:
        number = code[m.start():m.end()].replace(" ", "").replace("\t", "")
        p = m.end()
    label = None
    m = _LABEL.match(code, p)
    if m and not _is_word_start(m.group(1)):
        label = m.group(1)
        p = m.end()
    return Line(code, skip_blanks(code, p), label, number)


def _is_word_start(name: str) -> bool:
    """A name before ':' that is a word, not a label (labels have at least
    two characters; ``X:`` is no label)."""
    return len(name) < 2


def _upper_outside_strings(code: str) -> str:
    parts = code.split('"')
    return '"'.join(p.upper() if i % 2 == 0 else p for i, p in enumerate(parts))


def next_name(code: str, p: int) -> tuple[str, int]:
    """The run of letters (and ``_ $``) at ``p`` and the position after it."""
    m = _LETTERS.match(code, p)
    return (m.group(), m.end()) if m else ("", p)


def read_word(code: str, p: int) -> tuple[Word, int]:
    """The word at ``p`` (not a blank) and the position after it; the value
    of a ``=`` word is left for the caller to evaluate (it knows the
    variables): ``expr`` is where it starts, and the returned position too."""
    letters, q = next_name(code, p)
    if letters.startswith("$") or len(letters) > 1:
        # names of two letters or more, system variables among them, may carry
        # digits ($TC_DP6, CYCLE832, a variable LEN2); one letter and digits is
        # an address and its value (X10)
        q = _SYSTEM_NAME.match(code, q).end()
        letters = code[p:q]
    if not letters:
        raise ExprError(f"unexpected character {code[p]!r}: a word starts with an address "
                        "letter, e.g. G1 or X10", p)
    if len(letters) == 1 and letters in EXTENDED_ADDRESSES | NUMBER_ADDRESSES | {"L"}:
        d = _DIGITS.match(code, q)
        if d:
            after = skip_blanks(code, d.end())
            if after < len(code) and code[after] == "=" and letters in EXTENDED_ADDRESSES:
                return Word(letters + str(int(d.group())), p, expr=after + 1), after + 1
        if letters in NUMBER_ADDRESSES or (letters == "L" and d):
            n = _NUMBER.match(code, q)
            if n:
                value = float(n.group().replace(" ", "").replace("\t", ""))
                return Word(letters, p, literal=value), n.end()
    after = skip_blanks(code, q)
    if after < len(code) and code[after] == "[":
        close = code.find("]", after)
        if close < 0:
            raise ExprError("'[' has no closing ']'", after)
        eq = skip_blanks(code, close + 1)
        if eq >= len(code) or code[eq] != "=":
            raise ExprError(f"{letters}[...] must be set with '=' here", p)
        return Word(letters, p, expr=eq + 1, index=after), eq + 1
    if after < len(code) and code[after] == "=":
        return Word(letters, p, expr=after + 1), after + 1
    if letters == "R" and q < len(code) and code[q] == "[":
        raise ExprError("R[..] must be set with '=' here", p)
    return Word(letters, p), q


def string_argument(code: str, p: int) -> int:
    """The position after a parenthesised argument list starting at ``p``
    (``MSG("text")``), strings skipped."""
    p = skip_blanks(code, p)
    if p >= len(code) or code[p] != "(":
        raise ExprError("expected '(' and the argument", p)
    depth, quoted = 0, False
    for i in range(p, len(code)):
        ch = code[i]
        if ch == '"':
            quoted = not quoted
        elif not quoted and ch == "(":
            depth += 1
        elif not quoted and ch == ")":
            depth -= 1
            if depth == 0:
                return i + 1
    raise ExprError("'(' has no closing ')'", p)
