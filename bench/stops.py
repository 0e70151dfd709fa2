"""How soon ccopt stops: on a runaway O-word loop (the loop limit, exit 2)
and on Ctrl-C during ``run`` and a parallel ``compare`` (exit 130).

The tests (tests/test_inputs.py, tests/test_run_workers.py) assert that each
stops, how (exit code, located message, no worker or partial file left) and
by what rule (a count of loop lines); the time it takes is measured here:

* runaway loops: the wall time of ``ccopt show`` in a fresh process on each
  of the tests' runaway programs, the median of ``--repeat`` runs, against
  the same command on a two-move program (the peer: the interpreter's start
  and ccopt's imports, which every run pays), as a ratio; and the in-process
  reading of each kind of runaway loop;
* Ctrl-C: the seconds from SIGINT to the end of the process for
  ``ccopt run leadin-inside-line pocket --workers 2`` (interrupted 2 s after
  both workers are up) and ``ccopt compare freeform-hsm --workers 2`` (2.5 s),
  each ``--repeat`` times. The old tests held these under 5 s (loops) and 1 s
  (Ctrl-C).

    .venv/bin/python bench/stops.py [--repeat 3] [--no-interrupt]

Timings on a shared machine are inflated by the other load: compare ratios
from one run, not absolute figures across runs.
"""
from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from ccopt.errors import ProgramError  # noqa: E402
from ccopt.program.gcode import read_gcode  # noqa: E402
import test_inputs  # noqa: E402
import test_run_workers  # noqa: E402

PEER = "G21 F600\nG1 X1 Y0\nG1 Y1\nM2\n"
KINDS = {
    "while": "o1 while [1]\no1 endwhile\n",
    "do-while": "o1 do\no1 while [1]\n",
    "repeat 1e30": "o1 repeat [10 ** 30]\no1 endrepeat\n",
    "while + continue": "#1 = 0\no1 while [1]\n#1 = [#1 + 1]\no1 continue\no1 endwhile\n",
}


def show_seconds(text: str, repeat: int) -> tuple[float, int]:
    """Median wall time of ``ccopt show`` on ``text`` in a fresh process, and its exit code."""
    times, code = [], None
    with tempfile.TemporaryDirectory() as d:
        prog = Path(d) / "p.nc"
        prog.write_text(text)
        for _ in range(repeat):
            t0 = time.perf_counter()
            done = subprocess.run([sys.executable, "-m", "ccopt.cli", "show", str(prog)],
                                  capture_output=True, text=True, cwd=ROOT)
            times.append(time.perf_counter() - t0)
            code = done.returncode
    return statistics.median(times), code


def read_seconds(text: str, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        try:
            read_gcode(text, "p.nc")
        except ProgramError:
            pass
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-interrupt", action="store_true", help="time the runaway loops only")
    args = ap.parse_args()
    peer, _ = show_seconds(PEER, args.repeat)
    print(f"ccopt show, fresh process, median of {args.repeat}; peer (a two-move program): "
          f"{peer:.2f} s")
    for name, text in (("runaway, short body", test_inputs.RUNAWAY),
                       ("runaway, 48-move body", test_inputs.LONG_RUNAWAY)):
        t, code = show_seconds(text, args.repeat)
        print(f"  {name:24s} {t:6.2f} s  exit {code}  {t / peer:5.2f}x the peer")
    print("reading each kind of runaway loop in-process:")
    for name, loop in KINDS.items():
        print(f"  {name:24s} {read_seconds('G21' + chr(10) + loop, args.repeat):6.2f} s")
    if args.no_interrupt:
        return
    print(f"Ctrl-C to the end of the process, {args.repeat} runs each:")
    for label, argv, busy in (
            ("run leadin-inside-line pocket", ["run", "leadin-inside-line", "pocket", "-o",
                                               None, "--workers", "2"], 2.0),
            ("compare freeform-hsm", ["compare", "freeform-hsm", "--workers", "2"], 2.5)):
        stops, codes = [], []
        for _ in range(args.repeat):
            with tempfile.TemporaryDirectory() as d:
                cmd = [Path(d, "out").as_posix() if a is None else a for a in argv]
                code, _, stopped, _ = test_run_workers._interrupt(cmd, busy)
            stops.append(stopped)
            codes.append(code)
        print(f"  {label:30s} median {statistics.median(stops):.2f} s, max {max(stops):.2f} s  "
              f"exits {codes}")


if __name__ == "__main__":
    main()
