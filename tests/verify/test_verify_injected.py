"""Injected faults on random compensated closed contours.

A random star-shaped contour (lines and arcs bulging in or out, inside and
outside corners) is cut with CC1 or CC2 and a random radius. The lead-in
comes straight along the normal of the first edge's middle from the tool
side and the lead-out leaves the same way, so the unmodified tool path is
clean: nothing may be reported. Then every fully compensated tool segment
and every corner arc, one at a time, is moved by ``10 * eps``:

- inward (toward its programmed element: a line translated along the
  element's normal, an arc's radius changed toward the element's, a corner
  arc's radius shrunk toward its corner point): the gouge check must catch it,
  at that segment, with the depth ``10 * eps``;
- outward (the opposite way): the contact check must fail at that segment
  with the gap ``10 * eps``.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from ccopt.compensate import compensate
from ccopt.geometry import Arc, Line
from ccopt.program.model import Block, Modal, Motion, Program, Source
from ccopt.toolpath import Role, ToolPath
from ccopt.verify import verify

EPS = 1e-6
MOVE = 10 * EPS


def _block(line, motion, s, e, k, r, center=None):
    return Block(Source("<random>", line, 1), motion, (s[0], s[1], 0.0), (e[0], e[1], 0.0),
                 Modal(side=k, radius=r),
                 center=None if center is None else (center[0], center[1], 0.0), feed=10.0)


def _arc_block(line, p, q, b, k, r):
    """Arc from p to q with sagitta b * half chord; b > 0 bulges right of p->q."""
    half = math.dist(p, q) / 2
    sag = abs(b) * half
    R = (half ** 2 + sag ** 2) / (2 * sag)
    m = ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
    t = ((q[0] - p[0]) / (2 * half), (q[1] - p[1]) / (2 * half))
    left = (-t[1], t[0])
    side = 1.0 if b > 0 else -1.0
    c = (m[0] + side * (R - sag) * left[0], m[1] + side * (R - sag) * left[1])
    motion = Motion.ARC_CCW if b > 0 else Motion.ARC_CW
    return _block(line, motion, p, q, k, r, c)


@st.composite
def contours(draw):
    n = draw(st.integers(5, 10))
    gaps = draw(st.lists(st.floats(0.6, 1.4), min_size=n, max_size=n))
    total = sum(gaps)
    angles = np.cumsum([0.0] + [g / total * 2 * math.pi for g in gaps[:-1]])
    radii = draw(st.lists(st.floats(40.0, 60.0), min_size=n, max_size=n))
    pts = [(rad * math.cos(a), rad * math.sin(a)) for rad, a in zip(radii, angles)]
    bulges = draw(st.lists(st.one_of(st.just(0.0), st.floats(-0.25, -0.05), st.floats(0.05, 0.25)),
                           min_size=n, max_size=n))
    bulges[0] = 0.0                      # the lead-in meets the first edge, a line
    r = draw(st.floats(0.3, 2.0))
    k = draw(st.sampled_from([1, -1]))
    return pts, bulges, r, k


def contour_program(pts, bulges, r, k) -> Program:
    """Lead-in along the first edge's normal from the tool side to its middle,
    the closed contour from there round to the middle again, lead-out back."""
    n = len(pts)
    p0, p1 = pts[0], pts[1]
    mid = ((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2)
    L = math.dist(p0, p1)
    t = ((p1[0] - p0[0]) / L, (p1[1] - p0[1]) / L)
    o = (-k * t[1], k * t[0])             # the tool side
    start = (mid[0] + (r + 5) * o[0], mid[1] + (r + 5) * o[1])
    blocks = [_block(1, Motion.LINE, start, mid, k, r), _block(2, Motion.LINE, mid, p1, k, r)]
    line = 3
    for i in range(1, n):
        p, q = pts[i], pts[(i + 1) % n]
        if bulges[i] == 0.0:
            blocks.append(_block(line, Motion.LINE, p, q, k, r))
        else:
            blocks.append(_arc_block(line, p, q, bulges[i], k, r))
        line += 1
    blocks.append(_block(line, Motion.LINE, p0, mid, k, r))
    blocks.append(_block(line + 1, Motion.LINE, mid, start, 0, r))
    return Program(tuple(blocks), "<random>", "pmac")


def moved(seg, toward_element: bool):
    """The segment moved by MOVE toward (or away from) its programmed element."""
    g = seg.geom
    sgn = 1.0 if toward_element else -1.0
    blk = seg.block
    if seg.role is Role.CORNER:
        # arc of radius r about the corner point: toward it is a smaller radius
        return replace(seg, geom=Arc(g.center, g.radius - sgn * MOVE, g.theta0, g.sweep))
    if isinstance(g, Line):
        (a, b) = blk.start[:2], blk.end[:2]
        d = np.subtract(b, a) / math.dist(a, b)
        n = np.array([-d[1], d[0]])
        side = np.sign(np.dot(np.subtract(g.p0, a), n))          # tool side of the element
        shift = -side * sgn * MOVE * n
        return replace(seg, geom=Line(tuple(np.add(g.p0, shift)), tuple(np.add(g.p1, shift))))
    R_e = math.dist(blk.start[:2], blk.center[:2])
    toward = math.copysign(1.0, R_e - g.radius)
    return replace(seg, geom=Arc(g.center, g.radius + sgn * toward * MOVE, g.theta0, g.sweep))


def with_segment(path: ToolPath, i: int, seg) -> ToolPath:
    segs = list(path.segments)
    segs[i] = seg
    return replace(path, segments=tuple(segs))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(contours())
def test_injected_faults_are_caught(data):
    pts, bulges, r, k = data
    prog = contour_program(pts, bulges, r, k)
    path = compensate(prog, "pmac")
    clean = verify(path, prog, eps=EPS)
    assert clean.ok, clean.summary()
    assert clean.violations == ()
    # the tool touches the contour all round: the smallest clearance is r
    assert clean.min_clearance == pytest.approx(r, abs=1e-9)
    targets = [i for i, s in enumerate(path.segments)
               if s.role in (Role.COMPENSATED, Role.CORNER) and s.length > 0]
    assert targets
    for i in targets:
        inward = verify(with_segment(path, i, moved(path.segments[i], True)), prog, eps=EPS)
        g = [v for v in inward.violations_of("gouge") if v.tool_segment == i]
        assert g, f"inward move of segment {i} ({path.segments[i].role.value}) not caught"
        assert max(v.depth for v in g) == pytest.approx(MOVE, rel=1e-3)
        outward = verify(with_segment(path, i, moved(path.segments[i], False)), prog, eps=EPS)
        c = [v for v in outward.violations_of("contact") if v.tool_segment == i]
        assert c, f"outward move of segment {i} ({path.segments[i].role.value}) kept contact"
        assert c[0].depth == pytest.approx(MOVE, rel=1e-3)
