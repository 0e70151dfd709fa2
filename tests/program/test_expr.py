"""The shared expression evaluator: precedence, functions in degrees, and
every malformed expression an ExprError (never another exception)."""
from __future__ import annotations


import pytest

from ccopt.program.expr import (
    GCODE_BINARY, GCODE_FUNCTIONS, PMAC_BINARY, PMAC_FUNCTIONS, ExprError, Grammar, parse_bracketed,
)

G = Grammar("[", "]", GCODE_BINARY, GCODE_FUNCTIONS, atan2_form=True)
P = Grammar("(", ")", PMAC_BINARY, PMAC_FUNCTIONS)


@pytest.mark.parametrize("text, value", [
    ("[1+2*3]", 7.0),
    ("[2**3**2]", 64.0),             # RS274/NGC: left to right
    ("[7 MOD 3]", 1.0),
    ("[-7 MOD 3]", 2.0),             # sign of the divisor
    ("[SIN[30]+COS[60]]", 1.0),      # degrees
    ("[ATAN[1]/[1]]", 45.0),
    ("[ATAN[1]/[-1]]", 135.0),
    ("[FIX[-1.5]]", -2.0),
    ("[FUP[-1.5]]", -1.0),
    ("[ROUND[2.5]]", 3.0),
    ("[1 AND 0 OR 1]", 1.0),
    ("[1ANDABS[2]]", 1.0),           # LinuxCNC accepts a function right after a word operator
    ("[-.5 NE 0]", 1.0),
])
def test_gcode_values(text, value):
    assert parse_bracketed(text, 0, G)[0] == pytest.approx(value, abs=1e-12)


def test_pmac_values():
    assert parse_bracketed("(2*(3+4)%5)", 0, P)[0] == pytest.approx(4.0)
    assert parse_bracketed("(SQRT(16)+INT(-0.5))", 0, P)[0] == pytest.approx(3.0)


@pytest.mark.parametrize("text, fragment", [
    ("[3/0]", "division by zero"),
    ("[SQRT[-1]]", "SQRT"),
    ("[ACOS[2]]", "ACOS"),
    ("[" + "9" * 400 + "]", "not finite"),
    ("[" * 500 + "1" + "]" * 500, "too deeply"),
    ("[1+]", "unexpected ']'"),
    ("[1+", "ends too early"),
    ("[²]", "unexpected"),
    ("[1", "expected ']'"),
    ("[10**400]", "overflow"),
])
def test_errors(text, fragment):
    with pytest.raises(ExprError) as err:
        parse_bracketed(text, 0, G)
    assert fragment in err.value.message
    assert 0 <= err.value.col <= len(text)
