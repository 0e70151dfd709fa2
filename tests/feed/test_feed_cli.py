"""``ccopt feed``: JSON per planner, limits from case.toml, CSV, one-line errors."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from ccopt.cli import main

from _tolerances import TOPPRA_OVER

CASES = Path(__file__).resolve().parents[2] / "cases"
KEYS = {"duration", "samples", "max_axis_acc_ratio", "max_axis_vel_ratio"}


def run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:        # argparse errors
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def test_json_on_a_bundled_case_uses_its_limits(capsys):
    code, out, err = run(capsys, "feed", "pocket", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    assert KEYS <= set(data)
    assert data["limits"] == {"v": [100.0, 100.0, 30.0], "a": [1000.0, 1000.0, 300.0]}
    assert data["planner"] == "toppra" and list(data["planners"]) == ["toppra"]
    assert data["max_axis_vel_ratio"] <= TOPPRA_OVER and data["max_axis_acc_ratio"] <= TOPPRA_OVER
    assert data["samples"] == int(data["duration"] / 1e-3) + 1 or \
        data["samples"] == int(data["duration"] / 1e-3) + 2


def test_every_planner_asked_is_reported(capsys):
    code, out, _ = run(capsys, "feed", str(CASES / "profile"), "--planner", "all", "--json")
    assert code == 0
    data = json.loads(out)
    assert list(data["planners"]) == ["toppra", "stop", "junction"]
    for name, rep in data["planners"].items():
        assert KEYS <= set(rep), name
        assert rep["max_axis_vel_ratio"] <= TOPPRA_OVER and rep["max_axis_acc_ratio"] <= TOPPRA_OVER
    T = data["planners"]["toppra"]["duration"]
    assert T <= data["planners"]["stop"]["duration"]
    assert T <= data["planners"]["junction"]["duration"] * (1 + 1e-6)
    code, out2, _ = run(capsys, "feed", "profile", "--planner", "stop", "--planner", "junction",
                        "--json")
    assert list(json.loads(out2)["planners"]) == ["stop", "junction"]


def test_limits_from_the_command_line_override_the_case(capsys):
    code, out, _ = run(capsys, "feed", "pocket", "--vmax", "50,50,10", "--amax", "200,200,50",
                       "--json")
    assert code == 0
    slow = json.loads(out)
    code, out, _ = run(capsys, "feed", "pocket", "--json")
    assert slow["duration"] > json.loads(out)["duration"]
    assert slow["limits"]["v"] == [50.0, 50.0, 10.0]


def test_program_file_without_limits_takes_the_printed_default(capsys, tmp_path):
    # issue 17: one rule everywhere: --vmax/--amax, else the case's [limits],
    # else ccopt.cases.DEFAULT_LIMITS (100 units/s, 1000 units/s^2), which the
    # output names. (Until issue 17 a program without limits was an error.)
    prog = tmp_path / "p.nc"
    prog.write_text("G21 G90 F600\nG1 X10 Y0\nG3 X0 Y10 I-10 J0\n")
    code, out, err = run(capsys, "feed", str(prog), "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["limits_from"] == "default"
    code, out2, _ = run(capsys, "feed", str(prog), "--vmax", "100,100,100",
                        "--amax", "1000,1000,1000", "--json")
    assert code == 0
    assert json.loads(out2)["duration"] == pytest.approx(doc["duration"], rel=1e-9)
    code, text, _ = run(capsys, "feed", str(prog))
    assert code == 0 and "default" in text and "v=[100.0, 100.0, 100.0]" in text


def test_csv_per_planner(capsys, tmp_path):
    one = tmp_path / "one.csv"
    code, _, _ = run(capsys, "feed", "z-plunges", "--csv", str(one))
    assert code == 0 and one.read_text().startswith("t,s,block,x,y,z,")
    many = tmp_path / "many.csv"
    code, out, _ = run(capsys, "feed", "z-plunges", "--planner", "toppra,stop", "--csv", str(many),
                       "--json")
    assert code == 0
    assert (tmp_path / "many.toppra.csv").is_file() and (tmp_path / "many.stop.csv").is_file()
    assert json.loads(out)["planners"]["stop"]["csv"] == str(tmp_path / "many.stop.csv")


def test_text_output(capsys):
    code, out, err = run(capsys, "feed", "pocket", "--planner", "all")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[1].split()[0] == "planner"
    assert [ln.split()[0] for ln in lines[2:]] == ["toppra", "stop", "junction"]


@pytest.mark.parametrize("argv,needle", [
    (["--vmax", "1,x"], "--vmax"),
    (["--vmax", "100"], "--vmax"),
    (["--vmax", "1,2,3,4"], "--vmax"),
    (["--amax", "0,100"], "--amax"),
    (["--amax=-5,100,1"], "--amax: must be a finite number > 0: '-5'"),
    (["--vmax=0,100,1"], "--vmax: must be a finite number > 0: '0'"),
    (["--vmax", "nan,1"], "--vmax"),
    (["--planner", "fastest"], "--planner"),
    (["--dt", "0"], "--dt"),
    (["--junction-deviation", "-1"], "--junction-deviation"),
    (["--vmax", "100,100", "--amax", "1000,1000"], "axis Z"),     # the pocket plunges in Z
    (["--vmax", "100,100", "--amax", "1000,1000,300"], "same axes"),
    # limits the planners cannot square without under- or overflow
    (["--vmax", "1e-300,1,1", "--amax", "1,1,1"], "v for X must be between 1e-06 and 1e+09"),
    (["--vmax", "1,1,1", "--amax", "1,1e300,1"], "a for Y must be between 1e-06 and 1e+09"),
    (["--centripetal-acc", "1e-9"], "centripetal_acc must be between"),
    # the pocket takes 8.77 s: every 1e-8 s is 8.8e8 samples
    (["--dt", "1e-8"], "use a larger dt"),
])
def test_bad_values_exit_2_with_one_line(capsys, argv, needle):
    code, out, err = run(capsys, "feed", "pocket", *argv)
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and needle in err
    assert "Traceback" not in err


@pytest.mark.parametrize("text, duration", [
    ("G21 G90 F600\nG4 P1.5\n", 1.5),     # a dwell alone: no motion, 1.5 s
    ("G21\n", 0.0),                        # nothing at all
])
def test_programs_without_motion(capsys, tmp_path, text, duration):
    prog = tmp_path / "still.nc"
    prog.write_text(text)
    for extra in ([], ["--json"]):
        code, out, err = run(capsys, "feed", str(prog), "--vmax", "1,1", "--amax", "1,1",
                             "--planner", "all", *extra)
        assert code == 0, err
    doc = json.loads(out)
    for name in ("toppra", "stop", "junction"):
        r = doc["planners"][name]
        assert r["duration"] == pytest.approx(duration, abs=1e-12)
        assert r["max_axis_vel_ratio"] == 0.0 and r["max_axis_acc_ratio"] == 0.0
