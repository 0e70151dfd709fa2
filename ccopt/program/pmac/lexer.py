"""Lexing PMAC text: lines without comments, command words, constants.

PMAC is case-insensitive and ignores spaces; a comment runs from ``;`` to the
end of the line. The reader works on upper-case lines without comments and
looks words up here: the keyword tables (longest spelling first, so that
``CIRCLE1`` wins over ``CIR1`` and ``CC1`` over ``CC``), the axis letters and
the constant forms (decimal ``10``, ``.5``, hexadecimal ``$1F``).
"""
from __future__ import annotations

import math
import re

from ccopt.errors import ProgramError
from ccopt.program.expr import ExprError

#: Axes ccopt carries, in (x, y, z) order.
AXES = "XYZ"
#: Axes PMAC knows that ccopt does not carry (an error on a move).
OTHER_AXES = "ABCUVW"
#: Components of a circle's centre vector, in (x, y, z) order.
VECTORS = "IJK"

#: Move-mode spellings -> the mode.
MOVE_MODES = {
    "LINEAR": "LINEAR", "LIN": "LINEAR",
    "CIRCLE1": "CIRCLE1", "CIR1": "CIRCLE1",
    "CIRCLE2": "CIRCLE2", "CIR2": "CIRCLE2",
    "RAPID": "RAPID", "RPD": "RAPID",
}
#: Move modes ccopt does not read.
UNSUPPORTED_MODES = {"SPLINE1", "SPLINE2", "SPL1", "SPL2", "PVT"}
#: Commands ccopt does not read (ProgramError naming them).
UNSUPPORTED = {
    # flow and subroutines
    "GOTO", "GOSUB", "CALL", "IF", "WHILE", "ELSE", "ENDIF", "ENDI", "ENDWHILE", "ENDW",
    "AND", "OR", "STOP", "WAIT", "PRELUDE",
    # I/O and misc
    "READ", "PSET", "HOME", "HOMEZ", "CMD", "COMMAND", "SEND", "SENDS", "SENDP", "SENDC",
    "DISPLAY", "DISP", "ENABLE", "DISABLE", "LOCK", "UNLOCK", "SETPHASE",
    "BLOCKSTART", "BSTART", "BLOCKSTOP", "BSTOP", "NOFRAX", "ADDRESS",
    # transformations, 3-D compensation
    "TSEL", "TINIT", "ADIS", "IDIS", "AROT", "IROT", "NX", "NY", "NZ", "TR", "TX", "TY", "TZ",
}
#: Every multi-letter command word, longest first (a word is matched by prefix).
KEYWORDS = sorted(
    set(MOVE_MODES) | UNSUPPORTED_MODES | UNSUPPORTED | {
        "ABS", "INC", "DWELL", "DWE", "DELAY", "DLY", "NORMAL", "NRM", "FRAX",
        "RETURN", "RET", "CCR", "CC0", "CC1", "CC2", "CC3", "CC4", "TA", "TS", "TM",
        "OPEN", "CLOSE", "CLEAR", "DEFINE", "DELETE", "UNDEFINE",
    },
    key=len, reverse=True)
UNSUPPORTED_WHY = ("ccopt reads straight-line motion programs: no jumps, loops, "
                   "conditions, subroutine calls, I/O or coordinate transformations")

#: ``P1=``, ``I15=``, ``M1==``, ``M1->``: a variable assignment or definition.
ASSIGN_RE = re.compile(r"([PQIM])(\d+)[ \t]*(==|=|->)")
#: ``P(`` / ``Q(``: an indirect variable reference.
INDIRECT_RE = re.compile(r"([PQ])[ \t]*\(")
#: ``P12``, ``Q3``, ``I15``, ``M7``: a variable read.
VAR_RE = re.compile(r"([PQIM])(\d+)")
LETTERS_RE = re.compile(r"[A-Z]+")
#: The longest command word at a position: an alternation in the order of
#: :data:`KEYWORDS` (longest first), which a regular expression tries in order.
KEYWORD_RE = re.compile("|".join(re.escape(kw) for kw in KEYWORDS))
#: One statement of a plain move line: a move-mode or ``CC0``/``CC1``/``CC2``
#: word (group 1), or ``X Y Z I J K R F`` with a signed literal number (groups
#: 2, 3, 4; blanks as :meth:`~ccopt.program.pmac.variables.Variables.data`
#: allows them).
PLAIN_STATEMENT_RE = re.compile(
    r"[ \t]*(?:(LINEAR|LIN|CIRCLE1|CIR1|CIRCLE2|CIR2|RAPID|RPD|CC0|CC1|CC2)"
    r"|([XYZIJKRF])[ \t]*([-+]?)[ \t]*(\d+\.?\d*|\.\d+))")
