"""Fuzz: mutated bundled programs through the command line, in-process.

Every bundled case's program (and the pocket's G-code twin) is mutated with
:func:`text_mutations.mutate` from a fixed seed and run, as a copy of
its case folder (so the case's style, radius and limits apply), through
``ccopt show`` and ``ccopt compensate`` (500 programs) and ``ccopt verify``
and ``ccopt feed`` (100 programs). Whatever the text:

* the exit code is 0, 1 or 2 (3 is an internal error, anything else a crash);
* an exit 2 prints one line ``PROGRAM:LINE:`` (``:COL`` optional) on stderr,
  located in the mutated program or the case's ``case.toml``;
* no run uses more than :data:`RUN_CPU_LIMIT_S` of CPU (a CPU-time interval
  timer stops a longer one, and the test fails with the program text): a
  bound on the work, which load from other processes does not change. How
  long the runs take on the clock is measured by ``bench/fuzz.py``, not here.

Each test counts how the runs ended and asserts the share that got past
reading the program (exit 0 or 1, or exit 2 from a later stage): mutations
that only ever make the reader refuse would exercise nothing else.
"""
from __future__ import annotations

import contextlib
import io
import json
import re
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from ccopt.cases import bundled_cases
from ccopt.cli import main
from text_mutations import mutate

#: Most CPU time one command may use on a mutated program, seconds (a bound on
#: the work against runaways; the slowest run of the fuzz takes a few seconds).
RUN_CPU_LIMIT_S = 20.0
#: Mutated programs through show and compensate, and through verify and feed.
SHOW_PROGRAMS, VERIFY_PROGRAMS = 500, 100
FUZZ_SEED = 20261202
#: Share of the runs that must get past reading the mutated program (to
#: compensation and beyond): measured 62 % (show, compensate) and 60 % (verify,
#: feed) with FUZZ_SEED; the rest are located refusals of the reader.
SHARE_PAST_READING = 0.55


def _seeds() -> list[tuple[Path, str, str]]:
    """``(case folder, program file name, program text)`` of every bundled
    program: each case's own, and the pocket's G-code version."""
    out = []
    for case in bundled_cases():
        out.append((case.folder, case.program.name, case.program.read_text()))
    pocket = next(c for c in bundled_cases() if c.name == "pocket")
    out.append((pocket.folder, "pocket.nc", (pocket.folder / "pocket.nc").read_text()))
    return out


SEEDS = _seeds()

# Tokens of both dialects, numbers that grow a value by orders of magnitude,
# and the O-word loop and PMAC words that make a program run long.
TOKENS = ["X", "Y", "Z", "I", "J", "K", "R", "F", "G0", "G1", "G2", "G3", "G41", "G42", "G40",
          "G91", "G90", "G20", "G93", "D1", "CC1", "CC2", "CC0", "CCR", "CIRCLE1", "CIRCLE2",
          "LINEAR", "RAPID", "INC", "ABS", "[", "]", "(", ")", "#1", "#1=", "P1=", "0", "1",
          "9", "-", ".", "000", "99999", "1e400", "e", ";", " ", "\n",
          "\no1 while [1]\n", "\no1 endwhile\n", "\no2 repeat [99999]\n", "\no2 endrepeat\n",
          "X1e9", "J-1000000000000", "R0.001", "F0.0001", "TM1"]

_LOCATED = re.compile(r":\d+(:\d+)?: \S")


class _Overtime(BaseException):
    """Raised by the interval timer: a run used more than RUN_CPU_LIMIT_S. A
    BaseException, so the command's own ``except Exception`` lets it through."""


def _overtime(signum, frame):
    raise _Overtime()


@st.composite
def mutated_case(draw):
    folder, name, text = draw(st.sampled_from(SEEDS))
    return folder, name, mutate(draw, text, inserts=TOKENS, replaces=TOKENS, edits=(1, 4),
                                delete_max=8)


def _write_case(root: Path, k: int, folder: Path, name: str, text: str) -> tuple[Path, Path]:
    """A copy of the case at ``folder`` under ``root`` whose program is ``text``."""
    dest = root / f"m{k:04d}"
    dest.mkdir()
    toml = (folder / "case.toml").read_text()
    toml = re.sub(r"(?m)^program\s*=.*$", f'program = "{name}"', toml)
    (dest / "case.toml").write_text(toml)
    (dest / name).write_text(text)
    return dest, dest / name


