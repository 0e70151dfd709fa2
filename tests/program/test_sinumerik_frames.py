"""The SINUMERIK programmable frame: ``TRANS``, ``ATRANS``, ``ROT``, ``AROT``.

Expected points come from the frame worked out here: a programmed point
``p`` lies at ``shift + R(turn) p``, ``TRANS``/``ROT`` replace the frame,
``ATRANS d`` adds ``R(turn) d`` to the shift, ``AROT a`` adds ``a`` to the
turn (Programming Manual Fundamentals 2.12.4, 2.12.5). Generated programs
check that a contour read through a random chain of frames lies where that
chain puts it, and that compensating it gives the frame's image of the
unframed contour's compensation, certified, in the ``siemens`` and ``pmac``
styles.
"""
from __future__ import annotations

import math
import random

import pytest

from ccopt import compensate, verify
from ccopt.program.sinumerik import read_sinumerik
from located import assert_refused_at
from sinumerik_plates import generated_plate

TOL = 1e-9


def read(text: str, **kw):
    return read_sinumerik(text, "f.mpf", **kw)


def ends(prog):
    return [b.end for b in prog.blocks]


def close(p, q, tol=TOL):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def turned(p, deg):
    t = math.radians(deg)
    return (p[0] * math.cos(t) - p[1] * math.sin(t), p[0] * math.sin(t) + p[1] * math.cos(t))


def test_rotation_turns_the_programmed_axes():
    e = ends(read("ROT RPL=90\nG1 X10 Y0 F100\nG91 Y5\n"))
    assert close(e[0], (0, 10, 0)) and close(e[1], (-5, 10, 0))
    # ROT Z.. is the same turn about Z
    assert close(ends(read("ROT Z30\nG1 X10 Y0 F100\n"))[0], (*turned((10, 0), 30), 0))


def test_the_manuals_offset_and_rotation_example():
    # PM 2.12.5: N20 TRANS X20 Y10, N40 TRANS X30 Y26, N50 AROT RPL=45, the
    # same geometry each time, N70 TRANS clears offset and rotation.
    square = "G1 X0 Y0\nX10\nY10\nX0\nY0\n"
    e = ends(read("G17 G1 F100\nTRANS X20 Y10\n" + square + "TRANS X30 Y26\nAROT RPL=45\n"
                  + square + "TRANS\nG1 X0 Y0\n"))
    first = [(20, 10), (30, 10), (30, 20), (20, 20), (20, 10)]
    second = [(30 + q[0], 26 + q[1]) for q in
              (turned(p, 45) for p in [(0, 0), (10, 0), (10, 10), (0, 10), (0, 0)])]
    assert all(close(a, (*b, 0)) for a, b in zip(e, first + second + [(0, 0)]))


def test_atrans_runs_along_the_turned_axes_and_trans_clears_the_turn():
    e = ends(read("TRANS X10\nAROT RPL=90\nATRANS X5\nG1 X0 Y0 F100\nTRANS X1\nG1 X0 Y0\n"
                  "ROT RPL=90\nG1 X0 Y0\n"))
    # shift (10,0) + R90 (5,0) = (10,5); TRANS X1: unturned; ROT clears the shift
    assert close(e[0], (10, 5, 0)) and close(e[1], (1, 0, 0)) and close(e[2], (0, 0, 0))


def test_arcs_turn_with_the_frame():
    # a G2 quarter from (10,0) about the origin to (0,-10), turned 90 degrees:
    # from (0,10) about the origin to (10,0)
    prog = read("ROT RPL=90\nG1 X10 Y0 F100\nG2 X0 Y-10 I-10 J0\n")
    arc = prog.blocks[1]
    assert close(arc.start, (0, 10, 0)) and close(arc.end, (10, 0, 0))
    assert close(arc.center, (0, 0, 0))


CIRCLE_FORMS = [
    "G1 X10 Y0 F100\nCIP X0 Y10 I1=7.0710678 J1=7.0710678\n",
    "G1 X10 Y0 F100\nX20 Y5\nCT X30 Y0\n",
    "G1 X10 Y0 F100\nG3 AR=90 I-10 J0\n",
    "G1 X10 Y0 F100\nG2 X20 Y0 AR=120\n",
    "G1 X10 Y0 F100\nG3 X0 Y10 I=AC(0) J=AC(0)\n",
    "G91 G1 X10 Y0 F100\nCIP X-10 Y10 I1=-2.9289322 J1=7.0710678\nCT X-5 Y-5\n",
    "G1 X10 Y0 F100\nG2 X20 Y0 CR=-7 TURN=1 Z-3\n",
]


