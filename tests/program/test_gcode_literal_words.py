"""The G-code reader's quick road for lines of letters and literal numbers
(``codes._literal_words``) reads what its general loop reads: generated
programs of such lines, with blanks, lower case, signs, leading points,
numbers with blanks inside, repeated letters, values out of range and
words ccopt does not know, read with the quick road and without it, give
the same blocks, or the same located error."""
from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program import read_text
from ccopt.program.gcode import codes

_BLANK = st.sampled_from(["", "", " ", "  ", "\t"])
# mostly what CAM writes; now and then a form only the general loop reads
# (blanks inside a number, a sign apart from its digits) or an error (two
# points, a value out of range)
_CLEAN = ["0", "1", "2.5", "10.", ".5", "007", "12.3456", "99999"]
_ODD = ["1 0", "2. 5", "1e3", "1.2.3", "3" * 12]
_DIGITS = st.sampled_from(_CLEAN * 24 + _ODD)
_SIGN = st.sampled_from([""] * 8 + ["-"] * 4 + ["+", "- ", "--"])


@st.composite
def _word(draw, letter):
    letter = letter.lower() if draw(st.booleans()) and draw(st.booleans()) else letter
    return f"{letter}{draw(_BLANK)}{draw(_SIGN)}{draw(_DIGITS)}{draw(_BLANK)}"


@st.composite
def _program(draw):
    head = draw(st.sampled_from(["G21 G17 G90", "G20 G91", "G21 G90 G18"]))
    lines = [head, "F600", "G0 X1 Y1"]
    for _ in range(draw(st.integers(1, 12))):
        letters = draw(st.sampled_from(["XY"] * 8 + ["XYZ"] * 3 + ["XYF"] * 3 + [
            "XYIJ", "XYR", "XYQ", "XYN", "XYH"]))
        arcs = ["G2", "G3", "g03"] if "IJ" in letters or "R" in letters else []
        motion = draw(st.sampled_from(["", "", "G1", "G0", "g1 ", "G01", *arcs]))
        chosen = draw(st.permutations(letters))[:draw(st.integers(1, len(letters)))]
        if draw(st.integers(0, 39)) == 0:
            chosen = [*chosen, chosen[0]]                # now and then a letter twice
        words = [draw(_word(a)) for a in chosen]
        lines.append(draw(_BLANK) + motion + draw(_BLANK) + "".join(words))
    lines.append("M2")
    return "\n".join(lines) + "\n"


def _read(text):
    try:
        return read_text(text, "lit.ngc", "gcode").blocks
    except ProgramError as exc:
        return str(exc)


@settings(max_examples=300, deadline=None)
@given(_program())
def test_quick_road_reads_what_the_general_loop_reads(text):
    quick = _read(text)
    saved = codes._literal_words
    codes._literal_words = lambda *args: None
    try:
        general = _read(text)
    finally:
        codes._literal_words = saved
    assert quick == general
