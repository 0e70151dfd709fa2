"""Certified Bezier bounds and cuts (ccopt.geometry.curve) against independent means.

The reference curves here are numpy ``Polynomial`` objects built from the
Bernstein definition ``sum C(n,i) t^i (1-t)^(n-i) P_i`` and differentiated by
numpy, not through the module's hodograph or subdivision helpers.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.polynomial import Polynomial

from ccopt.geometry.curve import (
    bernstein_product,
    curvature_bound,
    de_casteljau_split,
    inflections,
    speed_lower_bound,
)


def power_curve(ctrl):
    """``(x(t), y(t))`` as numpy Polynomials from the Bernstein definition."""
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    t, one_minus_t = Polynomial([0.0, 1.0]), Polynomial([1.0, -1.0])
    basis = [math.comb(n, i) * t ** i * one_minus_t ** (n - i) for i in range(n + 1)]
    x = sum((b * c for b, c in zip(basis, ctrl[:, 0])), Polynomial([0.0]))
    y = sum((b * c for b, c in zip(basis, ctrl[:, 1])), Polynomial([0.0]))
    return x, y


def sampled_curvature_and_speed(ctrl, m: int = 4001):
    x, y = power_curve(ctrl)
    t = np.linspace(0.0, 1.0, m)
    x1, y1, x2, y2 = x.deriv()(t), y.deriv()(t), x.deriv(2)(t), y.deriv(2)(t)
    speed = np.hypot(x1, y1)
    return (x1 * y2 - y1 * x2) / speed ** 3, speed


def to_bernstein(power_coeffs, n: int) -> np.ndarray:
    """Bernstein coefficients (degree ``n``) of ``sum a_j t^j``:
    ``b_i = sum_{j<=i} C(i,j) / C(n,j) a_j`` (the textbook conversion)."""
    a = list(power_coeffs) + [0.0] * (n + 1 - len(power_coeffs))
    return np.array([sum(math.comb(i, j) / math.comb(n, j) * a[j] for j in range(i + 1))
                     for i in range(n + 1)])


control_polygons = st.integers(min_value=2, max_value=7).flatmap(
    lambda n: st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)),
                       min_size=n + 1, max_size=n + 1))


def min_speed(ctrl) -> float:
    """The exact minimum of ``|r'(t)|`` on [0, 1]: ends and the real roots of
    ``d/dt |r'|^2`` inside."""
    x, y = power_curve(ctrl)
    sq = x.deriv() ** 2 + y.deriv() ** 2
    # negligible leading coefficients would throw the roots to infinity
    sq = sq.trim(1e-13 * float(np.max(np.abs(sq.coef))))
    ts = [0.0, 1.0] + [float(r.real) for r in sq.deriv().roots()
                       if abs(r.imag) < 1e-9 and 0.0 < r.real < 1.0]
    return math.sqrt(max(0.0, min(float(sq(t)) for t in ts)))


@settings(max_examples=200, deadline=None)
@given(control_polygons)
def test_curvature_bound_is_never_below_the_sampled_curvature(ctrl):
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa, _ = sampled_curvature_and_speed(ctrl)
    bound = curvature_bound(ctrl)
    finite = np.abs(kappa[np.isfinite(kappa)])
    if finite.size:                    # (none: the "curve" is a single point)
        assert bound >= float(finite.max()) * (1 - 1e-9)
    # a regular curve gets a finite bound (subdivision makes every hodograph
    # piece one-sided); one that stops has unbounded curvature
    regular = min_speed(ctrl) > 1e-3 * max(1.0, float(np.abs(ctrl).max()))
    assume(regular)
    assert math.isfinite(bound)


@settings(max_examples=100, deadline=None)
@given(control_polygons)
def test_speed_lower_bound_is_never_above_the_sampled_speed(ctrl):
    with np.errstate(divide="ignore", invalid="ignore"):
        _, speed = sampled_curvature_and_speed(ctrl)
    assert speed_lower_bound(ctrl) <= float(speed.min()) * (1 + 1e-12) + 1e-12


