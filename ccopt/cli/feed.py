"""``ccopt feed``: time-optimal feed (TOPPRA), the jerk-limited planner and the baselines."""
from __future__ import annotations

import argparse
import math
from pathlib import Path

from ccopt.cli.inputs import limits_text, reading
from ccopt.cli.options import (add_limit_options, add_output_option, add_program,
                               add_quiet_option, add_reading_options, add_style_options,
                               add_ts_option, describe, positive_float)
from ccopt.cli.output import EXIT_OK, emit_json
from ccopt.feed import PLANNERS
from ccopt.pipeline import StageClock, pipeline

DESCRIPTION = """\
Time-optimal feed along the exact compensated path with TOPPRA, under
per-axis velocity and acceleration limits, the programmed F as a tangential
cap, stopping at tangent breaks; the stop-per-block and grbl-style junction
baselines and, with jerk limits (--jmax, or j in a case's [limits]), the
jerk-limited planner plan the same path (--planner). Limits: --vmax/--amax,
else the case's [limits], else 100 units/s and 1000 units/s^2 per axis; the
output prints the limits used and where they come from. -o writes the samples as CSV (time, position, velocity,
acceleration, feed, active limit)."""

EXAMPLE = """\
  ccopt feed cases/leadin-outside-line --planner all
  ccopt feed part.nc --vmax 100,100 --amax 1000,1000 -o part.feed.csv"""

#: ``--dt``, seconds: the sampling step of the ratios and the CSV.
DEFAULT_DT = 1e-3

#: the planners ``--planner`` knows (``all`` names them all), in the order they are reported
PLANNER_NAMES = tuple(PLANNERS)


def planner_names(text: str) -> list[str]:
    """``A,B`` -> planner names (argparse type of ``--planner``); ``all``: every one
    (``jerk`` only when jerk limits are known: :meth:`ccopt.cases.Job.planners_for`
    drops it otherwise)."""
    names = [n.strip() for n in text.split(",")]
    for n in names:
        if n not in PLANNER_NAMES + ("all",):
            raise argparse.ArgumentTypeError(f"unknown planner {n!r} "
                                             f"({', '.join(PLANNER_NAMES)}, all)")
    return ["all"] if "all" in names else names


def cmd_feed(args: argparse.Namespace) -> int:
    """Feed profiles of the compensated path: TOPPRA and/or the baselines."""
    # the first planner listed is the one reported first (``all`` starts with toppra)
    first_named = (args.planner or [["toppra"]])[0][0]
    own = {"planner": "toppra" if first_named == "all" else first_named}
    if not args.planner:
        own["planners"] = ("toppra",)
    with reading(args, "feed", **own) as (work, prog, say):
        # each planner shown as it starts (the pipeline's checkpoints)
        done = pipeline(work, program=prog, verify=False, clock=StageClock(say),
                        checkpoint=say).result()
        path, limits = done.path, done.limits
        out = _summaries(done.profiles, args, say)
    planners = list(out)
    first = out[planners[0]]
    if args.json:
        emit_json({"program": str(work.program), "style": path.style, "units": path.units,
                   "limits": limits.to_json(), "limits_from": work.limits_from,
                   "planner": planners[0],
                   **{k: first[k] for k in ("duration", "samples", "max_axis_acc_ratio",
                                            "max_axis_vel_ratio", "max_axis_jerk_ratio",
                                            "max_feed_ratio")},
                   "planners": out})
    elif not args.quiet:
        if prog.nothing_to_verify():    # said so; the table is its dwells' time (issue 29)
            print(f"{prog.file}: {prog.nothing_to_verify()} (below: its dwells' time, if any)")
        print(f"{prog.file}: style {path.style}, tool path {path.length:.4f} {path.units}, "
              f"{limits_text(limits, work)}")
        print("planner   duration_s  vs_first  max_vel_ratio  max_acc_ratio  max_jerk_ratio  "
              "max_feed_ratio")
        for name, r in out.items():
            vs = r["duration"] / first["duration"] if first["duration"] > 0 else math.nan
            jr = r["max_axis_jerk_ratio"]
            jr = f"{jr:14.4f}" if jr is not None else f"{'-':>14s}"
            print(f"{name:8s}  {r['duration']:10.4f}  {vs:8.4f}  "
                  f"{r['max_axis_vel_ratio']:13.4f}  {r['max_axis_acc_ratio']:13.4f}  {jr}  "
                  f"{r['max_feed_ratio']:14.4f}")
    return EXIT_OK


def _summaries(profiles: dict, args: argparse.Namespace, say) -> dict[str, dict]:
    """Each planner's summary (figures to a stated bound, ``FeedProfile.summary``),
    its samples every ``--dt`` s written as CSV when ``-o``/``--csv`` asks
    (``FILE.<planner>.csv`` when several)."""
    out: dict = {}
    target = args.output
    for name, prof in profiles.items():
        # the figures need no dt grid (FeedProfile.figure_samples); the CSV does
        out[name] = prof.summary(args.dt)
        if target:
            say(f"csv: {name}")
            csv = Path(target)
            if len(profiles) > 1:
                csv = csv.with_name(f"{csv.stem}.{name}{csv.suffix}")
            prof.to_csv(csv, args.dt)
            out[name]["csv"] = str(csv)
    return out


def add_commands(sub, commands: dict) -> None:
    """Register ``feed`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("feed", help="time-optimal feed (TOPPRA) and baseline planners",
                       **describe(DESCRIPTION, EXAMPLE))
    add_program(p)
    add_reading_options(p)
    add_style_options(p)
    add_limit_options(p)
    p.add_argument("--tangential-acc", type=positive_float, metavar="A",
                   help="limit on the acceleration along the path, units/s^2")
    p.add_argument("--centripetal-acc", type=positive_float, metavar="A",
                   help="limit on speed^2 * curvature, units/s^2")
    p.add_argument("--planner", type=planner_names, action="append", metavar="NAME[,NAME]",
                   help="toppra (default), stop, junction, jerk (needs jerk limits) or all; "
                        "repeat or comma-separate")
    add_ts_option(p)
    p.add_argument("--junction-deviation", type=positive_float, metavar="D",
                   help="allow grbl's corner speed at tangent breaks (default: stop there)")
    p.add_argument("--dt", type=positive_float, default=DEFAULT_DT, metavar="S",
                   help="sampling step for ratios and CSV, seconds (default 0.001)")
    add_output_option(p, "FILE.csv", help="write the samples as CSV (FILE.<planner>.csv per "
                                          "planner when several)", old=("--csv",))
    add_quiet_option(p)
    commands["feed"] = cmd_feed

