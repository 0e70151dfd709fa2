"""``ccopt show`` and ``ccopt compensate``: the programmed path and the tool-centre path."""
from __future__ import annotations

import argparse

from ccopt.cli.inputs import job
from ccopt.cli.options import add_program, add_reading_options, add_style_options
from ccopt.cli.output import EXIT_OK, emit_json, path_table
from ccopt.toolpath import programmed_path


def cmd_show(args: argparse.Namespace) -> int:
    """Print the programmed path as exact segments."""
    prog = job(args.program, args).read()
    path = programmed_path(prog)
    if args.json:
        emit_json(path.to_json())
    else:
        print(f"{prog.file}: {len(prog.blocks)} blocks, {prog.dialect}, units {prog.units}, "
              f"programmed path {path.length:.4f} {prog.units}")
        print(path_table(path))
    return EXIT_OK


def cmd_compensate(args: argparse.Namespace) -> int:
    """Print the tool-centre path the chosen controller style makes."""
    work = job(args.program, args)
    prog = work.read()
    path = work.compensate(prog)
    if args.json:
        emit_json(path.to_json())
    else:
        print(f"{prog.file}: style {path.style}, cutter radius {path.radius:g} {path.units}, "
              f"{len(path.segments)} segments, tool path {path.length:.4f} {path.units}")
        print(path_table(path))
    return EXIT_OK


def add_commands(sub, commands: dict) -> None:
    """Register ``show`` and ``compensate`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("show", help="print the programmed path as exact segments")
    add_program(p)
    add_reading_options(p)
    commands["show"] = cmd_show

    p = sub.add_parser("compensate", help="the tool-centre path a controller style makes")
    add_program(p)
    add_reading_options(p)
    add_style_options(p)
    commands["compensate"] = cmd_compensate
