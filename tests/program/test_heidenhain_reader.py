"""The HEIDENHAIN Klartext reader: every figure worked out here by hand
(trigonometry, tangency), never read back from the reader."""
from __future__ import annotations

import math

import pytest
from cli_run import run_cli

from ccopt.errors import ProgramError
from ccopt.program import dialect_of, read_program, read_text
from ccopt.program.model import Motion

TOL = 1e-9


def read(body: str, **kw):
    text = "0 BEGIN PGM T MM\n" + body + "\n99 END PGM T MM\n"
    return read_text(text, "t.h", "heidenhain", **kw)


def moves(prog):
    return [b for b in prog.blocks if b.motion.is_move]


def close(p, q, tol=TOL):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def test_suffix_and_dialect():
    assert dialect_of("part.h") == "heidenhain"
    prog = read("1 TOOL CALL 1 Z S1000\n2 L X+10 Y+5 R0 FMAX")
    assert prog.dialect == "heidenhain" and prog.units == "mm"
    b = moves(prog)[-1]
    assert b.motion is Motion.RAPID and close(b.end, (10, 5, 0))


def test_lines_incremental_feed_and_units():
    prog = read("1 L X+10 Y+0 R0 F600\n2 L IX+5 IY-2.5\n3 L Z-1 FMAX\n4 L X+Q1 Y-Q1")
    b = moves(prog)
    assert close(b[1].end, (15, -2.5, 0))
    assert b[0].feed == pytest.approx(10.0)          # 600 mm/min = 10 mm/s
    assert b[2].motion is Motion.RAPID and b[3].motion is Motion.LINE   # FMAX is blockwise
    assert close(b[3].end, (0, 0, -1))
    inch = read_text("0 BEGIN PGM T INCH\n1 L X+1 F100\n2 END PGM T INCH", "t.h", "heidenhain")
    assert inch.units == "inch" and moves(inch)[0].feed == pytest.approx(100 / 10 / 60)


def test_polar_cp_end_point_by_trigonometry():
    prog = read("1 L X+20 Y+5 R0 F100\n2 CC X+10 Y+5\n3 CP IPA+120 DR+\n"
                "4 LP PR+4 PA+30\n5 CP PA-90 DR-")
    b = moves(prog)
    a = math.radians(120)
    assert close(b[1].end, (10 + 10 * math.cos(a), 5 + 10 * math.sin(a), 0))
    assert b[1].motion is Motion.ARC_CCW and close(b[1].center, (10, 5, 0))
    assert close(b[2].end, (10 + 4 * math.cos(math.radians(30)), 5 + 2, 0))
    assert close(b[3].end, (10, 1, 0)) and b[3].motion is Motion.ARC_CW


def test_cp_full_turns_and_helix():
    prog = read("1 L X+5 Y+0 R0 F100\n2 CC X+0 Y+0\n3 CP IPA+720 IZ-2 DR+")
    b = moves(prog)[-1]
    assert close(b.end, (5, 0, -2), 1e-9) and b.turns == 1


def test_cc_in_x_z_selects_the_zx_plane():
    # A CAM ramp: from (155.3, z -3.6) a quarter turn about (x 156.7, z -3.6),
    # DR- and IPA-90 measured from +Z toward +X (the ZX plane, u = Z, v = X)
    prog = read("1 L X+155.3 Y-168.083 Z-3.6 R0 F400\n2 CC X+156.7 Z-3.6\n"
                "3 CP IPA-90 DR- F1206")
    b = moves(prog)[-1]
    assert b.modal.plane == "ZX" and b.motion is Motion.ARC_CW
    assert close(b.end, (156.7, -168.083, -5.0), 1e-9)


def test_cr_centre_short_and_long_arc():
    # chord (0,0)-(10,0), R 10: centre at (5, +-sqrt(75))
    h = math.sqrt(75)
    short = moves(read("1 L X+0 Y+0 R0 F100\n2 CR X+10 Y+0 R+10 DR+"))[-1]
    long_ = moves(read("1 L X+0 Y+0 R0 F100\n2 CR X+10 Y+0 R-10 DR+"))[-1]
    assert close(short.center, (5, h, 0)) and close(long_.center, (5, -h, 0))


def test_ct_tangent_arc_centre():
    # from (10,0) leaving along +X to (20,10): centre (10, rho) with
    # 10^2 + (10 - rho)^2 = rho^2, rho = 10
    b = moves(read("1 L X+0 Y+0 R0 F100\n2 L X+10\n3 CT X+20 Y+10"))[-1]
    assert close(b.center, (10, 10, 0)) and b.motion is Motion.ARC_CCW


