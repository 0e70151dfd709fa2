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

from text_mutations import mutate

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


def test_tool_number_without_a_tool_table_says_so(capsys, tmp_path):
    # "G41 D1" names tool 1; with no tool table its diameter is unknown
    prog = tmp_path / "tool.nc"
    prog.write_text("G21 G90 F600\nG41 D1\nG1 X10 Y0\nG1 X10 Y10\nG40\nG1 X20 Y10\n")
    code, _, err = run_cli(capsys, "compensate", str(prog))
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert err.startswith(f"{prog}:3:") and "tool 1" in err and "--tool-table" in err
    table = tmp_path / "tool.tbl"
    table.write_text("T1 P1 D4 ;4 mm end mill\n")
    code, out, err = run_cli(capsys, "compensate", str(prog), "--tool-table", str(table), "--json")
    assert code == 0, err
    assert json.loads(out)["radius"] == 2.0


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


def test_run_writes_report_and_exports(capsys, tmp_path):
    code, out, err = run_cli(capsys, "run", str(CASES / "pocket"), str(CASES / "short-move-overcut"),
                             "--out", str(tmp_path), "--json", "--no-compare")
    assert code == 0, err
    rows = json.loads(out)["cases"]
    assert [r["name"] for r in rows] == ["pocket", "short-move-overcut"]
    assert [r["status"] for r in rows] == ["ok", "gouge (expected)"]
    for name in ("pocket", "short-move-overcut"):
        for suffix in (".nc", ".pmc", ".svg", ".feed.csv", ".certificate.json", ".toolpath.json"):
            f = tmp_path / f"{name}{suffix}"
            assert f.is_file() and f.stat().st_size > 0, f
        cert = json.loads((tmp_path / f"{name}.certificate.json").read_text())
        assert cert["radius"] in (2, 3)
        # the exported G-code says how it was checked
        head = (tmp_path / f"{name}.nc").read_text().splitlines()[:6]
        assert any("read back with ccopt" in h for h in head)
        assert any("verified against the programmed contour" in h for h in head)
    index = (tmp_path / "index.html").read_text()
    for name in ("pocket", "short-move-overcut"):
        assert f'href="{name}.report.html"' in index        # the index opens each case's page
        page = (tmp_path / f"{name}.report.html").read_text()
        assert page.count("data:image/png;base64,") == 3   # three plots per case
    assert 'href="pocket.nc"' in (tmp_path / "pocket.report.html").read_text()
    assert json.loads((tmp_path / "summary.json").read_text())["cases"][0]["name"] == "pocket"



def test_run_out_short_option(capsys, tmp_path):
    # -o as for smooth, export and compare
    code, out, err = run_cli(capsys, "run", "leadin-inside-line", "-o", str(tmp_path / "r"),
                             "--no-compare")
    assert code == 0, err
    assert (tmp_path / "r" / "index.html").is_file()
    assert (tmp_path / "r" / "leadin-inside-line.nc").is_file()


def test_run_exit_codes(capsys, tmp_path):
    # an expected error is fine; an unexpected one is exit 2
    code, _, _ = run_cli(capsys, "run", str(CASES / "concave-arc-too-small"), "--out",
                         str(tmp_path), "--no-compare")
    assert code == 0
    # (the program beside the output folder, not in it: run -o DIR refuses to
    # start when DIR holds an input its files would replace, issue 29)
    (tmp_path / "in").mkdir()
    bad = tmp_path / "in" / "bad.pmc"
    bad.write_text("LINEAR ABS F10\nCCR5 CC1\nX10 Y0\nCIRCLE2 X10 Y2 I0 J1\nLINEAR X0 Y2\nCC0\nX0 Y0\n")
    code, _, err = run_cli(capsys, "run", str(bad), "--out", str(tmp_path), "--no-compare")
    assert code == 2 and "concave arc radius 1" in err


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


@pytest.mark.slow
def test_run_compares_with_the_case_radius(capsys, tmp_path):
    # The Fagor cases program "G41 D1" with no tool table: the radius (2) comes
    # from case.toml. The comparison must use it too, as compensation does,
    # not refuse the program for want of a radius.
    code, _, err = run_cli(capsys, "run", "fagor-g136-g139", "--out", str(tmp_path),
                           "--variants", "pmac,fagor-g139-g136", "--variants", "tangent-arc")
    assert code == 0, err
    row = json.loads((tmp_path / "summary.json").read_text())["cases"][0]
    assert row["radius"] == 2.0
    # compared, not refused: each path is built and certified; the case expects a
    # gouge (case.toml: expect = "gouge") and every variant's path has it, so no
    # row is ok (issue 29: a row is ok only when its path is certified)
    assert [(v["name"], v["status"]) for v in row["compare"]] == [
        ("pmac", "uncertified"), ("fagor-g139-g136", "uncertified"),
        ("tangent-arc", "uncertified")]
    assert all(v["message"].startswith("not certified: gouge failed") and
               v["duration"] is not None for v in row["compare"])


