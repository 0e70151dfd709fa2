"""Fanuc subprograms (M98/M99), computed O-call labels, ``return`` values,
``EXISTS[]`` and ``#`` before a function, as LinuxCNC reads them
(``interp_read.cc`` ``read_o``/``read_parameter``, ``interp_o_word.cc``).

LinuxCNC's own tests are kept in tests/conformance/linuxcnc/m98m99 and
.../oword (GPL-2.0 data, see its README): the ones with moves match move for
move, the error ones are refused where (or, for two, before) LinuxCNC stops,
with its words. The rest is derived by hand, and a seeded property: ``M98 P
L<n>`` of a subprogram of incremental moves is the same as its body written
out n times.
"""
from __future__ import annotations

import random
import re

import pytest

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import ENDLESS_MAIN, PROGRAM_END
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

MOVES = ["m98m99/01-basics", "m98m99/05-M98-loops", "m98m99/14-o-expression-call",
         "m98m99/12-M99-endless-main-program", "m98m99/02-variables", "m98m99/07-nested-subs",
         "m98m99/08-sub-follows-main", "m98m99/10-M98-P001", "oword/oword-bug315-p2",
         "oword/namedparam-bug424", "oword/return-value"]


def _path(folder: str, name: str = "test.ngc"):
    path = CONFORMANCE / folder / name
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    return path


@pytest.mark.parametrize("folder", MOVES)
def test_linuxcnc_subprogram_tests_match_move_for_move(folder):
    path = _path(folder)
    got = canonical_moves(compensate(read_gcode(path.read_text(), str(path)),
                                     style="linuxcnc"))
    want = expected_moves(folder)
    assert [k for k, _ in got] == [k for k, _ in want]
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        assert all(abs(a[q] - b[q]) <= TOL for q in range(3)), (i, kind, a, b[:3])


def test_exists_as_linuxcnc_without_its_a_word():
    # its A EXISTS[#<b>] is an A axis word (not read): X Y Z compared
    path = _path("oword/exists")
    text = path.read_text().replace(" A EXISTS[#<b>]", "")
    got = [b.end for b in read_gcode(text, str(path)).blocks]
    want = [m[:3] for _, m in expected_moves("oword/exists")]
    assert got == [tuple(w) for w in want]


@pytest.mark.parametrize("name, line, col, words", [
    ("03-error-M98-no-P-word/test.ngc", 4, 1, "Found 'm98' code with no P-word"),
    ("04-M98-but-no-sub/test.ngc", 4, 5, "no subprogram O1"),
    # LinuxCNC stops at the sub's head it jumped to; ccopt at the call
    ("06-error-mixed-sub-styles/O...-called-with-O..._call.ngc", 4, 1,
     "subroutine must be called with 'M98"),
    ("06-error-mixed-sub-styles/O...-ended-with-O..._endsub.ngc", 8, 1,
     "subroutine definition must end with 'M99'"),
    ("06-error-mixed-sub-styles/O...-sub-called-with-M98.ngc", 4, 5,
     "'O1 sub' subroutine must be called with 'O1 call'"),
    ("06-error-mixed-sub-styles/O...-sub-ended-with-M99.ngc", 8, 1,
     "'O1 endsub' or 'O1 return' must follow 'O1 sub' subroutine definition"),
])
def test_linuxcnc_subprogram_errors_are_refused_located(name, line, col, words):
    path = _path("m98m99", name)
    with pytest.raises(ProgramError) as err:
        read_gcode(path.read_text(), str(path))
    assert (err.value.line, err.value.col) == (line, col)
    assert words in str(err.value)


def test_named_and_numbered_program_heads_read():
    for name in ("test-named.ngc", "test-numbered.ngc"):
        path = _path("m98m99/13-named-program", name)
        assert read_gcode(path.read_text(), str(path)).blocks == ()


def _x(text: str) -> list[float]:
    return [b.end[0] for b in read_gcode(text, "t.ngc").blocks]


def test_m98_parameters_are_global_o_call_ones_local():
    # LinuxCNC 02-variables: after M98 the caller sees #1 = 13.01; after
    # o2 call its own #1 = 42.01 again, and #31 (not local) = 13.31
    text = ("G21 #1 = 42.01 #31 = 42.31\nM98 P1\nG0 X#1\n#1 = 42.01\no2 call\nG0 X#1\n"
            "G0 X#31\nM30\nO1\n#1 = 13.01 #31 = 13.31\nM99\no2 sub\n#1 = 13.01\n"
            "#31 = 13.31\no2 endsub\n")
    assert _x(text) == [13.01, 42.01, 13.31]


