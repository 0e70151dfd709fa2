"""Benchmark: feed planning of a long compensated pocket, ccopt vs plain toppra.

The pocket is a closed contour of ``n`` blocks around a large circle,
counter-clockwise, cut inside with CC1 (PMAC compensation, cutter radius
0.5): a rapid, a Z plunge, a lead-in, the contour, a lead-out and a retract.
Edges are about 2 mm long and repeat a motif of a straight edge, an arc
tangent to it, a straight edge meeting the next at a corner, and an arc
bulging the other way, with radial jitter, so the compensated path has tangent
joins with curvature breaks, inside corners (sharp, stops) and outside
corners (PMAC adds tangent arcs).

Measured in the same run, medians of ``--repeat`` runs:

- ccopt's planner (``plan_feed``, TOPPRA on the exact path: path set-up,
  gridpoints, constraints, TOPPRA, profile), time per gridpoint;
- plain toppra on the same gridpoints: ``SplineInterpolator`` through the
  exact positions at the gridpoints, toppra's ``JointVelocityConstraint`` and
  ``JointAccelerationConstraint`` (interpolation), ``TOPPRA`` with the
  ``seidel`` solver, ``compute_trajectory`` with ``ParametrizeConstAccel``,
  time per gridpoint (the spline rings through the corners instead of
  stopping, so its cycle time means nothing; it is the cost reference);
- the cycle times (and planning times) of the three planners;
- the jerk planner (``planner="jerk"``, jerk limits :data:`JERK`): its
  solve time per block and per gridpoint against TOPPRA's on the same path,
  and its cycle time against TOPPRA's and the jerk-limited stop baseline's
  (an S-curve per block). ``--no-jerk`` leaves it out.

A second program, ``--programs cam``, is CAM-style: ``n`` G1 chords of
0.5 mm along a smooth freeform curve at 6 m/min (:func:`cam_program`).
The jerk planner's CPU time counts its worker processes.

The 10,000-block figure of issue 18 (under 60 s on 2 cores), three runs:

    python bench/feed.py --sizes 10000 --programs pocket --repeat 1 --jerk-repeat 3

    python bench/feed.py [--sizes 1000,10000] [--repeat 3] [--jerk-repeat 1] [--no-jerk] [--programs pocket,cam] [--jerk-threads]
"""
from __future__ import annotations

import argparse
import math
import os
import resource
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
# the bench folder's own modules, also when a test loads this file by its path
sys.path.insert(0, str(Path(__file__).resolve().parent))

from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, GridOptions, plan_feed
from ccopt.program.model import Block, Modal, Motion, Program, Source
from ccopt.workers import default_workers
from docs_section import ROOT, printed_section  # noqa: E402

EDGE = 2.0          # mm, edge length of the contour
RADIUS = 0.5        # cutter radius, mm
FEED = 30.0         # mm/s
DEPTH = -2.0
LIMITS = AxisLimits(v=(100.0, 100.0, 30.0), a=(1000.0, 1000.0, 300.0))
#: axis jerk limits for the jerk planner, units/s^3 (20 times the acceleration: 50 ms ramps)
JERK = (20000.0, 20000.0, 6000.0)
#: the CAM-style program: chord length (mm) and feed (mm/s, 6 m/min)
CAM_CHORD = 0.5
CAM_FEED = 100.0


