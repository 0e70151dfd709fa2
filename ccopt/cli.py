"""The ``ccopt`` command.

Exit codes (DESIGN.md): 0 success, 1 verification failed, 2 bad input (one
line ``file:line: message`` on stderr, never a traceback). An unexpected
internal failure prints one line and exits 3; ``CCOPT_DEBUG=1`` shows the
traceback.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Sequence

import ccopt
from ccopt.cases import Case, bundled_cases, find_case
from ccopt.errors import CcoptError, ProgramError
from ccopt.program import read_program
from ccopt.program.model import Program
from ccopt.sweep.command import add_arguments as add_sweep_arguments
from ccopt.sweep.command import run_command as run_sweep_command
from ccopt.toolpath import ToolPath, programmed_path

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERNAL = 0, 1, 2, 3


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit code 2."""

    def error(self, message: str) -> None:  # noqa: D401 - argparse API
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: {message} (see {self.prog} --help)\n")


@dataclass(frozen=True)
class Input:
    """One thing to work on: a program file, maybe within a case."""

    label: str
    program: Path
    case: Case | None = None


def resolve_input(arg: str) -> Input:
    """A case folder, a bundled case name or a program file."""
    case = find_case(arg)
    if case is not None:
        return Input(case.name, case.program, case)
    p = Path(arg)
    if not p.exists():
        raise ProgramError("no such program, case folder or bundled case name", arg)
    if p.is_dir():
        raise ProgramError("a folder without case.toml is not a case", arg)
    return Input(p.name, p)


def load(inp: Input, args: argparse.Namespace) -> Program:
    return read_program(inp.program, getattr(args, "dialect", None),
                        tool_table=getattr(args, "tool_table", None))


# -- output helpers --------------------------------------------------------------
def _fmt(x: float) -> str:
    return f"{x:.4f}"


def path_table(path: ToolPath) -> str:
    """A readable table of a tool path's segments."""
    rows = [("#", "kind", "role", "line", "start", "end", "centre / sweep")]
    for i, seg in enumerate(path.segments):
        d = seg.to_json()
        extra = ""
        if "center" in d:
            extra = (f"({_fmt(d['center'][0])}, {_fmt(d['center'][1])}) "
                     f"{'ccw' if d['ccw'] else 'cw'} {d['sweep'] * 180 / 3.141592653589793:.3f} deg")
        rows.append((str(i), d["kind"], d["role"], str(d["block"] or ""),
                     f"({_fmt(d['start'][0])}, {_fmt(d['start'][1])})",
                     f"({_fmt(d['end'][0])}, {_fmt(d['end'][1])})", extra))
    widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip() for r in rows)


def emit_json(obj) -> None:
    """One JSON document on stdout (compact: it is for programs)."""
    json.dump(obj, sys.stdout, separators=(",", ":"))
    sys.stdout.write("\n")


# -- subcommands -----------------------------------------------------------------
def cmd_show(args: argparse.Namespace) -> int:
    inp = resolve_input(args.program)
    prog = load(inp, args)
    path = programmed_path(prog)
    if args.json:
        emit_json(path.to_json())
    else:
        print(f"{prog.file}: {len(prog.blocks)} blocks, {prog.dialect}, units {prog.units}, "
              f"programmed path {path.length:.4f} {prog.units}")
        print(path_table(path))
    return EXIT_OK


def compensate_input(inp: Input, prog: Program, args: argparse.Namespace) -> ToolPath:
    """Compensate with the command line's style options, defaulting to the case's."""
    from ccopt.compensate import compensate
    style = getattr(args, "style", None) or (inp.case.style if inp.case else "pmac")
    radius = getattr(args, "radius", None)
    if radius is None and inp.case is not None:
        radius = inp.case.radius
    options = {}
    if getattr(args, "break_cos", None) is not None:
        options["break_cos"] = args.break_cos
    if getattr(args, "ccbuf", None) is not None:
        options["ccbuf"] = args.ccbuf
    return compensate(prog, style=style, radius=radius, side=getattr(args, "side", None),
                      **options)


