"""``ccopt run``: the command-line side of the main job (:mod:`ccopt.run`)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ccopt.cases import bundled_cases
from ccopt.cli.inputs import job
from ccopt.cli.options import (add_limit_options, add_output_option, add_reading_options,
                               add_style_options, add_variants_option, chosen_variants)
from ccopt.cli.output import emit_json
from ccopt.compare.registry import require_known
from ccopt.errors import ProgramError
from ccopt.run import DEFAULT_LIMITS, RunOptions, default_out, exit_code, run_all

#: width of the progress bar on a terminal, characters
PROGRESS_WIDTH = 30


def cmd_run(args: argparse.Namespace) -> int:
    """The main job (:mod:`ccopt.run`): compensate, plan the feed, verify,
    compare blends, export and report, for every input; then a summary table.

    Exit 0 when every input did what its case expects, 1 when a verification
    failed, 2 when an input could not be read or compensated.
    """
    jobs = [job(a, args, DEFAULT_LIMITS) for a in args.inputs or bundled_cases()]
    if not jobs:
        raise ProgramError("no bundled cases found (is the cases/ folder next to ccopt/?)",
                           "cases")
    out = Path(args.out) if args.out else default_out()
    variants = chosen_variants(args)
    if variants:
        require_known(variants, "--variants")
    opts = RunOptions(compare=not args.no_compare, variants=variants)

    def progress(k: int, n: int, label: str) -> None:
        if sys.stderr.isatty() and not args.json:
            bar = "#" * int(PROGRESS_WIDTH * k / max(n, 1))
            sys.stderr.write(f"\r[{bar:{PROGRESS_WIDTH}s}] {k}/{n} {label[:40]:40s}")
            if k == n:
                sys.stderr.write("\n")
            sys.stderr.flush()

    rows = run_all(jobs, out, opts, progress)
    if args.json:
        emit_json({"out": str(out), "cases": [
            {k: v for k, v in r.items() if k not in ("plots", "compare", "feed", "certificate")}
            for r in rows]})
    else:
        _print_summary(rows, out)
    return exit_code(rows)


def _print_summary(rows: list[dict], out: Path) -> None:
    """One line per input on stdout, their messages on stderr, then where the report is."""
    w = max([len(r["name"]) for r in rows] + [4])
    print(f"{'case'.ljust(w)}  style     radius  cycle time  min clearance  status")
    for r in rows:
        if "duration" in r:
            print(f"{r['name'].ljust(w)}  {r['style']:8s}  {r['radius']:6g}  "
                  f"{r['duration']:8.3f} s  {r['min_clearance']:13.6g}  {r['status']}")
        else:
            print(f"{r['name'].ljust(w)}  {'':8s}  {'':6s}  {'':10s}  {'':13s}  {r['status']}")
    for r in rows:
        if r.get("message") and r["status"] != "error (expected)":
            print(r["message"], file=sys.stderr)
    print(f"report: {out / 'index.html'}")


def add_commands(sub, commands: dict) -> None:
    """Register ``run`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("run", help="the main job, on bundled cases or given programs")
    p.add_argument("inputs", nargs="*", metavar="CASE|PROGRAM")
    add_output_option(p, "out", "DIR",
                      help="write the report and exported files into DIR (default ccopt-out)")
    add_limit_options(p, "the case's, else 100", "the case's, else 1000")
    p.add_argument("--no-compare", action="store_true", help="skip the blend comparison")
    add_variants_option(p, "blend variants to compare (default: every available one; see "
                           "ccopt compare --list)")
    add_reading_options(p)
    add_style_options(p)
    commands["run"] = cmd_run
