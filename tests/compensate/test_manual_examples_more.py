"""More worked examples of the manuals (issue 32), each expected figure
printed in the manual or worked out here by hand from the rules of
docs/compensation.md (SINUMERIK rule 5, HEIDENHAIN rules 1-3), never copied
from ccopt's output.
"""
from __future__ import annotations

import math

import pytest

from ccopt import verify
from ccopt.compensate import compensate
from segment_expect import A, L
from segment_expect import check as check_all
from test_heidenhain import path as tnc_path
from test_siemens import prog as sinumerik_prog


def test_manual_example_sar_velocities_g341_fad():
    """SINUMERIK 840D sl Programming Manual Fundamentals 6FC5398-2EP40-0BA0
    (12/2019), 2.10.4.1, "Approach and retraction velocities", p.280
    (https://www.easymanua.ls/siemens/sinumerik-one-mcp-2400-4c/manual/1265481?p=280),
    the program as printed:

        $TC_DP1[1,1]=120 ;Milling tool T1/D1
        $TC_DP6[1,1]=7 ;Tool with 7 mm radius
        N10 G90 G0 X0 Y0 Z20 D1 T1
        N20 G41 G341 G247 DISCL=AC(5) DISR=13 FAD 500 X40 Y-10 Z=0 F200
        N30 X50
        N40 X60
        ...

    except ``FAD 500`` written ``FAD=500`` (the manual's own syntax,
    "FAD=...: Speed of the slow feed movement", p.273; the 808D manual's
    version of this example prints ``FAD=500``). The "..." is closed here by
    a plain ``G40`` block, not looked at.

    The manual's text: "All motions from P0 up to P2 are executed at this
    velocity [of the previous block (G0)]"; FAD for "G341: infeed movement
    perpendicular to the machining plane from P2 to P3"; F "effective as of
    P3". By hand: P4 = (40,-10), the contour leaves along +X (N30), G41 puts
    the tool left, r = 7: Q = (40,-3). G247 with G140 (the side of the
    compensation): the quadrant's centre Q + 13*(0,1) = (40,10), ending at Q
    (angle -90 deg) counter-clockwise, so it starts at angle 180 deg:
    P3 = (27,10). G341: P0 (0,0,20) -> P1 (27,10,20) -> P2 (27,10,5)
    (DISCL=AC(5)) in rapid, P2 -> P3 (27,10,0) at FAD 500 mm/min, then the
    quadrant in the plane Z0 at F200 mm/min. N30/N40 run on y = -3.
    """
    text = ("$TC_DP1[1,1]=120\n$TC_DP6[1,1]=7\nN10 G90 G0 X0 Y0 Z20 D1 T1\n"
            "N20 G41 G341 G247 DISCL=AC(5) DISR=13 FAD=500 X40 Y-10 Z=0 F200\n"
            "N30 X50\nN40 X60\nN50 G40 X70 Y-30\n")
    segs = compensate(sinumerik_prog(text), style="siemens").segments
    ap = [s for s in segs if s.block.source.line == 4]
    assert [(s.kind, s.start, s.end, s.w0, s.w1) for s in ap] == [
        ("line", (0, 0), pytest.approx((27, 10)), 20, 20),
        ("line", pytest.approx((27, 10)), pytest.approx((27, 10)), 20, 5),
        ("line", pytest.approx((27, 10)), pytest.approx((27, 10)), 5, 0),
        ("arc", pytest.approx((27, 10)), pytest.approx((40, -3)), 0, 0)]
    # rapid (None) to P2, FAD 500 mm/min from P2 to P3, F200 mm/min on the quadrant
    assert [s.feed for s in ap] == [None, None, pytest.approx(500 / 60),
                                    pytest.approx(200 / 60)]
    arc = ap[3].geom
    assert arc.center == pytest.approx((40, 10)) and arc.radius == pytest.approx(13)
    assert arc.sweep == pytest.approx(math.pi / 2)            # counter-clockwise quadrant
    contour = [(s.start, s.end) for s in segs if s.block.source.line in (5, 6)]
    assert contour == [(pytest.approx((40, -3)), pytest.approx((50, -3))),
                       (pytest.approx((50, -3)), pytest.approx((60, -3)))]


