"""Plain PMAC lines (move modes, CC0/CC1/CC2, axis and F words with literal
numbers) are run from one regular-expression tokenizer (issue 17): they read
to the blocks and errors that statement-by-statement reading gives, and to the
figures worked out here."""
from __future__ import annotations

import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program.model import Motion
from ccopt.program.pmac import read_pmac, statements
from ccopt.program.pmac.lexer import KEYWORDS, keyword_at, split_lines

HEAD = "F10 CCR1\n"


def _statement_by_statement(monkeypatch, text: str):
    """``read_pmac`` with the plain-line tokenizer switched off: every line
    goes through ``Interpreter.statement``."""
    with monkeypatch.context() as m:
        m.setattr(statements, "PLAIN_LINE_RE", re.compile(r"(?!)"))
        return _outcome(text)


def _outcome(text: str):
    try:
        prog = read_pmac(text, "p.pmc")
    except ProgramError as err:
        return ("error", str(err))
    return ("blocks", [(b.source.line, b.source.col, b.motion, b.start, b.end, b.center,
                        b.feed, b.modal.side, b.modal.radius) for b in prog.blocks])


def test_plain_lines_figures():
    # F10 is 10 units/s (Isx90 = 1000 ms); INC(R) centre = start + (I, J)
    prog = read_pmac(HEAD + "LINEAR X3 Y4\nCIRCLE1 X6 Y7 I3 J0\nCC1 LINEAR X-1.5 Y .5\n"
                     "RPD X 0 Y - 2\n", "p.pmc")
    b = prog.blocks
    assert [x.motion for x in b] == [Motion.LINE, Motion.ARC_CW, Motion.LINE, Motion.RAPID]
    assert b[0].end == (3.0, 4.0, 0.0) and b[0].feed == 10.0
    assert b[1].center == (6.0, 4.0, 0.0) and b[1].end == (6.0, 7.0, 0.0)
    assert b[2].end == (-1.5, 0.5, 0.0) and b[2].modal.side == 1 and b[2].modal.radius == 1.0
    assert b[1].modal.side == 0
    assert b[3].end == (0.0, -2.0, 0.0) and b[3].feed is None
    # the column of a move is its first axis word's: "CC1 LINEAR X-1.5" -> column 12
    assert (b[2].source.line, b[2].source.col) == (4, 12)


@pytest.mark.parametrize("line, message", [
    ("LINEAR X1 X2", "p.pmc:2:11: X is written twice in one move"),
    ("X2000000000", "p.pmc:2:1: X2e+09 is out of range"),
    ("X" + "9" * 400, "p.pmc:2:2: X: number too large"),
    ("F0 X1", "p.pmc:2:1: F0: the feedrate must be positive"),
    ("CIRCLE1 X1 Y1", "p.pmc:2:9: CIRCLE1 move without a centre"),
    ("LINEAR X1 I1", "p.pmc:2:8: I/J/K or R on a LINEAR move"),
    ("I1 J1", "p.pmc:2:1: a centre vector or radius without an end point"),
])
def test_plain_line_errors(line, message):
    with pytest.raises(ProgramError) as err:
        read_pmac(HEAD + line + "\n", "p.pmc")
    assert str(err.value).startswith(message)


WORDS = st.sampled_from(["LINEAR", "LIN", "CIRCLE1", "CIR2", "RAPID", "RPD", "CC0", "CC1",
                         "CC2", "X", "Y", "Z", "I", "J", "K", "R", "F"])
NUMBERS = st.sampled_from(["1", "-2.5", "+.5", " 3", "- 4", "0", "7.", "2000000000", "-0",
                           "9" * 400, ""])
SPACES = st.sampled_from(["", " ", "\t", "  "])


@st.composite
def plain_programs(draw):
    lines = []
    for _ in range(draw(st.integers(1, 6))):
        words = draw(st.lists(st.tuples(SPACES, WORDS, NUMBERS), min_size=0, max_size=5))
        lines.append("".join(sp + w + (n if len(w) == 1 else "") for sp, w, n in words))
    return HEAD + "\n".join(lines) + "\n"


@settings(max_examples=150, deadline=None)
@given(plain_programs())
def test_plain_lines_read_as_statements(text):
    with pytest.MonkeyPatch.context() as mp:
        assert _outcome(text) == _statement_by_statement(mp, text)


def test_keyword_at_is_longest_prefix():
    for text in ["CIRCLE1X", "CIR1", "CC1", "CCR2", "LINEARX", "LINX", "RETURN", "RET",
                 "DWELL5", "DWE5", "TSEL", "TS5", "ENDWHILE", "ENDW", "X1"]:
        longest = max((k for k in KEYWORDS if text.startswith(k)), key=len, default=None)
        assert keyword_at(text, 0) == longest


def test_split_lines_cuts_comments_and_cr():
    text = "x1 ;a\r\nY2\r\n;c\nz3\r\r\nq\r;x"
    assert split_lines(text, "f") == [(1, "X1 "), (2, "Y2"), (3, ""), (4, "Z3\r"), (5, "Q\r")]
