"""``G76`` threading as LinuxCNC runs it (ccopt.program.gcode.threading): the
passes below are worked out by hand from ``convert_threading_cycle`` and
``threading_pass`` (interp_convert.cc), in mm, never taken from ccopt's
output. Each move is ``(kind, x, z)``: ``R`` rapid, ``F`` feed (Y stays 0)."""
from __future__ import annotations

import math

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion

_KIND = {Motion.RAPID: "R", Motion.LINE: "F"}


def passes(text: str):
    """The G76 blocks of ``text`` (after a G18 G21 set-up and S600 M3 at X10 Z2)."""
    prog = read_gcode("G18 G21\nS600 M3\nG0 X10 Z2\n" + text, "t.ngc")
    blocks = [b for b in prog.blocks if b.cycle == "G76"]
    return [(_KIND[b.motion], b.end[0], b.end[2]) for b in blocks], blocks


def _pass(x_back, x_in, z_in, z_out):
    return [("R", x_back, z_in), ("R", x_in, z_in), ("F", x_in, z_out), ("R", x_back, z_out)]


def test_outside_thread_constant_depth_passes_then_the_full_depth():
    # I-1: crests 1 mm inside the drive line X10; J0.5 first depth, K1.2 thread
    # height, R1 (constant depth): depths 1.5, 2.0 (then 2.5 >= 2.2 stops) and
    # the full 2.2 once (H0). Retract depth: full 2.2, so X back = 10 + 2.2 - d.
    moves, blocks = passes("G76 P1.5 Z-20 I-1 J0.5 K1.2\n")
    want = []
    for d in (1.5, 2.0, 2.2):
        want += _pass(12.2 - d, 10 - d, 2, -20)
    want.append(("R", 10, -20))               # to the line's end point (X unchanged)
    assert [(k, round(x, 9), round(z, 9)) for k, x, z in moves] == \
        [(k, pytest.approx(x), pytest.approx(z)) for k, x, z in want]
    # synchronised: 1.5 mm per revolution at 600 rev/min is 15 mm/s
    assert all(b.feed == pytest.approx(15.0) for b in blocks if b.motion is Motion.LINE)


def test_degression_compound_angle_spring_passes_and_a_bore():
    # I+0.5 (a bore: depths go outwards), J0.2, K1, R2: depths 0.5 + 0.2*sqrt(n)
    # below 1.5 (n = 1..24), then 1.5 twice (H1). Q30: each pass starts
    # (d - 0.5) tan 30 further back in Z and ends at Z-10 + 1 * tan 30 - zoff.
    moves, _ = passes("G76 P1 Z-10 I0.5 J0.2 K1 R2 Q30 H1\n")
    t = math.tan(math.radians(30))
    depths = []
    n = 1
    while 0.5 + 0.2 * n ** 0.5 < 1.5:
        depths.append(0.5 + 0.2 * n ** 0.5)
        n += 1
    depths += [1.5, 1.5]
    want = []
    for d in depths:
        zoff = (d - 0.5) * t
        want += _pass(10 + d - 1.5, 10 + d, 2 - zoff, -10 + t - zoff)
    want.append(("R", 10, -10))
    assert len(moves) == len(want)
    for (k, x, z), (wk, wx, wz) in zip(moves, want):
        assert k == wk and x == pytest.approx(wx, abs=1e-12) and z == pytest.approx(wz, abs=1e-12)


def test_exit_taper_feeds_out_at_the_taper_pitch():
    # E2 L2: the cut stops 2 mm before Z-20 and feeds out to the crest depth at
    # Z-20 with the pitch scaled by the taper's length per unit of Z.
    moves, blocks = passes("G76 P2 Z-20 I-1 J1 K1.5 E2 L2\n")
    # depths: 2.0, then 1 + 1*2 = 3 >= 2.5 stops; full depth 2.5
    first = moves[:5]
    assert first == [("R", pytest.approx(10.5), 2), ("R", pytest.approx(8.0), 2),
                     ("F", pytest.approx(8.0), pytest.approx(-18.0)),
                     ("F", pytest.approx(9.5), pytest.approx(-20.0)),
                     ("R", pytest.approx(10.5), pytest.approx(-20.0))]
    taper_feed = 2 * math.hypot(2, 1.5) / 2 * 600 / 60
    assert blocks[2].feed == pytest.approx(20.0) and blocks[3].feed == pytest.approx(taper_feed)


