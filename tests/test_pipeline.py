"""One Job, one pipeline (issue 29): ``run``, ``compare``, ``verify``, the sweep
and the Python API resolve a job's settings in one function and run it
through one pipeline, so they give the same figures bit for bit; the default
style is the same everywhere; ``run`` and ``verify`` certify the same path
the same way with ``--side``/``--radius``; a sweep takes jerk limits; a
compare row is ``ok`` only when its path is certified.

The expected figures are derived here from the public API called stage by
stage (compensate, plan_feed, verify), not from the pipeline itself."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import ccopt
from ccopt.cases import find_case, resolve_input
from ccopt.cli import main
from ccopt.cli.inputs import job as cli_job
from ccopt.cli import build_parser
from ccopt.compare import compare
from ccopt.sweep import load_spec
from ccopt.sweep.execute import run_task
from ccopt.sweep.tasks import expand, resolve_programs

CASE = "leadin-inside-line"


def _by_hand(case_name: str, style: str = "pmac", radius=None, side=None, jmax=None,
             planner: str = "toppra"):
    """``(cycle time, verdict, min clearance)`` from the public API, stage by stage."""
    c = find_case(case_name)
    prog = ccopt.read_program(c.program)
    radius = c.radius if radius is None else radius
    path = ccopt.compensate(prog, style, radius=radius, side=side)
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=jmax)
    prof = ccopt.plan_feed(path, limits, planner=planner)
    cert = ccopt.verify(path, prog, profile=prof, radius=radius, side=side)
    return prof.duration, cert.ok, cert.min_clearance


def _run_row(tmp_path: Path, capsys, *argv, codes=(0,)) -> dict:
    """``ccopt run CASE ...``'s row in summary.json (the compare rows with it);
    its exit code one of ``codes``."""
    out = tmp_path / "run"
    assert main(["run", *argv, "-o", str(out), "--workers", "1", "--json"]) in codes
    capsys.readouterr()
    (row,) = json.loads((out / "summary.json").read_text())["cases"]
    return row


def _sweep_row(spec: dict) -> dict:
    spec = load_spec(spec)
    (program,) = resolve_programs(spec)
    (task,) = expand(spec, [program])
    row = run_task(ccopt.read_program(program.file), task.job)
    assert row.get("error") is None, row
    return row


def test_run_compare_sweep_and_the_api_give_bit_identical_figures(tmp_path, capsys):
    want = _by_hand(CASE)
    # the Python API's job through the pipeline
    out = ccopt.pipeline(ccopt.make_job(CASE)).result()
    assert (out.duration, out.certificate.ok, out.certificate.min_clearance) == want
    # ccopt run (its own path, and PMAC's row of its comparison, which reuses them)
    row = _run_row(tmp_path, capsys, CASE)
    assert (row["duration"], row["verified"], row["min_clearance"]) == want
    (pmac,) = [v for v in row["compare"] if v["name"] == "pmac"]
    assert (pmac["duration"], pmac["certified"], pmac["min_clearance"]) == want
    # ccopt compare
    assert main(["compare", CASE, "--variants", "pmac,tangent-arc", "--workers", "1",
                 "--json"]) == 0
    (cmp,) = [v for v in json.loads(capsys.readouterr().out)["variants"] if v["name"] == "pmac"]
    assert (cmp["duration"], cmp["certified"], cmp["min_clearance"]) == want
    # a sweep task on the case with the case's settings
    srow = _sweep_row({"programs": [CASE]})
    assert (srow["cycle_time"], srow["ok"], srow["min_clearance"]) == want


def test_under_jerk_limits_every_entry_point_takes_the_jerk_planner(tmp_path, capsys):
    c = find_case(CASE)
    jmax = tuple(10.0 * a for a in c.amax)
    want = _by_hand(CASE, jmax=jmax, planner="jerk")
    text = ",".join(f"{j:g}" for j in jmax)
    row = _run_row(tmp_path, capsys, CASE, "--jmax", text, "--no-compare")
    assert row["planner"] == "jerk"
    assert (row["duration"], row["verified"], row["min_clearance"]) == want
    out = ccopt.pipeline(ccopt.make_job(CASE, jmax=jmax)).result()
    assert out.planner == "jerk"
    assert (out.duration, out.certificate.ok, out.certificate.min_clearance) == want
    # a sweep spec with jerk limits runs (it was refused: "ccopt does not have yet")
    srow = _sweep_row({"programs": [CASE], "axes": {"limits": [
        {"name": "jerk", "v": list(c.vmax), "a": list(c.amax), "j": list(jmax)}]}})
    assert srow["cycle_time_jerk"] == srow["cycle_time"] == want[0]
    assert (srow["ok"], srow["min_clearance"]) == want[1:]
    assert srow["limits_ok"] is True


def test_run_and_verify_certify_the_same_path_with_side_and_radius(tmp_path, capsys):
    # PMAC on the right of leadin-inside-line's contour with a 1.5 cutter: certified
    # against the overridden side; judged against the programmed side (left) it fails
    c = find_case(CASE)
    prog = ccopt.read_program(c.program)
    path = ccopt.compensate(prog, "pmac", radius=1.5, side="right")
    assert not ccopt.verify(path, prog, radius=1.5, side="left").ok
    want = _by_hand(CASE, radius=1.5, side="right")
    assert want[1] is True
    overrides = ["--side", "right", "--radius", "1.5"]
    row = _run_row(tmp_path, capsys, CASE, *overrides, "--no-compare")
    assert (row["duration"], row["verified"], row["min_clearance"]) == want
    assert main(["verify", CASE, *overrides, "--feed", "--json"]) == 0
    cert = json.loads(capsys.readouterr().out)
    # the same certificate, check by check
    assert cert["checks"] == row["certificate"]["checks"]
    assert (cert["ok"], cert["min_clearance"]) == want[1:]


def _gcode(tmp_path: Path, fagor: bool) -> Path:
    """A small G-code plate with G41 and no tool number (the radius comes from
    the command line); with Fagor's G136 when ``fagor``."""
    path = tmp_path / ("fagor.ngc" if fagor else "plate.ngc")
    path.write_text(("G21 G90 G17 G136\n" if fagor else "G21 G90 G17\n") +
                    "G0 X-10 Y-5\nG41 G1 X0 Y0 F600\nG1 X20 Y0\nG1 X20 Y10\nG1 X0 Y10\n"
                    "G1 X0 Y0\nG40 G1 X-10 Y-5\nM2\n")
    return path


