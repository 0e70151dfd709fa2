"""Hand-worked G-code programs: every figure is derived in the test, not read back."""
from __future__ import annotations

import math

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import MESSAGES, PLANE_AXES, Motion


def moves(text, **kw):
    return [b for b in read_gcode(text, **kw).blocks if b.motion.is_move]


def approx3(p, q, tol=1e-9):
    return all(math.isclose(a, b, abs_tol=tol) for a, b in zip(p, q))


def arc_point(block, fraction):
    """Point at ``fraction`` of the sweep, in the model's convention (CCW seen down w)."""
    (cu, cv), (u0, v0) = block.center_uv, block.start_uv
    (u1, v1) = block.end_uv
    a0 = math.atan2(v0 - cv, u0 - cu)
    a1 = math.atan2(v1 - cv, u1 - cu)
    ccw = block.motion is Motion.ARC_CCW
    d = (a1 - a0) if ccw else (a0 - a1)
    d %= 2 * math.pi
    if d <= 1e-12:
        d += 2 * math.pi
    d += 2 * math.pi * block.turns
    a = a0 + (d if ccw else -d) * fraction
    r = math.hypot(u0 - cu, v0 - cv)
    uvw = [0.0, 0.0, 0.0]
    i, j, k = PLANE_AXES[block.modal.plane]
    uvw[i] = cu + r * math.cos(a)
    uvw[j] = cv + r * math.sin(a)
    uvw[k] = block.start[k] + (block.end[k] - block.start[k]) * fraction
    return tuple(uvw), d


# -- lines, units, feed ----------------------------------------------------------
def test_rapid_and_line_basics():
    prog = read_gcode("G21 G90\nG0 X1 Y2 Z3\nG1 X4 F600\n", "part.ngc")
    rapid, line = prog.blocks
    assert prog.dialect == "gcode" and prog.file == "part.ngc" and prog.units == "mm"
    assert rapid.motion is Motion.RAPID and rapid.feed is None
    assert rapid.start == (0.0, 0.0, 0.0) and rapid.end == (1.0, 2.0, 3.0)
    assert line.motion is Motion.LINE and line.start == (1.0, 2.0, 3.0) and line.end == (4.0, 2.0, 3.0)
    assert line.feed == pytest.approx(10.0)  # F600 per minute = 10 per second
    assert (line.source.file, line.source.line, line.source.col) == ("part.ngc", 3, 1)


def test_start_position_is_used():
    prog = read_gcode("G91 G1 X1 F60", start=(10, 20, 30))
    assert prog.start == (10.0, 20.0, 30.0)
    assert prog.blocks[0].start == (10.0, 20.0, 30.0) and prog.blocks[0].end == (11.0, 20.0, 30.0)


def test_incremental_moves():
    b = moves("G91 G1 X1 Y1 F60\nX1 Y1\nZ-2\nG90 X0\n")
    assert [m.end for m in b] == [(1, 1, 0), (2, 2, 0), (2, 2, -2), (0, 2, -2)]
    assert all(m.feed == pytest.approx(1.0) for m in b)


def test_inch_units_and_feed():
    prog = read_gcode("G20\nG1 X1 F60\n")
    assert prog.units == "inch" and prog.blocks[0].modal.units == "inch"
    assert prog.blocks[0].feed == pytest.approx(1.0)  # 60 in/min = 1 in/s


def test_units_may_repeat_but_not_change_after_a_move():
    assert read_gcode("G21\nG1 X1 F1\nG21\nG1 X2\n").units == "mm"


def test_inverse_time_feed_line_and_arc():
    b = moves("G93 G1 X3 Y4 F2\nG2 X3 Y4 I5 J0 F1\nG3 X3 Y4 Z3 I5 P2 F1\n")
    # 5 mm in 60/2 = 30 s
    assert b[0].feed == pytest.approx(5.0 / 30.0)
    # full circle of radius 5 in 60 s
    assert b[1].end == b[1].start and b[1].center == (8.0, 4.0, 0.0)
    assert b[1].feed == pytest.approx(2 * math.pi * 5 / 60.0)
    # helix: two full turns (P2) of radius 5 rising 3, in 60 s
    assert b[2].turns == 1
    assert b[2].feed == pytest.approx(math.hypot(2 * 2 * math.pi * 5, 3.0) / 60.0)


