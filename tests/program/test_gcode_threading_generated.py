"""Generated ``G76`` and ``G33`` lines (ccopt.program.gcode.threading and the
G33 feed): invariants worked out here from ``convert_threading_cycle`` and
``threading_pass`` (interp_convert.cc), never from ccopt's output.

A pass's cut is its one feed move at constant X; its depth is the distance
of that X from the drive line's X (inwards for an outside thread, I < 0;
outwards for a bore). Pass n (n >= 1) cuts to ``|I| + J * n**(1/R)`` while
that is below the full depth ``|I| + K``, then the full depth is cut H + 1
times. Feeds are synchronised: ``P * S / 60`` along Z, the taper pitch
``P * hypot(E, K) / E`` along a taper. Lengths are in the program's first
unit; a G20/G21 switch before the cycle scales its lengths P I J K E, not
the degression R (a plain number).
"""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.program.gcode import read_gcode
from ccopt.program.gcode.units import MM_PER_INCH
from ccopt.program.model import Motion

SLOW = settings(max_examples=300, deadline=None)
QUICK = settings(max_examples=6, deadline=None, derandomize=True, database=None)
#: Output units per written unit, for the (first, cycle's) unit codes.
FACTOR = {("G21", "G21"): 1.0, ("G20", "G20"): 1.0, ("G21", "G20"): MM_PER_INCH,
          ("G20", "G21"): 1 / MM_PER_INCH}
#: Depths compare to this (program units: far below a written digit).
EPS = 1e-9


def _milli(lo: int, hi: int):
    return st.integers(lo, hi).map(lambda n: n / 1000)


@st.composite
def g76_lines(draw):
    """(program text, the cycle's words in output units with X0 and Z1, S)."""
    units = draw(st.sampled_from(sorted(FACTOR)))
    k = draw(_milli(200, 3000))
    w = {"P": draw(_milli(100, 5000)),
         "I": draw(_milli(50, 3000)) * draw(st.sampled_from([-1, 1])),
         "J": max(0.001, round(k * draw(st.floats(0.1, 0.95)), 3)), "K": k,
         "R": draw(_milli(1000, 3000)), "Q": draw(_milli(0, 45000)),
         "H": draw(st.integers(0, 3)), "E": draw(_milli(0, 4000)), "L": draw(st.integers(0, 3))}
    x0, z0 = draw(_milli(5000, 30000)), draw(_milli(-5000, 5000))
    z1 = z0 + draw(_milli(2000, 40000)) * draw(st.sampled_from([-1, 1]))
    s = draw(st.integers(50, 3000))
    text = (f"G18 {units[0]}\nS{s} M3\nG0 X{x0} Z{z0}\n{units[1]}\n"
            f"G76 Z{z1} " + " ".join(f"{a}{v}" for a, v in w.items()) + "\nM2\n")
    f = FACTOR[units]
    scaled = {a: v * f if a in "PIJKE" else v for a, v in w.items()}
    scaled.setdefault("R", 1.0)
    scaled.update(X0=x0, Z1=z1 * f)
    return text, scaled, s


def _planned_cuts(w: dict) -> int:
    """How many passes cut below the full depth (LinuxCNC's while loop)."""
    n = 1
    while abs(w["I"]) + w["J"] * n ** (1 / w["R"]) < abs(w["I"]) + w["K"]:
        n += 1
    return n - 1


def _check_g76(case) -> None:
    text, w, s = case
    blocks = read_gcode(text, "thread.ngc").blocks[1:]
    assert blocks and all(b.cycle == "G76" for b in blocks), text
    sign = 1.0 if w["I"] > 0 else -1.0                  # a bore cuts outwards
    full = abs(w["I"]) + w["K"]
    feeds = [b for b in blocks if b.motion is Motion.LINE]
    cuts = [b for b in feeds if b.start[0] == b.end[0]]
    depths = [sign * (b.end[0] - w["X0"]) for b in cuts]
    # counted, not told apart by depth: a planned pass may end within rounding
    # of the full depth (J0.093 K0.93 R1: the tenth cuts to 0.98, full 0.98 + 1 ulp)
    planned = _planned_cuts(w)
    assert len(depths) == planned + w["H"] + 1, text
    below = depths[:planned]
    assert all(a < b for a, b in zip(below, below[1:])), text
    assert all(d < full + EPS for d in below), text
    assert depths[planned:] == pytest.approx([full] * (w["H"] + 1), abs=EPS), text
    for b in feeds:
        for p in (b.start, b.end):
            assert sign * (p[0] - w["X0"]) <= full + EPS, text
    last = blocks[-1]
    assert last.motion is Motion.RAPID, text
    assert last.end == pytest.approx((w["X0"], 0.0, w["Z1"]), abs=EPS), text
    tapered = w["E"] > 0 and w["L"] > 0
    assert len(feeds) == len(cuts) * (1 + tapered * ((w["L"] & 1) * 2 + (w["L"] >> 1))), text
    straight = w["P"] * s / 60
    taper = w["P"] * math.hypot(w["E"], w["K"]) / w["E"] * s / 60 if w["E"] > 0 else None
    for b in feeds:
        want = straight if b.start[0] == b.end[0] else taper
        assert b.feed == pytest.approx(want, rel=1e-12), (text, b.start, b.end)


@pytest.mark.slow
@SLOW
@given(g76_lines())
def test_g76_passes_generated(case):
    _check_g76(case)


@QUICK
@given(g76_lines())
def test_g76_passes(case):
    _check_g76(case)


@st.composite
def g33_programs(draw):
    """(text, [(end point, K)] of each G33 line, S)."""
    s = draw(st.integers(50, 3000))
    x, z = draw(_milli(1000, 30000)), draw(_milli(-5000, 5000))
    lines, want = [f"G18 G21\nS{s} M3\nG0 X{x} Z{z}"], []
    for _ in range(draw(st.integers(1, 5))):
        if draw(st.booleans()):
            x = draw(_milli(1000, 30000))
        z = draw(_milli(-40000, 40000))
        k = draw(_milli(100, 5000))
        lines.append(f"G33 X{x} Z{z} K{k}")
        want.append(((x, 0.0, z), k))
    return "\n".join(lines) + "\nM2\n", want, s


def _check_g33(case) -> None:
    text, want, s = case
    blocks = read_gcode(text, "g33.ngc").blocks[1:]
    assert len(blocks) == len(want), text
    for b, (end, k) in zip(blocks, want):
        assert b.motion is Motion.LINE and b.end == end, text
        assert b.feed == pytest.approx(k * s / 60, rel=1e-12), text


@pytest.mark.slow
@SLOW
@given(g33_programs())
def test_g33_is_k_per_revolution_to_the_programmed_point_generated(case):
    _check_g33(case)


@QUICK
@given(g33_programs())
def test_g33_is_k_per_revolution_to_the_programmed_point(case):
    _check_g33(case)
