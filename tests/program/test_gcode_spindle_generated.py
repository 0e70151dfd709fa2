"""Generated G95 programs under G96 constant surface speed and G97
(ccopt.program.gcode.spindle): feeds worked out here from LinuxCNC's rules,
rpm = k v / (2 pi r) at radius r = |X| (k = 1000 under G21, v in m/min;
12 under G20, v in ft/min), at most D; under G97 rpm = S; feed = F rpm / 60
units per second.

A move at one X is fed exactly at its radius's feed. A move that changes X
sees the speed change along it: its one feed is the slowest along it (at
its largest radius), so it is at most the feed at every radius it passes,
and the program carries one note saying its time is an upper bound exactly
when such a move is fed under G96.
"""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.program.gcode import read_gcode

SLOW = settings(max_examples=300, deadline=None)
QUICK = settings(max_examples=6, deadline=None, derandomize=True, database=None)
#: Length units per surface-speed unit (metre, foot) and the ranges drawn, in
#: thousandths of the program unit: |X|, F per revolution.
UNITS = {"G21": (1000.0, (500, 60000), (10, 500)), "G20": (12.0, (20, 2400), (1, 20))}


def _milli(lo: int, hi: int):
    return st.integers(lo, hi).map(lambda n: n / 1000)


def _feed(f: float, mode: tuple, k: float, radius: float) -> float:
    """LinuxCNC's feed (units/s) at ``radius`` for ``mode``: ("G97", S) or
    ("G96", v, D or None)."""
    if mode[0] == "G97":
        return f * mode[1] / 60
    _, v, d = mode
    rpm = math.inf if radius == 0 else k * v / (2 * math.pi * radius)
    return f * min(rpm, math.inf if d is None else d) / 60


@st.composite
def css_programs(draw):
    """(text, F, k, [(mode, X before, X after, line number)] of its G1 moves)."""
    unit = draw(st.sampled_from(sorted(UNITS)))
    k, xs, fs = UNITS[unit]
    x_word = _milli(*xs).flatmap(lambda v: st.sampled_from([v, v, v, -v]))
    f = draw(_milli(*fs))

    def g96():
        v, d = draw(st.integers(20, 400)), draw(st.none() | st.integers(100, 4000))
        return f"G96 S{v}" + ("" if d is None else f" D{d}"), ("G96", v, d)

    word, mode = g96()
    x, z = draw(x_word), 0.0
    lines = [f"G18 {unit}", f"{word} M3", f"G95 F{f}", f"G0 X{x} Z{z}"]
    moves = []
    for step in draw(st.lists(st.sampled_from(["Z", "X", "XZ", "G97", "G96"]), max_size=12)):
        if step == "G97":
            rpm = draw(st.integers(50, 3000))
            lines.append(f"G97 S{rpm}")
            mode = ("G97", rpm)
            continue
        if step == "G96":
            word, mode = g96()
            lines.append(word)
            continue
        x1 = draw(x_word) if "X" in step else x
        z = z - draw(_milli(1, 20000)) if "Z" in step else z
        lines.append("G1" + (f" X{x1}" if "X" in step else "") + (f" Z{z}" if "Z" in step else ""))
        moves.append((mode, x, x1, len(lines)))
        x = x1
    return "\n".join(lines) + "\nM2\n", f, k, moves


def _check_feeds(case) -> None:
    text, f, k, moves = case
    prog = read_gcode(text, "css.ngc")
    fed = [b for b in prog.blocks if b.feed is not None]
    assert len(fed) == len(moves), text
    bounded = [line for mode, x0, x1, line in moves if mode[0] == "G96" and x0 != x1]
    for b, (mode, x0, x1, line) in zip(fed, moves):
        far = max(abs(x0), abs(x1))
        assert b.feed == pytest.approx(_feed(f, mode, k, far), rel=1e-12), (text, line)
        for t in range(11):
            r = abs(x0 + (x1 - x0) * t / 10)
            assert b.feed <= _feed(f, mode, k, r) * (1 + 1e-12), (text, line, r)
    notes = prog.meta.get("notes", [])
    assert len(notes) == (1 if bounded else 0), (text, notes)
    if bounded:
        assert notes[0].startswith(f"css.ngc:{bounded[0]}:"), (text, notes)


@pytest.mark.slow
@SLOW
@given(css_programs())
def test_feeds_per_revolution_under_g96_and_g97_generated(case):
    _check_feeds(case)


@QUICK
@given(css_programs())
def test_feeds_per_revolution_under_g96_and_g97(case):
    _check_feeds(case)
