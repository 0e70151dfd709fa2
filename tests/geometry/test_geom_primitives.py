"""Line, Arc and Spiral: lengths, derivatives, curvature, bbox, split, reverse."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from ccopt.geometry import Arc, Line, Spiral

TAU = 2.0 * math.pi


def polar_point(c, rho0, rho1, th0, sweep, phi):
    """Spiral point at swept angle phi from the definition (no ccopt)."""
    Phi = abs(sweep)
    rho = rho0 + (rho1 - rho0) * phi / Phi
    ang = th0 + math.copysign(1.0, sweep) * phi
    return np.stack([c[0] + rho * np.cos(ang), c[1] + rho * np.sin(ang)], axis=-1)


def sample_primitives():
    """A fixed mix of the three primitives, with awkward cases included."""
    return [
        Line((0.0, 0.0), (3.0, 4.0)),
        Line((-2.5, 1.0), (7.0, -3.0)),
        Arc((1.0, -2.0), 2.5, 0.3, 2.0),
        Arc((0.0, 0.0), 0.7, -4.0, -5.5),
        Arc((3.0, 3.0), 1.0, 10.0, 8.0),                   # more than a full turn
        Spiral((0.0, 0.0), 1.0, 3.0, 0.0, 7.0),
        Spiral((1.0, 2.0), 4.0, 0.5, 2.0, -9.0),           # shrinking, clockwise
        Spiral((-1.0, 0.5), 2.0, 2.0 + 1e-7, 1.0, 3.0),    # nearly an arc
        Spiral((0.0, 0.0), 0.05, 5.0, 0.0, 0.3),           # large b
    ]


# --------------------------------------------------------------------------- spiral length


SPIRAL_CASES = [
    (1.0, 3.0, 7.0),
    (3.0, 1.0, -7.0),
    (2.0, 2.0 * (1 + 1e-12), 3.0),     # b ~ 7e-13: the textbook formula loses everything
    (2.0, 2.0 * (1 + 1e-8), -3.0),
    (2.0, 2.0 * (1 - 1e-5), 1.0),
    (2.0, 2.0, 2.0),                   # b == 0: an arc
    (0.01, 50.0, 0.2),                 # b = 250: nearly radial
    (50.0, 0.01, -0.2),
    (0.3, 12.0, 6 * TAU),              # six turns
]


@pytest.mark.parametrize("rho0, rho1, sweep", SPIRAL_CASES)
def test_spiral_length_matches_quadrature(rho0, rho1, sweep):
    sp = Spiral((0.4, -0.2), rho0, rho1, 0.7, sweep)
    Phi = abs(sweep)
    b = (rho1 - rho0) / Phi
    # |dp/dphi| = sqrt(rho^2 + b^2) for rho = rho0 + b phi.
    ref, err = quad(lambda p: math.hypot(rho0 + b * p, b), 0.0, Phi,
                    epsabs=0.0, epsrel=1e-13, limit=500)
    assert abs(sp.length - ref) <= 1e-9 * ref
    # Same on part of the spiral.
    ref_half, _ = quad(lambda p: math.hypot(rho0 + b * p, b), 0.0, 0.37 * Phi,
                       epsabs=0.0, epsrel=1e-13, limit=500)
    assert abs(float(sp.arclength(0.37 * Phi)) - ref_half) <= 1e-9 * ref_half


@pytest.mark.parametrize("rho0, rho1, sweep", SPIRAL_CASES)
def test_spiral_ends_and_inversion(rho0, rho1, sweep):
    sp = Spiral((0.4, -0.2), rho0, rho1, 0.7, sweep)
    assert tuple(sp.point(sp.length)) == sp.end
    assert tuple(sp.point(0.0)) == sp.start
    expected_end = polar_point((0.4, -0.2), rho0, rho1, 0.7, sweep, abs(sweep))
    assert np.allclose(sp.end, expected_end, rtol=0, atol=1e-12 * max(rho0, rho1))
    s = np.linspace(0.0, sp.length, 1001)
    phi = sp.swept_angle(s)
    assert np.all(np.diff(phi) > 0)
    assert np.max(np.abs(sp.arclength(phi) - s)) <= 1e-14 * sp.length * 4
    # Points at those angles agree with the definition.
    assert np.allclose(sp.point(s), polar_point((0.4, -0.2), rho0, rho1, 0.7, sweep, phi),
                       rtol=0, atol=1e-12 * max(rho0, rho1))


@settings(max_examples=200, deadline=None)
@given(rho0=st.floats(1e-3, 1e3), ratio=st.floats(-0.999, 5.0),
       sweep=st.floats(1e-3, 40.0), ccw=st.booleans(), frac=st.floats(0.0, 1.0))
def test_spiral_inversion_property(rho0, ratio, sweep, ccw, frac):
    rho1 = rho0 * (1.0 + ratio)
    sp = Spiral((0.0, 0.0), rho0, rho1, 0.0, sweep if ccw else -sweep)
    s = frac * sp.length
    phi = float(sp.swept_angle(s))
    assert 0.0 <= phi <= sweep
    assert abs(float(sp.arclength(phi)) - s) <= 1e-13 * sp.length


def test_spiral_small_b_is_stable_against_series():
    # For tiny b, s = int sqrt(rho^2 + b^2) dphi = rho0 Phi + b Phi^2/2 + O(b^2/rho).
    rho0, Phi = 3.0, 2.5
    for b in (1e-9, 1e-12, 1e-15):
        sp = Spiral((0, 0), rho0, rho0 + b * Phi, 0.0, Phi)
        series = rho0 * Phi + b * Phi ** 2 / 2
        assert abs(sp.length - series) <= 1e-15 * series + b * b * Phi / rho0


# --------------------------------------------------------------------------- derivatives


@pytest.mark.parametrize("g", sample_primitives(), ids=lambda g: type(g).__name__)
def test_derivatives_against_finite_differences(g):
    L = g.length
    s = np.linspace(0.05 * L, 0.95 * L, 37)
    # Steps balance truncation (h^2 |p'''|) against rounding (eps/h, eps/h^2).
    h1, h2 = 1e-5, 2e-4
    fd1 = (g.point(s + h1) - g.point(s - h1)) / (2 * h1)
    fd2 = (g.point(s + h2) - 2 * g.point(s) + g.point(s - h2)) / (h2 * h2)
    scale = max(1.0, float(np.max(np.abs(g.d2(s)))))
    assert np.allclose(g.d1(s), fd1, rtol=0, atol=1e-7)
    assert np.allclose(g.d2(s), fd2, rtol=0, atol=1e-5 * scale)
    t = g.tangent(s)
    assert np.allclose(np.hypot(t[:, 0], t[:, 1]), 1.0, atol=1e-14)
    assert np.allclose(t, fd1 / np.hypot(fd1[:, 0], fd1[:, 1])[:, None], atol=1e-7)
    n = g.normal(s)
    assert np.allclose(n[:, 0], -t[:, 1]) and np.allclose(n[:, 1], t[:, 0])
    # Signed curvature from the finite differences: cross(p', p'') / |p'|^3.
    k_fd = (fd1[:, 0] * fd2[:, 1] - fd1[:, 1] * fd2[:, 0]) / np.hypot(fd1[:, 0], fd1[:, 1]) ** 3
    assert np.allclose(g.curvature(s), k_fd, rtol=1e-5, atol=1e-5 * scale)
    # Scalar evaluation has the documented shapes.
    assert g.point(0.5 * L).shape == (2,)
    assert isinstance(g.curvature(0.5 * L), float)


@pytest.mark.parametrize("R, sweep", [(2.5, 2.0), (0.7, -5.5), (1e-3, 1.0), (1e3, -0.01)])
def test_arc_curvature_is_plus_minus_one_over_r(R, sweep):
    a = Arc((1.0, 1.0), R, 0.4, sweep)
    k = a.curvature(np.linspace(0, a.length, 9))
    assert np.all(k == math.copysign(1.0, sweep) / R)
    # d2 points at the centre with magnitude 1/R.
    s = 0.3 * a.length
    to_centre = np.subtract(a.center, a.point(s))
    assert np.allclose(a.d2(s), to_centre / R ** 2, atol=1e-12 / R)


@pytest.mark.parametrize("rho0, rho1, sweep", SPIRAL_CASES)
def test_spiral_curvature_polar_formula(rho0, rho1, sweep):
    sp = Spiral((0.0, 0.0), rho0, rho1, 0.2, sweep)
    Phi = abs(sweep)
    phi = np.linspace(0.0, Phi, 23)
    s = sp.arclength(phi)
    rho = rho0 + (rho1 - rho0) * phi / Phi
    # As a polar curve r(theta) with theta running in the sweep direction:
    # r' = dr/dtheta = +-(rho1 - rho0)/Phi, r'' = 0, and the formula's sign
    # is for counter-clockwise travel.
    r1 = (rho1 - rho0) / Phi * math.copysign(1.0, sweep)
    r2 = 0.0
    k = (rho ** 2 + 2 * r1 ** 2 - rho * r2) / (rho ** 2 + r1 ** 2) ** 1.5
    assert np.allclose(sp.curvature(s), math.copysign(1.0, sweep) * k, rtol=1e-12)
    # And against finite differences of the definition in phi.
    hphi = 1e-5
    inner = phi[1:-1]
    pp = polar_point((0, 0), rho0, rho1, 0.2, sweep, inner + hphi)
    pm = polar_point((0, 0), rho0, rho1, 0.2, sweep, inner - hphi)
    p0 = polar_point((0, 0), rho0, rho1, 0.2, sweep, inner)
    d1 = (pp - pm) / (2 * hphi)
    d2 = (pp - 2 * p0 + pm) / hphi ** 2
    k_fd = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(d1[:, 0], d1[:, 1]) ** 3
    assert np.allclose(sp.curvature(s[1:-1]), k_fd, rtol=1e-4)


def test_zero_length_line_has_no_direction():
    g = Line((1.0, 2.0), (1.0, 2.0))
    assert g.length == 0.0
    assert tuple(g.point(0.0)) == (1.0, 2.0)
    assert tuple(g.tangent(0.0)) == (0.0, 0.0)


# --------------------------------------------------------------------------- ends and bbox


@pytest.mark.parametrize("g", sample_primitives(), ids=lambda g: type(g).__name__)
def test_point_at_ends_is_start_and_end(g):
    assert tuple(g.point(0.0)) == g.start
    assert tuple(g.point(g.length)) == g.end
    assert np.allclose(g.tangent(0.0), g.start_tangent, atol=1e-15)
    assert np.allclose(g.tangent(g.length), g.end_tangent, atol=1e-15)
    # s is clipped to the piece.
    assert tuple(g.point(-1.0)) == g.start and tuple(g.point(g.length + 1.0)) == g.end


def _check_bbox(g, n=400001):
    xmin, ymin, xmax, ymax = g.bbox()
    pts = g.point(np.linspace(0, g.length, n))
    h = g.length / (n - 1)
    assert pts[:, 0].min() >= xmin - 1e-12 and pts[:, 0].max() <= xmax + 1e-12
    assert pts[:, 1].min() >= ymin - 1e-12 and pts[:, 1].max() <= ymax + 1e-12
    # At an extreme the coordinate is stationary, so sampling misses at most ~h^2 * curvature.
    slack = h * h * 10 + 1e-12
    assert pts[:, 0].min() <= xmin + slack and pts[:, 0].max() >= xmax - slack
    assert pts[:, 1].min() <= ymin + slack and pts[:, 1].max() >= ymax - slack


@pytest.mark.parametrize("g", sample_primitives(), ids=lambda g: type(g).__name__)
def test_bbox_against_sampling(g):
    _check_bbox(g)


def test_bbox_random_arcs_and_spirals():
    rng = np.random.default_rng(7)
    for _ in range(60):
        c = tuple(rng.uniform(-3, 3, 2))
        th0, sw = rng.uniform(-8, 8), rng.uniform(-9, 9)
        _check_bbox(Arc(c, rng.uniform(0.1, 3), th0, sw), n=100001)
        _check_bbox(Spiral(c, rng.uniform(0.1, 3), rng.uniform(0.1, 3), th0, sw), n=100001)


def test_bbox_hand_worked():
    # Quarter circle from angle 0 to pi/2 ccw about the origin: [0,1] x [0,1].
    assert np.allclose(Arc((0, 0), 1, 0, math.pi / 2).bbox(), (0, 0, 1, 1), atol=1e-15)
    # Same angles clockwise: three quarters, touching x=-1 and y=-1.
    assert np.allclose(Arc((0, 0), 1, 0, -1.5 * math.pi).bbox(), (-1, -1, 1, 1), atol=1e-15)
    assert Line((3, -1), (-2, 4)).bbox() == (-2, -1, 3, 4)


# --------------------------------------------------------------------------- split / reverse


@pytest.mark.parametrize("g", sample_primitives(), ids=lambda g: type(g).__name__)
@pytest.mark.parametrize("frac", [0.0, 0.23, 0.5, 0.91, 1.0])
def test_split_consistency(g, frac):
    s = frac * g.length
    first, second = g.split(s)
    assert type(first) is type(g) and type(second) is type(g)
    L = max(g.length, 1.0)
    assert abs(first.length - s) <= 1e-12 * L
    assert abs(first.length + second.length - g.length) <= 1e-12 * L
    assert np.allclose(first.start, g.start, atol=1e-12 * L)
    assert np.allclose(first.end, g.point(s), atol=1e-12 * L)
    assert np.allclose(second.start, g.point(s), atol=1e-12 * L)
    assert np.allclose(second.end, g.end, atol=1e-12 * L)
    # The pieces trace the same curve.
    if second.length > 0:
        u = np.linspace(0, second.length, 17)
        assert np.allclose(second.point(u), g.point(np.minimum(s + u, g.length)), atol=1e-10 * L)
        assert np.allclose(second.curvature(u), g.curvature(np.minimum(s + u, g.length)),
                           rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("g", sample_primitives(), ids=lambda g: type(g).__name__)
def test_reversed_consistency(g):
    r = g.reversed()
    L = g.length
    assert abs(r.length - L) <= 1e-12 * max(L, 1)
    assert np.allclose(r.start, g.end, atol=1e-12) and np.allclose(r.end, g.start, atol=1e-12)
    s = np.linspace(0, L, 29)
    assert np.allclose(r.point(s), g.point(L - s), atol=1e-10 * max(L, 1))
    assert np.allclose(r.tangent(s), -g.tangent(L - s), atol=1e-9)
    assert np.allclose(r.curvature(s), -g.curvature(L - s), rtol=1e-9, atol=1e-12)
    assert r.reversed() == g or np.allclose(r.reversed().point(s), g.point(s), atol=1e-10 * max(L, 1))


def test_split_keeps_direction_of_zero_sweep_piece():
    a = Arc((0, 0), 1, 0.5, -2.0)
    first, _ = a.split(0.0)
    assert first.sweep == 0.0 and math.copysign(1.0, first.sweep) == -1.0
    assert np.allclose(first.start_tangent, a.start_tangent)


# --------------------------------------------------------------------------- constructors


def test_arc_from_points():
    a = Arc.from_points((1, 0), (0, 1), (0, 0), ccw=True)
    assert math.isclose(a.sweep, math.pi / 2) and a.radius == 1.0
    b = Arc.from_points((1, 0), (0, 1), (0, 0), ccw=False)
    assert math.isclose(b.sweep, -1.5 * math.pi)
    full = Arc.from_points((2, 1), (2, 1), (1, 1), ccw=False)
    assert full.sweep == -TAU and math.isclose(full.length, TAU)
    turns = Arc.from_points((1, 0), (0, 1), (0, 0), ccw=True, turns=2)
    assert math.isclose(turns.sweep, math.pi / 2 + 2 * TAU)
    assert np.allclose(turns.end, (0, 1), atol=1e-15)
    with pytest.raises(ValueError):
        Arc.from_points((1, 0), (0, 1.1), (0, 0), ccw=True)
    assert Arc.from_points((1, 0), (0, 1.1), (0, 0), ccw=True, tol=0.2).radius == 1.0
    with pytest.raises(ValueError):
        Arc.from_points((0, 0), (0, 0), (0, 0), ccw=True)
    with pytest.raises(ValueError):
        Arc((0, 0), 0.0, 0.0, 1.0)


def test_spiral_from_points():
    sp = Spiral.from_points((1, 0), (0, 2), (0, 0), ccw=True)
    assert (sp.rho0, sp.rho1) == (1.0, 2.0) and math.isclose(sp.sweep, math.pi / 2)
    assert np.allclose(sp.end, (0, 2), atol=1e-15)
    cw = Spiral.from_points((1, 0), (3, 0), (0, 0), ccw=False)
    assert cw.sweep == -TAU        # same angle: one full turn
    with pytest.raises(ValueError):
        Spiral.from_points((0, 0), (1, 0), (0, 0), ccw=True)
    with pytest.raises(ValueError):
        Spiral.from_points((1, 0), (0, 0), (0, 0), ccw=True)
    with pytest.raises(ValueError):
        Spiral((0, 0), 1.0, 2.0, 0.0, 0.0)


def test_value_objects_are_immutable_and_hashable():
    a = Arc((0, 0), 1, 0, 1)
    assert hash(a) == hash(Arc((0.0, 0.0), 1.0, 0.0, 1.0))
    assert {Line((0, 0), (1, 1)), Line((0.0, 0.0), (1.0, 1.0))} == {Line((0, 0), (1, 1))}
    with pytest.raises(AttributeError):
        a.radius = 2.0
    assert isinstance(Line([0, 0], np.array([1, 2])).p1, tuple)
