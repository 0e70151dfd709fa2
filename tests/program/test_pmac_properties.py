"""Property-based checks of the PMAC reader.

* Random text and random mutations of valid programs either read or raise a
  ProgramError located at a line of the text (never another exception).
* Random valid straight-line programs end where an independent simulation of
  ABS/INC says, and random centre-vector arcs keep the centre the vector gives.
"""
from __future__ import annotations

import math

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ccopt.errors import ProgramError
from ccopt.program.model import Motion
from ccopt.program.pmac import read_pmac

from text_mutations import mutate

SETTINGS = settings(max_examples=300, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])

TOKENS = ["OPEN PROG 1", "OPEN PROG 2 CLEAR", "OPEN PLC 3", "CLOSE", "CLEAR", "LINEAR", "LIN",
          "CIRCLE1", "CIRCLE2", "CIR1", "RAPID", "SPLINE1", "PVT", "ABS", "INC", "ABS(R)",
          "INC(R)", "ABS(X,Y)", "INC(Z)", "X", "Y", "Z", "I", "J", "K", "R", "A", "F", "TA", "TS",
          "TM", "DWELL", "DELAY", "CC0", "CC1", "CC2", "CC3", "CCR", "NORMAL", "K-1", "J-1",
          "I-1", "P1=", "Q2=", "P(P1)=", "I15=", "I5190=", "I5189=", "M1=", "M3", "N10", "O5",
          "RETURN", "GOTO", "(", ")", "P1", "Q0", "SIN(", "ATAN2(", "SQRT(", "$1F", "+", "-",
          "*", "/", "%", "&", "|", "^", "=", "1", "0", "-5", "2.5", ".5", "1e3", "99999999999",
          " ", " ", "\n", "\n", ";", "#1->1000X", "&1", "\t", "\r\n", "\x00", "é"]


def _check(text: str, **kw) -> None:
    try:
        prog = read_pmac(text, "fuzz.pmc", **kw)
    except ProgramError as err:
        n_lines = text.count("\n") + 1
        assert err.line is not None and 1 <= err.line <= n_lines, (err, text)
        assert err.col is None or err.col >= 1
        assert err.file == "fuzz.pmc"
        assert "\n" not in str(err)
        return
    for b in prog:
        for p in (b.start, b.end) + ((b.center,) if b.center is not None else ()):
            assert all(math.isfinite(v) for v in p)
        assert b.source.line >= 1 and b.source.col >= 1
    for a, b in zip(prog.blocks, prog.blocks[1:]):
        assert b.start == a.end


@SETTINGS
@given(st.lists(st.sampled_from(TOKENS), max_size=40))
def test_random_token_soup_only_raises_located_program_errors(tokens):
    _check("".join(tokens))


@SETTINGS
@given(st.text(alphabet=st.sampled_from(list("XYZIJKRPQFTADWELCNOM0123456789.-+*/()=$; \n\t")),
               max_size=80))
def test_random_characters_only_raise_located_program_errors(text):
    _check(text)


VALID = """; sample download file
CLOSE
&1
P10=2.5
OPEN PROG 1 CLEAR
N1 LINEAR ABS TA100 TS20 F20
X10 Y0
CCR(P10) CC1
X10 Y10
CIRCLE2 X0 Y10 I-5 J0
INC(R) CIRCLE1 X0 Y0 R-5
ABS(R) CIRCLE1 X0 Y0 I0 J5
LINEAR TM300 INC X-5 Y-5 Z1
Q1=P10*2+1 X(Q1) Y(-Q1)
DWELL100 DELAY(50)
NORMAL J-1 ABS CIRCLE1 X0 Z0 R5
NORMAL K-1 CC0
RAPID X0 Y0 Z0
RETURN
CLOSE
"""


def test_valid_sample_reads():
    prog = read_pmac(VALID)
    assert [b.motion.value for b in prog] == ["line", "line", "ccw", "cw", "cw", "line", "line",
                                            "dwell", "dwell", "cw", "rapid"]


@st.composite
def mutations(draw):
    return mutate(draw, VALID, inserts=TOKENS, replaces=list("XYZIJKR0123456789.-()=; \nPQ"),
                  edits=(1, 4), delete_max=8)


@SETTINGS
@given(mutations())
def test_mutated_valid_programs_only_raise_located_program_errors(text):
    _check(text)


# ---------------------------------------------------------------------------
coord = st.integers(-50, 50).map(lambda n: n / 4)


@st.composite
def straight_programs(draw):
    """Random LINEAR/RAPID programs and the end points an independent simulation gives."""
    lines = ["F10"]
    pos = [0.0, 0.0, 0.0]
    inc = [False, False, False]
    ends = []
    for _ in range(draw(st.integers(1, 12))):
        words = []
        choice = draw(st.sampled_from(["ABS", "INC", "ABS(X)", "INC(Y,Z)", "", "", "RAPID",
                                       "LINEAR"]))
        if choice.startswith(("ABS", "INC")):
            flag = choice.startswith("INC")
            axes = "XYZ" if "(" not in choice else choice[4:-1].replace(",", "")
            for a in axes:
                inc["XYZ".index(a)] = flag
        if choice:
            words.append(choice)
        axes = draw(st.lists(st.sampled_from("XYZ"), min_size=1, max_size=3, unique=True))
        for a in axes:
            v = draw(coord)
            k = "XYZ".index(a)
            pos[k] = pos[k] + v if inc[k] else v
            words.append(f"{a}{v}" if draw(st.booleans()) else f"{a}({v}*2/2)")
        lines.append(" ".join(words))
        ends.append(tuple(pos))
    return "\n".join(lines), ends


@SETTINGS
@given(straight_programs())
def test_straight_programs_end_where_abs_inc_say(case):
    text, ends = case
    prog = read_pmac(text)
    assert [b.end for b in prog] == [tuple(float(v) for v in e) for e in ends]


@SETTINGS
@given(st.tuples(coord, coord), st.tuples(coord, coord), st.booleans(), st.booleans())
def test_ijk_arcs_keep_the_programmed_centre(start, vec, absolute, cw):
    """An arc whose end is the start rotated about the centre is a plain (non-spiral) arc."""
    sx, sy = start
    cx, cy = (vec if absolute else (sx + vec[0], sy + vec[1]))
    r = math.hypot(sx - cx, sy - cy)
    if r < 1e-3:
        return
    # rotate the start by 90 degrees about the centre
    ex, ey = cx - (sy - cy), cy + (sx - cx)
    mode = "CIRCLE1" if cw else "CIRCLE2"
    vmode = "ABS(R)" if absolute else "INC(R)"
    prog = read_pmac(f"F1 X{sx} Y{sy}\n{vmode} {mode} X({ex}) Y({ey}) I({vec[0]}) J({vec[1]})")
    arc = prog[1]
    assert arc.motion is (Motion.ARC_CW if cw else Motion.ARC_CCW)
    assert math.isclose(arc.center[0], cx, abs_tol=1e-12)
    assert math.isclose(arc.center[1], cy, abs_tol=1e-12)
    assert not arc.is_spiral(tol=1e-9 * max(1.0, r))
