"""Bounded, located inputs (issue 16, item 7).

* values in ``case.toml`` and on the command line that are not finite or out
  of range are exit 2 naming the key (and, in ``case.toml``, its line);
* coordinates, I J K R and F beyond 1e6 program units
  (``MAX_PROGRAM_COORDINATE``; 1e9 until issue 29) are located errors in both
  readers (they used to crash ``verify`` and ``feed`` with exit 3);
* an O-word loop stops after ``max_loop_iterations`` (all loops of a program
  together), located at the loop's first line, well within 5 s.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from ccopt.cases import load_case
from ccopt.errors import ProgramError
from ccopt.program import read_program, read_text
from ccopt.program.gcode import LOOP_LINES_PER_ITERATION, MAX_LOOP_ITERATIONS, read_gcode
from ccopt.program.model import MAX_PROGRAM_COORDINATE
from ccopt.program.pmac import read_pmac
from ccopt.program.tooltable import read_tool_table
from cli_run import run_cli

CASES = Path(__file__).resolve().parents[1] / "cases"


def one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


# -- case.toml ------------------------------------------------------------------------
def make_case(tmp_path: Path, toml: str) -> Path:
    folder = tmp_path / "case"
    folder.mkdir()
    (folder / "part.pmc").write_text((CASES / "leadin-inside-line" / "part.pmc").read_text())
    (folder / "case.toml").write_text(toml)
    return folder


PROGRAM = 'title = "t"\nprogram = "part.pmc"\n'


@pytest.mark.parametrize("toml, line, start", [
    # line numbers counted in the text as written
    (PROGRAM + "radius = inf\n", 3, "radius = inf: must be a finite number >= 0"),
    (PROGRAM + "radius = nan\n", 3, "radius = nan: must be a finite number >= 0"),
    (PROGRAM + "radius = -inf\n", 3, "radius = -inf: must be a finite number >= 0"),
    (PROGRAM + "radius = -1\n", 3, "radius = -1: must be a finite number >= 0"),
    (PROGRAM + "radius = true\n", 3, "radius = true: must be a finite number >= 0"),
    (PROGRAM + "radius = 2e9\n", 3, "radius = 2000000000.0: must be a finite number >= 0"),
    (PROGRAM + "\n[limits]\nv = [100.0, inf]\na = [1000.0, 1000.0]\n", 5,
     "limits.v = [100.0, inf]: must be a list of 2 or 3 numbers between 1e-06 and 1e+09"),
    (PROGRAM + "[limits]\nv = [100.0, 100.0]\na = [nan, 1000.0]\n", 5,
     "limits.a = [nan, 1000.0]: must be a list of 2 or 3 numbers"),
    (PROGRAM + "[limits]\nv = [100.0, 1e-7]\na = [1000.0, 1000.0]\n", 4,
     "limits.v = [100.0, 1e-07]: must be a list"),
    (PROGRAM + "[limits]\nv = [100.0, 100.0]\na = [1000.0, 1e10]\n", 5,
     "limits.a = [1000.0, 10000000000.0]: must be a list"),
    (PROGRAM + "limits.v = [1, 1]\nlimits.a = [1, -1]\n", 4, "limits.a = [1, -1]: must be"),
    (PROGRAM + "limits = {v = [1, 1], a = [1]}\n", 3, "limits.a = [1]: must be a list"),
    (PROGRAM + "[limits]\nv = [1, 1]\n", 3, "limits: [limits] needs a = [X, Y[, Z]]"),
    (PROGRAM + "limits = 5\n", 3, "limits = 5: must be a table"),
    (PROGRAM + 'style = "fanuc"\n', 3, 'style = "fanuc": must be one of fagor, heidenhain, linuxcnc, pmac'),
    (PROGRAM + 'expect = "maybe"\n', 3, 'expect = "maybe": must be one of ok, gouge, error'),
])
def test_bad_case_values_are_exit_2_at_their_key(capsys, tmp_path, toml, line, start):
    folder = make_case(tmp_path, toml)
    for command in ("show", "verify", "feed"):
        code, _, err = run_cli(capsys, command, str(folder))
        assert code == 2
        assert one_line(err).startswith(f"{folder / 'case.toml'}:{line}: {start}"), err


def test_good_case_values_load(tmp_path):
    folder = make_case(tmp_path, PROGRAM + "radius = 0\n[limits]\nv = [1e-6, 1e9, 5]\n"
                                           "a = [1e9, 1e-6]\n")
    case = load_case(folder)
    assert case.radius == 0.0 and case.vmax == (1e-6, 1e9, 5.0) and case.amax == (1e9, 1e-6)


# -- command-line values ----------------------------------------------------------------
@pytest.mark.parametrize("argv, fragment", [
    (["verify", "pocket", "--radius", "inf"], "--radius: must be a finite number >= 0"),
    (["verify", "pocket", "--radius", "2e9"], "--radius: must be at most 1e+09: '2e9'"),
    (["verify", "pocket", "--eps", "nan"], "--eps: must be a finite number > 0"),
    (["verify", "pocket", "--eps", "1e300"], "--eps: must be at most 1e+09"),
    (["smooth", "pocket", "--delta", "inf"], "--delta: must be a finite number > 0"),
    (["compare", "pocket", "--lead-radius", "1e300"], "--lead-radius: must be at most 1e+09"),
    (["export", "pocket", "-o", "x.nc", "--tol=-inf"], "--tol: must be a finite number > 0"),
    (["feed", "pocket", "--vmax", "100,inf"], "--vmax: must be a finite number > 0: 'inf'"),
    (["feed", "pocket", "--amax", "100,1e-9,1"], "bad limits: a for Y must be between 1e-06"),
    (["feed", "pocket", "--dt", "nan"], "--dt: must be a finite number > 0"),
    (["show", "pocket", "--max-loop-iterations", "-1"],
     "--max-loop-iterations: must be a whole number >= 0"),
    (["show", "pocket", "--max-loop-iterations", "1e9"],
     "--max-loop-iterations: not a whole number"),
])
def test_bad_option_values_are_exit_2_naming_the_option(capsys, argv, fragment):
    code, _, err = run_cli(capsys, *argv)
    assert code == 2 and fragment in one_line(err)


# -- coordinates beyond MAX_PROGRAM_COORDINATE (1e6) -------------------------------------
BIG = "1" + "0" * 30   # 1e30 written out (neither dialect reads exponents)


def gcode_error(text: str) -> ProgramError:
    with pytest.raises(ProgramError) as exc:
        read_gcode(text, "p.nc")
    return exc.value


def pmac_error(text: str) -> ProgramError:
    with pytest.raises(ProgramError) as exc:
        read_pmac(text, "p.pmc")
    return exc.value


def column(text: str, line: int, word: str) -> int:
    """1-based column of ``word`` on ``line`` of ``text``."""
    return text.splitlines()[line - 1].index(word) + 1


@pytest.mark.parametrize("text, line, word", [
    (f"G1 X0 Y0 F60\nG2 X0 Y-2 I0 J-{BIG}\n", 2, "J-"),
    ("G1 X1000001 F60\n", 1, "X"),            # one unit past the bound
    ("G1 X0 Y-1000000.5 F60\n", 1, "Y"),
    ("G1 Z5000000000 F60\n", 1, "Z"),
    ("G2 X1 Y1 R2000000000 F60\n", 1, "R2"),
    ("G1 X1 F2000000000\n", 1, "F"),
])
def test_gcode_words_beyond_the_bound_are_located(text, line, word):
    e = gcode_error(text)
    assert (e.line, e.col) == (line, column(text, line, word)) and "out of range" in e.message


def test_gcode_moves_that_add_up_beyond_the_bound_are_located():
    # 6e5 + 6e5 = 1.2e6 > 1e6: the second incremental move goes out of range
    e = gcode_error("G91 G1 X600000 F60\nX600000\n")
    assert (e.line, "beyond") == (2, "beyond") and "beyond" in e.message


def test_gcode_at_the_bound_is_read():
    prog = read_gcode(f"G1 X{MAX_PROGRAM_COORDINATE:.0f} Y-{MAX_PROGRAM_COORDINATE:.0f} F60\n")
    bound = MAX_PROGRAM_COORDINATE
    assert prog.blocks[0].end[:2] == (bound, -bound) == (1e6, -1e6)


@pytest.mark.parametrize("text, line, word", [
    (f"LINEAR ABS F10\nX1 Y1\nCIRCLE2 X1 Y-1 I0 J-{BIG}\n", 3, "J-"),
    ("LINEAR ABS F10\nX1000001\n", 2, "X"),
    ("LINEAR ABS F10\nCIRCLE1 X1 Y1 R2000000000\n", 2, "R2"),
    ("LINEAR ABS F2000000000\n", 1, "F"),
])
def test_pmac_words_beyond_the_bound_are_located(text, line, word):
    e = pmac_error(text)
    assert (e.line, e.col) == (line, column(text, line, word)) and "out of range" in e.message


def test_pmac_moves_that_add_up_beyond_the_bound_are_located():
    e = pmac_error("INC LINEAR F10\nX600000\nX600000\n")
    assert e.line == 3 and "beyond" in e.message


@pytest.mark.parametrize("name, text, line", [
    ("big.nc", (CASES / "fagor-seed-arc-cancel" / "part.nc").read_text().replace(
        "G03 X-20 Y-20 I0 J-20", f"G03 X-20 Y-20 I0 J-{BIG}"), 14),
    ("big.pmc", (CASES / "pocket" / "pocket.pmc").read_text().replace(
        "CIRCLE2 X6 Y0 I6 J0", f"CIRCLE2 X6 Y0 I6 J-{BIG}"), 11),
])
def test_huge_centre_offset_is_exit_2_in_verify_and_feed(capsys, tmp_path, name, text, line):
    # the reproducer: J-1e30 crashed verify and feed with exit 3
    prog = tmp_path / name
    prog.write_text(text)
    col = text.splitlines()[line - 1].index("J-1") + 1
    for argv in (["verify", "--radius", "2"], ["feed", "--radius", "2", "--vmax", "100,100,30",
                                               "--amax", "1000,1000,300"]):
        code, _, err = run_cli(capsys, *argv, str(prog))
        assert code == 2
        assert one_line(err).startswith(f"{prog}:{line}:{col}: J-1e+30 is out of range"), err


# -- the O-word loop limit -----------------------------------------------------------------
RUNAWAY = "G21 F600\n#1 = 0\no1 while [1]\n  G1 X[#1] Y0\n  G1 Y1\n  #1 = [#1 + 1]\no1 endwhile\nM2\n"
# the same with a body of 48 moves: the line budget stops it as soon
LONG_RUNAWAY = ("G21 F600\n#1 = 0\no1 while [1]\n"
                + "".join(f"  G1 X[#1] Y{i}\n" for i in range(48))
                + "  #1 = [#1 + 1]\no1 endwhile\nM2\n")


@pytest.mark.parametrize("text", [RUNAWAY, LONG_RUNAWAY], ids=["short-body", "long-body"])
def test_runaway_loop_stops_naming_the_loop(tmp_path, text):
    # stopped by the loop limit, a count of lines, not by a clock (how long it
    # takes: bench/stops.py; the timeout only keeps a hang from stalling the suite)
    prog = tmp_path / "runaway.nc"
    prog.write_text(text)
    done = subprocess.run([sys.executable, "-m", "ccopt.cli", "show", str(prog)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stderr
    # line 3 holds "o1 while [1]", its O-word in column 1; a pass runs 5 lines
    # (or 51): the loops' 3 * 10000 lines run out before the 10000 passes
    assert one_line(done.stderr).startswith(
        f"{prog}:3:1: o1 while: loops executed more than {3 * MAX_LOOP_ITERATIONS} lines")
    assert "--max-loop-iterations" in done.stderr


@pytest.mark.parametrize("loop", [
    "o1 while [1]\no1 endwhile\n",
    "o1 do\no1 while [1]\n",
    "o1 repeat [10 ** 30]\no1 endrepeat\n",
    "#1 = 0\no1 while [1]\n#1 = [#1 + 1]\no1 continue\no1 endwhile\n",
])
def test_every_kind_of_runaway_loop_stops(loop):
    e = gcode_error("G21\n" + loop)
    line = 1 + next(i for i, s in enumerate(loop.splitlines(), 1) if s.startswith("o1 ")
                    and s.split()[1] in ("while", "do", "repeat"))
    assert e.line == line and "--max-loop-iterations" in e.message


NESTED = "G21 F60\no1 repeat [2]\no2 repeat [3]\nG91 G1 X1\no2 endrepeat\no1 endrepeat\n"


def test_the_limit_counts_every_pass_of_every_loop():
    # 2 passes of o1 and 2 * 3 passes of o2: 8 iterations, 6 moves of X+1
    prog = read_gcode(NESTED, max_loop_iterations=8)
    assert len(prog.blocks) == 6 and prog.blocks[-1].end[0] == 6.0
    e = None
    with pytest.raises(ProgramError) as exc:
        read_gcode(NESTED, "n.nc", max_loop_iterations=7)
    e = exc.value
    # the 8th pass is o2's last, started at its repeat line (3)
    assert (e.file, e.line) == ("n.nc", 3) and "more than 7 loop iterations" in e.message


def test_do_while_counts_its_passes():
    text = "G21 F60\n#1 = 0\no1 do\n#1 = [#1 + 1]\nG91 G1 X1\no1 while [#1 LT 4]\n"
    assert len(read_gcode(text, max_loop_iterations=4).blocks) == 4
    with pytest.raises(ProgramError, match="more than 3 loop iterations"):
        read_gcode(text, max_loop_iterations=3)


def test_the_limit_is_an_option_of_every_reader_entry(capsys, tmp_path):
    prog = tmp_path / "n.nc"
    prog.write_text(NESTED)
    assert len(read_program(prog, max_loop_iterations=8).blocks) == 6
    assert len(read_text(NESTED, max_loop_iterations=8).blocks) == 6
    with pytest.raises(ProgramError):
        read_program(prog, max_loop_iterations=7)
    code, _, err = run_cli(capsys, "show", str(prog), "--max-loop-iterations", "7")
    assert code == 2 and one_line(err).startswith(f"{prog}:3:1: o2 repeat: more than 7")
    code, out, _ = run_cli(capsys, "show", str(prog), "--max-loop-iterations", "8")
    assert code == 0 and "6 blocks" in out
    with pytest.raises(ProgramError, match="max_loop_iterations must be a whole number"):
        read_gcode(NESTED, max_loop_iterations=-1)


def test_real_programs_loops_pass_under_the_default():
    # a pocket cleared in 40 depth passes of 100 zig-zag rows: 40 + 40 * 100 iterations
    text = ("G21 F600\n#1 = 0\no1 repeat [40]\n  #1 = [#1 - 0.1]\n  G1 Z#1\n  #2 = 0\n"
            "  o2 repeat [100]\n    G1 X50 Y#2\n    #2 = [#2 + 0.5]\n    G1 X0 Y#2\n"
            "  o2 endrepeat\no1 endrepeat\nM2\n")
    assert 40 + 40 * 100 <= MAX_LOOP_ITERATIONS
    prog = read_gcode(text)
    assert len(prog.blocks) == 40 * (1 + 2 * 100)
    assert prog.blocks[-1].end == pytest.approx((0.0, 50.0, -4.0))


def test_diameters_beyond_the_bound_are_located(tmp_path):
    # G41.1 D<diameter> and a tool table's D are lengths as well
    e = gcode_error("G41.1 D3000000000\n")
    assert (e.line, e.col) == (1, 7) and "out of range" in e.message
    table = tmp_path / "tools.tbl"
    table.write_text("T1 P1 D3\nT2 P2 D3000000000\n")
    with pytest.raises(ProgramError) as exc:
        read_tool_table(table)
    assert (exc.value.line, exc.value.col) == (2, 7) and "out of range" in exc.value.message


def test_the_loops_line_budget_is_three_lines_per_iteration():
    assert LOOP_LINES_PER_ITERATION == 3
    # two passes of a 6-move body: the loop is open for 6 moves and the
    # endrepeat of each pass, 2 * 7 = 14 lines, in 2 iterations
    text = "G21 F60\no1 repeat [2]\n" + "G91 G1 X1\n" * 6 + "o1 endrepeat\n"
    assert len(read_gcode(text, max_loop_iterations=5).blocks) == 12   # 15 lines allowed
    with pytest.raises(ProgramError) as exc:
        read_gcode(text, max_loop_iterations=4)                         # 12 lines allowed
    assert exc.value.line == 2 and "loops executed more than 12 lines" in exc.value.message


def test_the_line_budget_counts_the_subroutines_a_loop_calls():
    # the loop's 3 passes each run the call, the sub's 3 lines and the
    # endrepeat: 3 * 5 = 15 lines
    text = ("o9 sub\nG91 G1 X1\nG91 G1 Y1\no9 endsub\nG21 F60\n"
            "o1 repeat [3]\no9 call\no1 endrepeat\n")
    assert len(read_gcode(text, max_loop_iterations=5).blocks) == 6
    with pytest.raises(ProgramError) as exc:
        read_gcode(text, max_loop_iterations=4)
    # stopped inside the subroutine: located at the loop open in the caller
    assert exc.value.line == 6 and "more than 12 lines" in exc.value.message
