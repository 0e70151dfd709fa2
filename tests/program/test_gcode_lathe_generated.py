"""Generated G71 roughing and G70 finishing of monotone lathe profiles
(ccopt.program.gcode.lathe_cycles), checked against the profile drawn here.

The contour ``o100`` plunges from the start point (X Z of the cycle's line,
the stock's radius) to X0 at the start Z, then runs towards -Z in runs along
Z, faces up in X and tapers, X never decreasing and never above the stock:
a shaft turned from a bar. The part keeps the material under the profile
(and all of it beyond the profile's end, up to the stock). From LinuxCNC's
interp_g7x.cc (``do_g71``: ``add_distance(d)`` then ``move(w, u)``;
``pocket``: passes from the start X down by I, each to the offset profile,
the last one along it; ``do_g70``: its last pass ``E`` = 0 off the profile):

* the program reads without error, within a second;
* no point of a roughing feed, moved back by (W, U), is in the kept
  material or nearer to it than D;
* the roughing passes (the feeds that start at the cycle's start Z) begin at
  the stock's X, step down by I, and the last one, at most I lower, starts
  on the offset profile;
* G70's last pass runs on the profile and ends at the contour's end point.
"""
from __future__ import annotations

import math
import time

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion

SLOW = settings(max_examples=300, deadline=None)
QUICK = settings(max_examples=6, deadline=None, derandomize=True, database=None)
#: Geometry compares to this (mm; LinuxCNC's g7x tolerance is 1e-6).
EPS = 1e-6
#: Far away, for the rays that close the kept material.
FAR = 1e6


def _hundredths(lo: int, hi: int):
    return st.integers(lo, hi).map(lambda n: n / 100)


@st.composite
def profiles(draw):
    """(stock X, start Z, [(z, x)] of the profile from its first point).

    No two segments in a row are parallel (LinuxCNC's offset cannot
    intersect them), every slope lies between 1:4 and 4:1."""
    xs, zs = draw(_hundredths(800, 3000)), draw(_hundredths(50, 300))
    x = draw(_hundredths(100, int(xs * 100) - 200))
    z = zs - draw(_hundredths(50, 1000))
    points, last = [(zs, x), (z, x)], (-1.0, 0.0)
    for kind in draw(st.lists(st.sampled_from(["run", "face", "taper"]), max_size=6)):
        dz = draw(_hundredths(50, 800)) if kind != "face" else 0.0
        dx = draw(_hundredths(20, 400)) if kind != "run" else 0.0
        if kind == "taper":
            dx = min(max(dx, dz / 4), dz * 4)
        if x + dx > xs or dz * last[1] == dx * -last[0]:
            continue                                # above the stock, or parallel
        z, x, last = z - dz, x + dx, (-dz, dx)
        points.append((z, x))
    return xs, zs, points


def _shortest(xs, points) -> float:
    """The shortest segment of the profile closed up to the stock."""
    lengths = [math.dist(a, b) for a, b in zip(points[1:], points[2:])]
    lengths += [math.dist(points[0], points[1])] + ([xs - points[-1][1]] if points[-1][1] < xs
                                                     else [])
    return min(lengths)


def _program(xs, zs, points, d, i, r, u, w, d70, p70) -> str:
    lines = [f"G1 X{points[0][1]}"]
    for (z0, x0), (z1, x1) in zip(points, points[1:]):
        lines.append(("" if x1 == x0 else f"X{x1} ") + ("" if z1 == z0 else f"Z{z1}"))
    return ("G18 G21 G90 F200\nG0 X40 Z10\no100 sub\n" + "\n".join(lines) + "\no100 endsub\n"
            f"G71 Q100 X{xs} Z{zs} D{d} I{i} R{r} U{u} W{w}\n"
            f"G70 Q100 X{xs} Z{zs} D{d70} P{p70}\nM2\n")


@st.composite
def lathe_cases(draw):
    """Profiles with D at most a quarter of the shortest segment: LinuxCNC
    offsets by at most half a segment's length at a time, so D on a shorter
    segment falls short of D (its own interp_g7x.cc, ccopt alike)."""
    xs, zs, points = draw(profiles())
    cap = min(1.0, _shortest(xs, points) / 4)
    d = math.floor(draw(st.floats(0, 1)) * cap * 100) / 100
    words = (d, draw(_hundredths(30, 300)), draw(_hundredths(10, 100)),
             draw(_hundredths(0, 50)), draw(_hundredths(0, 50)), draw(_hundredths(0, 100)),
             draw(st.integers(1, 3)))
    return _program(xs, zs, points, *words), xs, zs, points, words