def pocket_program(n: int, seed: int = 1) -> Program:
    """The pocket: ``n`` contour blocks plus rapid, plunge, lead-in/out, retract."""
    rng = np.random.default_rng(seed)
    R = n * EDGE / (2 * math.pi)
    theta = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    rad = R + rng.uniform(-0.25, 0.25, n) * EDGE
    pts = np.c_[rad * np.cos(theta), rad * np.sin(theta)]
    on = Modal(side=1, radius=RADIUS)
    off = Modal(side=0, radius=RADIUS)
    src = iter(range(1, n + 10))

    def blk(motion, s, e, modal, z0=DEPTH, z1=DEPTH, center=None, feed=FEED):
        return Block(Source("pocket", next(src), 1), motion, (s[0], s[1], z0), (e[0], e[1], z1),
                     modal, center=None if center is None else (center[0], center[1], z1),
                     feed=None if motion is Motion.RAPID else feed)

    centre = (R - 10.0, 0.0)
    blocks = [blk(Motion.RAPID, (0.0, 0.0), centre, off, 0.0, 5.0),
              blk(Motion.LINE, centre, centre, off, 5.0, DEPTH),
              blk(Motion.LINE, centre, pts[0], on)]
    prev_dir = None
    for i in range(n):
        p, q = pts[i], pts[(i + 1) % n]
        kind = i % 4
        if kind in (1, 3) and prev_dir is not None:
            # arc from p to q; kind 1 leaves p tangent to the previous edge
            chord = q - p
            if kind == 1:
                t = prev_dir
            else:
                t = chord / np.linalg.norm(chord)
                t = np.array([t[0] * math.cos(0.3) + t[1] * math.sin(0.3),
                              -t[0] * math.sin(0.3) + t[1] * math.cos(0.3)])
            nrm = np.array([-t[1], t[0]])
            # centre on the normal through p, equidistant from p and q
            denom = 2.0 * float(np.dot(chord, nrm))
            if abs(denom) > 1e-9:
                rho = float(np.dot(chord, chord)) / denom
                c = p + rho * nrm
                ccw = rho > 0
                blocks.append(blk(Motion.ARC_CCW if ccw else Motion.ARC_CW, p, q, on, center=c))
                rv = q - c
                prev_dir = np.array([-rv[1], rv[0]]) * (1 if ccw else -1)
                prev_dir = prev_dir / np.linalg.norm(prev_dir)
                continue
        blocks.append(blk(Motion.LINE, p, q, on))
        d = q - p
        prev_dir = d / np.linalg.norm(d)
    blocks.append(blk(Motion.LINE, pts[0], centre, off))
    blocks.append(blk(Motion.LINE, centre, centre, off, DEPTH, 5.0))
    return Program(tuple(blocks), "pocket", "pmac")


def interleaved(fns: dict, repeat: int):
    """Run each function ``repeat`` times, taking turns (so a change in the
    machine's load hits all alike); ``{name: (median CPU s, median wall s, result)}``."""
    cpu = {k: [] for k in fns}
    wall = {k: [] for k in fns}
    out = {}
    for _ in range(repeat):
        for name, fn in fns.items():
            c0, w0 = time.process_time(), time.perf_counter()
            out[name] = fn()
            cpu[name].append(time.process_time() - c0)
            wall[name].append(time.perf_counter() - w0)
    return {k: (statistics.median(cpu[k]), statistics.median(wall[k]), out[k]) for k in fns}


def plain_toppra(path: ExactPath, gp: np.ndarray, scale: float):
    """toppra's own pipeline on the same gridpoints (see the module docstring)."""
    import toppra as ta
    import toppra.algorithm as algo
    from toppra import constraint

    q = path(gp)
    v, a = LIMITS.in_plane(path.toolpath.plane, path.dof)
    # the same time unit as ccopt's planner (its speed_scale): in mm/s toppra's
    # seidel solver fails on this path (see the module docstring)
    v, a = v / scale, a / scale ** 2

    def run():
        spline = ta.SplineInterpolator(gp, q)
        inst = algo.TOPPRA([constraint.JointVelocityConstraint(v),
                            constraint.JointAccelerationConstraint(
                                a, discretization_scheme=constraint.DiscretizationType.Interpolation)],
                           spline, gridpoints=gp, solver_wrapper="seidel",
                           parametrizer="ParametrizeConstAccel")
        traj = inst.compute_trajectory(0, 0)
        return inst.problem_data.return_code, traj
    return run


def cpu_with_children() -> tuple[float, float]:
    """CPU seconds of this process and of the worker processes it has waited for
    (the jerk planner solves its windows in workers on long programs)."""
    me = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime, kids.ru_utime + kids.ru_stime


