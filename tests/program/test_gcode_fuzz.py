"""Property-based: whatever the text, read_gcode returns a sound Program or raises
a located ProgramError, and nothing else escapes."""
from __future__ import annotations

import math
import re
from unittest import mock

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program import gcode
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion, Program

SETTINGS = settings(max_examples=300, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

TOKENS = (list("GXYZIJKRFPDMNOTSHQEL0123456789.-+*/[]#<>=()%; \t\n")
          + ["G0", "G1", "G2", "G3", "G4", "G17", "G18", "G19", "G20", "G21", "G40", "G41",
             "G42", "G41.1", "G42.1", "G90", "G91", "G93", "G94", "G90.1", "G136", "G137",
             "M2", "M6", "o1", "o<a>", " sub", " endsub", " call", " if", " elseif", " else",
             " endif", " do", " while", " endwhile", " repeat", " endrepeat", " break",
             " continue", " return", " MOD ", " EQ ", " LT ", "SIN", "ATAN", "SQRT", "#1",
             "#<x>", "X10", "Y-5", "I5", "J5", "R5", "R-5", "F60", "P2", "D3", "\n"])

SEEDS = [
    """%
O1000 (seed)
G21 G17 G90 G94
F600
#1 = 2
G0 X0 Y0 Z1
G1 Z-1
G41.1 D[#1 * 2] G1 X10 Y0
G3 X20 Y10 I0 J10
G2 X30 Y0 R10
G40 G1 X40
G18 G2 X50 Z-1 I5 K0
G17 G93 G1 X0 Y0 F2
G94 F100
M2
%
""",
    """o<sq> sub
  G91 G1 X#1 F60
  Y#1
  X-#1
  Y-#1
  G90
  o<sq> return [#1 * 4]
o<sq> endsub
#2 = 1
o1 while [#2 LE 3]
  o<sq> call [#2]
  o2 if [#<_value> GT 8]
    o1 break
  o2 elseif [#2 EQ 1]
    G4 P0.5
  o2 else
    G0 Z1
  o2 endif
  #2 = [#2 + 1]
o1 endwhile
o3 do
  #2 = [#2 - 1]
  G1 X#2 F120
o3 while [#2 GT 0]
o4 repeat [2]
  G2 X0 Y0 I1 J0 P2 F60
o4 endrepeat
""",
    """O0 sub (#1=radius)
F100
G0 X-100.000000 Y-100.000000
O1 if [#1 NE 0]
G41.1 D#1
O1 endif
g90 g1 y-102.000000
G2 I1.095697 J-0.097206 X-99.562609 Y-102.978473
G1 X-97.562609 Y-99.978473
G1 X-91.562609 Y-97.978473
G3 I-1.365837 J-2.212349 X-90.369054 Y-100.648542
G40
G1 X-80.369054 Y-95.648542
O0 endsub
F100
G21
O0 call [0]
O0 call [-.5]
O0 call [.5]
m2
""",
]


def check(text: str) -> None:
    """The property: a sound Program, or a located ProgramError; nothing else."""
    with mock.patch.object(gcode, "MAX_EXECUTED_LINES", 20_000):
        try:
            prog = read_gcode(text, "fuzz.ngc")
        except ProgramError as exc:
            assert exc.file == "fuzz.ngc"
            assert exc.line is not None and exc.line >= 1, str(exc)
            assert exc.col is None or exc.col >= 1
            assert "internal error" not in exc.message, str(exc)
            assert "\n" not in str(exc)
            return
    assert isinstance(prog, Program)
    n_lines = len(re.split(r"\r\n|\r|\n", text))
    pos = prog.start
    for b in prog.blocks:
        assert 1 <= b.source.line <= n_lines and b.source.col >= 1
        assert b.start == pos, "blocks must chain: each starts where the previous ended"
        pos = b.end
        assert all(math.isfinite(v) for v in b.start + b.end)
        if b.motion is Motion.RAPID or b.motion is Motion.DWELL:
            assert b.feed is None
        else:
            assert b.feed is not None and math.isfinite(b.feed) and b.feed >= 0
        if b.motion.is_arc:
            assert b.center is not None and all(math.isfinite(v) for v in b.center)
            assert b.turns >= 0
        else:
            assert b.center is None
        if b.motion is Motion.DWELL:
            assert b.start == b.end and b.dwell >= 0
        assert b.modal.side in (-1, 0, 1)
        assert b.modal.radius is None or b.modal.radius >= 0
        assert b.modal.plane in ("XY", "ZX", "YZ")


@SETTINGS
@given(st.lists(st.sampled_from(TOKENS), max_size=60).map("".join))
def test_gcodeish_token_soup(text):
    check(text)


@SETTINGS
@given(st.text(alphabet="GXYZIJKRFPDMO0123456789.-+[]#<>=()%; \n", max_size=80))
def test_gcodeish_characters(text):
    check(text)


@SETTINGS
@given(st.text(max_size=80))
def test_any_unicode(text):
    check(text)


def _mutate(data, text: str) -> str:
    kind = data.draw(st.sampled_from(["delete", "insert", "replace", "swap", "duplicate",
                                      "delete_line"]))
    if not text:
        return text
    i = data.draw(st.integers(0, len(text) - 1))
    if kind == "delete":
        return text[:i] + text[i + 1:]
    if kind == "insert":
        c = data.draw(st.sampled_from(TOKENS) | st.characters())
        return text[:i] + c + text[i:]
    if kind == "replace":
        c = data.draw(st.sampled_from(TOKENS) | st.characters())
        return text[:i] + c + text[i + 1:]
    lines = text.split("\n")
    if kind in ("swap", "delete_line"):
        a = data.draw(st.integers(0, len(lines) - 1))
        b = data.draw(st.integers(0, len(lines) - 1))
        if kind == "swap":
            lines[a], lines[b] = lines[b], lines[a]
        else:
            del lines[a]
        return "\n".join(lines)
    words = list(re.finditer(r"[A-Za-z][-+]?[\d.]+|#\d+|\[[^\]]*\]", text))
    if not words:
        return text
    w = words[data.draw(st.integers(0, len(words) - 1))]
    return text[:w.end()] + " " + w.group() + text[w.end():]


def test_seeds_are_valid():
    for seed in SEEDS:
        prog = read_gcode(seed)
        assert len(prog.blocks) > 5
        check(seed)


@pytest.mark.slow
@SETTINGS
@given(st.data())
def test_mutated_valid_programs(data):
    text = data.draw(st.sampled_from(SEEDS))
    for _ in range(data.draw(st.integers(1, 4))):
        text = _mutate(data, text)
    check(text)
