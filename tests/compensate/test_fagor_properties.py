"""Properties of the ``fagor`` style on random programs (all four G136/G137 x
G138/G139 combinations, lines and arcs, left and right).

* a tool path or a located CompensationError, never another exception;
* the tool path is continuous;
* every compensated line ends on its offset line and every compensated arc
  (not a spiral) ends on its offset circle about the programmed centre;
* corner arcs have radius ``r`` about the programmed corner, and corner lines
  (G137) never come closer than ``r`` to it.

The test counts how many drawn programs checked an offset (:mod:`exercised`)
and asserts the share. A refusal counts only where the program itself shows
it is warranted, checked here from its geometry: a concave arc (the tool
inside it) whose radius is not larger than the tool's, which no tool of that
radius can follow.
"""
from __future__ import annotations

import math
from collections import Counter

import numpy as np
from hypothesis import HealthCheck, given, settings, strategies as st

from ccopt.compensate import compensate
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line
from ccopt.program.gcode import read_gcode
from exercised import assert_share

TOL = 1e-7
#: Drawn programs, and the share that must check an offset.
PROGRAMS = 300
SHARE = 0.8
WARRANTED = "refused: a concave arc of radius <= r"


@st.composite
def programs(draw):
    n = draw(st.integers(1, 6))
    side = draw(st.sampled_from(["G41", "G42"]))
    corner = draw(st.sampled_from(["G136", "G137"]))
    start_end = draw(st.sampled_from(["G138", "G139"]))
    r = draw(st.sampled_from([0.25, 0.5, 1.5]))
    x, y = 0.0, 0.0
    lines = [f"G90 G17 F100 {corner} {start_end}", "G0 X0 Y0", f"{side} D1"]
    x += draw(st.floats(-20, 20).filter(lambda v: abs(v) > 1))
    lines.append(f"G1 X{x:.12f} Y{y:.12f}")
    for _ in range(n):
        if draw(st.booleans()):
            x += draw(st.floats(-20, 20).filter(lambda v: abs(v) > 0.5))
            y += draw(st.floats(-20, 20))
            lines.append(f"G1 X{x:.12f} Y{y:.12f}")
        else:
            R = draw(st.floats(0.5, 15))
            a0 = draw(st.floats(-math.pi, math.pi))
            a1 = a0 + draw(st.floats(0.2, 5.5)) * draw(st.sampled_from([1, -1]))
            cx, cy = x - R * math.cos(a0), y - R * math.sin(a0)
            ex, ey = cx + R * math.cos(a1), cy + R * math.sin(a1)
            g = draw(st.sampled_from(["G2", "G3"]))
            lines.append(f"{g} X{ex:.12f} Y{ey:.12f} I{cx - x:.12f} J{cy - y:.12f}")
            x, y = ex, ey
    x += draw(st.floats(-20, 20).filter(lambda v: abs(v) > 0.5))
    y += draw(st.floats(-20, 20))
    lines.append(f"G40 G1 X{x:.12f} Y{y:.12f}")
    return "\n".join(lines) + "\n", r


def _point_distance(p, geom) -> float:
    p = np.asarray(p, float)
    a, b = np.asarray(geom.start, float), np.asarray(geom.end, float)
    ab = b - a
    L2 = float(np.dot(ab, ab))
    s = 0.0 if L2 == 0 else min(1.0, max(0.0, float(np.dot(p - a, ab)) / L2))
    return float(np.hypot(*(a + s * ab - p)))


def test_random_programs():
    tally = Counter()

    @settings(max_examples=PROGRAMS, deadline=None,
              suppress_health_check=[HealthCheck.too_slow])
    @given(programs())
    def one(case):
        tally[check_program(*case)] += 1

    one()
    assert_share("fagor offsets", tally, {"offsets checked", WARRANTED}, SHARE, PROGRAMS)


def tool_cannot_follow(prog, r: float) -> bool:
    """Whether a compensated arc of ``prog`` has the tool inside it (G41 and
    counter-clockwise, G42 and clockwise) with a radius of at most ``r``
    (within the rounding of the written numbers, 12 decimals)."""
    for b in prog.blocks:
        if b.motion.is_arc and b.modal.side:
            inside = (b.modal.side > 0) == (b.motion.value == "ccw")
            R = min(math.dist(b.start[:2], b.center[:2]), math.dist(b.end[:2], b.center[:2]))
            if inside and R <= r + 1e-9:
                return True
    return False


def check_program(text: str, r: float) -> str:
    """Check the properties on one program; what it exercised."""
    prog = read_gcode(text, "rand.nc")
    try:
        path = compensate(prog, style="fagor", radius=r)
    except CompensationError as exc:
        assert exc.line is not None and exc.file == "rand.nc"
        return WARRANTED if tool_cannot_follow(prog, r) else "refused (not warranted here)"
    segs = list(path.segments)
    for a, b in zip(segs, segs[1:]):
        assert math.dist(a.end, b.start) < TOL
    k = prog.blocks[1].modal.side
    checked = 0
    for s in segs:
        blk = s.block
        P = blk.end[:2]
        if s.role.value == "corner":
            if isinstance(s.geom, Arc):
                assert abs(s.geom.radius - r) < TOL and math.dist(s.geom.center, P) < TOL
            else:
                assert isinstance(s.geom, Line)
                assert _point_distance(P, s.geom) >= r - TOL
        if s.role.value != "compensated" or s.length == 0:
            continue
        if blk.motion.is_arc:
            if s.kind != "arc":
                continue   # a gradual change (inside corner without intersection)
            c = blk.center[:2]
            R = math.dist(blk.end[:2], c)
            want = R - k * r if blk.motion.value == "ccw" else R + k * r
            assert math.dist(s.geom.center, c) < TOL
            assert abs(math.dist(s.end, c) - want) < TOL
        else:
            p0, p1 = np.array(blk.start[:2]), np.array(blk.end[:2])
            t = (p1 - p0) / np.hypot(*(p1 - p0))
            w = np.asarray(s.end) - p0
            assert abs(t[0] * w[1] - t[1] * w[0] - k * r) < TOL
        checked += 1
    return "offsets checked" if checked else "no compensated move checked"
