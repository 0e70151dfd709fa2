"""The fast paths of the PMAC reader read what statement-by-statement reading
reads (issue 34: reading 100,000 lines <= 0.4 s).

A straight move line (``[LINEAR|RAPID] [X..] [Y..] [Z..]``) is run by
``ccopt.program.pmac.straight.run_straight`` (runs of them in one loop, the
common spelling matched by ``AXES_LINE_RE`` first), a plain line (modes,
``CC0``-``CC2``, axis and ``F`` words with literal numbers) by
``Interpreter.plain_line``, any other
line statement by statement. Switching the fast paths off, one after the
other, must leave the Program unchanged: every block field, the meta and
every error message with its file:line:col. The blocks of a move are built
by ``ccopt.program.blocks.new_block``, and those of a run of straight moves
field by field for the whole run, without ``Block.__init__``: they must be
the blocks ``Block(...)`` makes.
"""
from __future__ import annotations

import re
from dataclasses import fields

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program.model import Block, Modal, Motion, Source
from ccopt.program.pmac import read_pmac, statements
from ccopt.program.blocks import new_block
from ccopt.program.pmac.lexer import split_lines
from ccopt.program.pmac.statements import Interpreter

NEVER = re.compile(r"(?!)")


def _outcome(text: str, start=(0.0, 0.0, 0.0)):
    """Everything a read gives, compared by ``repr`` (so that -0.0 is not 0.0)."""
    try:
        prog = read_pmac(text, "e.pmc", start=start)
    except ProgramError as err:
        return ("error", str(err), err.args)
    return ("program", repr(prog.blocks), repr(prog.meta), prog.start)


def _outcomes(text: str, start=(0.0, 0.0, 0.0)):
    """The outcome with every path, without the straight path, and statement by
    statement; the first also without the axes-line pattern (its lines left
    to ``STRAIGHT_LINE_RE``), which must give the same."""
    with pytest.MonkeyPatch.context() as mp:
        fast = _outcome(text, start)
        mp.setattr(statements, "AXES_LINE_RE", NEVER)
        assert _outcome(text, start) == fast
        mp.setattr(statements, "STRAIGHT_LINE_RE", NEVER)
        plain = _outcome(text, start)
        mp.setattr(statements, "PLAIN_LINE_RE", NEVER)
        general = _outcome(text, start)
    return fast, plain, general


BLANKS = st.sampled_from(["", "", " ", "\t", "  "])
DIGITS = st.one_of(
    st.decimals(min_value=-2000, max_value=2000, places=4, allow_nan=False,
                allow_infinity=False).map(lambda d: f"{d:f}"),
    st.integers(-10**7, 10**7).map(str),
    st.sampled_from(["0", "-0", "+0", ".5", "-.25", "7.", "00012.50", "999999.9999",
                     "1000000", "-1000000", "1000000.0001", "9" * 400]))


@st.composite
def axis_word(draw, letter: str) -> str:
    number = draw(DIGITS)
    sign, digits = (number[0], number[1:]) if number[0] in "+-" else ("", number)
    return draw(BLANKS) + letter + draw(BLANKS) + sign + draw(BLANKS) + digits


@st.composite
def straight_line(draw) -> str:
    """A line the straight path takes when its numbers are in range."""
    head = draw(st.sampled_from(["", "", "LINEAR", "LIN", "RAPID", "RPD"]))
    axes = [a for a in "XYZ" if draw(st.booleans())] or [draw(st.sampled_from("XYZ"))]
    words = "".join(draw(axis_word(a)) for a in axes)
    tail = draw(st.sampled_from(["", "", " ", " ; note", " ;ccopt: air", "\t"]))
    return draw(BLANKS) + head + draw(BLANKS) + words + tail


#: Lines that change what a straight line does, or that it must leave alone.
OTHER_LINES = st.sampled_from([
    "INC", "ABS", "INC(X)", "ABS(Y,Z)", "F20", "TM50", "F(P1*2)", "CCR2", "CC1", "CC0",
    "CIRCLE1 X1 Y1 I1 J0", "CIRCLE2", "LINEAR", "P1=3", "X(P1) Y1", "Y2 X1", "X1 X2",
    "X1 Y2 F5", "X1 Y2 M5", "DWELL5", "NORMAL J-1", "NORMAL K-1", "RAPID Z5", ""])


@st.composite
def programs(draw) -> str:
    head = draw(st.sampled_from(["F10\n", "F10 CCR1.5 CC1\n", "TM100\n", "", "INC F10\n",
                                 "CLOSE\nOPEN PROG 2 CLEAR\nF4\n"]))
    lines = draw(st.lists(st.one_of(straight_line(), straight_line(), OTHER_LINES),
                          min_size=1, max_size=12))
    text = head + "\n".join(lines) + ("\nCLOSE\n" if "OPEN" in head else "\n")
    if draw(st.booleans()):
        text = text.lower()
    if draw(st.booleans()):
        text = text.replace("\n", "\r\n")
    return text


@settings(max_examples=200, deadline=None)
@given(programs(), st.sampled_from([(0.0, 0.0, 0.0), (1.5, -2.0, 0.25),
                                    (999999.0, -999999.5, 999999.5)]))
