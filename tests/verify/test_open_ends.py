"""The open ends of the clearance check for many pairs at once
(:func:`ccopt.verify.open_ends.open_end_distances`) are the pair-by-pair
:func:`~ccopt.verify.clearance.clipped_distance` and
:func:`~ccopt.verify.clearance.tapered_pair` to the last bit: on generated
(seeded) lines and arcs with open starts, ends or both, and tool lines and
arcs about their ends, some of them laid along an end's normal."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from ccopt.geometry import Arc, Line
from ccopt.verify.clearance import clipped_distance, end_regions, end_tapers, tapered_pair
from ccopt.verify.open_ends import open_end_distances
from ccopt.verify.segments import pack


def element(rng):
    if rng.random() < 0.5:
        return Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2)))
    return Arc(tuple(rng.uniform(-3, 3, 2)), rng.uniform(0.5, 4), rng.uniform(-math.pi, math.pi),
               rng.choice([-1, 1]) * rng.uniform(0.1, 1.9 * math.pi))


def tool_about(rng, g, side: float):
    """A tool line or arc near one of ``g``'s ends (along its normal there, at times)."""
    P = np.asarray(g.start if rng.random() < 0.5 else g.end)
    kind = rng.random()
    if kind < 0.2:                      # along the end's normal, on either side
        t = np.asarray(g.start_tangent if np.array_equal(P, g.start) else g.end_tangent)
        n = side * np.array([-t[1], t[0]])
        r0, r1 = rng.uniform(-1, 3, 2)
        return Line(tuple(P + r0 * n), tuple(P + r1 * n))
    if kind < 0.6:
        return Line(tuple(P + rng.uniform(-3, 3, 2)), tuple(P + rng.uniform(-3, 3, 2)))
    return Arc(tuple(P + rng.uniform(-2, 2, 2)), rng.uniform(0.3, 3),
               rng.uniform(-math.pi, math.pi), rng.choice([-1, 1]) * rng.uniform(0.05, 2 * math.pi))


def bits(v) -> bytes:
    return np.asarray(v, np.float64).tobytes()


@pytest.mark.parametrize("seed", range(3))
def test_batch_is_pair_by_pair(seed):
    rng = np.random.default_rng(seed)
    m = 80
    elems = [element(rng) for _ in range(m)]
    ends = rng.integers(1, 4, m)                       # 1 start, 2 end, 3 both open
    start, end = (ends & 1) > 0, (ends & 2) > 0
    side = rng.choice([-1.0, 1.0], m)
    tools = [tool_about(rng, g, s) for g, s in zip(elems, side)]
    E, T = pack(elems), pack(tools)
    idx = np.arange(m)
    got = open_end_distances(T, E, idx, idx, start, end, side)
    assert got.done.all()
    contour = SimpleNamespace(elements=E, open_start=start, open_end=end, side=side)
    tapered = 0
    for k in range(m):
        regions = end_regions(E, k, bool(start[k]), bool(end[k]))
        d, wt, we = clipped_distance(T.geom(k), E.geom(k), regions)
        assert bits(got.d[k]) == bits(d), k
        if wt is not None:
            assert bits(got.wt[k]) + bits(got.we[k]) == bits(wt) + bits(we), k
        f, wf, at = tapered_pair(T.geom(k), regions, end_tapers(contour, k))
        assert bits(got.f[k]) == bits(f), k
        if wf is not None:
            assert bits(got.wf[k]) + bits(got.end[k]) == bits(wf) + bits(at), k
            tapered += 1
    assert tapered > m // 4                            # the taper is exercised
