"""Arc length of Bezier curves and its inverse against closed forms and an
independent quadrature: a straight Bezier (arc length = x), the parabola
``y = x^2`` (arc length, curvature and its derivative in closed form), and
curves whose speed varies a lot (scipy's adaptive quadrature of the speed
written out here)."""
from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from scipy.integrate import quad

from ccopt.geometry.bezier_arclength import ARC_LENGTH_REL_TOL
from ccopt.geometry.curve import BezierCurve

# Rounding of a quadrature sum on top of the stated tolerance (a few ulps of a length).
ROUNDING = 1e-14


def bezier(ctrl, t):
    """The Bezier polynomial written out (Bernstein sum), independent of ccopt."""
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    t = np.asarray(t, float)[..., None]
    return sum(math.comb(n, i) * t ** i * (1 - t) ** (n - i) * ctrl[i] for i in range(n + 1))


def speed(ctrl, t):
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    return float(np.linalg.norm(bezier(n * np.diff(ctrl, axis=0), t)))


def test_straight_bezier_arc_length_is_x():
    # control points on the x axis, unevenly spaced: x(t) increases, y = 0, so s = x
    P = [(0.0, 0.0), (1.0, 0.0), (5.0, 0.0), (6.0, 0.0)]
    c = BezierCurve(P)
    assert c.length == pytest.approx(6.0, rel=ARC_LENGTH_REL_TOL + ROUNDING)
    s = np.linspace(0.0, 6.0, 1001)
    t = c.t_of_s(s)
    x = bezier(P, t)[:, 0]
    assert np.max(np.abs(x - s)) <= (ARC_LENGTH_REL_TOL + ROUNDING) * 6.0
    assert np.allclose(c.point(s), np.c_[s, np.zeros_like(s)], rtol=0, atol=1e-11)
    assert np.allclose(c.d1(s), [1.0, 0.0], atol=1e-15)
    assert np.all(c.d2(s) == 0.0) and np.all(c.d3(s) == 0.0) and np.all(c.curvature(s) == 0.0)


# The parabola y = x^2 for x in [-1, 1] is the quadratic Bezier (-1, 1), (0, -1), (1, 1):
# r(t) = (2t - 1, (2t - 1)^2). Its arc length from x = -1 is F(x) - F(-1) with
# F(x) = x sqrt(1 + 4x^2) / 2 + asinh(2x) / 4.
PARABOLA = [(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0)]


def F(x):
    return 0.5 * x * np.sqrt(1.0 + 4.0 * x * x) + 0.25 * np.arcsinh(2.0 * x)


def test_parabola_length_and_inverse_in_closed_form():
    c = BezierCurve(PARABOLA)
    L = math.sqrt(5.0) + 0.5 * math.asinh(2.0)
    assert c.length == pytest.approx(L, rel=ARC_LENGTH_REL_TOL + ROUNDING)
    s = np.linspace(0.0, L, 2001)
    x = c.point(s)[:, 0]
    assert np.allclose(c.point(s)[:, 1], x * x, rtol=0, atol=1e-14)
    # the stated tolerance of the inverse: |s(t) - s| <= ARC_LENGTH_REL_TOL * length
    assert np.max(np.abs(F(x) - F(-1.0) - s)) <= (ARC_LENGTH_REL_TOL + ROUNDING) * L
    assert np.allclose(c.t_of_s(s), 0.5 * (x + 1.0), rtol=0, atol=1e-15)


def test_parabola_derivatives_in_closed_form():
    c = BezierCurve(PARABOLA)
    s = np.linspace(0.0, c.length, 101)
    x = c.point(s)[:, 0]
    w = np.sqrt(1.0 + 4.0 * x * x)
    T = np.c_[np.ones_like(x), 2.0 * x] / w[:, None]
    N = np.c_[-2.0 * x, np.ones_like(x)] / w[:, None]
    kappa = 2.0 / w ** 3
    # d kappa / ds = (d kappa / dx) / w = -24 x / w^6
    dkappa = -24.0 * x / w ** 6
    assert np.allclose(c.d1(s), T, rtol=0, atol=1e-13)
    assert np.allclose(c.curvature(s), kappa, rtol=1e-12, atol=0)
    assert np.allclose(c.d2(s), kappa[:, None] * N, rtol=0, atol=1e-12)
    d3 = dkappa[:, None] * N - (kappa * kappa)[:, None] * T
    assert np.allclose(c.d3(s), d3, rtol=0, atol=1e-11)


