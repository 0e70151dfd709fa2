"""Wall time and peak memory of every command on issue 29's bad programs.

tests/test_safety.py runs the arc of 2^31 turns (``G2 ... P2147483647``), the
line to ``X1000000000`` and an empty program through show, verify,
verify --feed, feed, export, compare and run, each in a fresh process, and
asserts a located exit 2 (or "nothing to ...", exit 0) within 200 MB; how
long they take on the clock is measured here (the issue asks for 2 s each).

    .venv/bin/python bench/bad_inputs.py [--repeat 3]

Prints, per program and command, the exit code, the median wall time and the
peak memory (the process's own, by ``os.wait4``). Timings on a shared machine
are inflated by the other load.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_safety import BAD, COMMANDS  # noqa: E402 - the test's own programs and commands


def timed(argv: list[str], cwd: Path) -> tuple[int, float, float]:
    """``(exit code, wall seconds, peak bytes)`` of ``ccopt argv``."""
    t0 = time.perf_counter()
    p = subprocess.Popen([sys.executable, "-m", "ccopt.cli", *argv], cwd=cwd,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    return os.waitstatus_to_exitcode(status), time.perf_counter() - t0, usage.ru_maxrss * 1024.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3, help="runs per command (median taken)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        print(f"{'program':14s} {'command':14s} exit  wall_s   peak_MB")
        for name, (text, _, _) in BAD.items():
            prog = folder / name
            prog.write_text(text)
            for command, argv in COMMANDS.items():
                argv = [a.format(out=folder) for a in argv]
                argv.insert(1, str(prog))
                runs = [timed(argv, folder) for _ in range(args.repeat)]
                wall = statistics.median(r[1] for r in runs)
                peak = max(r[2] for r in runs)
                print(f"{name:14s} {command:14s} {runs[0][0]:4d}  {wall:6.2f}  {peak / 1e6:8.0f}")


if __name__ == "__main__":
    main()
