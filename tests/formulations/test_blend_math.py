"""The Bezier helpers and clearance cases the blend models are built on."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from ccopt.geometry import Arc, BezierCurve, Line
from ccopt.geometry.bezier import (_interval_at, g2_end, g2_start, jerk_gram,
                                   path_acceleration_interval, speed_profile_time)
from ccopt.geometry.curve import bernstein, subdivision_matrix
from ccopt_formulations.clearance import CONCAVE, CONVEX, END, LINE, Element, classify, linear_rows


@settings(max_examples=40, deadline=None)
@given(st.floats(-0.5, 0.5), st.floats(0.2, 3.0), st.floats(-1.0, 1.0),
       st.floats(-0.5, 0.5), st.floats(0.2, 3.0), st.floats(0, 2 * math.pi),
       st.sampled_from([5, 7]))
def test_g2_end_conditions(k0, a0, e0, k1, a1, phi, n):
    t0 = np.array([math.cos(phi), math.sin(phi)])
    t1 = np.array([math.cos(phi + 1.0), math.sin(phi + 1.0)])
    start = g2_start((0.0, 0.0), t0, k0, a0, e0, n)
    end = g2_end((10.0, 3.0), t1, k1, a1, -e0, n)
    mid = [np.array([3.0 + i, 5.0 - i]) for i in range(n - 5)]
    P = np.vstack([start, *mid, end])
    c = BezierCurve(P)
    assert np.allclose(c.start_tangent, t0, atol=1e-9)
    assert np.allclose(c.end_tangent, t1, atol=1e-9)
    assert c.curvature(0.0) == pytest.approx(k0, abs=1e-7)
    assert c.curvature(c.length) == pytest.approx(k1, abs=1e-7)


@pytest.mark.parametrize("n", [3, 5, 7])
def test_jerk_gram_is_the_integral(n):
    rng = np.random.default_rng(n)
    P = rng.normal(size=(n + 1, 2))
    # r'''(t) from the power basis of each coordinate, integrated by a fine rule
    t = np.linspace(0.0, 1.0, 20001)
    B = bernstein(t, n)
    total = 0.0
    for c in range(2):
        poly = np.polynomial.Polynomial.fit(t, B @ P[:, c], n).convert()
        d3 = poly.deriv(3)(t)
        total += np.trapezoid(d3 * d3, t)
    assert float(np.sum(P * (jerk_gram(n) @ P))) == pytest.approx(total, rel=1e-6)


def test_subdivision_matches_de_casteljau():
    P = np.array([[0, 0], [1, 2], [3, 3], [4, 0], [6, 1], [7, 2]], float)
    c = BezierCurve(P)
    s = 0.37 * c.length
    left, right = c.split(s)
    t = float(c.t_of_s(s)[0])
    assert np.allclose(subdivision_matrix(5, 0.0, t) @ P, left.control_points, atol=1e-12)
    assert np.allclose(subdivision_matrix(5, t, 1.0) @ P, right.control_points, atol=1e-12)


def test_speed_profile_time_straight():
    # a straight line of length 10 along X from rest, feed 5, axis acceleration 20:
    # accelerate to the feed (5/20 s over 0.625, a cut of the 160 pieces), then run at
    # the feed: L/F + F/(2a); nothing is owed after the curve
    L, F, a = 10.0, 5.0, 20.0
    P = np.c_[np.linspace(0.0, L, 6), np.zeros(6)]
    expected = L / F + F / (2 * a)
    assert speed_profile_time(P, F, (a, 1000.0), m=161) == pytest.approx(expected, rel=1e-12)
    # along the diagonal both axes share the work: with a/sqrt2 per axis the path
    # acceleration is a again
    Q = P @ np.array([[1, 1], [0, 0]]) / math.sqrt(2)
    lim = a / math.sqrt(2)
    assert speed_profile_time(Q, F, (lim, lim), m=161) == pytest.approx(expected, rel=1e-12)
    # stopping short of the feed at the end costs the time to reach it afterwards
    Pshort = np.c_[np.linspace(0.0, 0.1, 6), np.zeros(6)]
    v_end = math.sqrt(2 * a * 0.1)
    assert speed_profile_time(Pshort, F, (a, a), m=161) == pytest.approx(
        v_end / a + (F - v_end) ** 2 / (2 * a * F), rel=1e-12)


def test_clearance_cases():
    line = Element("line", 1.0, Line((0.0, 0.0), (10.0, 0.0)))
    p = np.array([[5.0, 2.0], [-1.0, 3.0], [5.0, -2.0]])
    kind, vec, scal = classify(line, p)
    assert list(kind) == [LINE, END, LINE]
    assert vec[0] == pytest.approx((0.0, 1.0)) and scal[0] == pytest.approx(1.0)
    assert vec[2] == pytest.approx((0.0, -1.0))
    assert vec[1] == pytest.approx((0.0, 0.0))
    G, h, soc, *_ = linear_rows(line, p)
    # every row holds at its own point with the right slack: distance - clearance
    assert (G * p).sum(1) - h == pytest.approx([1.0, math.hypot(1, 3) - 1.0, 1.0])
    arc = Element("arc", 1.0, Arc((0.0, 0.0), 5.0, 0.0, math.pi / 2))
    q = np.array([[1.0, 1.0], [6.0, 6.0], [-2.0, -2.0]])
    kind, vec, scal = classify(arc, q)
    assert list(kind) == [CONCAVE, CONVEX, END]
    assert scal[0] == pytest.approx(4.0) and scal[1] == pytest.approx(6.0)
    G, h, soc, *_ = linear_rows(arc, q)
    assert list(soc) == [True, False, False] and not np.isfinite(h[0])
    # the half-plane of a convex case lies inside |p - c| >= R + r: tight at the point
    assert (G[1] @ q[1]) - h[1] == pytest.approx(math.hypot(6, 6) - 6.0)


def test_exempt_samples_beyond_a_lines_open_ends():
    # a line element (0, 0)-(10, 0), open at both ends: points with their foot beyond
    # an end are exempt; classify gives the half-plane beyond that end, exactly (the
    # CasADi model keeps such samples there), and the convex rows leave them free
    from ccopt_formulations.clearance import EXEMPT, LINE, Element, classify, linear_rows
    el = Element("line", 2.0, Line((0.0, 0.0), (10.0, 0.0)), open_start=True, open_end=True)
    p = np.array([[-1.0, 0.5], [-0.001, -3.0], [5.0, 3.0], [10.5, -1.0], [12.0, 4.0]])
    kind, vec, scal = classify(el, p)
    assert list(kind) == [EXEMPT, EXEMPT, LINE, EXEMPT, EXEMPT]
    # beyond the start: -x >= 0; beyond the end: x >= 10; alongside: y >= 2
    assert np.allclose(vec[[0, 1]], [[-1.0, 0.0]] * 2) and np.allclose(scal[[0, 1]], 0.0)
    assert np.allclose(vec[[3, 4]], [[1.0, 0.0]] * 2) and np.allclose(scal[[3, 4]], 10.0)
    assert np.allclose(vec[2], [0.0, 1.0]) and scal[2] == pytest.approx(2.0)
    assert np.all(np.einsum("ij,ij->i", vec, p) >= scal)
    G, h, _, _, _ = linear_rows(el, p)
    assert np.all(np.isneginf(h[kind == EXEMPT])) and np.allclose(G[kind == EXEMPT], 0.0)


def test_interval_at_one_cut_is_the_vectorised_interval():
    # speed_profile_time's passes take the feasible path acceleration cut by cut
    # in floats (_interval_at); it must be path_acceleration_interval's value,
    # bit for bit, including tangents with a zero component and infeasible cuts
    rng = np.random.default_rng(7)
    ang = rng.uniform(0.0, 2.0 * np.pi, 400)
    ang[::5] = 0.0                       # along x: the y component is zero
    ang[1::5] = np.pi / 2.0              # along y
    T = np.column_stack([np.cos(ang), np.sin(ang)])
    T[::5, 1] = 0.0
    T[1::5, 0] = 0.0
    K = rng.normal(size=(400, 2)) * rng.uniform(0.0, 2.0, (400, 1))
    b = rng.uniform(0.0, 4e4, 400)
    acc = (800.0, 1500.0)
    lo, hi = path_acceleration_interval(T, K, b, acc)
    assert np.any(lo > hi) and np.any(lo <= hi)          # both kinds of cut met
    for i in range(400):
        assert _interval_at(T[i].tolist(), K[i].tolist(), float(b[i]), acc) == (lo[i], hi[i])
