"""G-code comments are blanked by regular expressions (issue 17: no reading
character by character): the same text and errors as the RS274NGC rule read
one character at a time, written out here as the reference."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import blank_comments
from ccopt.program.model import MESSAGES


def _reference(text: str):
    """RS274NGC comments, character by character: ``(`` to ``)`` (not nested)
    and ``;`` to the end become blanks; outside them only printable ASCII
    and tabs. ``(blanked text, None)`` or ``(None, (column, message start))``."""
    out = list(text)
    opened = -1
    for k, ch in enumerate(text):
        if opened >= 0:
            out[k] = " "
            if ch == ")":
                opened = -1
            elif ch == "(":
                return None, (k, "'(' inside a comment")
        elif ch == "(":
            opened = k
            out[k] = " "
        elif ch == ";":
            out[k:] = " " * (len(text) - k)
            break
        elif not (ch == "\t" or " " <= ch <= "~"):
            return None, (k, f"character {ch!r}")
    if opened >= 0:
        return None, (opened, "unterminated comment")
    return "".join(out), None


def _blanked(text: str):
    state = GCodeState(text, "c.ngc", None, (0.0, 0.0, 0.0))
    try:
        return blank_comments(state, text, 0), None
    except ProgramError as err:
        return None, (err.col - 1, err.message)


@pytest.mark.parametrize("text, expected", [
    ("G1 X1 (feed) Y2", "G1 X1        Y2"),
    ("G1 X1 ; rest (x", "G1 X1          "),
    ("(a;b) X1 (c)", "      X1    "),
    ("\tX1", "\tX1"),
])
def test_comments_become_blanks(text, expected):
    assert _blanked(text) == (expected, None)


@pytest.mark.parametrize("text, col, start", [
    ("G1 X1 (oops F60", 6, "unterminated comment"),
    ("X1 (a (b)", 6, "'(' inside a comment"),
    ("X1 é (c)", 3, "character 'é'"),
    ("(c) X\x001", 5, "character '\\x00'"),
])
def test_comment_errors(text, col, start):
    got, err = _blanked(text)
    assert got is None and err[0] == col and err[1].startswith(start)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(["(", ")", ";", "X1", " ", "\t", "é", "\x00", "~", "a"]),
                max_size=12).map("".join))
def test_comments_as_character_by_character(text):
    got, err = _blanked(text)
    ref, ref_err = _reference(text)
    assert got == ref
    if ref_err is not None:
        assert err[0] == ref_err[0] and err[1].startswith(ref_err[1])


def test_abort_comment_stops_and_an_unset_parameter_prints_hashes():
    # LinuxCNC's convert_comment: leading blanks, the word in any case, then the
    # comma at once ("abort ," is a plain comment)
    prog = read_gcode("G21\nG0 X1 (abort is only a word here) (abort , nor here)\nM2\n")
    assert prog.blocks[-1].end[0] == 1.0
    with pytest.raises(ProgramError, match=r"\(abort\) at 7\.000000, ###### is ######") as err:
        read_gcode("G21\n#1 = 7\nG0 X1\n( ABORT, at #1, #<nope> is #<nope>)\nG0 X2\nM2\n")
    assert (err.value.line, err.value.col) == (4, 1)


def test_active_comments_only_in_parentheses_before_a_semicolon():
    """`; (abort, x)` is part of a `;` comment, so it does nothing; the first
    (msg, ...) of a line is its message; a position parameter is read-only."""
    prog = read_gcode("G21\nG0 X1 ; (abort, not this)\n(note) (msg, first) (msg, second)\n"
                      "G0 X2\nM2\n")
    assert prog.blocks[-1].end[0] == 2.0
    assert [m["text"] for m in prog.meta[MESSAGES]] == [" first"]
    with pytest.raises(ProgramError, match=r"read-only parameter #<_x>: it is the current"):
        read_gcode("G21\n#<_x> = 3\nM2\n")


def test_print_comments_carry_parameter_values_and_5599_silences_debug():
    """LinuxCNC's convert_comment: ``(print,...)`` goes to rs274's standard
    output with parameters replaced (%f, six decimals); ``(debug,...)`` is a
    MESSAGE only while #5599 > 0 (1 at start)."""
    prog = read_gcode("G21\n#1 = 2.5\n(PRINT,one #1)\n(debug, a)\n#5599 = 0\n(debug, b)\n"
                      "(msg, c)\n#5599 = 1\n(debug, d)\nM2\n")
    assert [(m["kind"], m["text"]) for m in prog.meta[MESSAGES]] == [
        ("print", "one 2.500000"), ("debug", " a"), ("msg", " c"), ("debug", " d")]


def test_message_formats_line_number_and_near_zero_values():
    """LinuxCNC's convert_param_comment: %d, %f and %.Nf set the format of the
    values after them (0, 4, N decimals); a value within 1e-4 of 0 prints as
    0; #<_line> is the line being executed (worked out from the text)."""
    prog = read_gcode("G21\n#1 = 1.1234567\n#2 = -0.00001\n"
                      "(debug,a #1 %d#1 %f#1 %.7f#1 #2 100%)\n(debug,line #<_line>)\nM2\n")
    assert [m["text"] for m in prog.meta[MESSAGES]] == [
        "a 1.123457 1 1.1235 1.1234567 0.0000000 100%", "line 5.000000"]


def test_position_parameters_of_the_rotary_axes():
    # A in degrees: A40 is programmed (work), machine = 40 + G54's A origin
    # (#5224 = 10) = 50
    prog = read_gcode("G21\nG0 X1 A40\n(debug,#5423 #5024 #<_a> #<_abs_a>)\nM2\n",
                      parameters={5224: 10.0})
    assert prog.meta[MESSAGES][0]["text"] == "40.000000 50.000000 40.000000 50.000000"
