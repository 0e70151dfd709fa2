"""The sweep spec and its tasks, without Dask: located errors, the product of
the axes, explicit combinations, stable task ids, one task's figures, the
timeout, and ``import ccopt`` staying light."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import ccopt
from ccopt.cli import main
from ccopt.compare import compare
from ccopt.sweep import load_spec
from ccopt.sweep.execute import run_task
from ccopt.sweep.spec import bundled_sweeps_dir
from ccopt.sweep.tasks import expand, resolve_programs

ROOT = Path(__file__).resolve().parents[2]


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "spec.toml"
    path.write_text(text)
    return path


BAD_SPECS = [
    ('programs = ["leadin-inside-line"]\n[axes]\nstyle = ["pmac"]\ncolour = ["red"]\n', 4,
     "unknown axis 'colour'"),
    ('programs = ["leadin-inside-line"]\n\n[axes]\nradius = [1.0, -2]\n', 4,
     "radius: -2 is not a number >= 0"),
    ('programs = ["leadin-inside-line"]\n[axes]\nside = ["up"]\n', 3, "not left or right"),
    ('programs = ["leadin-inside-line"]\n[axes]\nradius = [1.0]\ndelta = [0.01]\n', 4,
     "needs a variant axis"),
    ('programs = ["leadin-inside-line"]\n[axes]\nstyle = ["pmac"]\nvariant = ["smooth"]\n', 4,
     "cannot both be set"),
    ('programs = ["leadin-inside-line"]\n[axes]\nlimits = [{v = [1, 1], a = [1, 1], j = [9]}]\n',
     3, "limits.j: must be a list of 2 or 3 positive numbers"),
    ('programs = ["leadin-inside-line"]\ntolerance = -1\n', 2, "tolerance: -1 is not a number >= 0"),
    ('programs = ["leadin-inside-line"]\n[axes]\nplanner = ["fastest"]\n', 3, "unknown planner"),
    ('programs = ["no-such-case-*"]\n[axes]\nradius = [1.0]\n', 1, "matches none"),
    ('programs = ["leadin-inside-line"]\n[axes]\nradius = 1.0\n[[combinations]]\nstyle = "pmac"\n'
     '[[combinations]]\nradius = 2.0\n', 7, "also an axis"),
    ('programs = ["leadin-inside-line"]\nfoo = 1\n', 2, "unknown key 'foo'"),
    ('programs = ["leadin-inside-line"]\n[axes]\nradius = = 1\n', 3, "invalid TOML"),
    ('programs = ["leadin-inside-line"\n', 1, "invalid TOML"),
]


@pytest.mark.parametrize("text,line,message", BAD_SPECS)
def test_bad_spec_is_one_located_line_and_exit_2(tmp_path, capsys, text, line, message):
    spec = _write(tmp_path, text)
    assert main(["sweep", str(spec), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert err.startswith(f"{spec}:{line}: "), err
    assert message in err
    assert not (tmp_path / "out" / "results.parquet").exists()


def test_product_of_axes_times_combinations(tmp_path):
    spec = load_spec(_write(tmp_path, """
