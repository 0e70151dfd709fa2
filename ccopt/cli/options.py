"""The parser class, the argument types and the option groups the commands share.

Each option shared by several commands is defined once here; a command's
module adds the groups it takes, in the order its ``--help`` lists them.
"""
from __future__ import annotations

import argparse
import math
import os
from pathlib import Path

from ccopt.cases import DEFAULT_LIMITS
from ccopt.cli.output import EXIT_BAD_INPUT
from ccopt.compare.registry import expand
from ccopt.compensate import STYLES
from ccopt.program import DIALECTS
from ccopt.program.gcode import MAX_LOOP_ITERATIONS
from ccopt.program.model import MAX_COORDINATE
from ccopt.sides import SIDE_NAMES
from ccopt.feed.planners import DEFAULT_TS
from ccopt.tolerances import GOUGE_TOLERANCE, PMAC_BREAK_COS


#: Old spellings of options, still taken but left out of ``--help`` so nothing
#: written for an older ccopt breaks (``--out`` is ``-o/--output`` now).
HIDDEN_ALIASES = frozenset({"--out", "--csv", "--plot"})


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit code 2."""

    def error(self, message: str) -> None:  # noqa: D401 - argparse API
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: {message} (see {self.prog} --help)\n")


class Formatter(argparse.RawDescriptionHelpFormatter):
    """The description and example as written (paragraph and example lines),
    the old option spellings (:data:`HIDDEN_ALIASES`) left out."""

    def _format_action_invocation(self, action: argparse.Action) -> str:
        shown = [o for o in action.option_strings if o not in HIDDEN_ALIASES]
        if len(shown) == len(action.option_strings):
            return super()._format_action_invocation(action)
        trimmed = argparse.Action(shown, action.dest, action.nargs, metavar=action.metavar)
        return super()._format_action_invocation(trimmed)


def describe(description: str, example: str) -> dict:
    """``add_parser`` keywords for a command's ``--help``: its one-paragraph
    ``description`` and its ``example`` lines."""
    return {"description": description, "epilog": "example:\n" + example,
            "formatter_class": Formatter}


# -- argument types: each checks its value and says what it needs ------------------
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


# Lengths, times and rates on the command line are bounded as a program's
# coordinates are (ccopt.program.model.MAX_COORDINATE): beyond, the geometry's
# work and the doubles' precision run out.
def _at_most_bound(x: float, text: str) -> float:
    if x > MAX_COORDINATE:
        raise argparse.ArgumentTypeError(f"must be at most {MAX_COORDINATE:g}: {text!r}")
    return x


def positive_float(text: str) -> float:
    """A finite number > 0, at most MAX_COORDINATE."""
    return _at_most_bound(_checked(text, float, lambda x: 0 < x < math.inf,
                                   "a finite number > 0"), text)


def nonneg_float(text: str) -> float:
    """A finite number >= 0, at most MAX_COORDINATE."""
    return _at_most_bound(_checked(text, float, lambda x: 0 <= x < math.inf,
                                   "a finite number >= 0"), text)


def nonneg_int(text: str) -> int:
    return _checked(text, int, lambda n: n >= 0, "a whole number >= 0")


def positive_int(text: str) -> int:
    return _checked(text, int, lambda n: n >= 1, "a whole number >= 1")


def cosine(text: str) -> float:
    return _checked(text, float, lambda x: -1.0 <= x <= 1.0, "a cosine, between -1 and 1")


def axis_values(text: str) -> tuple[float, ...]:
    """``X,Y[,Z]`` -> positive numbers per axis."""
    parts = text.split(",")
    if not 2 <= len(parts) <= 3:
        raise argparse.ArgumentTypeError(f"give 2 or 3 comma-separated numbers X,Y[,Z]: {text!r}")
    # the range the planners take is AxisLimits' own check (LIMIT_RANGE), made there
    return tuple(_checked(x, float, lambda v: 0 < v < math.inf, "a finite number > 0")
                 for x in parts)


def folder_list(text: str) -> tuple[str, ...]:
    """``DIR[:DIR...]`` (the platform's path separator) -> folders, each existing."""
    folders = tuple(f for f in text.split(os.pathsep) if f)
    missing = [f for f in folders if not os.path.isdir(f)]
    if not folders or missing:
        raise argparse.ArgumentTypeError(f"no such folder: {', '.join(missing) or text!r}")
    return folders


def variant_names(text: str) -> list[str]:
    """``A,B`` -> ``["A", "B"]`` (argparse type of ``--variants``)."""
    return [n.strip() for n in text.split(",") if n.strip()]


def chosen_variants(args: argparse.Namespace) -> list[str] | None:
    """Every ``--variants`` name given, in order, ``all`` standing for every
    available variant; ``None`` when none was."""
    names = [n for group in (args.variants or []) for n in group]
    return expand(names) or None


# -- option groups -----------------------------------------------------------------
def add_program(p: argparse.ArgumentParser) -> None:
    """The one input of a command."""
    p.add_argument("program", metavar="PROGRAM", help="program file, case folder or case name")


def add_json_option(p: argparse.ArgumentParser) -> None:
    """``--json`` (every command has it)."""
    p.add_argument("--json", action="store_true", help="machine-readable output on stdout")


def add_reading_options(p: argparse.ArgumentParser) -> None:
    """How to read the program, and ``--json``."""
    p.add_argument("--dialect", choices=list(DIALECTS),
                   help="program dialect (default: from the file suffix)")
    # a Path, so the reader takes it as a file name, never as table text
    p.add_argument("--tool-table", metavar="FILE", type=Path,
                   help="LinuxCNC tool table for G41/G42 D<tool number> (and HEIDENHAIN "
                        "TOOL CALL <tool number>)")
    p.add_argument("--var-file", metavar="FILE", type=Path,
                   help="LinuxCNC parameter file (linuxcnc.var): coordinate system origins "
                        "and offsets in force at the start of a G-code program")
    p.add_argument("--units", choices=["mm", "inch"],
                   help="G-code: convert every length to this unit (default: the program's "
                        "first G20/G21; they may change anywhere)")
    p.add_argument("--table-units", choices=["mm", "inch"],
                   help="the tool table's units (LinuxCNC's are the machine's; default: "
                        "the program's output unit)")
    p.add_argument("--sub-path", metavar="DIR[:DIR...]", type=folder_list,
                   help="G-code: folders where o<name> call finds name.ngc when the program "
                        "does not define it (LinuxCNC's SUBROUTINE_PATH), and nowhere else")
    p.add_argument("--ini", metavar="FILE", type=Path,
                   help="G-code: the machine's LinuxCNC INI file: its [EMCIO] TOOL_TABLE, "
                        "[TRAJ] LINEAR_UNITS (the table's units; inch without it, as "
                        "rs274), [RS274NGC] SUBROUTINE_PATH and PARAMETER_FILE where the "
                        "options above do not say, and #<_ini[SECTION]NAME> values")
    p.add_argument("--max-loop-iterations", type=nonneg_int, metavar="N",
                   help="G-code: most O-word loop iterations, all loops together, before "
                        f"a runaway loop is stopped (default {MAX_LOOP_ITERATIONS})")
    add_json_option(p)


def add_output_option(p: argparse.ArgumentParser, metavar: str, help: str,
                      required: bool = False, old: tuple[str, ...] = ()) -> None:
    """``-o/--output``: where a command writes (a file or a folder, by command);
    ``--out`` and the command's ``old`` spellings are taken too (hidden,
    :data:`HIDDEN_ALIASES`)."""
    p.add_argument("-o", "--output", "--out", *old, dest="output", required=required,
                   metavar=metavar, help=help)


def add_quiet_option(p: argparse.ArgumentParser) -> None:
    """``-q/--quiet``: no progress and no summary on a terminal."""
    p.add_argument("-q", "--quiet", action="store_true",
                   help="print nothing but errors (no progress, no summary)")


def add_workers_option(p: argparse.ArgumentParser, help: str) -> None:
    """``--workers N``: worker processes (default: one per core)."""
    p.add_argument("--workers", type=positive_int, metavar="N", help=help)


def add_ts_option(p: argparse.ArgumentParser) -> None:
    """``--ts``: the interpolation period of the jerk-limited planners."""
    p.add_argument("--ts", type=positive_float, metavar="S",
                   help="interpolation period of the jerk planner, seconds: the acceleration "
                        f"step at a curvature break is at most jmax * ts (default {DEFAULT_TS:g})")


def add_radius_side(p: argparse.ArgumentParser) -> None:
    """The compensation overrides every command that compensates takes."""
    p.add_argument("--radius", type=nonneg_float, metavar="R",
                   help="cutter radius in program units, overriding the program")
    p.add_argument("--side", choices=SIDE_NAMES,
                   help="compensation side wherever it is on, overriding the program")


def add_tolerance_option(p: argparse.ArgumentParser) -> None:
    """``--tolerance T``: the verifier's gouge tolerance, program units."""
    p.add_argument("--tolerance", type=nonneg_float, metavar="T",
                   help="gouges no deeper than T (program units) are warnings, the verdict "
                        f"'ok within tolerance'; deeper ones fail (default {GOUGE_TOLERANCE['mm']:g} "
                        f"mm, {GOUGE_TOLERANCE['inch']:g} inch, by the program's units)")


def add_style_options(p: argparse.ArgumentParser) -> None:
    """The controller style, the radius and side, and the style's own options."""
    p.add_argument("--style", choices=sorted(STYLES),
                   help="controller style (default: the case's, else by dialect: pmac for "
                        "PMAC, heidenhain for Klartext, siemens for SINUMERIK, linuxcnc for "
                        "G-code, fagor where "
                        "G136-G139 appear)")
    add_radius_side(p)
    p.add_argument("--break-cos", type=cosine, metavar="C",
                   help="PMAC Isx99 outside-corner break (cos of the turn) (default: the "
                        f"program's Isx99, else {PMAC_BREAK_COS:g})")
    p.add_argument("--ccbuf", type=nonneg_int, metavar="N",
                   help="Turbo PMAC DEFINE CCBUF: non-plane moves looked through at a corner")


def _per_axis(values) -> str:
    """``100`` when every axis has the same value, else ``100,100,30``."""
    return f"{values[0]:g}" if len(set(values)) == 1 else ",".join(f"{x:g}" for x in values)


def add_limit_options(p: argparse.ArgumentParser) -> None:
    """The axis limits ``--vmax``/``--amax``/``--jmax``; their help names the real
    defaults (the case's ``[limits]``, else :data:`ccopt.cases.DEFAULT_LIMITS`)."""
    v, a = _per_axis(DEFAULT_LIMITS["v"]), _per_axis(DEFAULT_LIMITS["a"])
    p.add_argument("--vmax", type=axis_values, metavar="X,Y[,Z]",
                   help=f"axis velocity limits, units/s (default: the case's [limits] v, "
                        f"else {v} per axis)")
    p.add_argument("--amax", type=axis_values, metavar="X,Y[,Z]",
                   help=f"axis acceleration limits, units/s^2 (default: the case's [limits] a, "
                        f"else {a} per axis)")
    p.add_argument("--jmax", type=axis_values, metavar="X,Y[,Z]",
                   help="axis jerk limits, units/s^3 (default: the case's [limits] j, else "
                        "none); the jerk planner and the jerk-limited stop baseline use them")


def add_variants_option(p: argparse.ArgumentParser, help: str) -> None:
    """``--variants``: blend variants by name, repeated or comma-separated."""
    p.add_argument("--variants", type=variant_names, action="append", metavar="NAME[,NAME]",
                   help=help)
