"""Completeness of the intersection kernels: on random pairs the kernels return
exactly as many points as an independent count says (dense sampling, the
quadratic's discriminant, the classic centre-distance test, the law of
cosines), every point on both curves; the vectorised kernels agree with the
scalar ones and raise no numpy warning on degenerate pairs.

Pairs within 1e-6 (relative) of a tangency, or with a crossing within 1e-6
of a piece's end, are ambiguous for an independent count and skipped."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from ccopt.geometry import Arc, Line, circle_circle, intersections, line_circle
from ccopt.geometry.intersect_many import circles_circles, lines_circles, lines_lines

N_PAIRS = 1000
ON = 1e-9           # "on the curve" tolerance (coordinates are O(10))
NEAR = 1e-6         # ambiguity margin for the independent count
SAMPLES = 20001     # dense samples along a segment
TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------- helpers
def dist_to_line(p, a, b):
    """Distance from ``p`` to the infinite line through ``a``, ``b``."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    return abs(dx * (p[1] - a[1]) - dy * (p[0] - a[0])) / math.hypot(dx, dy)


def on_segment(p, seg: Line, tol=ON):
    (x0, y0), (x1, y1) = seg.p0, seg.p1
    L = seg.length
    s = ((p[0] - x0) * (x1 - x0) + (p[1] - y0) * (y1 - y0)) / L
    return dist_to_line(p, seg.p0, seg.p1) <= tol and -tol <= s <= L + tol


def on_circle(p, c, R, tol=ON):
    return abs(math.hypot(p[0] - c[0], p[1] - c[1]) - R) <= tol


def along(phi, theta0, sweep):
    """Angle travelled from theta0 in the sweep's direction to reach phi, in [0, 2 pi)."""
    return ((phi - theta0) * math.copysign(1.0, sweep)) % TWO_PI


def passes(phi, theta0, sweep):
    """How many times the arc passes polar angle phi; None when within NEAR of an end."""
    off = along(phi, theta0, sweep)
    if off < NEAR or off > TWO_PI - NEAR:
        return None
    n, k = 0, 0
    while off + TWO_PI * k <= abs(sweep) + NEAR:
        if abs(off + TWO_PI * k - abs(sweep)) < NEAR:
            return None
        n += 1
        k += 1
    return n


def on_arc(p, arc: Arc, tol=ON):
    if not on_circle(p, arc.center, arc.radius, tol):
        return False
    off = along(math.atan2(p[1] - arc.center[1], p[0] - arc.center[0]), arc.theta0, arc.sweep)
    slack = tol / arc.radius
    return off <= abs(arc.sweep) + slack or off >= TWO_PI - slack


