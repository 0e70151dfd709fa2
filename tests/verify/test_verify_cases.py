"""The verifier on the bundled cases: every verdict, and the failing figures
derived by hand from each program's geometry."""
from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import ccopt
from ccopt.cases import bundled_cases, find_case
from ccopt.cli import main
from ccopt.compensate import compensate
from ccopt.geometry import Line
from ccopt.toolpath import Role
from ccopt.verify import verify

EPS = 1e-6
CASES = [c for c in bundled_cases() if c.expect != "error"]


def run_case(name, **overrides):
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    path = compensate(prog, case.style, radius=case.radius, **overrides)
    return case, prog, path


def line_of(case, text: str, exact: bool = False) -> int:
    """Source line number of the first program line containing ``text`` (or,
    with ``exact``, whose code before any comment is ``text``)."""
    for i, line in enumerate(Path(case.program).read_text().splitlines(), 1):
        code = line.split(";")[0].strip()
        if (code == text) if exact else (text in code):
            return i
    raise AssertionError(f"{text!r} not in {case.program}")


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_every_case_verifies_with_its_expected_verdict(case):
    prog = ccopt.read_program(case.program)
    path = compensate(prog, case.style, radius=case.radius)
    cert = verify(path, prog, radius=case.radius)
    if case.expect == "ok":
        assert cert.ok, cert.summary()
        assert cert.violations == ()
        fig = cert.check("gouge").figure
        assert fig is None or fig >= -EPS
    else:
        assert case.expect == "gouge"
        assert not cert.ok
        assert not cert.check("gouge").ok
        assert cert.violations_of("gouge")


def test_short_move_overcut_gouge_depth_and_block():
    # CC1 (left), r = 2. First move (0,0)->(20,0): its offset is y = 2. The step
    # (20,0)->(20,1) goes +y: its left offset is the line x = 20 - 2 = 18, and the
    # inside corner with the first move puts its start at (18, 2). The next move
    # (20,1)->(40,1) turns right (outside for CC1): the step ends at its own
    # offset end point (20,1) + 2*(-1,0) = (18,1). So the tool centre runs down
    # to (18,1), whose distance to the first move's line y = 0 (foot (18,0),
    # inside 0..20) is 1: a gouge of r - 1 = 1 at the step's block.
    case, prog, path = run_case("short-move-overcut")
    cert = verify(path, prog)
    assert not cert.ok
    r = 2.0
    tool_centre = (18.0, 1.0)
    depth = r - tool_centre[1]
    gouges = cert.violations_of("gouge")
    step_line = line_of(case, "X20 Y1")
    first_line = line_of(case, "X20 Y0")
    at_step = [v for v in gouges if v.tool_block == step_line and v.tool_role == "compensated"]
    assert len(at_step) == 1
    v = at_step[0]
    assert v.depth == pytest.approx(depth, abs=1e-12)
    assert v.element_block == first_line
    assert v.witness_tool == pytest.approx(tool_centre, abs=1e-12)
    assert v.witness_contour == pytest.approx((18.0, 0.0), abs=1e-12)
    assert v.basis == "exact"
    # the corner arc about (20,1) starts at (18,1): the same depth, same blocks
    assert all(g.depth == pytest.approx(depth, abs=1e-12) for g in gouges)
    assert {g.element_block for g in gouges} == {first_line}
    assert cert.min_clearance == pytest.approx(1.0, abs=1e-12)
    assert cert.check("gouge").figure == pytest.approx(-depth, abs=1e-12)


def test_sidechange_reversal_crosses_the_first_move():
    # After the 180-degree arc about (20,0) the tool is at (20,-2); the gradual
    # change runs to the new-side end (10,0) + 2*(0,1) = (10,2). That line meets
    # y = 0 where 20 - 10*s = x, -2 + 4*s = 0: s = 1/2, x = 15, inside the first
    # move (0..20): distance 0, depth r = 2.
    case, prog, path = run_case("sidechange-reversal")
    cert = verify(path, prog)
    g = cert.violations_of("gouge")
    assert len(g) == 1
    assert g[0].depth == pytest.approx(2.0, abs=1e-12)
    assert g[0].witness_tool == pytest.approx((15.0, 0.0), abs=1e-12)
    assert g[0].element_block == line_of(case, "X20 Y0")
    assert g[0].tool_block == line_of(case, "X10 Y0")


