"""SINUMERIK polar coordinates: the pole ``G110``/``G111``/``G112`` and moves
by ``AP=``/``RP=``.

Expected points are worked out here: ``pole + RP (cos AP, sin AP)`` in the
plane's first and second axis, the pole from the last position (``G110``),
the work zero (``G111``) or the last pole (``G112``). Generated contours
written in polar words read to the same blocks as the same contour written
in ``X Y`` (the test's own trigonometry), and compensate to the same path.
"""
from __future__ import annotations

import math
import random

import pytest

from ccopt import compensate, verify
from ccopt.program.model import Motion
from ccopt.program.sinumerik import read_sinumerik
from located import assert_refused_at

TOL = 1e-9


def read(text: str, **kw):
    return read_sinumerik(text, "p.mpf", **kw)


def close(p, q, tol=TOL):
    return all(abs(a - b) <= tol for a, b in zip(p, q))


def polar(c, ap, rp):
    return (c[0] + rp * math.cos(math.radians(ap)), c[1] + rp * math.sin(math.radians(ap)))


def test_moves_about_an_absolute_pole():
    b = read("G111 X10 Y10\nG1 AP=0 RP=5 F100\nAP=90\nG3 AP=180\nG1 RP=2\n").blocks
    assert close(b[0].end, (15, 10, 0)) and close(b[1].end, (10, 15, 0))
    # the circle turns about the pole to AP=180 at the radius kept
    assert b[2].motion is Motion.ARC_CCW and close(b[2].center, (10, 10, 0))
    assert close(b[2].end, (5, 10, 0)) and close(b[3].end, (8, 10, 0))


def test_relative_poles_and_incremental_angle():
    b = read("G1 X3 Y4 F100\nG110 X1 Y1\nG1 AP=30 RP=2\nAP=IC(60)\nG112 AP=90 RP=10\n"
             "AP=0 RP=0\nZ-1 AP=AC(45) RP=IC(3)\n").blocks
    pole = (4, 5)                                  # G110: from (3, 4)
    assert close(b[1].end[:2], polar(pole, 30, 2)) and close(b[2].end[:2], polar(pole, 90, 2))
    pole = polar(pole, 90, 10)                     # G112: from the last pole
    assert close(b[3].end[:2], pole)
    assert close(b[4].end, (*polar(pole, 45, 3), -1))


def test_other_planes_and_a_turned_frame():
    # G18: AP from Z toward X
    b = read("G18\nG111 Z10 X0\nG1 AP=90 RP=5 F100\nAP=0\n").blocks
    assert close(b[0].end, (5, 0, 10)) and close(b[1].end, (0, 0, 15))
    # under ROT RPL=90 the pole and the points are in the turned work frame
    b = read("ROT RPL=90\nG111 X10 Y0\nG1 AP=0 RP=5 F100\nG91 G2 AP=IC(-90)\n").blocks
    assert close(b[0].end, (0, 15, 0))
    assert close(b[1].end, (5, 10, 0)) and close(b[1].center, (0, 10, 0))
    assert b[1].motion is Motion.ARC_CW


