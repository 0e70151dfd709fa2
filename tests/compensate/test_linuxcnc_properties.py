"""Properties of the ``linuxcnc`` style on random programs.

* it either returns a tool path or refuses the program with a located
  CompensationError (never another exception);
* the tool path is continuous;
* away from corners it is LinuxCNC's offset: every compensated arc runs about
  its programmed centre at ``R -/+ r`` (``ARC_FEED`` keeps the centre), every
  compensated line ends on its offset line (its end may be pulled back along
  it, never off it), and every corner arc is about a programmed point with
  radius ``r``;
* with ``D0`` (radius 0) the tool path is the programmed path.
"""
from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings, strategies as st

from ccopt.compensate import compensate
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line
from ccopt.program.gcode import read_gcode
from ccopt.toolpath import programmed_path

TOL = 1e-7


@st.composite
def programs(draw):
    """G-code text: a rapid, G41.1/G42.1, random lines and arcs, G40 and an exit."""
    n = draw(st.integers(1, 6))
    side = draw(st.sampled_from(["G41.1", "G42.1"]))
    dia = draw(st.sampled_from([0.0, 0.5, 1.0, 3.0]))
    x, y = 0.0, 0.0
    lines = ["G21 G17 F100", "G0 X0 Y0", f"{side} D{dia}"]
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
    x += draw(st.floats(-20, 20))
    y += draw(st.floats(-20, 20))
    lines += ["G40", f"G1 X{x:.12f} Y{y:.12f}"]
    return "\n".join(lines) + "\n", dia / 2.0


def _left_of(p0, p1, q) -> float:
    t = np.asarray(p1, float) - np.asarray(p0, float)
    t /= np.hypot(*t)
    w = np.asarray(q, float) - np.asarray(p0, float)
    return float(t[0] * w[1] - t[1] * w[0])


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(programs())
def test_random_programs(case):
    text, r = case
    prog = read_gcode(text, "rand.ngc")
    try:
        path = compensate(prog, style="linuxcnc")
    except CompensationError as exc:
        assert exc.line is not None and exc.file == "rand.ngc"
        return
    segs = list(path.segments)
    for a, b in zip(segs, segs[1:]):
        assert math.dist(a.end, b.start) < TOL
    if r == 0.0:
        want = programmed_path(prog).segments
        assert len(segs) == len(want)
        for a, b in zip(segs, want):
            assert a.kind == b.kind
            assert np.allclose([a.start, a.end], [b.start, b.end], atol=TOL, rtol=0)
        return
    k = prog.blocks[2].modal.side
    for s in segs:
        blk = s.block
        if s.role.value == "corner" and isinstance(s.geom, Arc):
            assert abs(s.geom.radius - r) < TOL
            assert min(math.dist(s.geom.center, b.end[:2]) for b in prog.blocks) < TOL
        if s.role.value != "compensated":
            continue
        if blk.motion.is_arc:
            c = blk.center[:2]
            R = math.dist(blk.end[:2], c)
            ccw = blk.motion.value == "ccw"
            want = R - k * r if ccw else R + k * r
            assert math.dist(s.geom.center, c) < TOL
            assert abs(math.dist(s.end, c) - want) < TOL
        elif isinstance(s.geom, Line) and blk.start[:2] != blk.end[:2]:
            assert abs(_left_of(blk.start[:2], blk.end[:2], s.end) - k * r) < TOL
