"""``ccopt sweep SPEC.toml [-o DIR] [--scheduler ADDRESS] [--workers N]
[--task-timeout S] [--json]``: programs x settings on Dask, as a resumable table.

Exit codes: 0 when the sweep ran (failed tasks are rows of the table, with
their errors: data, not a failure of the command), 2 for a bad spec or input
(one line ``file:line: message`` on stderr).
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ccopt.atomic import refuse_overwriting_inputs
from ccopt.cases import LIMITS_FROM
from ccopt.cli.options import (add_json_option, add_output_option, describe, positive_float,
                               positive_int)
from ccopt.cli.output import EXIT_BAD_INPUT, EXIT_OK
from ccopt.errors import CcoptError
from ccopt.sweep import sweep
from ccopt.sweep.results import CSV, META, PARQUET


def _report(table, out: Path, as_json: bool) -> None:
    computed, total = table.attrs["computed"], table.attrs["total"]
    failed = int(table["error"].notna().sum())
    files = {"parquet": str(out / PARQUET), "csv": str(out / CSV),
             "summary": str(out / "summary.html")}
    if as_json:
        json.dump({"out": str(out), "tasks": total, "computed": computed, "failed": failed,
                   "files": files, "rows": json.loads(table.to_json(orient="records"))},
                  sys.stdout)
        sys.stdout.write("\n")
        return
    print(f"{total} tasks ({computed} computed now, {total - computed} from before), "
          f"{failed} failed")
    ran = table[table["error"].isna()]
    if len(ran):
        print(f"cycle time {ran['cycle_time'].min():.4f} .. {ran['cycle_time'].max():.4f} s; "
              f"certified {int(ran['ok'].astype(bool).sum())} of {len(ran)}")
        print(_limits_line(ran))
    print(f"results: {files['parquet']}, {files['csv']}; summary: {files['summary']}")


#: how the summary names limits a task got from the spec (the Job's "command line")
SPEC_LIMITS = "the spec's [axes] limits"


def _limits_line(ran) -> str:
    """Where the tasks' axis limits came from, with how many tasks each."""
    if "limits_from" not in ran:
        return "limits: not recorded (rows of an older ccopt)"
    counts = ran["limits_from"].fillna("not recorded").value_counts(sort=False)
    # in a sweep, limits "from the command line" are the spec's [axes] limits
    said = [f"{LIMITS_FROM.get(k, k).replace('--vmax/--amax', SPEC_LIMITS)} "
            f"({n} task{'s' if n != 1 else ''})" for k, n in counts.items()]
    return "limits: " + "; ".join(said)


#: the sweep's other files in DIR: the summary and its plot, the spec's copy
SWEEP_FILES = ("summary.html", "summary.png", "spec.toml", "spec.json")


def cmd_sweep(args: argparse.Namespace) -> int:
    """Run the sweep a spec describes; returns the exit code."""
    out = Path(args.output) if args.output else Path(f"sweep-{Path(args.spec).stem}")
    if args.scheduler and args.workers:
        print("ccopt sweep: --workers sets the local cluster's size; a cluster given by "
              "--scheduler has its own workers", file=sys.stderr)
        return EXIT_BAD_INPUT
    # the files of DIR must not replace the spec (``-o .`` beside spec.toml): exit 2 first
    refuse_overwriting_inputs([out / name for name in (PARQUET, CSV, META, *SWEEP_FILES)],
                              [args.spec])
    try:
        table = sweep(args.spec, out=out, scheduler=args.scheduler, workers=args.workers,
                      task_timeout=args.task_timeout,
                      log=lambda msg: print(msg, file=sys.stderr))
    except CcoptError as exc:
        print(str(exc), file=sys.stderr)
        return EXIT_BAD_INPUT
    _report(table, out, args.json)
    return EXIT_OK


DESCRIPTION = """\
A research sweep: the programs of SPEC.toml times every combination of its
settings (controller styles, cutter radii, sides, machine limits, feed
planners, compare variants, the smoother's band), each task compensate, feed,
verify (and compare) on Dask: a local cluster of worker processes by default
(--workers), any cluster with --scheduler. The result is one row per task in
DIR (results.parquet, results.csv, summary.html); running again with the same
DIR computes only the missing tasks."""

EXAMPLE = """\
  ccopt sweep styles-radii -o sweep-out --workers 2"""


def add_commands(sub, commands: dict) -> None:
    """Register ``sweep`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("sweep", help="programs x settings (styles, radii, limits, variants) "
                                     "on Dask, as a resumable table",
                       **describe(DESCRIPTION, EXAMPLE))
    p.add_argument("spec", metavar="SPEC.toml",
                   help="the sweep spec (TOML), or a bundled one by name: styles-radii, "
                        "limits-planners, variants")
    add_output_option(p, "DIR",
                      help="results folder; run again with the same DIR to compute only "
                           "the missing tasks (default: sweep-<spec name>)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a running Dask scheduler, e.g. tcp://host:8786 (default: a "
                        "local cluster)")
    p.add_argument("--workers", type=positive_int, metavar="N",
                   help="worker processes of the local cluster (default: one per core)")
    p.add_argument("--task-timeout", type=positive_float, metavar="S",
                   help="seconds per task; a task past it is a row with a timeout error")
    add_json_option(p)
    commands["sweep"] = cmd_sweep
