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

That bound is loose: the feed-limited time leaves out every acceleration of
the whole program, corners included. ``window_bound`` is tighter. A lead
blend changes the path only between the approach point ``A`` and the join
``J`` (``Q`` for a lead-out), and the comparison's timing rests on profiles
meeting again a few settle distances past a change (:mod:`ccopt_formulations.
lead_timing`); so a blend can save at most the fastest controller's time over
a window: for a lead-in from the path's start (the rapid to ``A`` starts at
rest) to ``reach`` past ``J``, for a lead-out from ``reach`` before ``J`` to
the path's end (the tool stops at ``Q``). No motion covers a window faster
than one-dimensional bounds: the rapid (a line the blend keeps) from rest
under its own direction's limits, arriving at the lead's feed
(:func:`rapid_to_feed`),
then the chord ``|A - J|`` and the reach
at the lead's feed (a lead-out's chord ending at rest, under the projection
of its motion on the chord: speed at most the feed, acceleration and jerk at
most their limits' norms). ``window_bound`` sums, over the leads, the controller's window time
less that, as a share of its cycle time.

It also checks the property the comparison promises: every optimised row is
certified and no slower than the fastest certified controller variant
(relative :data:`~ccopt.compare.baseline.SAME_TIME_REL`); exit 1 and the rows
that break it otherwise.

    python bench/blend_gains.py [--programs 20] [--first 0] [--search 0] [--workers N]
                                [--limits a|b|both] [--bounds-only]
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys

import numpy as np
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from cam_programs import cam_program  # noqa: E402

from ccopt.compare import compare  # noqa: E402
from ccopt.compare.baseline import SAME_TIME_REL  # noqa: E402
from ccopt.compare.contract import CONTROLLER_NAMES  # noqa: E402
from ccopt.compare.leads import find_leads  # noqa: E402
from ccopt.feed import AxisLimits, certified_planner, feed_limited_time, plan_feed  # noqa: E402
from ccopt.feed.path import ExactPath  # noqa: E402
from ccopt.program import read_text  # noqa: E402
from ccopt.toolpath import Role  # noqa: E402
from ccopt_formulations.lead_timing import SETTLE_SPANS, settle_distance  # noqa: E402

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


def travel_from_rest(L: float, v: float, a: float, j: float) -> float:
    """Least time (s) to travel ``L`` from rest in one dimension with speed
    <= ``v``, acceleration <= ``a``, jerk <= ``j`` and any end state: the
    jerk-limited ramp up to ``v``, then ``v``; the ramp's own distance by
    bisection on its closed-form position."""
    tj = min(a / j, math.sqrt(v / j))            # jerk phase (no constant-acceleration phase
    ta = max(v / a - a / j, 0.0)                 # when v < a^2 / j)
    ap = j * tj                                  # peak acceleration

    def pos(t: float) -> float:
        if t <= tj:
            return j * t ** 3 / 6.0
        p1, v1 = j * tj ** 3 / 6.0, 0.5 * j * tj * tj
        if t <= tj + ta:
            u = t - tj
            return p1 + v1 * u + 0.5 * ap * u * u
        u0 = ta
        p2, v2 = p1 + v1 * u0 + 0.5 * ap * u0 * u0, v1 + ap * u0
        u = min(t - tj - ta, tj)
        p3 = p2 + v2 * u + 0.5 * ap * u * u - j * u ** 3 / 6.0
        return p3 + v * max(t - 2.0 * tj - ta, 0.0)

    ramp = 2.0 * tj + ta
    if L >= pos(ramp):
        return ramp + (L - pos(ramp)) / v
    lo, hi = 0.0, ramp
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if pos(mid) < L else (lo, mid)
    return lo


def rapid_to_feed(L: float, v: float, a: float, j: float, f: float) -> float:
    """A lower bound (s) of the time to travel ``L`` from rest (acceleration 0)
    and arrive at speed <= ``f``, with speed <= ``v``, acceleration <= ``a``,
    jerk <= ``j`` (one dimension). At time ``t`` of a motion of duration ``T``
    the speed is at most ``v``, at most what rest reaches by ``t``
    (acceleration ``min(j t, a)``) and at most ``f + a (T - t)`` (it must come
    down to ``f`` by ``T``); ``T`` is the least whose integral of that envelope
    reaches ``L``. The integral is an upper Riemann sum (each step's larger end,
    plus one step at ``v`` for the peak), so the bound stays a lower bound."""
    f = min(f, v)

    def reach(T: float) -> float:
        t = np.linspace(0.0, T, 4001)
        rise = np.where(t <= a / j, 0.5 * j * t * t, 0.5 * a * a / j + a * (t - a / j))
        env = np.minimum(np.minimum(v, rise), f + a * (T - t))
        dt = T / 4000.0
        return float(np.sum(np.maximum(env[:-1], env[1:])) * dt + v * dt)

    lo, hi = 0.0, 1.0
    while reach(hi) < L:
        lo, hi = hi, 2.0 * hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if reach(mid) < L else (lo, mid)
    return lo


