"""Bezier curves evaluated together (BezierBatch) against each curve alone,
and the arc-length inversion against an independent quadrature."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from ccopt.feed.path import ExactPath
from ccopt.geometry import Line
from ccopt.geometry.bezier_arclength import ARC_LENGTH_REL_TOL
from ccopt.geometry.bezier_batch import BezierBatch
from ccopt.geometry.curve import BezierCurve
from ccopt.toolpath import PathSegment, Role, ToolPath


def curves(seed: int, n: int, degree: int):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        steps = rng.uniform(0.2, 2.0, (degree + 1, 2)) * [1.0, rng.choice([-1.0, 1.0])]
        out.append(BezierCurve(tuple(map(tuple, np.cumsum(steps, axis=0)))))
    return out


def speed(c: BezierCurve, t: float) -> float:
    """|r'(t)| from de Casteljau on the hodograph's control points."""
    n = c.degree
    P = np.diff(np.asarray(c.control_points, float), axis=0) * n
    while len(P) > 1:
        P = (1.0 - t) * P[:-1] + t * P[1:]
    return float(np.hypot(*P[0]))


@pytest.mark.parametrize("degree", [3, 5, 7])
def test_batch_gives_each_curves_own_points_and_derivatives(degree):
    cs = curves(degree, 12, degree)
    batch = BezierBatch(cs)
    rng = np.random.default_rng(1)
    c = rng.integers(0, len(cs), 500)
    L = np.array([g.length for g in cs])
    s = rng.uniform(0.0, 1.0, 500) * L[c]
    s[:12], c[:12] = 0.0, np.arange(12)                # both ends of every curve exactly
    s[12:24], c[12:24] = L, np.arange(12)
    t = batch.t_of_s(c, s)
    got = batch.at("P", c, t)
    for k, g in enumerate(cs):
        m = c == k
        scale = max(1.0, float(np.abs(g.control_points).max()))
        assert np.allclose(got[m], g.point(s[m]), rtol=0, atol=1e-13 * scale)
        r1, r2, r3 = batch.derivatives(c[m], t[m], 3)
        assert np.allclose(r1 / np.hypot(*r1.T)[:, None], g.tangent(s[m]), rtol=0, atol=1e-13)
    assert np.array_equal(got[:12], np.array([g.control_points[0] for g in cs]))
    assert np.array_equal(got[12:24], np.array([g.control_points[-1] for g in cs]))


def test_inversion_meets_its_arc_length_bound_by_quadrature():
    cs = curves(11, 6, 7)
    batch = BezierBatch(cs)
    c = np.repeat(np.arange(6), 5)
    s = np.tile(np.linspace(0.1, 0.9, 5), 6) * np.array([g.length for g in cs])[c]
    t = batch.t_of_s(c, s)
    for k, (ck, sk, tk) in enumerate(zip(c, s, t)):
        g = cs[ck]
        along = quad(lambda u: speed(g, u), 0.0, tk, epsabs=1e-13, epsrel=1e-13, limit=200)[0]
        assert abs(along - sk) <= 10 * ARC_LENGTH_REL_TOL * g.length + 1e-13


def test_one_degree_per_batch():
    with pytest.raises(ValueError, match="one degree"):
        BezierBatch(curves(0, 1, 3) + curves(0, 1, 5))


def test_exact_path_evaluates_its_bezier_segments_as_the_curves_do():
    # lines and Bezier curves of two degrees, end to end
    a, b = curves(3, 1, 5)[0], curves(4, 1, 7)[0]
    shift = np.subtract(a.end, b.start)
    b = BezierCurve(tuple(map(tuple, np.asarray(b.control_points) + shift)))
    segs = [Line((a.start[0] - 1.0, a.start[1]), a.start), a, b,
            Line(b.end, (b.end[0] + 2.0, b.end[1]))]
    path = ExactPath(ToolPath(tuple(PathSegment(g, Role.COMPENSATED, None, feed=10.0)
                                    for g in segs), radius=0.5))
    s = np.linspace(0.0, path.length, 801)
    k = path.locate(s)
    for order, method in ((0, "point"), (1, "d1"), (2, "d2"), (3, "d3")):
        q = path.eval_segments(k, s, order)
        for i, g in enumerate(segs):
            m = k == i
            if isinstance(g, BezierCurve) and m.any():
                ref = getattr(g, method)(s[m] - path.offsets[i])
                assert np.allclose(q[m], ref, rtol=1e-12, atol=1e-12), (order, i)


@pytest.mark.parametrize("seed", range(3))
def test_each_point_finds_its_arc_length_piece(seed):
    # plain curves and a wiggly one with more arc-length knots, so rows of
    # different knot counts (padded with +inf); points on knots exactly, just
    # below them, at both ends and between: the count of a row's knots at or
    # below s, by definition
    cs = curves(30 + seed, 9, 7)
    cs += [BezierCurve(((0, 0), (1, 0), (2, 3), (3, -3), (4, 5), (5, 0.001), (1, 1), (0, 9)))]
    batch = BezierBatch(cs)
    assert len(set(batch.last_piece.tolist())) > 1          # rows padded differently
    rng = np.random.default_rng(seed)
    c = rng.integers(0, len(cs), 3000)
    width = batch.knots_s.shape[1]
    k = rng.integers(0, width, c.size)
    s = np.where(np.isfinite(batch.knots_s[c, k]), batch.knots_s[c, k], batch.length[c])
    s[::3] = rng.uniform(0.0, 1.0, s[::3].size) * batch.length[c[::3]]
    s[1::7] = np.nextafter(s[1::7], -np.inf)
    want = np.count_nonzero(batch.knots_s[c] <= s[:, None], axis=1)
    assert np.array_equal(batch._knots_at_or_below(c, s), want)
