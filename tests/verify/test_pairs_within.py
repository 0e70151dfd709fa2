"""Points within ``eps`` of each other (:func:`ccopt.verify.surface.pairs_within`,
issue 34): the same pairs as ``scipy.spatial.cKDTree.query_pairs``, which the
closed-loop rule used before, over generated point sets: contour vertices,
points placed just inside and just outside ``eps`` of others (the boundary),
repeated points, mirrored contours (many equal x), and points crowded along
a vertical line (where the sweep hands over to the tree)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from ccopt.verify.surface import pairs_within

EPS = 1e-6


def _as_set(pairs) -> set:
    return {(min(int(p), int(q)), max(int(p), int(q))) for p, q in np.asarray(pairs).reshape(-1, 2)}


def _points(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    kind = seed % 5
    n = int(rng.integers(2, 400))
    if kind == 0:          # a wavy closed contour, back to its start
        t = np.linspace(0, 2 * np.pi, n)
        r = 50 + rng.uniform(-1, 1) * np.sin(rng.integers(2, 9) * t)
        pts = np.c_[r * np.cos(t), r * np.sin(t)]
    elif kind == 1:        # mirrored: every x twice
        half = rng.uniform(-100, 100, (n // 2 + 1, 2))
        pts = np.r_[half, half * [1, -1]]
    elif kind == 2:        # a vertical line of points, a few within eps of each
        pts = np.c_[np.full(n, 3.0), np.cumsum(rng.uniform(0, 3 * EPS, n))]
    elif kind == 3:        # crowded: dozens within eps of each (the tree takes over)
        pts = np.c_[np.full(n, -7.0) + rng.choice([0.0, EPS / 3], n),
                    np.cumsum(rng.uniform(0, EPS / 20, n))]
    else:                  # random, with neighbours placed about eps away
        pts = rng.uniform(-100, 100, (n, 2))
        m = int(rng.integers(1, n + 1))
        src = pts[rng.integers(0, n, m)]
        ang = rng.uniform(0, 2 * np.pi, m)
        d = EPS * (1 + rng.choice([-1e-12, -1e-16, 0.0, 1e-16, 1e-12, 0.5, -0.5], m))
        pts = np.r_[pts, src + d[:, None] * np.c_[np.cos(ang), np.sin(ang)], src[: m // 3]]
    return rng.permutation(pts)


@pytest.mark.parametrize("seed", [*range(20),
                                  *(pytest.param(k, marks=pytest.mark.slow) for k in range(20, 300))])
def test_pairs_within_equal_the_k_d_trees(seed):
    pts = _points(seed)
    want = _as_set(cKDTree(pts).query_pairs(EPS, output_type="ndarray"))
    assert _as_set(pairs_within(pts, EPS)) == want


def test_the_pairs_worked_by_hand():
    pts = np.array([[0.0, 0.0], [EPS, 0.0], [0.0, 2 * EPS], [0.0, 0.0], [5.0, 5.0]])
    # (0, 1) exactly eps apart, (0, 3) the same point, (1, 3) eps, (0, 2) 2 eps
    assert _as_set(pairs_within(pts, EPS)) == {(0, 1), (0, 3), (1, 3)}
    assert pairs_within(pts[:1], EPS).shape == (0, 2)
