"""Canned cycles as LinuxCNC runs them (ccopt.program.gcode.cycles): every
expected move below is worked out by hand from ``interp_cycles.cc`` (the
``CYCLE_MACRO`` positioning, then the cycle's body), in mm, never taken from
ccopt's output. Each list is ``(kind, x, y, z)`` with kind ``R`` rapid, ``F``
feed, ``D`` dwell (then the seconds instead of x, y, z)."""
from __future__ import annotations

import pytest

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import NOTES, Motion
from cli_run import run_cli
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

_KIND = {Motion.RAPID: "R", Motion.LINE: "F", Motion.DWELL: "D"}


def moves(text: str, **kw):
    """The blocks of ``text`` after its first line's rapid to the start."""
    prog = read_gcode("G21 G17 F60\n" + text, "p.ngc", **kw)
    out = []
    for b in prog.blocks[1:]:
        if b.motion is Motion.DWELL:
            out.append(("D", b.dwell))
        else:
            out.append((_KIND[b.motion], *(round(c, 9) for c in b.end)))
    return out


def test_g81_g99_from_above_r():
    # start Z5 above R1: over the hole at Z5, down to R, feed to Z-2, back to R (G99)
    assert moves("G0 X0 Y0 Z5\nG81 X3 Y4 Z-2 R1\n") == [
        ("R", 3, 4, 5), ("R", 3, 4, 1), ("F", 3, 4, -2), ("R", 3, 4, 1)]


def test_g81_g98_returns_to_the_initial_level_for_every_hole():
    assert moves("G0 X0 Y0 Z5\nG98 G81 X3 Y4 Z-2 R1\nX6\n") == [
        ("R", 3, 4, 5), ("R", 3, 4, 1), ("F", 3, 4, -2), ("R", 3, 4, 5),
        ("R", 6, 4, 5), ("R", 6, 4, 1), ("F", 6, 4, -2), ("R", 6, 4, 5)]


def test_start_below_r_rises_to_r_first():
    # initial level 0 < R 2: straight up to R where it stands, then over the hole
    assert moves("G0 X0 Y0 Z0\nG98 G81 X1 Y0 Z-1 R2\n") == [
        ("R", 0, 0, 2), ("R", 1, 0, 2), ("F", 1, 0, -1), ("R", 1, 0, 2)]


def test_sticky_r_and_z_and_a_new_z():
    assert moves("G0 X0 Y0 Z5\nG81 X1 Y0 Z-1 R1\nX2\nY3 Z-2\nG80\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("R", 1, 0, 1),
        ("R", 2, 0, 1), ("F", 2, 0, -1), ("R", 2, 0, 1),
        ("R", 2, 3, 1), ("F", 2, 3, -2), ("R", 2, 3, 1)]


def test_g91_l_repeats_step_from_the_initial_level_and_l_is_not_sticky():
    # G91: R is 2 below the initial level 5 (Z3), the bottom 4 below R (Z-1);
    # X1 added at each of the 3 repeats; the next line (no L) drills once more
    assert moves("G0 X0 Y0 Z5\nG91 G98 G81 X1 Z-4 R-2 L3\nX1\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 3), ("F", 1, 0, -1), ("R", 1, 0, 5),
        ("R", 2, 0, 5), ("R", 2, 0, 3), ("F", 2, 0, -1), ("R", 2, 0, 5),
        ("R", 3, 0, 5), ("R", 3, 0, 3), ("F", 3, 0, -1), ("R", 3, 0, 5),
        ("R", 4, 0, 5), ("R", 4, 0, 3), ("F", 4, 0, -1), ("R", 4, 0, 5)]


def test_a_rapid_ends_the_series_and_the_next_cycle_takes_a_new_initial_level():
    got = moves("G0 X0 Y0 Z5\nG98 G81 X1 Z-1 R1\nG0 Z8\nG81 X2 Z-1 R1\n")
    assert got[-1] == ("R", 2, 0, 8)   # G98 back to the new initial level Z8


