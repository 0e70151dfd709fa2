"""SINUMERIK straight lines by angle, ``ANG=`` with one coordinate.

The line leaves the start at ``ANG`` degrees from the plane's first axis
(G17 X toward Y, G18 Z toward X) and ends at the coordinate written; the
other coordinate is worked out here with the test's own trigonometry.
Generated polylines written with ``ANG`` read to the same blocks as the
same polylines written with both coordinates.
"""
from __future__ import annotations

import math
import random

import pytest

from ccopt.program.sinumerik import read_sinumerik
from located import assert_refused_at


def read(text: str, **kw):
    return read_sinumerik(text, "a.mpf", **kw)


def ends(prog):
    return [b.end for b in prog.blocks]


def test_angle_gives_the_other_coordinate():
    e = ends(read("G1 X0 Y0 F100\nX10 ANG=30\nY20 ANG=90\nG91 X-5 ANG=180\n"))
    assert e[1] == pytest.approx((10, 10 * math.tan(math.radians(30)), 0))
    assert e[2] == pytest.approx((10, 20, 0))
    assert e[3] == pytest.approx((5, 20, 0))


def test_angle_in_g18_runs_from_z_toward_x():
    e = ends(read("G18 G1 X0 Z0 F100\nZ-10 ANG=180\nX20 ANG=135\n"))
    assert e[1] == pytest.approx((0, 0, -10)) and e[2] == pytest.approx((20, 0, -30))


def test_angle_under_a_turned_frame():
    # ROT RPL=90: the work X runs along the machine Y
    e = ends(read("ROT RPL=90\nG1 X0 Y0 F100\nX10 ANG=45\n"))
    assert e[1] == pytest.approx((-10, 10, 0))


REFUSALS = {
    "no coordinate": ("G1 X0 Y0 F100\nANG=30\n", 2, 1, "two or three blocks"),
    "both coordinates": ("G1 X1 Y2 ANG=30 F100\n", 1, 10, "two or three blocks"),
    "parallel": ("G1 F100\nX10 ANG=90\n", 2, 5, "never reaches"),
    "backwards": ("G1 F100 X10\nX0 ANG=0\n", 2, 4, "behind the start"),
    "on a circle": ("G1 F100\nG2 X10 ANG=30 CR=20\n", 2, 8, "not a circle"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    text, line, col, words = REFUSALS[name]
    assert_refused_at(read, text, ("a.mpf", line, col), words)


def angle_pair(seed: int):
    """A random polyline in a random plane and distance mode, written with
    ANG and one coordinate, and with both: ``(angle text, plain text)``."""
    rng = random.Random(seed)
    plane, (a, b) = rng.choice((("G17", "XY"), ("G18", "ZX"), ("G19", "YZ")))
    incremental = rng.random() < 0.3
    head = [f"{plane} G1 F300 {a}0 {b}0", "G91" if incremental else "G90"]
    with_ang, plain = list(head), list(head)
    u = v = 0.0
    for _ in range(rng.randint(2, 8)):
        ang = rng.uniform(-180, 180)
        if min(abs(math.cos(math.radians(ang))), abs(math.sin(math.radians(ang)))) < 0.05:
            continue
        along = rng.uniform(1, 30)
        du, dv = along * math.cos(math.radians(ang)), along * math.sin(math.radians(ang))
        word_u = round(du, 6) if incremental else round(u + du, 6)
        word_v = round(dv, 6) if incremental else round(v + dv, 6)
        # the coordinate written is the one the program gives; the other follows
        du = word_u if incremental else word_u - u
        dv = du * math.tan(math.radians(ang))
        with_ang.append(f"{a}{word_u!r} ANG={ang!r}")
        plain.append(f"{a}{word_u!r} {b}{(dv if incremental else v + dv)!r}")
        u, v = u + du, v + dv
    return "\n".join(with_ang) + "\n", "\n".join(plain) + "\n"


def _check(seed: int) -> None:
    with_ang, plain = angle_pair(seed)
    got, want = ends(read(with_ang)), ends(read(plain))
    assert len(got) == len(want)
    for p, q in zip(got, want):
        assert p == pytest.approx(q, abs=1e-9), (seed, with_ang)


@pytest.mark.parametrize("seed", range(4))
def test_generated_angle_polylines(seed):
    _check(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 204))
def test_generated_angle_polylines_slow(seed):
    _check(seed)
