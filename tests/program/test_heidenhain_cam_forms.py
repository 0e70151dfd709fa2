"""Klartext forms met in CAM output (the polymech-info/heidenhain-simulator
corpus of issue 32, written by a Fusion/HSM post): synthetic programs that
reproduce them, every figure worked out by hand."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program import read_text
from ccopt.program.model import Motion

TOL = 1e-9


def read(body: str):
    text = "0 BEGIN PGM T MM\n" + body + "\n99 END PGM T MM\n"
    return read_text(text, "t.h", "heidenhain")


def moves(prog):
    return [b for b in prog.blocks if b.motion.is_move]


def close(p, q, tol=TOL):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def zs_and_feeds(prog, tag):
    cyc = [b for b in prog.blocks if b.cycle == tag and b.motion.is_move]
    return ([round(b.end[2], 9) for b in cyc],
            [None if b.feed is None else round(b.feed * 60, 9) for b in cyc])


TAP = ("1 TOOL CALL 8 Z S1000\n2 L X+0 Y+0 Z+20 R0 FMAX\n"
       "3 CYCL DEF 209 TAPPING W/ CHIP BRKG ~\n Q200=+2 ;SET-UP CLEARANCE ~\n"
       " Q201=-10 ;DEPTH OF THREAD ~\n Q239=+1.5 ;THREAD PITCH ~\n"
       " Q203=+0 ;SURFACE COORDINATE ~\n Q204=+10 ;2ND SET-UP CLEARANCE ~\n"
       " Q257={q257} ;DEPTH FOR CHIP BRKNG ~\n Q256={q256} ;DIST FOR CHIP BRKNG ~\n"
       " Q336=+0 ;ANGLE OF SPINDLE ~\n Q403=+2 ;RPM FACTOR\n"
       "4 L X+5 FMAX M99")


def test_cycle_209_retracts_q256_pitches_after_each_infeed():
    prog = read(TAP.format(q257="+4", q256="+1"))
    zs, feeds = zs_and_feeds(prog, "CYCL 209")
    # pitch 1.5 at S1000: 1500 mm/min in and for the chip-breaking retracts
    # (1 pitch = 1.5 mm); infeeds of 4 below the surface: -4, -8; the rest
    # (2 < 4) goes to the depth -10; out of the hole at 2 x 1500 (Q403=2)
    assert zs == [2, -4, -2.5, -8, -6.5, -10, 2, 10]
    assert feeds == [None, 1500, 1500, 1500, 1500, 1500, 3000, None]


def test_cycle_209_q256_zero_retracts_out_of_the_hole():
    prog = read(TAP.format(q257="+6", q256="+0"))
    zs, feeds = zs_and_feeds(prog, "CYCL 209")
    # Q256=0: after the infeed to -6, out to the set-up clearance (at the
    # retraction feed) and back down to -6 at the pitch feed
    assert zs == [2, -6, 2, -6, -10, 2, 10]
    assert feeds == [None, 1500, 3000, 1500, 1500, 3000, None]


def test_cycle_209_without_chip_breaking_is_rigid_tapping():
    prog = read(TAP.format(q257="+0", q256="+1"))
    assert zs_and_feeds(prog, "CYCL 209") == ([2, -10, 2, 10], [None, 1500, 3000, None])


def test_cycle_209_needs_the_spindle_speed():
    body = TAP.format(q257="+4", q256="+1").replace(" S1000", "")
    with pytest.raises(ProgramError) as info:
        read(body)
    assert (info.value.line, info.value.col) == (14, 3) and "Q239" in info.value.message


def test_fn_without_blanks_and_q_parameter_in_a_cycle():
    # FN 0:Q1=1202 as some posts write it; FN 9 likewise; Q206=Q2
    prog = read("1 FN 0:Q1=1202 ; XY FEED RATE\n2 FN 0:Q2=600\n"
                "3 FN 9:IF +Q1 EQU +1202 GOTO LBL 5\n4 L X+9 R0 F100\n5 LBL 5\n"
                "6 L X+4 Y+0 Z+20 R0 FQ1\n"
                "7 CYCL DEF 200 DRILLING~\n Q200=2 ;SET-UP CLEARANCE~\n Q201=-5 ;DEPTH~\n"
                " Q206=Q2 ;FEED~\n Q202=5~\n Q203=+0~\n Q204=20\n8 L X+4 Y+0 R0 FMAX M99")
    b = moves(prog)
    assert close(b[0].end, (4, 0, 20)) and b[0].feed == pytest.approx(1202 / 60)
    assert zs_and_feeds(prog, "CYCL 200") == ([2, -5, 2, 20], [None, 600, None, None])


def test_cam_arcs_in_the_yz_plane_then_a_helix_in_xy():
    # CC with Y and Z only selects the YZ plane (u = Y, v = Z): from
    # (10, -2, 0) about (y 0, z 0) a quarter turn DR+ from 180 deg to 270 deg
    # ends at (10, 0, -2); then a two-turn helix about (10, 0) of radius 3
    # from (13, 0, -2) to z -4 ends where it started in the plane
    prog = read("1 L X+10 Y-2 Z+0 R0 F500\n2 CC Y+0 Z+0\n3 CP IPA+90 DR+\n"
                "4 L X+13 Y+0\n5 CC X+10 Y+0\n6 CP IPA+720 Z-4 DR+")
    b = moves(prog)
    assert b[1].modal.plane == "YZ" and b[1].motion is Motion.ARC_CCW
    assert close(b[1].end, (10, 0, -2)) and close(b[1].center, (10, 0, 0))
    assert b[-1].modal.plane == "XY" and close(b[-1].end, (13, 0, -4))
    assert b[-1].turns == 1 and close(b[-1].center, (10, 0, -2))


def test_touch_probe_block_over_continuation_lines_is_located():
    with pytest.raises(ProgramError) as info:
        read("1 TOOL CALL 100 Z S50\n2 L X+0 Y+0 R0 FMAX\n"
             "3 TCH PROBE 412 DATUM INSIDE CIRCLE ~\n    Q321=+0    ;CENTER IN 1ST AXIS ~\n"
             "    Q365=+1    ;TYPE OF TRAVERSE\n4 L Z+55 FMAX")
    assert (info.value.line, info.value.col) == (4, 3) and "touch probe" in info.value.message


def test_a_wrapped_comment_takes_its_continuation_lines():
    # a post wraps a long ';' comment with '~'; the next line is comment too
    prog = read("1 ;  description: This machine has YX axis on the Table and Z axis on the~\n"
                " Head\n2 * - a long operation name ~\n more of it\n3 L X+1 Y+2 R0 FMAX")
    b = moves(prog)
    assert len(b) == 1 and close(b[0].end, (1, 2, 0))


REAM = ("1 TOOL CALL 3 Z S1000 F150\n2 L X+0 Y+0 Z+20 R0 FMAX\n"
        "3 CYCL DEF 201 REAMING ~\n Q200=+2 ~\n Q201=-8 ~\n Q206=+120 ~\n Q211=+0 ~\n"
        " Q208= {q208} ;RETRACTION FEED RATE ~\n Q203=+0 ~\n Q204=+10\n4 L X+5 FMAX M99")


def test_retraction_feed_written_apart_max_and_auto():
    # 'Q208= MAX' (a post's spelling): the reamer leaves the hole at rapid;
    # 'Q208= AUTO': at the F150 of TOOL CALL; a number as before
    assert zs_and_feeds(read(REAM.format(q208="MAX")), "CYCL 201") == (
        [2, -8, 2, 10], [None, 120, None, None])
    assert zs_and_feeds(read(REAM.format(q208="AUTO")), "CYCL 201") == (
        [2, -8, 2, 10], [None, 120, 150, None])
    assert zs_and_feeds(read(REAM.format(q208="+600")), "CYCL 201") == (
        [2, -8, 2, 10], [None, 120, 600, None])


def test_rapid_is_refused_for_a_plunging_feed():
    body = REAM.format(q208="+600").replace("Q206=+120", "Q206= MAX")
    with pytest.raises(ProgramError) as info:
        read(body)
    assert (info.value.line, info.value.col) == (4, 2) and "Q208 only" in info.value.message


PRESET = ("1 LBL 1\n2 CYCL DEF 247 DATUM SETTING ~\n    Q339=+1    ;DATUM NUMBER\n"
          "3 LBL 0\n4 L X+5 Y+0 Z+20 R0 FMAX\n5 CALL LBL 1\n6 L X+6 R0 FMAX")


def test_cycle_247_one_preset_is_the_frame():
    # the post's pattern: the preset in a label run in line and called again
    prog = read(PRESET)
    assert prog.meta["cycle247_preset"] == [{"line": 3, "preset": 1}] * 2
    assert close(moves(prog)[-1].end, (6, 0, 20))


def test_cycle_247_another_preset_is_refused():
    with pytest.raises(ProgramError) as info:
        read(PRESET + "\n7 CYCL DEF 247 DATUM SETTING ~\n    Q339=+2    ;DATUM NUMBER")
    assert (info.value.line, info.value.col) == (9, 3)
    assert "preset 2 after preset 1 (line 3)" in info.value.message


def test_tool_call_with_an_axis_and_no_tool_number_keeps_the_tool():
    # the Autodesk posts' 'TOOL CALL Z' (before 'L M140 MB MAX'), and an axis-only
    # call later with a DR: the tool of the last numbered call stays (tool 7,
    # diameter 6 from the table, so radius 3; with DR+0.5 3.5), the axis sets the
    # working plane (Y: ZX, whose arcs turn about Y)
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL  Z ;SET TOOL AXIS FOR M140\n"
            "2 L M140 MB MAX\n3 TOOL CALL 7 Z S4000\n4 L X+0 Y+0 RL F100\n"
            "5 TOOL CALL Z DR+0.5\n6 L X+10 Y+0 RL F100\n7 L R0 Z+50 FMAX\n"
            "8 TOOL CALL Y S2000\n9 L X+20 R0 F100\n99 END PGM T MM\n")
    prog = read_text(text, "t.h", "heidenhain", tool_table={7: 6.0})
    m = moves(prog)
    # source lines count from the file's first line, the block numbers from 0
    radii = [b.modal.radius for b in m if b.source.line in (5, 7)]
    assert radii == [pytest.approx(3.0), pytest.approx(3.5)]
    assert [b.modal.plane for b in m if b.source.line == 10] == ["ZX"]
