"""``ccopt sweep SPEC.toml [-o DIR] [--scheduler ADDRESS] [--workers N]
[--task-timeout S] [--json]``.

:func:`add_arguments` fills the subcommand's parser, :func:`run_command`
runs it. Exit codes: 0 when the sweep ran (failed tasks are rows of the
table, with their errors: data, not a failure of the command), 2 for a bad
spec or input (one line ``file:line: message`` on stderr).
"""
from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from ccopt.errors import CcoptError
from ccopt.sweep import sweep
from ccopt.sweep.results import CSV, PARQUET

EXIT_OK, EXIT_BAD_INPUT = 0, 2


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number >= 1")
    return n


def _positive_seconds(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        x = math.nan
    if not (math.isfinite(x) and x > 0):
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds > 0")
    return x


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The arguments of ``ccopt sweep``."""
    parser.add_argument("spec", metavar="SPEC.toml",
                        help="the sweep spec (TOML), or a bundled one by name: styles-radii, "
                             "limits-planners, variants")
    parser.add_argument("-o", "--out", metavar="DIR",
                        help="results folder; run again with the same DIR to compute only "
                             "the missing tasks (default: sweep-<spec name>)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="a running Dask scheduler, e.g. tcp://host:8786 (default: a "
                             "local cluster)")
    parser.add_argument("--workers", type=_positive_int, metavar="N",
                        help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--task-timeout", type=_positive_seconds, metavar="S",
                        help="seconds per task; a task past it is a row with a timeout error")
    parser.add_argument("--json", action="store_true",
                        help="machine-readable summary and rows on stdout")


def _json_rows(table) -> list[dict]:
    rows = json.loads(table.to_json(orient="records"))
    return rows


def _report(table, out: Path, as_json: bool) -> None:
    computed, total = table.attrs["computed"], table.attrs["total"]
    failed = int(table["error"].notna().sum())
    files = {"parquet": str(out / PARQUET), "csv": str(out / CSV),
             "summary": str(out / "summary.html")}
    if as_json:
        json.dump({"out": str(out), "tasks": total, "computed": computed, "failed": failed,
                   "files": files, "rows": _json_rows(table)}, sys.stdout)
        sys.stdout.write("\n")
        return
    print(f"{total} tasks ({computed} computed now, {total - computed} from before), "
          f"{failed} failed")
    ran = table[table["error"].isna()]
    if len(ran):
        print(f"cycle time {ran['cycle_time'].min():.4f} .. {ran['cycle_time'].max():.4f} s; "
              f"certified {int(ran['ok'].astype(bool).sum())} of {len(ran)}")
    print(f"results: {files['parquet']}, {files['csv']}; summary: {files['summary']}")


def run_command(args: argparse.Namespace) -> int:
    """Run ``ccopt sweep``; returns the exit code."""
    out = Path(args.out) if args.out else Path(f"sweep-{Path(args.spec).stem}")
    if args.scheduler and args.workers:
        print("ccopt sweep: --workers sets the local cluster's size; a cluster given by "
              "--scheduler has its own workers", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        table = sweep(args.spec, out=out, scheduler=args.scheduler, workers=args.workers,
                      task_timeout=args.task_timeout,
                      log=lambda msg: print(msg, file=sys.stderr))
    except CcoptError as exc:
        print(str(exc), file=sys.stderr)
        return EXIT_BAD_INPUT
    _report(table, out, args.json)
    return EXIT_OK