def test_nested_m98_repeats_as_linuxcnc_07():
    text = ("#1 = 0\nM98 P2 L5\nG0 X#1\nM30\nO2\nM98 P1 L5\n#1 = [FIX[#1] + 1]\nM99\n"
            "O1\n#1 = [#1 + 0.1]\nM99\n")
    assert _x(text) == [5.0]


def test_m98_l0_does_not_call_and_p_may_be_an_expression():
    text = "#2 = 3\nM98 P[#2 * 100] L0\nM98 P[#2 * 100]\nM30\nO300\nG0 X7\nM99\n"
    assert _x(text) == [7.0]


def test_m99_ending_the_main_program_reads_one_pass_and_says_where():
    prog = read_gcode("G21 G0 X1\nM99\nG0 X2\n", "main.ngc")
    assert [b.end[0] for b in prog.blocks] == [1.0]
    assert prog.meta[ENDLESS_MAIN].startswith("main.ngc:2: M99 ends the main program")
    assert prog.meta[PROGRAM_END] == "M99"


def test_return_under_another_label_returns_its_value():
    text = ("o1 sub\no2 if [#1 GT 0]\no2 return [#1 * 2]\no2 endif\no1 endsub [7]\n"
            "o1 call [4]\nG0 X#<_value>\no1 call [0]\nG0 X#<_value>\n")
    assert _x(text) == [8.0, 7.0]


@pytest.mark.parametrize("text, line, col, words", [
    ("G0 X1 M98 P1\n", 1, 7, "M98 must be the first word of its line"),
    ("M98 P1 X2\nO1\nM99\n", 1, 8, "M98 takes only P"),
    ("M98 P1.5\nO1\nM99\n", 1, 5, "P must be a whole number"),
    ("M98 P1\nM30\nO1\nM99 P2\n", 4, 5, "Unexpected character after M99"),
    ("o[1 + 1] sub\n", 1, 1, "read with call only"),
    ("G0 X EXISTS[1]\n", 1, 13, "Expected # reading parameter"),
])
def test_subprogram_misuse_is_refused_located(text, line, col, words):
    with pytest.raises(ProgramError) as err:
        read_gcode(text, "t.ngc")
    assert (err.value.line, err.value.col) == (line, col), str(err.value)
    assert words in str(err.value)


def _pattern(rng: random.Random) -> list[str]:
    moves = []
    for _ in range(rng.randint(1, 5)):
        dx, dy = rng.uniform(-5, 5), rng.uniform(-5, 5)
        if rng.random() < 0.3:
            moves.append(f"G3 X{dx:.3f} Y{dy:.3f} R{max(abs(dx), abs(dy)) + 1:.3f}")
        else:
            moves.append(f"G{rng.choice((0, 1))} X{dx:.3f} Y{dy:.3f}")
    return moves


def _check_m98_repeats_are_the_body_written_out(seed: int) -> None:
    rng = random.Random(seed)
    body, n = _pattern(rng), rng.randint(1, 6)
    head = "G21 G17 F300\nG0 X0 Y0\nG91\n"
    called = head + f"M98 P{rng.randint(1, 9999)} L{n}\nG90 G0 X0 Y0\nM30\n"
    label = re.search(r"M98 P(\d+)", called).group(1)
    called += f"O{label}\n" + "\n".join(body) + "\nM99\n"
    inline = head + "\n".join(body * n) + "\nG90 G0 X0 Y0\nM30\n"
    a = read_gcode(called, "a.ngc").blocks
    b = read_gcode(inline, "b.ngc").blocks
    assert [(x.motion, x.end, x.center) for x in a] == [(y.motion, y.end, y.center) for y in b]


@pytest.mark.parametrize("seed", range(5))
def test_m98_repeats_are_the_body_written_out_quick(seed):
    _check_m98_repeats_are_the_body_written_out(seed)


@pytest.mark.slow
def test_m98_repeats_are_the_body_written_out_generated():
    for seed in range(100, 400):
        _check_m98_repeats_are_the_body_written_out(seed)
