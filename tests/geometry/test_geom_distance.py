"""Closed-form distance kernels against dense brute-force sampling.

For each kernel, 1,000 seeded random pairs (with degenerate cases mixed in:
zero-length segments, zero and full sweeps, concentric arcs, points at arc
centres, crossings). With curves sampled every ``h`` of arc length, every
curve point is within ``h/2`` of a sample, so

    0 <= sampled_min - kernel <= (h_a + h_b) / 2      (+1e-12 rounding)

must hold. A damped Newton refinement started at the best sample pair then pins the
local minimum far more tightly and the kernel must match it to 1e-9.
Witnesses must lie on their curves and be ``d`` apart.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from _geom_sampling import (TAU, dist_to_segment, on_arc, random_arcs, random_points,
                            random_segments, sample_arc, sample_segment)

from ccopt.geometry import (KIND_ARC, KIND_LINE, KIND_SPIRAL, Arc, Line, SegmentArray, Spiral,
                            arc_arc, distance, pair_distance, point_arc, point_point,
                            point_segment, segment_arc, segment_segment)

N = 1000
M = 400          # samples per curve for the brute force


# --------------------------------------------------------------------------- curves by kind
# A curve is a function of fractions t (shape (n, k), one row per pair) giving
# points (n, k, 2); with derivs=True it also gives dp/dt and d2p/dt2.


def seg_curve(a0, a1):
    def f(t, derivs=False):
        r = (a1 - a0)[:, None, :]
        p = a0[:, None, :] + t[..., None] * r
        if not derivs:
            return p
        return p, np.broadcast_to(r, p.shape), np.zeros_like(p)
    return f


def arc_curve(c, R, th0, sw):
    def f(t, derivs=False):
        ang = th0[:, None] + sw[:, None] * t
        e = np.stack([np.cos(ang), np.sin(ang)], axis=-1)
        p = c[:, None, :] + R[:, None, None] * e
        if not derivs:
            return p
        e_perp = np.stack([-e[..., 1], e[..., 0]], axis=-1)
        k = (R * sw)[:, None, None]
        return p, k * e_perp, -(R * sw * sw)[:, None, None] * e
    return f


def point_curve(p):
    def f(t, derivs=False):
        q = np.broadcast_to(p[:, None, :], t.shape + (2,))
        if not derivs:
            return q
        return q, np.zeros_like(q), np.zeros_like(q)
    return f


def refined_min(fa, fb, ta, tb, fixed_a=False, iters=60):
    """Local minimum of |A(t) - B(u)| over the box [0,1]^2 from starts (ta, tb).

    A generic optimiser on the curve definitions, no closed form: damped
    (Levenberg-Marquardt) Newton on f = |A(t) - B(u)|^2 / 2 with the exact
    Hessian, variables pinned while they sit on a bound the gradient pushes
    against, steps accepted only when f decreases. Vectorised over pairs.
    """
    x = np.stack([ta, tb], axis=1).astype(float)

    def evaluate(x):
        pa, da, dda = (np.array(v[:, 0]) for v in fa(x[:, :1], True))
        pb, db, ddb = (np.array(v[:, 0]) for v in fb(x[:, 1:], True))
        return pa - pb, da, dda, db, ddb

    G, da, dda, db, ddb = evaluate(x)
    f = 0.5 * (G * G).sum(-1)
    lam = np.full(len(x), 1e-3)
    for _ in range(iters):
        g0 = (G * da).sum(-1)
        g1 = -(G * db).sum(-1)
        H00 = (da * da).sum(-1) + (G * dda).sum(-1)
        H11 = (db * db).sum(-1) - (G * ddb).sum(-1)
        H01 = -(da * db).sum(-1)
        free0 = ~(((x[:, 0] <= 0) & (g0 > 0)) | ((x[:, 0] >= 1) & (g0 < 0)))
        free1 = ~(((x[:, 1] <= 0) & (g1 > 0)) | ((x[:, 1] >= 1) & (g1 < 0)))
        if fixed_a:
            free0[:] = False
        D0 = (da * da).sum(-1) + 1e-300
        D1 = (db * db).sum(-1) + 1e-300
        A00 = np.where(free0, H00 + lam * D0, 1.0)
        A11 = np.where(free1, H11 + lam * D1, 1.0)
        A01 = np.where(free0 & free1, H01, 0.0)
        b0 = np.where(free0, -g0, 0.0)
        b1 = np.where(free1, -g1, 0.0)
        det = A00 * A11 - A01 * A01
        pd = (A00 > 0) & (A11 > 0) & (det > 0)
        det = np.where(pd, det, 1.0)
        step = np.stack([(b0 * A11 - A01 * b1) / det, (A00 * b1 - A01 * b0) / det], axis=1)
        step[~pd] = 0.0
        xn = np.clip(x + step, 0.0, 1.0)
        Gn, dan, ddan, dbn, ddbn = evaluate(xn)
        fn = 0.5 * (Gn * Gn).sum(-1)
        ok = pd & (fn < f)
        x[ok], G[ok], da[ok], dda[ok], db[ok], ddb[ok], f[ok] = (
            xn[ok], Gn[ok], dan[ok], ddan[ok], dbn[ok], ddbn[ok], fn[ok])
        lam = np.where(ok, np.maximum(lam / 3.0, 1e-12), np.minimum(lam * 4.0, 1e12))
    return np.sqrt(2.0 * f)


def coarse_blocks(P, Q, blocks, chunk=50):
    """Sampled minimum per pair and, for a ``blocks x blocks`` tiling of the
    sample grid, each tile's best sample pair (the refinement's starts, so that
    every basin -- e.g. both crossings of a line and a circle -- gets one).

    Returns ``(dmin (n,), ia (n, T), ib (n, T))`` with T tiles.
    """
    n, ma, mb = P.shape[0], P.shape[1], Q.shape[1]
    ka, kb = min(blocks, ma), min(blocks, mb)
    sa, sb = ma // ka, mb // kb
    dmin = np.empty(n)
    ia = np.empty((n, ka * kb), dtype=int)
    ib = np.empty((n, ka * kb), dtype=int)
    for i in range(0, n, chunk):
        sl = slice(i, i + chunk)
        d2 = P[sl, :, None, 0] - Q[sl, None, :, 0]
        d2 *= d2
        dy = P[sl, :, None, 1] - Q[sl, None, :, 1]
        dy *= dy
        d2 += dy
        m = d2.shape[0]
        dmin[sl] = np.sqrt(d2.reshape(m, -1).min(axis=1))
        tiles = d2.reshape(m, ka, sa, kb, sb).transpose(0, 1, 3, 2, 4).reshape(m, ka * kb, sa * sb)
        j = tiles.argmin(axis=2)
        ia[sl] = (np.arange(ka * kb) // kb)[None, :] * sa + j // sb
        ib[sl] = (np.arange(ka * kb) % kb)[None, :] * sb + j % sb
    return dmin, ia, ib


def check_against_brute_force(d, fa, fb, ha, hb, ma, mb):
    """Core assertions for one kernel's output ``d`` (N,)."""
    ta = np.linspace(0, 1, ma)
    tb = np.linspace(0, 1, mb)
    P = fa(np.broadcast_to(ta, (N, ma)))
    Q = fb(np.broadcast_to(tb, (N, mb)))
    smin, ia, ib = coarse_blocks(P, Q, blocks=8)
    gap = smin - d
    assert np.all(gap >= -1e-12), f"kernel above sampled min by {-gap.min():.3g}"
    bound = 0.5 * (ha + hb) + 1e-12
    assert np.all(gap <= bound), f"gap {np.max(gap - bound):.3g} beyond sampling bound"
    # Refine from each tile's best sample pair: every refined figure is a
    # genuine distance, so the kernel may not exceed any of them; and as the
    # kernel's witnesses are checked to be on the curves, d cannot be below
    # the true minimum, so a close match pins d to the true minimum.
    zmin = smin.copy()
    for k in range(ia.shape[1]):
        z = refined_min(fa, fb, ta[ia[:, k]], tb[ib[:, k]], fixed_a=(ma == 1))
        np.minimum(zmin, z, out=zmin)
    assert np.all(d <= zmin + 1e-12)
    assert np.max(zmin - d) <= 1e-9, f"refined gap {np.max(zmin - d):.3g}"