def test_curvature_bound_of_a_circle_like_cubic_is_close():
    # quarter of the unit circle (k = 4/3 (sqrt2 - 1)): curvature within 1 %
    # of 1 everywhere, so a useful bound is a small multiple of 1
    k = 4.0 / 3.0 * (math.sqrt(2.0) - 1.0)
    ctrl = [(1, 0), (1, k), (k, 1), (0, 1)]
    kappa, _ = sampled_curvature_and_speed(ctrl)
    bound = curvature_bound(ctrl)
    assert float(np.abs(kappa).max()) <= bound < 2.5
    # and a straight one has none
    assert curvature_bound([(0, 0), (1, 1), (3, 3)]) == 0.0
    assert curvature_bound([(0, 0), (2, 1)]) == 0.0


def test_curvature_bound_of_a_cusp_is_infinite():
    # (0,0) (1,1) (0,0): turns back at t = 1/2, speed 0 there
    assert curvature_bound([(0, 0), (1, 1), (0, 0)]) == math.inf


@pytest.mark.parametrize("y_power, n, expected", [
    # x = t, so the curvature's sign is the sign of y''
    ([0.0, 0.0, -0.9, 1.0], 3, [0.3]),                        # y'' = 6t - 1.8
    ([0.0, 0.0, 0.07, -0.15, 1.0 / 12.0], 5, [0.2, 0.7]),     # y'' = (t - .2)(t - .7)
    ([0.0625, -0.5, 1.5, -2.0, 1.0], 4, []),                  # y = (t - 1/2)^4: y'' >= 0
    ([0.0, 1.0, 0.0], 2, []),                                 # a straight line
])
def test_inflections_at_known_parameters(y_power, n, expected):
    xs = to_bernstein([0.0, 1.0], n)
    ys = to_bernstein(y_power, n)
    found = inflections(np.c_[xs, ys])
    assert len(found) == len(expected)
    for t, e in zip(found, expected):
        assert t == pytest.approx(e, abs=1e-12)


def test_inflection_of_a_symmetric_s_curve_is_its_middle():
    # point-symmetric about (6, 0): the turn changes sign at t = 1/2
    assert inflections([(0, 0), (4, 4), (8, -4), (12, 0)]) == [pytest.approx(0.5, abs=1e-15)]


@pytest.mark.parametrize("t", [0.5, 0.3, 0.97])
def test_de_casteljau_split_pieces_trace_the_curve(t):
    ctrl = [(0, 0), (2, 0), (4, 1), (5, 3), (5, 5), (4, 7)]
    x, y = power_curve(ctrl)
    left, right = de_casteljau_split(ctrl, t)
    assert np.array_equal(left[0], ctrl[0]) and np.array_equal(right[-1], ctrl[-1])
    assert np.array_equal(left[-1], right[0])      # bit for bit: pieces join exactly
    u = np.linspace(0.0, 1.0, 101)
    for piece, a, b in ((left, 0.0, t), (right, t, 1.0)):
        px, py = power_curve(piece)
        assert np.allclose(px(u), x(a + (b - a) * u), atol=1e-12)
        assert np.allclose(py(u), y(a + (b - a) * u), atol=1e-12)


def test_bernstein_product_evaluates_to_the_product():
    rng = np.random.default_rng(7)
    for m, k in ((0, 3), (2, 2), (4, 3), (5, 6)):
        a, b = rng.normal(size=m + 1), rng.normal(size=k + 1)
        c = bernstein_product(a, b)
        assert np.allclose(evaluate(c), evaluate(a) * evaluate(b), atol=1e-12)


def evaluate(coeffs, t=np.linspace(0.0, 1.0, 51)) -> np.ndarray:
    """A scalar polynomial from its Bernstein coefficients, by the definition."""
    n = len(coeffs) - 1
    return sum(math.comb(n, i) * t ** i * (1 - t) ** (n - i) * coeffs[i] for i in range(n + 1))
