"""The jerk-limited stop baseline, jerk in samples, --jmax/--ts and [limits] j.

Closed forms (derived here): rest to rest over a line of length L under path
limits v, a, j, with v j >= a^2 and room to cruise, takes
T = L / v + v / a + a / j; with v j < a^2 the acceleration never reaches a
and T = L / v + 2 sqrt(v / j).
"""
from __future__ import annotations

import csv
import io
import json
import math

import pytest

from ccopt.cases import load_case
from ccopt.cli import main
from ccopt.errors import ProgramError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.geometry import Line
from ccopt.toolpath import PathSegment, Role, ToolPath

from _tolerances import JERK_OVER


def seg(geom, feed):
    return PathSegment(geom, Role.COMPENSATED, None, 0.0, 0.0, feed)


def test_stop_baseline_is_an_s_curve_per_block():
    """Two perpendicular 50 mm lines (a stop between): each block is a
    rest-to-rest S-curve, 50/100 + 100/1000 + 1000/20000 s; and 2 sqrt(v/j)
    in place of v/a + a/j when v j < a^2 (j = 5000, v = 100 < a^2 / j = 200)."""
    tp = ToolPath((seg(Line((0, 0), (50, 0)), 1000.0), seg(Line((50, 0), (50, 50)), 1000.0)))
    prof = plan_feed(tp, AxisLimits((100, 100), (1000, 1000), j=(20000, 20000)), planner="stop")
    assert prof.duration == pytest.approx(2 * (0.5 + 0.1 + 0.05), rel=1e-12)
    smp = prof.sample(1e-4)
    assert smp.axis_jerk_ratio.max() <= 1 + 1e-9
    assert smp.axis_acceleration_ratio.max() == pytest.approx(1.0, abs=1e-9)
    soft = plan_feed(tp, AxisLimits((100, 100), (1000, 1000), j=(5000, 5000)), planner="stop")
    assert soft.duration == pytest.approx(2 * (0.5 + 2 * math.sqrt(100 / 5000)), rel=1e-12)
    # without j it stays the trapezoid: 50/100 + 100/1000 per block
    plain = plan_feed(tp, AxisLimits((100, 100), (1000, 1000)), planner="stop")
    assert plain.duration == pytest.approx(2 * 0.6, rel=1e-12)


def test_samples_carry_jerk_of_the_s_curve():
    """On the S-curve the X jerk is +-j in the jerk phases and 0 elsewhere."""
    tp = ToolPath((seg(Line((0, 0), (50, 0)), 1000.0),))
    prof = plan_feed(tp, AxisLimits((100, 100), (1000, 1000), j=(20000, 20000)), planner="stop")
    smp = prof.at([0.025, 0.075, 0.125, 0.3])
    assert smp.jerk[:, 0] == pytest.approx([20000, 0, -20000, 0], abs=1e-6)
    text = smp.to_csv_text()
    header = next(csv.reader(io.StringIO(text)))
    assert header[9:11] == ["jx", "jy"]
    assert prof.summary(1e-3)["max_axis_jerk_ratio"] == pytest.approx(1.0, abs=1e-9)


def test_axis_limits_validate_j():
    with pytest.raises(ValueError, match="j for X"):
        AxisLimits((100, 100), (1000, 1000), j=(0, 10))
    with pytest.raises(ValueError, match="2 or 3"):
        AxisLimits((100, 100), (1000, 1000), j=(10,))
    assert AxisLimits((1, 1, 1), (1, 1, 1), j=(5, 6)).to_json()["j"] == [5.0, 6.0]


def test_case_limits_j(tmp_path):
    (tmp_path / "p.nc").write_text("G1 X10 F600\n")
    toml = 'program = "p.nc"\n[limits]\nv = [100, 100]\na = [1000, 1000]\nj = [20000, 30000]\n'
    (tmp_path / "case.toml").write_text(toml)
    assert load_case(tmp_path).jmax == (20000.0, 30000.0)
    (tmp_path / "case.toml").write_text(toml.replace("[20000, 30000]", "[20000, -1]"))
    with pytest.raises(ProgramError, match="limits.j") as err:
        load_case(tmp_path)
    assert err.value.line == 5


class Result:
    def __init__(self, code, out, err):
        self.returncode, self.stdout, self.stderr = code, out, err


@pytest.fixture
def run_cli(capsys):
    def run(*argv):
        try:
            code = main(list(argv))
        except SystemExit as exc:        # argparse errors
            code = exc.code
        out, err = capsys.readouterr()
        return Result(code, out, err)
    return run


def test_feed_cli_jmax_and_ts(run_cli):
    r = run_cli("feed", "leadin-outside-line", "--jmax", "10000,10000", "--planner", "all",
                "--ts", "0.002", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert list(out["planners"]) == ["toppra", "stop", "junction", "jerk"]
    jerk = out["planners"]["jerk"]
    assert jerk["ts"] == 0.002
    assert jerk["max_axis_jerk_ratio"] <= JERK_OVER
    # more limits: never faster than TOPPRA; never slower than the S-curve per block
    assert out["planners"]["toppra"]["duration"] <= jerk["duration"]
    assert jerk["duration"] <= out["planners"]["stop"]["duration"]
    assert out["limits"]["j"] == [10000.0, 10000.0]


def test_feed_cli_jerk_needs_limits(run_cli):
    r = run_cli("feed", "leadin-outside-line", "--planner", "jerk")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "jerk limits" in r.stderr
    r = run_cli("feed", "leadin-outside-line", "--planner", "all", "--json")
    assert r.returncode == 0
    assert "jerk" not in json.loads(r.stdout)["planners"]
