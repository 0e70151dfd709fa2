"""The ``ccopt`` command run in this process, for the tests: ``(exit code,
stdout, stderr)``, argparse's own exit (``--help``, a bad option) included."""
from __future__ import annotations

from ccopt.cli import main


def run_cli(capsys, *argv: str) -> tuple[int, str, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:  # argparse's own exit
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err
