"""Write docs/cli.md from the parsers' own ``--help``: ``python docs/cli_reference.py``.

``tests/test_docs_tour.py`` checks that docs/cli.md is what this writes, so
the reference never drifts from the options and their defaults.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import os
import sys
from pathlib import Path

OUT = Path(__file__).resolve().parent / "cli.md"
#: the width the help is wrapped at
WIDTH = 100


def _help(argv: list[str]) -> str:
    from ccopt.cli import main
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        try:
            main(argv)
        except SystemExit:
            pass
    return buf.getvalue().rstrip()


def reference() -> str:
    """docs/cli.md's text (the help wrapped at :data:`WIDTH` columns)."""
    before = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(WIDTH)
    try:
        return _reference()
    finally:
        if before is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = before


def _reference() -> str:
    from ccopt.cli import build_parser
    parser, _ = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    parts = ["# Command-line reference", "",
             "Written by `python docs/cli_reference.py` from the parsers' own `--help`",
             "(do not edit by hand). What the commands do, at length: "
             "[commands.md](commands.md).", "",
             "```", _help(["--help"]), "```"]
    for name in sub.choices:
        parts += ["", f"## `ccopt {name}`", "", "```", _help([name, "--help"]), "```"]
    return "\n".join(parts) + "\n"


if __name__ == "__main__":
    OUT.write_text(reference())
    print(f"written: {OUT}", file=sys.stderr)
