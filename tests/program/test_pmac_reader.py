"""Hand-worked PMAC programs: the expected geometry is worked out here, not by the reader."""
from __future__ import annotations

import math

import pytest

from ccopt.errors import ProgramError
from ccopt.program.model import Motion
from ccopt.program.pmac import read_pmac



def pts(p):
    return [(b.start, b.end) for b in p]


def close(a, b, tol=1e-9):
    return all(math.isclose(x, y, abs_tol=tol) for x, y in zip(a, b))


def wrap(body: str) -> str:
    return f"OPEN PROG 1 CLEAR\n{body}\nCLOSE\n"


# ---------------------------------------------------------------------------
# lines, ABS / INC
def test_lines_abs_and_inc():
    p = read_pmac(wrap("""
LINEAR ABS F10
X10 Y20
INC X5 Y-5 Z1
ABS(X) X0      ; X absolute, Y and Z still incremental
Y2
INC(Z) ABS(Y) Y7 Z3
"""))
    ends = [b.end for b in p]
    assert ends == [(10, 20, 0), (15, 15, 1), (0, 15, 1), (0, 17, 1), (0, 7, 4)]
    assert p[0].start == (0, 0, 0)
    for a, b in zip(p.blocks, p.blocks[1:]):
        assert b.start == a.end
    assert all(b.motion is Motion.LINE for b in p)
    assert p.dialect == "pmac" and p.units == "mm"


def test_start_position_and_no_spaces():
    p = read_pmac(wrap("linear abs f2 x10y20z-1\ninc x1y1"), start=(1.0, 2.0, 3.0))
    assert p.start == (1.0, 2.0, 3.0)
    assert pts(p) == [((1, 2, 3), (10, 20, -1)), ((10, 20, -1), (11, 21, -1))]


def test_rapid_has_no_feed_and_source_columns():
    p = read_pmac(wrap("F7\nRAPID X1 Y1\n  N20 LINEAR X2"))
    assert p[0].motion is Motion.RAPID and p[0].feed is None and p[0].move_time is None
    assert p[1].feed == 7.0
    assert (p[0].source.line, p[0].source.col) == (3, 7)
    assert (p[1].source.line, p[1].source.col) == (4, 14)   # "  N20 LINEAR X2"


# ---------------------------------------------------------------------------
# circles with a centre vector
def test_circle_ijk_incremental_default():
    # start (10, 0); centre 10 to the left of the start -> (0, 0)
    p = read_pmac(wrap("LINEAR F1 X10\nCIRCLE2 X0 Y10 I-10 J0\nCIRCLE1 X-10 Y0 I0 J-10"))
    a, b = p[1], p[2]
    assert a.motion is Motion.ARC_CCW and a.center == (0, 0, 0)
    assert a.end == (0, 10, 0) and not a.is_spiral()
    assert b.motion is Motion.ARC_CW and b.center == (0, 0, 0) and b.end == (-10, 0, 0)


def test_plain_abs_inc_do_not_touch_vector_mode():
    # ABS(R): centre absolute; a later plain INC keeps it absolute.
    p = read_pmac(wrap("""
F1 X0 Y10
ABS(R)
CIRCLE1 X10 Y0 I0 J0
INC
CIRCLE1 X-10 Y-10 I0 J0
INC(R)
CIRCLE1 X10 Y10 I10 J0
"""))
    assert p[1].center == (0, 0, 0) and p[1].end == (10, 0, 0)
    assert p[2].center == (0, 0, 0) and p[2].end == (0, -10, 0)
    # incremental vector from the start (0, -10): centre (10, -10)
    assert p[3].center == (10, -10, 0) and p[3].end == (10, 0, 0)
    for arc in p[1:]:
        cx, cy, _ = arc.center
        r0 = math.hypot(arc.start[0] - cx, arc.start[1] - cy)
        r1 = math.hypot(arc.end[0] - cx, arc.end[1] - cy)
        assert r0 == pytest.approx(r1) == pytest.approx(10)


def test_full_circle_with_ijk():
    p = read_pmac(wrap("F1 X10\nCIRCLE1 X10 Y0 I-10\nINC CIRCLE2 X0 Y0 J5"))
    full, inc_full = p[1], p[2]
    assert full.start == full.end == (10, 0, 0) and full.center == (0, 0, 0)
    assert full.in_plane and full.motion is Motion.ARC_CW
    assert inc_full.start == inc_full.end and inc_full.center == (10, 5, 0)


def test_helix_keeps_z_linear_and_centre_in_start_plane():
    p = read_pmac(wrap("F1 X10\nCIRCLE2 X10 Y0 Z-3 I-10 K99"))
    h = p[1]
    assert h.end == (10, 0, -3) and h.center == (0, 0, 0)


def test_spiral_block_is_kept_with_its_centre():
    # start radius 10 about the origin, end radius 20: PMAC spirals
    p = read_pmac(wrap("F1 X10\nCIRCLE2 X0 Y20 I-10 J0"))
    s = p[1]
    assert s.motion is Motion.ARC_CCW
    assert s.center == (0, 0, 0) and s.end == (0, 20, 0)
    assert s.is_spiral()
    assert math.hypot(*s.end_uv) - math.hypot(*s.start_uv) == pytest.approx(10)