def test_g73_chip_break_pecks():
    # Q1 pecks from R1: to 0, -1, -2, each backing off D0.2, then the bottom -2.5
    assert moves("G0 X0 Y0 Z5\nG73 X1 Y1 Z-2.5 R1 Q1 D0.2\n") == [
        ("R", 1, 1, 5), ("R", 1, 1, 1),
        ("F", 1, 1, 0), ("R", 1, 1, 0.2), ("F", 1, 1, -1), ("R", 1, 1, -0.8),
        ("F", 1, 1, -2), ("R", 1, 1, -1.8), ("F", 1, 1, -2.5), ("R", 1, 1, 1)]


def test_g83_peck_clears_to_r_each_time_and_default_clearance_is_1_mm():
    assert moves("G0 X0 Y0 Z5\nG83 X1 Y1 Z-2.5 R1 Q1.5\n") == [
        ("R", 1, 1, 5), ("R", 1, 1, 1),
        ("F", 1, 1, -0.5), ("R", 1, 1, 1), ("R", 1, 1, 0.5),
        ("F", 1, 1, -2), ("R", 1, 1, 1), ("R", 1, 1, -1),
        ("F", 1, 1, -2.5), ("R", 1, 1, 1)]


def test_g82_dwells_and_p_is_sticky():
    got = moves("G0 X0 Y0 Z5\nG82 X1 Z-1 R1 P0.5\nX2\n")
    assert got == [("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("D", 0.5), ("R", 1, 0, 1),
                   ("R", 2, 0, 1), ("F", 2, 0, -1), ("D", 0.5), ("R", 2, 0, 1)]


def test_g85_feeds_out_to_r_and_g89_dwells_then_feeds_out():
    assert moves("G0 X0 Y0 Z5\nG98 G85 X1 Z-1 R1\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("F", 1, 0, 1), ("R", 1, 0, 5)]
    assert moves("G0 X0 Y0 Z5\nG98 G89 X1 Z-1 R1 P2\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("D", 2), ("F", 1, 0, 5)]


def test_tapping_and_boring_need_the_spindle():
    assert moves("G0 X0 Y0 Z5\nM4\nG74 X1 Z-1 R1\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("D", 0), ("F", 1, 0, 1)]
    assert moves("G0 X0 Y0 Z5\nS500 M3 G86 X1 Z-1 R1 P1\n") == [
        ("R", 1, 0, 5), ("R", 1, 0, 1), ("F", 1, 0, -1), ("D", 1), ("R", 1, 0, 1)]


def test_g87_back_bore():
    # in through the hole 1 off-centre (I-1) at R and down to the bottom -5,
    # over to the axis, bore up to K-3 and back, out the same way to G98's Z5
    assert moves("G0 X0 Y0 Z5\nM3\nG98 G87 X10 Y0 Z-5 R2 I-1 J0 K-3\n") == [
        ("R", 10, 0, 5), ("R", 10, 0, 2),
        ("R", 9, 0, 2), ("R", 9, 0, -5), ("R", 10, 0, -5), ("F", 10, 0, -3),
        ("F", 10, 0, -5), ("R", 9, 0, -5), ("R", 9, 0, 5), ("R", 10, 0, 5)]


def test_g18_drills_along_y_and_g19_along_x():
    assert moves("G0 X0 Y5 Z0\nG18 G81 Z1 X2 Y-1 R1\n") == [
        ("R", 2, 5, 1), ("R", 2, 1, 1), ("F", 2, -1, 1), ("R", 2, 1, 1)]
    assert moves("G0 X5 Y0 Z0\nG19 G81 Y1 Z2 X-1 R1\n") == [
        ("R", 5, 1, 2), ("R", 1, 1, 2), ("F", -1, 1, 2), ("R", 1, 1, 2)]


def test_g84_outside_g17_feeds_where_linuxcnc_feeds_and_says_so():
    # interp_cycles.cc:324 and :342 pass cycle_feed its (u, v, w) permuted: in
    # G18 ((u, v, w) = (Z, X, Y)) the feed goes to (v, w, u), in G19 ((Y, Z, X))
    # to (w, u, v). G18 hole Z1 X1, bottom Y-1, start Y2 under G98: the feed
    # to Z1 X-1 Y1 (not X1 Y-1 Z1), back to Z1 X2 Y1 (LinuxCNC's g84/g18/g98).
    text = "G0 X0 Y2 Z0\nM3 G18 G98 G84 X1 Z1 Y-1 R1\n"
    assert moves(text) == [("R", 1, 2, 1), ("R", 1, 1, 1), ("F", -1, 1, 1), ("D", 0),
                           ("F", 2, 1, 1)]
    # G19 hole Y1 Z1, bottom X-1, start X2: feed to X1 Y-1 Z1, back to X1 Y2 Z1
    text = "G0 X2 Y0 Z0\nM3 G19 G98 G84 Y1 Z1 X-1 R1\n"
    assert moves(text) == [("R", 2, 1, 1), ("R", 1, 1, 1), ("F", 1, -1, 1), ("D", 0),
                           ("F", 1, 2, 1)]
    prog = read_gcode("G21 F60\nG0 X0 Y2 Z0\nM3 G18 G84 X1 Z1 Y-1 R1\n", "p.ngc")
    assert prog.meta[NOTES] == [
        "p.ngc:3:8: G84 in the XZ plane feeds off the hole, as LinuxCNC does: it passes the "
        "axes permuted to its feed there (interp_cycles.cc:324, :342); use G17 to tap along Z"]


def test_cycle_in_a_work_offset_is_in_work_coordinates():
    # G55 at X100 Y50 Z-10 (parameters 5241-5243): the hole at work (1, 2), bottom Z-1
    params = {5241: 100.0, 5242: 50.0, 5243: -10.0}
    assert moves("G55 G0 X0 Y0 Z5\nG81 X1 Y2 Z-1 R1\n", parameters=params) == [
        ("R", 101, 52, -5), ("R", 101, 52, -9), ("F", 101, 52, -11), ("R", 101, 52, -9)]


def test_cycle_moves_carry_the_cycle_and_the_line():
    prog = read_gcode("G21 F60\nG0 X0 Y0 Z5\nG81 X1 Z-1 R1 M8\n", "p.ngc")
    cyc = prog.blocks[1:]
    assert {b.cycle for b in cyc} == {"G81"} and prog.blocks[0].cycle is None
    assert {(b.source.line, b.source.col) for b in cyc} == {(3, 1)}
    assert cyc[0].mcodes == (8,) and all(b.mcodes == () for b in cyc[1:])
    assert cyc[2].motion is Motion.LINE and cyc[2].feed == pytest.approx(1.0)  # F60 mm/min


@pytest.mark.parametrize("text, line, col, message", [
    ("G41.1 D2 G1 X1 Y1\nG81 X2 Z-1 R1\n", 3, 1,
     "Cannot use canned cycles with cutter compensation on"),
    ("G41.1 D2 G1 X1 Y1\nG98\n", 3, 1,
     "Cannot change retract mode with cutter radius compensation on"),
    ("G0 Z5\nG81 X1 Z-1\n", 3, 1, "R clearance plane unspecified in cycle"),
    ("G0 Z5\nG81 X1 R1\n", 3, 1, "Z value unspecified in xy plane canned cycle"),
    ("G0 Z5\nG81 X1 Z2 R1\n", 3, 1, "R less than z in cycle in xy plane"),
    ("G0 Z5\nG81 X1 Z-1 R1 L0\n", 3, 15, "Cannot do zero repeats of cycle"),
    ("G0 Z5\nG81 X1 Z-1 R1 L-2\n", 3, 15, "Negative l word used"),
    ("G0 Z5\nG82 X1 Z-1 R1\n", 3, 1, "Dwell time p word missing with g82"),
    ("G0 Z5\nG83 X1 Z-1 R1\n", 3, 1, "Q word missing with g83"),
    ("G0 Z5\nG73 X1 Z-1 R1 Q0\n", 3, 15, "Negative or zero q value used"),
    ("G0 Z5\nG87 X1 Z-1 R1 I1 J0\n", 3, 1, "K word missing with g87"),
    ("G0 Z5\nG84 X1 Z-1 R1\n", 3, 1, "Spindle not turning in G84"),
    ("G0 Z5\nM4\nG84 X1 Z-1 R1\n", 4, 1, "Spindle turning counterclockwise in G84"),
    ("G0 Z5\nG86 X1 Z-1 R1 P1\n", 3, 1, "Spindle not turning in g86"),
    ("G0 Z5\nM3 G88 X1 Z-1 R1 P1\n", 3, 4, "G88 is not supported"),
    ("G0 Z5\nG93 G81 X1 Z-1 R1\n", 3, 5, "Cannot use inverse time feed with canned cycles"),
    ("G0 Z5\nF0 G81 X1 Z-1 R1\n", 3, 4, "Cannot feed with zero feed rate"),
    ("G0 Z5\nG81 X1 Z-1 R1 Q1\n", 3, 15, "Q word with no G10, G64, G73, G83 or M19"),
])
def test_refusals_are_linuxcncs_and_located(text, line, col, message):
    with pytest.raises(ProgramError) as err:
        read_gcode("G21 F60\n" + text, "p.ngc")
    assert message in str(err.value)
    assert (err.value.line, err.value.col) == (line, col)


def test_cli_refuses_a_cycle_under_compensation_located_with_exit_2(tmp_path, capsys):
    p = tmp_path / "plate.ngc"
    p.write_text("G21 F600\nG0 X0 Y0 Z5\nG41.1 D6 G1 X10 Y0\nG1 Y10\n  G81 X5 Y5 Z-3 R2\nM30\n")
    code, out, err = run_cli(capsys, "show", str(p))
    assert code == 2
    assert err.strip().startswith(f"{p}:5:3: Cannot use canned cycles with cutter "
                                  "compensation on")
    assert "Traceback" not in err


def test_rigid_tapping_is_linuxcncs_rigid_tap_and_back():
    """LinuxCNC's g33.1 test: from (0, 0, 1), S1000 M3, `g33.1 z-1.2 k0.1` is
    canon's RIGID_TAP(0, 0, -1.2): a feed to Z-1.2 and back to Z1 along the
    same line, synchronised to the spindle at 0.1 per revolution x 1000 per
    minute = 100 per minute (100 / 60 per second)."""
    d = CONFORMANCE / "cycles" / "g33.1"
    prog = read_gcode((d / "g33.1.ngc").read_text(), "g33.1.ngc")
    tap = [b for b in prog.blocks if b.cycle == "G33.1"]
    assert [(b.start[2], b.end[2]) for b in tap] == [(1.0, -1.2), (-1.2, 1.0)]
    assert all(b.motion is Motion.LINE and b.feed == pytest.approx(0.1 * 1000 / 60) for b in tap)
    got = canonical_moves(compensate(prog, style="linuxcnc"))
    want = expected_moves("cycles/g33.1")
    assert [k for k, _ in got] == [k for k, _ in want] == ["STRAIGHT_TRAVERSE", "RIGID_TAP"]
    assert got[1][1] == pytest.approx(want[1][1], abs=TOL)


@pytest.mark.parametrize("text, message", [
    ("G0 Z1\nS1000 M3\nG33.1 Z-1\n", "pitch K > 0"),
    ("G0 Z1\nS1000\nG33.1 Z-1 K0.1\n", "spindle not turning"),
    ("G0 Z1\nM3\nG33.1 Z-1 K0.1\n", "spindle not turning"),
    ("G0 X0 Z1\nS1000 M3\nG41.1 D1\nG1 F100 X1\nG33.1 Z-1 K0.1\n", "compensation on"),
])
def test_rigid_tapping_refusals_are_located(text, message):
    with pytest.raises(ProgramError, match=message) as err:
        read_gcode(text + "M2\n", "tap.ngc")
    assert err.value.line == text.count("\n")