def segment_roots(p0, p1, c, R):
    """Analytic roots t of |p0 + t (p1 - p0) - c| = R (all real t), or None if near-tangent."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    fx, fy = p0[0] - c[0], p0[1] - c[1]
    h = abs(dx * (c[1] - p0[1]) - dy * (c[0] - p0[0])) / math.hypot(dx, dy)
    if abs(h - R) <= NEAR * R:
        return None
    a = dx * dx + dy * dy
    b = 2.0 * (dx * fx + dy * fy)
    cc = fx * fx + fy * fy - R * R
    disc = b * b - 4.0 * a * cc
    if disc < 0.0:
        assert h > R
        return []
    assert h < R
    sq = math.sqrt(disc)
    return sorted([(-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)])


def sign_changes(p0, p1, c, R, n=SAMPLES):
    """Sign changes of |p(t) - c| - R on dense samples of t in [0, 1]."""
    t = np.linspace(0.0, 1.0, n)
    x = p0[0] + t * (p1[0] - p0[0]) - c[0]
    y = p0[1] + t * (p1[1] - p0[1]) - c[1]
    f = np.hypot(x, y) - R
    assert np.all(f != 0.0)
    return int(np.count_nonzero(f[:-1] * f[1:] < 0.0))


def random_line_circle_pairs(seed):
    """Infinite lines ``p + t d`` (d unit) and circles ``(c, R)``, as arrays."""
    rng = np.random.default_rng(seed)
    p = rng.uniform(-5, 5, (N_PAIRS, 2))
    phi = rng.uniform(-math.pi, math.pi, N_PAIRS)
    d = np.c_[np.cos(phi), np.sin(phi)]
    c = rng.uniform(-3, 3, (N_PAIRS, 2))
    R = rng.uniform(0.2, 4.0, N_PAIRS)
    return p, d, c, R


def random_circle_pairs(seed):
    rng = np.random.default_rng(seed)
    c1 = rng.uniform(-3, 3, (N_PAIRS, 2))
    c2 = rng.uniform(-3, 3, (N_PAIRS, 2))
    R1 = rng.uniform(0.2, 4.0, N_PAIRS)
    R2 = rng.uniform(0.2, 4.0, N_PAIRS)
    return c1, R1, c2, R2


def classic_circle_count(c1, R1, c2, R2):
    """2 if |R1 - R2| < D < R1 + R2, else 0; None within NEAR (relative) of tangency."""
    D = math.hypot(c2[0] - c1[0], c2[1] - c1[1])
    rsum = R1 + R2
    if abs(D - rsum) <= NEAR * rsum or abs(D - abs(R1 - R2)) <= NEAR * rsum:
        return None
    return 2 if abs(R1 - R2) < D < rsum else 0


def law_of_cosines_angles(c1, R1, c2, R2):
    """Polar angles of the two crossing points about c1 and about c2: [(phi1, phi2)]."""
    D = math.hypot(c2[0] - c1[0], c2[1] - c1[1])
    base1 = math.atan2(c2[1] - c1[1], c2[0] - c1[0])
    base2 = base1 + math.pi
    alpha = math.acos((R1 * R1 + D * D - R2 * R2) / (2.0 * R1 * D))   # angle at c1
    beta = math.acos((R2 * R2 + D * D - R1 * R1) / (2.0 * R2 * D))    # angle at c2
    # The point left of c1 -> c2 is at base1 + alpha about c1 and base2 - beta about c2.
    return [(base1 + alpha, base2 - beta), (base1 - alpha, base2 + beta)]


# --------------------------------------------------------------------------- line-circle
def test_line_circle_infinite_count_is_complete():
    p, d, c, R = random_line_circle_pairs(101)
    checked = hits = 0
    for i in range(N_PAIRS):
        h = abs(d[i, 0] * (c[i, 1] - p[i, 1]) - d[i, 1] * (c[i, 0] - p[i, 0]))
        if abs(h - R[i]) <= NEAR * R[i]:
            continue
        expected = 2 if h < R[i] else 0
        q = p[i] + d[i]
        res = line_circle(p[i], q, c[i], R[i])
        assert len(res) == expected, (p[i], q, c[i], R[i], res)
        for pt, t, theta in res:
            assert dist_to_line(pt, p[i], q) <= ON and on_circle(pt, c[i], R[i])
            assert np.allclose(p[i] + t * d[i], pt, atol=ON)
            assert np.allclose(c[i] + R[i] * np.array([math.cos(theta), math.sin(theta)]), pt,
                               atol=ON)
        if len(res) == 2:
            assert res[0][1] < res[1][1]
        checked += 1
        hits += expected
    assert checked >= 990 and hits >= 400


def random_segment_circle(rng, sweep):
    """A random segment and arc (``sweep`` given, or drawn in +-3 pi when ``None``) with
    the segment's parameters where its line crosses the circle (``roots``, by the
    discriminant), those within it (``inside``) and their points; ``None`` when the
    segment or the sweep is degenerate or a root is within ``NEAR`` of a segment end."""
    p0, p1 = tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2))
    c, R = tuple(rng.uniform(-3, 3, 2)), rng.uniform(0.2, 4.0)
    theta0 = rng.uniform(-math.pi, math.pi)
    if sweep is None:
        sweep = rng.uniform(-3 * math.pi, 3 * math.pi)
    if math.dist(p0, p1) < 1e-3 or abs(sweep) < 1e-3:
        return None
    roots = segment_roots(p0, p1, c, R)
    if roots is None or any(abs(t) < NEAR or abs(t - 1.0) < NEAR for t in roots):
        return None
    inside = [t for t in roots if 0.0 < t < 1.0]
    pts = [(p0[0] + t * (p1[0] - p0[0]), p0[1] + t * (p1[1] - p0[1])) for t in inside]
    return p0, p1, c, R, theta0, sweep, roots, inside, pts


def test_segment_full_circle_count_is_complete():
    rng = np.random.default_rng(102)
    checked = sampled = total = 0
    for _ in range(N_PAIRS):
        pair = random_segment_circle(rng, rng.choice([-TWO_PI, TWO_PI]))
        if pair is None:
            continue
        p0, p1, c, R, theta0, sweep, roots, inside, pts = pair
        angles = [math.atan2(q[1] - c[1], q[0] - c[0]) for q in pts]
        if any(passes(a, theta0, sweep) is None for a in angles):
            continue                                   # crossing at the circle's seam
        expected = len(inside)
        # Dense sampling agrees with the discriminant wherever the roots are
        # more than two samples apart.
        if len(roots) < 2 or roots[1] - roots[0] > 2.0 / (SAMPLES - 1):
            assert sign_changes(p0, p1, c, R) == expected, (p0, p1, c, R)
            sampled += 1
        seg, circ = Line(p0, p1), Arc(c, R, theta0, sweep)
        res = intersections(seg, circ)
        assert len(res) == expected, (p0, p1, c, R, theta0, sweep, res)
        for pt, sa, sb in res:
            assert on_segment(pt, seg) and on_circle(pt, c, R)
            assert np.allclose(seg.point(sa), pt, atol=ON)
            assert np.allclose(circ.point(sb), pt, atol=ON)
        assert [h[1] for h in res] == sorted(h[1] for h in res)
        checked += 1
        total += expected
    assert checked >= 980 and sampled >= 970 and total >= 300


def test_segment_arc_count_is_complete():
    """Segments against arcs of any sweep, including multi-turn ones (one entry per pass)."""
    rng = np.random.default_rng(103)
    checked = total = 0
    for _ in range(N_PAIRS):
        pair = random_segment_circle(rng, None)
        if pair is None:
            continue
        p0, p1, c, R, theta0, sweep, roots, inside, pts = pair
        counts = [passes(math.atan2(q[1] - c[1], q[0] - c[0]), theta0, sweep) for q in pts]
        if any(n is None for n in counts):
            continue
        expected = sum(counts)
        seg, arc = Line(p0, p1), Arc(c, R, theta0, sweep)
        for a, b, swap in ((seg, arc, False), (arc, seg, True)):
            res = intersections(a, b)
            assert len(res) == expected, (p0, p1, c, R, theta0, sweep, swap, res)
            for pt, sa, sb in res:
                s_seg, s_arc = (sb, sa) if swap else (sa, sb)
                assert on_segment(pt, seg) and on_arc(pt, arc)
                assert np.allclose(seg.point(s_seg), pt, atol=ON)
                assert np.allclose(arc.point(s_arc), pt, atol=ON)
        checked += 1
        total += expected
    assert checked >= 980 and total >= 200


# --------------------------------------------------------------------------- circle-circle
def test_circle_circle_count_is_complete():
    c1, R1, c2, R2 = random_circle_pairs(201)
    checked = hits = 0
    for i in range(N_PAIRS):
        expected = classic_circle_count(c1[i], R1[i], c2[i], R2[i])
        if expected is None:
            continue
        res = circle_circle(c1[i], R1[i], c2[i], R2[i])
        assert len(res) == expected, (c1[i], R1[i], c2[i], R2[i], res)
        for pt, th1, th2 in res:
            assert on_circle(pt, c1[i], R1[i]) and on_circle(pt, c2[i], R2[i])
        if expected == 2:
            # Same points as the law of cosines gives, left of c1 -> c2 first.
            for (pt, th1, th2), (phi1, phi2) in zip(res, law_of_cosines_angles(
                    c1[i], R1[i], c2[i], R2[i])):
                q1 = c1[i] + R1[i] * np.array([math.cos(phi1), math.sin(phi1)])
                q2 = c2[i] + R2[i] * np.array([math.cos(phi2), math.sin(phi2)])
                assert np.allclose(pt, q1, atol=ON) and np.allclose(pt, q2, atol=ON)
        checked += 1
        hits += expected
    assert checked >= 990 and hits >= 600


def test_arc_arc_count_is_complete():
    rng = np.random.default_rng(202)
    checked = total = 0
    for _ in range(N_PAIRS):
        c1, c2 = tuple(rng.uniform(-3, 3, 2)), tuple(rng.uniform(-3, 3, 2))
        R1, R2 = rng.uniform(0.2, 4.0), rng.uniform(0.2, 4.0)
        t1, t2 = rng.uniform(-math.pi, math.pi, 2)
        s1, s2 = rng.uniform(-3 * math.pi, 3 * math.pi, 2)
        if abs(s1) < 1e-3 or abs(s2) < 1e-3:
            continue
        n = classic_circle_count(c1, R1, c2, R2)
        if n is None:
            continue
        counts = []
        if n == 2:
            for phi1, phi2 in law_of_cosines_angles(c1, R1, c2, R2):
                k1, k2 = passes(phi1, t1, s1), passes(phi2, t2, s2)
                counts.append(None if k1 is None or k2 is None else k1 * k2)
        if any(k is None for k in counts):
            continue
        expected = sum(counts)
        a, b = Arc(c1, R1, t1, s1), Arc(c2, R2, t2, s2)
        res = intersections(a, b)
        assert len(res) == expected, (c1, R1, t1, s1, c2, R2, t2, s2, res)
        for pt, sa, sb in res:
            assert on_arc(pt, a) and on_arc(pt, b)
            assert np.allclose(a.point(sa), pt, atol=ON) and np.allclose(b.point(sb), pt, atol=ON)
        checked += 1
        total += expected
    assert checked >= 980 and total >= 300


# --------------------------------------------------------------------------- vectorised
def test_lines_circles_matches_scalar_and_independent_count():
    p, d, c, R = random_line_circle_pairs(101)
    x1, x2, n, delicate = lines_circles(p, d, c, R)
    assert x1.shape == x2.shape == (N_PAIRS, 2) and n.shape == delicate.shape == (N_PAIRS,)
    compared = 0
    for i in np.flatnonzero(~delicate):
        ref = line_circle(p[i], p[i] + d[i], c[i], R[i])
        assert n[i] == len(ref), (p[i], d[i], c[i], R[i], n[i], ref)
        h = abs(d[i, 0] * (c[i, 1] - p[i, 1]) - d[i, 1] * (c[i, 0] - p[i, 0]))
        if abs(h - R[i]) > NEAR * R[i]:
            assert n[i] == (2 if h < R[i] else 0)
        if n[i] == 2:
            assert np.allclose(x1[i], ref[0][0], atol=ON) and np.allclose(x2[i], ref[1][0], atol=ON)
            for x in (x1[i], x2[i]):
                assert dist_to_line(x, p[i], p[i] + d[i]) <= ON and on_circle(x, c[i], R[i])
        compared += 1
    assert compared >= 990


def test_circles_circles_matches_scalar_and_independent_count():
    c1, R1, c2, R2 = random_circle_pairs(201)
    x1, x2, n, delicate = circles_circles(c1, R1, c2, R2)
    assert x1.shape == x2.shape == (N_PAIRS, 2) and n.shape == delicate.shape == (N_PAIRS,)
    compared = 0
    for i in np.flatnonzero(~delicate):
        ref = circle_circle(c1[i], R1[i], c2[i], R2[i])
        assert n[i] == len(ref), (c1[i], R1[i], c2[i], R2[i], n[i], ref)
        expected = classic_circle_count(c1[i], R1[i], c2[i], R2[i])
        if expected is not None:
            assert n[i] == expected
        if n[i] == 2:
            assert np.allclose(x1[i], ref[0][0], atol=ON) and np.allclose(x2[i], ref[1][0], atol=ON)
            for x in (x1[i], x2[i]):
                assert on_circle(x, c1[i], R1[i]) and on_circle(x, c2[i], R2[i])
        compared += 1
    assert compared >= 990


def test_vectorised_kernels_emit_no_warning_on_degenerate_pairs():
    # lines_lines: parallel, antiparallel and collinear next to one ordinary crossing.
    p = np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]])
    d = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0]])
    q = np.array([[0.0, 1.0], [3.0, 0.0], [2.0, 5.0], [2.0, -1.0]])
    e = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        x, _, n, delicate = lines_lines(p, d, q, e)
    assert delicate.tolist() == [True, True, True, False]
    assert n.tolist() == [0, 0, 0, 1]
    assert np.allclose(x[3], (2.0, 0.0))

    # circles_circles: concentric (different radii), identical, and one ordinary pair.
    c1 = np.array([[1.0, 2.0], [1.0, 2.0], [0.0, 0.0]])
    R1 = np.array([1.0, 1.5, 1.0])
    c2 = np.array([[1.0, 2.0], [1.0, 2.0], [1.0, 0.0]])
    R2 = np.array([2.0, 1.5, 1.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        x1, x2, n, delicate = circles_circles(c1, R1, c2, R2)
    assert delicate.tolist() == [True, True, False]
    assert n.tolist() == [0, 0, 2]
    assert np.allclose(x1[2], (0.5, math.sqrt(3) / 2)) and np.allclose(x2[2], (0.5, -math.sqrt(3) / 2))

    # lines_circles: through the centre, tangent, missing, far away.
    p = np.array([[-5.0, 0.0], [-5.0, 1.0], [-5.0, 3.0], [1e8, 1e8]])
    d = np.array([[1.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    c = np.zeros((4, 2))
    R = np.ones(4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        x1, x2, n, delicate = lines_circles(p, d, c, R)
    assert delicate.tolist() == [False, True, False, False]
    assert n[0] == 2 and n[2] == 0 and n[3] == 0
    assert np.allclose(x1[0], (-1.0, 0.0)) and np.allclose(x2[0], (1.0, 0.0))