def test_profile_spiral_lead_in_overcut():
    # The lead-in CIRCLE2 from (-10,5) to (0,15) about (-10,15) is a spiral from
    # radius 10 to 10 - 3 = 7 over a quarter turn: rho(phi) = 10 - 6 phi / pi,
    # point (-10 + rho sin(phi), 15 - rho cos(phi)) for phi in [0, pi/2]. The
    # closing edge is x = 0, y in [0, 15]; the point's distance to it is
    # 10 - rho sin(phi), smallest where d/dphi [rho sin(phi)] = 0.
    case, prog, path = run_case("profile")
    cert = verify(path, prog)

    def g(phi):
        return (10 - 6 * phi / math.pi) * math.sin(phi)

    phi = brentq(lambda f: -6 / math.pi * math.sin(f) + (10 - 6 * f / math.pi) * math.cos(f),
                 0.1, math.pi / 2)
    y = 15 - (10 - 6 * phi / math.pi) * math.cos(phi)
    assert 0 < y < 15
    depth = 3 - (10 - g(phi))
    lead_in = [v for v in cert.violations_of("gouge") if v.tool_role == "lead-in"]
    # against the closing edge, and against the loop's first edge x = 0,
    # y in [15, 25], which it joins at (0, 15): there the distance is to that
    # point, |P(phi) - (0, 15)|^2 = (10 - rho sin phi)^2 + (rho cos phi)^2
    assert len(lead_in) == 2
    v, w = sorted(lead_in, key=lambda v: -v.depth)
    rho = lambda f: 10 - 6 * f / math.pi          # noqa: E731
    near = minimize_scalar(lambda f: math.hypot(10 - rho(f) * math.sin(f), rho(f) * math.cos(f)),
                           bounds=(0.0, math.pi / 2), method="bounded", options={"xatol": 1e-12})
    assert w.element_block == line_of(case, "LINEAR X0 Y25", exact=True)
    assert 3 - near.fun - 1e-9 <= w.depth <= 3 - near.fun + 0.1 * EPS + 1e-9
    assert v.basis == "certified-bound"
    # a certified lower bound of the distance: the depth is at least the true
    # one and within the certified gap (0.1 eps) of it
    assert depth - 1e-12 <= v.depth <= depth + 0.1 * EPS + 1e-12
    assert v.element_block == line_of(case, "X0 Y15", exact=True)


def test_fagor_g138_activation_cuts_through_at_120_degrees():
    # Episode 2: G41 from (110,-17.320508) straight to P + r*o(t_next) = (100,2)
    # (the first move (100,0)->(120,0) runs +x, left normal (0,1)). The line
    # crosses y = 0 at x = 110 - 10 * 17.320508/19.320508, inside 100..120.
    case, prog, path = run_case("fagor-g136-g138")
    cert = verify(path, prog, radius=case.radius)
    x = 110 - 10 * 17.320508 / 19.320508
    assert 100 < x < 120
    hit = [v for v in cert.violations_of("gouge") if v.tool_role == "lead-in"
           and v.element_block == line_of(case, "G01 X120 Y0")]
    assert len(hit) == 1
    assert hit[0].depth == pytest.approx(2.0, abs=1e-12)
    assert hit[0].witness_tool == pytest.approx((x, 0.0), abs=1e-9)


def test_fagor_g139_activation_at_170_degrees_passes_under_the_element():
    # Episode 3: from S = (219.696155,-3.472964) to P = (200,0), then +x. G139
    # ends the activation at A = P + r*o(t_lead), o(t) = (-t_y, t_x) for G41.
    # The tool line S -> A reaches x = 200 (the start of the element's band,
    # beyond it the nearest point is the open end P) at height y(200): the
    # cutter then overlaps the element by r - |y(200)|.
    case, prog, path = run_case("fagor-g136-g139")
    cert = verify(path, prog, radius=case.radius)
    S = np.array([219.696155, -3.472964])
    P = np.array([200.0, 0.0])
    t = (P - S) / np.linalg.norm(P - S)
    A = P + 2.0 * np.array([-t[1], t[0]])
    f = (S[0] - 200.0) / (S[0] - A[0])
    y = S[1] + f * (A[1] - S[1])
    depth = 2.0 - abs(y)
    hit = [v for v in cert.violations_of("gouge") if v.tool_role == "lead-in"
           and v.element_block == line_of(case, "G01 X220 Y0")]
    assert len(hit) == 1
    assert hit[0].depth == pytest.approx(depth, abs=1e-9)
    assert hit[0].witness_tool == pytest.approx((200.0, y), abs=1e-9)


