"""Wall time of ``ccopt run``: per case and per stage, serial and parallel.

Runs ``ccopt run`` twice in fresh processes on the same cases, once with
``--workers 1`` (one case after the other) and once with ``--workers N``
(default: one per core), and prints

* per case, the wall time of each stage (read, compensate, feed, verify,
  compare, export; from ``summary.json``'s ``stage_seconds``, measured in the
  worker that ran the case) in the serial run, and the case's total in both;
* the whole command's wall time (imports, workers, report included) in both,
  and the parallel/serial ratio.

::

    .venv/bin/python bench/run.py                        # every bundled case (long)
    .venv/bin/python bench/run.py leadin-inside-line pocket --workers 2
    .venv/bin/python bench/run.py --no-compare --json

Timings on a shared machine are inflated by the other load: compare ratios
from one run, not absolute figures across runs.

Run on every bundled case with the default options (no argument), it also
writes the main job's section of ``docs/benchmarks.md``: the table, the
machine (cores, platform), the load average before and after, the date and
the commit (``--no-write``: print only).

``--load N`` times the main job as on a busy machine: N processes that keep
a core busy each (a Python loop) run from a warm-up before the first run
until the last ends, and the runs are those a user makes (the parallel
one, with the default workers; ``--serial`` adds the serial one). On every
bundled case it writes a section of its own, "the main job at load N".
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from docs_section import commit, machine, now, speed_reference, write_section

ROOT = Path(__file__).resolve().parents[1]
STAGES = ("read", "compensate", "feed", "verify", "compare", "export")


def timed_run(cases: list[str], workers: int, extra: list[str], out: Path) -> dict:
    """``ccopt run`` in a fresh process: its wall time (s) and each case's row
    (name, status, stage_seconds)."""
    cmd = [sys.executable, "-m", "ccopt.cli", "run", *cases, "-o", str(out), "--workers",
           str(workers), "--quiet", *extra]
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        sys.exit(f"ccopt run failed ({proc.returncode}): {proc.stderr.strip()}")
    rows = json.loads((out / "summary.json").read_text())["cases"]
    return {"wall": wall, "workers": workers,
            "cases": [{"name": r["name"], "status": r["status"],
                       "stage_seconds": r.get("stage_seconds", {})} for r in rows]}


def report(serial: dict, parallel: dict) -> str:
    """The table: per case and stage (serial), each case's total serial and
    parallel, then the commands' wall times and their ratio."""
    w = max([len(r["name"]) for r in serial["cases"]] + [5])
    head = f"{'case'.ljust(w)}  " + "  ".join(f"{s:>10s}" for s in STAGES) + \
        f"  {'serial':>8s}  {'parallel':>8s}"
    lines = [head]
    par = {r["name"]: r for r in parallel["cases"]}
    for r in serial["cases"]:
        st = r["stage_seconds"]
        total = sum(st.values())
        ptotal = sum(par[r["name"]]["stage_seconds"].values())
        lines.append(f"{r['name'].ljust(w)}  " + "  ".join(
            f"{st[s]:10.3f}" if s in st else f"{'-':>10s}" for s in STAGES)
            + f"  {total:8.3f}  {ptotal:8.3f}")
    sums = {s: sum(r["stage_seconds"].get(s, 0.0) for r in serial["cases"]) for s in STAGES}
    lines.append(f"{'all'.ljust(w)}  " + "  ".join(f"{sums[s]:10.3f}" for s in STAGES))
    ratio = parallel["wall"] / serial["wall"]
    lines.append(f"ccopt run wall time: serial (--workers 1) {serial['wall']:.2f} s, parallel "
                 f"(--workers {parallel['workers']}) {parallel['wall']:.2f} s, "
                 f"parallel/serial {ratio:.3f}")
    return "\n".join(lines)


BENCHMARKS = ROOT / "docs" / "benchmarks.md"
#: the section this script writes in BENCHMARKS (between its markers)
SECTION = "bench/run.py"


def write_main_job(table: str, load_before: tuple, load_after: tuple, workers: int,
                   speed: tuple | None = None) -> None:
    """The main job's section of docs/benchmarks.md (``speed``: the speed
    reference before and after the runs, ms, :func:`docs_section.speed_reference`)."""
    write_section(BENCHMARKS, SECTION,
                  f"`python bench/run.py` on {now()}, commit {commit()}: "
                  f"{machine(load_before, load_after, speed)}; parallel run with --workers "
                  f"{workers}."
                  f"\n\n```\n{table}\n```")


