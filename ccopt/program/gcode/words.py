"""Reading the text of a line (LinuxCNC ``interp_read.cc``, lexical part).

A line is lexed once and cached: comments become blanks (so columns stay
those of the file), the characters are checked, a leading ``N`` word is
skipped, an O-word's label and keyword are read, and ``%`` lines are
recognised. Literal numbers are read here too, with the RS274NGC rule that
blanks may appear inside them (``X1 0`` is ``X10``). Columns are 0-based.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ccopt.program.expr import ExprError
from ccopt.program.gcode.state import GCodeState

#: A value read where a whole number is meant (an M code, a T or D tool
#: number, a parameter number) may be this far from it: rounding in a
#: computed value, not a fraction the program meant.
WHOLE_NUMBER_TOL = 1e-4

O_KEYWORDS = ("sub", "endsub", "call", "do", "while", "endwhile", "if", "elseif",
              "else", "endif", "break", "continue", "return", "repeat", "endrepeat")

_BLANKS = re.compile(r"[ \t]*")
# A literal number not followed by a blank and a digit (the common, fast case).
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?![.\d]|[ \t]+[.\d])")
# The number of an N word: digits, points and blanks (the code is ASCII here).
_N_NUMBER = re.compile(r"[\d. \t]*")
# The number of an O-word label: digits and blanks.
_O_NUMBER = re.compile(r"[\d \t]*")
_O_KEYWORD = re.compile(r"[A-Za-z]*")
# A keyword written with blanks between its letters: LinuxCNC drops the blanks
# of a line before reading it, so "o100 end sub" is "o100 endsub".
_O_SPACED = re.compile("(?:" + "|".join("[ \t]*".join(kw) for kw in sorted(
    O_KEYWORDS, key=len, reverse=True)) + ")(?![A-Za-z])", re.IGNORECASE)
# Where a comment starts: '(' to the next ')', ';' to the end of the line.
_COMMENT_START = re.compile(r"[(;]")
# The end of a '(' comment, or a '(' nested in it (an error).
_PAREN = re.compile(r"[()]")
# A character not allowed outside comments: anything but printable ASCII and tab.
_NOT_CODE = re.compile(r"[^\t -~]")


def fmt(x: float) -> str:
    """A number for a message: short, no trailing zeros."""
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.6g}"


def gname(tenths: int) -> str:
    """A G-code's name from its number in tenths (411 -> ``G41.1``)."""
    return f"G{tenths // 10}" if tenths % 10 == 0 else f"G{tenths // 10}.{tenths % 10}"


def olabel(label: str) -> str:
    """An O-word label as written: ``o100`` or ``o<name>``."""
    return f"o{label}" if label.isdigit() else f"o<{label}>"


def skip_blanks(code: str, p: int) -> int:
    """The first position at or after ``p`` that is not a space or a tab."""
    if p < len(code) and code[p] != " " and code[p] != "\t":
        return p            # the common case, without a match
    return _BLANKS.match(code, p).end()


@dataclass(slots=True)
class OWord:
    """The head of an O-word line."""

    label: str
    keyword: str | None  # None: Fanuc program number "O1234" alone on a line
    col: int             # 0-based column of the 'O'
    rest: int            # position after the keyword
    computed: int | None = None  # a label computed at the call: its value's position


@dataclass(slots=True)
class Lexed:
    """A lexed line."""

    code: str                 # the line with comments turned into spaces
    first: int | None         # 0-based column of the first word (None: no code)
    start: int                # position of the first word after an N word
    oword: OWord | None = None
    percent: bool = False
    fanuc: int | None = None  # 98 or 99: the line starts with M98/M99 (fanuc.py)
    abort: tuple[int, str] | None = None  # an (abort, ...) comment: its column and text
    message: tuple[str, str] | None = None  # a (debug, ...)/(msg, ...) comment: kind, text


def lex(state: GCodeState, i: int) -> Lexed:
    """Line ``i`` (0-based) lexed, cached in the state."""
    lx = state.lexed.get(i)
    if lx is None:
        lx = _lex_line(state, i)
        state.lexed[i] = lx
    return lx


#: LinuxCNC's comments that act (``convert_comment``: the word, any case, then
#: a comma): ``(abort, message)`` stops the program there; ``(debug, ...)``
#: (parameters replaced) and ``(msg, ...)`` are messages; ``(print, ...)``
#: (parameters replaced) is printed on rs274's standard output.
ACTIVE_COMMENT = re.compile(r"\s*(abort|debug|msg|print),(.*)", re.IGNORECASE | re.DOTALL)


