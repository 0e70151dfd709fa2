"""Values read back from programs for reader features otherwise tested only for
acceptance: G-code TAN/ASIN/ACOS (degrees) as coordinates, a 30-argument
O-word call, and PMAC CCR with an expression argument (and the offset the
PMAC engine then applies). Every expected figure is worked out here."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion
from ccopt.program.pmac import read_pmac
from ccopt.toolpath import Role


def moves(text, **kw):
    return [b for b in read_gcode(text, **kw).blocks if b.motion.is_move]


def close3(p, q, tol=1e-12):
    return all(math.isclose(a, b, abs_tol=tol) for a, b in zip(p, q))


def wrap(body: str) -> str:
    return f"OPEN PROG 1 CLEAR\n{body}\nCLOSE\n"


def tan_deg(x):
    return math.tan(math.radians(x))


def asin_deg(x):
    return math.degrees(math.asin(x))


def acos_deg(x):
    return math.degrees(math.acos(x))


# --------------------------------------------------------------------------- G-code functions
@pytest.mark.parametrize("expr, value", [
    ("TAN[45]", 1.0),
    ("ASIN[0.5]", 30.0),
    ("ACOS[0.5]", 60.0),
    ("TAN[-45]", -1.0),
    ("ASIN[-1]", -90.0),
    ("ACOS[-1]", 180.0),
    ("ACOS[1]", 0.0),
    ("TAN[0]", 0.0),
    ("TAN[60]", math.sqrt(3.0)),
    ("TAN[30]", 1.0 / math.sqrt(3.0)),
    ("TAN[135]", -1.0),              # second quadrant
    ("TAN[225]", 1.0),               # period 180 degrees
    ("ASIN[SQRT[2]/2]", 45.0),
    ("ACOS[SQRT[3]/2]", 30.0),
    # non-trivial values: the reference is math.* in degrees
    ("TAN[37.5]", tan_deg(37.5)),
    ("TAN[-71.25]", tan_deg(-71.25)),
    ("ASIN[0.3]", asin_deg(0.3)),
    ("ASIN[-0.815]", asin_deg(-0.815)),
    ("ACOS[0.3]", acos_deg(0.3)),
    ("ACOS[-0.62]", acos_deg(-0.62)),
])
def test_gcode_trig_functions_as_a_coordinate(expr, value):
    b, = moves(f"G21 G90 G1 F60 X[{expr}] Y[2*{expr}] Z1\n")
    assert b.motion is Motion.LINE
    tol = 1e-12 * max(1.0, abs(value))
    assert close3(b.end, (value, 2.0 * value, 1.0), tol), (expr, b.end, value)


def test_gcode_trig_functions_nested_and_combined():
    # TAN[45] + ASIN[0.5] = 1 + 30; ACOS[0.5] - ASIN[1] = 60 - 90;
    # ASIN[TAN[30] * SQRT[3] / 2] = ASIN[1/2] = 30; ACOS[TAN[45] / 2] = 60.
    a, b = moves("G1 F60 X[TAN[45]+ASIN[0.5]] Y[ACOS[0.5]-ASIN[1]] Z[ASIN[TAN[30]*SQRT[3]/2]]\n"
                 "G1 X[ACOS[TAN[45]/2]]\n")
    assert close3(a.end, (31.0, -30.0, 30.0), 1e-12), a.end
    assert close3(b.end, (60.0, -30.0, 30.0), 1e-12), b.end


def test_gcode_trig_functions_with_parameters_and_incremental():
    text = ("#1 = 0.5\n#2 = 37.5\n#<a> = -0.62\n"
            "G1 F60 X[ASIN[#1]] Y[TAN[#2]] Z[ACOS[#<a>]]\n"
            "G91 X[ACOS[#1]] Y[-TAN[#2]] Z[ASIN[#1]]\n")
    a, b = moves(text)
    assert close3(a.end, (30.0, tan_deg(37.5), acos_deg(-0.62)), 1e-12)
    assert close3(b.start, a.end, 0.0)
    assert close3(b.end, (30.0 + 60.0, 0.0, acos_deg(-0.62) + 30.0), 1e-12)


# --------------------------------------------------------------------------- 30-argument call
def test_sub_call_with_thirty_positional_arguments():
    args = [float(10 * k + 0.5) for k in range(1, 31)]          # #k = 10k + 0.5
    call = "o<many> call " + " ".join(f"[{a}]" for a in args)
    text = f"""G21 G90 G1 F60