def bench_jerk(tp, toppra_cpu: float, toppra_wall: float, toppra_n: int, toppra_T: float,
               n_blocks: int, repeat: int = 1, threads_too: bool = False) -> None:
    """The jerk planner ``repeat`` times (medians; it takes long), against
    TOPPRA's figures (same path, same run), and the jerk-limited baselines.
    Its CPU time is split into this process's and the workers'; on ``P``
    quiet processors the wall time is about ``own + workers / P`` (most of
    this process's time is before and after the workers), printed beside the
    wall time measured and the load average seen."""
    lim = AxisLimits(LIMITS.v, LIMITS.a, j=JERK)
    runs = []
    for _ in range(repeat):
        (m0, k0), w0 = cpu_with_children(), time.perf_counter()
        prof = plan_feed(tp, lim, planner="jerk")
        (m1, k1), w1 = cpu_with_children(), time.perf_counter()
        runs.append((m1 - m0 + k1 - k0, w1 - w0, m1 - m0, k1 - k0))
    cpu, wall, own, kids = (statistics.median(r[i] for r in runs) for i in range(4))
    load = os.getloadavg()[0]
    procs = default_workers()           # the CPUs the jerk windows' workers may use
    N = prof.info["gridpoints"]
    stop = plan_feed(tp, lim, planner="stop")
    junction = plan_feed(tp, lim, planner="junction")
    print(f"  jerk planner (j = {JERK})       : {cpu:7.3f} CPU s in {prof.info['workers']} "
          f"process(es), {prof.info['threads']} thread(s) here "
          f"({wall:.3f} wall, median of {repeat}; load average {load:.1f} on "
          f"{procs} CPUs), {N:,} gridpoints, {prof.info['windows']} windows, "
          f"{prof.info['lp_rounds']} LPs")
    print(f"    CPU here {own:.3f} s, in workers {kids:.3f} s: quiet {procs}-CPU wall about "
          f"{own + kids / procs:.1f} s" if kids > 0 else f"    CPU all here ({own:.3f} s)")
    print(f"    per block {cpu / n_blocks * 1e3:.2f} ms CPU; per gridpoint {cpu / N * 1e6:.1f} us = "
          f"{(cpu / N) / (toppra_cpu / toppra_n):.1f} x TOPPRA's (CPU); wall "
          f"{wall / toppra_wall:.1f} x TOPPRA's")
    print(f"    cycle time {prof.duration:.3f} s = {prof.duration / toppra_T:.4f} x TOPPRA's, "
          f"{prof.duration / stop.duration:.4f} x the jerk-limited stop baseline's "
          f"({stop.duration:.3f} s), {prof.duration / junction.duration:.4f} x the "
          f"jerk-limited junction baseline's ({junction.duration:.3f} s)")
    if threads_too:
        bench_jerk_threads(tp, lim, prof, wall)


def bench_jerk_threads(tp, lim: AxisLimits, prof, wall: float) -> None:
    """The jerk planner once more, its chains solved the other way: in
    threads of this process where the run above used processes, in processes
    where it used threads (``PARALLEL_MIN_POINTS`` moved), against that run:
    where processes pay off (:data:`ccopt.feed.jerk.windows.PARALLEL_MIN_POINTS`)."""
    from ccopt.feed.jerk import windows as jerk_windows
    kept = jerk_windows.PARALLEL_MIN_POINTS
    jerk_windows.PARALLEL_MIN_POINTS = math.inf if prof.info["workers"] > 1 else 0
    try:
        w0 = time.perf_counter()
        other = plan_feed(tp, lim, planner="jerk")
        w1 = time.perf_counter()
    finally:
        jerk_windows.PARALLEL_MIN_POINTS = kept

    def how(p):
        return (f"{p.info['workers']} processes" if p.info["workers"] > 1
                else f"{p.info['threads']} thread(s)")
    print(f"    in {how(other)} instead: {w1 - w0:.3f} s wall, {(w1 - w0) / wall:.2f} x the run "
          f"above ({how(prof)}); the same cycle time: {other.duration == prof.duration}")


def cam_program(n: int) -> Program:
    """A CAM-style program: ``n`` G1 chords of about 0.5 mm along a smooth
    closed freeform curve (a circle with a five-lobed ripple of 15 %), cut
    inside with CC1 at :data:`CAM_FEED`, so the machine is acceleration- and
    jerk-limited most of the way; with rapid, plunge, lead-in/out, retract."""
    R = n * CAM_CHORD / (2 * math.pi)
    theta = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    rad = R * (1.0 + 0.15 * np.sin(5 * theta))
    pts = np.c_[rad * np.cos(theta), rad * np.sin(theta)]
    on, off = Modal(side=1, radius=RADIUS), Modal(side=0, radius=RADIUS)
    src = iter(range(1, n + 10))

    def blk(motion, s, e, modal, z0=DEPTH, z1=DEPTH):
        return Block(Source("cam", next(src), 1), motion, (s[0], s[1], z0), (e[0], e[1], z1),
                     modal, feed=None if motion is Motion.RAPID else CAM_FEED)

    centre = (0.5 * R, 0.0)
    blocks = [blk(Motion.RAPID, (0.0, 0.0), centre, off, 0.0, 5.0),
              blk(Motion.LINE, centre, centre, off, 5.0, DEPTH),
              blk(Motion.LINE, centre, pts[0], on)]
    blocks += [blk(Motion.LINE, pts[i], pts[(i + 1) % n], on) for i in range(n)]
    blocks += [blk(Motion.LINE, pts[0], centre, off), blk(Motion.LINE, centre, centre, off, DEPTH, 5.0)]
    return Program(tuple(blocks), "cam", "pmac")