def test_fast_paths_read_as_statements(text, start):
    fast, plain, general = _outcomes(text, start)
    assert fast == general
    assert plain == general


@pytest.mark.parametrize("text, start", [
    ("INC F10\nX600000 Y1\nX600000\n", (0.0, 0.0, 0.0)),   # the end leaves +-1e6 on X
    ("INC F10\nY600000\nRPD Y600000\n", (0.0, 0.0, 0.0)),
    ("INC F10\nY-600000\nRPD Y-600000\n", (0.0, 0.0, 0.0)),
    ("INC F10\nZ.5 Y1\nZ999999.9\n", (0.0, 0.0, 0.0)),
    ("F10\nX1000000 Y-1000000 Z1000000\nINC X-0 Y0\n", (0.0, 0.0, 0.0)),
    # a word beyond +-1e6 whose incremental end is within
    ("INC F10\nY1000000.0001\n", (0.0, -999999.5, 0.0)),
    ("INC F10\nX-1000000.5 Z1\n", (999999.5, 0.0, 0.0)),
    # INC and ABS per axis
    ("INC(X) F10\nX1 Y2\nX1 Y2 Z3\nINC(Z) ABS(X)\nX1 Y2 Z3\nX1 Z3\n", (0.5, 0.5, 0.5)),
    ("INC(Y) TM20\nRAPID X1 Y2\nLINEAR X1 Y2\n", (0.0, 0.0, 0.0)),
    # feed or move time: the one programmed last
    ("F10 TM20\nX1 Y2\nF5\nX2\nTM30 X3\nX4\n", (0.0, 0.0, 0.0)),
])
def test_fast_paths_at_the_bound_and_per_axis(text, start):
    fast, plain, general = _outcomes(text, start)
    assert fast == plain == general


def test_straight_line_is_taken_and_refused():
    run = Interpreter("e.pmc", (0.0, 0.0, 0.0), {"ignored": [], "delay_blocks": []})
    assert not run.straight_line(1, "X1 Y2")           # no feed yet: an error, left to the rest
    run.feed = 10.0
    assert run.straight_line(2, " LINEAR X1 Y - 2.5")
    assert run.blocks[-1].end == (1.0, -2.5, 0.0) and run.blocks[-1].source.col == 9
    for line in ["Y1 X2", "X1 X2", "X1 I1", "X1 F5", "CIRCLE1 X1", "X" + "9" * 400,
                 "X1000000.1", "X(1)", "LINEAR", "", "X1 M5"]:
        assert not run.straight_line(3, line), line
    assert len(run.blocks) == 1


def test_new_block_is_the_dataclass_block():
    modal = Modal(side=1, radius=2.0, accel_time=0.05)
    args = dict(motion=Motion.ARC_CW, start=(0.0, 1.0, 2.0), end=(3.0, -4.0, 2.0), modal=modal,
                center=(1.0, 1.0, 2.0), feed=12.5, move_time=None, mcodes=(5, 8), surface="air")
    made = new_block("f.pmc", 7, 3, **args)
    expected = Block(source=Source("f.pmc", 7, 3), **args)
    assert made == expected and hash(made) == hash(expected)
    assert type(made) is Block and type(made.source) is Source
    for f in fields(Block):
        assert getattr(made, f.name) == getattr(expected, f.name), f.name


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="aX1;\r\n \t", max_size=30))
def test_split_lines_line_by_line(text):
    """``split_lines`` cuts the text as one would line by line: one CR before
    the line end goes, then the comment from ``;``."""
    expected = []
    for n, line in enumerate(text.split("\n"), start=1):
        if line.endswith("\r"):
            line = line[:-1]
        expected.append((n, line.split(";", 1)[0].upper()))
    assert split_lines(text, "f") == expected


def test_straight_run_blocks_are_the_dataclass_blocks():
    """The blocks of a run of straight lines (mode changes, markers, feed and
    move time within it) have every field set, and are the blocks ``Block``
    makes of those fields."""
    text = ("F10 CCR1 CC1\nX1 Y2 ; ccopt: air\nRAPID Z3\nLINEAR X-0\nY-1.5 Z.5\n\n"
            "TM20\nX2\n LINEAR Y 3\n")
    prog = read_pmac(text, "s.pmc")
    assert [b.source.line for b in prog.blocks] == [2, 3, 4, 5, 8, 9]
    assert [b.source.col for b in prog.blocks] == [1, 7, 8, 1, 1, 9]
    assert [b.surface for b in prog.blocks] == ["air", None, None, None, None, None]
    assert [b.feed for b in prog.blocks] == [10.0, None, 10.0, 10.0, None, None]
    assert [b.move_time for b in prog.blocks] == [None] * 4 + [0.02, 0.02]
    for block in prog.blocks:
        expected = Block(**{f.name: getattr(block, f.name) for f in fields(Block)})
        assert type(block) is Block and type(block.source) is Source
        assert block == expected and hash(block) == hash(expected)
        assert repr(block) == repr(expected)
    assert repr(prog.blocks[2].end) == "(-0.0, 2.0, 3.0)"