def cmd_compensate(args: argparse.Namespace) -> int:
    inp = resolve_input(args.program)
    prog = load(inp, args)
    path = compensate_input(inp, prog, args)
    if args.json:
        emit_json(path.to_json())
    else:
        print(f"{prog.file}: style {path.style}, cutter radius {path.radius:g} {path.units}, "
              f"{len(path.segments)} segments, tool path {path.length:.4f} {path.units}")
        print(path_table(path))
    return EXIT_OK


def cmd_export(args: argparse.Namespace) -> int:
    """Compensate, then write the tool-centre path (read back and verified
    first, see :mod:`ccopt.export`). Exit 1 when the verification fails."""
    from ccopt.export import export
    inp = resolve_input(args.program)
    prog = load(inp, args)
    path = compensate_input(inp, prog, args)
    res = export(path, args.output, program=prog, tol=args.tol,
                 title=inp.case.title if inp.case else "")
    if args.json:
        emit_json(res.to_json())
    else:
        verdict = {True: "verified OK", False: "verification FAILED", None: "not verified"}
        print(f"{res.file}: {res.format}, read back within {res.roundtrip_error:.3g} "
              f"{path.units} (tolerance {res.tolerance:g}), {verdict[res.verified]}")
    return EXIT_FAILED if res.verified is False else EXIT_OK


def cmd_run(args: argparse.Namespace) -> int:
    """The main job (:mod:`ccopt.run`): compensate, plan the feed, verify,
    compare blends, export and report, for every input; then a summary table.

    Exit 0 when every input did what its case expects, 1 when a verification
    failed, 2 when an input could not be read or compensated.
    """
    from ccopt.run import RunOptions, default_out, exit_code, run_all
    if args.inputs:
        inputs = [resolve_input(a) for a in args.inputs]
    else:
        inputs = [Input(c.name, c.program, c) for c in bundled_cases()]
        if not inputs:
            raise ProgramError("no bundled cases found (is the cases/ folder next to ccopt/?)",
                               "cases")
    out = Path(args.out) if args.out else default_out()
    variants = [n for group in (args.variants or []) for n in group] or None
    if variants:
        from ccopt.compare.registry import require_known
        require_known(variants, "--variants")
    style_options = {}
    if args.break_cos is not None:
        style_options["break_cos"] = args.break_cos
    if args.ccbuf is not None:
        style_options["ccbuf"] = args.ccbuf
    opts = RunOptions(style=args.style, radius=args.radius, side=args.side, dialect=args.dialect,
                      tool_table=args.tool_table, vmax=args.vmax, amax=args.amax,
                      compare=not args.no_compare, style_options=style_options,
                      variants=variants)

    def progress(k: int, n: int, label: str) -> None:
        if sys.stderr.isatty() and not args.json:
            bar = "#" * int(30 * k / max(n, 1))
            sys.stderr.write(f"\r[{bar:30s}] {k}/{n} {label[:40]:40s}")
            if k == n:
                sys.stderr.write("\n")
            sys.stderr.flush()

    rows = run_all([(i.label, i.program, i.case) for i in inputs], out, opts, progress)
    if args.json:
        emit_json({"out": str(out), "cases": [
            {k: v for k, v in r.items() if k not in ("plots", "compare", "feed", "certificate")}
            for r in rows]})
    else:
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
    return exit_code(rows)


