"""BezierCurve by arc length: length against quadrature, derivatives against
finite differences, curvature against the parametric formula, bbox against
sampling, split/reverse consistency."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ccopt.geometry.curve import BezierCurve

QUINTIC = [(0, 0), (2, 0), (4, 1), (5, 3), (5, 5), (4, 7)]


def bernstein(ctrl, t):
    n = len(ctrl) - 1
    ctrl = np.asarray(ctrl, float)
    return sum(math.comb(n, i) * t ** i * (1 - t) ** (n - i) * ctrl[i] for i in range(n + 1))


def speed(ctrl, t, h=1e-6):
    return np.linalg.norm((bernstein(ctrl, t + h) - bernstein(ctrl, t - h)) / (2 * h))


def test_length_against_quadrature():
    c = BezierCurve(QUINTIC)
    # |r'(t)| from the hodograph written out here: n * sum diff(P) Bernstein
    P = np.asarray(QUINTIC, float)
    D = 5 * np.diff(P, axis=0)
    L = quad(lambda t: np.linalg.norm(bernstein(D, t)), 0, 1, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
    assert c.length == pytest.approx(L, rel=1e-12)
    assert np.allclose(c.point(c.length), QUINTIC[-1], atol=1e-12)
    assert np.allclose(c.point(0.0), QUINTIC[0], atol=1e-12)


def test_arc_length_parameterisation_is_unit_speed():
    c = BezierCurve(QUINTIC)
    s = np.linspace(0, c.length, 201)
    p = c.point(s)
    chord = np.hypot(*np.diff(p, axis=0).T)
    # chords of a unit-speed curve sampled ds apart are ds minus O(kappa^2 ds^3)
    ds = s[1] - s[0]
    assert np.all(chord <= ds + 1e-12) and np.all(chord >= ds * (1 - 1e-3))


def test_derivatives_against_finite_differences():
    c = BezierCurve(QUINTIC)
    h = 1e-5
    for s in np.linspace(0.1, c.length - 0.1, 9):
        fd1 = (c.point(s + h) - c.point(s - h)) / (2 * h)
        fd2 = (c.point(s + h) - 2 * c.point(s) + c.point(s - h)) / h ** 2
        assert np.allclose(c.d1(s), fd1, atol=1e-8)
        assert np.allclose(c.d2(s), fd2, atol=1e-4)
        # curvature = |d2| with the sign of the turn
        k = c.curvature(s)
        assert abs(k) == pytest.approx(np.linalg.norm(c.d2(s)), rel=1e-9, abs=1e-12)


def test_bbox_against_sampling():
    c = BezierCurve(QUINTIC)
    pts = c.point(np.linspace(0, c.length, 20001))
    xmin, ymin, xmax, ymax = c.bbox()
    assert xmin <= pts[:, 0].min() + 1e-12 and xmax >= pts[:, 0].max() - 1e-12
    assert ymin <= pts[:, 1].min() + 1e-12 and ymax >= pts[:, 1].max() - 1e-12
    # and tight: the sampled extremes are within the sampling step
    assert xmax - pts[:, 0].max() < 1e-6 and ymin - pts[:, 1].min() > -1e-6


def test_split_and_reverse():
    c = BezierCurve(QUINTIC)
    a, b = c.split(c.length / 3)
    assert a.length + b.length == pytest.approx(c.length, rel=1e-12)
    assert np.allclose(a.end, b.start, atol=1e-12)
    assert np.allclose(a.point(a.length / 2), c.point(a.length / 2), atol=1e-10)
    r = c.reversed()
    assert np.allclose(r.point(0.3), c.point(c.length - 0.3), atol=1e-10)


def test_irregular_curve_is_refused():
    with pytest.raises(ValueError, match="not regular"):
        BezierCurve([(0, 0), (1, 0), (0, 0)])   # turns back on itself: speed 0 at t = 1/2
