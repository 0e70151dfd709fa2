"""``ccopt run``: the command-line side of the main job (:mod:`ccopt.run`)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ccopt.cases import bundled_cases
from ccopt.cli.inputs import job, limits_words
from ccopt.cli.options import (add_limit_options, add_output_option, add_quiet_option,
                               add_reading_options, add_style_options, add_tolerance_option,
                               add_ts_option, add_variants_option, add_workers_option,
                               chosen_variants, describe)
from ccopt.cli.output import emit_json
from ccopt.cli.progress import cases_progress
from ccopt.compare.contract import LEAD_FAMILY_NAMES
from ccopt.compare.registry import MAIN_JOB_ON_DEMAND, main_job_variants, require_known
from ccopt.errors import ProgramError
from ccopt.run import PLANNERS, RunOptions, default_out, distinct_labels, exit_code, run_all
from ccopt.workers import resolve_workers

DESCRIPTION = """\
The main job, for every bundled case (no argument) or the given cases and
programs: read, compensate, plan the feed (TOPPRA and the baselines), verify,
compare the blend variants, export (.nc, .pmc, .svg, feed CSV, certificate,
tool path) and write one HTML report, DIR/index.html, with summary.json.
Independent cases run in parallel worker processes (--workers, default one per
core); a Ctrl-C stops them all at once (exit 130) and leaves no partial file.
Limits: --vmax/--amax, else a case's [limits], else 100 units/s and 1000
units/s^2 per axis; style: --style, else a case's, else by dialect (pmac for
PMAC programs, siemens for SINUMERIK, linuxcnc for G-code, fagor where G136-G139
appear). The comparison leaves out the lead families (HEIDENHAIN APPR/DEP and
SINUMERIK approach parameter searches) and opt-cvxpy (the costliest variant
per lead; opt-casadi optimises the same leads) unless --variants names them
or says all; ccopt compare runs them by default. Exit 0 when
every case gets its expected verdict, 1 when a verification fails
unexpectedly, 2 when an input cannot be read or compensated."""

EXAMPLE = """\
  ccopt run leadin-inside-line pocket -o out --workers 2
  ccopt run                      # every bundled case, report in ccopt-out/"""


def cmd_run(args: argparse.Namespace) -> int:
    """The main job (:mod:`ccopt.run`): compensate, plan the feed, verify,
    compare blends, export and report, for every input; then a summary table.

    Exit 0 when every input did what its case expects, 1 when a verification
    failed, 2 when an input could not be read or compensated.
    """
    variants = chosen_variants(args)
    if variants:
        require_known(variants, "--variants")
    # the lead families and opt-cvxpy on demand: the main job's comparison without them
    compared = tuple(variants or main_job_variants())
    # inputs that share a name (part.mpf, part.h) get distinct ones: their files share a folder
    jobs = distinct_labels([job(a, args, planners=PLANNERS, variants=compared)
                            for a in args.inputs or bundled_cases()])
    if not jobs:
        raise ProgramError("no bundled cases found (is the cases/ folder next to ccopt/?)",
                           "cases")
    out = Path(args.output) if args.output else default_out()
    workers = resolve_workers(args.workers)
    # cases share the workers; a single case's comparison gets them instead
    opts = RunOptions(compare=not args.no_compare,
                      compare_workers=workers if len(jobs) == 1 else 1)
    progress = cases_progress(args, [j.label for j in jobs])
    try:
        rows = run_all(jobs, out, opts, workers=workers, progress=progress)
    finally:
        progress.close()
    if args.json:
        emit_json({"out": str(out), "cases": [
            {k: v for k, v in r.items()
             if k not in ("plots", "compare", "feed", "certificate", "certificate_text")}
            for r in rows]})
    elif not args.quiet:
        _print_summary(rows, out)
    return exit_code(rows)


def _print_summary(rows: list[dict], out: Path) -> None:
    """One line per input on stdout, their messages on stderr, then where the report is."""
    w = max([len(r["name"]) for r in rows] + [4])
    ws = max([len(r.get("style") or "") for r in rows] + [8])     # heidenhain is 10
    print(f"{'case'.ljust(w)}  {'style'.ljust(ws)}  radius  cycle time  min clearance  status")
    for r in rows:
        if "duration" in r:
            # no clearance figure: the path has no compensated move to check
            clear = "-" if r["min_clearance"] is None else f"{r['min_clearance']:.6g}"
            print(f"{r['name'].ljust(w)}  {r['style'].ljust(ws)}  {r['radius'] or 0:6g}  "
                  f"{r['duration']:8.3f} s  {clear:>13s}  {r['status']}")
        else:
            print(f"{r['name'].ljust(w)}  {''.ljust(ws)}  {'':6s}  {'':10s}  {'':13s}  "
                  f"{r['status']}")
    for r in rows:
        if r.get("message") and r["status"] != "error (expected)":
            print(r["message"], file=sys.stderr)
    _print_limits(rows)
    print(f"report: {out / 'index.html'}")


def _print_limits(rows: list[dict]) -> None:
    """The limits each input was planned under and where they came from, one
    line per set of limits (the cases that share it named)."""
    groups: dict[str, list[str]] = {}
    for r in rows:
        if r.get("limits") is not None:
            groups.setdefault(limits_words(r["limits"], r.get("limits_from")), []).append(r["name"])
    for words, names in groups.items():
        print(f"{words} for {', '.join(names)}")


def add_commands(sub, commands: dict) -> None:
    """Register ``run`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("run", help="the main job, on bundled cases or given programs",
                       **describe(DESCRIPTION, EXAMPLE))
    p.add_argument("inputs", nargs="*", metavar="CASE|PROGRAM")
    add_output_option(p, "DIR",
                      help="write the report and exported files into DIR (default ccopt-out)")
    add_workers_option(p, "cases (or a single case's variants) run in N worker processes "
                          "(default: one per core; 1: one after the other)")
    add_limit_options(p)
    add_ts_option(p)
    p.add_argument("--no-compare", action="store_true", help="skip the blend comparison")
    add_variants_option(p, "blend variants to compare, or all (default: every available one "
                           "but the lead families " + ", ".join(LEAD_FAMILY_NAMES)
                           + ", which search a parameter set each, and "
                           + ", ".join(MAIN_JOB_ON_DEMAND) + "; see ccopt compare --list)")
    add_reading_options(p)
    add_quiet_option(p)
    add_style_options(p)
    add_tolerance_option(p)
    commands["run"] = cmd_run
