"""Certified distances of many spiral pairs at once, and the closed forms for
spirals about a common centre (a tool segment and its element, offset)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from brute_distance import point_distances
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.curve import BezierCurve
from ccopt.verify.distance import certified
from ccopt.verify.distance.certified_batch import batchable, min_distances
from ccopt.verify.distance.concentric import polar_gap


def spiral_point(sp: Spiral, phi):
    """The spiral's point at swept angle ``phi`` (its definition: polar radius
    linear in the swept angle)."""
    rho = sp.rho0 + (sp.rho1 - sp.rho0) * phi / abs(sp.sweep)
    ang = sp.theta0 + math.copysign(1.0, sp.sweep) * phi
    return np.array([sp.center[0] + rho * math.cos(ang), sp.center[1] + rho * math.sin(ang)])


def dist_to_spiral(q, sp: Spiral) -> float:
    """min |q - p| over the spiral: a fine grid, then a bounded search around its best."""
    phi = np.linspace(0.0, abs(sp.sweep), 20_001)
    pts = np.array([spiral_point(sp, f) for f in phi[::20]])
    k = 20 * int(np.argmin(np.hypot(*(pts - q).T)))
    lo, hi = phi[max(k - 40, 0)], phi[min(k + 40, phi.size - 1)]
    res = minimize_scalar(lambda f: float(np.hypot(*(spiral_point(sp, f) - q))),
                          bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
    return float(res.fun)


def random_pairs(seed: int, n: int):
    rng = np.random.default_rng(seed)
    pairs = []
    for _ in range(n):
        c = tuple(rng.uniform(-2, 2, 2))
        sp = Spiral(c, rng.uniform(2, 6), rng.uniform(2, 6), rng.uniform(-3, 3),
                    rng.choice([-1, 1]) * rng.uniform(0.5, 5))
        kind = rng.integers(4)
        if kind == 0:
            other = Line(tuple(rng.uniform(-8, 8, 2)), tuple(rng.uniform(-8, 8, 2)))
        elif kind == 1:
            other = Arc(tuple(rng.uniform(-1, 1, 2)), rng.uniform(1, 9), rng.uniform(-3, 3),
                        rng.choice([-1, 1]) * rng.uniform(0.5, 3))
        elif kind == 2:       # about the same centre: the radial bound applies
            other = Arc(c, rng.uniform(1, 9), rng.uniform(-3, 3), rng.uniform(-3, 3))
        else:
            other = Spiral(c if rng.random() < 0.5 else tuple(rng.uniform(-2, 2, 2)),
                           rng.uniform(2, 6), rng.uniform(2, 6), rng.uniform(-3, 3),
                           rng.choice([-1, 1]) * rng.uniform(0.5, 3))
        pairs.append((sp, other))
    return pairs


@pytest.mark.parametrize("seed", range(3))
def test_batch_gives_the_one_at_a_time_bounds_exactly(seed):
    pairs = random_pairs(seed, 24)
    assert all(batchable(a, b) for a, b in pairs)
    caps = [math.inf if k % 3 else 1.5 for k in range(len(pairs))]
    one = [certified.min_distance(a, b, 1e-7, cap=c) for (a, b), c in zip(pairs, caps)]
    assert min_distances(pairs, 1e-7, caps) == one


@pytest.mark.parametrize("seed", range(2))
def test_pairs_sharing_their_curves_give_the_one_at_a_time_bounds(seed):
    # a tool spiral near many elements is in many pairs (the same object): the
    # batch works out each curve's first pieces once, and must still give
    # every pair's own bounds
    pairs = random_pairs(10 + seed, 30)
    spirals = [a for a, _ in pairs[:6]]
    shared = [(spirals[k % 6], b) for k, (_, b) in enumerate(pairs) if not isinstance(b, Spiral)]
    shared += [(b, spirals[k % 6]) for k, (_, b) in enumerate(pairs) if isinstance(b, Spiral)]
    caps = [math.inf if k % 4 else 2.0 for k in range(len(shared))]
    one = [certified.min_distance(a, b, 1e-7, cap=c) for (a, b), c in zip(shared, caps)]
    assert min_distances(shared, 1e-7, caps) == one


def test_not_batchable():
    sp = Spiral((0, 0), 2.0, 3.0, 0.0, 1.0)
    assert not batchable(Arc((0, 0), 2.0, 0.0, 1.0), sp)       # the curved one goes first
    assert not batchable(sp, object())


def test_spiral_and_its_concentric_offset_settle_at_once():
    # a controller's arc whose end is 1e-6 off its radius, and the tool's offset of
    # it by r = 0.25 about the same centre: the distance is 0.25 to within
    # r (1 - cos(pitch)), pitch ~ b / rho ~ 1e-7
    e = Spiral((3.0, -1.0), 1.5, 1.500001, 0.4, 4.0)
    t = Spiral((3.0, -1.0), 1.75, 1.750001, 0.4, 4.0)
    b = certified.min_distance(t, e, 1e-7, cap=0.25001)
    true = min(dist_to_spiral(spiral_point(t, f), e) for f in np.linspace(0, 4.0, 41))
    assert b.lb <= true + 1e-12 and b.ub - b.lb <= 1e-7
    assert b.ub == pytest.approx(0.25, abs=1e-7)
    assert b.pieces < 1000              # not cut into thousands of piece pairs
    assert min_distances([(t, e)], 1e-7, [0.25001]) == [b]


@pytest.mark.parametrize("t,e", [
    # a tool arc about a spiral element's centre, inside it by about 0.25
    (Arc((1.0, 2.0), 4.75, 0.5, 2.0), Spiral((1.0, 2.0), 5.0, 5.0000008, 0.45, 2.1)),
    # a tool spiral outside its element spiral, clockwise, ends 3e-8 rad past the
    # element's (the rounding a controller's arc ends leave)
    (Spiral((0.0, 0.0), 2.25, 2.2500007, 1.0 + 3e-8, -3.0 - 6e-8),
     Spiral((0.0, 0.0), 2.0, 2.0000007, 1.0, -3.0)),
])
def test_farthest_distance_about_a_common_centre_in_closed_form(t, e):
    pt = certified.param_of(t)
    # the farthest tool point from e, measured point by point against e itself
    ref = max(dist_to_spiral(q, e)
              for q in pt.eval(np.linspace(0.0, pt.U, 61)))
    b = certified.max_distance(t, e, 1e-7)
    assert b.converged and b.pieces == 1          # the closed form, no chords
    assert b.lb <= ref + 1e-9 and ref <= b.ub + 1e-9 and b.ub - b.lb <= 1e-7
    # the witness is a genuine point of t at distance >= lb from e
    assert dist_to_spiral(np.array(b.wa), e) >= b.lb - 1e-9


@pytest.mark.parametrize("seed", range(3))
def test_polar_gap_is_below_the_distance_of_the_pieces(seed):
    rng = np.random.default_rng(40 + seed)
    c = (0.3, -0.2)
    th = rng.uniform(-3, 3)
    a = certified.param_of(Spiral(c, rng.uniform(1, 2), rng.uniform(1, 2), th, 2.0))
    b = certified.param_of(Spiral(c, rng.uniform(1.2, 2.2), rng.uniform(1.2, 2.2),
                                  th + rng.uniform(-0.2, 0.2), 2.0))
    ua0 = rng.uniform(0, 1.8, 20)
    ua1 = ua0 + rng.uniform(0.01, 0.2, 20)
    ub0 = np.clip(ua0 + rng.uniform(-0.3, 0.3, 20), 0, 1.8)
    ub1 = ub0 + rng.uniform(0.01, 0.2, 20)
    gap = polar_gap(a, ua0, ua1, b, ub0, ub1)
    assert (gap > 0).any()
    for k in range(20):
        P = a.eval(np.linspace(ua0[k], ua1[k], 801))
        Q = b.eval(np.linspace(ub0[k], ub1[k], 801))
        d = np.hypot(P[:, None, 0] - Q[None, :, 0], P[:, None, 1] - Q[None, :, 1]).min()
        assert gap[k] <= d + 1e-12


def test_offset_spirals_with_a_larger_radius_change_settle_quickly():
    # inside-corners' kind: arc ends 1e-4 off their radius, offset by 0.075
    e = Spiral((1.0341, 3.548), 0.26020808980506355, 0.26032352947822446, -2.7169689, -2.0088653)
    t = Spiral((1.0341, 3.548), 0.18520808985960727, 0.1853235294782246, -2.7169819, -2.0088523)
    b = certified.min_distance(t, e, 1e-7, cap=0.07501)
    true = min(dist_to_spiral(spiral_point(t, f), e) for f in np.linspace(0, 2.0088523, 41))
    assert b.converged and b.lb <= true + 1e-12 and b.ub - b.lb <= 1e-7
    assert b.pieces < 1000


def test_batch_with_open_end_exemptions_gives_the_one_at_a_time_bounds():
    # a half-plane x <= x0 exempt (what an open end of a line makes): pieces
    # inside it by their chord deviation skipped, witnesses in it not counted
    def half_plane(x0):
        return (lambda pts, m: pts[:, 0] <= x0 - m, lambda pts: pts[:, 0] <= x0)

    pairs = [p for p in random_pairs(7, 30) if certified.is_exact(p[1])]
    exempts = [half_plane(x0) if k % 2 else None
               for k, x0 in enumerate(np.linspace(-3, 3, len(pairs)))]
    one = [certified.min_distance(a, b, 1e-7, exempt=ex) for (a, b), ex in zip(pairs, exempts)]
    assert min_distances(pairs, 1e-7, [math.inf] * len(pairs), exempts) == one
    with pytest.raises(ValueError, match="exact second"):
        sp = Spiral((0, 0), 2.0, 3.0, 0.0, 1.0)
        min_distances([(sp, sp)], 1e-7, [math.inf], [half_plane(0.0)])


def random_bezier_pairs(seed: int, n: int):
    """Blend-like Bezier curves (degrees 3, 5 and 7, as the smoother's) against
    lines and arcs around them."""
    rng = np.random.default_rng(seed)
    pairs = []
    for k in range(n):
        deg = (3, 5, 7)[k % 3]
        steps = rng.uniform(0.3, 1.5, (deg + 1, 2)) * [1.0, rng.choice([-1.0, 1.0])]
        a = BezierCurve(tuple(map(tuple, np.cumsum(steps, axis=0))))
        if k % 2:
            b = Line(tuple(rng.uniform(-3, 8, 2)), tuple(rng.uniform(-3, 8, 2)))
        else:
            b = Arc(tuple(rng.uniform(-1, 5, 2)), rng.uniform(1, 4), rng.uniform(-3, 3),
                    rng.choice([-1, 1]) * rng.uniform(0.5, 3))
        pairs.append((a, b))
    return pairs


@pytest.mark.parametrize("seed", range(2))
def test_bezier_pairs_batch_gives_the_one_at_a_time_bounds_exactly(seed):
    pairs = random_bezier_pairs(seed, 30)
    pairs.insert(5, random_pairs(seed, 1)[0])         # a spiral among them: its own family
    assert all(batchable(a, b) for a, b in pairs)
    caps = [math.inf if k % 3 else 0.5 for k in range(len(pairs))]
    one = [certified.min_distance(a, b, 1e-7, cap=c) for (a, b), c in zip(pairs, caps)]
    assert min_distances(pairs, 1e-7, caps) == one
    # and the bounds hold the distance measured on 20,001 points of the curve:
    # that is at least the true one (>= lb), and ub is within the 1e-7 gap of it
    for (a, b), bound in list(zip(pairs, one))[:8]:
        if bound.lb >= 0.5 or isinstance(a, Spiral):
            continue
        q = np.asarray(a.point(np.linspace(0.0, a.length, 20_001)))
        d = float(np.min(certified._points_to(b, q)[0]))
        assert bound.lb <= d + 1e-12 and bound.ub <= d + 1e-7 + 1e-12


def test_bezier_batch_with_open_end_exemptions_gives_the_one_at_a_time_bounds():
    def half_plane(x0):
        return (lambda pts, m: pts[:, 0] <= x0 - m, lambda pts: pts[:, 0] <= x0)

    pairs = random_bezier_pairs(9, 12)
    exempts = [half_plane(x0) if k % 2 else None
               for k, x0 in enumerate(np.linspace(0, 6, len(pairs)))]
    one = [certified.min_distance(a, b, 1e-7, exempt=ex) for (a, b), ex in zip(pairs, exempts)]
    assert min_distances(pairs, 1e-7, [math.inf] * len(pairs), exempts) == one


def test_bezier_against_a_curve_goes_one_at_a_time():
    a = random_bezier_pairs(3, 1)[0][0]
    assert not batchable(a, Spiral((0, 0), 2.0, 3.0, 0.0, 1.0))
    assert not batchable(a, a)
    assert not batchable(Line((0, 0), (1, 0)), Line((0, 1), (1, 1)))


@pytest.mark.parametrize("seed", range(3))
def test_first_pieces_of_every_pair_at_once_are_the_one_at_a_time_cuts(seed):
    # the batch cuts all pairs' first pieces at once; each pair's must be the
    # cuts np.linspace gives one curve at a time (a spiral one per pi/16 of
    # sweep, at least 8; a Bezier curve 8), curved pairs as their outer product
    from ccopt.verify.distance.certified_batch import _first
    from ccopt.verify.distance.curve_rows import BezierRows, SpiralRows
    rng = np.random.default_rng(seed)
    spirals = [Spiral((0.0, 0.0), rng.uniform(1, 5), rng.uniform(1, 5), rng.uniform(-3, 3),
                      rng.choice([-1, 1]) * rng.uniform(0.01, 12)) for _ in range(40)]
    beziers = [BezierCurve(rng.uniform(-5, 5, (4, 2))) for _ in range(10)]

    def cuts(U, spiral):
        n = max(8, math.ceil(U / (math.pi / 16))) if spiral else 8
        u = np.linspace(0.0, U, n + 1)
        return u[:-1], u[1:]

    sel = rng.integers(0, 40, 25)
    for A, spiral in ((SpiralRows(spirals), True), (BezierRows(beziers), False)):
        s = sel % len(A.U)
        others = [spirals[i] for i in rng.integers(0, 40, s.size)]
        B = SpiralRows(others)
        for curved in (False, True):
            (pid, ua0, ua1, ub0, ub1), alike = _first(A, B, s, curved)
            if spiral:
                # each curve's pieces once: the same cuts as each pair's
                k, u0, u1, at = alike
                assert np.array_equal(u0[at], ua0) and np.array_equal(u1[at], ua1)
                assert np.array_equal(A.obj[k[at]], A.obj[s[pid]])
            for m, i in enumerate(s):
                a0, a1 = cuts(A.U[i], spiral)
                mine = pid == m
                if not curved:
                    assert np.array_equal(ua0[mine], a0) and np.array_equal(ua1[mine], a1)
                    continue
                b0, b1 = cuts(B.U[m], True)
                assert np.array_equal(ua0[mine], np.repeat(a0, b0.size))
                assert np.array_equal(ua1[mine], np.repeat(a1, b0.size))
                assert np.array_equal(ub0[mine], np.tile(b0, a0.size))
                assert np.array_equal(ub1[mine], np.tile(b1, a0.size))


@pytest.mark.parametrize("seed", range(4))
def test_mid_arc_bound_is_below_every_point_of_the_piece(seed):
    # random spiral pieces against lines and arcs: the bound is at most the
    # distance of each of 2,001 points of the piece, measured here point by point
    rng = np.random.default_rng(90 + seed)
    for _ in range(25):
        c = tuple(rng.uniform(-2, 2, 2))
        sp = Spiral(c, rng.uniform(1, 4), rng.uniform(1, 4), rng.uniform(-3, 3),
                    rng.choice([-1, 1]) * rng.uniform(0.05, 4))
        other = (Line(tuple(rng.uniform(-6, 6, 2)), tuple(rng.uniform(-6, 6, 2)))
                 if rng.random() < 0.5 else
                 Arc(tuple(rng.uniform(-2, 2, 2)), rng.uniform(0.5, 6), rng.uniform(-3, 3),
                     rng.choice([-1, 1]) * rng.uniform(0.2, 5)))
        pa = certified.param_of(sp)
        u0 = rng.uniform(0, pa.U, 6)
        u1 = np.minimum(u0 + rng.uniform(0, pa.U, 6), pa.U)
        lb = certified._mid_arc(pa, other, u0, u1)
        for k in range(6):
            pts = pa.eval(np.linspace(u0[k], u1[k], 2001))
            assert lb[k] <= point_distances(pts, other).min() + 1e-12


@pytest.mark.parametrize("rho1", [2.0 + 3e-7, 2.0 - 8e-7, 2.0 + 1.2e-6])
def test_a_rounded_corner_arc_against_the_edge_ending_at_its_centre_settles_at_once(rho1):
    # A tool's corner arc about the part's vertex V = (0, 0), r = 2, its end
    # rounded by an export so that it is a spiral 1e-7 off its radius; the
    # part's edge ends at V and runs along -x. Every spiral point projects past
    # V, so its distance to the edge is its polar radius: the minimum is
    # min(rho0, rho1), at an end.
    sp = Spiral((0.0, 0.0), 2.0, rho1, 0.5 * math.pi, -0.21)
    edge = Line((-0.07, 0.0), (0.0, 0.0))
    true = min(2.0, rho1)
    cap = 2.0 + 1e-5
    b = certified.min_distance(sp, edge, 1e-7, cap=cap)
    assert b.converged and b.lb <= true <= b.ub and b.ub - b.lb <= 1e-7
    assert b.pieces <= 64              # the chords alone cut it into hundreds of pieces
    assert min_distances([(sp, edge)], 1e-7, [cap]) == [b]


def test_a_spiral_wholly_beyond_its_cap_is_not_cut():
    # 3 from the edge at its nearest (the arc's end straight above the edge's end)
    sp = Spiral((0.0, 5.0), 2.0, 2.0000004, -0.5 * math.pi, 1.0)
    edge = Line((-4.0, 0.0), (0.0, 0.0))
    b = certified.min_distance(sp, edge, 1e-7, cap=2.5)
    assert b.pieces == 0 and 2.5 <= b.lb <= 3.0
    assert min_distances([(sp, edge)], 1e-7, [2.5]) == [b]


@pytest.mark.parametrize("seed", range(3))
def test_mid_arc_bound_of_two_spirals_is_below_every_pair_of_their_points(seed):
    rng = np.random.default_rng(120 + seed)
    for _ in range(20):
        a, b = (Spiral(tuple(rng.uniform(-3, 3, 2)), rng.uniform(1, 4), rng.uniform(1, 4),
                       rng.uniform(-3, 3), rng.choice([-1, 1]) * rng.uniform(0.05, 4))
                for _ in range(2))
        pa, pb = certified.param_of(a), certified.param_of(b)
        u0, v0 = rng.uniform(0, pa.U, 4), rng.uniform(0, pb.U, 4)
        u1 = np.minimum(u0 + rng.uniform(0, pa.U, 4), pa.U)
        v1 = np.minimum(v0 + rng.uniform(0, pb.U, 4), pb.U)
        lb = certified._mid_arc(pa, None, u0, u1, pb, v0, v1)
        for k in range(4):
            P = pa.eval(np.linspace(u0[k], u1[k], 801))
            Q = pb.eval(np.linspace(v0[k], v1[k], 801))
            d = np.hypot(P[:, None, 0] - Q[None, :, 0], P[:, None, 1] - Q[None, :, 1]).min()
            assert lb[k] <= d + 1e-12
