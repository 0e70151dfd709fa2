"""SINUMERIK straight lines by angle: ``ANG=`` with one coordinate, and the
contour definition over two blocks (``ANG``, then ``X Y ANG``).

The line leaves the start at ``ANG`` degrees from the plane's first axis
(G17 X toward Y, G18 Z toward X) and ends at the coordinate written; the
other coordinate is worked out here with the test's own trigonometry.
Generated polylines written with ``ANG`` read to the same blocks as the
same polylines written with both coordinates, and generated corners written
as two-block definitions to the same blocks as their two lines (the corner
worked out here by Cramer's rule).
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


def _meet(p0, a1, p2, a2):
    """The corner of a two-block definition, by Cramer's rule on
    ``p0 + t1 d1 + t2 d2 = p2``: ``(P1, t1, t2)``."""
    d1 = (math.cos(math.radians(a1)), math.sin(math.radians(a1)))
    d2 = (math.cos(math.radians(a2)), math.sin(math.radians(a2)))
    det = d1[0] * d2[1] - d1[1] * d2[0]
    w = (p2[0] - p0[0], p2[1] - p0[1])
    t1 = (w[0] * d2[1] - w[1] * d2[0]) / det
    t2 = (d1[0] * w[1] - d1[1] * w[0]) / det
    return (p0[0] + t1 * d1[0], p0[1] + t1 * d1[1]), t1, t2


def test_the_manuals_two_block_definition_with_chamfer_and_rounding():
    # PM 2.9.9 (12/2019): N10 X10 Z100 F1000 G18, N20 ANG=140 CHR=7.5,
    # N30 X80 Z70 ANG=95.824 RND=10, N40 X70 Z50. In G18 (u, v) = (Z, X).
    prog = read("N10 X10 Z100 F1000 G18 G1\nN20 ANG=140 CHR=7.5\n"
                "N30 X80 Z70 ANG=95.824 RND=10\nN40 X70 Z50\n")
    (z1, x1), t1, t2 = _meet((100, 10), 140, (70, 80), 95.824)
    assert t1 > 0 and t2 > 0
    b = prog.blocks
    d1 = (math.cos(math.radians(140)), math.sin(math.radians(140)))
    # the chamfer's side 7.5 back along the first line from the corner P1
    assert b[1].end == pytest.approx((x1 - 7.5 * d1[1], 0, z1 - 7.5 * d1[0]))
    assert [m.source.line for m in b] == [1, 2, 2, 3, 3, 4]
    assert b[2].motion is b[1].motion                 # the chamfer: a line
    assert b[4].motion.is_arc and b[5].end == pytest.approx((70, 0, 50))
    # the rounding of radius 10 at P2 = (Z70, X80)
    assert math.dist(b[4].start, b[4].center) == pytest.approx(10)


REFUSALS = {
    "no second block": ("G1 X0 Y0 F100\nANG=30\n", 2, 1, "never comes"),
    "second block without ANG": ("G1 X0 Y0 F100\nANG=30\nX5 Y9\n", 3, 1, "second block"),
    "parallel lines": ("G1 X0 Y0 F100\nANG=30\nX10 Y9 ANG=30\n", 3, 8, "parallel"),
    "meeting behind": ("G1 X0 Y0 F100\nANG=0\nX-10 Y10 ANG=90\n", 3, 10, "behind"),
    "under G91": ("G91 G1 F100\nANG=30\n", 2, 1, "under G90"),
    "frame between": ("G1 X0 Y0 F100\nANG=30\nTRANS X1\n", 3, 1, "follow its first"),
    "both coordinates alone": ("G1 X1 Y2 ANG=30 F100\n", 1, 10, "two or three blocks"),
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


def _same_ends(seed: int, written: str, plain: str, tol: float) -> None:
    """The blocks of ``written`` end where those of ``plain`` do, within ``tol``."""
    got, want = ends(read(written)), ends(read(plain))
    assert len(got) == len(want)
    for p, q in zip(got, want):
        assert p == pytest.approx(q, abs=tol), (seed, written)


def _check(seed: int) -> None:
    _same_ends(seed, *angle_pair(seed), 1e-9)


@pytest.mark.parametrize("seed", range(4))
def test_generated_angle_polylines(seed):
    _check(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 204))
def test_generated_angle_polylines_slow(seed):
    _check(seed)


def two_block_pair(seed: int):
    """A random corner P1 between P0 and P2, written as a two-block contour
    definition (ANG, then X Y ANG) and as two lines: ``(definition, plain)``."""
    rng = random.Random(seed)
    while True:
        p0, p1, p2 = ([round(rng.uniform(-50, 50), 4) for _ in range(2)] for _ in range(3))
        a1 = math.degrees(math.atan2(p1[1] - p0[1], p1[0] - p0[0]))
        a2 = math.degrees(math.atan2(p2[1] - p1[1], p2[0] - p1[0]))
        turn = abs((a2 - a1 + 180) % 360 - 180)
        if math.dist(p0, p1) > 2 and math.dist(p1, p2) > 2 and 5 < turn < 175:
            break
    head = f"G17 G90 G1 F300 X{p0[0]} Y{p0[1]}\n"
    definition = head + f"ANG={a1!r}\nX{p2[0]} Y{p2[1]} ANG={a2!r}\nX0 Y0\n"
    plain = head + f"X{p1[0]} Y{p1[1]}\nX{p2[0]} Y{p2[1]}\nX0 Y0\n"
    return definition, plain


def _check_two_blocks(seed: int) -> None:
    _same_ends(seed, *two_block_pair(seed), 1e-7)


@pytest.mark.parametrize("seed", range(4))
def test_generated_two_block_definitions(seed):
    _check_two_blocks(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 204))
def test_generated_two_block_definitions_slow(seed):
    _check_two_blocks(seed)

