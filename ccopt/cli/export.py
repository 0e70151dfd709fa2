"""``ccopt export``: write the verified tool-centre path."""
from __future__ import annotations

import argparse

from ccopt.atomic import job_inputs, refuse_overwriting_inputs
from ccopt.cli.inputs import job
from ccopt.cli.options import (add_output_option, add_program, add_reading_options,
                               add_style_options, describe, positive_float)
from ccopt.export.arcfit import DEFAULT_TOL
from ccopt.cli.output import EXIT_FAILED, EXIT_OK, emit_json
from ccopt.pipeline import Target, pipeline


DESCRIPTION = """\
Compensate PROGRAM, then write the tool-centre path with no compensation
words, in the format -o's suffix names: G-code (.nc, .ngc; spirals and blend
curves as arcs within --tol, with a certified bound), PMAC (.pmc), SVG or
JSON. A program is read back, compared with the computed path and verified
against the contour before it is written (atomically); the verdict is in the
file's header and the exit code (1 when it fails). OUT is never one of the
input files (the program, a link to it, its tool table...): that is exit 2
and nothing is written."""

EXAMPLE = """\
  ccopt export cases/leadin-outside-arc -o leadin.nc"""


def cmd_export(args: argparse.Namespace) -> int:
    """Compensate, then write the tool-centre path (read back and verified
    first, see :mod:`ccopt.export`). Exit 1 when the verification fails; the
    failing file is then written as ``NAME.failed.EXT`` if ``NAME.EXT`` exists,
    and the message says so."""
    work = job(args.program, args)
    # before any work: the output must not replace an input (exit 2, nothing written)
    refuse_overwriting_inputs([args.output], job_inputs(work))
    done = pipeline(work, feed=False, verify=False,
                    export=[Target(args.output, title=work.title, tol=args.tol)]).result()
    path, (res,) = done.path, done.exports
    if args.json:
        emit_json(res.to_json())
    else:
        verdict = {True: "verified OK", False: "verification FAILED",
                   None: res.nothing_to_verify or "not verified"}
        print(f"{res.file}: {res.format}, read back within {res.roundtrip_error:.3g} "
              f"{path.units} (tolerance {res.tolerance:g}), {verdict[res.verified]}"
              f"{res.where_written()}")
    return EXIT_FAILED if res.verified is False else EXIT_OK


def add_commands(sub, commands: dict) -> None:
    """Register ``export`` on ``sub`` (argparse subparsers)."""
    p = sub.add_parser("export", help="write the verified tool-centre path (.nc .pmc .svg .json)",
                       **describe(DESCRIPTION, EXAMPLE))
    add_program(p)
    add_output_option(p, "OUT", required=True,
                      help="output file; the suffix picks the format (.nc .ngc .pmc .svg .json)")
    p.add_argument("--tol", type=positive_float, metavar="T",
                   help="arc-fit tolerance of spirals and blend curves written as arcs, "
                        f"program units (default {DEFAULT_TOL['mm']:g} mm, "
                        f"{DEFAULT_TOL['inch']:.3g} inch)")
    add_reading_options(p)
    add_style_options(p)
    commands["export"] = cmd_export