def _time_at(prof, s: float) -> float:
    """The profile's time (s) at path position ``s`` (constant acceleration between knots)."""
    i = int(np.clip(np.searchsorted(prof.s, s, side="right") - 1, 0, prof.s.size - 2))
    ds, v0, acc = s - prof.s[i], prof.sd[i], prof.sdd[i] if i < prof.sdd.size else 0.0
    if ds <= 0.0:
        return float(prof.t[i])
    if abs(acc) * ds < 1e-12 * max(v0 * v0, 1e-300):
        return float(prof.t[i] + ds / v0)
    return float(prof.t[i] + (math.sqrt(max(v0 * v0 + 2.0 * acc * ds, 0.0)) - v0) / acc)


def window_bound(path, limits: AxisLimits, parts: list | None = None) -> float | None:
    """The most any lead blend of ``path`` can gain, as a share of its cycle
    time (module docstring); ``None`` when a lead is not of the shape the bound
    is made for (a lead-in after a rapid from the path's start, a lead-out that
    ends the path). ``parts``: if given, gets ``(kind, controller's window
    time, its lower bound)`` of each lead (s)."""
    prof = plan_feed(ExactPath(path), limits, planner=certified_planner(limits))
    ep = prof.path
    v, a = limits.in_plane(path.plane, 2)
    j = limits.jerk_in_plane(path.plane, 2)
    vn, an = float(np.hypot(*v)), float(np.hypot(*a))
    jn = float(np.hypot(*j)) if j is not None else 1e300
    segs = path.segments

    def at(k: int) -> float:                     # path position where segment k starts
        return float(ep.offsets[np.searchsorted(ep.source_index, k)])

    saved = 0.0
    for ld in find_leads(path):
        feed = segs[ld.first if ld.kind == "in" else ld.last].feed
        if not feed:
            return None
        F = min(float(feed), vn)
        reach = SETTLE_SPANS * settle_distance(F, float(np.min(a)),
                                               None if j is None else float(np.min(j)))
        if ld.kind == "in":
            before = segs[:ld.first]
            if len(before) != 1 or before[0].role is not Role.RAPID:
                return None
            A, J = segs[ld.first].start, segs[ld.host].start
            s1 = min(at(ld.host) + reach, float(ep.offsets[-1]))
            t_c = _time_at(prof, s1)
            # the rapid is a line the blend leaves as it is: its own direction's limits
            d = np.abs(np.subtract(A, before[0].start)) / max(before[0].length, 1e-300)
            along = [min(lim[k] / d[k] for k in range(2) if d[k] > 0) if lim is not None
                     else 1e300 for lim in (v, a, j)]
            rapid = max(travel_from_rest(before[0].length, *along),
                        rapid_to_feed(before[0].length, *along, F))
            t_lb = rapid + math.dist(A, J) / F + (s1 - at(ld.host)) / F
        else:
            if ld.last != len(segs) - 1:
                return None
            J, Q = segs[ld.host].end, segs[ld.last].end
            s0 = max(at(ld.host + 1) - reach, 0.0)
            t_c = prof.duration - _time_at(prof, s0)
            t_lb = travel_from_rest(math.dist(J, Q), F, an, jn) + (at(ld.host + 1) - s0) / F
        saved += max(t_c - t_lb, 0.0)
        if parts is not None:
            parts.append((ld.kind, t_c, t_lb))
    return saved / prof.duration


#: The limits of a run (``--limits``), in words.
LIMITS_WORDS = {"a": "(a) v/a limits", "b": "(b) v/a/j limits",
                "both": "(a) v/a and (b) v/a/j limits"}


def _spread(values) -> str:
    """Median and quartiles of ``values`` (shares), in percent."""
    v = sorted(values)
    # the median to a thousandth of a point: the acceptance bar is a round 1 %
    return (f"{100 * statistics.median(v):+.3f} % (quartiles {100 * v[len(v) // 4]:+.2f} to "
            f"{100 * v[3 * len(v) // 4]:+.2f} %, {len(v)} programs)")


