"""The ``ccopt`` command: exit codes, one-line errors, JSON schema."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import ccopt
from ccopt.cli import main

CASES = Path(__file__).resolve().parents[1] / "cases"


def run_cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"ccopt {ccopt.__version__}"


def test_show_json_schema(capsys, tmp_path):
    prog = tmp_path / "p.nc"
    prog.write_text("G21 G90 F600\nG1 X10 Y0\nG3 X0 Y10 I-10 J0\n")
    code, out, err = run_cli(capsys, "show", str(prog), "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    segs = data["segments"]
    assert [s["kind"] for s in segs] == ["line", "arc"]
    assert segs[0]["start"] == [0, 0] and segs[0]["end"] == [10, 0]
    assert segs[0]["block"] == 2 and segs[1]["block"] == 3
    arc = segs[1]
    assert arc["center"] == pytest.approx([0, 0], abs=1e-12)
    assert arc["ccw"] is True
    assert arc["sweep"] == pytest.approx(math.pi / 2, abs=1e-12)
    # F600 per minute is 10 mm/s
    assert segs[0]["feed"] == pytest.approx(10.0)


def test_compensate_json_on_a_case(capsys):
    code, out, _ = run_cli(capsys, "compensate", str(CASES / "leadin-outside-line"), "--json")
    assert code == 0
    data = json.loads(out)
    assert data["style"] == "pmac" and data["radius"] == 2
    roles = [s["role"] for s in data["segments"]]
    assert roles == ["rapid", "lead-in", "corner", "compensated", "lead-out"]
    corner = data["segments"][2]
    # arc about the programmed corner (0,0) from (-2,0) to (0,2), clockwise
    assert corner["center"] == pytest.approx([0, 0], abs=1e-12)
    assert corner["sweep"] == pytest.approx(-math.pi / 2, abs=1e-12)


def test_compensate_overrides_radius_and_side(capsys):
    code, out, _ = run_cli(capsys, "compensate", str(CASES / "leadout-inside-line-line"),
                           "--radius", "1", "--side", "left", "--json")
    assert code == 0
    segs = json.loads(out)["segments"]
    comp = next(s for s in segs if s["role"] == "compensated")
    # left of +X by 1
    assert comp["start"][1] == pytest.approx(1.0) and comp["end"][1] == pytest.approx(1.0)


@pytest.mark.parametrize("argv, fragment", [
    (["show", "does-not-exist.nc"], "does-not-exist.nc: no such program"),
    (["compensate", str(CASES / "concave-arc-too-small")], "part.pmc:8:1: concave arc radius 1"),
    (["compensate", str(CASES / "pocket"), "--radius", "-1"], "must be a finite number >= 0"),
    (["compensate", str(CASES / "pocket"), "--style", "nope"], "invalid choice"),
    (["frobnicate"], "invalid choice"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, fragment):
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse usage errors
        code = exc.code
    out, err = capsys.readouterr()
    assert code == 2
    assert fragment in err
    assert len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err


def test_missing_radius_is_located(capsys, tmp_path):
    prog = tmp_path / "noradius.pmc"
    prog.write_text("LINEAR ABS F10\nCC1\nX10 Y0\nX10 Y10\nCC0\nX0 Y10\n")
    code, _, err = run_cli(capsys, "compensate", str(prog))
    assert code == 2
    assert err.startswith(f"{prog}:3:") and "no cutter radius" in err
    # --radius supplies it
    code, out, _ = run_cli(capsys, "compensate", str(prog), "--radius", "1", "--json")
    assert code == 0


@pytest.mark.parametrize("text, line, fragment", [
    ("LINEAR ABS F10\nCCR1 CC1\nX10 Y0\nTM100\nX10 Y10\nCC0\nX0 Y10\n", 5, "TM"),
    ("LINEAR ABS F10\nCCR1 CC1\nX10 Y0\nNORMAL J-1\nX10 Z10\nCC0\n", 5, "plane change"),
])
def test_pmac_conditions_that_cannot_be_compensated(capsys, tmp_path, text, line, fragment):
    prog = tmp_path / "bad.pmc"
    prog.write_text(text)
    code, _, err = run_cli(capsys, "compensate", str(prog))
    assert code == 2
    assert err.startswith(f"{prog}:{line}:"), err
    assert fragment in err


def test_run_writes_toolpaths_and_summary(capsys, tmp_path):
    code, out, err = run_cli(capsys, "run", str(CASES / "pocket"), str(CASES / "profile"),
                             "--out", str(tmp_path), "--json")
    assert code == 0, err
    rows = json.loads(out)["cases"]
    assert [r["name"] for r in rows] == ["pocket", "profile"]
    for r in rows:
        data = json.loads(Path(r["toolpath"]).read_text())
        assert data["style"] == "pmac" and data["radius"] == 3
    assert (tmp_path / "summary.json").is_file()


def test_run_without_arguments_runs_every_bundled_case(capsys, tmp_path):
    code, out, err = run_cli(capsys, "run", "--json")
    assert code == 0, err
    rows = json.loads(out)["cases"]
    names = {p.name for p in CASES.iterdir() if (p / "case.toml").is_file()}
    assert {r["name"] for r in rows} == names
    err_row = next(r for r in rows if r["name"] == "concave-arc-too-small")
    assert err_row["status"] == "error (expected)"


# -- property: random text never gives anything but exit 0 or a one-line error --------
GCODE_ALPHABET = "GMXYZIJKRFPDNOT0123456789.-+#[]()=; \n%abcdefghijklmnopqrstuvwxyz<>/*"


@settings(max_examples=200, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=st.one_of(st.text(alphabet=GCODE_ALPHABET, max_size=200), st.text(max_size=100)),
       suffix=st.sampled_from([".nc", ".pmc"]))
def test_show_on_random_text(tmp_path, capsys, text, suffix):
    prog = tmp_path / f"fuzz{suffix}"
    prog.write_text(text, encoding="utf-8")
    code = main(["show", str(prog)])
    out, err = capsys.readouterr()
    assert code in (0, 2), err
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(str(prog)), err
        assert "Traceback" not in err and "internal error" not in err


def test_no_traceback_in_a_real_process(tmp_path):
    prog = tmp_path / "bad.nc"
    prog.write_text("G1 X1 Y1\nG2 X2 Y2\n")  # feed missing and arc without centre
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    proc = subprocess.run([sys.executable, "-m", "ccopt.cli", "show", str(prog)],
                          capture_output=True, text=True, env=env)
    assert proc.returncode == 2
    assert proc.stderr.startswith(f"{prog}:1:"), proc.stderr
    assert "Traceback" not in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
