"""``ccopt verify PROGRAM --toolpath FILE.json``: any tool path in ccopt's
JSON schema certified against the program's contour (issue 16, build item 4).

Acceptance: on the JSON of every bundled case (what ``ccopt compensate
--json`` prints) it gives the same verdict as ``ccopt verify`` on the case;
a hand-edited JSON with one end point moved into the part fails; a bad file
is one located line ``FILE.json: message`` and exit 2.
"""
from __future__ import annotations

import json
import math

import pytest

import ccopt
from ccopt.cases import bundled_cases
from ccopt.cli import main
from ccopt.geometry import Arc, Spiral
from ccopt.toolpath_json import read_toolpath_json, toolpath_from_json

CASES = bundled_cases()


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def case_json(capsys, name: str, tmp_path) -> tuple[int, dict, object]:
    code, out, _ = run(capsys, "compensate", name, "--json")
    if code != 0:
        return code, {}, None
    f = tmp_path / f"{name}.json"
    f.write_text(out)
    return code, json.loads(out), f


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_same_verdict_as_verify_on_the_case(case, capsys, tmp_path):
    code, data, f = case_json(capsys, case.name, tmp_path)
    direct, out, _ = run(capsys, "verify", case.name, "--json")
    if code != 0:                       # the style refuses the program: nothing to read
        assert case.expect == "error" and direct == 2
        return
    via, out2, err = run(capsys, "verify", case.name, "--toolpath", str(f), "--json")
    assert (via, err) == (direct, "")
    a, b = json.loads(out), json.loads(out2)
    assert (a["ok"], a["geometry_ok"]) == (b["ok"], b["geometry_ok"])
    assert [c["ok"] for c in a["checks"]] == [c["ok"] for c in b["checks"]]
    assert len(a["violations"]) == len(b["violations"])
    if a["min_clearance"] is not None:
        assert b["min_clearance"] == pytest.approx(a["min_clearance"], abs=1e-12)
    # the file is read exactly: written again, it is the same path to rounding
    prog = ccopt.read_program(case.program)
    again = read_toolpath_json(f, prog).to_json()
    assert [s["kind"] for s in again["segments"]] == [s["kind"] for s in data["segments"]]
    for s, t in zip(again["segments"], data["segments"]):
        assert s["role"] == t["role"] and s["block"] == t["block"]
        assert math.dist(s["end"], t["end"]) <= 1e-12 * max(1.0, abs(max(t["end"], key=abs)))


def test_an_end_point_moved_into_the_part_fails(capsys, tmp_path):
    """leadin-outside-line: the contour move is line 7, (0,0) -> (20,0), cutter
    radius 2 on the left, so its compensated move runs (0,2) -> (20,2). Its end
    moved to (20,1) is 1 from the contour's end: a gouge of depth 2 - 1 = 1,
    and a gap of 1 to the lead-out that still starts at (20,2)."""
    _, data, f = case_json(capsys, "leadin-outside-line", tmp_path)
    seg = data["segments"][3]
    assert (seg["role"], seg["block"], seg["end"]) == ("compensated", 7, [20.0, 2.0])
    seg["end"] = [20.0, 1.0]
    f.write_text(json.dumps(data))
    code, out, err = run(capsys, "verify", "leadin-outside-line", "--toolpath", str(f), "--json")
    cert = json.loads(out)
    assert code == 1 and err == "" and not cert["ok"] and not cert["geometry_ok"]
    gouge = [v for v in cert["violations"] if v["kind"] == "gouge"]
    assert gouge and gouge[0]["depth"] == pytest.approx(1.0, abs=1e-12)
    assert gouge[0]["witness_tool"] == pytest.approx([20.0, 1.0])
    gap = [v for v in cert["violations"] if v["kind"] == "gap"]
    assert gap and gap[0]["depth"] == pytest.approx(1.0, abs=1e-12)


def test_exact_primitives_are_rebuilt():
    """An arc and a spiral from their centre, radii, start and sweep; a curve
    from its control points."""
    data = {"radius": 1.0, "segments": [
        {"kind": "arc", "start": [1.0, 0.0], "end": [0.0, 1.0], "role": "corner", "block": None,
         "center": [0.0, 0.0], "ccw": True, "sweep": math.pi / 2, "radius": 1.0},
        {"kind": "spiral", "start": [0.0, 1.0], "end": [-2.0, 0.0], "role": "lead-in",
         "block": None, "center": [0.0, 0.0], "ccw": True, "sweep": math.pi / 2,
         "radius": [1.0, 2.0], "feed": 10.0},
        {"kind": "curve", "start": [-2.0, 0.0], "end": [-2.0, -2.0], "role": "lead-out",
         "block": None, "control_points": [[-2.0, 0.0], [-2.5, -1.0], [-2.0, -2.0]],
         "degree": 2, "w": [0.0, -1.0]},
    ]}
    tp = toolpath_from_json(data, None, "t.json")
    arc, spiral, curve = (s.geom for s in tp.segments)
    assert isinstance(arc, Arc) and arc.length == pytest.approx(math.pi / 2, rel=1e-15)
    assert isinstance(spiral, Spiral) and (spiral.rho0, spiral.rho1) == (1.0, 2.0)
    assert tp.segments[1].feed == 10.0 and tp.segments[2].w1 == -1.0
    assert curve.control_points[1] == (-2.5, -1.0)