PROGRAMS = {"pocket": pocket_program, "cam": cam_program}


def bench(n: int, repeat: int, jerk: bool = True, program: str = "pocket",
          jerk_repeat: int = 1, jerk_threads: bool = False) -> None:
    prog = PROGRAMS[program](n)
    tp = compensate(prog, "pmac")
    kinds: dict[str, int] = {}
    for s in tp.segments:
        kinds[s.kind] = kinds.get(s.kind, 0) + 1
    path = ExactPath(tp)
    print(f"\n{program} of {n:,} contour blocks -> {len(tp.segments):,} segments {kinds}, "
          f"{path.length:,.1f} mm, {int(path.tangent_break.sum()):,} stops")

    prof = plan_feed(tp, LIMITS)            # the gridpoints (and a warm-up)
    N = prof.info["gridpoints"]
    gp = prof.s                             # the profile's knots are its gridpoints (no dwells)
    assert gp.size == N
    res = interleaved({
        "ccopt": lambda: plan_feed(tp, LIMITS),
        "toppra": plain_toppra(path, gp, prof.info["time_scale"]),
        "stop": lambda: plan_feed(tp, LIMITS, planner="stop"),
        "junction": lambda: plan_feed(tp, LIMITS, planner="junction"),
    }, repeat)
    (c_cpu, c_wall, prof), (p_cpu, p_wall, (code, _)) = res["ccopt"], res["toppra"]
    print(f"  gridpoints                       : {N:,}")
    print("                                      CPU s   us/gridpoint   (wall s)")
    print(f"  ccopt plan_feed (toppra, exact)  : {c_cpu:7.3f}   {c_cpu / N * 1e6:8.2f}      "
          f"({c_wall:.3f})")
    print(f"  plain toppra (SplineInterpolator): {p_cpu:7.3f}   {p_cpu / N * 1e6:8.2f}      "
          f"({p_wall:.3f})  return code {code.name}")
    print(f"  ratio ccopt / toppra per gridpoint: {c_cpu / p_cpu:6.2f} CPU, "
          f"{c_wall / p_wall:.2f} wall   (target <= 1.5)")
    T0 = prof.duration
    print("  planner    cycle time   vs toppra   planning CPU s")
    for name in ("ccopt", "stop", "junction"):
        cpu_s, _, p = res[name]
        label = "toppra" if name == "ccopt" else name
        print(f"  {label:9s} {p.duration:10.3f} s  {p.duration / T0:9.4f}   {cpu_s:10.3f}")
    if jerk:
        bench_jerk(tp, c_cpu, c_wall, N, T0, n, jerk_repeat, jerk_threads)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1000,10000")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-jerk", action="store_true", help="leave the jerk planner out")
    ap.add_argument("--jerk-repeat", type=int, default=1,
                    help="runs of the jerk planner (medians), e.g. 3 with --sizes 10000")
    ap.add_argument("--jerk-threads", action="store_true",
                    help="also time the jerk planner with its chains in threads, not processes")
    ap.add_argument("--programs", default="pocket,cam",
                    help="which generated programs: pocket (lines and arcs), cam (G1 chords)")
    ap.add_argument("--docs", action="store_true",
                    help="also write what it prints into docs/benchmarks.md (its own section)")
    args = ap.parse_args()
    command = " ".join(["python bench/feed.py", *(a for a in sys.argv[1:] if a != "--docs")])
    with printed_section(ROOT / "docs" / "benchmarks.md" if args.docs else None,
                         "bench/feed.py", command,
                         "Feed planning of long programs (bench/feed.py)"):
        print(f"limits v={LIMITS.v} a={LIMITS.a}, feed {FEED} mm/s, cutter radius {RADIUS} mm; "
              f"medians of {args.repeat} interleaved runs; grid {GridOptions()}")
        for program in args.programs.split(","):
            for n in (int(x) for x in args.sizes.split(",")):
                bench(n, args.repeat, not args.no_jerk, program, args.jerk_repeat,
                      args.jerk_threads)


if __name__ == "__main__":
    main()