def test_run_rejects_unknown_variants(capsys, tmp_path):
    code, _, err = run_cli(capsys, "run", "pocket", "--out", str(tmp_path),
                           "--variants", "pmac,no-such-blend")
    assert code == 2
    assert err.startswith("--variants: unknown variant(s) no-such-blend; available: pmac")
    assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "index.html").exists()


@pytest.mark.parametrize("table, fragment", [
    ("tools.txt", "No such file"),           # a file name that does not exist
    ("T1 P1 D4", "No such file"),            # table text is not a file name
    (".", "Is a directory"),
])
def test_tool_table_argument_is_a_file(capsys, tmp_path, monkeypatch, table, fragment):
    monkeypatch.chdir(tmp_path)
    prog = tmp_path / "tool.nc"
    prog.write_text("G21 G90 F600\nG41 D1\nG1 X10 Y0\nG1 X10 Y10\nG40\nG1 X20 Y10\n")
    code, _, err = run_cli(capsys, "compensate", str(prog), "--tool-table", table)
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert err.startswith(f"{table}: cannot read tool table") and fragment in err


@pytest.mark.parametrize("argv, fragment", [
    (["--ccbuf=-1"], "--ccbuf: must be a whole number >= 0"),
    (["--ccbuf", "1.5"], "--ccbuf: not a whole number"),
    (["--break-cos", "1.5"], "--break-cos: must be a cosine"),
])
def test_pmac_options_are_checked(capsys, argv, fragment):
    with pytest.raises(SystemExit) as exc:          # argparse's own exit
        main(["compensate", "pocket", *argv])
    code, err = exc.value.code, capsys.readouterr().err
    assert code == 2 and fragment in err and len(err.strip().splitlines()) == 1


# -- property: mutations of valid programs give exit 0 or one located line -----------
_POCKET = {".pmc": (CASES / "pocket" / "pocket.pmc").read_text(),
           ".nc": (CASES / "pocket" / "pocket.nc").read_text()}
_TOKENS = ["X", "Y", "I", "J", "R", "F", "G2", "G41", "G40", "CC1", "CC0", "CCR", "CIRCLE1",
           "LINEAR", "[", "]", "(", ")", "#1", "P1=", "/", "0", "-", ".", "1e400", ";", "\n"]


@st.composite
def _mutated(draw):
    suffix = draw(st.sampled_from(sorted(_POCKET)))
    return suffix, mutate(draw, _POCKET[suffix], inserts=_TOKENS, replaces=_TOKENS,
                          edits=(1, 3), delete_max=6)


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=_mutated())
def test_show_on_mutated_programs(tmp_path, capsys, case):
    suffix, text = case
    prog = tmp_path / f"mutant{suffix}"
    prog.write_text(text, encoding="utf-8")
    code = main(["show", str(prog)])
    _, err = capsys.readouterr()
    assert code in (0, 2), err
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1, err
        # file:line[:col]: message, the line within the program
        head = lines[0][len(str(prog)):]
        assert lines[0].startswith(str(prog)) and head[0] == ":", err
        line_no = int(head[1:].split(":")[0])
        assert 1 <= line_no <= text.count("\n") + 1, err
        assert "Traceback" not in err and "internal error" not in err


#: The lead families (issue 33: on demand in the main job), named here as the
#: compare variants that search a parameter set each.
LEAD_FAMILIES = {"heidenhain-lt", "heidenhain-ln", "heidenhain-ct", "heidenhain-lct",
                 "siemens-norm", "siemens-kont", "siemens-g147", "siemens-g247",
                 "siemens-g347"}


#: The plug-in blend the main job runs on demand too (issue 33: the costliest
#: variant per lead; opt-casadi optimises the same leads).
ON_DEMAND = {"opt-cvxpy"}


def test_run_compares_all_but_the_lead_families_unless_asked(capsys, tmp_path):
    import json

    from ccopt.compare.registry import available
    code, _, _ = run_cli(capsys, "run", "leadin-inside-line", "--out", str(tmp_path / "a"),
                         "-q")
    assert code == 0
    row = json.loads((tmp_path / "a" / "summary.json").read_text())["cases"][0]
    names = [v["name"] for v in row["compare"]]
    assert names == [n for n in available() if n not in LEAD_FAMILIES | ON_DEMAND]
    # what was left out is said, in the summary and on the case's page
    assert set(row["not_compared"]) == (LEAD_FAMILIES | ON_DEMAND) & set(available())
    page = (tmp_path / "a" / "leadin-inside-line.report.html").read_text()
    assert "not compared in this run: " in page and "opt-cvxpy" in page
    assert {"pmac", "linuxcnc", "heidenhain", "siemens", "tangent-arc"} <= set(names)
    # `all` stands for every variant, wherever it is given
    from ccopt.cli.options import chosen_variants
    from argparse import Namespace
    assert chosen_variants(Namespace(variants=[["all"]])) == available()
    assert chosen_variants(Namespace(variants=[["pmac"], ["all"]])) == available()
    assert chosen_variants(Namespace(variants=None)) is None
