"""Injected faults on random compensated closed contours.

A random star-shaped contour (:mod:`random_contours`: lines and arcs bulging
in or out, inside and outside corners, CC1 or CC2, a random radius, a
straight lead-in to the middle of the first edge) is compensated; the
unmodified tool path is clean: nothing may be reported. Then every fully
compensated tool segment and every corner arc, one at a time, is moved by
``10 * eps``:

- inward (toward its programmed element: a line translated along the
  element's normal, an arc's radius changed toward the element's, a corner
  arc's radius shrunk toward its corner point): the gouge check must catch it,
  at that segment, with the depth ``10 * eps``;
- outward (the opposite way): the contact check must fail at that segment
  with the gap ``10 * eps``.

Faults this small are far below the default gouge tolerance (1e-3 mm): the
checks run with ``tolerance=0``, where every violation beyond ``eps`` fails.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from ccopt.compensate import compensate
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, ToolPath
from ccopt.verify import verify
from random_contours import contour_program, contours

EPS = 1e-6
MOVE = 10 * EPS


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


@pytest.mark.slow
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
        inward = verify(with_segment(path, i, moved(path.segments[i], True)), prog, eps=EPS,
                        tolerance=0.0)
        g = [v for v in inward.violations_of("gouge") if v.tool_segment == i]
        assert g, f"inward move of segment {i} ({path.segments[i].role.value}) not caught"
        assert max(v.depth for v in g) == pytest.approx(MOVE, rel=1e-3)
        outward = verify(with_segment(path, i, moved(path.segments[i], False)), prog, eps=EPS,
                         tolerance=0.0)
        c = [v for v in outward.violations_of("contact") if v.tool_segment == i]
        assert c, f"outward move of segment {i} ({path.segments[i].role.value}) kept contact"
        assert c[0].depth == pytest.approx(MOVE, rel=1e-3)
