"""SINUMERIK chamfers and roundings (``CHF``, ``CHR``, ``RND``, ``RNDM``,
``FRC``, ``FRCM``): the elements the reader inserts at contour corners.

Expected points are worked out here from the corner's geometry (a rounding
of radius ``r`` at a corner turning by ``phi`` touches each line at
``r tan(phi/2)`` from the corner; a chamfer of width ``w`` at ``w``; one of
length ``h`` has sides ``h / (2 cos(phi/2))``), never taken from ccopt.
"""
from __future__ import annotations

import math

import pytest

from ccopt.program.model import Motion
from ccopt.program.sinumerik import read_sinumerik
from ccopt.program.sinumerik.corners import NOT_INSERTED
from located import assert_refused_at

TOL = 1e-9


def read(text: str, **kw):
    return read_sinumerik(text, "p.mpf", **kw)


def moves(prog):
    return [b for b in prog.blocks if b.motion.is_move]


def close(p, q, tol=TOL):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def _corner_program(theta_deg: float, word: str) -> tuple[str, tuple, tuple, tuple]:
    """Along +X to (20, 0), then 15 units at ``theta_deg`` (the turn)."""
    t = math.radians(theta_deg)
    t_out = (math.cos(t), math.sin(t))
    end = (20 + 15 * t_out[0], 15 * t_out[1])
    text = (f"G17 G71 G90 G94\nG0 X0 Y0\nG1 X20 Y0 F600 {word}\n"
            f"X{end[0]:.12f} Y{end[1]:.12f}\nM30\n")
    return text, (1.0, 0.0), t_out, end


@pytest.mark.parametrize("theta", [90.0, -90.0, 30.0, -45.0, 135.0, -150.0, 5.0])
def test_rounding_between_lines_touches_each_at_r_tan_half_turn(theta):
    r = 2.5
    text, t_in, t_out, end = _corner_program(theta, f"RND={r}")
    b = moves(read(text))
    assert [m.motion for m in b] == [Motion.RAPID, Motion.LINE,
                                     Motion.ARC_CCW if theta > 0 else Motion.ARC_CW,
                                     Motion.LINE]
    d = r * math.tan(math.radians(abs(theta)) / 2)
    ta = (20 - d, 0.0, 0.0)
    tb = (20 + d * t_out[0], d * t_out[1], 0.0)
    left = 1.0 if theta > 0 else -1.0
    centre = (20 - d, left * r, 0.0)
    assert close(b[1].end, ta) and close(b[2].start, ta)
    assert close(b[2].end, tb) and close(b[3].start, tb)
    assert close(b[2].center, centre)
    assert close(b[3].end, (end[0], end[1], 0.0))
    assert b[1].start == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("theta", [90.0, -60.0, 120.0, 20.0])
def test_chamfers_chr_width_and_chf_length(theta):
    w = 1.5
    text, t_in, t_out, _ = _corner_program(theta, f"CHR={w}")
    b = moves(read(text))
    assert [m.motion for m in b[1:]] == [Motion.LINE] * 3
    assert close(b[1].end, (20 - w, 0, 0)) and close(b[2].start, (20 - w, 0, 0))
    tb = (20 + w * t_out[0], w * t_out[1], 0.0)
    assert close(b[2].end, tb) and close(b[3].start, tb)
    h = 1.2
    text, _, t_out, _ = _corner_program(theta, f"CHF={h}")
    b = moves(read(text))
    side = h / (2 * math.cos(math.radians(abs(theta)) / 2))
    assert close(b[1].end, (20 - side, 0, 0))
    assert math.dist(b[2].start, b[2].end) == pytest.approx(h, abs=TOL)


def test_rounding_from_a_line_into_an_arc():
    # +X to the origin, then G2 about (10, 0), radius 10, leaving along +Y:
    # a left turn of 90 degrees onto a circle curving right. The rounding's
    # centre lies r above the line and R + r from the arc's centre.
    R, r = 10.0, 2.0
    prog = read(f"G17 G1 X-20 Y0 F600\nX0 Y0 RND={r}\nG2 X20 Y0 I10 J0\nM30\n")
    b = moves(prog)
    cx = 10 - math.sqrt((R + r) ** 2 - r ** 2)
    assert [m.motion for m in b] == [Motion.LINE, Motion.LINE, Motion.ARC_CCW, Motion.ARC_CW]
    assert close(b[2].center, (cx, r, 0.0))
    assert close(b[1].end, (cx, 0.0, 0.0))
    u = ((cx - 10) / (R + r), r / (R + r))
    on_arc = (10 + R * u[0], R * u[1], 0.0)
    assert close(b[2].end, on_arc) and close(b[3].start, on_arc)
    assert b[3].center == (10.0, 0.0, 0.0) and close(b[3].end, (20, 0, 0))