def test_manual_example_m97_tnc7():
    """HEIDENHAIN TNC7 basic User's Manual 81762x-19, "Machining small contour
    steps with M97", application example
    (https://content.heidenhain.de/doku/tnc_guide/pdf_files/TNC7_basic/81762x-19/html5/TNC7basic_EN_81762x-19.tncdoc),
    as printed:

        11 TOOL CALL 8 Z S5000   ; Insert the tool with diameter 16
        * - ...
        21 L X+0 Y+30 RL
        22 L X+10 M97            ; Machine the contour step using the path intersection
        23 L Y+25
        24 L X+50 M97            ; Machine the contour step using the path intersection
        25 L Y+23
        26 L X+100

    Tool diameter 16: r = 8 (TOOL DEF 1 R+8 here). The elided "..." is a
    start point (-20,50) at R0 and, after block 26, a departure at R0: not
    the manual's, only the blocks 21-26 are checked. The manual: "the control
    uses M97 to determine a path intersection that is in the extension of the
    tool path. The control extends the tool path each time by the tool
    radius." By hand (RL: the tool above the +X lines, right of the -Y
    lines): the offsets y = 38 and x = 18 meet at (18,38) (8 past the corner
    x = 10); x = 18 and y = 33 at the inside corner (18,33); y = 33 and
    x = 58 at (58,33) (8 past x = 50); x = 58 and y = 31 at (58,31); the
    contour starts at (0,38) perpendicular to block 22 (HEIDENHAIN rule 1).
    Without M97 (the manual's "Contour step without M97"; iTNC 530 p.379:
    "If the contour steps are very small, however, the tool would damage the
    contour") the transition arcs of radius 8 at steps of 5 and 2 cut the
    contour: the verifier must report it.
    """
    body = ("4 L X-20 Y+50 R0 FMAX\n21 L X+0 Y+30 RL F300\n22 L X+10 M97\n23 L Y+25\n"
            "24 L X+50 M97\n25 L Y+23\n26 L X+100\n27 L X+120 Y+50 R0 FMAX")
    p, tp = tnc_path(body, radius=8.0)
    check_all(tp, [
        L("lead-in", (-20, 50), (0, 38)),
        L("compensated", (0, 38), (18, 38)),
        L("compensated", (18, 38), (18, 33)),
        L("compensated", (18, 33), (58, 33)),
        L("compensated", (58, 33), (58, 31)),
        L("compensated", (58, 31), (100, 31)),
        L("lead-out", (100, 31), (120, 50)),
    ])
    p, tp = tnc_path(body.replace(" M97", ""), radius=8.0)
    assert not verify(tp, p).ok


def test_manual_example_tnc426_arc_connecting_to_a_straight_line():
    """HEIDENHAIN TNC 426/TNC 425/TNC 415 B/TNC 407 User's Manual (ISO
    programming), 5 "Programming Tool Movements", "Path Contours - Cartesian
    Coordinates", p.5-25, "Example for exercise: Circular arc connecting to a
    straight line"
    (https://manualshive.com/en/manual/heidenhain/tnc-407/2118718?page=158).
    The manual prints: transition point (10,40), arc end point (50,50),
    milling depth Z-15, tool radius R = 20 mm, and the program

        N30 G99 T12 L-25 R+20 *
        N60 X+30 Y-30 *                 (G00 G40 from N50)
        N70 Z-15 M03 *
        N80 G01 G41 X+50 Y+0 F100 *
        N90 X+10 Y+40 *
        N100 G06 X+50 Y+50 *            (arc with tangential connection)
        N110 G01 X+100 *
        N120 G00 G40 X+130 Y+70 *
        N130 Z+100 M02 *

    written here in Klartext, word for word (G41 = RL, G40 = R0, G06 = CT,
    G00 = FMAX, as the TNC manuals pair them).

    By hand, r = 20: the first element runs along t = (-1,1)/sqrt2, its left
    normal is (-1,-1)/sqrt2, so the tool starts at (50,0) + 20*(-1,-1)/sqrt2
    (HEIDENHAIN rule 1) and reaches (10,40) + 20*(-1,-1)/sqrt2. The CT arc is
    tangent to t at (10,40) and passes through (50,50): its centre
    (10,40) + s*(1,1)/sqrt2 with s^2 = |C - (50,50)|^2 gives s = 17*sqrt2,
    C = (27,57), radius 17*sqrt2, clockwise (the centre right of t). The tool
    runs outside it (RL, clockwise) on radius 17*sqrt2 + 20. The arc ends at
    (50,50) heading (-7,-23)/|.|, the next line heads +X: a left turn, an
    inside corner for RL: the offset circle meets the offset line y = 70 at
    x = 27 + sqrt((17*sqrt2 + 20)^2 - 13^2) (the other root, x < 0, lies off
    the line). The departure leaves from (100,70), the offset end of the
    last line, to (130,70).
    """
    body = ("4 L Z+100 R0 FMAX M6\n5 L X+30 Y-30 R0 FMAX\n6 L Z-15 R0 FMAX M3\n"
            "7 L X+50 Y+0 RL F100\n8 L X+10 Y+40\n9 CT X+50 Y+50\n10 L X+100\n"
            "11 L X+130 Y+70 R0 FMAX\n12 L Z+100 R0 FMAX M2")
    _, tp = tnc_path(body, radius=20.0)
    h = 20 / math.sqrt(2)
    rho = 17 * math.sqrt(2) + 20
    xi = 27 + math.sqrt(rho ** 2 - 13 ** 2)
    a0 = math.atan2(-h - 17, -h - 17)                  # start of the offset arc, -135 deg
    a1 = math.atan2(13, xi - 27)                        # the inside-corner point
    sweep = a1 - (a0 + 2 * math.pi)                     # clockwise from 225 deg to a1
    check_all(tp, [
        L("lead-in", (30, -30), (50 - h, -h)),
        L("compensated", (50 - h, -h), (10 - h, 40 - h)),
        A("compensated", (27, 57), (10 - h, 40 - h), (xi, 70), sweep),
        L("compensated", (xi, 70), (100, 70)),
        L("lead-out", (100, 70), (130, 70)),
    ], tol=1e-6)