def _lex_line(state: GCodeState, i: int) -> Lexed:
    text = state.lines[i]
    lx = _lex_code(state, blank_comments(state, text, i), i)
    if "(" in text:
        for col, body in _paren_comments(text):
            m = ACTIVE_COMMENT.match(body)
            if m is None:
                continue
            kind = m.group(1).lower()
            if kind == "abort":
                lx.abort = lx.abort or (col, m.group(2))
            elif lx.message is None:
                lx.message = (kind, m.group(2))
    return lx


def _paren_comments(text: str):
    """``(column, body)`` of each ``( ... )`` comment of a line, up to a ``;``
    comment (which runs to the end of the line, parentheses and all); the line
    passed :func:`blank_comments`, so they are closed and not nested."""
    i = 0
    while True:
        j, k = text.find("(", i), text.find(";", i)
        if j < 0 or 0 <= k < j:
            return
        end = text.find(")", j)
        if end < 0:
            return
        yield j, text[j + 1:end]
        i = end + 1


def _lex_code(state: GCodeState, code: str, i: int) -> Lexed:
    n = len(code)
    p = skip_blanks(code, 0)
    if p >= n:
        return Lexed(code, None, n)
    if code[p] == "%":
        q = skip_blanks(code, p + 1)
        if q < n:
            raise state.error("a '%' line must hold nothing else", q, i)
        return Lexed(code, None, n, percent=True)
    first = p
    if code[p] in "nN":
        number = _N_NUMBER.match(code, skip_blanks(code, p + 1))
        if not any(ch.isdigit() for ch in number.group()):
            raise state.error("N word (line number) has no number: write e.g. N10", p, i)
        p = number.end()
    lx = Lexed(code, first, p)
    if p < n and code[p] in "oO":
        lx.oword = _lex_oword(state, code, p, i)
    elif p < n and code[p] in "mM":
        m = FANUC_CALL.match(code, p)
        if m:
            lx.fanuc = int(m.group(1))
    return lx


def blank_comments(state: GCodeState, text: str, i: int) -> str:
    """``text`` with comments replaced by spaces (columns kept); checks characters.

    Outside comments only printable ASCII and tabs are allowed, so the code
    every later stage reads is plain ASCII. The comments and the characters
    are found by regular expressions, the text between them taken whole.
    """
    if "(" not in text and ";" not in text:
        if text.isascii() and text.isprintable():
            return text
    parts = []
    n = len(text)
    k = 0
    while True:
        opened = _COMMENT_START.search(text, k)
        stop = n if opened is None else opened.start()
        bad = _NOT_CODE.search(text, k, stop)
        if bad is not None:
            ch = bad.group()
            raise state.error(f"character {ch!r} (U+{ord(ch):04X}) is not allowed outside "
                              "comments: G-code is plain ASCII", bad.start(), i)
        parts.append(text[k:stop])
        if opened is None:
            return "".join(parts)
        if opened.group() == ";":
            parts.append(" " * (n - stop))
            return "".join(parts)
        close = _PAREN.search(text, stop + 1)
        if close is None:
            raise state.error("unterminated comment: add ')' to close the '(' opened here",
                              stop, i)
        if close.group() == "(":
            raise state.error("'(' inside a comment: comments cannot be nested; "
                              "remove the inner '('", close.start(), i)
        k = close.end()
        parts.append(" " * (k - stop))


#: ``M98``/``M99`` as the first word of a line (Fanuc subprograms, fanuc.py).
FANUC_CALL = re.compile(r"[mM][ \t]*0*(9[89])(?![0-9.])")


def _lex_oword(state: GCodeState, code: str, p: int, i: int) -> OWord:
    """The label and keyword of the O-word whose 'O' is at ``p``."""
    n = len(code)
    col = p
    computed = None
    q = skip_blanks(code, p + 1)
    if q < n and code[q] in "[#":
        # O[#2 * 10] call, o#<sub> call: LinuxCNC's read_integer_value
        computed, label = q, ""
        q = _value_end(state, code, q, i)
    else:
        label, q = _o_label(state, code, p, i)
    q = skip_blanks(code, q)
    if q >= n:
        if computed is not None:
            raise state.error("an O-word label computed from a parameter or expression is "
                              "read with call only", col, i)
        # a program number, or a Fanuc subprogram's head (O1234, O<name>)
        return OWord(label, None, col, q)
    k = _O_KEYWORD.match(code, q).end()
    keyword = code[q:k].lower()
    spaced = _O_SPACED.match(code, q) if keyword not in O_KEYWORDS else None
    if spaced is not None:
        k = spaced.end()
        keyword = "".join(spaced.group().split()).lower()
    if keyword not in O_KEYWORDS:
        if not keyword:
            raise state.error(f"unexpected {code[q]!r} after {olabel(label)}: a program number "
                              "O-word must be alone on its line, a control O-word needs a "
                              "keyword (sub, call, if, while, ...)", q, i)
        hint = (f" (a program number {olabel(label).upper()} must be alone on its line)"
                if label.isdigit() else "")
        raise state.error(f"unknown O-word keyword {keyword!r}{hint}: use sub, endsub, call, "
                          "if, elseif, else, endif, do, while, endwhile, repeat, endrepeat, "
                          "break, continue or return", q, i)
    if computed is not None and keyword != "call":
        raise state.error(f"an O-word label computed from a parameter or expression is read "
                          f"with call only, not with {keyword}: write its number", col, i)
    return OWord(label, keyword, col, k, computed)


