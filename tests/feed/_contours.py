"""Random compensated contours for the feed tests (programs built in memory)."""
from __future__ import annotations

import math

import numpy as np

from ccopt.program.model import Block, Modal, Motion, Program, Source


def _block(line, motion, s, e, k, r, feed, center=None):
    return Block(Source("<random>", line, 1), motion, tuple(s), tuple(e), Modal(side=k, radius=r),
                 center=None if center is None else (center[0], center[1], e[2]), feed=feed)


def contour_program(rng: np.random.Generator, n: int | None = None, scale: float = 30.0,
                    plunge: bool = True) -> Program:
    """A star-shaped closed contour (lines and arcs bulging in or out, random
    feeds), reached by a rapid and a Z plunge, cut with CC1 or CC2, left by a
    lead-out and a retract."""
    n = int(rng.integers(4, 9)) if n is None else n
    gaps = rng.uniform(0.6, 1.4, n)
    angles = np.cumsum(np.r_[0.0, gaps[:-1] / gaps.sum() * 2 * math.pi])
    radii = rng.uniform(0.7, 1.0, n) * scale
    pts = [(rad * math.cos(a), rad * math.sin(a)) for rad, a in zip(radii, angles)]
    bulges = np.where(rng.random(n) < 0.4, 0.0, rng.uniform(-0.25, 0.25, n))
    r = float(rng.uniform(0.02, 0.08) * scale)
    k = int(rng.choice([1, -1]))
    z0, z1 = 5.0, -float(rng.uniform(1.0, 4.0))
    feeds = rng.uniform(10.0, 80.0, n + 2)
    blocks, line = [], 1
    start = (0.0, 0.0)
    if plunge:
        blocks.append(_block(line, Motion.RAPID, (0.0, 0.0, 0.0), (*start, z0), 0, r, None)); line += 1
        blocks.append(_block(line, Motion.LINE, (*start, z0), (*start, z1), 0, r, feeds[0])); line += 1
        z = z1
    else:
        z = 0.0
    blocks.append(_block(line, Motion.LINE, (*start, z), (*pts[0], z), k, r, feeds[0])); line += 1
    for i in range(n):
        p, q = pts[i], pts[(i + 1) % n]
        b = bulges[i]
        if abs(b) < 1e-3:
            blocks.append(_block(line, Motion.LINE, (*p, z), (*q, z), k, r, feeds[i + 1]))
        else:
            half = math.dist(p, q) / 2
            sag = abs(b) * half
            R = (half ** 2 + sag ** 2) / (2 * sag)
            m = ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
            t = ((q[0] - p[0]) / (2 * half), (q[1] - p[1]) / (2 * half))
            left = (-t[1], t[0])
            side = 1.0 if b > 0 else -1.0
            c = (m[0] + side * (R - sag) * left[0], m[1] + side * (R - sag) * left[1])
            motion = Motion.ARC_CCW if b > 0 else Motion.ARC_CW
            blocks.append(_block(line, motion, (*p, z), (*q, z), k, r, feeds[i + 1], c))
        line += 1
    blocks.append(_block(line, Motion.LINE, (*pts[0], z), (*start, z), 0, r, feeds[-1])); line += 1
    if plunge:
        blocks.append(_block(line, Motion.LINE, (*start, z), (*start, z0), 0, r, feeds[-1]))
    return Program(tuple(blocks), "<random>", "pmac")


def random_limits(rng: np.random.Generator):
    from ccopt.feed import AxisLimits
    v = rng.uniform(40.0, 150.0, 3)
    a = rng.uniform(200.0, 3000.0, 3)
    v[2] *= 0.3
    a[2] *= 0.3
    return AxisLimits(v=tuple(v), a=tuple(a))