def test_rnd_and_chf_between_lines():
    prog = read("1 L X+0 Y+0 R0 F100\n2 L X+10\n3 RND R2\n4 L Y+10\n5 CHF 3\n6 L X+0")
    b = moves(prog)
    # rounding a 90 degree left turn at (10,0): centre (8,2), tangent points (8,0) and (10,2)
    assert close(b[1].end, (8, 0, 0))
    assert b[2].motion is Motion.ARC_CCW and close(b[2].center, (8, 2, 0))
    assert close(b[2].end, (10, 2, 0))
    # chamfer 3 at (10,10): (10,7) -> (7,10)
    assert close(b[3].end, (10, 7, 0)) and close(b[4].end, (7, 10, 0))
    assert close(b[5].start, (7, 10, 0)) and close(b[5].end, (0, 10, 0))


def test_rnd_tangency_between_line_and_arc():
    # line along +X to (10,0), then clockwise about (20,0) up to (20,10): a
    # left turn of 90 degrees. The rounding circle of radius 1 lies above the
    # line (centre y = 1) and outside the circle of radius 10 (distance 11):
    # centre x = 20 - sqrt(11^2 - 1)
    prog = read("1 L X+0 Y+0 R0 F100\n2 L X+10\n3 RND R1\n4 CC X+20 Y+0\n5 C X+20 Y+10 DR-")
    b = moves(prog)
    fx = 20 - math.sqrt(120)
    assert close(b[2].center, (fx, 1, 0), 1e-9) and close(b[2].start, (fx, 0, 0), 1e-9)
    touch = (20 + (fx - 20) * 10 / 11, 10 / 11)
    assert close(b[2].end, (*touch, 0), 1e-9) and close(b[3].start, (*touch, 0), 1e-9)
    assert b[2].motion is Motion.ARC_CCW and b[3].motion is Motion.ARC_CW


def test_labels_repeat_and_subprogram_and_q():
    prog = read("1 Q1 = 2 * 3\n2 FN 1: Q2 = +Q1 + +4\n3 L X+0 Y+0 R0 F100\n"
                "4 LBL 1\n5 L IX+1\n6 CALL LBL 1 REP 2\n7 CALL LBL 5\n8 L X+Q2\n9 M30\n"
                "10 LBL 5\n11 L Y+7\n12 LBL 0")
    b = moves(prog)
    xs = [m.end[0] for m in b]
    assert xs[:4] == [0, 1, 2, 3]                   # the section runs 1 + 2 times
    assert close(b[4].end, (3, 7, 0)) and close(b[5].end, (10, 7, 0))


def test_fn_conditional_jump():
    prog = read("1 FN 0: Q1 = +0\n2 L X+0 Y+0 R0 F100\n3 LBL 2\n4 FN 1: Q1 = +Q1 + +1\n"
                "5 L X+Q1\n6 FN 12: IF +Q1 LT +3 GOTO LBL 2\n7 L Y+1")
    assert [m.end[0] for m in moves(prog)] == [0, 1, 2, 3, 3]


def test_tool_radius_from_tool_def_table_and_dr():
    prog = read("1 TOOL DEF 3 L+0 R+4\n2 TOOL CALL 3 Z S100 DR+0.5\n3 L X+0 Y+0 RL F100")
    assert moves(prog)[0].modal.radius == pytest.approx(4.5)
    prog = read("1 TOOL CALL 7 Z S100\n2 L X+0 Y+0 RL F100", tool_table={7: 6.0})
    assert moves(prog)[0].modal.radius == pytest.approx(3.0)


def test_cycle_32_recorded_and_drilling_with_pecks():
    prog = read("1 CYCL DEF 32.0 TOLERANCE\n2 CYCL DEF 32.1 T0.05\n"
                "3 CYCL DEF 200 DRILLING ~\n Q200=+2 ;SET-UP ~\n Q201=-3 ~\n Q206=+60 ~\n"
                " Q202=+1 ~\n Q203=+0 ~\n Q204=+10 ~\n Q211=+0.5\n"
                "4 L X+5 Y+5 Z+20 R0 FMAX M99")
    assert prog.meta["cycle32_tolerance"] == [{"line": 3, "tolerance": 0.05}]
    zs = [round(b.end[2], 9) for b in prog.blocks if b.cycle == "CYCL 200" and b.motion.is_move]
    # clearance 2; pecks to -1 and -2 with retracts; depth -3; back to 2, then 10
    assert zs == [2, -1, 2, 1, -2, 2, 0, -3, 2, 10]
    assert any(b.motion is Motion.DWELL and b.dwell == 0.5 for b in prog.blocks)