def _value_end(state: GCodeState, code: str, q: int, i: int) -> int:
    """The end of the parameter reference or bracketed expression at ``q``
    (not evaluated: that happens at the call)."""
    n = len(code)
    while q < n and code[q] == "#":
        q = skip_blanks(code, q + 1)
    if q < n and code[q] == "<":
        end = code.find(">", q)
        if end < 0:
            raise state.error("parameter name has no closing '>'", q, i)
        return end + 1
    if q < n and code[q] == "[":
        depth = 0
        for k in range(q, n):
            depth += {"[": 1, "]": -1}.get(code[k], 0)
            if depth == 0:
                return k + 1
        raise state.error("O-word label expression has no closing ']'", q, i)
    number = _O_NUMBER.match(code, q)
    if not any(ch.isdigit() for ch in number.group()):
        raise state.error("O-word needs a number or a <name>, e.g. o100 or o<part>", q, i)
    return number.end()


def _o_label(state: GCodeState, code: str, p: int, i: int) -> tuple[str, int]:
    """The label after the 'O' at ``p`` (a number, or a lower-cased ``<name>``
    without blanks) and the position after it."""
    q = skip_blanks(code, p + 1)
    if q < len(code) and code[q] == "<":
        end = code.find(">", q)
        if end < 0:
            raise state.error("O-word name has no closing '>'", q, i)
        label = "".join(code[q + 1:end].split()).lower()
        if not label:
            raise state.error("empty O-word name '<>'", q, i)
        return label, end + 1
    number = _O_NUMBER.match(code, q)
    digits = "".join(ch for ch in number.group() if ch.isdigit())
    if not digits:
        raise state.error("O-word needs a number or a <name>, e.g. o100 or o<part>", p, i)
    return str(int(digits)), number.end()


def program_span(state: GCodeState) -> tuple[int, int]:
    """Lines ``[first, end)`` (0-based) that form the program (``%`` handling):
    a ``%`` line before any code opens the program and the next one ends it;
    without an opening ``%``, a ``%`` line ends the program."""
    first = 0
    n = len(state.lines)
    for i in range(n):
        lx = lex(state, i)
        if lx.percent:
            first = i + 1
            break
        if lx.first is not None:
            break
    for j in range(first, n):
        if "%" in state.lines[j] and lex(state, j).percent:
            return first, j
    return first, n


def read_number(state: GCodeState, code: str, p: int, letter: str) -> tuple[float, int]:
    """A literal number at ``p`` (sign, digits, one point; blanks allowed
    inside) and the position after it; ``letter`` names the word in errors."""
    m = _NUMBER.match(code, p)
    if m is not None:
        value = float(m.group())
        if math.isfinite(value):
            return value, m.end()
    n = len(code)
    start = p
    chars = []
    if code[p] in "+-":
        chars.append(code[p])
        p = skip_blanks(code, p + 1)
    dots = 0
    digits = 0
    while p < n:
        ch = code[p]
        if ch.isdigit():
            chars.append(ch)
            digits += 1
        elif ch == ".":
            dots += 1
            if dots > 1:
                raise ExprError(f"number with two decimal points after {letter}", p)
            chars.append(ch)
        elif ch == " " or ch == "\t":
            # RS274NGC ignores blanks: "X1 0" is X10, but not across another
            # word or a comment (comments are blanked in ``code``).
            q = skip_blanks(code, p)
            original = state.lines[state.line_no]
            if q < n and (code[q].isdigit() or code[q] == ".") and \
                    original[p:q].strip(" \t") == "":
                p = q
                continue
            break
        else:
            break
        p += 1
    if not digits:
        raise ExprError(f"{letter} word has no value: write a number after {letter}", start)
    value = float("".join(chars))
    if not math.isfinite(value):
        raise ExprError(f"number after {letter} is too large", start)
    return value, p
