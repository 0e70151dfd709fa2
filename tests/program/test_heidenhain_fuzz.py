"""Mutated Klartext programs: every one is read (and compensated, and
verified) or refused with a located error, never a traceback; and the corpus
bench (bench/klartext_corpus.py) classifies a folder of programs."""
from __future__ import annotations

import importlib.util
from pathlib import Path

from hypothesis import HealthCheck, given, settings, strategies as st

from ccopt import verify
from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program import read_text
from text_mutations import mutate

SEED = """0 BEGIN PGM F MM
1 BLK FORM 0.1 Z X+0 Y+0 Z-10
2 BLK FORM 0.2 X+100 Y+80 Z+0
3 TOOL DEF 1 L+0 R+3
4 TOOL CALL 1 Z S3000 DR+0.1
5 L M140 MB MAX
6 Q1 = 5 * 2
7 L X-30 Y-30 R0 FMAX M3
8 L Z-5 R0 F1000
9 APPR CT X+50 Y+0 CCA90 R+8 RR F500
10 L X+100 Y+0
11 RND R5
12 L X+100 Y+80
13 CHF 5
14 L X+40 Y+80
15 CT X+0 Y+40
16 CC X+0 Y+20
17 CP IPA+90 DR+
18 LP PR+20 PA+270
19 L X+50 Y+0
20 DEP LCT X+80 Y-30 R8 F800
21 LBL 1
22 L IX+Q1 R0 FMAX
23 CALL LBL 1 REP 2
24 CYCL DEF 200 DRILLING ~
  Q200=+2 ;SET-UP ~
  Q201=-3 ~
  Q206=+150 ~
  Q202=+1 ~
  Q203=+0 ~
  Q204=+20
25 L X+10 Y+10 FMAX M99
26 FN 9: IF +Q1 EQU +10 GOTO LBL 2
27 L X+0
28 LBL 2
29 M30
30 END PGM F MM
"""
INSERTS = [" L", " X+", "IX-3", " RL", " RR", " R0", " DR-", " CC", " C", " CT", " RND R",
           " CHF ", " CR X+3 R+2 DR+", " APPR LT", " DEP LN LEN2", " LEN", " CCA400", " R-", " Q", "=", " FN 4:",
           " ~", "\n", ";", "*", " M97", " M98", " M99", " LBL 0", " CALL LBL 9", " F0",
           " FMAX", " PA+", " IPA-720", " 1e309", " CYCL DEF 251", " Z+", "99999999"]
REPLACES = ["+", "-", "0", "9", ".", " ", "~", "Q", "X", "R", "L", "C", "\n"]


@st.composite
def programs(draw):
    return mutate(draw, SEED, inserts=INSERTS, replaces=REPLACES, edits=(1, 4),
                  delete_max=6)


def test_the_seed_reads_compensates_and_verifies():
    prog = read_text(SEED, "f.h", "heidenhain")
    path = compensate(prog, style="heidenhain")
    assert verify(path, prog).ok


@settings(max_examples=150, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(programs())
def test_mutated_programs_never_raise_a_traceback(text):
    try:
        prog = read_text(text, "f.h", "heidenhain")
    except ProgramError as exc:
        assert exc.line is not None and exc.file == "f.h"
        return
    for style in ("heidenhain", "pmac"):
        try:
            path = compensate(prog, style=style, radius=1.0)
        except ProgramError as exc:
            assert exc.line is not None or "radius" in exc.message
            continue
        verify(path, prog)


def test_corpus_bench_classifies_a_folder(tmp_path):
    spec = importlib.util.spec_from_file_location(
        "klartext_corpus", Path(__file__).resolve().parents[2] / "bench" / "klartext_corpus.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    (tmp_path / "ok.h").write_text(SEED)
    (tmp_path / "pocket.h").write_text("0 BEGIN PGM P MM\n1 CYCL DEF 251 POCKET\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "fk.h").write_text("0 BEGIN PGM P MM\n1 FL X+5\n")
    results = bench.run(tmp_path, jobs=1)
    status = {Path(r["file"]).name: r["status"] for r in results}
    assert status == {"ok.h": "read", "pocket.h": "refused", "fk.h": "refused"}
    assert [r["verified"] for r in results if r["status"] == "read"] == [True]
    assert "2 programs" not in bench.report(results) and "traceback" in bench.report(results)
