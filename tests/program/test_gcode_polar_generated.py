"""Generated programs with LinuxCNC's polar words ``@`` (radius) and ``^``
(angle, degrees) mixed with X Y Z, G90 and G91 (ccopt.program.gcode.polar).

The expected points are worked out here from ``find_ends`` (interp_find.cc),
in work coordinates about the work origin (a G54 offset moves the machine
points): under G90 ``@r ^a`` is the point at radius r and angle a and a
word left out keeps the current point's radius or angle; under G91 ``@``
grows the radius along the current ray, then ``^`` turns about the origin.
A ``G91 G81 ... ^a Lk`` drills k holes on the start's circle, a degrees apart.
"""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion

SLOW = settings(max_examples=300, deadline=None)
QUICK = settings(max_examples=6, deadline=None, derandomize=True, database=None)
#: No polar word is written where the point is this close to the work origin
#: (LinuxCNC refuses G91 polar motion and G90 ``@`` alone there).
NEAR_ORIGIN = 1e-3

_value = st.integers(-50000, 50000).map(lambda n: n / 1000)        # three decimals
_angle = st.integers(-720000, 720000).map(lambda n: n / 1000)
_step = st.tuples(st.sampled_from(["G90", "G91"]), st.sampled_from(["G0", "G1"]),
                  st.sampled_from(["xy", "x", "y", "@^", "@", "^"]),
                  _value, _value, _angle, st.none() | _value)


def _fmt(v: float) -> str:
    return f"{v:.3f}"


def _polar_end(mode: str, kind: str, x: float, y: float, a: float, b: float, deg: float):
    """The end point (work X, Y) of a polar line from (x, y): ``@a`` ``^deg``
    as the words of ``kind`` say; None where LinuxCNC would refuse it."""
    if math.hypot(x, y) < NEAR_ORIGIN and not (mode == "G90" and "^" in kind):
        return None
    if mode == "G90":
        r = a if "@" in kind else math.hypot(x, y)
        t = math.radians(deg) if "^" in kind else math.atan2(y, x)
        return r * math.cos(t), r * math.sin(t)
    if "@" in kind:
        r, t = math.hypot(x, y) + a, math.atan2(y, x)
        x, y = r * math.cos(t), r * math.sin(t)
        if "^" in kind and math.hypot(x, y) < NEAR_ORIGIN:
            return None
    if "^" in kind:
        r, t = math.hypot(x, y), math.atan2(y, x) + math.radians(deg)
        x, y = r * math.cos(t), r * math.sin(t)
    return x, y


def _words(kind: str, a: float, b: float, deg: float) -> str:
    parts = {"x": f"X{_fmt(a)}", "y": f"Y{_fmt(b)}", "@": f"@{_fmt(a)}", "^": f"^{_fmt(deg)}"}
    return " ".join(parts[k] for k in kind)


@st.composite
def polar_programs(draw):
    """(text, expected machine end points of its moves)."""
    ox, oy = draw(_value), draw(_value)
    x, y, z = draw(_value), draw(_value), 0.0
    if math.hypot(x, y) < 1.0:
        x += 5.0                                        # start off the origin
    lines = [f"G21 G17 F600\nG10 L2 P1 X{_fmt(ox)} Y{_fmt(oy)}\nG54\n"
             f"G90 G0 X{_fmt(x)} Y{_fmt(y)} Z0"]
    ends = [(x + ox, y + oy, z)]
    for mode, motion, kind, a, b, deg, dz in draw(st.lists(_step, min_size=1, max_size=12)):
        if kind in ("xy", "x", "y"):
            nx = (x + a if mode == "G91" else a) if "x" in kind else x
            ny = (y + b if mode == "G91" else b) if "y" in kind else y
            end = (nx, ny)
        else:
            end = _polar_end(mode, kind, x, y, a, b, deg)
            if end is None:
                continue
        line = f"{mode} {motion} {_words(kind, a, b, deg)}"
        if dz is not None:
            line += f" Z{_fmt(dz)}"
            z = z + dz if mode == "G91" else dz
        (x, y) = end
        lines.append(line)
        ends.append((x + ox, y + oy, z))
    return "\n".join(lines) + "\nM2\n", ends


def _check_ends(program) -> None:
    text, ends = program
    blocks = read_gcode(text, "polar.ngc").blocks
    assert len(blocks) == len(ends), text
    for block, want in zip(blocks, ends):
        assert block.end == pytest.approx(want, abs=1e-9, rel=0), (text, block.source.line)


@pytest.mark.slow
@SLOW
@given(polar_programs())
def test_polar_ends_follow_linuxcncs_rules_generated(program):
    _check_ends(program)


@QUICK
@given(polar_programs())
def test_polar_ends_follow_linuxcncs_rules(program):
    _check_ends(program)


@st.composite
def bolt_circles(draw):
    """(text, start work point, G54 X offset, angle step in degrees, holes)."""
    r = draw(st.integers(500, 50000)) / 1000
    t0 = draw(_angle)
    step = draw(st.integers(1000, 120000)) / 1000 * draw(st.sampled_from([-1, 1]))
    holes = draw(st.integers(1, 12))
    ox = draw(_value)
    x, y = r * math.cos(math.radians(t0)), r * math.sin(math.radians(t0))
    if math.hypot(float(_fmt(x)), float(_fmt(y))) < NEAR_ORIGIN:
        x = 1.0
    text = (f"G21 G17 G90 F100\nG10 L2 P1 X{_fmt(ox)} Y3\nG54\n"
            f"G0 X{_fmt(x)} Y{_fmt(y)} Z5\n"
            f"G91 G81 R-2 Z-3 ^{_fmt(step)} L{holes}\nM2\n")
    return text, (float(_fmt(x)), float(_fmt(y))), ox, step, holes


def _check_bolt_circle(case) -> None:
    text, (x, y), ox, step, holes = case
    prog = read_gcode(text, "holes.ngc")
    drilled = [(b.end[0] - ox, b.end[1] - 3.0) for b in prog.blocks if b.motion is Motion.LINE]
    assert len(drilled) == holes, text
    radius, angle = math.hypot(x, y), math.degrees(math.atan2(y, x))
    for hole in drilled:
        assert math.hypot(*hole) == pytest.approx(radius, abs=1e-9), text
        turned = math.degrees(math.atan2(hole[1], hole[0])) - angle
        assert math.remainder(turned - step, 360.0) == pytest.approx(0.0, abs=1e-7), text
        angle += step


@pytest.mark.slow
@SLOW
@given(bolt_circles())
def test_g91_cycle_turns_drill_a_bolt_circle_generated(case):
    _check_bolt_circle(case)


@QUICK
@given(bolt_circles())
def test_g91_cycle_turns_drill_a_bolt_circle(case):
    _check_bolt_circle(case)