def test_wrong_side_fails_the_side_check():
    # The pocket is cut with CC1 (tool inside). Compensating it on the right
    # puts every fully compensated segment at distance r = 3 on the other side:
    # its signed offset is -3, not +3.
    case, prog, made = run_case("pocket", side="right")
    # a path that says it was made on the right is verified as made
    # (test_recorded_overrides_verify_as_given); one that does not (another
    # system's, or ccopt's with the record dropped) is held to the program
    path = replace(made, meta={})
    cert = verify(path, prog)
    side = cert.check("side")
    assert not side.ok
    assert side.figure == pytest.approx(-3.0, abs=1e-9)
    assert side.violations == side.count > 0
    assert all(v.detail["programmed_side"] == "left" for v in cert.violations_of("side"))
    # and the right path against a right-side program is fine again
    cert2 = verify(path, prog, side="right")
    assert cert2.check("side").ok and cert2.check("side").figure == pytest.approx(3.0, abs=1e-9)


def test_recorded_overrides_verify_as_given():
    # compensate(side=, radius=) records them on the path: verify without them
    # certifies the same path exactly as verify told them does
    prog = ccopt.read_program(find_case("pocket").program)
    path = compensate(prog, "pmac", side="right", radius=2.5)
    assert path.compensation == {"radius": 2.5, "side": -1}
    told = verify(path, prog, side="right", radius=2.5)
    recorded = verify(path, prog)
    assert recorded.to_json() == told.to_json()
    # on the right of the pocket's wall: at r = 2.5 on the side it was made
    assert recorded.check("side").ok
    assert recorded.check("side").figure == pytest.approx(2.5, abs=1e-9)


def test_contact_gap_where_the_tool_is_pulled_away():
    # Pocket, CC1, r = 3: the move "Y6" runs from (0,20) down to (0,6); its
    # tool segment is x = 3. Pulled 0.5 away from the wall (to x = 3.5) it no
    # longer touches it: a contact gap of 0.5 at that block, and jumps of 0.5
    # at both ends.
    case, prog, path = run_case("pocket")
    y6 = line_of(case, "Y6")
    idx = [i for i, s in enumerate(path.segments)
           if s.role is Role.COMPENSATED and s.block.source.line == y6]
    assert len(idx) == 1
    i = idx[0]
    seg = path.segments[i]
    assert seg.start[0] == pytest.approx(3.0) and seg.end[0] == pytest.approx(3.0)
    moved = Line((seg.start[0] + 0.5, seg.start[1]), (seg.end[0] + 0.5, seg.end[1]))
    segs = list(path.segments)
    segs[i] = replace(seg, geom=moved)
    cert = verify(replace(path, segments=tuple(segs)), prog)
    contact = cert.violations_of("contact")
    assert len(contact) == 1
    assert contact[0].tool_block == y6 and contact[0].tool_segment == i
    assert contact[0].depth == pytest.approx(0.5, abs=1e-12)
    gaps = cert.violations_of("gap")
    assert sorted(round(g.depth, 12) for g in gaps) == [0.5, 0.5]
    assert not cert.violations_of("gouge")


def test_radius_change_move_keeps_the_smaller_radius_and_no_contact():
    # CCR3 before "X40 Y0": the radius goes 2 -> 3 over that move, the tool from
    # (20,2) to (37,3). Its element needs clearance min(2, 3) = 2 and no contact.
    case, prog, path = run_case("radius-change")
    cert = verify(path, prog)
    assert cert.ok, cert.summary()
    C = cert.context.contour
    j = [q for q, b in enumerate(C.blocks) if b.source.line == line_of(case, "X40 Y0")][0]
    assert C.clearance[j] == 2.0 and C.radius[j] == 3.0 and not C.steady[j]


def test_certificate_json_schema():
    case, prog, path = run_case("short-move-overcut")
    data = json.loads(json.dumps(verify(path, prog).to_json()))
    assert set(data) >= {"ok", "min_clearance", "radius", "checks", "violations"}
    assert data["ok"] is False and data["radius"] == 2.0
    names = [c["name"] for c in data["checks"]]
    assert names == ["gouge", "contact", "side", "continuity", "limits"]
    for c in data["checks"]:
        assert c["basis"] in ("exact", "certified-bound", "sampled", "not-run")
        assert {"ok", "figure", "tolerance", "unit"} <= set(c)
    v = data["violations"][0]
    assert {"kind", "depth", "tool_segment", "tool_block", "element", "element_block",
            "witness_tool", "witness_contour", "basis"} <= set(v)