def check_witnesses(d, wa, wb, tol=1e-9):
    assert d.shape == (N,) and wa.shape == (N, 2) and wb.shape == (N, 2)
    assert np.all(np.isfinite(d)) and np.all(d >= 0)
    assert np.allclose(np.hypot(*(wa - wb).T), d, rtol=0, atol=tol)


# --------------------------------------------------------------------------- kernels


def test_point_point():
    rng = np.random.default_rng(1)
    p, q = random_points(rng, N), random_points(rng, N)
    d, wa, wb = point_point(p, q)
    assert np.allclose(d, np.sqrt(((p - q) ** 2).sum(-1)), rtol=1e-15)
    assert np.array_equal(wa, p) and np.array_equal(wb, q)


def test_point_segment_brute_force():
    rng = np.random.default_rng(2)
    p = random_points(rng, N)
    a0, a1 = random_segments(rng, N)
    # Some points exactly on their segments.
    p[50:80] = a0[50:80] + rng.uniform(0, 1, (30, 1)) * (a1[50:80] - a0[50:80])
    d, wa, wb = point_segment(p, a0, a1)
    check_witnesses(d, wa, wb)
    assert np.array_equal(wa, p)
    assert np.all(dist_to_segment(wb, a0, a1) <= 1e-12)
    _, h = sample_segment(a0, a1, M)
    check_against_brute_force(d, point_curve(p), seg_curve(a0, a1), 0 * h, h, 1, M)
    assert np.all(d[50:80] <= 1e-14)