def test_inverse_time_quarter_arc_length():
    # quarter circle radius 2 from (2,0) to (0,2) about the origin, CCW; F0.5 -> 120 s
    b = moves("G0 X2\nG93 G3 X0 Y2 I-2 J0 F0.5")
    assert b[1].feed == pytest.approx((math.pi / 2 * 2) / 120.0)


def test_feed_is_modal_and_reset_when_mode_switches():
    b = moves("F120\nG1 X1\nX2 F240\nX3\n")
    assert [m.feed for m in b] == pytest.approx([2.0, 4.0, 4.0])


def test_spaces_inside_words_and_comments():
    b = moves("G 1 X 1 0 Y-2 . 5 F 6 0 (a comment) ; rest is ignored\n  g1x3\n")
    assert b[0].end == (10.0, -2.5, 0.0) and b[0].feed == pytest.approx(1.0)
    assert b[1].end == (3.0, -2.5, 0.0)
    assert b[1].source.col == 3


def test_line_numbers_program_number_percent_and_mcodes():
    text = "%\nO1234 (PART)\nN10 G1 X1 F60 M3 M8\nN20 M5\n%\nthis is never read\n"
    prog = read_gcode(text)
    assert len(prog.blocks) == 1
    b = prog.blocks[0]
    assert b.mcodes == (3, 8) and b.source.line == 3 and b.source.col == 1
    assert prog.meta["program_number"] == 1234


def test_program_end_stops_execution():
    b = moves("G1 X1 F60\nM2\nG1 X5\nthis would be an error\n")
    assert [m.end for m in b] == [(1, 0, 0)]
    b = moves("o1 sub\nG1 X2 M30\nG1 X9\no1 endsub\nG1 X1 F60\no1 call\nG1 X5\n")
    assert [m.end for m in b] == [(1, 0, 0), (2, 0, 0)] and b[1].mcodes == (30,)


def test_dwell_block():
    prog = read_gcode("G1 X1 F60\nG4 P1.5\n")
    dwell = prog.blocks[1]
    assert dwell.motion is Motion.DWELL and dwell.dwell == 1.5
    assert dwell.start == dwell.end == (1.0, 0.0, 0.0) and dwell.feed is None


def test_dwell_runs_before_motion_on_the_same_line():
    prog = read_gcode("G1 F60\nG4 P2 X5\n")
    assert [b.motion for b in prog.blocks] == [Motion.DWELL, Motion.LINE]
    assert prog.blocks[1].end == (5.0, 0.0, 0.0)


def test_mode_only_lines_make_no_block():
    text = "G1 F100\nG0\nG17 G21 G40 G49 G80 G54 G64 P0.01 Q0.01 G90 G94\nG61\nG61.1 S1000 M3\n"
    assert read_gcode(text).blocks == ()


def test_zero_length_move_with_axis_words_is_kept():
    b = moves("G1 X1 F60\nX1\n")
    assert len(b) == 2 and b[1].start == b[1].end


def test_g43_recorded_without_moving_the_plane():
    prog = read_gcode("T2 M6\nG43 H2\nG1 X1 Z-1 F60\nG49\n")
    assert prog.meta["tool_length"] == [(2, "G43", 2.0), (4, "G49", None)]
    assert prog.blocks[0].end == (1.0, 0.0, -1.0)


# -- arcs ------------------------------------------------------------------------
def test_r_arc_short_and_long():
    # chord (0,0)->(10,0), R10: the centre is on the perpendicular bisector x=5
    # at sqrt(10^2 - 5^2) = 8.660254 from the chord.
    h = math.sqrt(100 - 25)
    cw_short, = moves("G2 X10 Y0 R10 F60")
    # clockwise <= 180 deg: the centre lies right of the travel direction (+X): below
    assert approx3(cw_short.center, (5.0, -h, 0.0))
    mid, sweep = arc_point(cw_short, 0.5)
    assert sweep == pytest.approx(math.radians(60))     # 2*asin(5/10)
    assert approx3(mid, (5.0, 10 - h, 0.0))             # bulges up, 10 from the centre
    cw_long, = moves("G2 X10 Y0 R-10 F60")
    assert approx3(cw_long.center, (5.0, h, 0.0))
    mid, sweep = arc_point(cw_long, 0.5)
    assert sweep == pytest.approx(math.radians(300))
    assert approx3(mid, (5.0, h + 10, 0.0))             # goes round over the top
    ccw_short, = moves("G3 X10 Y0 R10 F60")
    assert approx3(ccw_short.center, (5.0, h, 0.0)) and ccw_short.motion is Motion.ARC_CCW
    assert arc_point(ccw_short, 0.5)[1] == pytest.approx(math.radians(60))