def test_m140_retracts_above_the_blank():
    prog = read("1 BLK FORM 0.1 Z X+0 Y+0 Z-10\n2 BLK FORM 0.2 X+10 Y+10 Z+0\n"
                "3 TOOL CALL 1 Z S100\n4 L M140 MB MAX")
    assert moves(prog)[-1].end[2] == pytest.approx(50.0)


def test_approach_paths_at_radius_zero():
    # first element from PA (10,0) along +X, tool left (RL): normal +Y
    def appr(words):
        prog = read(f"1 L X-20 Y+20 R0 F100\n2 APPR {words} RL\n3 L X+30 Y+0")
        return [b for b in moves(prog) if b.surface == "air"]
    lt = appr("LT X+10 Y+0 LEN5")
    assert close(lt[0].end, (5, 0, 0)) and close(lt[1].end, (10, 0, 0))
    ln = appr("LN X+10 Y+0 LEN5")
    assert close(ln[0].end, (10, 5, 0))
    ct = appr("CT X+10 Y+0 CCA90 R+5")
    assert close(ct[0].end, (5, 5, 0)) and close(ct[1].center, (10, 5, 0))
    assert ct[1].motion is Motion.ARC_CCW


@pytest.mark.parametrize("body, where, words", [
    ("1 CYCL DEF 251 RECTANGULAR POCKET", (2, 12), "pocket"),
    ("1 CYCL DEF 14.0 CONTOUR GEOMETRY", (2, 12), "SL contour"),
    ("1 FL X+10 Y+5", (2, 3), "FK free contour"),
    ("1 PLANE SPATIAL SPA+0", (2, 3), "PLANE"),
    ("1 L X+10 B+5 F100", (2, 10), "rotary"),
    ("1 L X+0 Y+0 R0 F100\n2 CR X+10 Y+0 R+2 DR+", (3, 3), "too small"),
    ("1 L X+0 Y+0 R0 F100\n2 CC X+5 Y+0\n3 C X+5 Y+7 DR+", (4, 3), "not an arc"),
    ("1 L X+0 Y+0 R0 F100\n2 L X+3\n3 RND R20\n4 L Y+3", (4, 3), "too large"),
    ("1 L X+0 Y+0 R0 F100\n2 CALL LBL 7", (3, 3), "not defined"),
    ("1 L X+0 Y+0 R0 F100 QQ", (2, 21), "QQ"),
    ("1 L X+1 Y+0 R0", (2, 3), "feed"),
    ("1 L X+1 Y+0 R0 F100 M120 LA2", (2, 21), "LOOK AHEAD"),
    ("1 L X+0 Y+1 R0 F100\n2 CC X+0 Y+0\n3 C X+1 Y+0 DR- RL", (4, 3), "straight line"),
])
def test_refusals_are_located(body, where, words):
    with pytest.raises(ProgramError) as info:
        read(body)
    err = info.value
    assert (err.line, err.col) == where and words in err.message


def test_unterminated_continuation_is_located():
    with pytest.raises(ProgramError) as info:
        read_text("0 BEGIN PGM T MM\n1 CYCL DEF 200 DRILLING ~", "t.h", "heidenhain")
    assert info.value.line == 2


def test_cli_refusal_exit_2(tmp_path, capsys):
    prog = tmp_path / "p.h"
    prog.write_text("0 BEGIN PGM P MM\n1 CYCL DEF 252 CIRCULAR POCKET\n2 END PGM P MM\n")
    code, _, err = run_cli(capsys, "verify", str(prog))
    assert code == 2 and "Traceback" not in err
    assert err.startswith(f"{prog}:2:12:")


def test_read_program_from_file(tmp_path):
    prog = tmp_path / "q.h"
    prog.write_text("0 BEGIN PGM Q MM\n1 L X+1 Y+2 R0 FMAX\n2 END PGM Q MM\n")
    p = read_program(prog)
    assert p.dialect == "heidenhain" and close(p.blocks[-1].end, (1, 2, 0))


def test_cam_parameter_forms():
    # as CAM posts write them: FN 0 with '=+value', feeds from Q parameters
    prog = read("1 FN 0: Q50 =+202 ; Cutting\n2 Q1=5\n3 QL3 = Q1 * 2 + SIN ( 90 )\n"
                "4 L X+QL3 Y-Q1 R0 FQ50")
    b = moves(prog)[-1]
    assert close(b.end, (11, -5, 0)) and b.feed == pytest.approx(202 / 60)


