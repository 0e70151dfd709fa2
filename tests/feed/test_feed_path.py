"""ExactPath: the tool path as a toppra geometric path, exact and arc-length parameterised."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.feed import AxisLimits, ExactPath
from ccopt.geometry import Arc, Line, Spiral
from ccopt.toolpath import PathSegment, Role, ToolPath

from _tolerances import TOPPRA_OVER


def seg(geom, w0=0.0, w1=0.0, feed=10.0, role=Role.COMPENSATED):
    return PathSegment(geom, role, None, w0, w1, feed)


def mixed_path():
    """Line, tangent arc, spiral, helix (arc with w moving), Z plunge, line."""
    segs = [
        seg(Line((0, 0), (10, 0))),
        seg(Arc((10, 5), 5, -math.pi / 2, math.pi / 2)),              # tangent to the line
        seg(Spiral.from_points((15, 5), (5, 12), (10, 5), ccw=True)),
        seg(Arc((5, 5), 7, math.pi / 2, math.pi / 2), w0=0.0, w1=-3.0),  # helix
        seg(Line((-2, 5), (-2, 5)), w0=-3.0, w1=-5.0),                # plunge: no in-plane motion
        seg(Line((-2, 5), (-2, 0)), w0=-5.0, w1=-5.0),
        seg(Line((-2, 0), (-2, 0))),                                   # no motion at all: left out
    ]
    return ToolPath(tuple(segs))


def test_lengths_offsets_and_dof():
    path = ExactPath(mixed_path())
    assert path.dof == 3
    assert len(path.segments) == 6                     # the motionless segment is left out
    L_helix = 7 * math.pi / 2
    assert path.lengths[3] == pytest.approx(math.hypot(L_helix, 3.0), rel=1e-15)
    assert path.lengths[4] == pytest.approx(2.0, rel=1e-15)   # plunge measured by its w length
    assert np.allclose(path.offsets, np.r_[0, np.cumsum(path.lengths)], rtol=0, atol=1e-12)
    assert np.array_equal(path.path_interval, [0.0, path.offsets[-1]])
    flat = ExactPath(ToolPath((seg(Line((0, 0), (1, 0))),)))
    assert flat.dof == 2


def test_matches_the_primitives_on_every_segment():
    """q, q', q'' equal the primitives' point/d1/d2 (scaled for w) to rounding."""
    tp = mixed_path()
    path = ExactPath(tp)
    for k, sg in enumerate(path.segments):
        S, L = path.lengths[k], sg.geom.length
        sigma = np.linspace(0.0, S, 41)
        lam = sigma * (L / S)
        s = path.offsets[k] + sigma
        kk = np.full(s.size, k)
        q0, q1, q2 = (path.eval_segments(kk, s, o) for o in (0, 1, 2))
        r = L / S
        assert np.allclose(q0[:, :2], sg.geom.point(lam), rtol=0, atol=1e-12)
        assert np.allclose(q1[:, :2], sg.geom.d1(lam) * r, rtol=0, atol=1e-12)
        assert np.allclose(q2[:, :2], sg.geom.d2(lam) * r * r, rtol=0, atol=1e-12)
        dw = sg.w1 - sg.w0
        assert np.allclose(q0[:, 2], sg.w0 + dw * sigma / S, rtol=0, atol=1e-12)
        assert np.allclose(q1[:, 2], dw / S, rtol=0, atol=1e-15)
        assert np.allclose(q2[:, 2], 0.0)
        # arc length parameter: unit speed, curvature vector normal to the tangent
        assert np.allclose(np.linalg.norm(q1, axis=1), 1.0, rtol=0, atol=1e-12)
        assert np.allclose(np.einsum("ij,ij->i", q1, q2), 0.0, atol=1e-9)


def test_derivatives_agree_with_finite_differences():
    path = ExactPath(mixed_path())
    h = 1e-5
    for k in range(len(path.segments)):
        s = path.offsets[k] + path.lengths[k] * np.linspace(0.1, 0.9, 9)
        kk = np.full(s.size, k)
        d1 = (path.eval_segments(kk, s + h, 0) - path.eval_segments(kk, s - h, 0)) / (2 * h)
        d2 = (path.eval_segments(kk, s + h, 1) - path.eval_segments(kk, s - h, 1)) / (2 * h)
        assert np.allclose(d1, path.eval_segments(kk, s, 1), atol=1e-8)
        assert np.allclose(d2, path.eval_segments(kk, s, 2), atol=1e-7)


def test_scalar_and_array_shapes_and_sides():
    path = ExactPath(mixed_path())
    assert path(1.0).shape == (3,)
    assert path(1.0, 1).shape == (3,)
    assert path(np.array([1.0, 2.0]), 2).shape == (2, 3)
    assert path.eval(1.0).shape == (3,) and path.evald(1.0).shape == (3,)
    assert path.evaldd(np.linspace(0, 1, 5)).shape == (5, 3)
    # at the line->arc boundary: q'' is 0 on the left, 1/R on the right
    b = path.offsets[1]
    assert np.allclose(path.eval_sided(b, 2, "left"), 0.0)
    assert np.linalg.norm(path.eval_sided(b, 2, "right")) == pytest.approx(1 / 5, rel=1e-12)
    assert np.allclose(path(b, 2), path.eval_sided(b, 2, "right"))
    # positions agree on both sides (continuous path)
    for b in path.offsets[1:-1]:
        assert np.allclose(path.eval_sided(b, 0, "left"), path.eval_sided(b, 0, "right"),
                           atol=1e-12)
    # the last point belongs to the last segment
    assert np.allclose(path(path.offsets[-1]), [-2, 0, -5])


def test_tangent_breaks():
    path = ExactPath(mixed_path())
    # line->arc tangent, arc->spiral: spiral starts at radius 5 about the same centre
    # but turns outwards (not tangent); spiral->helix, helix->plunge, plunge->line: breaks
    brk = path.tangent_break
    assert not brk[0] and not brk[-1]
    assert not brk[1]
    assert brk[2] and brk[4] and brk[5]
    assert np.array_equal(path.stop_positions, path.offsets[brk])


def test_dwells_map_to_path_positions():
    from ccopt.program.model import Block, Modal, Motion, Source
    dwell = Block(Source("p", 7, 1), Motion.DWELL, (0, 0, 0), (0, 0, 0), Modal(), dwell=0.5)
    segs = (seg(Line((0, 0), (1, 0))), seg(Line((1, 0), (1, 0))), seg(Line((1, 0), (2, 0))))
    tp = ToolPath(segs, dwells=((1, 0.5, dwell), (3, 0.25, dwell)))
    path = ExactPath(tp)
    assert [(d.s, d.seconds, d.line) for d in path.dwells] == [(1.0, 0.5, 7), (2.0, 0.25, 7)]
    # a dwell between collinear lines still stops the tool
    assert not path.tangent_break.any()
    assert list(path.stop_positions) == [1.0, 2.0]


def test_limits_in_plane_order_and_missing_axis():
    lim = AxisLimits(v=[1, 2, 3], a=[10, 20, 30])
    v, a = lim.in_plane("ZX", 3)
    assert list(v) == [3, 1, 2] and list(a) == [30, 10, 20]
    assert lim.axis_names("YZ", 2) == ("Y", "Z")
    with pytest.raises(ValueError, match="moves axis Z"):
        AxisLimits(v=[1, 2], a=[1, 2]).in_plane("XY", 3)
    with pytest.raises(ValueError):
        AxisLimits(v=[1, -2], a=[1, 2])
    with pytest.raises(ValueError):
        AxisLimits(v=[1, 2], a=[1, 2, 3])
    with pytest.raises(ValueError):
        AxisLimits(v=[1, 2], a=[1, 2], tangential_acc=0)


def test_plain_toppra_constraints_accept_the_exact_path():
    """ExactPath plugs into toppra's own constraints and algorithm unchanged."""
    import toppra.algorithm as algo
    from toppra import constraint

    path = ExactPath(ToolPath((seg(Line((0, 0), (30, 40)), feed=None, role=Role.RAPID),)))
    gp = np.linspace(0, 50, 101)
    inst = algo.TOPPRA([constraint.JointVelocityConstraint([30.0, 40.0]),
                        constraint.JointAccelerationConstraint(
                            [300.0, 400.0],
                            discretization_scheme=constraint.DiscretizationType.Interpolation)],
                       path, gridpoints=gp, solver_wrapper="seidel",
                       parametrizer="ParametrizeConstAccel")
    traj = inst.compute_trajectory(0, 0)
    # direction (0.6, 0.8): v = 50, a = 500; T = L/v + v/a = 1 + 0.1
    assert traj.duration == pytest.approx(1.1, rel=1e-3)


