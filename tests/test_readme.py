"""The Python example (docs/python.md, which the README points to) runs as
written, on a bundled program copied to ``part.pmc``, and gives figures
worked out here from the program."""
from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# PMAC lead-in on a LINEAR move: CCR2 CC1, lead-in (0,-20)->(0,0), the first
# compensated move (0,0)->(20,0) at F20 (PMAC: units per second), CC0.
CASE = ROOT / "cases" / "leadin-outside-line"
CUTTER_RADIUS = 2.0
FIRST_MOVE_LENGTH, FEED = 20.0, 20.0


def _python_example() -> str:
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "docs" / "python.md").read_text(), re.S)
    assert blocks, "docs/python.md has no Python example"
    return blocks[0]


def test_readme_python_example_runs(tmp_path, monkeypatch, capsys):
    shutil.copy(CASE / "part.pmc", tmp_path / "part.pmc")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(_python_example(), "docs/python.md", "exec"), namespace)
    cert, prof, path = namespace["cert"], namespace["prof"], namespace["path"]
    assert cert.ok
    # the move along the contour runs at r from it; nothing comes closer
    assert math.isclose(cert.min_clearance, CUTTER_RADIUS, abs_tol=1e-9)
    # its offset is as long as the move itself, and it cannot run faster than F
    assert prof.duration > FIRST_MOVE_LENGTH / FEED
    printed = capsys.readouterr().out.splitlines()
    assert len(printed) == len(list(path)) + 1   # one line per segment, then the figures
    written = (tmp_path / "part-comp.nc").read_text()
    assert "verified against the programmed contour: OK" in written


def test_export_is_callable_at_the_top_level():
    import ccopt
    assert callable(ccopt.export)
