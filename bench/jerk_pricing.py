"""The jerk planner's LPs under HiGHS's two dual simplex pricings, on the same plans.

``ccopt.feed.jerk.lp.DUAL_EDGE_WEIGHTS`` chooses how HiGHS's dual simplex
prices its window LPs: 1 (Devex, ccopt's setting) or 2 (steepest edge,
HiGHS's default). This plans the same paths with the jerk planner under
each, alternating, and prints per path the median wall time of each, their
ratio and the cycle times (the LP's optimum is the same; the figures agree
to the LP's tolerances):

* PMAC's path of bundled cases under their jerk limits, or ten times their
  acceleration limits where they give none;
* the 1,000-block pocket and the 1,000-chord CAM program of ``bench/feed.py``
  under its jerk limits.

Paths are kept below the size at which the planner hands windows to worker
processes, which start afresh and would not see the setting.

    python bench/jerk_pricing.py [--repeat 3] [--cases fagor-g136-g138,pocket]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from feed import JERK, cam_program, pocket_program  # noqa: E402

from ccopt.cases import make_job  # noqa: E402
from ccopt.compensate import compensate  # noqa: E402
from ccopt.feed import plan_feed  # noqa: E402
from ccopt.feed.jerk import lp  # noqa: E402
from ccopt.feed.limits import AxisLimits  # noqa: E402
from ccopt.pipeline import pipeline  # noqa: E402

PRICINGS = {"devex": 1, "steepest edge": 2}
CASES = ("fagor-g136-g138", "fagor-seed-arc-cancel", "sinumerik-sar-plate", "pocket",
         "pocket-chords", "profile", "freeform-hsm")


def case_path(name: str):
    """PMAC's path of bundled case ``name`` and its limits with jerk."""
    done = pipeline(make_job(name), compare=False, export=[])
    radius = None if done.path is None else done.path.radius
    path = compensate(done.program, "pmac", radius=radius)
    lim = done.limits
    jerk = lim.j if lim.j else tuple(10.0 * a for a in lim.a)
    return path, AxisLimits(v=lim.v, a=lim.a, j=jerk)


def bench_path(label: str, path, limits: AxisLimits, repeat: int) -> dict:
    seconds = {k: [] for k in PRICINGS}
    duration = {}
    for _ in range(repeat):
        for name, value in PRICINGS.items():
            lp.DUAL_EDGE_WEIGHTS = value
            t0 = time.perf_counter()
            prof = plan_feed(path, limits, planner="jerk")
            seconds[name].append(time.perf_counter() - t0)
            duration[name] = prof.duration
    lp.DUAL_EDGE_WEIGHTS = PRICINGS["devex"]
    med = {k: statistics.median(v) for k, v in seconds.items()}
    return {"path": label, **{f"s {k}": v for k, v in med.items()},
            "ratio": med["devex"] / med["steepest edge"],
            "cycle devex": duration["devex"], "cycle steepest": duration["steepest edge"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    args = ap.parse_args()
    paths = [(c, *case_path(c)) for c in args.cases.split(",") if c]
    vmax, amax = (200.0, 200.0, 50.0), (2000.0, 2000.0, 500.0)
    for label, prog in (("pocket-1000 (bench/feed.py)", pocket_program(1000)),
                        ("cam-1000 (bench/feed.py)", cam_program(1000))):
        paths.append((label, compensate(prog, "pmac"), AxisLimits(v=vmax, a=amax, j=JERK)))
    print(f"{'path':30s} {'devex s':>8s} {'steepest s':>10s} {'ratio':>6s}  cycle time devex / "
          f"steepest edge (s), relative difference")
    ratios = []
    for label, path, limits in paths:
        r = bench_path(label, path, limits, args.repeat)
        ratios.append(r["ratio"])
        rel = r["cycle devex"] / r["cycle steepest"] - 1.0
        print(f"{label:30s} {r['s devex']:8.3f} {r['s steepest edge']:10.3f} {r['ratio']:6.2f}  "
              f"{r['cycle devex']:.9g} / {r['cycle steepest']:.9g}, {rel:+.2e}", flush=True)
    print(f"median ratio devex / steepest edge: {statistics.median(ratios):.2f} "
          f"(wall, medians of {args.repeat})")


if __name__ == "__main__":
    main()
