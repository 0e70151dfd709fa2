"""A program with no compensation word goes through export and run (issue 17:
it crashed formatting a clearance that does not exist)."""
from __future__ import annotations

import json

import pytest

from ccopt.cli import main


def test_export_and_run_of_a_program_without_compensation(tmp_path, capsys):
    prog = tmp_path / "plain.nc"
    prog.write_text("G21 G90 F6000\nG1 X100 Y0\n")
    assert main(["export", str(prog), "-o", str(tmp_path / "out.nc")]) == 0
    text = (tmp_path / "out.nc").read_text()
    assert "no compensated move to check" in text and "G1 X100 Y0" in text
    capsys.readouterr()
    assert main(["run", str(prog), "-o", str(tmp_path / "run"), "--no-compare"]) == 0
    row = json.loads((tmp_path / "run" / "summary.json").read_text())["cases"][0]
    # 100 mm at F6000 (100 mm/s) under the default 100 mm/s, 1000 mm/s^2:
    # a trapezoid with 0.1 s ramps, 1.0 s + 0.1 s
    assert row["duration"] == pytest.approx(1.1, rel=1e-6)
    assert row["min_clearance"] is None and row["status"] == "ok"