def _segment_distance(p: complex, a: complex, b: complex) -> float:
    if a == b:
        return abs(p - a)
    t = min(1.0, max(0.0, ((p - a) / (b - a)).real))
    return abs(p - (a + t * (b - a)))


def _boundary(xs, zs, points) -> list[complex]:
    """The kept material's edge, z + x*1j: up the start Z, along the profile,
    up to the stock and back along it."""
    z_end, x_end = points[-1]
    edge = [complex(zs, -FAR)] + [complex(z, x) for z, x in points]
    return edge + [complex(z_end, max(xs, x_end)), complex(-FAR, max(xs, x_end))]


def _inside(q: complex, edge: list[complex]) -> bool:
    """Whether q is inside the kept material (``edge`` closed far below it;
    even-odd rule, so meaningful only off the edge)."""
    ring = edge + [complex(-FAR, -FAR)]
    crossings = 0
    for a, b in zip(ring, ring[1:] + ring[:1]):
        if (a.imag > q.imag) != (b.imag > q.imag):
            z = a.real + (q.imag - a.imag) / (b.imag - a.imag) * (b.real - a.real)
            crossings += z > q.real
    return crossings % 2 == 1


def _samples(block) -> list[complex]:
    """Points z + x*1j along a feed block (lines and G18 arcs)."""
    a, b = complex(block.start[2], block.start[0]), complex(block.end[2], block.end[0])
    if block.motion is Motion.LINE:
        return [a + (b - a) * t / 8 for t in range(9)]
    c = complex(block.center[2], block.center[0])
    turn = math.remainder(math.atan2((b - c).imag, (b - c).real)
                          - math.atan2((a - c).imag, (a - c).real), 2 * math.pi)
    return [c + (a - c) * complex(math.cos(turn * t / 8), math.sin(turn * t / 8))
            for t in range(9)]


def _check_roughing(blocks, xs, zs, points, d, i, u, w) -> None:
    edge = _boundary(xs, zs, points)
    shift = complex(w, u)
    for b in blocks:
        for q in _samples(b):
            q -= shift
            near = min(_segment_distance(q, e0, e1) for e0, e1 in zip(edge, edge[1:]))
            assert near >= d - EPS and (near <= EPS or not _inside(q, edge)), (b, q, near)
    starts = [b.start[0] for b in blocks if abs(b.start[2] - (zs + w)) < EPS]
    assert starts[0] == pytest.approx(xs + u, abs=EPS)
    assert [a - b for a, b in zip(starts[:-1], starts[1:-1])] == pytest.approx(
        [i] * (len(starts) - 2), abs=EPS)
    assert 0 < starts[-2] - starts[-1] <= i + EPS
    assert starts[-1] == pytest.approx(points[0][1] + d + u, abs=EPS)


def _check_finishing(blocks, xs, points) -> None:
    rapids = [k for k, b in enumerate(blocks) if b.motion is Motion.RAPID]
    last_pass = blocks[rapids[-1] + 1:]
    assert last_pass, blocks
    profile = [complex(z, x) for z, x in points]
    for b in last_pass:
        for q in _samples(b):
            assert min(_segment_distance(q, e0, e1)
                       for e0, e1 in zip(profile, profile[1:])) <= EPS, (b, q)
    z_end, x_end = points[-1]
    assert blocks[-1].end == pytest.approx((x_end, 0.0, z_end), abs=EPS)


def _check(case) -> None:
    text, xs, zs, points, (d, i, r, u, w, d70, p70) = case
    began = time.perf_counter()
    blocks = read_gcode(text, "lathe.ngc").blocks
    assert time.perf_counter() - began < 1.0, text
    feeds = [b for b in blocks if b.cycle == "G71" and b.motion is not Motion.RAPID]
    try:
        _check_roughing(feeds, xs, zs, points, d, i, u, w)
        _check_finishing([b for b in blocks if b.cycle == "G70"], xs, points)
    except AssertionError as exc:
        raise AssertionError(f"{text}\n{exc}") from None


@pytest.mark.slow
@SLOW
@given(lathe_cases())
def test_g71_roughs_outside_the_profile_and_g70_finishes_on_it_generated(case):
    _check(case)


@QUICK
@given(lathe_cases())
def test_g71_roughs_outside_the_profile_and_g70_finishes_on_it(case):
    _check(case)
