"""Benchmark: the optimised blends and the smoother on the pocket cases.

Measured in one run, medians of ``--repeat`` runs (the first run of each
also pays its imports, CasADi's or CVXPY's, and is left out when
``--repeat`` > 1):

- solve time of ``opt-casadi`` (IPOPT) and ``opt-cvxpy`` (Clarabel) for the
  pocket's lead-in and lead-out, verification of the result included;
- solve time of the smoother at ``delta`` = 1 % of the cutter radius (and at
  the other ``--deltas`` given, as fractions of the radius);
- TOPPRA cycle time of each under the case's limits, and its ratio to
  PMAC's;
- what bounds any path this close to PMAC's from below: every feed move at
  its programmed feed with no acceleration limit (the rapid at the axis
  speeds; ``ccopt.feed.feed_limited_time``), as a ratio to PMAC's cycle time.

Run on ``pocket`` (corners as arcs: it cuts at F30 most of the way, so the
floor is close to PMAC's time) and ``pocket-chords`` (the same pocket with
its corners as CAM chords: 66 inside corners where PMAC's exact path stops)
by default.

    python bench/blends.py [--case pocket,pocket-chords] [--repeat 3] [--deltas 0.01,0.1]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import ccopt  # noqa: E402
from ccopt.cases import find_case  # noqa: E402
from ccopt.compare import BlendOutcome, BlendProblem, load  # noqa: E402
from ccopt.compare.deviation import max_deviation  # noqa: E402
from ccopt.compare.figures import path_figures  # noqa: E402
from ccopt.compare.leads import lead_joins  # noqa: E402
from ccopt.feed import feed_limited_time as feed_bound  # noqa: E402


def timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat + (1 if repeat > 1 else 0)):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    if repeat > 1:
        times = times[1:]
    return statistics.median(times), out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="pocket,pocket-chords",
                    help="bundled case names or folders, comma-separated")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--deltas", default="0.01,0.1,0.3",
                    help="smoother bands as fractions of the cutter radius")
    args = ap.parse_args(argv)
    for i, name in enumerate(args.case.split(",")):
        if i:
            print()
        bench_case(find_case(name), args.repeat, [float(f) for f in args.deltas.split(",")])
    return 0


def bench_case(case, repeat: int, deltas: list[float]) -> None:
    prog = ccopt.read_program(case.program)
    limits = ccopt.AxisLimits(case.vmax, case.amax)
    ref = ccopt.compensate(prog, "pmac")
    t_ref = ccopt.plan_feed(ref, limits).duration
    r = ref.radius
    print(f"{case.name}: cutter radius {r:g} {prog.units}, limits v={list(limits.v)} "
          f"a={list(limits.a)}, {repeat} runs (median)")
    print(f"PMAC cycle time {t_ref:.4f} s; feed-limited bound {feed_bound(ref, limits):.4f} s "
          f"= {feed_bound(ref, limits) / t_ref:.4f} of PMAC")
    print(f"{'variant':26s} {'solve_s':>8s} {'cycle_s':>8s} {'vs_pmac':>8s} {'bound':>8s} "
          f"{'certified':>9s} {'max_dev':>8s}  continuity")
    rows = [(name, {}) for name in ("opt-casadi", "opt-cvxpy")]
    rows += [(f"smooth delta={f:g}r", {"delta": f * r}) for f in deltas]
    for label, kw in rows:
        name = label.split()[0]
        blend = load(name)
        problem = BlendProblem(prog, ref, limits, kw.get("delta"))
        solve, out = timed(lambda: blend(problem), repeat)
        path = out.toolpath if isinstance(out, BlendOutcome) else out
        cert = out.info.get("certificate") if isinstance(out, BlendOutcome) else None
        cert = cert or problem.certify(path)
        t = ccopt.plan_feed(path, limits).duration
        dev, _ = max_deviation(path, ref)
        cont = path_figures(path, lead_joins(path))["continuity"]
        print(f"{label:26s} {solve:8.3f} {t:8.4f} {t / t_ref:8.4f} "
              f"{feed_bound(path, limits) / t_ref:8.4f} {str(cert.ok):>9s} {dev:8.4f}  {cont}")

if __name__ == "__main__":
    sys.exit(main())
