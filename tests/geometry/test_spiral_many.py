"""``Spiral.many_from_numbers`` of ``spirals_from_polar`` (the spirals of
many moves at once, their lengths worked out together, as the programmed
path's rows make them) makes each spiral ``Spiral.from_points`` makes,
bit for bit: every field and the numbers it keeps beside them (``b``, the
length), over seeded random spirals (growing and shrinking, either way round,
near-full and extra turns), and it refuses what ``from_points`` refuses."""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from ccopt.geometry import Spiral
from ccopt.geometry.primitives import polar_ends
from ccopt.geometry.spiral import spirals_from_polar


def _moves(seed: int, n: int) -> list[tuple]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        c = (rng.uniform(-500, 500), rng.uniform(-500, 500))
        r0 = rng.choice((rng.uniform(0.01, 1.0), rng.uniform(1.0, 200.0)))
        r1 = r0 * (1.0 + rng.choice((1e-8, 1e-4, 0.3)) * rng.choice((-1, 1)))
        a0 = rng.uniform(-math.pi, math.pi)
        a1 = a0 + rng.choice((rng.uniform(-6.3, 6.3), 1e-10, 0.0, rng.uniform(1e-9, 4e-9)))
        s = (c[0] + r0 * math.cos(a0), c[1] + r0 * math.sin(a0))
        e = (c[0] + r1 * math.cos(a1), c[1] + r1 * math.sin(a1))
        out.append((s, e, c, rng.random() < 0.5, rng.choice((0, 0, 0, 1, 3))))
    return out


def _many(moves: list[tuple]) -> list[Spiral]:
    """The spirals of ``moves`` made together."""
    if not moves:
        return []
    s, e, c, ccw, turns = (np.array(col, float) for col in zip(*moves))
    return Spiral.many_from_numbers(c, *spirals_from_polar(*polar_ends(s, e, c),
                                                          ccw.astype(bool), turns))


def _numbers(g: Spiral) -> str:
    return repr((g.center, g.rho0, g.rho1, g.theta0, g.sweep, g.b, g.length))


@pytest.mark.parametrize("seed", range(3))
def test_many_spirals_are_the_spirals_one_by_one(seed):
    moves = _moves(seed, 3000)
    many = _many(moves)
    one = [Spiral.from_points(*m[:4], turns=m[4]) for m in moves]
    assert [_numbers(g) for g in many] == [_numbers(g) for g in one]
    assert many == one and all(type(g) is Spiral for g in many)


def test_refused_as_one_by_one():
    moves = _moves(7, 20)
    s, e, c, ccw, turns = moves[5]
    for bad in ((c, e, c, ccw, turns), ((math.inf, 0.0), e, c, ccw, turns)):
        with pytest.raises(ValueError):
            Spiral.from_points(*bad[:4], turns=bad[4])
        with pytest.raises(ValueError):
            _many(moves[:5] + [bad] + moves[6:])
    assert _many([]) == []