def test_point_arc_brute_force():
    rng = np.random.default_rng(3)
    p = random_points(rng, N)
    c, R, th0, sw = random_arcs(rng, N)
    p[60:90] = c[60:90]                      # at the centre: distance R
    d, wa, wb = point_arc(p, c, R, th0, sw)
    check_witnesses(d, wa, wb)
    assert np.all(on_arc(wb, c, R, th0, sw, 1e-9))
    assert np.allclose(d[60:90], R[60:90], rtol=1e-14)
    _, h = sample_arc(c, R, th0, sw, M)
    check_against_brute_force(d, point_curve(p), arc_curve(c, R, th0, sw), 0 * h, h, 1, M)


def test_point_arc_hand_worked():
    # Quarter arc (1,0) -> (0,1) ccw about the origin.
    d, _, w = point_arc([[2.0, 2.0], [0.5, 0.0], [-1.0, -1.0], [0.0, 0.0], [1.0, -3.0]],
                        (0.0, 0.0), 1.0, 0.0, math.pi / 2)
    assert np.allclose(d, [2 * math.sqrt(2) - 1, 0.5, math.sqrt(5), 1.0, 3.0], atol=1e-15)
    assert np.allclose(w[0], [math.sqrt(0.5)] * 2) and np.allclose(w[4], [1.0, 0.0])
    # Same end points clockwise (three quarters): (-1,-1) is now radially outside.
    d, _, _ = point_arc([-1.0, -1.0], (0.0, 0.0), 1.0, 0.0, -1.5 * math.pi)
    assert math.isclose(d[0], math.sqrt(2) - 1)


@pytest.mark.slow
def test_segment_segment_brute_force():
    rng = np.random.default_rng(4)
    a0, a1 = random_segments(rng, N)
    b0, b1 = random_points(rng, N), random_points(rng, N)
    # Collinear overlapping and collinear disjoint pairs.
    b0[100:120] = a0[100:120] + 0.3 * (a1[100:120] - a0[100:120])
    b1[100:120] = a0[100:120] + 1.7 * (a1[100:120] - a0[100:120])
    b0[120:140] = a0[120:140] + 1.2 * (a1[120:140] - a0[120:140])
    b1[120:140] = a0[120:140] + 2.0 * (a1[120:140] - a0[120:140])
    d, wa, wb = segment_segment(a0, a1, b0, b1)
    check_witnesses(d, wa, wb)
    assert np.all(dist_to_segment(wa, a0, a1) <= 1e-12)
    assert np.all(dist_to_segment(wb, b0, b1) <= 1e-12)
    assert np.all(d[100:120] <= 1e-12)
    la = np.hypot(*(a1 - a0)[120:140].T)
    assert np.allclose(d[120:140], 0.2 * la, rtol=1e-9)
    _, ha = sample_segment(a0, a1, M)
    _, hb = sample_segment(b0, b1, M)
    check_against_brute_force(d, seg_curve(a0, a1), seg_curve(b0, b1), ha, hb, M, M)