def _write_docs(args, summary: list[str], broken: list[str], medians: dict) -> None:
    """The figures as a marked section of docs/benchmarks.md (one per kind of run,
    :mod:`docs_section`), and from a run of the optimised blends under (b) their
    medians in one paragraph of README.md."""
    from docs_section import commit, now, write_section
    kind = "bounds" if args.bounds_only else "gains"
    cmd = (f"python bench/blend_gains.py --programs {args.programs} --first {args.first} "
           f"--limits {args.limits}" + (" --bounds-only" if args.bounds_only else "")
           + (f" --search {args.search}" if args.search else ""))
    lines = [f"`{cmd}` at {commit()}, {now()}: seeds {args.first}-"
             f"{args.first + args.programs - 1} of the tests' CAM plate generator under "
             f"{LIMITS_WORDS[args.limits]}; gain over the fastest certified controller "
             f"variant:", ""]
    lines += [f"- {line}" for line in summary]
    if not args.bounds_only:
        lines += ["", "Optimised rows certified and never slower than the fastest controller: "
                  + ("all." if not broken else f"{len(broken)} not.")]
    write_section(ROOT / "docs" / "benchmarks.md", f"bench/blend_gains.py {kind}",
                  "\n".join(lines))
    if args.bounds_only or "b" not in medians:
        return
    m = medians["b"]
    n = len(m.get("smooth", ()))
    med = {k: 100 * statistics.median(v) for k, v in m.items() if v}
    readme = (f"Under jerk limits, median gain over the fastest certified controller on {n} "
              f"generated CAM plates: smoother {med.get('smooth', 0):+.3f} %, opt-cvxpy "
              f"{med.get('opt-cvxpy', 0):+.2f} %, opt-casadi {med.get('opt-casadi', 0):+.2f} %; "
              f"no lead blend could gain more than {med.get('window', 0):+.2f} % (median window "
              f"bound). Distribution and bounds: [docs/benchmarks.md](docs/benchmarks.md#"
              f"blend-gains-on-generated-plates) (`bench/blend_gains.py` at {commit()}).")
    write_section(ROOT / "README.md", "bench/blend_gains.py", readme)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--programs", type=int, default=20)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--search", type=int, default=0, help="planner search runs per lead")
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--limits", choices=("a", "b", "both"), default="both",
                    help="(a) v/a, (b) v/a/j, or both")
    ap.add_argument("--bounds-only", action="store_true",
                    help="the controllers and the bounds alone, no optimised variant")
    ap.add_argument("--docs", action="store_true",
                    help="write the medians into docs/benchmarks.md and README.md")
    args = ap.parse_args(argv)
    chosen = LIMITS if args.limits == "both" else {args.limits: LIMITS[args.limits]}
    optimised = () if args.bounds_only else OPTIMISED
    gains: dict = {(k, v): [] for k in chosen for v in optimised}
    broken: list[str] = []      # rows not certified, or slower than the fastest controller
    bounds: dict = {k: [] for k in chosen}
    windows: dict = {k: [] for k in chosen}
    print("seed limits fastest_controller  " + "  ".join(optimised) + "  lead_bound  window_bound")
    for seed in range(args.first, args.first + args.programs):
        cp = cam_program(seed)
        prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
        for key, limits in chosen.items():
            kw = {} if args.workers is None else {"workers": args.workers}
            cmp = compare(prog, list(CONTROLLER_NAMES) + list(optimised), limits=limits,
                          options={"search": args.search}, **kw)
            rows = {r.name: r for r in cmp}
            fastest = rows["pmac"].figures.get("fastest_controller")
            if fastest is None:
                print(f"{seed:4d} {key}      (no certified controller)")
                continue
            base = rows[fastest]
            bound = lead_bound(base.toolpath, limits, base.figures["duration"])
            bounds[key].append(bound)
            window = window_bound(base.toolpath, limits)
            if window is not None:
                windows[key].append(window)
            line = []
            for name in optimised:
                r = rows[name]
                g = r.figures.get("gain_vs_fastest_controller")
                if r.status != "ok" or not r.certificate.ok or g is None \
                        or g < -SAME_TIME_REL:
                    broken.append(f"seed {seed} ({key}) {name}: {r.status} {r.message}")
                line.append("-" if g is None else f"{g:+.4f}")
                if g is not None:
                    gains[(key, name)].append(g)
            print(f"{seed:4d} {key}      {fastest:18s}  " + "  ".join(line) + f"  {bound:+.4f}"
                  + ("  -" if window is None else f"  {window:+.4f}"), flush=True)
    print("\nmedians over the programs (gain over the fastest certified controller variant)")
    summary = []
    for key in chosen:
        parts = [f"{name} {_spread(gains[(key, name)])}"
                 for name in optimised if gains[(key, name)]]
        if bounds[key]:
            parts.append(f"lead bound {_spread(bounds[key])}")
        if windows[key]:
            parts.append(f"window bound {_spread(windows[key])}")
        summary.append(f"({key}) " + ", ".join(parts))
        print("  " + summary[-1])
    if args.docs:
        medians = {key: {**{name: gains[(key, name)] for name in optimised},
                         "window": windows[key]} for key in chosen}
        _write_docs(args, summary, broken, medians)
    print(f"optimised rows certified and never slower than the fastest controller: "
          f"{'all' if not broken else f'{len(broken)} not'}")
    for line in broken:
        print("  " + line)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