def test_r_arc_semicircle_and_rounding_tolerance():
    semi, = moves("G2 X10 R5 F60")
    assert approx3(semi.center, (5.0, 0.0, 0.0))
    # R a hair smaller than half the chord (within 0.002 mm) is a semicircle
    semi2, = moves("G3 X10 R4.999 F60")
    assert approx3(semi2.center, (5.0, 0.0, 0.0))


def test_ijk_arc_and_full_circle():
    arc, circle = moves("G0 X10\nG3 X0 Y10 I-10 J0 F60\nG2 I0 J-10\n")[1:]
    assert arc.motion is Motion.ARC_CCW and arc.center == (0.0, 0.0, 0.0)
    assert arc.feed == pytest.approx(1.0)
    assert arc_point(arc, 0.5)[0] == pytest.approx((10 / math.sqrt(2), 10 / math.sqrt(2), 0.0))
    # "G2 I0 J-10" with no axis word: a full clockwise circle about (0, 0)
    assert circle.start == circle.end == (0.0, 10.0, 0.0) and circle.center == (0.0, 0.0, 0.0)
    assert circle.motion is Motion.ARC_CW and circle.turns == 0
    assert arc_point(circle, 0.25)[0] == pytest.approx((10.0, 0.0, 0.0))


def test_arc_turns_and_helix():
    b, = moves("G3 X0 Y0 Z-2 I5 P3 F60")
    assert b.turns == 2 and b.end == (0.0, 0.0, -2.0) and b.center == (5.0, 0.0, 0.0)


def test_g18_arc_plane_zx():
    # G18: (u, v) = (Z, X), normal Y, centre words K (Z) and I (X).
    b, = moves("G18 G2 X10 Z0 I5 K0 F60")
    assert b.modal.plane == "ZX" and b.motion is Motion.ARC_CW
    assert b.center == (5.0, 0.0, 0.0)
    assert b.start_uv == (0.0, 0.0) and b.center_uv == (0.0, 5.0) and b.end_uv == (0.0, 10.0)
    # Seen from +Y (Z to the right, X up) clockwise from x=0 to x=10 about x=5
    # passes through z = -5 at x = 5: LinuxCNC's "clockwise seen from +Y".
    assert arc_point(b, 0.5)[0] == pytest.approx((5.0, 0.0, -5.0))
    c, = moves("G18 G3 X10 Z0 R5 F60")
    assert approx3(c.center, (5.0, 0.0, 0.0)) and c.motion is Motion.ARC_CCW
    assert arc_point(c, 0.5)[0] == pytest.approx((5.0, 0.0, 5.0))


def test_g19_arc_plane_yz_with_helix_on_x():
    # G19: (u, v) = (Y, Z), normal X, centre words J (Y) and K (Z).
    b, = moves("G19 G3 Y10 Z0 X4 J5 K0 F60")
    assert b.modal.plane == "YZ" and b.motion is Motion.ARC_CCW
    assert b.center == (0.0, 5.0, 0.0)
    # CCW seen from +X (Y right, Z up) from y=0 to y=10 about y=5 goes under: z=-5
    mid = arc_point(b, 0.5)[0]
    assert mid == pytest.approx((2.0, 5.0, -5.0))


def test_arc_absolute_centre_mode():
    b = moves("G0 X10\nG90.1 G3 X0 Y10 I0 J0 F60\nG91.1 G3 X-10 Y0 I0 J-10\n")
    assert b[1].center == (0.0, 0.0, 0.0) and b[2].center == (0.0, 0.0, 0.0)


def test_arc_radius_tolerance_absolute_or_relative():
    # r0 = 10, r1 = 10.0015: 0.0015 <= 0.002 mm absolute
    assert len(moves("G0 X10\nG3 X0 Y10.0015 I-10 F60")) == 2
    # r0 = 100, r1 = 100.05: 0.05 > 0.002 but 0.05/100.05 < 0.1 % relative
    assert len(moves("G0 X100\nG3 X0 Y100.05 I-100 F60")) == 2