o<many> sub
  G1 X#30 Y#1 Z#15
  G1 X[#30 + #1] Y[#29 - #2]
o<many> endsub
{call}
G1 X#30 Y#1
M2
"""
    a, b, c = moves(text)
    # #30 = 300.5, #1 = 10.5, #15 = 150.5, #29 = 290.5, #2 = 20.5
    assert a.end == pytest.approx((300.5, 10.5, 150.5), abs=1e-12)
    assert b.end == pytest.approx((311.0, 270.0, 150.5), abs=1e-12)
    # After the call #1..#30 of the main program are back to their value there: 0.
    assert c.end == pytest.approx((0.0, 0.0, 150.5), abs=1e-12)


def test_sub_call_with_thirty_expression_arguments():
    # Every argument is an expression; #30 = 30*TAN[45] = 30, #1 = ASIN[0.5] = 30,
    # #16 = 16 * 2 = 32.
    args = ["ASIN[0.5]"] + [f"{k}*2" for k in range(2, 30)] + ["30*TAN[45]"]
    assert len(args) == 30
    text = ("o1 sub\nG1 F60 X#30 Y#1 Z#16\no1 endsub\no1 call "
            + " ".join(f"[{a}]" for a in args) + "\n")
    b, = moves(text)
    assert close3(b.end, (30.0, 30.0, 32.0), 1e-12), b.end


# --------------------------------------------------------------------------- PMAC CCR(expr)
@pytest.mark.parametrize("setup, ccr, r", [
    ("", "CCR(1+1)", 2.0),
    ("P10=1.25", "CCR(P10*2)", 2.5),
    ("", "P10=1.25 CCR(P10*2)", 2.5),     # assignment and CCR on one line
    ("P10=1.25 Q3=0.5", "CCR(P10+Q3*(2+1))", 2.75),
    ("", "CCR(SQRT(2.25))", 1.5),
])
def test_pmac_ccr_expression_radius_and_offset(setup, ccr, r):
    prog = read_pmac(wrap(f"""LINEAR ABS F10
{setup}
{ccr} CC1
X10 Y0
X20 Y0
X30 Y0
CC0
X40 Y0
"""))
    blocks = list(prog)
    assert [b.end for b in blocks] == [(10, 0, 0), (20, 0, 0), (30, 0, 0), (40, 0, 0)]
    assert [b.modal.radius for b in blocks] == pytest.approx([r] * 4, abs=1e-12)
    assert [b.modal.side for b in blocks] == [1, 1, 1, 0]

    path = ccopt.compensate(prog, "pmac")
    comp = [s for s in path if s.role is Role.COMPENSATED]
    assert comp, [s.role for s in path]
    # The programmed line is y = 0 travelling +X; CC1 (left) puts the tool
    # centre at y = +r: each compensated piece is a line along y = r.
    for s in comp:
        assert s.kind == "line"
        assert s.start[1] == pytest.approx(r, abs=1e-9) and s.end[1] == pytest.approx(r, abs=1e-9)
    # Between the lead-in and lead-out the compensated pieces cover x = 10..30.
    assert comp[0].start[0] == pytest.approx(10.0, abs=1e-9)
    assert comp[-1].end[0] == pytest.approx(30.0, abs=1e-9)


def test_pmac_negative_ccr_expression_flips_side():
    # CCR(-(1+0.5)) with CC1: radius 1.5 on the right (spec decision), y = -1.5.
    prog = read_pmac(wrap("LINEAR ABS F10\nP1=0.5\nCCR(-(1+P1)) CC1\nX10 Y0\nX20 Y0\nX30 Y0\nCC0\nX40 Y0"))
    assert [(b.modal.radius, b.modal.side) for b in prog][:3] == [(1.5, -1)] * 3
    comp = [s for s in ccopt.compensate(prog, "pmac") if s.role is Role.COMPENSATED]
    assert comp and all(s.start[1] == pytest.approx(-1.5, abs=1e-9)
                        and s.end[1] == pytest.approx(-1.5, abs=1e-9) for s in comp)