# ---------------------------------------------------------------------------
# circles with a radius
def _chord_centres(s, e, r):
    """Both circle centres of radius |r| through s and e, by intersecting two circles."""
    (x0, y0), (x1, y1) = s, e
    d = math.hypot(x1 - x0, y1 - y0)
    a = d / 2
    h = math.sqrt(r * r - a * a)
    mx, my = x0 + (x1 - x0) / 2, y0 + (y1 - y0) / 2
    ox, oy = -(y1 - y0) / d * h, (x1 - x0) / d * h
    return [(mx + ox, my + oy), (mx - ox, my - oy)]


def _sweep(c, s, e, ccw):
    """Angle swept from s to e about c turning counter-clockwise (ccw) or clockwise."""
    a0 = math.atan2(s[1] - c[1], s[0] - c[0])
    a1 = math.atan2(e[1] - c[1], e[0] - c[0])
    d = (a1 - a0) % (2 * math.pi) if ccw else (a0 - a1) % (2 * math.pi)
    return d


@pytest.mark.parametrize("mode,r", [("CIRCLE1", 13), ("CIRCLE1", -13),
                                    ("CIRCLE2", 13), ("CIRCLE2", -13)])
def test_r_arcs_short_and_long(mode, r):
    s, e = (2.0, 1.0), (12.0, 6.0)    # chord sqrt(125) ~ 11.18 < 26
    p = read_pmac(wrap(f"F1 X{s[0]} Y{s[1]}\n{mode} X{e[0]} Y{e[1]} R{r}"))
    arc = p[1]
    ccw = mode == "CIRCLE2"
    want = [c for c in _chord_centres(s, e, abs(r))
            if (_sweep(c, s, e, ccw) <= math.pi) == (r > 0)]
    assert len(want) == 1
    assert close(arc.center_uv, want[0])
    assert arc.motion is (Motion.ARC_CCW if ccw else Motion.ARC_CW)
    sweep = _sweep(arc.center_uv, s, e, ccw)
    assert (sweep < math.pi) if r > 0 else (sweep > math.pi)
    assert not arc.is_spiral()


def test_r_half_circle_exact_chord():
    p = read_pmac(wrap("F1\nCIRCLE1 X10 Y0 R5"))
    assert close(p[0].center, (5, 0, 0))


# ---------------------------------------------------------------------------
# planes
def test_normal_j_minus_1_arc_turns_by_right_hand_rule():
    p = read_pmac(wrap("NORMAL J-1 F1\nCIRCLE1 X10 Z10 I0 K10"))
    arc = p[0]
    assert arc.modal.plane == "ZX" and arc.motion is Motion.ARC_CW
    assert arc.center == (0, 0, 10)
    # PMAC UM p.177: thumb along the normal (0,-1,0), fingers curl clockwise.
    # Velocity at the start = n x (start - centre) must point towards the arc.
    n = (0.0, -1.0, 0.0)
    r = tuple(a - b for a, b in zip(arc.start, arc.center))
    v = (n[1] * r[2] - n[2] * r[1], n[2] * r[0] - n[0] * r[2], n[0] * r[1] - n[1] * r[0])
    assert v[0] > 0 and v[2] == 0            # heads to +X, towards the end (10, 0, 10)
    assert arc.end == (10, 0, 10)
    assert arc.center_uv == (10, 0)          # (u, v) = (z, x)


def test_normal_i_minus_1_and_k_minus_1():
    p = read_pmac(wrap("F1 NORMAL I-2\nX1\nNRM K(-1)\nX2"))
    assert p[0].modal.plane == "YZ" and p[1].modal.plane == "XY"


# ---------------------------------------------------------------------------
# variables and expressions
def test_variables_and_expressions():
    p = read_pmac(wrap("""
P1=3 Q2=P1*2        ; 6
P(P1)=7             ; P3
P4=P2*2+1           ; unset P2 reads 0 -> 1
F1 X(P1+Q2) Y(P(3)) Z(P4)
X(SIN(30)*4) Y($10) Z(2^1)
X(0.5^0.875) Y(5^7) Z(3^-3)
X(P99) Y(INT(-1.5)) Z(6&3)
"""))
    assert p[0].end == (9, 7, 1)
    assert close(p[1].end, (2, 16, 3))
    assert close(p[2].end, (0.375, 2, -2))    # Turbo SRM p.489 examples
    assert close(p[3].end, (0, -2, 2))


def test_i15_radians_and_atan2_with_q0():
    p = read_pmac(wrap("F1\nQ0=-1\nX(ATAN2(0))\nI15=1\nX(SIN(3.141592653589793/2))"))
    assert p[0].end[0] == pytest.approx(180.0)
    assert p[1].end[0] == pytest.approx(1.0)
    assert p.meta["i_variables"][15] == 1