@pytest.mark.parametrize("form", range(len(CIRCLE_FORMS)))
def test_circle_forms_turn_with_the_frame(form):
    # every circle form read through TRANS X7 Y-3, AROT RPL=37 is the image
    # of the same form read plain: p -> (7,-3) + R(37) p, centres alike
    plain = read(CIRCLE_FORMS[form])
    framed = read("TRANS X7 Y-3\nAROT RPL=37\nG0 X0 Y0\n" + CIRCLE_FORMS[form])
    moves = framed.blocks[1:]
    assert len(moves) == len(plain.blocks)

    def image(p):
        q = turned(p, 37)
        return (7 + q[0], -3 + q[1], p[2])
    for a, b in zip(moves, plain.blocks):
        assert a.motion is b.motion and a.turns == b.turns
        assert close(a.end, image(b.end), 1e-7)
        if b.center is not None:
            assert close(a.center[:2], image(b.center)[:2], 1e-7)


REFUSALS = {
    "rotation in space": ("ROT X30\n", 1, 5, "about Z only"),
    "RPL outside G17": ("G18\nROT RPL=30\n", 2, 5, "G17 only"),
    "RPL in a move": ("G1 X1 F100 RPL=3\n", 1, 12, "ROT or AROT block"),
    "RPL with TRANS": ("TRANS X1 RPL=3\n", 1, 10, "belongs to ROT"),
    "frame with a move": ("ROT RPL=30 G1 F100\n", 1, 1, "its block"),
    "settable frame while turned": ("ROT RPL=30\nG55 G1 X1 F100\n", 2, 1, "turned"),
    "with compensation on": ("T1 D1\nG41 G1 X1 F100\nAROT RPL=5\n", 3, 1, "G40 first"),
    "scaling": ("SCALE X2\n", 1, 1, "scaling and mirroring"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    text, line, col, words = REFUSALS[name]
    assert_refused_at(read, text, ("f.mpf", line, col), words, tool_table={1: 2.0})


# -- generated: a contour through a random chain of frames ---------------------------
def _chain(rng):
    """Frame instructions and the frame they make, worked out step by step."""
    shift, turn, lines = (0.0, 0.0), 0.0, []
    for _ in range(rng.randint(1, 4)):
        kind = rng.choice(("TRANS", "ATRANS", "ROT", "AROT"))
        if kind in ("TRANS", "ATRANS"):
            d = (round(rng.uniform(-50, 50), 3), round(rng.uniform(-50, 50), 3))
            lines.append(f"{kind} X{d[0]} Y{d[1]}")
            if kind == "TRANS":
                shift, turn = d, 0.0
            else:
                r = turned(d, turn)
                shift = (shift[0] + r[0], shift[1] + r[1])
        else:
            a = round(rng.uniform(-180, 180), 4)
            lines.append(f"{kind} RPL={a}")
            shift, turn = ((0.0, 0.0), a) if kind == "ROT" else (shift, turn + a)
    return lines, shift, turn


def framed_program(seed: int):
    """A generated plate (tests/sinumerik_plates.py: corners, chamfers and
    roundings, G41 or G42) read plain and through a random frame chain."""
    plain, _, _ = generated_plate(seed)
    frame_lines, shift, turn = _chain(random.Random(seed + 10_000))
    framed = plain.replace("T1 D1\n", "T1 D1\n" + "\n".join(frame_lines) + "\n", 1)
    return framed, plain, shift, turn


def _check_framed(seed: int) -> None:
    framed, plain, shift, turn = framed_program(seed)
    pf, pp = read(framed), read(plain)
    assert len(pf.blocks) == len(pp.blocks)
    for b, c in zip(pf.blocks, pp.blocks):
        q = turned(c.end, turn)
        assert close(b.end, (shift[0] + q[0], shift[1] + q[1], c.end[2]), 1e-8), (seed, framed)
    for style in ("siemens", "pmac"):
        cf, cp = compensate(pf, style=style), compensate(pp, style=style)
        assert len(cf.segments) == len(cp.segments)
        for a, b in zip(cf.segments, cp.segments):
            q = turned(b.end, turn)
            assert close(a.end, (shift[0] + q[0], shift[1] + q[1]), 1e-8), (seed, style)
        assert verify(cf, pf).ok, (seed, style, framed)


@pytest.mark.parametrize("seed", range(3))
def test_generated_framed_contours(seed):
    _check_framed(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(3, 203))
def test_generated_framed_contours_slow(seed):
    _check_framed(seed)