def test_arc_radius_tolerance_scales_with_inch():
    # r0 = 0.05, r1 = 0.0501: 0.0001 apart, 0.2 % relative.
    text = "G0 X0.05\nG3 X0 Y0.0501 I-0.05 F60\n"
    # mm: 0.0001 mm is within the 0.002 mm absolute tolerance
    assert len(moves("G21\n" + text)) == 2
    # inch: 0.0001 in exceeds 0.002/25.4 = 0.0000787 in and the 0.1 % relative tolerance
    with pytest.raises(ProgramError, match="inconsistent arc radii"):
        read_gcode("G20\n" + text)


# -- parameters and expressions ---------------------------------------------------
def test_parameter_settings_take_effect_after_the_line():
    b = moves("#1=5\n#1=7 #2=#1 G1 X#1 Y#2 F60\nG1 X#1 Y#2\n")
    assert b[0].end == (5.0, 0.0, 0.0)   # X reads the old #1, Y the old (unset) #2
    assert b[1].end == (7.0, 5.0, 0.0)   # #2 got the old #1


def test_unset_numbered_parameter_reads_zero_and_named_parameters():
    b = moves("#<depth> = -1.5\n#<_feed> = 120\nG1 X#99 Z#<depth> F#<_feed>\n")
    assert b[0].end == (0.0, 0.0, -1.5) and b[0].feed == pytest.approx(2.0)


def test_expressions_and_functions():
    b = moves("G1 X[1+2*3] Y[2**3] Z[7 MOD 3] F60\n"
              "G1 X[ATAN[1]/[1]] Y[SIN[30]*4] Z[SQRT[16] - ABS[-2]]\n"
              "G1 X[FIX[2.7]] Y[FUP[2.1]] Z[ROUND[2.5]]\n"
              "G1 X[1 GT 0] Y[[2 EQ 3] OR [1 LT 2]] Z-SIN[90]\n"
              "#3=2\nG1 X#[1+2] Y##3 Z-#3\n")
    assert b[0].end == pytest.approx((7.0, 8.0, 1.0))
    assert b[1].end == pytest.approx((45.0, 2.0, 2.0))
    assert b[2].end == pytest.approx((2.0, 3.0, 3.0))
    assert b[3].end == pytest.approx((1.0, 1.0, -1.0))
    # #[1+2] is #3 = 2; ##3 is #[#3] = #2 = 0
    assert b[4].end == pytest.approx((2.0, 0.0, -2.0))


# -- O-words ----------------------------------------------------------------------
def test_sub_call_arguments_are_local_and_restored():
    text = """#1 = 42
o100 sub
  G1 X#1 Y#2 Z#3 F60
  #1 = 99
o100 endsub
o100 call [1] [2]
G1 X#1
"""
    b = moves(text)
    assert b[0].end == (1.0, 2.0, 0.0)      # #3 not passed: 0
    assert b[0].source.line == 3 and b[0].source.col == 3
    assert b[1].end == (42.0, 2.0, 0.0)     # caller's #1 restored after the call


def test_sub_defined_after_the_call_and_named_subs():
    b = moves("G1 F60\no<square> call [2]\nM2\no<square> sub\nG91 X#1\nY#1\nX-#1\nY-#1\nG90\no<square> endsub\n")
    assert [m.end for m in b] == [(2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 0)]
    assert [m.source.line for m in b] == [5, 6, 7, 8]


def test_return_value_and_return_from_inside_a_loop():
    text = """o<twice> sub
  o1 while [1]
    o<twice> return [#1 * 2]
  o1 endwhile
o<twice> endsub
o<twice> call [21]
G1 X#<_value> Y#<_value_returned> F60
"""
    b, = moves(text)
    assert b.end == (42.0, 1.0, 0.0)


def test_named_locals_are_per_subroutine_globals_are_shared():
    text = """#<x> = 5
#<_g> = 1
o1 sub
  #<x> = 7
  #<_g> = 3
o1 endsub
o1 call
G1 X#<x> Y#<_g> F60
"""
    b, = moves(text)
    assert b.end == (5.0, 3.0, 0.0)


