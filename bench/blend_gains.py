"""Benchmark: the gains of the optimised blends over the fastest controller,
on generated CAM plates, against what any lead blend could gain at most.

For each program of the tests' CAM-style generator (``tests/cam_programs.py``:
rectangles and star polygons, mid-edge and corner entries, arc and
perpendicular leads, tool radii 0.5-5 mm, G-code and PMAC) ``ccopt compare``
runs the controller variants and the optimised ones under (a) v/a limits and
(b) v/a/j limits, and this prints per program and variant the gain over the
fastest certified controller variant (``gain_vs_fastest_controller``), then
the medians.

The bound. A lead blend keeps the fastest controller's path but for its lead
runs, each replaced by a curve from the same approach point ``A`` to the same
join ``J`` at the lead's feed, so no lead blend runs faster than that path's
feed-limited time (:func:`ccopt.feed.feed_limited_time`: every feed move at
its feed, no acceleration limit) with each lead run replaced by its chord
``|A - J|`` at its feed. ``bound`` is the gain that time would give over the
fastest controller's cycle time: no lead blend of the program can gain more
(the smoother, which also changes corners, is not bound by it).

It also checks the property the comparison promises: every optimised row is
certified and no slower than the fastest certified controller variant
(relative :data:`~ccopt.compare.baseline.SAME_TIME_REL`); exit 1 and the rows
that break it otherwise.

    python bench/blend_gains.py [--programs 20] [--first 0] [--search 0] [--workers N]
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from cam_programs import cam_program  # noqa: E402

from ccopt.compare import compare  # noqa: E402
from ccopt.compare.baseline import SAME_TIME_REL  # noqa: E402
from ccopt.compare.contract import CONTROLLER_NAMES  # noqa: E402
from ccopt.compare.leads import find_leads  # noqa: E402
from ccopt.feed import AxisLimits, feed_limited_time  # noqa: E402
from ccopt.program import read_text  # noqa: E402

OPTIMISED = ("opt-casadi", "opt-cvxpy", "smooth")
LIMITS = {
    "a": AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0)),
    "b": AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0),
                    j=(20000.0, 20000.0, 10000.0)),
}


def lead_bound(path, limits: AxisLimits, duration: float) -> float:
    """The largest gain (share of ``duration``) any lead blend of ``path`` can
    have (module docstring)."""
    t = feed_limited_time(path, limits)
    segs = path.segments
    for ld in find_leads(path):
        run = range(ld.first, ld.host) if ld.kind == "in" else range(ld.host + 1, ld.last + 1)
        feed = segs[ld.first if ld.kind == "in" else ld.last].feed
        if not run or not feed:
            continue
        a = segs[run[0]].start
        b = segs[run[-1]].end
        t -= sum(segs[i].length for i in run) / feed - math.dist(a, b) / feed
    return 1.0 - t / duration


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--programs", type=int, default=20)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--search", type=int, default=0, help="planner search runs per lead")
    ap.add_argument("--workers", type=int, default=None)
    args = ap.parse_args(argv)
    gains: dict = {(k, v): [] for k in LIMITS for v in OPTIMISED}
    broken: list[str] = []      # rows not certified, or slower than the fastest controller
    bounds: dict = {k: [] for k in LIMITS}
    print("seed limits fastest_controller  " + "  ".join(OPTIMISED) + "  lead_bound")
    for seed in range(args.first, args.first + args.programs):
        cp = cam_program(seed)
        prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
        for key, limits in LIMITS.items():
            kw = {} if args.workers is None else {"workers": args.workers}
            cmp = compare(prog, list(CONTROLLER_NAMES) + list(OPTIMISED), limits=limits,
                          options={"search": args.search}, **kw)
            rows = {r.name: r for r in cmp}
            fastest = rows["pmac"].figures.get("fastest_controller")
            if fastest is None:
                print(f"{seed:4d} {key}      (no certified controller)")
                continue
            base = rows[fastest]
            bound = lead_bound(base.toolpath, limits, base.figures["duration"])
            bounds[key].append(bound)
            line = []
            for name in OPTIMISED:
                r = rows[name]
                g = r.figures.get("gain_vs_fastest_controller")
                if r.status != "ok" or not r.certificate.ok or g is None \
                        or g < -SAME_TIME_REL:
                    broken.append(f"seed {seed} ({key}) {name}: {r.status} {r.message}")
                line.append("-" if g is None else f"{g:+.4f}")
                if g is not None:
                    gains[(key, name)].append(g)
            print(f"{seed:4d} {key}      {fastest:18s}  " + "  ".join(line) + f"  {bound:+.4f}")
    print("\nmedians over the programs (gain over the fastest certified controller variant)")
    for key in LIMITS:
        parts = [f"{name} {statistics.median(gains[(key, name)]):+.4f}"
                 for name in OPTIMISED if gains[(key, name)]]
        if bounds[key]:
            parts.append(f"lead bound {statistics.median(bounds[key]):+.4f}")
        print(f"  ({key}) " + ", ".join(parts))
    print(f"optimised rows certified and never slower than the fastest controller: "
          f"{'all' if not broken else f'{len(broken)} not'}")
    for line in broken:
        print("  " + line)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