def _run(argv: list[str]) -> tuple[int, str]:
    """``ccopt argv`` in-process: exit code and stderr; stops the run with
    :class:`_Overtime` once it has used :data:`RUN_CPU_LIMIT_S` of CPU."""
    err = io.StringIO()
    old = signal.signal(signal.SIGPROF, _overtime)
    signal.setitimer(signal.ITIMER_PROF, RUN_CPU_LIMIT_S)
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            try:
                code = main(argv)
            except SystemExit as exc:  # argparse's own exit
                code = exc.code
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, old)
    return code, err.getvalue()


def _check(commands: list[list[str]], folder: Path, program: Path, text: str,
           ends: list[str]) -> list[str]:
    """Run each command on the mutated case ``folder``; what is wrong with
    its exit, message or work (empty: nothing). How each run ended goes to
    ``ends``: ``"ran"`` (exit 0 or 1), ``"read"`` (exit 2 located in the
    program's text by the reader), ``"later"`` (exit 2 from a later stage)."""
    problems = []
    for cmd in commands:
        name = f"ccopt {' '.join(cmd)}"
        try:
            code, err = _run([*cmd, str(folder)])
        except _Overtime:
            problems.append(f"{name} used more than {RUN_CPU_LIMIT_S} s of CPU on:\n{text}")
            continue
        if code not in (0, 1, 2):
            problems.append(f"{name}: exit {code}: {err}\n{text}")
        elif code == 2:
            lines = err.strip().splitlines()
            located = [str(program), str(folder / "case.toml")]
            if len(lines) != 1 or not any(lines[0].startswith(f)
                                          and _LOCATED.match(lines[0], len(f))
                                          for f in located):
                problems.append(f"{name}: not one line file:line: message: {err}\n{text}")
            ends.append("later" if _refused_after_reading(program, text) else "read")
        else:
            ends.append("ran")
    return problems


def _refused_after_reading(program: Path, text: str) -> bool:
    """Whether ccopt's reader accepts ``text`` (so an exit 2 came from a later
    stage: compensation, the feed planner, a size limit)."""
    from ccopt.program import read_program
    try:
        read_program(program)
    except Exception:  # noqa: BLE001 - any refusal of the reader
        return False
    return True


def _fuzz(tmp_path: Path, commands: list[list[str]], programs: int) -> dict[str, int]:
    """``programs`` mutated cases through ``commands``; how the runs ended
    (counts of ``"ran"``, ``"read"``, ``"later"``). Problems are collected and
    reported together after the run (not raised inside Hypothesis, which
    would re-run a slow example)."""
    ends: list[str] = []
    problems: list[str] = []
    count = [0]

    @seed(FUZZ_SEED + programs)
    @settings(max_examples=programs, deadline=None, database=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(case=mutated_case())
    def one(case):
        folder, name, text = case
        count[0] += 1
        dest, program = _write_case(tmp_path, count[0], folder, name, text)
        problems.extend(_check(commands, dest, program, text, ends))

    one()
    assert not problems, f"{len(problems)} problems:\n" + "\n----\n".join(problems)
    assert count[0] >= programs
    assert len(ends) == len(commands) * count[0]
    tally = {k: ends.count(k) for k in ("ran", "read", "later")}
    print(f"fuzz {commands}: {count[0]} programs, runs {tally}")
    return tally


def _fuzz_isolated(tmp_path: Path, commands: list[list[str]], programs: int) -> dict[str, int]:
    """:func:`_fuzz` in a fresh interpreter: the examples Hypothesis draws from
    the fixed seed depend on the engine's state in the process (after the rest
    of the suite, the verify/feed run drew other programs from example 18 on),
    so the test runs where only it has run and draws the same programs
    wherever it runs in the suite."""
    out = subprocess.run([sys.executable, __file__, json.dumps(commands), str(programs),
                          str(tmp_path)], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    print(out.stdout)
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_mutated_programs_through_show_and_compensate(tmp_path):
    ends = _fuzz_isolated(tmp_path, [["show"], ["compensate"]], SHOW_PROGRAMS)
    assert ends["ran"] + ends["later"] >= SHARE_PAST_READING * 2 * SHOW_PROGRAMS, ends


@pytest.mark.slow
def test_mutated_programs_through_verify_and_feed(tmp_path):
    ends = _fuzz_isolated(tmp_path, [["verify"], ["feed"]], VERIFY_PROGRAMS)
    assert ends["ran"] + ends["later"] >= SHARE_PAST_READING * 2 * VERIFY_PROGRAMS, ends


if __name__ == "__main__":      # one fuzz run, for _fuzz_isolated
    print(json.dumps(_fuzz(Path(sys.argv[3]), json.loads(sys.argv[1]), int(sys.argv[2]))))