programs = ["leadin-*"]
[axes]
radius = [1.0, 2.0, 3.0]
side = "left"
[[combinations]]
variant = "pmac"
[[combinations]]
variant = "smooth"
delta = 0.02
"""))
    programs = resolve_programs(spec)
    assert [p.label for p in programs] == ["leadin-inside-arc", "leadin-inside-line",
                                           "leadin-outside-arc", "leadin-outside-line"]
    tasks = expand(spec, programs)
    assert len(tasks) == 4 * 3 * 2
    assert len({t.id for t in tasks}) == len(tasks)
    smooth = [t for t in tasks if t.settings["variant"] == "smooth"]
    assert {t.settings["delta"] for t in smooth} == {0.02}
    assert all(t.job.side == "left" for t in tasks)
    # ids depend on the program and setting only, not on the order of the spec
    again = expand(spec, list(reversed(programs)))
    assert {t.id for t in again} == {t.id for t in tasks}


def test_case_defaults_apply_where_the_sweep_sets_nothing():
    spec = load_spec({"programs": ["fagor-seed-line-cancel"], "axes": {"radius": [1.0]}})
    (task,) = expand(spec, resolve_programs(spec))
    case = ccopt.cases.find_case("fagor-seed-line-cancel")
    assert task.job.style == case.style == "fagor"
    assert (task.job.vmax, task.job.amax) == (case.vmax, case.amax)
    assert task.job.radius == 1.0


def test_one_task_equals_the_public_api():
    spec = load_spec({"programs": ["leadin-outside-arc"], "planners": ["toppra", "stop"],
                      "axes": {"style": "linuxcnc", "radius": 1.5}})
    (task,) = expand(spec, resolve_programs(spec))
    prog = ccopt.read_program(resolve_programs(spec)[0].file)
    row = run_task(prog, task.job)
    path = ccopt.compensate(prog, style="linuxcnc", radius=1.5)
    limits = ccopt.AxisLimits(task.job.vmax, task.job.amax)
    prof = ccopt.plan_feed(path, limits)
    cert = ccopt.verify(path, prog, profile=prof, radius=1.5)
    assert row.get("error") is None
    assert row["cycle_time"] == row["cycle_time_toppra"] == prof.duration
    assert row["cycle_time_stop"] == ccopt.plan_feed(path, limits, planner="stop").duration
    assert row["min_clearance"] == cert.min_clearance
    assert row["ok"] is cert.ok and row["path_length"] == path.length
    assert row["limits_ok"] is cert.check("limits").ok
    assert row["max_curvature"] == pytest.approx(1 / 1.5)


def test_a_task_past_its_timeout_is_a_row_with_the_error():
    spec = load_spec({"programs": ["pocket"], "axes": {"planner": "toppra"}})
    (task,) = expand(spec, resolve_programs(spec))
    prog = ccopt.read_program(resolve_programs(spec)[0].file)
    row = run_task(prog, task.job, timeout=0.001)
    assert row["error"].startswith("timeout")


def test_a_bad_program_is_a_row_with_its_error(tmp_path):
    bad = tmp_path / "bad.nc"
    bad.write_text("G1 X(\n")
    spec = load_spec(_write(tmp_path, 'programs = ["bad.nc"]\n[axes]\nradius = [1.0, 2.0]\n'))
    table = ccopt.sweep(spec, serial=True, out=tmp_path / "out")
    assert len(table) == 2 and table["error"].str.contains("bad.nc:1").all()


def test_bundled_specs_load_and_expand():
    names = sorted(p.name for p in bundled_sweeps_dir().glob("*.toml"))
    assert names == ["limits-planners.toml", "styles-radii.toml", "variants.toml"]
    counts = {}
    for name in names:
        spec = load_spec(name.removesuffix(".toml"))  # a bundled spec by name
        counts[name] = len(expand(spec, resolve_programs(spec)))
    assert counts == {"limits-planners.toml": 36, "styles-radii.toml": 108, "variants.toml": 24}


def test_import_ccopt_does_not_import_dask_pandas_pyarrow():
    code = ("import sys, ccopt; assert callable(ccopt.sweep); "
            "print(sorted(m for m in ('dask', 'distributed', 'pandas', 'pyarrow', 'tqdm') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out.strip() == "[]"


def test_a_variant_task_has_the_compare_figures():
    spec = load_spec({"programs": ["leadin-inside-line"], "axes": {"variant": "tangent-arc"}})
    (inp,) = resolve_programs(spec)
    (task,) = expand(spec, [inp])
    prog = ccopt.read_program(inp.file)
    row = run_task(prog, task.job)
    limits = ccopt.AxisLimits(v=list(inp.case.vmax), a=list(inp.case.amax))
    want = compare(prog, ["tangent-arc"], limits=limits, radius=inp.case.radius)["tangent-arc"]
    assert row.get("error") is None
    # compare times a variant by its stop-to-stop stretches (issue 17,
    # ccopt/compare/timing.py), the sweep plans the whole path: equal within
    # toppra's margin (measured 5e-15 relative here), not to the last bit
    assert row["cycle_time"] == pytest.approx(want.figures["duration"], rel=1e-6)
    assert row["deviation"] == want.figures["max_deviation"]
    assert row["path_length"] == want.figures["length"]
    assert row["ok"] is want.figures["certified"]
    assert row["min_clearance"] == want.figures["min_clearance"]
