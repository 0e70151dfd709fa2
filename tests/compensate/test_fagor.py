"""The ``fagor`` style: rules beyond the bundled cases, and its errors.

Expected figures are derived by hand (G41: ``o(t) = (-t_y, t_x)``, r = 2 from
``radius=``); never copied from ccopt's output.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt import cli
from ccopt.compensate import STYLES, compensate
from ccopt.compensate.fagor import linear_transition
from ccopt.program.gcode import read_gcode
from segment_expect import L, A, check

TOL = 1e-9
PI = math.pi
R = 2.0


def comp(text: str, **kw):
    kw.setdefault("radius", R)
    return compensate(read_gcode(text, "f.nc"), style="fagor", **kw)


def test_registered():
    assert "fagor" in STYLES


def test_linear_transition_construction():
    # +X then -Y (90 deg right) at P = 0, r = 2, left: A = (0,2), B = (2,0).
    # Tangent lines y = 2 and x = 2 meet at (2,2).
    pts = linear_transition((0, 2), (2, 0), (1, 0), (0, -1), 0.0, 2.0)
    assert np.allclose(pts, [(0, 2), (2, 2), (2, 0)])
    # 135 deg right: t_out = (-1,-1)/sqrt2, B = P + 2*o(t_out) = (sqrt2, -sqrt2)...
    h = 1 / math.sqrt(2)
    B = np.array([2 * h, -2 * h])
    pts = linear_transition((0, 2), B, (1, 0), (-h, -h), -h, 2.0)
    assert np.allclose(pts, [(0, 2), (2, 2), B - 2 * np.array([-h, -h]), B])


HEAD = "G90 G17 F600\nG0 X0 Y-20\nG41 D1\nG1 X0 Y0\n"     # activation along +Y


def test_inside_corners_at_start_and_end_behave_as_g138():
    # +Y then -X: a left turn, inside for G41: even with G139 the activation
    # ends at P + r*o(-X) = (0,-2). -X then lead-out -Y: left turn, inside: the
    # last move ends at (-20,0) + r*o(-X) = (-20,-2), then straight to (-20,-20).
    check(comp(HEAD.replace("F600", "F600 G139 G137") + "G1 X-20 Y0\nG40 G1 X-20 Y-20\n"), [
        L("lead-in", (0, -20), (0, -2)),
        L("compensated", (0, -2), (-20, -2)),
        L("lead-out", (-20, -2), (-20, -20)),
    ])


def test_compensated_corners_inside_and_outside():
    # +Y activation, then +X (right: outside, G139/G136: to (-2,0), arc about
    # (0,0) to (0,2)); +X then +Y at (10,0): left: inside: intersection of
    # y = 2 and x = 8 -> (8,2); +Y then +X at (10,10): right: outside G136 arc
    # about (10,10) from (8,10) to (10,12); cancellation -Y at (20,10): right
    # turn, outside, G139/G136: (20,12) arc to (22,10), then to (20,0).
    path = comp(HEAD + "G1 X10 Y0\nG1 X10 Y10\nG1 X20 Y10\nG40 G1 X20 Y0\n")
    check(path, [
        L("lead-in", (0, -20), (-2, 0)),
        A("corner", (0, 0), (-2, 0), (0, 2), -PI / 2),
        L("compensated", (0, 2), (8, 2)),
        L("compensated", (8, 2), (8, 10)),
        A("corner", (10, 10), (8, 10), (10, 12), -PI / 2),
        L("compensated", (10, 12), (20, 12)),
        A("corner", (20, 10), (20, 12), (22, 10), -PI / 2),
        L("lead-out", (22, 10), (20, 0)),
    ])


def test_g136_adds_an_arc_even_at_a_shallow_outside_corner():
    # +X then a right turn of atan(0.01): far below PMAC's break angle, Fagor
    # G136 still rounds it with an arc about the corner.
    path = comp("G90 F600\nG0 X-20 Y0\nG41 D1\nG1 X0 Y0\nG1 X20 Y0\nG1 X120 Y-1\n"
                "G40 G1 X120 Y-20\n")
    arcs = [s.to_json() for s in path.segments if s.role.value == "corner"]
    assert arcs[0]["center"] == pytest.approx([20, 0])
    assert arcs[0]["sweep"] == pytest.approx(-math.atan(0.01))


def test_g137_up_to_90_degrees_line_line_is_the_intersection():
    # +X then a 60-degree right turn, G137: the offsets y = 2 and the next
    # offset meet at (20 + 2*tan(30 deg), 2): no inserted segment.
    t = (math.cos(-PI / 3), math.sin(-PI / 3))
    q = (20 + 20 * t[0], 20 * t[1])
    path = comp(f"G90 F600 G137\nG0 X-20 Y0\nG41 D1\nG1 X0 Y0\nG1 X20 Y0\n"
                f"G1 X{q[0]:.12f} Y{q[1]:.12f}\nG40 G1 X{q[0]:.12f} Y-40\n")
    x = (20 + 2 * math.tan(PI / 6), 2)
    segs = [s for s in path.segments if s.role.value == "compensated"]
    assert segs[0].end == pytest.approx(x) and segs[1].start == pytest.approx(x)


def test_modal_of_the_outgoing_block_decides_the_transition():
    # G137 written on the block after the corner makes that corner linear;
    # the corner before it stays circular (G136 default).
    path = comp(HEAD + "G1 X10 Y0\nG1 X10 Y-10\nG137 G1 X0 Y-10\nG40 G1 X0 Y-30\n")
    kinds = [s.kind for s in path.segments if s.role.value == "corner"]
    # activation corner at (0,0) (outgoing block X10 Y0, G136 default): arc;
    # corner at (10,0) (outgoing X10 Y-10, still G136): arc; corner at
    # (10,-10) (outgoing block carries G137, 90 deg line-line): the tangent
    # lines' intersection (12,-12) is merged into both lines, no segment;
    # cancellation at (0,-10) turns left (inside): as G138, no transition.
    assert kinds == ["arc", "arc"]
    comp_lines = [s for s in path.segments if s.role.value == "compensated"]
    assert comp_lines[1].end == pytest.approx((12, -12))
    assert comp_lines[2].start == pytest.approx((12, -12))


def test_options_override_the_program():
    text = HEAD + "G1 X10 Y0\nG40 G1 X10 Y-20\n"
    direct = comp(text, start_end="direct")
    # activation straight to (0,2); cancellation from (10,2) straight to (10,-20)
    check(direct, [
        L("lead-in", (0, -20), (0, 2)),
        L("compensated", (0, 2), (10, 2)),
        L("lead-out", (10, 2), (10, -20)),
    ])
    linear = comp(text, corner="linear")
    # 90 degrees: tangent lines meet at (-2,2) (start) and (12,2) (end)
    check(linear, [
        L("lead-in", (0, -20), (-2, 0)),
        L("corner", (-2, 0), (-2, 2)),
        L("compensated", (-2, 2), (12, 2)),
        L("corner", (12, 2), (12, 0)),
        L("lead-out", (12, 0), (10, -20)),
    ])


def test_reversal_is_a_half_turn():
    # +X to (10,0) then straight back: a 180-degree outside corner: G136 half
    # arc about (10,0) from (10,2) clockwise to (10,-2).
    path = comp(HEAD + "G1 X10 Y0\nG1 X0 Y0\nG40 G1 X0 Y20\n")
    arcs = [s.to_json() for s in path.segments if s.role.value == "corner"]
    assert arcs[1]["center"] == pytest.approx([10, 0]) and arcs[1]["sweep"] == pytest.approx(-PI)
    assert arcs[1]["start"] == pytest.approx([10, 2]) and arcs[1]["end"] == pytest.approx([10, -2])


def test_z_only_cancellation_block_moves_to_the_programmed_point():
    # G40 on a Z-only move: cancelled in place; that block goes from the offset
    # end (10,2) to the programmed end (10,0) while Z goes to 5.
    path = comp(HEAD + "G1 X10 Y0\nG40 G1 Z5\nG2 X20 Y0 I5 J0\n")
    segs = [s for s in path.segments if s.role.value != "rapid"]
    out = segs[-2]
    assert out.role.value == "lead-out" and out.block.source.line == 6
    assert out.start == pytest.approx((10, 2)) and out.end == pytest.approx((10, 0))
    assert (out.w0, out.w1) == (0.0, 5.0)
    # the arc after it is uncompensated (an arc is fine once G40 is done)
    assert segs[-1].kind == "arc" and segs[-1].role.value == "uncompensated"


def test_radius_zero_is_the_programmed_path():
    path = comp(HEAD + "G1 X10 Y0\nG1 X10 Y-10\nG40 G1 X0 Y-20\n", radius=0.0)
    assert [(s.start, s.end) for s in path.segments if s.length > 0] == [
        ((0, 0), (0, -20)), ((0, -20), (0, 0)), ((0, 0), (10, 0)), ((10, 0), (10, -10)),
        ((10, -10), (0, -20))]


def test_program_end_while_on_returns_to_the_programmed_point():
    path = comp(HEAD + "G1 X10 Y0\n")
    last = path.segments[-1]
    assert last.role.value == "lead-out"
    assert last.start == pytest.approx((10, 2)) and last.end == pytest.approx((10, 0))


def test_gap_moves_run_after_the_transition():
    # Z move between two compensated moves at an outside corner: after the arc.
    path = comp(HEAD + "G1 X10 Y0\nG1 Z-1\nG1 X10 Y-10\nG40 G1 X0 Y-10\n")
    segs = [s for s in path.segments if s.role.value != "rapid"]
    i = next(i for i, s in enumerate(segs) if s.w1 == -1.0)
    assert segs[i - 1].role.value == "corner" and segs[i].start == pytest.approx((12, 0))


# -- errors: exit 2, one located line -----------------------------------------------
ERRORS = {
    "arc as the cancellation move": (
        HEAD + "G1 X10 Y0\nG40 G2 X20 Y0 I5 J0\n", 6,
        ["cancels cutter compensation", "must be linear", "not an arc"]),
    "arc as the activation move": (
        "G90 F600\nG0 X0 Y-20\nG41 D1\nG3 X0 Y0 I0 J10\nG1 X10 Y0\nG40 G1 X10 Y-10\n", 4,
        ["activates cutter compensation", "must be linear", "not an arc"]),
    "concave arc smaller than the tool": (
        HEAD + "G1 X10 Y0\nG3 X10 Y2 I0 J1\nG40 G1 X0 Y2\n", 6,
        ["concave arc radius 1", "cutter radius 2"]),
    "no radius at all": (
        HEAD + "G1 X10 Y0\nG40 G1 X10 Y-10\n", 4, ["no cutter radius"]),
}


@pytest.mark.parametrize("name", list(ERRORS))
def test_errors_exit_2_one_line(name, tmp_path, capsys):
    text, line, words = ERRORS[name]
    prog = tmp_path / "part.nc"
    prog.write_text(text)
    args = ["compensate", str(prog), "--style", "fagor"]
    if name != "no radius at all":
        args += ["--radius", "2"]
    rc = cli.main(args)
    err = capsys.readouterr().err
    assert rc == 2, f"{name}: exit {rc}, {err!r}"
    assert err.count("\n") == 1 and err.startswith(f"{prog}:{line}:"), err
    for w in words:
        assert w in err, f"{w!r} not in {err!r}"
