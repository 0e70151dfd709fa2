"""``ccopt show`` and ``ccopt compensate``: the programmed path and the tool-centre path."""
from __future__ import annotations

import argparse

from ccopt.cli.inputs import job
from ccopt.cli.options import add_program, add_reading_options, add_style_options, describe
from ccopt.cli.output import EXIT_OK, emit_json, path_table
from ccopt.pipeline import pipeline
from ccopt.program.heidenhain.cycles import TOLERANCES
from ccopt.toolpath import programmed_path


def _tolerance_notes(prog) -> list[str]:
    """The HEIDENHAIN ``CYCL DEF 32`` tolerances of ``prog``, one line each:
    recorded and reported, never applied (ccopt runs the exact path)."""
    return [f"  CYCL DEF 32 tolerance {t['tolerance']:g} {prog.units} (line {t['line']}): "
            "recorded, not applied (ccopt runs the exact path)" if t["tolerance"] is not None
            else f"  CYCL DEF 32 (line {t['line']}): the machine's default tolerance"
            for t in prog.meta.get(TOLERANCES, ())]


def _json(path, prog) -> dict:
    doc = path.to_json()
    if prog.meta.get(TOLERANCES):
        doc["cycle32_tolerance"] = list(prog.meta[TOLERANCES])
    return doc


def cmd_show(args: argparse.Namespace) -> int:
    """Print the programmed path as exact segments."""
    prog = job(args.program, args).read()
    path = programmed_path(prog)
    if args.json:
        emit_json(_json(path, prog))
    else:
        print(f"{prog.file}: {len(prog.blocks)} blocks, {prog.dialect}, units {prog.units}, "
              f"programmed path {path.length:.4f} {prog.units}")
        for line in _tolerance_notes(prog):
            print(line)
        print(path_table(path))
    return EXIT_OK


def cmd_compensate(args: argparse.Namespace) -> int:
    """Print the tool-centre path the chosen controller style makes."""
    done = pipeline(job(args.program, args), feed=False, verify=False).result()
    prog, path = done.program, done.path
    if args.json:
        emit_json(_json(path, prog))
    else:
        print(f"{prog.file}: style {path.style} ({done.style_from}), cutter radius "
              f"{path.radius:g} {path.units}, {len(path.segments)} segments, tool path "
              f"{path.length:.4f} {path.units}")
        for line in _tolerance_notes(prog):
            print(line)
        print(path_table(path))
    return EXIT_OK


SHOW_DESCRIPTION = """\
The programmed path of PROGRAM (a .pmc PMAC program, a .nc/.ngc G-code
program, a .h HEIDENHAIN Klartext program, a case folder or a bundled case's
name) before any compensation, as
exact lines, arcs and spirals, each with its role and the program line it
comes from; --json prints the same schema as ccopt compensate --json."""

COMPENSATE_DESCRIPTION = """\
The tool-centre path a controller makes from PROGRAM with cutter radius
compensation (G41/G42/G40, CC1/CC2/CC0): exact lines, arcs and spirals with
their roles (lead-in, compensated, corner, lead-out) and source lines. The
style is --style, else the case's, else by dialect: pmac for PMAC programs,
heidenhain for Klartext, siemens for SINUMERIK, linuxcnc for G-code, fagor where
G136-G139 appear (the output says which); CYCL DEF 32 tolerances are reported,
not applied;
--radius and --side override the program."""


def add_commands(sub, commands: dict) -> None:
    """Register ``show`` and ``compensate`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("show", help="print the programmed path as exact segments",
                       **describe(SHOW_DESCRIPTION, "  ccopt show leadout-inside-line-arc"))
    add_program(p)
    add_reading_options(p)
    commands["show"] = cmd_show

    p = sub.add_parser("compensate", help="the tool-centre path a controller style makes",
                       **describe(COMPENSATE_DESCRIPTION,
                                  "  ccopt compensate cases/leadin-outside-arc --radius 1.5"))
    add_program(p)
    add_reading_options(p)
    add_style_options(p)
    commands["compensate"] = cmd_compensate
