"""Random closed contours with a clean lead-in and lead-out, for the verifier's tests.

A star-shaped polygon round the origin (counter-clockwise, 5 to 10 vertices at
radius 40..60), each edge a line or an arc bulging in or out (inside and
outside corners), cut with CC1 or CC2 and a radius 0.3..2. The lead-in comes
straight along the normal of the first edge's middle from the tool side and
the lead-out leaves the same way, so PMAC's constructions make a clean tool
path (no lead-in corner cuts the closing edge).
"""
from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from ccopt.program.model import Block, Modal, Motion, Program, Source


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
    """``(pts, bulges, r, k)``: vertices, per-edge bulge, radius, side."""
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
