"""One program, three controller styles: the tool paths differ exactly where the
spec says the styles differ, and nowhere else.

The program (G41, r = 2 from the command line for every style):

* an inside lead-in: (0,-20) -> (0,0) up, then -X (a left turn);
* a sharp outside corner at (-40,0): -X then +Y (90 degrees right);
* a shallow outside corner at (-40,30): +Y then a turn right by atan(0.01),
  0.01 rad (cos 0.99995, above PMAC's break 0.9998; below LinuxCNC's 0.05);
* an outside lead-out at (-39.7,60): a right turn of about 90.6 degrees.

Spec differences:

* lead-in: PMAC and Fagor (inside: as G138) end it at ``P + r*o(t_next)``;
  LinuxCNC goes to ``P + r*n`` (perpendicular to the entry) and then pulls
  that end back to the offsets' intersection;
* sharp outside corner: an arc of radius r about P in all three;
* shallow outside corner: PMAC extends the offsets to their intersection,
  LinuxCNC goes straight on (no arc, no pull-back), Fagor G136 adds an arc;
* outside lead-out: PMAC and Fagor (G139/G136 default) end the last move at
  ``A``, add the arc to ``B`` and go straight to the end point; LinuxCNC goes
  straight from ``A`` to the end point.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.compensate import compensate
from ccopt.program.gcode import read_gcode

R = 2.0
TOL = 1e-9
PROGRAM = """G90 G17 G21 F600
G0 X0 Y-20
G41 D1
G1 X0 Y0
G1 X-40 Y0
G1 X-40 Y30
G1 X-39.7 Y60
G40 G1 X-19.7 Y59.8
"""


def o(t):
    return np.array([-t[1], t[0]])   # left (G41)


def unit(v):
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def meet(A, ta, B, tb):
    w = np.asarray(B) - np.asarray(A)
    s = (w[0] * tb[1] - w[1] * tb[0]) / (ta[0] * tb[1] - ta[1] * tb[0])
    return np.asarray(A) + s * np.asarray(ta)


S, P0, P1, P2, P3, Q = (np.array(p, float) for p in
                         [(0, -20), (0, 0), (-40, 0), (-40, 30), (-39.7, 60), (-19.7, 59.8)])
t0, t1, t2, t3, t4 = (unit(b - a) for a, b in [(S, P0), (P0, P1), (P1, P2), (P2, P3), (P3, Q)])


def L(role, s, e):
    return ("line", role, tuple(s), tuple(e), None, None)


def A(role, c, s, e, sweep):
    return ("arc", role, tuple(s), tuple(e), tuple(c), sweep)


def turn(ti, to):
    return math.atan2(ti[0] * to[1] - ti[1] * to[0], float(np.dot(ti, to)))


# Pieces common to all three styles: the sharp corner at P1.
SHARP = A("corner", P1, P1 + R * o(t1), P1 + R * o(t2), -math.pi / 2)


def expected(style):
    seq = []
    # -- lead-in ----------------------------------------------------------------
    if style == "linuxcnc":
        # entry offset: the line through P0 + r*o(t0) along t0 (x = -2); next
        # offset y = -2: the entry ends at their intersection.
        start1 = meet(P0 + R * o(t0), t0, P0 + R * o(t1), t1)
        assert np.allclose(start1, (-2, -2))
    else:
        start1 = P0 + R * o(t1)                       # (0,-2)
    seq.append(L("lead-in", S, start1))
    seq.append(L("compensated", start1, P1 + R * o(t1)))
    seq.append(SHARP)
    # -- shallow corner at P2 -----------------------------------------------------
    a2, b2 = P2 + R * o(t2), P2 + R * o(t3)
    if style == "pmac":
        x = meet(a2, t2, b2, t3)
        seq += [L("compensated", P1 + R * o(t2), x)]
        start3 = x
    elif style == "linuxcnc":
        seq += [L("compensated", P1 + R * o(t2), a2)]
        start3 = a2
    else:
        seq += [L("compensated", P1 + R * o(t2), a2), A("corner", P2, a2, b2, turn(t2, t3))]
        start3 = b2
    # -- lead-out at P3 -------------------------------------------------------------
    a3, b3 = P3 + R * o(t3), P3 + R * o(t4)
    seq.append(L("compensated", start3, a3))
    if style == "linuxcnc":
        seq.append(L("lead-out", a3, Q))
    else:
        seq += [A("corner", P3, a3, b3, turn(t3, t4)), L("lead-out", b3, Q)]
    return seq


def path_of(style):
    return compensate(read_gcode(PROGRAM, "differ.nc"), style=style, radius=R)


def as_tuples(path):
    out = []
    for s in path.segments:
        if s.role.value == "rapid":
            continue
        d = s.to_json()
        out.append((d["kind"], d["role"], tuple(d["start"]), tuple(d["end"]),
                    tuple(d["center"]) if "center" in d else None, d.get("sweep")))
    return out


def same(a, b) -> bool:
    if a[:2] != b[:2]:
        return False
    for x, y in zip(a[2:], b[2:]):
        if (x is None) != (y is None):
            return False
        if x is not None and not np.allclose(x, y, atol=TOL, rtol=0):
            return False
    return True


@pytest.mark.parametrize("style", ["pmac", "linuxcnc", "fagor"])
def test_each_style_follows_its_rules(style):
    got, want = as_tuples(path_of(style)), expected(style)
    assert [g[:2] for g in got] == [w[:2] for w in want], f"{style}: {got}"
    for i, (g, w) in enumerate(zip(got, want)):
        assert same(g, w), f"{style} segment {i}: {g} != {w}"


def test_the_corner_angles_are_what_the_docstring_says():
    assert turn(t0, t1) == pytest.approx(math.pi / 2)            # inside lead-in (left turn)
    assert turn(t1, t2) == pytest.approx(-math.pi / 2)           # sharp outside
    shallow = -turn(t2, t3)
    assert shallow == pytest.approx(math.atan(0.01)) and shallow < 0.05
    assert math.cos(shallow) > 0.9998                            # PMAC: shallow
    assert -turn(t3, t4) > math.pi / 2                           # outside lead-out


def test_differences_are_exactly_where_the_spec_puts_them():
    p, lc, fa = (as_tuples(path_of(s)) for s in ("pmac", "linuxcnc", "fagor"))
    # lead-in: PMAC == Fagor != LinuxCNC
    assert same(p[0], fa[0]) and not same(p[0], lc[0])
    # the sharp outside corner arc: identical in all three
    for path in (p, lc, fa):
        assert sum(same(seg, SHARP) for seg in path) == 1
    # the shallow corner: three different answers (intersection, straight on, arc)
    shallow_p = p[3][3]
    shallow_lc = lc[3][3]
    shallow_fa = fa[3][3]
    assert not np.allclose(shallow_p, shallow_lc) and not np.allclose(shallow_p, shallow_fa)
    assert [s[0] for s in fa if s[1] == "corner"] == ["arc", "arc", "arc"]
    assert [s[0] for s in p if s[1] == "corner"] == ["arc", "arc"]
    assert [s[0] for s in lc if s[1] == "corner"] == ["arc"]
    # the outside lead-out: PMAC == Fagor (arc, then straight), LinuxCNC straight
    assert same(p[-1], fa[-1]) and same(p[-2], fa[-2])
    assert lc[-1][1] == "lead-out" and not same(lc[-1], p[-1])
