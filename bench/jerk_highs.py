"""The jerk planner's LPs under two values of one HiGHS setting, on the same plans.

``--setting pricing``: ``ccopt.feed.jerk.lp.DUAL_EDGE_WEIGHTS``, how HiGHS's
dual simplex prices the window LPs: 1 (Devex, ccopt's setting) or 2
(steepest edge, HiGHS's default). ``--setting scaling``:
``ccopt.feed.jerk.lp.SIMPLEX_SCALE``, how HiGHS scales them: 4 (max value,
ccopt's setting) or 2 (equilibration, HiGHS's default). ``--setting start``:
``ccopt.feed.jerk.lp.CRASH``, the basis a window's first solve starts from:
ccopt's crash basis (``WindowLP._crash``) or HiGHS's slack basis.
``--setting perturbation``: ``ccopt.feed.jerk.lp.WARM_PERTURBATION``, HiGHS's
cost perturbation in the re-solves from the last round's basis: none
(ccopt's setting) or HiGHS's default. This plans the same
paths with the jerk planner under each value, alternating, and prints per
path the median CPU time of each, their ratio and the cycle times (the LP is
the same; the figures agree to the LP's tolerances):

* PMAC's path of bundled cases under their jerk limits, or ten times their
  acceleration limits where they give none;
* the 1,000-block pocket and the 1,000-chord CAM program of ``bench/feed.py``
  under its jerk limits.

Every window is solved in this process (``PARALLEL_MIN_POINTS`` raised past
every path): worker processes start afresh from the files and would not see
the setting (the 1,000-block pocket has about 66,000 gridpoints, past the
default).

    python bench/jerk_highs.py [--setting pricing|scaling|start|perturbation] [--repeat 3]
                               [--cases fagor-g136-g138,pocket]
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
from ccopt.feed.jerk import lp, windows  # noqa: E402
from ccopt.feed.limits import AxisLimits  # noqa: E402
from ccopt.pipeline import pipeline  # noqa: E402

#: Per setting: the attribute of ``ccopt.feed.jerk.lp`` and its two values,
#: ccopt's first.
SETTINGS = {"pricing": ("DUAL_EDGE_WEIGHTS", {"devex": 1, "steepest edge": 2}),
            "scaling": ("SIMPLEX_SCALE", {"max value": 4, "equilibration": 2}),
            "start": ("CRASH", {"crash basis": True, "slack basis": False}),
            "perturbation": ("WARM_PERTURBATION", {"none": 0.0, "HiGHS's": 1.0})}
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


def bench_path(label: str, path, limits: AxisLimits, repeat: int, setting: str) -> dict:
    """Median CPU seconds and the cycle time of the jerk plan of ``path`` under
    each value of ``setting``; ``ratio``: ccopt's value over the other."""
    attr, values = SETTINGS[setting]
    seconds = {k: [] for k in values}
    duration = {}
    for _ in range(repeat):
        for name, value in values.items():
            setattr(lp, attr, value)
            c0 = time.process_time()
            prof = plan_feed(path, limits, planner="jerk")
            seconds[name].append(time.process_time() - c0)
            duration[name] = prof.duration
    ours, other = values
    setattr(lp, attr, values[ours])
    med = {k: statistics.median(v) for k, v in seconds.items()}
    return {"path": label, "seconds": med, "ratio": med[ours] / med[other],
            "cycle": duration}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--setting", choices=tuple(SETTINGS), default="pricing")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    args = ap.parse_args()
    windows.PARALLEL_MIN_POINTS = sys.maxsize       # see the module docstring
    paths = [(c, *case_path(c)) for c in args.cases.split(",") if c]
    vmax, amax = (200.0, 200.0, 50.0), (2000.0, 2000.0, 500.0)
    for label, prog in (("pocket-1000 (bench/feed.py)", pocket_program(1000)),
                        ("cam-1000 (bench/feed.py)", cam_program(1000))):
        paths.append((label, compensate(prog, "pmac"), AxisLimits(v=vmax, a=amax, j=JERK)))
    ours, other = SETTINGS[args.setting][1]
    print(f"{'path':30s} {ours + ' s':>14s} {other + ' s':>14s} {'ratio':>6s}  cycle time "
          f"{ours} / {other} (s), relative difference")
    ratios = []
    for label, path, limits in paths:
        r = bench_path(label, path, limits, args.repeat, args.setting)
        ratios.append(r["ratio"])
        a, b = r["cycle"][ours], r["cycle"][other]
        print(f"{label:30s} {r['seconds'][ours]:14.3f} {r['seconds'][other]:14.3f} "
              f"{r['ratio']:6.2f}  {a:.9g} / {b:.9g}, {a / b - 1.0:+.2e}", flush=True)
    print(f"median ratio {ours} / {other}: {statistics.median(ratios):.2f} "
          f"(CPU, medians of {args.repeat})")


if __name__ == "__main__":
    main()