@pytest.mark.parametrize("P", [
    [(0, 0), (2, 0), (4, 1), (5, 3), (5, 5), (4, 7)],
    # a quintic turning 90 degrees in its last 0.1 mm: its speed varies a hundredfold
    [(0, 0), (5, 0), (9, 0), (10, 0.0), (10.05, 0.05), (10.05, 1.0)],
    [(0, 0), (0.001, 0), (10, 0.002), (10, 5), (0, 5)],
])
def test_inverse_within_the_stated_tolerance(P):
    c = BezierCurve(P)
    L = quad(lambda u: speed(P, u), 0.0, 1.0, epsabs=1e-13, epsrel=1e-13, limit=400)[0]
    assert c.length == pytest.approx(L, rel=ARC_LENGTH_REL_TOL + ROUNDING)
    s = np.r_[0.0, np.sort(np.random.default_rng(7).uniform(0.0, L, 25)), c.length]
    t = c.t_of_s(s)
    assert t[0] == 0.0 and t[-1] == 1.0
    for si, ti in zip(s, t):
        got = quad(lambda u: speed(P, u), 0.0, ti, epsabs=1e-13, epsrel=1e-13, limit=400)[0]
        assert abs(got - si) <= (ARC_LENGTH_REL_TOL + ROUNDING) * L
    assert np.array_equal(c.point(0.0), P[0]) and np.array_equal(c.point(L * 2), P[-1])


def test_repeated_and_interleaved_evaluations_agree():
    P = [(0, 0), (2, 0), (4, 1), (5, 3), (5, 5), (4, 7)]
    c = BezierCurve(P)
    a = np.linspace(0.0, c.length, 7)
    b = np.linspace(0.1, 0.9 * c.length, 5)
    pa, pb = c.point(a), c.point(b)
    assert np.array_equal(c.point(a), pa) and np.array_equal(c.d2(b), c.d2(b.copy()))
    assert np.array_equal(c.point(b), pb)
    # the arrays handed out are the caller's own
    t = c.t_of_s(a)
    t[:] = 0.0
    assert np.array_equal(c.point(a), pa)
    # against the polynomial at the inverted parameters
    assert np.allclose(pa, bezier(P, c.t_of_s(a)), rtol=0, atol=1e-13)


def test_pickle_carries_the_control_points():
    c = BezierCurve([(0, 0), (2, 0), (4, 1), (5, 3)])
    d = pickle.loads(pickle.dumps(c))
    assert d.control_points == c.control_points and d.length == c.length
    assert np.array_equal(d.point(np.linspace(0, c.length, 9)),
                          c.point(np.linspace(0, c.length, 9)))


def test_pickle_keeps_the_arc_length_table_and_every_figure(monkeypatch):
    """A curve sent to a worker is the curve made here: its arc-length table
    travels (none is built again on arrival) and every figure of it is the
    same as a curve built anew from its control points, bit for bit."""
    import ccopt.geometry.curve as curve_module
    P = [(0, 0), (1.5, 2.0), (4.0, -1.0), (6.0, 0.5), (7.0, 3.0)]
    c = BezierCurve(P)
    blob = pickle.dumps(c)
    built = []
    real = curve_module.ArcLengthTable
    monkeypatch.setattr(curve_module, "ArcLengthTable",
                        lambda D1: built.append(1) or real(D1))
    d = pickle.loads(blob)
    assert built == []
    fresh = BezierCurve(P)
    assert built == [1]
    s = np.linspace(0.0, fresh.length, 41)
    assert d.length == fresh.length and d.control_points == fresh.control_points
    for figure in ("point", "tangent", "normal", "curvature", "d2", "d3", "t_of_s"):
        assert np.array_equal(getattr(d, figure)(s), getattr(fresh, figure)(s)), figure
    assert d.bbox() == fresh.bbox() if callable(fresh.bbox) else d.bbox == fresh.bbox
    assert d.start_tangent == fresh.start_tangent and d.end_tangent == fresh.end_tangent
    assert d is not c and d != c          # equality is identity, as for any curve