class Clothoid:
    """Euler spiral from the origin along +X, curvature s / A^2: a stand-in for
    a parametric blend curve (same interface as the primitives, by arc length)."""

    def __init__(self, A: float, length: float):
        self.A, self.length = A, length
        self.start, self.end = (0.0, 0.0), tuple(self.point(length))

    def point(self, s):
        from scipy.special import fresnel
        k = self.A * math.sqrt(math.pi)
        S, C = fresnel(np.asarray(s, float) / k)
        return np.stack([k * C, k * S], axis=-1)

    def d1(self, s):
        th = np.asarray(s, float) ** 2 / (2 * self.A ** 2)
        return np.stack([np.cos(th), np.sin(th)], axis=-1)

    def d2(self, s):
        s = np.asarray(s, float)
        th = s ** 2 / (2 * self.A ** 2)
        return np.stack([-np.sin(th), np.cos(th)], axis=-1) * (s / self.A ** 2)[..., None]

    def curvature(self, s):
        return np.asarray(s, float) / self.A ** 2


def test_blend_curve_from_its_own_methods():
    """A segment that is neither line, arc nor spiral is evaluated through its
    own point/d1/d2; its turning (for the grid) integrates the curvature."""
    from ccopt.feed import plan_feed

    cl = Clothoid(A=5.0, length=10.0)              # turns 10^2 / (2 * 25) = 2 rad
    tp = ToolPath((seg(Line((-20.0, 0.0), (0.0, 0.0))), seg(cl)))
    path = ExactPath(tp)
    assert path.segments[1].kind == "curve"
    assert path.turning(1) == pytest.approx(2.0, rel=1e-4)
    assert not path.tangent_break[1]               # G2-continuous join
    s = np.linspace(20.0, 30.0, 11)
    k = np.full(s.size, 1)
    assert np.allclose(path.eval_segments(k, s, 0), cl.point(s - 20.0), atol=1e-12)
    assert np.allclose(path.eval_segments(k, s, 2), cl.d2(s - 20.0), atol=1e-12)
    lim = AxisLimits((100.0, 100.0), (1000.0, 1000.0), centripetal_acc=300.0)
    smp = plan_feed(path, lim).sample(1e-3)
    kappa_v2 = smp.curvature * smp.feed ** 2
    assert kappa_v2.max() <= 300.0 * TOPPRA_OVER
    assert smp.axis_acceleration_ratio.max() <= TOPPRA_OVER
