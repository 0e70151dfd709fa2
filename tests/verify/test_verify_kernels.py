"""The verifier's building blocks against brute force: farthest distances,
certified bounds for spirals and Bezier curves, the broad phase, open-end
regions, the contour's geometry and classification."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree

import ccopt
from ccopt.cases import bundled_cases
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.curve import BezierCurve
from ccopt.geometry.distance import point_arc, point_segment
from ccopt.toolpath import block_geometry
from ccopt.verify import contour_of
from ccopt.verify.distance import certified
from ccopt.verify.distance.broadphase import MAX_CELLS, candidate_pairs
from ccopt.verify.clearance import clipped_distance, end_regions, in_regions
from ccopt.verify.distance.maxdist import max_distance
from ccopt.verify.segments import pack


def random_prim(rng):
    if rng.random() < 0.5:
        return Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2)))
    return Arc(tuple(rng.uniform(-3, 3, 2)), rng.uniform(0.5, 4), rng.uniform(-math.pi, math.pi),
               rng.choice([-1, 1]) * rng.uniform(0.1, 2 * math.pi))


def dense(g, n):
    return g.point(np.linspace(0, g.length, n))


# --------------------------------------------------------------------------- farthest distance


def _point_dist(q, g):
    """Exact distance from points ``q`` to a line or arc (the geometry's point kernels)."""
    if isinstance(g, Line):
        return point_segment(q, np.asarray(g.p0), np.asarray(g.p1))[0]
    return point_arc(q, np.asarray(g.center), g.radius, g.theta0, g.sweep)[0]


def test_max_distance_against_sampling():
    # Sampled points of A at their exact distances to B: none may exceed the
    # farthest distance, which is realised at its witness on A and matched by
    # the samples to within the sampling step (the distance is 1-Lipschitz).
    rng = np.random.default_rng(3)
    n = 400
    A = [random_prim(rng) for _ in range(n)]
    B = [random_prim(rng) for _ in range(n)]
    dm, q, t = max_distance(pack(A).arr, np.arange(n), pack(B).arr, np.arange(n))
    for k in range(n):
        m = 20001
        sampled = _point_dist(dense(A[k], m), B[k])
        assert sampled.max() <= dm[k] + 1e-12
        assert dm[k] <= sampled.max() + A[k].length / (m - 1) + 1e-12
        assert _point_dist(q[k][None, :], B[k])[0] == pytest.approx(dm[k], abs=1e-12)
        assert np.allclose(A[k].point(t[k] * A[k].length), q[k], atol=1e-9)


# --------------------------------------------------------------------------- certified bounds


def _spiral_point(sp, phi):
    rho = sp.rho0 + sp.b * phi
    ang = sp.theta0 + math.copysign(1.0, sp.sweep) * phi
    return np.array([sp.center[0] + rho * math.cos(ang), sp.center[1] + rho * math.sin(ang)])


def _dist_point_line(p, a, b):
    a, b = np.asarray(a), np.asarray(b)
    d = b - a
    u = np.clip(np.dot(p - a, d) / np.dot(d, d), 0, 1)
    return float(np.hypot(*(p - a - u * d)))


def _true_min(fun, lo, hi, n=20001):
    """Global minimum of a 1-D function: dense grid, then bounded refinement."""
    x = np.linspace(lo, hi, n)
    y = np.array([fun(v) for v in x])
    k = int(np.argmin(y))
    a, b = x[max(k - 1, 0)], x[min(k + 1, n - 1)]
    res = minimize_scalar(fun, bounds=(a, b), method="bounded", options={"xatol": 1e-13})
    return min(float(res.fun), float(y[k]))


@pytest.mark.parametrize("seed", range(6))
def test_certified_spiral_to_line(seed):
    rng = np.random.default_rng(seed)
    sp = Spiral(tuple(rng.uniform(-2, 2, 2)), rng.uniform(2, 6), rng.uniform(2, 6),
                rng.uniform(-3, 3), rng.choice([-1, 1]) * rng.uniform(0.5, 5))
    ln = Line(tuple(rng.uniform(-8, 8, 2)), tuple(rng.uniform(-8, 8, 2)))
    tol = 1e-7
    b = certified.min_distance(sp, ln, tol)
    # grid + bounded refinement: an upper estimate of the true minimum
    est = _true_min(lambda f: _dist_point_line(_spiral_point(sp, f), ln.p0, ln.p1), 0, abs(sp.sweep))
    assert b.converged
    assert b.lb <= est + 1e-12            # a lower bound of the true minimum (<= est)
    assert b.ub <= est + tol              # and the realised distance is within tol of it
    assert b.ub - b.lb <= tol
    # the witness is a genuine spiral point (polar radius rho0 + b*phi at its
    # swept angle phi) at distance ub from the line
    v = np.array(b.wa) - np.array(sp.center)
    phi = ((math.atan2(v[1], v[0]) - sp.theta0) * math.copysign(1, sp.sweep)) % (2 * math.pi)
    assert phi <= abs(sp.sweep) + 1e-12
    assert math.hypot(*v) == pytest.approx(sp.rho0 + sp.b * phi, abs=1e-9)
    assert _dist_point_line(np.array(b.wa), ln.p0, ln.p1) == pytest.approx(b.ub, abs=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_certified_spiral_to_arc(seed):
    rng = np.random.default_rng(10 + seed)
    sp = Spiral(tuple(rng.uniform(-1, 1, 2)), rng.uniform(3, 5), rng.uniform(3, 5),
                rng.uniform(-3, 3), rng.choice([-1, 1]) * rng.uniform(1, 4))
    arc = Arc(tuple(rng.uniform(-1, 1, 2)), rng.uniform(6, 9), rng.uniform(-3, 3),
              rng.choice([-1, 1]) * rng.uniform(0.5, 3))
    true = _true_min(lambda f: _point_dist(_spiral_point(sp, f)[None, :], arc)[0], 0,
                     abs(sp.sweep), 4001)
    b = certified.min_distance(sp, arc, 1e-7)
    assert b.lb <= true + 1e-12 and b.ub <= true + 1e-7 and b.ub - b.lb <= 1e-7


@pytest.mark.slow
def test_certified_bezier_to_line_and_spiral_to_spiral():
    bz = BezierCurve(((0, 0), (2, 3), (5, -1), (7, 2)))
    ln = Line((0, 3), (8, 2.5))
    ts = np.linspace(0, 1, 200_001)
    P = np.asarray(bz.control_points)
    pts = ((1 - ts) ** 3)[:, None] * P[0] + (3 * ts * (1 - ts) ** 2)[:, None] * P[1] \
        + (3 * ts ** 2 * (1 - ts))[:, None] * P[2] + (ts ** 3)[:, None] * P[3]
    true = min(_dist_point_line(p, ln.p0, ln.p1) for p in pts[::50])
    true = min(true, _true_min(lambda t: _dist_point_line(
        ((1 - t) ** 3) * P[0] + 3 * t * (1 - t) ** 2 * P[1] + 3 * t * t * (1 - t) * P[2]
        + t ** 3 * P[3], ln.p0, ln.p1), 0, 1))
    b = certified.min_distance(bz, ln, 1e-7)
    assert b.lb <= true + 1e-12 <= b.ub + 1e-12 and b.ub - b.lb <= 1e-7
    s1 = Spiral((0, 0), 3, 4, 0.0, 2.0)
    s2 = Spiral((0.5, 0), 6, 5, 0.3, 2.5)
    q1 = np.array([_spiral_point(s1, f) for f in np.linspace(0, 2.0, 3001)])
    q2 = np.array([_spiral_point(s2, f) for f in np.linspace(0, 2.5, 300_001)])
    true = cKDTree(q2).query(q1)[0].min()
    b = certified.min_distance(s1, s2, 1e-7)
    assert b.lb <= true + 1e-9 and b.ub - b.lb <= 1e-7 and b.ub <= true + 1e-3


def test_certified_max_distance_spiral_vs_arc():
    # a spiral about the arc's centre: the farthest point is where the radii
    # differ most (the radial distance, the arc covering every angle used)
    arc = Arc((0, 0), 10.0, 0.0, 2.0)
    sp = Spiral((0, 0), 8.0, 7.0, 0.2, 1.5)
    b = certified.max_distance(sp, arc, 1e-7)
    assert b.lb <= 3.0 + 1e-12 <= b.ub + 1e-12 and b.ub - b.lb <= 1e-7


# --------------------------------------------------------------------------- broad phase


def test_broad_phase_finds_every_overlapping_pair_once():
    rng = np.random.default_rng(5)
    n, m = 1500, 1200
    lo = rng.uniform(0, 100, (n, 2))
    tool = np.c_[lo, lo + rng.exponential(1.0, (n, 2))]
    lo = rng.uniform(0, 100, (m, 2))
    elem = np.c_[lo, lo + rng.exponential(1.0, (m, 2))]
    elem[:3, 2:] = elem[:3, :2] + 60.0          # a few huge boxes (direct test path)
    tool[:2, 2:] = tool[:2, :2] + 70.0
    reach = rng.uniform(0, 0.5, m)
    it, je = candidate_pairs(tool, elem, reach)
    got = set(zip(it.tolist(), je.tolist()))
    assert len(got) == it.size                   # no pair twice
    g = elem + np.c_[-reach, -reach, reach, reach]
    ov = ((tool[:, None, 0] <= g[None, :, 2]) & (g[None, :, 0] <= tool[:, None, 2])
          & (tool[:, None, 1] <= g[None, :, 3]) & (g[None, :, 1] <= tool[:, None, 3]))
    want = set(zip(*map(lambda a: a.tolist(), np.nonzero(ov))))
    assert got == want
    assert MAX_CELLS < 70 * 70                   # the huge boxes did take the direct route


# --------------------------------------------------------------------------- open ends


@pytest.mark.parametrize("which", ["line", "arc-ccw", "arc-cw"])
def test_end_regions_are_the_points_nearest_an_end(which):
    if which == "line":
        g = Line((1.0, 2.0), (6.0, -1.0))
    elif which == "arc-ccw":
        g = Arc((0.0, 0.0), 4.0, 0.5, 2.0)
    else:
        g = Arc((0.0, 0.0), 4.0, 0.5, -2.5)
    E = pack([g])
    pts = np.random.default_rng(1).uniform(-9, 9, (4000, 2))
    curve = dense(g, 50_001)
    _, k = cKDTree(curve).query(pts)
    for start, end in ((True, False), (False, True)):
        reg = end_regions(E, 0, start, end)
        got = in_regions(reg, pts)
        want = (k == 0) if start else (k == len(curve) - 1)
        # sampling decides ties within ~1e-4 of a boundary either way
        d_end = np.hypot(*(pts - (g.start if start else g.end)).T)
        d_in = cKDTree(curve[1:-1]).query(pts)[0]
        clear = np.abs(d_end - d_in) > 1e-3
        assert np.array_equal(got[clear], want[clear])


def test_clipped_distance_ignores_the_part_beyond_an_open_end():
    # element (0,0)->(10,0), open at its start: the tool line from (-3, 0.5) to
    # (2, 2) counts only where x > 0, from (0, 1.4) on: distance 1.4
    E = pack([Line((0.0, 0.0), (10.0, 0.0))])
    reg = end_regions(E, 0, True, False)
    d, wt, we = clipped_distance(Line((-3.0, 0.5), (2.0, 2.0)), E.geom(0), reg)
    assert d == pytest.approx(1.4, abs=1e-12)
    assert wt == pytest.approx((0.0, 1.4), abs=1e-12) and we == pytest.approx((0.0, 0.0))
    # entirely beyond the end: nothing counts
    d, _, _ = clipped_distance(Line((-3.0, 0.5), (-1.0, 0.1)), E.geom(0), reg)
    assert d == math.inf


# --------------------------------------------------------------------------- contour


def test_contour_geometry_is_block_geometry():
    for case in bundled_cases():
        if case.expect == "error":
            continue
        prog = ccopt.read_program(case.program)
        C = contour_of(prog, radius=case.radius)
        for j, b in enumerate(C.blocks):
            want = block_geometry(b)
            got = C.elements.geom(j)
            assert type(got) is type(want), case.name
            assert np.allclose(got.start, want.start, atol=1e-12)
            assert np.allclose(got.end, want.end, atol=1e-12)
            if isinstance(want, Arc):
                assert got.center == pytest.approx(want.center, abs=1e-12)
                assert got.radius == pytest.approx(want.radius, abs=1e-12)
                assert got.sweep == pytest.approx(want.sweep, abs=1e-12)
            assert np.allclose(C.elements.bbox[j], want.bbox(), atol=1e-12)


def test_contour_classification():
    prog = ccopt.read_program(next(c for c in bundled_cases()
                                   if c.name == "sidechange-through-line").program)
    C = contour_of(prog)
    # lead-in X0 Y0 (not contour), X20 Y0 (steady, left), X40 Y0 (side change:
    # a transition, not contour), lead-out: one element, open at both ends
    assert len(C) == 1
    assert C.side.tolist() == [1] and C.steady.tolist() == [True]
    assert C.open_start.tolist() == [True] and C.open_end.tolist() == [True]
    prog = ccopt.read_program(next(c for c in bundled_cases() if c.name == "pocket").program)
    C = contour_of(prog)
    # the pocket's wall is a closed loop from (0, 20) back to (0, 20): its first
    # element starts where its last ends, a joint of the surface, so no end is
    # open (the lead-in and lead-out meet the wall there)
    assert C.steady.all() and not C.open_start.any() and not C.open_end.any()
    assert (C.radius == 3.0).all() and (C.clearance == 3.0).all()