def test_diameter_mode_halves_x_and_i_j_k():
    radius, _ = passes("G76 P1.5 Z-20 I-1 J0.5 K1.2\n")
    diameter, _ = passes("G7 G0 X20\nG76 P1.5 Z-20 I-2 J1 K2.4\n")
    assert diameter == [(k, pytest.approx(x), pytest.approx(z)) for k, x, z in radius]


@pytest.mark.parametrize("line, col, message", [
    ("G76 Z-20 I-1 J0.5 K1.2", 1, "P word missing with G76"),
    ("G76 P1 Z-20 I-1 K1.2", 1, "I J or K words missing with G76"),
    ("G76 P1 Z-20 I0 J0.5 K1.2", 13, "In G76, I must not be 0"),
    ("G76 P1 Z-20 I-1 J0 K1.2", 17, "In G76, J must be greater than 0"),
    ("G76 P1 Z-20 I-1 J0.5 K0.5", 22, "In G76, K must be greater than J"),
    ("G76 P1 Z-20 I-1 J0.5 K1 A5", 25, "Cannot move rotary axes with G76"),
    ("M5\nG76 P1 Z-20 I-1 J0.5 K1", 1, "not turning in G76"),
    ("G1 X1 E2 F100", 7, "E word with no G70 or G76 to use it"),
])
def test_refusals_are_located(line, col, message):
    with pytest.raises(ProgramError) as err:
        passes(line + "\n")
    assert message in str(err.value)
    assert err.value.col == col


def test_g33_is_a_straight_feed_synchronised_to_the_spindle():
    # K1.5 mm per revolution at 600 rev/min: 15 mm/s along the path; the
    # 45-degree exit with K 1.5 * sqrt 2 keeps 1.5 mm of Z per revolution
    prog = read_gcode("G18 G21\nS600 M3\nG0 X10 Z2\nG33 Z-20 K1.5\n"
                      f"G33 X11 Z-21 K{1.5 * math.sqrt(2)!r}\nM2\n", "t.ngc")
    cut, exit_ = prog.blocks[1:]
    assert cut.motion is Motion.LINE and cut.end == (10.0, 0.0, -20.0)
    assert cut.feed == pytest.approx(15.0)
    assert exit_.end == (11.0, 0.0, -21.0) and exit_.feed == pytest.approx(15.0 * math.sqrt(2))
    z_per_second = exit_.feed / math.dist(exit_.start, exit_.end)
    assert z_per_second * 60 / 600 == pytest.approx(1.5)


@pytest.mark.parametrize("line, col, message", [
    ("G33 Z-20", 1, "K word missing with G33"),
    ("G33 Z-20 K1 F100", 13, "F word used with G33"),
    ("M5\nG33 Z-20 K1", 1, "Spindle not turning in G33"),
])
def test_g33_refusals_are_located(line, col, message):
    with pytest.raises(ProgramError) as err:
        passes(line + "\n")
    assert message in str(err.value) and err.value.col == col


def test_g76_degression_is_a_number_whatever_the_units_and_passes_are_bounded():
    # R is no length: after a G21 -> G20 switch, J0.01 K0.05 R2 still cuts the
    # n >= 1 with 0.01 * sqrt(n) < 0.05, n = 1..24, then the full depth once
    prog = read_gcode("G18 G21\nS600 M3\nG0 X10 Z2\nG20\n"
                      "G76 P0.1 Z-1 I-0.04 J0.01 K0.05 R2\nM2\n", "t.ngc")
    cuts = [b for b in prog.blocks if b.per_revolution is not None]
    assert len(cuts) == 24 + 1
    # (K/J)**R = 10**12 passes: refused, located, in bounded time
    with pytest.raises(ProgramError, match="G76 would cut about 1e[+]12 passes") as err:
        passes("G76 P1 Z-10 I-1 J0.1 K1 R12\n")
    assert (err.value.line, err.value.col) == (4, 1)
