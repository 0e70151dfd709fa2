"""The ``ccopt`` command: the parser assembled from one module per command
group, and :func:`main`.

- :mod:`.show`: ``show`` and ``compensate``; :mod:`.feed`: ``feed``;
  :mod:`.verify`: ``verify``; :mod:`.export`: ``export``; :mod:`.run`:
  ``run``; :mod:`.compare`: ``compare`` and ``smooth``;
- :mod:`.inputs`: the input and its settings, resolved once for every command;
- :mod:`.options`: the option groups the commands share; :mod:`.output`: exit
  codes, JSON and tables.

Exit codes (DESIGN.md): 0 success, 1 verification failed, 2 bad input (one
line ``file:line: message`` on stderr, never a traceback). An unexpected
internal failure prints one line and exits 3; ``CCOPT_DEBUG=1`` shows the
traceback.
"""
from __future__ import annotations

import argparse
import os
import sys
from typing import Callable, Sequence

from ccopt.atomic import inputs_guarded
from ccopt.cli import compare, export, feed, run, show, sweep, verify
from ccopt.cli.options import Parser
from ccopt.cli.output import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_OK
from ccopt.errors import CcoptError
from ccopt.version import __version__

Command = Callable[[argparse.Namespace], int]

#: exit code of an interrupted command (128 + SIGINT, as a shell reports it)
EXIT_INTERRUPTED = 130


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, Command]]:
    """The ``ccopt`` parser and each command's function by name."""
    parser = Parser(prog="ccopt", description=(
        "Cutter radius compensation as a controller does it (PMAC reference), "
        "time-optimal feed, verification, blend comparison and export."))
    parser.add_argument("--version", action="version", version=f"ccopt {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    commands: dict[str, Command] = {}
    for group in (show, feed, verify, export, run, compare, sweep):
        group.add_commands(sub, commands)
    return parser, commands


def _flush_and_exit(code: int) -> None:
    """End the process now with ``code``, what was printed flushed."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


def main(argv: Sequence[str] | None = None) -> int:
    """The ``ccopt`` command with ``argv`` (``None``: this process's own
    arguments, and then a Ctrl-C ends the process at once); returns the exit
    code."""
    parser, commands = build_parser()
    args = parser.parse_args(argv)
    if not args.command:
        parser.print_help()
        return EXIT_BAD_INPUT
    try:
        # no file a command reads as input is written over (ccopt.atomic)
        with inputs_guarded():
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
        if argv is None:
            # the process's own command: leave at once, not after tearing down
            # the solvers' modules (a second or more); temporary files are gone
            # already (ccopt.atomic removes its own on the way out)
            _flush_and_exit(EXIT_INTERRUPTED)
        return EXIT_INTERRUPTED
    except Exception as exc:  # an internal bug: one line, traceback on request
        if os.environ.get("CCOPT_DEBUG"):
            # a worker process's failure carries the worker's traceback as text
            if getattr(exc, "child_traceback", ""):
                print(exc.child_traceback, file=sys.stderr)
            raise
        print(f"ccopt: internal error: {type(exc).__name__}: {exc} "
              "(set CCOPT_DEBUG=1 for the traceback and please report it)", file=sys.stderr)
        return EXIT_INTERNAL
