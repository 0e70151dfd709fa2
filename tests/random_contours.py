"""Random closed contours with a clean lead-in and lead-out, for the verifier's tests.

A star-shaped polygon round the origin (counter-clockwise, 5 to 10 vertices at
radius 40..60), each edge a line or an arc bulging in or out (inside and
outside corners), cut with CC1 or CC2 and a radius 0.3..2. The lead-in comes
straight along the normal of the first edge's middle from the tool side and
the lead-out leaves the same way, so PMAC's constructions make a clean tool
path (no lead-in corner cuts the closing edge).

:func:`hard_contours` draws the same kind of contour with the tool near the
size of its features: on one to three edges a short feature (a line or an
arc of 0.7 to 2.5 tool radii, or two such moves, each bent by up to 145
degrees from the move before) between two moves along it, so there are moves shorter than the tool, tight concave
arcs the tool does not fit (radius at or below its own), and inside corners
whose offsets do not meet (PMAC's no-intersection rule).
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


@st.composite
def hard_contours(draw, smallest_arc: float = 0.7):
    """``(pts, bulges, r, k)`` as :func:`contours`, the tool near feature size:
    a star-shaped polygon of 4 to 7 vertices at radius 20..35, a radius
    0.5..3, and on one to three edges (never the first, which the lead-in
    meets) a short feature: the edge ``p -> q`` becomes ``p -> a -> b -> q``
    or ``p -> a -> b -> b' -> q``, with ``a`` 30..60 % along it and each of
    ``b``, ``b'`` the end of a short move whose chord turns up to 145 degrees
    from the one before: a line of 0.3..4 radii, or an arc of radius 0.7..2.5
    tool radii over 0.3 rad to a half circle, bulging either way or (half of
    the arcs) concave for the tool after a turn toward it. ``smallest_arc``:
    the short arcs' least radius in tool radii (above 1: the tool fits every
    arc, so every contour compensates)."""
    n = draw(st.integers(4, 7))
    gaps = draw(st.lists(st.floats(0.6, 1.4), min_size=n, max_size=n))
    total = sum(gaps)
    angles = np.cumsum([0.0] + [g / total * 2 * math.pi for g in gaps[:-1]])
    radii = draw(st.lists(st.floats(20.0, 35.0), min_size=n, max_size=n))
    corners = [(rad * math.cos(a), rad * math.sin(a)) for rad, a in zip(radii, angles)]
    r = draw(st.floats(0.5, 3.0))
    k = draw(st.sampled_from([1, -1]))
    featured = set(draw(st.lists(st.integers(1, n - 1), min_size=1, max_size=3)))
    pts, bulges = [], []
    for i in range(n):
        p, q = corners[i], corners[(i + 1) % n]
        if i not in featured:
            pts.append(p)
            bulges.append(0.0 if i == 0 else draw(st.one_of(
                st.just(0.0), st.floats(-0.25, -0.05), st.floats(0.05, 0.25))))
            continue
        L = math.dist(p, q)
        d = ((q[0] - p[0]) / L, (q[1] - p[1]) / L)
        u = draw(st.floats(0.3, 0.6))
        a = (p[0] + u * L * d[0], p[1] + u * L * d[1])
        pts += [p, a]
        bulges.append(0.0)
        heading = d
        for _ in range(draw(st.integers(1, 2))):
            if draw(st.booleans()):
                phi, c, bulge = draw(st.floats(-2.53, 2.53)), draw(st.floats(0.3, 4.0)) * r, 0.0
            else:
                # an arc of radius 0.7 (smallest_arc)..2.5 r over 0.3 rad to a half circle; half of
                # them concave for the tool after a turn toward it of 0.2..2.5 rad (its
                # start tangent turns by phi minus half its angle), where the offsets
                # of a line before it miss its offset circle when R (1 + cos turn) < 2 r
                R = draw(st.floats(smallest_arc, 2.5)) * r
                alpha = draw(st.floats(0.3, math.pi))
                c = 2.0 * R * math.sin(alpha / 2.0)
                if draw(st.booleans()):
                    sign = float(k)
                    phi = sign * (alpha / 2.0 + draw(st.floats(0.2, 2.5)))
                else:
                    sign = draw(st.sampled_from([1.0, -1.0]))
                    phi = draw(st.floats(-2.53, 2.53))
                bulge = sign * math.tan(alpha / 4.0)
            heading = (heading[0] * math.cos(phi) - heading[1] * math.sin(phi),
                       heading[0] * math.sin(phi) + heading[1] * math.cos(phi))
            a = (a[0] + c * heading[0], a[1] + c * heading[1])
            pts.append(a)
            bulges.append(bulge)
        bulges.append(0.0)
    return pts, bulges, r, k
