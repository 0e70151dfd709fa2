"""Raw offsets: side, distance, radius change, vanishing arcs and spirals."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ccopt.geometry import Arc, Line, Spiral, offset


@pytest.mark.parametrize("d", [0.5, -0.5, 2.0, -3.25])
def test_line_offset_side_and_distance(d):
    p0, p1 = np.array([1.0, -2.0]), np.array([4.0, 2.0])      # direction (0.6, 0.8)
    g = offset(Line(tuple(p0), tuple(p1)), d)
    assert isinstance(g, Line)
    left = np.array([-0.8, 0.6])                              # +90 deg from (0.6, 0.8)
    assert np.allclose(g.p0, p0 + d * left, atol=1e-15)
    assert np.allclose(g.p1, p1 + d * left, atol=1e-15)
    # Every point is |d| away on the side given by the sign of d.
    for q in (g.p0, g.p1, g.point(0.4 * g.length)):
        v = np.subtract(q, p0)
        cross = 0.6 * v[1] - 0.8 * v[0]                       # > 0: left of travel
        assert math.isclose(cross, d, abs_tol=1e-14)


def test_zero_length_line_cannot_be_offset():
    with pytest.raises(ValueError):
        offset(Line((1, 1), (1, 1)), 0.1)


@pytest.mark.parametrize("sweep, d, expected", [
    (1.0, 0.5, 1.5),      # ccw: left is toward the centre
    (1.0, -0.5, 2.5),
    (-1.0, 0.5, 2.5),     # cw: left is away from the centre
    (-1.0, -0.5, 1.5),
])
def test_arc_offset_radius(sweep, d, expected):
    a = Arc((1.0, 2.0), 2.0, 0.3, sweep)
    g = offset(a, d)
    assert isinstance(g, Arc)
    assert g.radius == expected
    assert (g.center, g.theta0, g.sweep) == (a.center, a.theta0, a.sweep)
    # The offset point at the same angle is the original point moved d along its left normal.
    s = np.linspace(0, a.length, 11)
    moved = a.point(s) + d * a.normal(s)
    assert np.allclose(g.point(s * g.radius / a.radius), moved, atol=1e-13)


@pytest.mark.parametrize("sweep, d", [(1.0, 2.0), (1.0, 3.0), (-1.0, -2.0), (-2.0, -5.0)])
def test_arc_offset_vanishes(sweep, d):
    assert offset(Arc((0, 0), 2.0, 0.0, sweep), d) is None


def test_spiral_offset_is_radial_and_may_vanish():
    sp = Spiral((0.5, -1.0), 1.0, 3.0, 0.2, 5.0)                # ccw
    g = offset(sp, 0.4)
    assert isinstance(g, Spiral)
    assert (g.rho0, g.rho1) == (0.6, 2.6)
    # Same swept angle, radius reduced by 0.4: the radial offset.
    phi = np.linspace(0, 5.0, 9)
    p = np.array(sp.point(sp.arclength(phi)))
    q = np.array(g.point(g.arclength(phi)))
    assert np.allclose(np.hypot(*(p - q).T), 0.4, atol=1e-12)
    radial = (p - sp.center) / np.hypot(*(p - sp.center).T)[:, None]
    assert np.allclose(p - q, 0.4 * radial, atol=1e-12)
    cw = Spiral((0, 0), 1.0, 3.0, 0.0, -5.0)
    assert (offset(cw, 0.4).rho0, offset(cw, 0.4).rho1) == (1.4, 3.4)
    assert offset(sp, 1.0) is None and offset(sp, 1.5) is None
    assert offset(cw, -1.0) is None


@settings(max_examples=200, deadline=None)
@given(R=st.floats(0.01, 100), sweep=st.floats(-20, 20).filter(lambda v: abs(v) > 1e-6),
       d=st.floats(-50, 50))
def test_arc_offset_property(R, sweep, d):
    a = Arc((0.0, 0.0), R, 0.0, sweep)
    g = offset(a, d)
    R_new = R - d * math.copysign(1.0, sweep)
    if R_new <= 0:
        assert g is None
    else:
        assert math.isclose(g.radius, R_new)
        # The start moved by exactly |d| along the start normal.
        moved = np.add(a.start, d * np.asarray(a.normal(0.0)))
        assert np.allclose(g.start, moved, atol=1e-12 * max(R, abs(d), 1.0))


def test_offset_rejects_other_objects():
    with pytest.raises(TypeError):
        offset((0.0, 0.0), 1.0)