@pytest.mark.parametrize("fagor,style", [(False, "linuxcnc"), (True, "fagor")])
def test_the_default_style_is_the_same_in_every_entry_point(tmp_path, capsys, fagor, style):
    program = _gcode(tmp_path, fagor)
    # ccopt compensate
    assert main(["compensate", str(program), "--radius", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["style"] == style
    # the Python API
    out = ccopt.pipeline(ccopt.make_job(str(program), radius=1.0), feed=False,
                         verify=False).result()
    assert out.path.style == style
    # a sweep of the bare program (it took pmac)
    spec = load_spec({"programs": [str(program)], "axes": {"radius": 1.0},
                      "planners": ["stop"]})
    (task,) = expand(spec, resolve_programs(spec))
    row = run_task(ccopt.read_program(program), task.job)
    assert row.get("error") is None, row
    sweep_out = ccopt.pipeline(task.job, feed=False, verify=False).result()
    assert sweep_out.path.style == style
    # ccopt run (its verdict is the verifier's business here: the style is what counts)
    run = _run_row(tmp_path, capsys, str(program), "--radius", "1", "--no-compare",
                   codes=(0, 1))
    assert run["style"] == style


def test_a_case_without_style_takes_the_dialects(tmp_path):
    program = _gcode(tmp_path, False)
    (tmp_path / "case.toml").write_text(f'program = "{program.name}"\nradius = 1.0\n')
    job = resolve_input(str(tmp_path))
    assert job.style is None
    assert job.style_for(job.read())[0] == "linuxcnc"


def test_settings_resolve_the_same_from_the_command_line_a_sweep_row_and_the_api():
    fields = ("style", "radius", "side", "vmax", "amax", "jmax", "tolerance", "program")
    api = ccopt.make_job(CASE, radius=1.5, side="right", tolerance=0.01)
    parser, _ = build_parser()
    args = parser.parse_args(["compare", CASE, "--radius", "1.5", "--side", "right",
                              "--tolerance", "0.01"])
    cli = cli_job(CASE, args)
    spec = load_spec({"programs": [CASE], "tolerance": 0.01,
                      "axes": {"radius": 1.5, "side": "right"}})
    (task,) = expand(spec, resolve_programs(spec))
    for other in (cli, task.job):
        assert {f: getattr(other, f) for f in fields} == {f: getattr(api, f) for f in fields}
    assert api.tolerance == 0.01 and api.radius == 1.5


def test_no_compare_row_is_ok_unless_its_path_is_certified():
    c = find_case("leadout-outside-line-line")
    prog = ccopt.read_program(c.program)
    cmp = compare(prog, ["pmac", "linuxcnc", "line-arc"], limits=ccopt.AxisLimits(c.vmax, c.amax),
                  radius=c.radius)
    for row in cmp:
        cert = ccopt.verify(row.toolpath, prog, radius=c.radius)   # certified again here
        assert (row.status == "ok") == bool(cert.ok), row.name
        assert row.figures["certified"] is bool(cert.ok)
    # the geometric line-arc lead gouges here: it says so, and keeps its figures
    line_arc = cmp["line-arc"]
    assert line_arc.status == "uncertified"
    assert line_arc.message.startswith("not certified: gouge failed")
    assert line_arc.figures["duration"] is not None


def _calls(names: set[str]) -> dict[str, set[str]]:
    """name -> the ccopt modules (paths relative to the repository) that call it."""
    import ast
    root = Path(__file__).resolve().parents[1]
    found: dict[str, set[str]] = {n: set() for n in names}
    for path in sorted((root / "ccopt").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
                if name in found:
                    found[name].add(str(path.relative_to(root)))
    return found


def test_settings_are_resolved_in_one_function_and_stages_ordered_in_one_pipeline():
    calls = _calls({"resolve_input", "Overrides", "default_style", "plan_feed"})
    # a job is resolved by resolve_input (ccopt.cases), from the command line's options
    # (cli.inputs), a sweep row (sweep.tasks) or the API's keywords (cases.make_job)
    assert calls["resolve_input"] == {"ccopt/cases.py", "ccopt/cli/inputs.py",
                                      "ccopt/sweep/tasks.py"}
    assert calls["Overrides"] == calls["resolve_input"]
    assert calls["default_style"] == {"ccopt/cases.py"}
    # no command, nor run nor the sweep, plans a job's feed by itself: the pipeline
    # does (and the comparison its variants' cycle times)
    assert calls["plan_feed"] == {"ccopt/pipeline.py", "ccopt/compare/timing.py"}


def test_the_tolerance_travels_in_the_job_to_every_verification(tmp_path, capsys):
    # LinuxCNC's straight joins at outside-break's shallow corners gouge by microns:
    # within a tolerance of 0.1 those are warnings, with 0 they fail (one more
    # violation is deeper than either and fails both ways)
    c = find_case("outside-break")
    prog = ccopt.read_program(c.program)
    path = ccopt.compensate(prog, "linuxcnc", radius=c.radius)
    strict = ccopt.verify(path, prog, radius=c.radius, tolerance=0.0)
    loose = ccopt.verify(path, prog, radius=c.radius, tolerance=0.1)
    assert len(strict.violations) > len(loose.violations) and loose.warnings
    want = (len(loose.violations), len(loose.warnings), 0.1)

    def seen(cert: dict):
        return len(cert["violations"]), len(cert["warnings"]), cert["tolerance"]

    assert main(["verify", "outside-break", "--style", "linuxcnc", "--tolerance", "0.1",
                 "--json"]) == 1
    assert seen(json.loads(capsys.readouterr().out)) == want
    row = _run_row(tmp_path, capsys, "outside-break", "--style", "linuxcnc", "--tolerance",
                   "0.1", "--no-compare", codes=(1,))
    assert seen(row["certificate"]) == want
    assert main(["compare", "outside-break", "--variants", "linuxcnc", "--tolerance", "0.1",
                 "--workers", "1", "--json"]) == 0
    (variant,) = json.loads(capsys.readouterr().out)["variants"]
    assert variant["violations"] == want[0] and variant["status"] == "uncertified"
    spec = load_spec({"programs": ["outside-break"], "tolerance": 0.1,
                      "axes": {"style": "linuxcnc"}})
    (task,) = expand(spec, resolve_programs(spec))
    assert task.job.tolerance == 0.1 and task.settings["tolerance"] == 0.1
    cert = ccopt.pipeline(task.job, program=prog).result().certificate
    assert seen(cert.to_json()) == want