def test_rigid_tapping_and_fauto():
    prog = read("1 TOOL CALL 8 Z S2000 F300\n2 L X+0 Y+0 Z+20 R0 FMAX\n"
                "3 CYCL DEF 207 RIGID TAPPING ~\n Q200=+5 ~\n Q201=-10 ~\n Q239=+1.25 ~\n"
                " Q203=+0 ~\n Q204=+10\n4 L X+5 FMAX M99\n5 L X+9 FAUTO")
    cyc = [b for b in prog.blocks if b.cycle == "CYCL 207"]
    # 1.25 mm per turn at 2000 rev/min: 2500 mm/min down and back up
    assert [round(b.end[2], 9) for b in cyc] == [5, -10, 5, 10]
    assert cyc[1].feed == pytest.approx(2500 / 60) and cyc[2].feed == pytest.approx(2500 / 60)
    assert moves(prog)[-1].feed == pytest.approx(300 / 60)


def test_tnc_tool_table(tmp_path):
    table = tmp_path / "TOOL.T"
    table.write_text("BEGIN TOOL.T MM\nT    NAME      L      R      R2     DL     DR\n"
                     "0    NULLTOOL  +0     +0     +0     +0     +0\n"
                     "1    MILL_D10  +50    +5     +0     +0     -0.02\n[END]\n")
    prog = tmp_path / "p.h"
    prog.write_text("0 BEGIN PGM P MM\n1 TOOL CALL 1 Z S100 DR+0.5\n2 L X+0 Y+0 RL F100\n"
                    "3 END PGM P MM\n")
    # compensation value = R + DR(table) + DR(TOOL CALL) = 5 - 0.02 + 0.5
    b = read_program(prog, tool_table=table).blocks[0]
    assert b.modal.radius == pytest.approx(5.48)
    table.write_text("BEGIN TOOL.T MM\nT NAME L R\n1 X +50 +5a\n[END]\n")
    with pytest.raises(ProgramError) as info:
        read_program(prog, tool_table=table)
    assert info.value.line == 3 and "R of tool 1" in info.value.message


def test_polar_approach_and_departure_and_cycl_call_pos():
    prog = read("1 L X-20 Y+20 R0 F100\n2 CC X+0 Y+0\n3 APPR PLT PR+10 PA+0 LEN5 RL\n"
                "4 L X+30 Y+0\n5 DEP PLCT PR+40 PA+90 R5\n"
                "6 CYCL DEF 200 DRILLING ~\n Q200=+2 ~\n Q201=-3 ~\n Q206=+60 ~\n Q203=+0 ~\n"
                " Q204=+10\n7 L Z+20 R0 FMAX\n8 CYCL CALL POS X+50 Y+50 Z-4")
    air = [b for b in prog.blocks if b.surface == "air"]
    # PA polar (10, 0); PH 5 before it along +X; PN polar (0, 40)
    assert close(air[0].end, (5, 0, 0)) and close(air[1].end, (10, 0, 0))
    assert close(air[-1].end, (0, 40, 0))
    cyc = [b for b in prog.blocks if b.cycle == "CYCL 200"]
    # at (50, 50): the surface is Z-4 instead of Q203: clearance -2, depth -7
    assert close(cyc[0].start, (50, 50, 20)) and [b.end[2] for b in cyc] == [-2, -7, -2, 6]


@pytest.mark.parametrize("off, refused", [(1e-3, False), (2e-4, False), (4e-5, True),
                                          (1e-5, True)])
def test_a_ct_nearly_along_the_tangent_is_refused_past_the_coordinate_bound(off, refused):
    """``CT`` from (10, 0) leaving along +X to (20, off): the centre is
    (10, R) with R = |d|^2 / (2 off) (d = (10, off)): 5e4, 2.5e5, 1.25e6 and
    5e6. Past +-1e6, as the other readers bound a centre, the block is
    refused where it is written; within it, the arc is read."""
    text = ("BEGIN PGM C MM\nTOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z S1000\nL X+0 Y+0 R0 FMAX\n"
            f"L X+10 Y+0 F100\nCT X+20 Y+{off:.6f}\nEND PGM C MM\n")
    R = (100.0 + off * off) / (2.0 * off)
    assert refused == (R > 1e6)
    if refused:
        with pytest.raises(ProgramError) as info:
            read_text(text, "c.h", "heidenhain")
        assert (info.value.line, info.value.col) == (6, 1) and "centre" in str(info.value)
        return
    arc = read_text(text, "c.h", "heidenhain").blocks[-1]
    assert arc.motion is Motion.ARC_CCW
    assert arc.center[:2] == pytest.approx((10.0, R), rel=1e-12, abs=1e-9)