BAD = [
    ("[1, 2]", "t.json: a tool path must be a JSON object"),
    ('{"segments": {}}', "t.json: 'segments' must be a list"),
    ('{"segments": [{"kind": "helix"}]}', "t.json: segment 0: 'kind' must be one of"),
    ('{"segments": [{"kind": "line", "role": "cut"}]}', "segment 0: 'role' must be one of"),
    ('{"segments": [{"kind": "line", "role": "rapid", "start": [0], "end": [1, 1]}]}',
     "segment 0: 'start' must be two numbers"),
    ('{"segments": [{"kind": "line", "role": "rapid", "start": [0, NaN], "end": [1, 1]}]}',
     "segment 0: 'start' must be a finite number"),
    ('{"radius": -1, "segments": []}', "'radius' must be >= 0"),
    ('{"segments": [{"kind": "arc", "role": "corner", "start": [1, 0], "end": [0, 2], '
     '"center": [0, 0], "sweep": 1.5707963267948966, "radius": 1}]}',
     "segment 0: 'end' (0, 2) is not the arc's own end (6.123234e-17, 1): off by 1"),
    ('{"segments": [{"kind": "arc", "role": "corner", "start": [1, 0], "end": [0, 1], '
     '"center": [0, 0], "ccw": false, "sweep": 1.5707963267948966, "radius": 1}]}',
     "'ccw' False contradicts 'sweep'"),
    ('{"segments": [{"kind": "arc", "role": "corner", "start": [1, 0], "end": [1, 0], '
     '"center": [0, 0], "sweep": 0, "radius": 0}]}', "Arc radius must be finite and > 0"),
    ('{"segments": [{"kind": "line", "role": "rapid", "start": [0, 0], "end": [1, 1], '
     '"block": 999}]}', "'block' 999: the program has no move on line 999"),
    ('{"segments": [{"kind": "line", "role": "rapid", "start": [0, 0], "end": [1, 1], '
     '"feed": -3}]}', "'feed' must be > 0"),
    ('{"units": "inch", "segments": []}', "'units' inch differ from the program's (mm)"),
    ('{"segm', "t.json:1:2: not JSON: Unterminated string"),
]


@pytest.mark.parametrize("text,message", BAD, ids=[m[:30] for _, m in BAD])
def test_bad_file_is_one_located_line_and_exit_2(text, message, capsys, tmp_path):
    f = tmp_path / "t.json"
    f.write_text(text)
    code, out, err = run(capsys, "verify", "leadin-outside-line", "--toolpath", str(f))
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert err.startswith(str(f)) and message.replace("t.json", str(f)) in err, err


def test_missing_file_is_exit_2(capsys, tmp_path):
    code, _, err = run(capsys, "verify", "leadin-outside-line", "--toolpath",
                       str(tmp_path / "none.json"))
    assert code == 2 and err.startswith(str(tmp_path / "none.json") + ": cannot read")


def test_arc_end_edited_without_its_arc_is_refused(capsys, tmp_path):
    """pocket: segment 4 is the R3 arc of line 11 about (6,6) from (3,6) to
    (6,3); its end moved 0.5 into the part, to (6,3.5), is no longer on it."""
    _, data, f = case_json(capsys, "pocket", tmp_path)
    seg = data["segments"][4]
    assert seg["kind"] == "arc" and seg["center"] == pytest.approx([6.0, 6.0])
    seg["end"] = [6.0, 3.5]
    f.write_text(json.dumps(data))
    code, _, err = run(capsys, "verify", "pocket", "--toolpath", str(f))
    assert code == 2 and f"{f}: segment 4: 'end' (6, 3.5) is not the arc's own end" in err


def test_overrides_and_each_segments_side_and_radius_travel_in_the_json():
    # compensated on the right with r = 2.5 (the pocket is programmed CC1, r 3):
    # the file says so, per segment too, and verifying it read back without
    # being told gives the certificate of the path verified as made
    case = next(c for c in bundled_cases() if c.name == "pocket")
    prog = ccopt.read_program(case.program)
    path = ccopt.compensate(prog, "pmac", radius=2.5, side="right")
    data = json.loads(json.dumps(path.to_json()))
    assert data["overrides"] == {"radius": 2.5, "side": -1}
    on = [s for s in data["segments"] if s["role"] in ("compensated", "corner")]
    assert on and all(s["side"] == -1 and s["radius_in_force"] == 2.5 for s in on)
    assert all(s.get("surface") == "air" for s in data["segments"]
               if s["role"] in ("rapid", "lead-in", "lead-out", "uncompensated"))
    back = toolpath_from_json(data, prog)
    assert back.compensation == {"radius": 2.5, "side": -1}
    got, want = ccopt.verify(back, prog), ccopt.verify(path, prog, radius=2.5, side="right")
    assert got.verdict == want.verdict and got.radius == want.radius == 2.5
    for a, b in zip(got.checks, want.checks):   # figures up to the rebuild's rounding
        assert (a.name, a.ok, a.count, a.violations) == (b.name, b.ok, b.count, b.violations)
        assert a.figure == pytest.approx(b.figure, abs=1e-12)
    # a file without them (older, or another system's) is read and inferred as before
    del data["overrides"]
    assert toolpath_from_json(data, prog).compensation is None


@pytest.mark.parametrize("bad", [{"radius": -1, "side": None}, {"radius": None, "side": 2},
                                 "left", {"radius": None, "side": True}])
def test_bad_overrides_are_refused(bad):
    data = {"segments": [], "overrides": bad}
    with pytest.raises(ccopt.ProgramError, match="overrides"):
        toolpath_from_json(data, None)
