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

The programs are drawn where LinuxCNC compensates them (a tool of diameter
0.5, 1 or 3, never D0 in the offset test; lines at least 6 r long, arcs of
radius at least 2 r + 0.5, turns at the corners of at most 160 degrees), so
that nearly every drawn program checks an offset; each test counts how many
did (:mod:`exercised`) and asserts the share. A refusal counts only where
LinuxCNC refuses too, by its own rule checked here from the program: an entry
arc whose end is within the tool radius of its start (``convert_arc_comp1``:
"Radius of cutter compensation entry arc is not greater than the tool
radius").
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
from ccopt.toolpath import programmed_path
from exercised import assert_share

TOL = 1e-7
#: Drawn programs per test, and the share that must check an offset.
PROGRAMS, D0_PROGRAMS = 300, 60
SHARE = 0.8


@st.composite
def programs(draw, diameters=(0.5, 1.0, 3.0)):
    """G-code text and the tool radius: a rapid, G41.1/G42.1, 2 to 7 lines
    and arcs (the first is the entry move, compensated from its end on), each turning from the last by up to 160 degrees (or tangent),
    G40 and an exit line."""
    n = draw(st.integers(2, 7))
    side = draw(st.sampled_from(["G41.1", "G42.1"]))
    dia = draw(st.sampled_from(diameters))
    r = dia / 2.0
    shortest = max(2.0, 6.0 * r)
    x, y = 0.0, 0.0
    h = draw(st.floats(-math.pi, math.pi))
    turn = st.floats(-2.8, 2.8)
    lines = ["G21 G17 F100", "G0 X0 Y0", f"{side} D{dia}"]
    for i in range(n):
        if i > 0:
            h += draw(st.one_of(st.just(0.0), turn))
        if draw(st.booleans()):
            L = draw(st.floats(shortest, 20))
            x, y = x + L * math.cos(h), y + L * math.sin(h)
            lines.append(f"G1 X{x:.12f} Y{y:.12f}")
        else:
            R = draw(st.floats(2.0 * r + 0.5, 15))
            sweep = draw(st.floats(0.2, 3.0)) * draw(st.sampled_from([1, -1]))
            sg = 1.0 if sweep > 0 else -1.0           # centre left of the heading for G3
            cx, cy = x - sg * R * math.sin(h), y + sg * R * math.cos(h)
            a1 = math.atan2(y - cy, x - cx) + sweep
            ex, ey = cx + R * math.cos(a1), cy + R * math.sin(a1)
            g = "G3" if sweep > 0 else "G2"
            lines.append(f"{g} X{ex:.12f} Y{ey:.12f} I{cx - x:.12f} J{cy - y:.12f}")
            x, y, h = ex, ey, h + sweep
    h += draw(turn)
    L = draw(st.floats(shortest, 20))
    x, y = x + L * math.cos(h), y + L * math.sin(h)
    lines += ["G40", f"G1 X{x:.12f} Y{y:.12f}"]
    return "\n".join(lines) + "\n", r


def linuxcnc_refuses(prog, r: float) -> str | None:
    """Why LinuxCNC itself refuses ``prog``, by the rule checked here from the
    programmed geometry alone, or None: an entry arc (the first move after
    G41.1/G42.1 an arc) whose end is within ``r`` of its start."""
    first = next(b for b in prog.blocks if b.modal.side and b.motion.value != "rapid")
    if first.motion.is_arc and math.dist(first.start[:2], first.end[:2]) <= r:
        return "refused as LinuxCNC does: entry arc chord <= r"
    return None


def _left_of(p0, p1, q) -> float:
    t = np.asarray(p1, float) - np.asarray(p0, float)
    t /= np.hypot(*t)
    w = np.asarray(q, float) - np.asarray(p0, float)
    return float(t[0] * w[1] - t[1] * w[0])


def test_random_programs():
    tally = Counter()

    @settings(max_examples=PROGRAMS, deadline=None,
              suppress_health_check=[HealthCheck.too_slow])
    @given(programs())
    def one(case):
        tally[check_program(*case)] += 1

    one()
    assert_share("linuxcnc offsets", tally, {"offsets checked", *WARRANTED}, SHARE, PROGRAMS)


def test_random_programs_with_d0():
    tally = Counter()

    @settings(max_examples=D0_PROGRAMS, deadline=None,
              suppress_health_check=[HealthCheck.too_slow])
    @given(programs(diameters=(0.0,)))
    def one(case):
        tally[check_program(*case)] += 1

    one()
    assert_share("linuxcnc D0", tally, {"programmed path"}, 1.0, D0_PROGRAMS)


WARRANTED = {"refused as LinuxCNC does: entry arc chord <= r"}


def check_program(text: str, r: float) -> str:
    """Check the properties on one program; what it exercised."""
    prog = read_gcode(text, "rand.ngc")
    try:
        path = compensate(prog, style="linuxcnc")
    except CompensationError as exc:
        assert exc.line is not None and exc.file == "rand.ngc"
        return linuxcnc_refuses(prog, r) or "refused (not checked against LinuxCNC)"
    segs = list(path.segments)
    for a, b in zip(segs, segs[1:]):
        assert math.dist(a.end, b.start) < TOL
    if r == 0.0:
        want = programmed_path(prog).segments
        assert len(segs) == len(want)
        for a, b in zip(segs, want):
            assert a.kind == b.kind
            assert np.allclose([a.start, a.end], [b.start, b.end], atol=TOL, rtol=0)
        return "programmed path"
    k = prog.blocks[2].modal.side
    checked = 0
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
            checked += 1
        elif isinstance(s.geom, Line) and blk.start[:2] != blk.end[:2]:
            assert abs(_left_of(blk.start[:2], blk.end[:2], s.end) - k * r) < TOL
            checked += 1
    return "offsets checked" if checked else "no compensated move"