def cmd_feed(args: argparse.Namespace) -> int:
    """Feed profiles of the compensated path: TOPPRA and/or the baselines."""
    from ccopt.feed import AxisLimits, ExactPath, plan_feed
    inp = resolve_input(args.program)
    prog = load(inp, args)
    path = compensate_input(inp, prog, args)
    vmax = args.vmax or (inp.case.vmax if inp.case else None)
    amax = args.amax or (inp.case.amax if inp.case else None)
    if vmax is None or amax is None:
        raise ProgramError("no axis limits: give --vmax and --amax (X,Y[,Z]) or use a case "
                           "whose case.toml has [limits]", str(inp.program))
    try:
        limits = AxisLimits(vmax, amax, tangential_acc=args.tangential_acc,
                            centripetal_acc=args.centripetal_acc)
    except ValueError as exc:
        raise ProgramError(f"bad limits: {exc}", str(inp.program)) from None
    planners = list(dict.fromkeys(p for group in (args.planner or [["toppra"]]) for p in group))
    exact = ExactPath(path)
    out: dict = {}
    for i, name in enumerate(planners):
        prof = plan_feed(exact, limits, planner=name, junction_deviation=args.junction_deviation)
        smp = prof.sample(args.dt)
        out[name] = prof.summary(args.dt, smp)
        if args.csv:
            csv = Path(args.csv)
            if len(planners) > 1:
                csv = csv.with_name(f"{csv.stem}.{name}{csv.suffix}")
            from ccopt.export.atomic import write_text_atomic
            write_text_atomic(csv, smp.to_csv_text())
            out[name]["csv"] = str(csv)
    first = out[planners[0]]
    if args.json:
        emit_json({"program": str(inp.program), "style": path.style, "units": path.units,
                   "limits": limits.to_json(), "planner": planners[0],
                   **{k: first[k] for k in ("duration", "samples", "max_axis_acc_ratio",
                                            "max_axis_vel_ratio", "max_feed_ratio")},
                   "planners": out})
    else:
        print(f"{prog.file}: style {path.style}, tool path {path.length:.4f} {path.units}, "
              f"limits v={list(limits.v)} a={list(limits.a)}")
        print("planner   duration_s  vs_first  max_vel_ratio  max_acc_ratio  max_feed_ratio")
        for name, r in out.items():
            vs = r["duration"] / first["duration"] if first["duration"] > 0 else math.nan
            print(f"{name:8s}  {r['duration']:10.4f}  {vs:8.4f}  "
                  f"{r['max_axis_vel_ratio']:13.4f}  {r['max_axis_acc_ratio']:13.4f}  "
                  f"{r['max_feed_ratio']:14.4f}")
    return EXIT_OK


def _axis_values(text: str) -> tuple[float, ...]:
    parts = text.split(",")
    if not 2 <= len(parts) <= 3:
        raise argparse.ArgumentTypeError(f"give 2 or 3 comma-separated numbers X,Y[,Z]: {text!r}")
    return tuple(_positive_float(x) for x in parts)


def _checked(text: str, parse, ok, need: str):
    """``parse(text)`` if ``ok`` of it holds; else an argparse error saying ``need``."""
    try:
        x = parse(text)
    except ValueError:
        what = "a whole number" if parse is int else "a number"
        raise argparse.ArgumentTypeError(f"not {what}: {text!r}") from None
    if not ok(x):
        raise argparse.ArgumentTypeError(f"must be {need}: {text!r}")
    return x


def _positive_float(text: str) -> float:
    return _checked(text, float, lambda x: 0 < x < math.inf, "a finite number > 0")


def _nonneg_float(text: str) -> float:
    return _checked(text, float, lambda x: 0 <= x < math.inf, "a finite number >= 0")


def _nonneg_int(text: str) -> int:
    return _checked(text, int, lambda n: n >= 0, "a whole number >= 0")


def _cosine(text: str) -> float:
    return _checked(text, float, lambda x: -1.0 <= x <= 1.0, "a cosine, between -1 and 1")


def _planner_names(text: str) -> list[str]:
    names = [n.strip() for n in text.split(",")]
    known = ("toppra", "stop", "junction")
    for n in names:
        if n not in known + ("all",):
            raise argparse.ArgumentTypeError(f"unknown planner {n!r} (toppra, stop, junction, all)")
    return list(known) if "all" in names else names