#: Statements a plain line may hold (``CIRCLE1 X Y Z I J F`` is 7).
PLAIN_STATEMENTS = 8


def _plain_line_re(slots: int) -> re.Pattern:
    """A line of up to ``slots`` :data:`PLAIN_STATEMENT_RE` statements, each
    in its own four groups (statement ``k`` from 0: groups ``4k+1 .. 4k+4``,
    ``None`` past the last): one match reads the whole line, where a match per
    statement cost twice as much (a line is made of statements alone in one
    way only: each starts with a letter, and no number holds one)."""
    pattern = ""
    for _ in range(slots):
        pattern = "(?:" + PLAIN_STATEMENT_RE.pattern + pattern + ")?"
    return re.compile(pattern + r"[ \t]*")


#: A plain move line (:func:`_plain_line_re`): any other line, or a longer
#: one, is run statement by statement.
PLAIN_LINE_RE = _plain_line_re(PLAIN_STATEMENTS)
#: A straight move line, the most common plain line: ``LINEAR``/``RAPID`` (or
#: neither) and then ``X``, ``Y``, ``Z`` words, in this order, each at most
#: once, with literal numbers: groups mode, then letter, sign, digits of X, Y
#: and Z (``None`` when not written). The quantifiers inside a word are
#: possessive (``*+``, 15 % faster): what they would give back, blanks or
#: digits, nothing after them could match.
STRAIGHT_LINE_RE = re.compile(
    r"[ \t]*(?:(LINEAR|LIN|RAPID|RPD)[ \t]*)?"
    + "".join(rf"(?:({a})[ \t]*+([-+]?)[ \t]*+(\d++\.?\d*+|\.\d++)[ \t]*+)?" for a in AXES))
#: A straight move line as CAM writes it, a subset of :data:`STRAIGHT_LINE_RE`
#: with fewer groups and choices, tried first: ``X``, ``Y``, ``Z`` words from the first column,
#: in this order, each at most once, the sign right before the digits, one
#: blank or none after each word: groups the signed numbers of X, Y and Z
#: (``None`` when not written). Possessive throughout: the blank after a
#: number, if given back, could start nothing that follows.
AXES_LINE_RE = re.compile("".join(
    rf"(?:{a}([-+]?(?:\d++\.?\d*+|\.\d++)) ?+)?+" for a in AXES))
HEX_RE = re.compile(r"\$([0-9A-F]+)")
NUMBER_RE = re.compile(r"(\d+\.?\d*|\.\d+)")
_WORD_RE = re.compile(r"[A-Z][A-Z0-9]*")
#: A comment: ``;`` to the end of the line.
_COMMENT_RE = re.compile(r";[^\n]*")


def split_lines(text: str, file: str) -> list[tuple[int, str]]:
    """``(1-based line number, upper-case text without its comment)`` for every line."""
    if not isinstance(text, str):
        raise ProgramError("program text must be a str", file, None)
    if "\r" in text:
        # the CR of a CR LF line end (one, as a line's last character), first:
        # in a comment or not, it goes, and the comment ends at the LF anyway
        text = text.replace("\r\n", "\n")
        if text.endswith("\r"):
            text = text[:-1]
    if ";" in text:
        # two passes, each a plain search: one regex for both scanned 4 times slower
        text = _COMMENT_RE.sub("", text)
    return list(enumerate(text.upper().split("\n"), start=1))


def skip(text: str, pos: int) -> int:
    """The first position at or after ``pos`` that is not a blank."""
    while pos < len(text) and text[pos] in " \t":
        pos += 1
    return pos


def word(text: str, pos: int) -> str:
    """The word (a letter, then letters and digits) at ``pos``, for messages."""
    m = _WORD_RE.match(text, pos)
    return m.group(0) if m else ""


def keyword_at(text: str, pos: int) -> str | None:
    """The longest command word of :data:`KEYWORDS` that starts at ``pos``."""
    m = KEYWORD_RE.match(text, pos)
    return m.group(0) if m else None


def hex_value(digits: str, pos: int) -> float:
    """Value of the hexadecimal constant ``$digits``; :class:`ExprError` at ``pos``."""
    try:
        value = float(int(digits, 16))
    except OverflowError:
        raise ExprError(f"${digits}: hexadecimal constant too large", pos) from None
    if not math.isfinite(value):  # pragma: no cover - float(int) raises instead
        raise ExprError(f"${digits}: hexadecimal constant too large", pos)
    return value