def test_cli_verify_exit_codes(capsys, tmp_path):
    assert main(["verify", "pocket"]) == 0
    out = capsys.readouterr().out
    assert "PASSED" in out
    assert main(["verify", "short-move-overcut", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["ok"] is False
    assert data["violations"][0]["kind"] == "gouge"
    assert main(["verify", str(tmp_path / "missing.pmc")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    with pytest.raises(SystemExit) as exc:
        main(["verify", "pocket", "--eps", "0"])
    assert exc.value.code == 2


def test_cli_verify_side_override_fails(capsys):
    # --side overrides both the compensation and the programmed side the path is
    # verified against, so the path is on the side it claims (the exit code
    # depends on what the lead-in does on that side, not asserted here)
    main(["verify", "leadin-inside-line", "--side", "right", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert [c for c in data["checks"] if c["name"] == "side"][0]["ok"] is True


def test_the_programmed_path_does_not_pass():
    # The uncompensated programmed path runs on the contour, its moves are not
    # compensated: no element is reached by a compensated tool segment.
    case, prog, path = run_case("pocket")
    cert = verify(ccopt.programmed_path(prog), prog)
    assert not cert.ok
    missing = [v for v in cert.violations_of("contact") if v.tool_segment is None]
    assert len(missing) == len(cert.context.contour) == 15
    assert all(v.depth == math.inf for v in missing)
    js = [v for v in cert.to_json()["violations"] if v["kind"] == "contact"]
    assert js and all(v["depth"] is None for v in js)          # JSON has no infinity


def test_empty_program_and_path():
    from ccopt.program.model import Program
    from ccopt.toolpath import ToolPath
    cert = verify(ToolPath(()), Program((), "<empty>", "pmac"))
    assert cert.ok and cert.min_clearance is None
    assert [c.figure for c in cert.checks] == [None, None, None, 0.0, None]


def test_linuxcnc_corner_arcs_are_checked_at_their_corner():
    # LinuxCNC attaches an outside-corner arc to the *outgoing* block (PMAC to
    # the incoming one). On the pocket, CC1 r = 3, the boss's corner where
    # "Y8" (0..8 at x = 25) meets "X35" is P = (25, 8): LinuxCNC's arc about it
    # is carried by "X35", whose own end (35, 8) is another corner. The clean
    # path passes. The arc (angles 180 -> 90 deg about P) moved by 0.25 along
    # its bisector (-1, 1)/sqrt2: |P - (c + 3u)| is largest, 3 + 0.25, at the
    # mid-sweep point u = (-1, 1)/sqrt2, so a contact gap of 0.25 at P,
    # reported at "Y8", the move ending there.
    case, prog, _ = run_case("pocket")
    path = compensate(prog, "linuxcnc")
    assert verify(path, prog).ok
    y8, x35 = line_of(case, "Y8"), line_of(case, "X35")
    idx = [i for i, s in enumerate(path.segments)
           if s.role is Role.CORNER and s.block.source.line == x35]
    assert len(idx) == 1
    i = idx[0]
    seg = path.segments[i]
    assert seg.geom.center == pytest.approx((25.0, 8.0), abs=1e-12)
    h = 0.25 / math.sqrt(2.0)
    shifted = replace(seg, geom=replace(seg.geom, center=(25.0 - h, 8.0 + h)))
    segs = list(path.segments)
    segs[i] = shifted
    cert = verify(replace(path, segments=tuple(segs)), prog)
    contact = cert.violations_of("contact")
    assert len(contact) == 1
    v = contact[0]
    assert v.tool_segment == i and v.tool_block == x35 and v.element_block == y8
    assert v.depth == pytest.approx(0.25, abs=1e-12)
    assert v.detail["corner_point"] == pytest.approx([25.0, 8.0], abs=1e-12)
    assert v.detail["corner_between_blocks"] == [y8, x35]


@pytest.mark.parametrize("name", ["leadin-inside-line", "leadin-outside-line", "pocket",
                                  "z-plunges"])
def test_linuxcnc_paths_of_clean_cases_verify(name):
    # Every tool position of these LinuxCNC paths is an offset at exactly r or
    # an arc of radius r about a programmed corner: nothing to report.
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    cert = verify(compensate(prog, "linuxcnc", radius=case.radius), prog)
    assert cert.ok, cert.summary()
    assert cert.violations == ()
