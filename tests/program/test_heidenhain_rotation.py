"""HEIDENHAIN ``CYCL DEF 10`` ROTATION (with the datum shift ``CYCL DEF 7``).

A programmed point ``p`` of the working plane lies at ``datum + R(rot) p``;
``PA`` is measured from the turned first axis; incremental words run along
the turned axes; ``ROT+0`` ends the rotation. Worked out by hand here, and
over generated Klartext contours (tests/klartext_contours.py: lines, CR, CC
+ C/CP, CT arcs, RND, CHF, APPR/DEP): read through a datum shift and a
rotation, every block is the image of the plain contour's, and so is the
``heidenhain`` style's compensated path, which verifies.
"""
from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from ccopt import compensate, verify
from ccopt.errors import ProgramError
from ccopt.program import read_text
from klartext_contours import contours

HEAD = "BEGIN PGM T MM\nTOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z S1000\n"


def read(body: str):
    return read_text(HEAD + body + "END PGM T MM\n", "t.h", "heidenhain")


def turned(p, deg):
    t = math.radians(deg)
    return (p[0] * math.cos(t) - p[1] * math.sin(t), p[0] * math.sin(t) + p[1] * math.cos(t))


def close(p, q, tol=1e-9):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def test_shift_then_turn_by_hand():
    b = read("CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+10\nCYCL DEF 7.2 Y+5\n"
             "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+90\nL X+10 Y+0 R0 FMAX\n"
             "L IX+5 F100\nCC X+0 Y+0\nLP PA+0 PR+3\nCP IPA+90 DR+\n"
             "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+0\nL X+0 Y+0\n").blocks
    # datum (10,5), turned 90 degrees: (10,0) -> (10,15); IX+5 along the turned X
    assert close(b[0].end, (10, 15, 0)) and close(b[1].end, (10, 20, 0))
    # the pole at the datum; PA+0 along the turned X: (10,5) + (0,3)
    assert close(b[2].end, (10, 8, 0))
    assert b[3].motion.value == "ccw" and close(b[3].end, (7, 5, 0))
    assert close(b[3].center, (10, 5, 0))
    assert close(b[4].end, (10, 5, 0))              # ROT+0: the datum again


def test_incremental_rotation_adds():
    b = read("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\nCYCL DEF 10.0 ROTATION\n"
             "CYCL DEF 10.1 IROT+15\nL X+10 Y+0 R0 FMAX\n").blocks
    assert close(b[0].end, (*turned((10, 0), 45), 0))


REFUSALS = {
    "no angle": ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1\n", 5, "give the angle"),
    "other word": ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 X+3\n", 5, "ROT+"),
    "shift after the turn": ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\n"
                             "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+3\n", 7, "shift first"),
    "tool axis change": ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\n"
                         "TOOL CALL 1 Y S1000\n", 6, "another tool axis"),
    "pole in another plane": ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\n"
                              "CC X+1 Z+2\n", 6, "another plane"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    body, line, words = REFUSALS[name]
    with pytest.raises(ProgramError) as info:
        read(body)
    assert info.value.line == line and info.value.col is not None, str(info.value)
    assert words in str(info.value)


def _check_framed(text: str, dx: float, dy: float, rot: float) -> None:
    dx, dy, rot = round(dx, 3), round(dy, 3), round(rot, 4)
    frame = (f"CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X{dx:+}\nCYCL DEF 7.2 Y{dy:+}\n"
             f"CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT{rot:+}\n")
    framed_text = text.replace("Z S1000\n", "Z S1000\n" + frame, 1)
    try:
        plain = read_text(text, "r.h", "heidenhain")
    except ProgramError as refused:
        # a contour the reader refuses (a CT whose end lies on, or a micrometre
        # off, the tangent: no arc, or one of radius 1e9) is refused framed too,
        # at the same block (the frame's 5 lines come before it)
        with pytest.raises(ProgramError) as framed_refused:
            read_text(framed_text, "r.h", "heidenhain")
        assert framed_refused.value.line == refused.line + 5, (str(refused), text)
        return
    framed = read_text(framed_text, "r.h", "heidenhain")

    def image(p):
        q = turned(p, rot)
        return (dx + q[0], dy + q[1], p[2])
    assert len(plain.blocks) == len(framed.blocks)
    # from the first block that sets X and Y (the first one moves Z alone and
    # keeps the machine's X Y, which the frame does not move)
    for a, b in list(zip(framed.blocks, plain.blocks))[1:]:
        assert close(a.end, image(b.end), 1e-7), text
        if b.center is not None:
            assert close(a.center[:2], image(b.center)[:2], 1e-7)
    pf, pp = compensate(framed, style="heidenhain"), compensate(plain, style="heidenhain")
    # the same curve: at a tangent join (CT after C, a CP) the turned numbers
    # may leave a corner of 1e-13 rad, whose corner piece has no length
    sf, sp = ([seg for seg in p.segments[2:] if seg.length > 1e-7] for p in (pf, pp))
    assert len(sf) == len(sp)
    for a, b in zip(sf, sp):
        assert close(a.end, image((*b.end, 0.0))[:2], 1e-7)
    assert verify(pf, framed).ok


FRAMES = (contours(), st.floats(-60, 60), st.floats(-60, 60), st.floats(-180, 180))


@settings(max_examples=20, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(*FRAMES)
def test_generated_contours_turn_with_the_frame(text, dx, dy, rot):
    _check_framed(text, dx, dy, rot)


@pytest.mark.slow
@settings(max_examples=300, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(*FRAMES)
def test_generated_contours_turn_with_the_frame_slow(text, dx, dy, rot):
    _check_framed(text, dx, dy, rot)