def cmd_verify(args: argparse.Namespace) -> int:
    """Compensate, then certify the radius offset (exit 1 when a check fails)."""
    from ccopt.verify import verify
    inp = resolve_input(args.program)
    prog = load(inp, args)
    path = compensate_input(inp, prog, args)
    radius = args.radius if args.radius is not None else (inp.case.radius if inp.case else None)
    cert = verify(path, prog, eps=args.eps, radius=radius, side=args.side)
    report = cert.to_json()
    agree = True
    if args.crosscheck:
        from ccopt.verify.crosschecks import run_crosschecks
        report["crosschecks"] = run_crosschecks(cert)
        agree = all(x["agree"] for x in report["crosschecks"])
    if args.json:
        emit_json(report)
    else:
        print(f"{prog.file}: style {path.style}, {len(path.segments)} tool segments")
        print(cert.summary())
        for x in report.get("crosschecks", ()):
            print(f"  cross-check {x['name']}: {'agrees' if x['agree'] else 'DISAGREES'} - "
                  f"{x.get('summary', '')}")
        if args.crosscheck and not report["crosschecks"]:
            print("  cross-checks: none installed (entry points 'ccopt.crosschecks')")
    return EXIT_OK if cert.ok and agree else EXIT_FAILED


Command = Callable[[argparse.Namespace], int]


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, Command]]:
    parser = _Parser(prog="ccopt", description=(
        "Cutter radius compensation as a controller does it (PMAC reference), "
        "time-optimal feed, verification, blend comparison and export."))
    parser.add_argument("--version", action="version", version=f"ccopt {ccopt.__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    commands: dict[str, Command] = {}

    def program_args(p: argparse.ArgumentParser) -> None:
        p.add_argument("--dialect", choices=["gcode", "pmac"],
                       help="program dialect (default: from the file suffix)")
        # a Path, so the reader takes it as a file name, never as table text
        p.add_argument("--tool-table", metavar="FILE", type=Path,
                       help="LinuxCNC tool table for G41/G42 D<tool number>")
        p.add_argument("--json", action="store_true", help="machine-readable output on stdout")

    p = sub.add_parser("show", help="print the programmed path as exact segments")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    commands["show"] = cmd_show

    def style_args(p: argparse.ArgumentParser) -> None:
        from ccopt.compensate import STYLES
        p.add_argument("--style", choices=sorted(STYLES),
                       help="controller style (default: the case's, else pmac)")
        p.add_argument("--radius", type=_nonneg_float, metavar="R",
                       help="cutter radius in program units, overriding the program")
        p.add_argument("--side", choices=["left", "right"],
                       help="compensation side wherever it is on, overriding the program")
        p.add_argument("--break-cos", type=_cosine, metavar="C",
                       help="PMAC Isx99 outside-corner break (cos of the turn), default 0.9998")
        p.add_argument("--ccbuf", type=_nonneg_int, metavar="N",
                       help="Turbo PMAC DEFINE CCBUF: non-plane moves looked through at a corner")

    p = sub.add_parser("compensate", help="the tool-centre path a controller style makes")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    style_args(p)
    commands["compensate"] = cmd_compensate

    p = sub.add_parser("feed", help="time-optimal feed (TOPPRA) and baseline planners")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    style_args(p)
    p.add_argument("--vmax", type=_axis_values, metavar="X,Y[,Z]",
                   help="axis velocity limits, units/s (default: the case's [limits] v)")
    p.add_argument("--amax", type=_axis_values, metavar="X,Y[,Z]",
                   help="axis acceleration limits, units/s^2 (default: the case's [limits] a)")
    p.add_argument("--tangential-acc", type=_positive_float, metavar="A",
                   help="limit on the acceleration along the path, units/s^2")
    p.add_argument("--centripetal-acc", type=_positive_float, metavar="A",
                   help="limit on speed^2 * curvature, units/s^2")
    p.add_argument("--planner", type=_planner_names, action="append", metavar="NAME[,NAME]",
                   help="toppra (default), stop, junction or all; repeat or comma-separate")
    p.add_argument("--junction-deviation", type=_positive_float, metavar="D",
                   help="allow grbl's corner speed at tangent breaks (default: stop there)")
    p.add_argument("--dt", type=_positive_float, default=1e-3, metavar="S",
                   help="sampling step for ratios and CSV, seconds (default 0.001)")
    p.add_argument("--csv", metavar="FILE", help="write the samples as CSV "
                   "(FILE.<planner>.csv per planner when several)")
    commands["feed"] = cmd_feed

    p = sub.add_parser("verify", help="certify that the tool path keeps the radius offset")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    program_args(p)
    style_args(p)
    p.add_argument("--eps", type=_positive_float, default=1e-6, metavar="E",
                   help="tolerance in program units (default 1e-6)")
    p.add_argument("--crosscheck", action="store_true",
                   help="also run the registered cross-check formulations (CVXPY, CasADi)")
    commands["verify"] = cmd_verify

    p = sub.add_parser("export", help="write the verified tool-centre path (.nc .pmc .svg .json)")
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")
    p.add_argument("-o", "--output", required=True, metavar="OUT",
                   help="output file; the suffix picks the format (.nc .ngc .pmc .svg .json)")
    p.add_argument("--tol", type=_positive_float, metavar="T",
                   help="arc-fit tolerance for spirals in G-code (default 0.001 mm or its inch "
                        "equivalent)")
    program_args(p)
    style_args(p)
    commands["export"] = cmd_export

    p = sub.add_parser("run", help="the main job, on bundled cases or given programs")
    p.add_argument("inputs", nargs="*", metavar="CASE|PROGRAM")
    p.add_argument("-o", "--out", metavar="DIR",
                   help="write the report and exported files into DIR (default ccopt-out)")
    p.add_argument("--vmax", type=_axis_values, metavar="X,Y[,Z]",
                   help="axis velocity limits, units/s (default: the case's, else 100)")
    p.add_argument("--amax", type=_axis_values, metavar="X,Y[,Z]",
                   help="axis acceleration limits, units/s^2 (default: the case's, else 1000)")
    p.add_argument("--no-compare", action="store_true", help="skip the blend comparison")
    from ccopt.compare.cli import variant_names
    p.add_argument("--variants", type=variant_names, action="append", metavar="NAME[,NAME]",
                   help="blend variants to compare (default: every available one; see "
                        "ccopt compare --list)")
    program_args(p)
    style_args(p)
    commands["run"] = cmd_run

    from ccopt.compare.cli import add_commands as add_compare_commands
    add_compare_commands(sub, commands, program_args, _axis_values, _nonneg_float, _positive_float)
    p = sub.add_parser("sweep", help="programs x settings (styles, radii, limits, variants) "
                                     "on Dask, as a resumable table")
    add_sweep_arguments(p)
    commands["sweep"] = run_sweep_command
    return parser, commands


def main(argv: Sequence[str] | None = None) -> int:
    parser, commands = build_parser()
    args = parser.parse_args(argv)
    if not args.command:
        parser.print_help()
        return EXIT_BAD_INPUT
    try:
        return commands[args.command](args)
    except CcoptError as exc:
        print(str(exc), file=sys.stderr)
        return EXIT_BAD_INPUT
    except BrokenPipeError:
        # The reader went away (``ccopt ... | head``): not an error of ours.
        try:
            sys.stdout = open(os.devnull, "w")
        except OSError:
            pass
        return EXIT_OK
    except KeyboardInterrupt:
        print("ccopt: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # an internal bug: one line, traceback on request
        if os.environ.get("CCOPT_DEBUG"):
            raise
        print(f"ccopt: internal error: {type(exc).__name__}: {exc} "
              "(set CCOPT_DEBUG=1 for the traceback and please report it)", file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