def test_m_and_i_variables_recorded():
    p = read_pmac(wrap("M1=1 M2==0 I5113=10\nF1 X(I5113) M3"))
    assert p.meta["m_variables"] == {1: 1.0, 2: 0.0}
    assert p.meta["i_variables"] == {5113: 10.0}
    assert p[0].end[0] == 10 and p[0].mcodes == (3,)


# ---------------------------------------------------------------------------
# compensation modal state
def test_cc_flags_on_the_right_blocks():
    p = read_pmac(wrap("""
F1 X1
CCR2 CC1
X2
CC2 X3
CC0
X4
CCR-0.5 CC1 X5
CCR0.5 X6
CCR-1 CC2 X7
"""))
    got = [(b.end[0], b.modal.side, b.modal.radius) for b in p]
    assert got == [(1, 0, None), (2, 1, 2), (3, -1, 2), (4, 0, 2),
                   (5, -1, 0.5),          # CC1 with a negative radius: right
                   (6, 1, 0.5),           # CC1 kept, radius positive again: left
                   (7, 1, 1)]             # CC2 with a negative radius: left


# ---------------------------------------------------------------------------
# units: F, TM, TA, TS
def test_feed_time_units_and_move_time_mode():
    p = read_pmac(wrap("""
TA200 TS50 F100
X1
TM250 X2
X3
F5 X4
X5 TM(1000/4)
"""))
    assert [b.feed for b in p] == [100, None, None, 5, None]
    assert [b.move_time for b in p] == [None, 0.25, 0.25, None, 0.25]
    assert p[0].modal.accel_time == pytest.approx(0.2)
    assert p[0].modal.scurve_time == pytest.approx(0.05)


def test_isx_variables_of_the_selected_coordinate_system():
    p = read_pmac("&2\nI5290=60000 I5287=100 I5190=1\nOPEN PROG 1\nF600 X1\nCLOSE")
    assert p[0].feed == pytest.approx(10.0)          # 600 units/min
    assert p[0].modal.accel_time == pytest.approx(0.1)
    q = read_pmac("I5189=25\nOPEN PROG 1\nX1\nCLOSE")  # default feedrate Isx89
    assert q[0].feed == 25


# ---------------------------------------------------------------------------
# dwell and delay
def test_dwell_and_delay():
    p = read_pmac(wrap("F1 X3 Y4\nDWELL250\nDELAY(P1+100) X5"))
    d, e = p[1], p[2]
    assert d.motion is Motion.DWELL and e.motion is Motion.DWELL
    assert d.dwell == pytest.approx(0.25) and e.dwell == pytest.approx(0.1)
    assert d.start == d.end == (3, 4, 0) == e.start
    assert p.meta["delay_blocks"] == [2]
    assert p[3].end == (5, 4, 0)


# ---------------------------------------------------------------------------
# buffers
TWO = """; download file
CLOSE
P7=2
OPEN PROG 5 CLEAR
F1 X(P7)
CLOSE
OPEN PLC 1 CLEAR
anything at all
CLOSE
OPEN PROG 9
F1 Y1
CLOSE
OPEN PROG 5
Y3            ; appended: no CLEAR
CLOSE
"""


def test_open_prog_selection_and_append():
    first = read_pmac(TWO)
    assert first.meta["program"] == 5 and first.meta["programs"] == [5, 9]
    assert [b.end for b in first] == [(2, 0, 0), (2, 3, 0)]
    assert first.meta["skipped_buffers"] == ["PLC 1"]
    nine = read_pmac(TWO, program=9)
    assert [b.end for b in nine] == [(0, 1, 0)]
    with pytest.raises(ProgramError, match="program 3 is not in the file"):
        read_pmac(TWO, program=3)


def test_clear_line_and_return():
    p = read_pmac("OPEN PROG 1\nF1 X1\nCLEAR\nF1 X2\nRETURN\nX99 GOTO 5\nCLOSE")
    assert [b.end for b in p] == [(2, 0, 0)]


def test_bare_body():
    p = read_pmac("LINEAR F3\nX1")
    assert p.meta["program"] is None and p[0].end == (1, 0, 0)
    with pytest.raises(ProgramError):
        read_pmac("X1", program=1)


def test_statement_order_on_one_line():
    # F after the axis words applies to that move (QRG p.49: "X3 Y4 F50");
    # a mode or compensation command after axis words acts from the next move.
    p = read_pmac(wrap("X3 Y4 F50 TA10\nX1 CC1 CIRCLE1 X3 Y4 R5 F2"))
    assert p[0].feed == 50 and p[0].modal.accel_time == pytest.approx(0.01)
    # "X1" is executed when CC1 is read, before F2: it keeps F50
    assert p[1].motion is Motion.LINE and p[1].modal.side == 0 and p[1].feed == 50
    assert p[2].motion is Motion.ARC_CW and p[2].modal.side == 1 and p[2].feed == 2


def test_online_ccbuf_and_break_cos():
    p = read_pmac("DEFINE CCBUF 5\nI5199=0.99\nOPEN PROG 1\nF1 X1\nCLOSE")
    assert p.meta["ccbuf"] == 5 and p.meta["break_cos"] == pytest.approx(0.99)