def test_if_elseif_else():
    text = """o1 sub
  o2 if [#1 LT 0]
    G1 X-1 F60
  o2 elseif [#1 EQ 0]
    G1 X0 F60
  o2 elseif [#1 LT 10]
    G1 X5 F60
  o2 else
    G1 X10 F60
  o2 endif
o1 endsub
o1 call [-3]
o1 call [0]
o1 call [7]
o1 call [70]
"""
    assert [m.end[0] for m in moves(text)] == [-1.0, 0.0, 5.0, 10.0]


def test_while_endwhile_break_continue():
    text = """#1 = 0
F60
o1 while [#1 LT 10]
  #1 = [#1 + 1]
  o2 if [#1 EQ 3]
    o1 continue
  o2 endif
  o3 if [#1 GT 5]
    o1 break
  o3 endif
  G1 X#1
o1 endwhile
G1 Y1
"""
    assert [m.end for m in moves(text)] == [(1, 0, 0), (2, 0, 0), (4, 0, 0), (5, 0, 0), (5, 1, 0)]


def test_do_while_runs_at_least_once_and_continue_tests_condition():
    text = """#1 = 5
F60
o1 do
  #1 = [#1 + 1]
  G1 X#1
o1 while [#1 LT 3]
#2 = 0
o2 do
  #2 = [#2 + 1]
  o3 if [#2 EQ 2]
    o2 continue
  o3 endif
  G1 Y#2
o2 while [#2 LT 4]
"""
    assert [m.end for m in moves(text)] == [(6, 0, 0), (6, 1, 0), (6, 3, 0), (6, 4, 0)]


def test_repeat():
    assert [m.end for m in moves("F60\no1 repeat [3]\nG91 G1 X1\no1 endrepeat\n")] == \
        [(1, 0, 0), (2, 0, 0), (3, 0, 0)]


def test_recursion_within_the_limit():
    text = """o<down> sub
  o1 if [#1 GT 0]
    G1 X#1 F60
    o<down> call [#1 - 1]
  o1 endif
o<down> endsub
o<down> call [50]
"""
    assert [m.end[0] for m in moves(text)] == [float(k) for k in range(50, 0, -1)]


# -- compensation modal state -------------------------------------------------------
def test_g41_with_tool_table_number():
    b = moves("G41 D3 G1 X1 F60\nG40 X2\n", tool_table={3: 10.0})
    assert (b[0].modal.side, b[0].modal.radius, b[0].modal.tool) == (1, 5.0, 3)
    assert (b[1].modal.side, b[1].modal.radius, b[1].modal.tool) == (0, 5.0, 3)


def test_g41_without_table_keeps_tool_number():
    b, = moves("G42 D7 G1 X1 F60")
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (-1, None, 7)
    b, = moves("G42 D7 G1 X1 F60", tool_table={3: 10.0})
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (-1, None, 7)


def test_g41_uses_loaded_tool_and_negative_table_diameter_flips():
    b, = moves("T4 M6\nG42 G1 X1 F60", tool_table={4: 8.0})
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (-1, 4.0, 4)
    b, = moves("T4 M6\nG41 G1 X1 F60", tool_table={4: -8.0})
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (-1, 4.0, 4)
    # selected but never loaded: LinuxCNC compensates with the spindle's tool 0
    # ("no tool", diameter 0), and the reader says so
    prog = read_gcode("T4\nG41 G1 X1 F60", "p.ngc", tool_table={4: 8.0})
    b, = prog.blocks
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (1, 0.0, 0)
    assert prog.meta["notes"] == ["p.ngc:2:1: G41 with no tool loaded and no D word: LinuxCNC "
                                  "compensates with tool 0, of diameter 0 (no offset); load "
                                  "the tool (T M6) or give D"]


def test_tool_zero_is_no_tool_radius_zero():
    # LinuxCNC: T0 is "no tool"; its ccomp/mill-zchanges test compensates
    # with G41 D0 and a table that lists no T0: the offset is 0.
    b, = moves("G41 D0 G1 X1 F60")
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (1, 0.0, 0)
    b, = moves("G42 D0 G1 X1 F60", tool_table={1: 6.0})
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (-1, 0.0, 0)
    b, = moves("T0 M6\nG41 G1 X1 F60", tool_table={1: 6.0})
    assert (b.modal.side, b.modal.radius, b.modal.tool) == (1, 0.0, 0)