#: Seconds the busy processes of ``--load`` run before the first timed run, so
#: that the 1-minute load average has risen towards N when the run starts.
LOAD_WARMUP = 60.0


@contextlib.contextmanager
def busy_processes(n: int):
    """``n`` processes each spinning a core (a Python loop) while the block runs."""
    procs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(n)]
    try:
        if n:
            time.sleep(LOAD_WARMUP)
        yield
    finally:
        for p in procs:
            p.kill()
            p.wait()


def loaded_report(parallel: dict, serial: dict | None, n: int) -> str:
    """The table of a ``--load`` run: per case its total, then the wall times."""
    w = max([len(r["name"]) for r in parallel["cases"]] + [5])
    lines = [f"{'case'.ljust(w)}  {'compare':>8s}  {'case':>8s}"]
    for r in parallel["cases"]:
        st = r["stage_seconds"]
        lines.append(f"{r['name'].ljust(w)}  {st.get('compare', 0.0):8.3f}  "
                     f"{sum(st.values()):8.3f}")
    lines.append(f"ccopt run wall time with {n} busy processes: parallel (--workers "
                 f"{parallel['workers']}) {parallel['wall']:.2f} s"
                 + (f", serial (--workers 1) {serial['wall']:.2f} s" if serial else ""))
    return "\n".join(lines)


def write_loaded(table: str, load_before: tuple, load_start: tuple, load_after: tuple,
                 n: int) -> None:
    """The section "the main job at load ``n``" of docs/benchmarks.md."""
    fmt = lambda la: "/".join(f"{x:.2f}" for x in la)  # noqa: E731
    write_section(BENCHMARKS, f"{SECTION} --load {n}",
                  f"`python bench/run.py --load {n}` on {now()}, commit {commit()}: "
                  f"{os.cpu_count()} cores, {platform.platform()}, Python "
                  f"{platform.python_version()}; {n} busy processes started "
                  f"{LOAD_WARMUP:.0f} s before the run; load average (1/5/15 min) "
                  f"{fmt(load_before)} before they started, {fmt(load_start)} when the run "
                  f"started, {fmt(load_after)} after it.\n\n```\n{table}\n```")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", nargs="*", help="cases or programs (default: every bundled case)")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                    help="workers of the parallel run (default: one per core)")
    ap.add_argument("--no-compare", action="store_true", help="pass --no-compare")
    ap.add_argument("--variants", help="pass --variants")
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    ap.add_argument("--load", type=int, default=0, metavar="N",
                    help="time the parallel run with N busy processes beside it")
    ap.add_argument("--serial", action="store_true",
                    help="with --load: time the serial run under the load too")
    ap.add_argument("--no-write", action="store_true",
                    help="do not write docs/benchmarks.md (written only for every bundled case "
                         "with the default options)")
    args = ap.parse_args()
    load_before = os.getloadavg()
    speed_before = speed_reference()
    extra = ["--no-compare"] if args.no_compare else []
    if args.variants:
        extra += ["--variants", args.variants]
    if args.load:
        loaded(args, extra, load_before)
        return
    with tempfile.TemporaryDirectory() as tmp:
        serial = timed_run(args.cases, 1, extra, Path(tmp) / "serial")
        parallel = timed_run(args.cases, args.workers, extra, Path(tmp) / "parallel")
    if args.json:
        print(json.dumps({"serial": serial, "parallel": parallel,
                          "ratio": parallel["wall"] / serial["wall"]}))
    else:
        print(report(serial, parallel))
    if not (args.no_write or args.cases or extra):
        write_main_job(report(serial, parallel), load_before, os.getloadavg(), args.workers,
                       (speed_before, speed_reference()))
        print(f"written: {BENCHMARKS.relative_to(ROOT)}")


def loaded(args, extra: list[str], load_before: tuple) -> None:
    """``--load``: the parallel run (and the serial one with ``--serial``)
    beside ``args.load`` busy processes; prints and writes its section."""
    with busy_processes(args.load), tempfile.TemporaryDirectory() as tmp:
        load_start = os.getloadavg()
        parallel = timed_run(args.cases, args.workers, extra, Path(tmp) / "parallel")
        serial = timed_run(args.cases, 1, extra, Path(tmp) / "serial") if args.serial else None
        load_after = os.getloadavg()
    table = loaded_report(parallel, serial, args.load)
    if args.json:
        print(json.dumps({"load": args.load, "parallel": parallel, "serial": serial}))
    else:
        print(table)
    if not (args.no_write or args.cases or extra):
        write_loaded(table, load_before, load_start, load_after, args.load)
        print(f"written: {BENCHMARKS.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
