"""``ccopt verify``: certify that the tool path keeps the radius offset."""
from __future__ import annotations

import argparse

from ccopt.cli.inputs import limits_text, reading
from ccopt.cli.options import (add_limit_options, add_program, add_quiet_option,
                               add_reading_options, add_style_options, add_tolerance_option,
                               add_ts_option, describe, nonneg_float, positive_float)
from ccopt.cli.output import EXIT_FAILED, EXIT_OK, emit_json
from ccopt.pipeline import StageClock, pipeline
from ccopt.tolerances import VERIFY_EPS
from ccopt.verify.crosschecks import run_crosschecks
from ccopt.verify.limits import LIMITS_TOL
from ccopt.verify.surface import parse_part_lines


def part_line_ranges(text: str) -> tuple[tuple[int, int], ...]:
    """``--part-lines A-B[,C-D]``: program line ranges, checked."""
    try:
        return parse_part_lines(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


DESCRIPTION = """\
The certificate of the compensated path (or of --toolpath FILE.json, a path
made elsewhere) against PROGRAM's contour: no gouge (every tool position at
least r - eps from every part element), contact, side and continuity, exact
for lines and arcs and certified bounds for spirals and curves; with --feed
also the planned profile within the axis limits (--vmax/--amax, else the
case's [limits], else 100 units/s and 1000 units/s^2 per axis; the first line
names them and where they come from): TOPPRA's, or the jerk planner's when the limits carry jerk
(--jmax or the case's j). Exit 1 when a check fails. A program with no
moves (empty, or settings and dwells only) says "nothing to verify" and
exits 0."""

EXAMPLE = """\
  ccopt verify short-move-overcut
  ccopt verify leadin-outside-line --feed --json"""


def cmd_verify(args: argparse.Namespace) -> int:
    """Compensate (or read ``--toolpath``), then certify the radius offset and,
    with ``--feed``, the feed limits of the certified planner's profile (the jerk
    planner's when the limits carry jerk, else TOPPRA's); exit 1 when a check fails."""
    with reading(args, "verify") as (work, prog, say):
        done = pipeline(work, program=prog, feed=args.feed, clock=StageClock(say)).result()
    path, cert = done.path, done.certificate
    report = cert.to_json()
    if args.feed and done.limits is not None:
        report.update(limits=done.limits.to_json(), limits_from=work.limits_from)
    nothing = prog.nothing_to_verify() or (None if path.segments else
                                           "nothing to verify: the tool path has no segments")
    if nothing:     # said in so many words, not "PASSED" over no checks; exit 0
        report["nothing_to_verify"] = nothing
        if args.json:
            emit_json(report)
        elif not args.quiet:
            print(f"{prog.file}: {nothing}")
        return EXIT_OK
    agree = True
    if args.crosscheck:
        report["crosschecks"] = run_crosschecks(cert)
        agree = all(x["agree"] for x in report["crosschecks"])
    if args.json:
        emit_json(report)
    elif not args.quiet:
        made = f"tool path {args.toolpath}" if args.toolpath else f"style {path.style}"
        limits = f", {limits_text(done.limits, work)}" if args.feed and done.limits else ""
        print(f"{prog.file}: {made}, {len(path.segments)} tool segments{limits}")
        print(cert.summary())
        for x in report.get("crosschecks", ()):
            print(f"  cross-check {x['name']}: {'agrees' if x['agree'] else 'DISAGREES'} - "
                  f"{x.get('summary', '')}")
        if args.crosscheck and not report["crosschecks"]:
            print("  cross-checks: none installed (entry points 'ccopt.crosschecks')")
    return EXIT_OK if cert.ok and agree else EXIT_FAILED


def add_commands(sub, commands: dict) -> None:
    """Register ``verify`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("verify", help="certify that the tool path keeps the radius offset",
                       **describe(DESCRIPTION, EXAMPLE))
    add_program(p)
    add_reading_options(p)
    add_style_options(p)
    p.add_argument("--eps", type=positive_float, default=VERIFY_EPS, metavar="E",
                   help="tolerance in program units (default 1e-6)")
    p.add_argument("--toolpath", metavar="FILE.json",
                   help="verify this tool path (ccopt's JSON schema, as `ccopt compensate --json` "
                        "prints it) against PROGRAM's contour instead of compensating")
    add_tolerance_option(p)
    p.add_argument("--feed", action="store_true",
                   help="also plan the feed under the axis limits and check them (TOPPRA's, "
                        "or the jerk planner's when the limits carry jerk)")
    add_limit_options(p)
    add_ts_option(p)
    p.add_argument("--limits-tol", type=nonneg_float, default=LIMITS_TOL, metavar="T",
                   help="relative tolerance of the limits check: a sample may exceed its limit "
                        "by this fraction (default 1e-3)")
    p.add_argument("--crosscheck", action="store_true",
                   help="also run the registered cross-check formulations (CVXPY, CasADi)")
    p.add_argument("--part-lines", type=part_line_ranges, metavar="A-B[,C-D]",
                   help="program lines whose moves are part surface; the other compensated "
                        "moves are air (default: a closed loop is the part, leads before "
                        "and after it air; (ccopt: part|air) comments mark single moves)")
    add_quiet_option(p)
    commands["verify"] = cmd_verify