def test_segment_segment_crossing_agrees_with_shapely():
    shapely = pytest.importorskip("shapely")
    rng = np.random.default_rng(5)
    a0, a1 = random_points(rng, N), random_points(rng, N)
    b0, b1 = random_points(rng, N), random_points(rng, N)
    d, _, _ = segment_segment(a0, a1, b0, b1)
    ga = shapely.linestrings(np.stack([a0, a1], axis=1))
    gb = shapely.linestrings(np.stack([b0, b1], axis=1))
    assert np.allclose(d, shapely.distance(ga, gb), rtol=0, atol=1e-12)
    assert np.array_equal(d <= 1e-12, shapely.intersects(ga, gb))


@pytest.mark.slow
def test_segment_arc_brute_force():
    rng = np.random.default_rng(6)
    a0, a1 = random_segments(rng, N)
    c, R, th0, sw = random_arcs(rng, N)
    # Segments tangent to their circle (touching at the foot of the centre).
    n = np.stack([-np.sin(th0[200:230]), np.cos(th0[200:230])], axis=-1)
    touch = c[200:230] + R[200:230, None] * np.stack([np.cos(th0[200:230]),
                                                     np.sin(th0[200:230])], axis=-1)
    a0[200:230] = touch - 2.0 * n
    a1[200:230] = touch + 2.0 * n
    d, wa, wb = segment_arc(a0, a1, c, R, th0, sw)
    check_witnesses(d, wa, wb)
    assert np.all(dist_to_segment(wa, a0, a1) <= 1e-9)
    assert np.all(on_arc(wb, c, R, th0, sw, 1e-9))
    assert np.all(d[200:230] <= 1e-12)         # the arc starts on the tangent line
    _, ha = sample_segment(a0, a1, M)
    _, hb = sample_arc(c, R, th0, sw, M)
    check_against_brute_force(d, seg_curve(a0, a1), arc_curve(c, R, th0, sw), ha, hb, M, M)


@pytest.mark.slow
def test_arc_arc_brute_force():
    rng = np.random.default_rng(7)
    c1, R1, t1, s1 = random_arcs(rng, N)
    c2, R2, t2, s2 = random_arcs(rng, N)
    c2[300:350] = c1[300:350]                   # concentric
    R2[330:350] = R1[330:350]                   # co-circular
    c2[350:370] = c1[350:370] + np.array([1.0, 0.0]) * (R1[350:370] + R2[350:370])[:, None]
    d, wa, wb = arc_arc(c1, R1, t1, s1, c2, R2, t2, s2)
    check_witnesses(d, wa, wb)
    assert np.all(on_arc(wa, c1, R1, t1, s1, 1e-9))
    assert np.all(on_arc(wb, c2, R2, t2, s2, 1e-9))
    _, ha = sample_arc(c1, R1, t1, s1, M)
    _, hb = sample_arc(c2, R2, t2, s2, M)
    check_against_brute_force(d, arc_curve(c1, R1, t1, s1), arc_curve(c2, R2, t2, s2),
                              ha, hb, M, M)


def test_arc_arc_hand_worked():
    # Two unit circles 3 apart: gap 1 on the line of centres.
    d, wa, wb = arc_arc((0, 0), 1.0, 0.0, TAU, (3, 0), 1.0, 0.0, TAU)
    assert math.isclose(d[0], 1.0) and np.allclose(wa, [[1, 0]]) and np.allclose(wb, [[2, 0]])
    # Upper half of the first against lower half of the second: the line-of-centres
    # points (1,0)/(2,0) are ends of both arcs, so still 1.
    d, _, _ = arc_arc((0, 0), 1.0, 0.0, math.pi, (3, 0), 1.0, math.pi, math.pi)
    assert math.isclose(d[0], 1.0)
    # Concentric, radii 1 and 2, disjoint angular ranges: nearest ends.
    d, _, _ = arc_arc((0, 0), 1.0, 0.0, 0.5, (0, 0), 2.0, 1.0, 1.0)
    assert math.isclose(d[0], math.sqrt(1 + 4 - 4 * math.cos(0.5)))


def test_broadcasting_and_single_pairs():
    d, wa, wb = segment_segment((0, 0), (1, 0), (0, 1), (1, 1))
    assert d.shape == (1,) and wa.shape == (1, 2) and math.isclose(d[0], 1.0)
    # One arc against many points.
    p = np.array([[2.0, 0.0], [0.0, 3.0], [-4.0, 0.0]])
    d, _, _ = point_arc(p, (0.0, 0.0), 1.0, 0.0, TAU)
    assert np.allclose(d, [1.0, 2.0, 3.0])


