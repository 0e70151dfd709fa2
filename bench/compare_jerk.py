"""Wall time of ``ccopt compare`` and ``ccopt run`` under jerk limits, per case.

For each case (default: every bundled case with a compensated path), in
fresh processes, medians of ``--rounds`` runs:

* ``ccopt compare CASE --jmax J`` (every variant, as ``compare`` runs by
  default), and without ``--jmax`` for the ratio;
* ``ccopt run CASE --jmax J`` and ``ccopt run CASE`` (the main job's
  variants), and their ratio.

``J`` is the case's own ``[limits] j`` where it has one, else ten times its
acceleration limits per axis (the axis reaches its full acceleration in
0.1 s, as freeform-hsm's limits have it); cases without limits get ten times
the default acceleration. Each command runs in a fresh interpreter, so its
imports are in every figure, as a user sees them.

::

    .venv/bin/python bench/compare_jerk.py                    # every case, 3 rounds (long)
    .venv/bin/python bench/compare_jerk.py pocket freeform-hsm --rounds 1 --no-run

Run on every bundled case with three rounds (with or without ``--no-run``) it
writes its section of ``docs/benchmarks.md`` (``--no-write``: print only).
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from docs_section import commit, now, write_section

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ccopt.cases import DEFAULT_LIMITS, bundled_cases, find_case  # noqa: E402

#: Jerk limit per axis when a case gives none: this many times its acceleration
#: limit (1/s): full acceleration reached in 1/JERK_PER_ACC seconds.
JERK_PER_ACC = 10.0


def jerk_of(name: str) -> tuple[float, ...]:
    """The jerk limits the case is timed under (see the module docstring)."""
    case = find_case(name)
    if case is not None and case.jmax:
        return case.jmax
    acc = case.amax if case is not None and case.amax else tuple(DEFAULT_LIMITS["a"])
    return tuple(JERK_PER_ACC * a for a in acc)


def wall(cmd: list[str]) -> float:
    """Seconds ``cmd`` took in a fresh process (exit 0 or 1 expected)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    seconds = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        sys.exit(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.strip()[-2000:]}")
    return seconds


def median_wall(cmd: list[str], rounds: int) -> float:
    return statistics.median(wall(cmd) for _ in range(rounds))


def measure(name: str, rounds: int, with_run: bool, out: Path) -> dict:
    """The case's medians: compare with and without jerk, run with and without."""
    j = ",".join(f"{x:g}" for x in jerk_of(name))
    cli = [sys.executable, "-m", "ccopt.cli"]
    row = {"case": name, "jmax": j,
           "compare_jerk": median_wall(cli + ["compare", name, "--jmax", j, "-q"], rounds),
           "compare": median_wall(cli + ["compare", name, "-q"], rounds)}
    if with_run:
        run = cli + ["run", name, "-o", str(out / name), "-q"]
        row["run_jerk"] = median_wall(run + ["--jmax", j], rounds)
        row["run"] = median_wall(run, rounds)
    return row


def table(rows: list[dict], rounds: int) -> str:
    w = max([len(r["case"]) for r in rows] + [4])
    head = f"{'case'.ljust(w)}  {'compare -j':>10s}  {'compare':>8s}  {'ratio':>6s}"
    runs = "run_jerk" in rows[0]
    if runs:
        head += f"  {'run -j':>8s}  {'run':>8s}  {'ratio':>6s}"
    lines = [head]
    for r in rows:
        line = (f"{r['case'].ljust(w)}  {r['compare_jerk']:10.2f}  {r['compare']:8.2f}  "
                f"{r['compare_jerk'] / r['compare']:6.2f}")
        if runs:
            line += f"  {r['run_jerk']:8.2f}  {r['run']:8.2f}  {r['run_jerk'] / r['run']:6.2f}"
        lines.append(line)
    worst = max(rows, key=lambda r: r["compare_jerk"])
    lines.append(f"compare with jerk limits: slowest {worst['case']} {worst['compare_jerk']:.2f} s; "
                 f"median over cases {statistics.median(r['compare_jerk'] for r in rows):.2f} s "
                 f"(wall seconds, medians of {rounds} run(s) each, imports included)")
    if runs:
        tot_j, tot = sum(r["run_jerk"] for r in rows), sum(r["run"] for r in rows)
        lines.append(f"ccopt run summed over cases: {tot_j:.1f} s with jerk limits, {tot:.1f} s "
                     f"without, ratio {tot_j / tot:.2f}")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", nargs="*", help="cases (default: every bundled case)")
    ap.add_argument("--rounds", type=int, default=3, help="runs per command (median)")
    ap.add_argument("--no-run", action="store_true", help="time ccopt compare only")
    ap.add_argument("--no-write", action="store_true", help="do not write docs/benchmarks.md")
    args = ap.parse_args()
    names = args.cases or [c.name for c in bundled_cases() if c.expect != "error"]
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        rows = []
        for name in names:
            rows.append(measure(name, args.rounds, not args.no_run, Path(tmp)))
            print(table(rows[-1:], args.rounds).splitlines()[1], flush=True)
    text = table(rows, args.rounds)
    print(text)
    if not (args.no_write or args.cases) and args.rounds == 3:
        load = "/".join(f"{x:.2f}" for x in load_before), "/".join(
            f"{x:.2f}" for x in os.getloadavg())
        write_section(ROOT / "docs" / "benchmarks.md", "bench/compare_jerk.py",
                      f"`python bench/compare_jerk.py` on {now()}, commit {commit()}: "
                      f"{os.cpu_count()} cores, {platform.platform()}, Python "
                      f"{platform.python_version()}; load average (1/5/15 min) {load[0]} "
                      f"before, {load[1]} after. Jerk limits: the case's, else "
                      f"{JERK_PER_ACC:g} times its acceleration limits.\n\n```\n{text}\n```")
        print("written: docs/benchmarks.md")


if __name__ == "__main__":
    main()
