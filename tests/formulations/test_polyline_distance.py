"""The models' distance to a fine polyline (spirals, Bezier curves) is the exact
distance to that polyline: checked against the closed-form point-to-segment
distance taken piece by piece, on random walks (zero-length pieces included)
and on a dense curve with points near and far."""
from __future__ import annotations

import numpy as np
import pytest

from ccopt.geometry import point_segment
from ccopt_formulations.clearance import PIECE_BLOCK, polyline_distance


def _by_piece(q, p):
    d = np.full(len(p), np.inf)
    for a, b in zip(q[:-1], q[1:]):
        d = np.minimum(d, point_segment(p, a, b)[0])
    return d


@pytest.mark.parametrize("m", [2, 3, PIECE_BLOCK, PIECE_BLOCK + 1, PIECE_BLOCK + 2, 300, 2049])
def test_polyline_distance_is_the_piecewise_minimum(m):
    rng = np.random.default_rng(m)
    q = rng.normal(size=(m, 2)).cumsum(axis=0)
    if m > 6:
        q[5] = q[4]                       # a zero-length piece
    p = np.vstack([rng.normal(size=(400, 2)) * 5, q[::7] + 1e-3 * rng.normal(size=(len(q[::7]), 2))])
    assert np.allclose(polyline_distance(q, p), _by_piece(q, p), rtol=0, atol=1e-12)


def test_polyline_distance_on_a_dense_spiral():
    t = np.linspace(0.0, 6 * np.pi, 2049)
    q = np.c_[(1 + t) * np.cos(t), (1 + t) * np.sin(t)]
    g = np.linspace(-30, 30, 41)
    p = np.array([(x, y) for x in g for y in g])
    assert np.allclose(polyline_distance(q, p), _by_piece(q, p), rtol=0, atol=1e-12)