# --------------------------------------------------------------------------- objects


def test_distance_objects():
    line = Line((-2.0, 3.0), (2.0, 3.0))
    arc = Arc((0.0, 0.0), 1.0, 0.0, math.pi)
    d, wa, wb = distance(line, arc)
    assert math.isclose(d, 2.0) and np.allclose(wa, (0, 3)) and np.allclose(wb, (0, 1))
    d2, wa2, wb2 = distance(arc, line)
    assert d2 == d and wa2 == wb and wb2 == wa
    assert distance((0.0, 0.0), arc)[0] == 1.0
    assert math.isclose(distance(line, (0.0, 0.0))[0], 3.0)
    assert distance((1.0, 1.0), (4.0, 5.0))[0] == 5.0
    assert math.isclose(distance(arc, Arc((0.0, 0.0), 3.0, 1.0, 0.5))[0], 2.0)
    with pytest.raises(ValueError):
        distance(Spiral((0, 0), 1.0, 2.0, 0.0, 1.0), line)


# --------------------------------------------------------------------------- packed


def _random_objects(rng, n):
    out = []
    for _ in range(n):
        if rng.random() < 0.5:
            out.append(Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2))))
        else:
            out.append(Arc(tuple(rng.uniform(-4, 4, 2)), rng.uniform(0.2, 3),
                           rng.uniform(-4, 4), rng.uniform(-7, 7)))
    return out


def test_pair_distance_matches_object_distance():
    rng = np.random.default_rng(11)
    objs_a, objs_b = _random_objects(rng, 60), _random_objects(rng, 50)
    A, B = SegmentArray.from_segments(objs_a), SegmentArray.from_segments(objs_b)
    assert len(A) == 60 and A.kind.dtype == np.int8
    assert set(np.unique(A.kind)) <= {KIND_LINE, KIND_ARC}
    ia = rng.integers(0, 60, 3000)
    ib = rng.integers(0, 50, 3000)
    d, wa, wb = pair_distance(A, ia, B, ib)
    ref = np.array([distance(objs_a[i], objs_b[j])[0] for i, j in zip(ia[:400], ib[:400])])
    assert np.allclose(d[:400], ref, rtol=0, atol=1e-13)
    # Witnesses are on the right rows.
    for k in range(0, 3000, 97):
        da, _, _ = distance(tuple(wa[k]), objs_a[ia[k]])
        db, _, _ = distance(tuple(wb[k]), objs_b[ib[k]])
        assert da <= 1e-9 and db <= 1e-9
    assert np.allclose(np.hypot(*(wa - wb).T), d, atol=1e-9)
    # Row round trip.
    assert A.segment(3) == objs_a[3] or np.allclose(A.segment(3).start, objs_a[3].start)


def test_pair_distance_rejects_spirals():
    A = SegmentArray.from_segments([Line((0, 0), (1, 0)), Spiral((0, 0), 1.0, 2.0, 0.0, 1.0)])
    assert A.kind[1] == KIND_SPIRAL
    assert isinstance(A.segment(1), Spiral)
    d, _, _ = pair_distance(A, [0], A, [0])
    assert d[0] == 0.0
    with pytest.raises(ValueError, match="spiral"):
        pair_distance(A, [0, 1], A, [0, 0])
    with pytest.raises(ValueError):
        A.kind[0] = 1                       # read-only packing


def test_pair_distance_empty_and_blocks():
    A = SegmentArray.from_segments([Line((0, 0), (1, 0)), Arc((0, 3), 1.0, math.pi, math.pi)])
    d, wa, wb = pair_distance(A, [], A, [])
    assert d.shape == (0,) and wa.shape == (0, 2) and wb.shape == (0, 2)
    # More pairs than one processing block: results do not depend on the blocking.
    rng = np.random.default_rng(12)
    n = 20000
    ia, ib = rng.integers(0, 2, n), rng.integers(0, 2, n)
    d, _, _ = pair_distance(A, ia, A, ib)
    ref = {(i, j): distance(A.segment(i), A.segment(j))[0] for i in (0, 1) for j in (0, 1)}
    assert np.array_equal(d, np.array([ref[i, j] for i, j in zip(ia, ib)]))
    assert math.isclose(ref[0, 1], 2.0)