def test_rounding_from_an_arc_into_a_line():
    # G3 a half circle about the origin from (10, 0) to (-10, 0), then -Y:
    # the arc arrives along -Y, a tangent corner: nothing to round; then a
    # line +X meets at a right angle, rounded inside, centre r from both.
    prog = read("G1 X10 Y0 F600\nG3 X-10 Y0 I-10 J0 RND=1\nG1 Y-5 RND=1\nX0\nM30\n")
    b = moves(prog)
    assert [m.motion for m in b] == [Motion.LINE, Motion.ARC_CCW, Motion.LINE,
                                     Motion.ARC_CCW, Motion.LINE]
    assert close(b[2].start, (-10, 0, 0)) and close(b[2].end, (-10, -4, 0))
    assert close(b[3].center, (-9, -4, 0)) and close(b[3].end, (-9, -5, 0))
    assert "RND: the transition is tangent (no corner)" in prog.meta[NOT_INSERTED]


def test_modal_rounding_feeds_and_units():
    # a square with RNDM=1 at three corners; RNDM=0 before the last one.
    # FRCM=120 (2 mm/s) modal, FRC=300 (5 mm/s) at one corner; F 600 = 10 mm/s.
    text = ("G17 G71 G94 G1 X0 Y0 F600\nRNDM=1 FRCM=120\nX10\nY10 FRC=300\nX0\n"
            "RNDM=0\nY0\nX5\nM30\n")
    b = moves(read(text))
    arcs = [m for m in b if m.motion.is_arc]
    assert len(arcs) == 3
    assert [a.feed for a in arcs] == pytest.approx([2.0, 5.0, 2.0])
    assert all(math.dist(a.start, a.center) == pytest.approx(1.0) for a in arcs)
    assert close(b[-2].end, (0, 0, 0))     # the corner at (0, 0) stays sharp
    # no FRC/FRCM: the feed of the block leading away from the corner
    b = moves(read("G1 X10 F600 RND=1\nY10 F300\nM30\n"))
    assert b[1].feed == pytest.approx(5.0)
    # G70: the radius is in inches, converted with the rest
    b = moves(read("G70 G1 X1 F10 RND=0.1\nY1\nM30\n", units="mm"))
    assert math.dist(b[1].start, b[1].center) == pytest.approx(2.54)


def test_corners_not_inserted_are_noted():
    prog = read("G1 X10 F600 RND=1\nZ-1\nY10\nM30\n")           # leaves the plane
    assert not any(m.motion.is_arc for m in prog.blocks)
    assert "RND: the next move leaves the plane" in prog.meta[NOT_INSERTED]
    prog = read("G1 X10 F600 RND=1\nM8\nM9\nS100\nM5\nY10\nM30\n")   # four idle blocks
    assert not any(m.motion.is_arc for m in prog.blocks)
    assert NOT_INSERTED in prog.meta and prog.meta[NOT_INSERTED]
    prog = read("G1 X10 F600 RND=1\nM8\nM9\nS100\nY10\nM30\n")      # three: inserted
    assert sum(m.motion.is_arc for m in prog.blocks) == 1
    prog = read("G1 X10 F600 CHR=1\n")                           # nothing follows
    assert "CHR: no block follows the corner" in prog.meta[NOT_INSERTED]
    prog = read("G1 X10 F600 RND=1\nG18 Z5\nM30\n")              # the plane changes
    assert "RND: the plane changes at the corner" in prog.meta[NOT_INSERTED]


REFUSALS = {
    "too large": ("G1 X2 F100 RND=5\nY10\n", 1, 12, "too large"),
    "chamfer at an arc": ("G1 X10 F100 CHF=1\nG3 X0 Y10 CR=10\n", 1, 13, "line and an arc"),
    "rounding at a rapid": ("G0 X10 RND=1\nY10\n", 1, 8, "rapid"),
    "two elements": ("G1 X10 F100 RND=1 CHF=1\n", 1, 19, "one corner element"),
    "negative size": ("G1 X10 F100 RND=-1\n", 1, 13, "must be > 0"),
    "on an idle block": ("G1 X10 F100\nRND=1\n", 2, 1, "does not move"),
    "FRC per revolution": ("S1000 M3 G95 G1 X10 F0.1 RND=1 FRC=0.2\n", 1, 32, "G93/G95"),
    "switching compensation": ("T1 D1 G1 X10 F100 RND=1\nG41 Y10\n", 1, 19, "switches"),
    "modal at a rapid": ("RNDM=1\nG1 X10 F100\nG0 Y10\n", 2, 1, "rapid"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located_at_the_word(name):
    text, line, col, words = REFUSALS[name]
    assert_refused_at(read, text, ("p.mpf", line, col), words, tool_table={1: 4.0})
