"""``spiral_bboxes`` and ``spiral_end_tangents`` (the ends, boxes and end
tangents of many spirals at once) give what ``Spiral.start``, ``end``,
``bbox``, ``start_tangent`` and ``end_tangent`` give one by one, bit for bit,
over seeded random spirals: growing, shrinking and circular, either way round,
tiny sweeps, points, full and many turns, start angles on the axes; and the
verifier's ``pack``, ``end_tangents`` and ``lengths`` put those numbers in
their rows."""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from ccopt.geometry import Line, Spiral
from ccopt.geometry.spiral import spiral_bboxes, spiral_end_tangents
from ccopt.verify.segments import KIND_SPIRAL, end_tangents, lengths, pack


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
    ts, te = spiral_end_tangents(*numbers[1:])
    moving = [g.length > 0.0 for g in spirals]
    assert _bits(ts[moving]) == _bits([g.start_tangent for g in spirals if g.length > 0.0])
    assert _bits(te[moving]) == _bits([g.end_tangent for g in spirals if g.length > 0.0])


def test_pack_end_tangents_and_lengths_of_spirals():
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
    ts, te = end_tangents(pk)
    moving = [g.length > 0.0 for g in spirals]
    assert _bits(ts[rows]) == _bits([g.start_tangent if m else (0.0, 0.0)
                                     for g, m in zip(spirals, moving)])
    assert _bits(te[rows]) == _bits([g.end_tangent if m else (0.0, 0.0)
                                     for g, m in zip(spirals, moving)])
    assert _bits(lengths(pk)[rows]) == _bits([g.length for g in spirals])
    assert spiral_bboxes(np.empty((0, 2)), *[np.empty(0)] * 5)[2].shape == (0, 4)
