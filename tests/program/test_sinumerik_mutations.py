"""Mutated SINUMERIK programs: read or refused with a located error, never a
traceback; and compensated as an 840D or refused with a located error."""
from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ccopt.compensate import compensate
from ccopt.errors import CcoptError, ProgramError
from ccopt.program.sinumerik import read_sinumerik
from text_mutations import mutate

BASE = """; plate
$TC_DP6[1,1]=2
N10 G90 G17 G71 T1 D1
R1=40 R2=R1/2
DEF INT CNT=0
N20 G0 X-20 Y-20 Z5
N30 G1 Z0 F600
N40 G41 G247 G340 DISR=4 X0 Y0
N50 Y=R1
N60 G2 X=R2 Y=R1+R2 CR=R2
N70 G1 X60
WHILE CNT<2
  CNT=CNT+1
ENDWHILE
IF CNT==2 GOTOF DOWN
X999
DOWN: G451 Y0
N80 CIP X30 Y-10 I1=45 J1=-6
N90 CT X0 Y0
N100 G40 G248 DISR=4 X-20 Y-20
N110 M30
"""
INSERTS = ["G41", "G42", "G40", "G450", "G451", "DISC=50", "KONT", "KONTT", "G147", "G247",
           "G348", "DISR=0", "CR=-3", "AR=90", "CIP", "CT", "I1=3", "R5=", "(", ")", "GOTOB",
           "ENDIF", "ELSE", "LOOP", "FOR R9=1 TO 3", "ENDFOR", ";", "=", "AC(", "IC(2)",
           "$TC_DP6[1,1]=", "L9", "P3", "X", "Y-", "Z=", " ", "\n", "D0", "OFFN=1", "TURN=2",
           "G3", "G2", "G0", "G1", "F0", "1e999", "N5", "LBL:", "TRANS", "DEF REAL Q",
           "RND=2", "RND=50", "CHF=1", "CHR=1.5", "RNDM=3", "RNDM=0", "FRC=100", "FRCM=0",
           "\nG111 X5 Y5\n", "\nG110 AP=30 RP=4\n", "AP=30", "RP=5", "AP=IC(15)",
           "\nROT RPL=30\n", "\nAROT RPL=-20\n", "\nATRANS X2 Y1\n",
           "\nCYCLE81(10, 0, 2, -5)\n", "\nMCALL CYCLE82(10, 0, 1, -3, , 0.2)\n", "\nMCALL\n",
           "ANG=30", "\nX20 ANG=-60\n", "\nANG=45\nX30 Y5 ANG=-30\n"]
REPLACES = ["0", "1", "-", ".", "X", "Y", "G", "=", "(", ")", " ", "R", "\n", "9"]


@st.composite
def mutated(draw):
    return mutate(draw, BASE, inserts=INSERTS, replaces=REPLACES, edits=(1, 4), delete_max=6)


@settings(max_examples=150, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutated_programs_read_or_refuse_located(text):
    try:
        prog = read_sinumerik(text, "m.mpf", max_loop_iterations=200)
    except ProgramError as exc:
        assert exc.file == "m.mpf" and exc.line is not None, str(exc)
        assert "internal error" not in str(exc), (text, str(exc))
        return
    try:
        compensate(prog, style="siemens")
    except CcoptError as exc:
        assert exc.line is not None or "radius" in str(exc), (text, str(exc))
