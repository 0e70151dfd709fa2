"""The jerk planner on graded and on even grids, on the same paths.

``ccopt.feed.jerk.planner.GRADED`` chooses the LP's gridpoints on lines and
arcs: graded by S-curve ramps (True, ccopt's setting: dense within the ramp
zones at both ends of a segment, growing in between where the speed is at
its cap) or evenly spaced by TOPPRA's braking rule (False). This plans the
same paths under both, alternating, and prints per path the gridpoints, the
median wall time of each, their ratio and the relative difference of the
cycle times:

* PMAC's path of every bundled case (but those that end in an error) under
  its jerk limits, or ten times its acceleration limits where it gives none;
* ``--generated N`` CAM programs of the tests' generator
  (``tests/cam_programs.py``, seeds 0..N-1), PMAC style, under limits drawn
  from the seed (v 50-300 mm/s, a 500-5000 mm/s^2, j 5-50 times a).

Paths are kept below the size at which the planner hands windows to worker
processes, which start afresh and would not see the setting. With
``--write`` (every bundled case, the default three rounds) the table goes
into its section of ``docs/benchmarks.md``.

    python bench/jerk_grid.py [--repeat 3] [--generated 40] [--cases a,b] [--write]
"""
from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from cam_programs import cam_program  # noqa: E402
from docs_section import commit, now, write_section  # noqa: E402

from ccopt.cases import bundled_cases, resolve_input  # noqa: E402
from ccopt.compensate import compensate  # noqa: E402
from ccopt.feed import ExactPath, plan_feed  # noqa: E402
from ccopt.feed.jerk import planner  # noqa: E402
from ccopt.feed.limits import AxisLimits  # noqa: E402
from ccopt.program import read_text  # noqa: E402


def case_paths(names: list[str] | None):
    """``(label, ExactPath, limits)`` of PMAC's path of each bundled case."""
    for case in bundled_cases():
        if case.expect == "error" or (names and case.name not in names):
            continue
        job = resolve_input(case)
        path = ExactPath(compensate(job.read(), "pmac", radius=job.radius))
        j = job.jmax or tuple(10.0 * a for a in job.amax)
        yield case.name, path, AxisLimits(job.vmax, job.amax, j=j)


def generated_paths(n: int):
    """``(label, ExactPath, limits)`` of the first ``n`` generated CAM programs."""
    for seed in range(n):
        cp = cam_program(seed)
        prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
        rng = random.Random(10_000 + seed)
        v, a = rng.uniform(50.0, 300.0), rng.uniform(500.0, 5000.0)
        j = a * rng.uniform(5.0, 50.0)
        yield f"cam seed {seed}", ExactPath(compensate(prog, "pmac")), \
            AxisLimits((v, v), (a, a), j=(j, j))


def bench_path(path, limits: AxisLimits, repeat: int) -> dict:
    default = planner.GRADED
    seconds = {True: [], False: []}
    figures = {}
    for _ in range(repeat):
        for graded in (True, False):
            planner.GRADED = graded
            t0 = time.perf_counter()
            prof = plan_feed(path, limits, planner="jerk")
            seconds[graded].append(time.perf_counter() - t0)
            figures[graded] = (prof.duration, prof.info["gridpoints"])
    planner.GRADED = default
    med = {k: statistics.median(v) for k, v in seconds.items()}
    return {"graded s": med[True], "even s": med[False], "ratio": med[True] / med[False],
            "graded gp": figures[True][1], "even gp": figures[False][1],
            "cycle": figures[True][0], "rel": figures[True][0] / figures[False][0] - 1.0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--generated", type=int, default=40)
    ap.add_argument("--cases", default="", help="bundled cases, comma-separated (default: all)")
    ap.add_argument("--write", action="store_true", help="write the docs/benchmarks.md section")
    args = ap.parse_args()
    names = [c for c in args.cases.split(",") if c] or None
    head = (f"| path | gridpoints graded / even | graded s | even s | time ratio | "
            f"cycle time graded (s) | relative to even |\n|---|---|---|---|---|---|---|")
    print(head)
    rows, ratios, rels = [], [], []
    for label, path, limits in [*case_paths(names), *generated_paths(args.generated)]:
        r = bench_path(path, limits, args.repeat)
        ratios.append(r["ratio"])
        rels.append(r["rel"])
        row = (f"| {label} | {r['graded gp']:,} / {r['even gp']:,} | {r['graded s']:.3f} | "
               f"{r['even s']:.3f} | {r['ratio']:.2f} | {r['cycle']:.6f} | {r['rel']:+.2e} |")
        rows.append(row)
        print(row, flush=True)
    summary = (f"{len(ratios)} paths: median time ratio graded / even "
               f"{statistics.median(ratios):.2f} (largest {max(ratios):.2f}); cycle time "
               f"relative to the even grid from {min(rels):+.2e} to {max(rels):+.2e} "
               f"(median {statistics.median(rels):+.2e})")
    print(summary)
    if args.write:
        body = (f"`python bench/jerk_grid.py --write` at {commit()}, {now()}, medians of "
                f"{args.repeat} (wall, one process, quiet machine). {summary}.\n\n"
                + head + "\n" + "\n".join(rows))
        write_section(ROOT / "docs" / "benchmarks.md", "bench/jerk_grid.py", body)


if __name__ == "__main__":
    main()