REFUSALS = {
    "pole with a move": ("G111 X1 Y1 G1 F100\n", 1, 1, "block of its own"),
    "pole with one axis": ("G111 X1\n", 1, 1, "needs the pole's X and Y"),
    "pole by a mix": ("G112 X1 AP=3 RP=2\n", 1, 1, "not a mix"),
    "nothing kept": ("G1 AP=30 F100\n", 1, 4, "RP is not known"),
    "kept across a new pole": ("G1 AP=30 RP=2 F100\nG111 X0 Y0\nAP=40\n", 3, 1,
                               "RP is not known"),
    "both forms": ("G1 X1 AP=30 RP=2 F100\n", 1, 7, "one way"),
    "plain under G91": ("G91 G1 AP=30 RP=2 F100\n", 1, 8, "G91"),
    "negative radius": ("G1 AP=30 RP=-2 F100\n", 1, 4, ">= 0"),
    "with CIP": ("G1 X1 F100\nCIP X3 Y1 I1=2 J1=1\nAP=30 RP=2\n", 3, 1, "G0-G3"),
    "circle with a centre": ("G1 X5 F100\nG2 AP=90 RP=5 I-5\n", 2, 4, "turns about the pole"),
    "another plane": ("G111 X0 Y0\nG18\nG1 AP=30 RP=2 F100\n", 3, 4, "another plane"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    text, line, col, words = REFUSALS[name]
    assert_refused_at(read, text, ("p.mpf", line, col), words)


# -- generated: a contour in polar words and in X Y -----------------------------------
def polar_pair(seed: int):
    """A round plate about a random pole: corners on a circle about it,
    joined by lines and by arcs about the pole (G2/G3 with AP), entered and
    left along the normal at the middle of its first edge (a line), tool
    outside; written once in polar words and once in X Y with I J:
    ``(polar text, cartesian text)``."""
    rng = random.Random(seed)
    pole = (round(rng.uniform(-50, 50), 3), round(rng.uniform(-50, 50), 3))
    n = rng.randint(4, 8)
    aps = sorted(round(rng.uniform(0, 360), 4) for _ in range(n))
    gaps = [b - a for a, b in zip(aps, aps[1:] + [aps[0] + 360])]
    if min(gaps) < 8 or max(gaps) > 150:
        return polar_pair(seed + 1000)
    rp = round(rng.uniform(20, 40), 4)
    kinds = ["line"] + [rng.choice(("line", "arc")) for _ in range(n - 1)]
    radius = rng.uniform(0.3, 2.0)
    head = ["G17 G71 G90", f"$TC_DP6[1,1]={radius:.4f}", "T1 D1"]
    # the middle of the chord aps[0] -> aps[1] lies on the bisecting ray
    apm = (aps[0] + aps[1]) / 2
    rpm = rp * math.cos(math.radians(aps[1] - aps[0]) / 2)
    lead, start = polar(pole, apm, rpm + 15), polar(pole, apm, rpm)
    p_lines = head + [f"G111 X{pole[0]} Y{pole[1]}", f"G0 AP={apm!r} RP={rpm + 15!r}",
                      f"G42 G1 AP={apm!r} RP={rpm!r} F600", f"AP={aps[1]} RP={rp}"]
    here = polar(pole, aps[1], rp)
    c_lines = head + [f"G0 X{lead[0]!r} Y{lead[1]!r}",
                      f"G42 G1 X{start[0]!r} Y{start[1]!r} F600", f"X{here[0]!r} Y{here[1]!r}"]
    for i in range(1, n):
        ap = aps[(i + 1) % n]
        to = polar(pole, ap, rp)
        if kinds[i] == "line":
            p_lines.append(f"G1 AP={ap}")
            c_lines.append(f"G1 X{to[0]!r} Y{to[1]!r}")
        else:
            p_lines.append(f"G3 AP={ap}")
            c_lines.append(f"G3 X{to[0]!r} Y{to[1]!r} I{pole[0] - here[0]!r} "
                           f"J{pole[1] - here[1]!r}")
        here = to
    p_lines += [f"G1 AP={apm!r} RP={rpm!r}", f"G40 G1 AP={apm!r} RP={rpm + 15!r}", "M30"]
    c_lines += [f"G1 X{start[0]!r} Y{start[1]!r}", f"G40 G1 X{lead[0]!r} Y{lead[1]!r}", "M30"]
    return "\n".join(p_lines) + "\n", "\n".join(c_lines) + "\n"


def _check_pair(seed: int) -> None:
    ptext, ctext = polar_pair(seed)
    pp, pc = read(ptext), read(ctext)
    assert len(pp.blocks) == len(pc.blocks)
    for a, b in zip(pp.blocks, pc.blocks):
        assert a.motion is b.motion and close(a.end, b.end, 1e-8), (seed, ptext)
        if b.center is not None:
            assert close(a.center[:2], b.center[:2], 1e-8)
    cp, cc = compensate(pp, style="siemens"), compensate(pc, style="siemens")
    assert len(cp.segments) == len(cc.segments)
    assert all(close(a.end, b.end, 1e-8) for a, b in zip(cp.segments, cc.segments))
    assert verify(cp, pp).ok, (seed, ptext)


@pytest.mark.parametrize("seed", range(3))
def test_generated_polar_plates(seed):
    _check_pair(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(3, 203))
def test_generated_polar_plates_slow(seed):
    _check_pair(seed)
