"""The comparison's deviation (``max_deviation``) over generated pairs of
paths as two controller styles make them of one contour: lines and corner
arcs, the variant offset by up to 3e-4, its lines split elsewhere, a corner
arc turning a little further or less (its next line starting from the arc's
new end). Each pair's Hausdorff distance is measured here by brute force
(points every 1e-4 of arc length, exact distances to the other path's lines
and arcs by their formulas), and the figures must hold it:

* the estimate is a measured distance (at most the true maximum);
* the bound is at least the true maximum, and within ``h / 8`` of the estimate
  (the branch and bound's promise where the targets are lines and arcs).
"""
from __future__ import annotations

import math
import random

import pytest

from brute_distance import one_sided_deviation
from ccopt.compare.figures import max_deviation
from ccopt.geometry import Arc, Line
from ccopt.toolpath import PathSegment, Role, ToolPath

H = 1e-3
SPACING = 1e-4


def _seg(g):
    return PathSegment(g, Role.COMPENSATED, None, 0.0, 0.0, 10.0)


def _contour(rng: random.Random):
    """``[(kind, data)]``: lines ``(p0, p1)`` and corner arcs ``(centre, R, theta0,
    sweep)``, each starting where the last ended, tangent."""
    x, y, heading = 0.0, 0.0, rng.uniform(-math.pi, math.pi)
    out = []
    for _ in range(rng.randint(2, 4)):
        length = rng.uniform(2.0, 10.0)
        x1, y1 = x + length * math.cos(heading), y + length * math.sin(heading)
        out.append(("line", ((x, y), (x1, y1))))
        x, y = x1, y1
        R = rng.uniform(0.5, 5.0)
        turn = rng.choice([-1.0, 1.0]) * rng.uniform(0.2, 2.0)
        side = math.copysign(1.0, turn)          # centre on the left for a left turn
        cx, cy = x - side * R * math.sin(heading), y + side * R * math.cos(heading)
        theta0 = math.atan2(y - cy, x - cx)
        out.append(("arc", ((cx, cy), R, theta0, turn)))
        x, y = cx + R * math.cos(theta0 + turn), cy + R * math.sin(theta0 + turn)
        heading += turn
    return out


def _variant(contour, rng: random.Random):
    """Another style's path of the same contour (module docstring)."""
    e = rng.choice([0.0, rng.uniform(1e-7, 3e-4)]) * rng.choice([-1.0, 1.0])   # left offset
    late = rng.randrange(len(contour) // 2)      # this corner arc turns delta further
    delta = rng.choice([1.0, -1.0]) * rng.uniform(1e-6, 1e-4)
    out, k_arc, start = [], 0, None
    for kind, data in contour:
        if kind == "line":
            (x0, y0), (x1, y1) = data
            L = math.hypot(x1 - x0, y1 - y0)
            nx, ny = -(y1 - y0) / L, (x1 - x0) / L
            a = (x0 + e * nx, y0 + e * ny) if start is None else start
            b = (x1 + e * nx, y1 + e * ny)
            cuts = sorted(rng.uniform(0.05, 0.95) for _ in range(rng.randint(0, 3)))
            pts = [a] + [(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])) for f in cuts] + [b]
            out += [Line(p, q) for p, q in zip(pts, pts[1:])]
            start = None
        else:
            c, R, theta0, sweep = data
            Rv = R - math.copysign(1.0, sweep) * e    # a left offset shrinks a left turn
            extra = delta if k_arc == late else 0.0
            out.append(Arc(c, Rv, theta0, sweep + extra))
            end = theta0 + sweep + extra
            start = (c[0] + Rv * math.cos(end), c[1] + Rv * math.sin(end)) if extra else None
            k_arc += 1
    return out


def _reference(contour):
    return [Line(*d) if kind == "line" else Arc(*d) for kind, d in contour]


def _check(seed: int) -> None:
    rng = random.Random(seed)
    contour = _contour(rng)
    ref, var = _reference(contour), _variant(contour, rng)
    truth = max(one_sided_deviation(var, ref, SPACING), one_sided_deviation(ref, var, SPACING))   # sampled: within SPACING below
    est, bound = max_deviation(ToolPath(tuple(map(_seg, var))), ToolPath(tuple(map(_seg, ref))),
                               H)
    assert est <= truth + SPACING + 1e-12, (seed, est, truth)
    assert bound >= truth - 1e-12, (seed, bound, truth)
    assert bound <= est + H / 8 + 1e-9, (seed, est, bound)


@pytest.mark.parametrize("seed", range(4))
def test_deviation_of_generated_style_pairs_quick(seed):
    _check(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 104))
def test_deviation_of_generated_style_pairs(seed):
    _check(seed)
