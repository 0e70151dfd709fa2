"""Every class of bad PMAC input gives a ProgramError at the right line and column."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program.pmac import read_pmac

# (program text, line, column, part of the message)
CASES = [
    ("F1\nFOO X1", 2, 1, "unknown command 'FOO'"),
    ("F1\nCIRCLE X1", 2, 1, "CIRCLE1"),
    ("F1\nX", 2, 2, "X needs a value"),
    ("F1 X10 Y", 1, 9, "Y needs a value"),
    ("CCRX", 1, 4, "CCR needs a value"),
    ("F1\n  X(1/0)", 2, 6, "division by zero"),
    ("F1 X(SQRT(-1))", 1, 6, "SQRT of negative"),
    ("F1 X(EXP(1000))", 1, 6, "overflows"),
    ("F1 X1" + "0" * 400, 1, 5, "too large"),
    ("F1 P1=1" + "0" * 400 + " X(P1)", 1, 7, "finite"),
    ("F1 X(1+2", 1, 9, "expected ')'"),
    ("F1 X((((1)))", 1, 13, "expected ')'"),
    ("F1\nCIRCLE1 X10", 2, 9, "without a centre"),
    ("F1\nCIRCLE1 X10 I5 R5", 2, 9, "not both"),
    ("F1\nCIRCLE2 X10 R4", 2, 9, "too small for the chord"),
    ("F1\nCIRCLE2 X0 Y0 R4", 2, 9, "full circle"),
    ("F1\nCIRCLE2 X5 R0", 2, 9, "zero"),
    ("F1\nCIRCLE2 X5 I0 J0", 2, 9, "centre is on the start"),
    ("F1\nCIRCLE2 X5 I5", 2, 9, "centre is on the end"),
    ("F1\nCIRCLE2 I5", 2, 9, "without an end point"),
    ("F1 X1 I5", 1, 4, "LINEAR move"),
    ("RAPID X1 R5", 1, 7, "RAPID move"),
    ("LINEAR X1", 1, 8, "without a speed"),
    ("F1 X1 X2", 1, 7, "twice"),
    ("F1 A5", 1, 4, "axis A"),
    ("F1 X1 W2", 1, 7, "axis W"),
    ("SPLINE1 X1", 1, 1, "unsupported move mode"),
    ("PVT100", 1, 1, "unsupported move mode"),
    ("F1\n GOTO 10", 2, 2, "unsupported command GOTO"),
    ("IF(P1>0) X1", 1, 1, "unsupported command IF"),
    ("CC3", 1, 1, "CC3 is not supported"),
    ("CC4", 1, 1, "CC4 is not supported"),
    ("CC7", 1, 1, "unknown command 'CC7'"),
    ("NORMAL K1", 1, 1, "unsupported NORMAL"),
    ("NORMAL I1 J1", 1, 1, "unsupported NORMAL"),
    ("NORMAL", 1, 1, "NORMAL needs"),
    ("F0", 1, 1, "must be positive"),
    ("F-3", 1, 1, "must be positive"),
    ("DWELL-5", 1, 1, "negative"),
    ("TA(-1)", 1, 1, "negative"),
    ("G1 X5", 1, 1, "G-codes"),
    ("T1", 1, 1, "T-codes"),
    ("P1", 1, 1, "P-variable on its own"),
    ("P9000=1", 1, 1, "0 to 8191"),
    ("F1 X(I5190)", 1, 6, "never set"),
    ("Q(1.5)=2", 1, 1, "integer"),
    ("P1=", 1, 4, "ends too early"),
    ("F1 X10 # 1", 1, 8, "unexpected '#'"),
    ("ABS(X,E)", 1, 5, "expected axis letters"),
    ("ABS(X", 1, 4, "missing ')'"),
    ("FRAX(X,Y)", 1, 1, "FRAX"),
    ("CLOSE", 1, 1, "CLOSE without OPEN"),
    ("OPEN PROG 1\nX1\n", 1, 1, "never closed"),
    ("OPEN PROG\nCLOSE", 1, 1, "program number"),
    ("OPEN PROG 1\nOPEN PROG 2\nCLOSE", 2, 1, "OPEN inside"),
    ("OPEN PROG 1\nCLOSE\nX10", 3, 1, "outside OPEN PROG"),
    ("OPEN PROG 1\nF1 X1 OPEN PROG 2\nCLOSE", 2, 7, "alone on its line"),
    ("OPEN PLC 1\nCLOSE", 1, 1, "opens no PROG"),
    ("I5190=0\nOPEN PROG 1\nCLOSE", 1, None, "time unit"),
    ("OPEN PROG 1\nF1 X1\nI5190=60000\nCLOSE", 3, 1, "after the first move"),
    ("F1 X1 \x00", 1, 7, "unexpected"),
]


@pytest.mark.parametrize("text,line,col,message", CASES)
def test_error_location_and_message(text, line, col, message):
    with pytest.raises(ProgramError) as info:
        read_pmac(text, "part.pmc")
    err = info.value
    assert message in err.message
    assert (err.file, err.line, err.col) == ("part.pmc", line, col)
    assert str(err).startswith(f"part.pmc:{line}")
    assert "\n" not in str(err)


def test_deep_nesting_is_a_program_error():
    with pytest.raises(ProgramError) as info:
        read_pmac("F1 X" + "(" * 5000 + "1" + ")" * 5000)
    assert info.value.line == 1


def test_error_in_unselected_program_is_not_checked():
    text = "OPEN PROG 1\nF1 X1\nCLOSE\nOPEN PROG 2\nBOGUS\nCLOSE"
    assert len(read_pmac(text)) == 1
    with pytest.raises(ProgramError) as info:
        read_pmac(text, program=2)
    assert info.value.line == 5
