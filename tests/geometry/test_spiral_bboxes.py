"""``spiral_bboxes`` (the ends and boxes of many spirals at once) gives what
``Spiral.start``, ``Spiral.end`` and ``Spiral.bbox`` give one by one, bit for
bit, over seeded random spirals: growing, shrinking and circular, either way
round, tiny sweeps, points, full and many turns, start angles on the axes;
and the verifier's ``pack`` puts those numbers in its rows."""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from ccopt.geometry import Line, Spiral
from ccopt.geometry.spiral import spiral_bboxes
from ccopt.verify.segments import KIND_SPIRAL, pack


def _spirals(seed: int, n: int) -> list[Spiral]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        c = (rng.uniform(-500, 500), rng.uniform(-500, 500))
        r0 = rng.choice((rng.uniform(1e-3, 1.0), rng.uniform(1.0, 200.0)))
        grow = rng.choice((1e-12, 1e-6, 1e-2, 0.5, 3.0)) * rng.choice((-0.25, 0.25))
        r1 = rng.choice((r0, r0 * (1.0 + grow)))
        th0 = rng.choice((rng.uniform(-math.pi, math.pi), rng.uniform(-30.0, 30.0),
                          rng.choice((0.0, -0.0, 0.5 * math.pi, math.pi, -0.5 * math.pi))))
        sweep = rng.choice((rng.uniform(-7.0, 7.0), rng.uniform(-1e-6, 1e-6),
                            rng.uniform(-40.0, 40.0), rng.choice((1.0, -1.0)) * 2.0 * math.pi,
                            0.5 * math.pi))
        if rng.random() < 0.05:
            sweep, r1 = rng.choice((0.0, -0.0)), r0
        out.append(Spiral(c, r0, r1, th0, sweep))
    return out


def _bits(a) -> list:
    return np.asarray(a, float).view(np.int64).tolist()


@pytest.mark.parametrize("seed", range(3))
def test_boxes_are_each_spirals_bbox(seed):
    spirals = _spirals(seed, 3000)
    numbers = [np.array([getattr(g, f) for g in spirals])
               for f in ("center", "rho0", "rho1", "theta0", "sweep", "b")]
    start, end, box = spiral_bboxes(*numbers)
    assert _bits(start) == _bits([g.start for g in spirals])
    assert _bits(end) == _bits([g.end for g in spirals])
    assert _bits(box) == _bits([g.bbox() for g in spirals])


def test_pack_rows_of_spirals():
    spirals = _spirals(9, 400)
    geoms = [g for s in spirals for g in (s, Line((0.0, 0.0), (1.0, 2.0)))]
    pk = pack(geoms)
    rows = np.arange(0, len(geoms), 2)
    assert (pk.arr.kind[rows] == KIND_SPIRAL).all()
    assert _bits(pk.bbox[rows]) == _bits([g.bbox() for g in spirals])
    assert _bits(pk.arr.p0[rows]) == _bits([g.start for g in spirals])
    assert _bits(pk.arr.p1[rows]) == _bits([g.end for g in spirals])
    assert _bits(pk.arr.radius_end[rows]) == _bits([g.rho1 for g in spirals])
    assert _bits(pk.arr.sweep[rows]) == _bits([g.sweep for g in spirals])
    assert spiral_bboxes(np.empty((0, 2)), *[np.empty(0)] * 5)[2].shape == (0, 4)