def test_g41_1_diameter_and_negative_flip():
    b = moves("G41.1 D6 G1 X1 F60\nG41.1 D-4 X2\nG42.1 D-4 X3\nG42.1 D0 X4\n")
    assert [(m.modal.side, m.modal.radius) for m in b] == [(1, 3.0), (-1, 2.0), (1, 2.0), (-1, 0.0)]
    assert all(m.modal.tool is None for m in b)


def test_fagor_modal_flags():
    b = moves("G1 X1 F60\nG137 X2\nG138 X3\nG136 G139 X4\n")
    assert [(m.modal.corner, m.modal.start_end) for m in b] == [
        ("circular", "contour"), ("linear", "contour"), ("linear", "direct"),
        ("circular", "contour")]


def test_plane_recorded_in_modal():
    b = moves("G18 G1 X1 F60\nG19 X2\nG17 X3\n")
    assert [m.modal.plane for m in b] == ["ZX", "YZ", "XY"]


def test_modal_arc_with_no_plane_motion_is_a_zero_length_move():
    # Fagor 8070 manual, 9.1.5, first example: G03 is still modal when
    # "G91 G40 Y0" cancels compensation without moving in the plane.
    prog = read_gcode("G21 G90 F600\nG1 X0 Y0\nG03 X-20 Y-20 I0 J-20\nG91 G40 Y0\nG01 X-20\n")
    b = prog.blocks[2]
    assert b.motion.value == "line" and b.start == b.end == (-20.0, -20.0, 0.0)
    assert b.source.line == 4
    # with in-plane motion the missing centre is still an error
    with pytest.raises(ProgramError, match="no centre"):
        read_gcode("G21 G90 F600\nG3 X1 Y1\n")


def test_spindle_orientation_and_g64_take_their_words():
    """LinuxCNC's m19 and g64-r-planner tests: `M19 R45 Q2`, `M19 R90 P1`
    (orientation angle, timeout, direction) and `G64 P1 R0.5` (tolerance and
    the planner's peak scale) move nothing and are read; R, P and Q with
    neither are still errors."""
    prog = read_gcode("G21\nM19\nM19 R45 Q2\nM19 P1\nM19 R90 P0\nG64\nG64 P1 R0.5\nG64 P1 Q0.01"
                      "\nG0 X1\nM2\n")
    assert [b.end[0] for b in prog.blocks] == [1.0]
    with pytest.raises(ProgramError, match="R word with no G2, G3, G10, G64, M19"):
        read_gcode("G21\nM3 R45\nM2\n")


def test_position_parameters_and_messages_are_linuxcncs():
    """#5021-#5023 and #<_abs_x/y/z>: where G53 put the tool (machine
    coordinates), whatever the origin, rotation, G92 offset or tool length
    offset; #5420-#5422 and #<_x/y/z>: the same point in the work coordinates
    in force; in the program's units of the moment. (debug, ...) messages are
    kept in order with the values (LinuxCNC's rotation/abs-pts and
    machine-coord-params tests)."""
    text = ("G21\nG10 L2 P1 X3 Y7 Z0 R45\nG54\nG43.1 Z5\nG53 G0 X1 Y2 Z3\n"
            "(debug,#5021 #5022 #<_abs_z>)\n(debug, work #5420 #<_y> #5422)\n"
            "G20\n(debug,#<_abs_x>)\n(msg, no #1 here)\nM2\n")
    prog = read_gcode(text, "p.ngc")
    c, s = math.cos(math.radians(45)), math.sin(math.radians(45))
    x, y = 1 - 3, 2 - 7                 # off the G54 origin, then turned back by 45 degrees
    wx, wy = x * c + y * s, -x * s + y * c
    texts = [m["text"] for m in prog.meta[MESSAGES]]
    assert texts == ["1.000000 2.000000 3.000000",
                     f" work {wx:f} {wy:f} 3.000000",
                     f"{1 / 25.4:f}",
                     " no #1 here"]
    assert [m["line"] for m in prog.meta[MESSAGES]] == [6, 7, 9, 10]
    assert prog.blocks[-1].end == pytest.approx((1.0, 2.0, 3.0))    # G43.1 moved nothing
    assert any(w == "G43.1 Z5" for b in prog.blocks for w in b.words)
