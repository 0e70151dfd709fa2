"""Certified distance bounds for spirals and parametric curves.

A curve without a closed-form distance is cut into pieces ``[u0, u1]`` of a
parameter ``u``; on each piece it is replaced by its chord. With
``|p''(u)| <= K`` on the piece, every curve point is within

    delta = K (u1 - u0)^2 / 8

of the chord point at the same parameter (``g = p - chord`` vanishes at both
ends and ``|g''| <= K``, so ``|g(u)| <= K (u - u0)(u1 - u) / 2``; this is
the second-order bound). Hence for a piece against another object ``B``:

    dist(chord, B) - delta  <=  dist(piece, B)

(a certified lower bound, the chord distance being exact), and the curve
point at the chord's witness parameter gives a true distance, an upper
bound. Pieces are split in two (branch and bound) until the lowest lower
bound is within ``tol`` of the best upper bound; pieces whose lower bound
is already above ``best - tol`` (or above a caller's ``cap``) are dropped.
The answer is ``[lb, ub]`` with ``ub - lb <= tol`` unless the round limit
stopped it, and then the gap says how far it got.

A spiral piece also lies within half its polar radius change of the arc about
its centre at its middle radius, so that arc's exact distance less the half
is a lower bound too (:func:`~ccopt.verify.distance.mid_arc.mid_arc_bound`):
it settles the pieces of a rounded arc (an export's read-back, a CAM arc of
rounded ends) that lie at one distance from the other object all along,
which the chords alone would halve down to ``tol`` everywhere; over a whole
spiral it drops a pair that is beyond its cap before any piece is cut.

Parameters: a spiral by its swept angle ``phi`` (``|p''| = sqrt(rho^2 +
4 b^2)``, exact and monotone in ``rho``), an arc by its swept angle
(``|p''| = R``), a line by its fraction (``p'' = 0``) and any other curve
by arc length, through its own ``d2_bound(s0, s1)`` (an upper bound of
``|d^2 p / ds^2|``, i.e. of the curvature, on ``[s0, s1]``); a Bezier curve
(``control_points``) by its own parameter, bounded by its second hodograph.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import Arc, Line, SegmentArray, Spiral
from ccopt.geometry.angles import sweep_sign
from ccopt.geometry.bezier_arclength import bernstein_basis, bezier_points
from ccopt.geometry.distance import point_arc, point_segment, segment_arc, segment_segment
from ccopt.tolerances import VERIFY_CERTIFIED_MAX_ROUNDS
from ccopt.verify.distance.concentric import farthest_concentric, polar_gap, same_angle
from ccopt.verify.distance.maxdist import max_distance as exact_max_distance
from ccopt.verify.distance.mid_arc import arcs_to, mid_arc, mid_arc_bound

#: Pieces per pair are never more than this (the bound is then reported with its gap).
MAX_PIECES = 1 << 18

#: Chords per curve in a certified farthest distance (contact), at most.
MAX_CHORDS = 1 << 15
#: Chords measured exactly for every point before the ball search for nearer ones.
_NEAR_CHORDS = 8
#: Up to this many chords the chord nearest each middle is found exactly.
_KD_TREE_CHORDS = 2048
#: Chords on each side of a seed searched for the nearest (see _near_chords).
_NEAR_WINDOW = 4

#: The first cut of a curve's parameter range: this many equal pieces ...
FIRST_PIECES = 8
#: ... and, for an arc or a spiral, at least one per this swept angle
#: (radians), so the first chords already follow the turns.
FIRST_PIECE_ANGLE = math.pi / 16


# --------------------------------------------------------------------------- parameterisations


class Param:
    """A curve as ``p(u)``, ``u`` in ``[0, U]``, with a bound of ``|p''|`` on intervals."""

    U: float

    def eval(self, u: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def d2(self, u0: np.ndarray, u1: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def delta(self, u0, u1):
        """Largest distance from the curve to its chord on each ``[u0, u1]``."""
        h = u1 - u0
        return self.d2(u0, u1) * h * h / 8.0


class LineParam(Param):
    def __init__(self, g: Line):
        self.p0 = np.asarray(g.p0, float)
        self.p1 = np.asarray(g.p1, float)
        self.U = 1.0

    def eval(self, u):
        u = np.asarray(u, float)[:, None]
        return (1.0 - u) * self.p0 + u * self.p1

    def d2(self, u0, u1):
        return np.zeros(np.shape(u0))


class SpiralParam(Param):
    """Arc or spiral by swept angle ``phi``: ``rho = rho0 + b phi``."""

    def __init__(self, g):
        self.c = np.asarray(g.center, float)
        if isinstance(g, Arc):
            self.rho0, self.b = g.radius, 0.0
        else:
            self.rho0, self.b = g.rho0, g.b
        self.th0 = g.theta0
        self.sg = sweep_sign(g.sweep)
        self.U = abs(g.sweep)

    def eval(self, u):
        u = np.asarray(u, float)
        rho = self.rho0 + self.b * u
        ang = self.th0 + self.sg * u
        out = np.empty((u.size, 2))     # (np.c_ costs more than the trigonometry here)
        np.multiply(rho, np.cos(ang), out=out[:, 0])
        np.multiply(rho, np.sin(ang), out=out[:, 1])
        out += self.c
        return out

    def d2(self, u0, u1):
        rho = np.maximum(self.rho0 + self.b * np.asarray(u0), self.rho0 + self.b * np.asarray(u1))
        return np.sqrt(rho * rho + 4.0 * self.b * self.b)


class BezierParam(Param):
    """A Bezier curve by its own parameter ``t`` in ``[0, 1]``; ``|p''(t)|`` is at
    most the largest second-hodograph control point (convex hull property)."""

    def __init__(self, g):
        P = np.asarray(g.control_points, float)
        self.P = P
        n = len(P) - 1
        D2 = n * (n - 1) * np.diff(P, n=2, axis=0) if n >= 2 else np.zeros((1, 2))
        self.K = float(np.hypot(D2[:, 0], D2[:, 1]).max())
        self.U = 1.0

    def eval(self, u):
        # the Bernstein basis times the control points, where de Casteljau's
        # rounds made a copy per point and a pass per degree (a quarter of the
        # certificate's time on freeform-hsm's smoothed path)
        return bezier_points(bernstein_basis(u, len(self.P) - 1), self.P)

    def d2(self, u0, u1):
        return np.full(np.shape(u0), self.K)


class CurveParam(Param):
    """Any curve by arc length, via its ``point(s)`` and ``d2_bound(s0, s1)``."""

    def __init__(self, g):
        if not hasattr(g, "d2_bound"):
            raise TypeError(f"{type(g).__name__} has no d2_bound(s0, s1): the verifier cannot "
                            "bound its distances")
        self.g = g
        self.U = float(g.length)

    def eval(self, u):
        return np.asarray(self.g.point(np.asarray(u, float)), float).reshape(-1, 2)

    def d2(self, u0, u1):
        try:
            return np.asarray(self.g.d2_bound(u0, u1), float) * np.ones(np.shape(u0))
        except (TypeError, ValueError):
            return np.array([float(self.g.d2_bound(a, b)) for a, b in zip(u0, u1)])


def param_of(g) -> Param:
    if isinstance(g, Line):
        return LineParam(g)
    if isinstance(g, (Arc, Spiral)):
        return SpiralParam(g)
    if is_bezier(g):
        return BezierParam(g)
    return CurveParam(g)


def is_bezier(g) -> bool:
    """Whether ``g`` is measured by its Bezier parameter (:class:`BezierParam`):
    it has control points and no ``d2_bound`` of its own."""
    return getattr(g, "control_points", None) is not None and not hasattr(g, "d2_bound")


def is_exact(g) -> bool:
    return isinstance(g, (Line, Arc))


# --------------------------------------------------------------------------- kernels against exact objects


def _chords_to(g, c0, c1):
    """``(d, w_chord, w_g)`` from chords ``c0 c1`` to an exact primitive ``g``."""
    if isinstance(g, Line):
        return segment_segment(c0, c1, np.asarray(g.p0), np.asarray(g.p1))
    return segment_arc(c0, c1, np.asarray(g.center), g.radius, g.theta0, g.sweep)


def _points_to(g, q):
    if isinstance(g, Line):
        return point_segment(q, np.asarray(g.p0), np.asarray(g.p1))
    return point_arc(q, np.asarray(g.center), g.radius, g.theta0, g.sweep)


def _fraction(w, c0, c1):
    r = c1 - c0
    rr = np.einsum("ij,ij->i", r, r)
    t = np.einsum("ij,ij->i", w - c0, r) / np.where(rr > 0.0, rr, 1.0)
    return np.clip(t, 0.0, 1.0)


@dataclass(frozen=True)
class Bound:
    """Certified ``lb <= true value <= ub``; witnesses realise ``ub`` (min
    distance) or ``lb`` (max distance). ``converged``: ``ub - lb <= tol``."""

    lb: float
    ub: float
    wa: tuple[float, float] | None
    wb: tuple[float, float] | None
    converged: bool
    pieces: int

    @property
    def gap(self) -> float:
        return self.ub - self.lb


def _initial(U, n0=FIRST_PIECES):
    u = np.linspace(0.0, U, n0 + 1)
    return u[:-1], u[1:]


def _first_pieces(p: Param):
    """The first cut of ``[0, p.U]``: ``(u0, u1)`` of each piece; an arc or a
    spiral gets at least one piece per :data:`FIRST_PIECE_ANGLE` of sweep."""
    if isinstance(p, SpiralParam):
        return _initial(p.U, max(FIRST_PIECES, int(math.ceil(p.U / FIRST_PIECE_ANGLE))))
    return _initial(p.U, FIRST_PIECES)


def min_distance(a, b, tol: float, cap: float = math.inf, exempt=None,
                 max_rounds: int = VERIFY_CERTIFIED_MAX_ROUNDS) -> Bound:
    """Certified bounds of ``min dist(a, b)``; at least one of ``a``, ``b`` is curved.

    ``cap``: pieces whose lower bound reaches it are dropped (the caller only
    cares below it); when everything is dropped ``lb >= cap`` and ``ub`` may be
    ``inf``. ``exempt``: optional ``(inside_by(points, margin) -> bool mask,
    contains(points) -> bool mask)`` describing a region of ``a``'s points not
    to be counted (the open-end exemption of an exact ``b``): a piece whose
    chord lies inside it by ``delta`` is skipped, and upper bounds only come
    from points outside it.
    """
    if is_exact(a) and not is_exact(b):
        if exempt is not None:
            raise ValueError("exemptions apply to the first (curved) argument")
        r = min_distance(b, a, tol, cap, None, max_rounds)
        return Bound(r.lb, r.ub, r.wb, r.wa, r.converged, r.pieces)
    pa = param_of(a)
    pb = None if is_exact(b) else param_of(b)
    if isinstance(pa, SpiralParam) and (pb is None or isinstance(pb, SpiralParam)) \
            and cap < math.inf:
        # the whole spiral beyond the cap: nothing to refine (pairs a broad
        # phase found by their boxes, most of them a tool's neighbours)
        whole = float(_mid_arc(pa, b, np.zeros(1), np.full(1, pa.U), pb, np.zeros(1),
                               None if pb is None else np.full(1, pb.U))[0])
        if whole >= cap:
            return Bound(whole, math.inf, None, None, True, 0)
    pieces = _first_piece_pairs(pa, pb)
    best = math.inf
    wa = wb = None
    dropped_lb = math.inf
    rounds = 0
    remaining_lb = math.inf
    while pieces[0].size:
        rounds += 1
        lb, live, dq, qa, qb, ok_ub = _bound_pieces(pa, b, pb, pieces, exempt)
        if ok_ub.any():
            k = int(np.argmin(np.where(ok_ub, dq, np.inf)))
            if dq[k] < best:
                best = float(dq[k])
                wa, wb = (float(qa[k, 0]), float(qa[k, 1])), (float(qb[k, 0]), float(qb[k, 1]))
        keep = live & (lb < best - tol) & (lb < cap)
        gone = live & ~keep
        if gone.any():
            dropped_lb = min(dropped_lb, float(lb[gone].min()))
        if not keep.any():
            remaining_lb = math.inf
            break
        remaining_lb = float(lb[keep].min())
        if rounds >= max_rounds or 2 * keep.sum() * (1 if pb is None else 2) > MAX_PIECES:
            break
        pieces = _halve(pieces, keep)
    lbv = min(dropped_lb, remaining_lb, best)
    converged = best - lbv <= tol or lbv >= cap
    return Bound(lbv, best, wa, wb, bool(converged), int(pieces[0].size))


def _first_piece_pairs(pa: Param, pb: Param | None):
    """``(ua0, ua1, ub0, ub1)``: the first pieces of ``a`` and, when ``b`` is
    curved (``pb``), every pair of them with the first pieces of ``b``
    (``ub0 = ub1 = None`` for an exact ``b``)."""
    ua0, ua1 = _first_pieces(pa)
    if pb is None:
        return ua0, ua1, None, None
    b0, b1 = _first_pieces(pb)
    return (np.repeat(ua0, b0.size), np.repeat(ua1, b1.size),
            np.tile(b0, ua0.size), np.tile(b1, ua1.size))


def _bound_pieces(pa: Param, b, pb: Param | None, pieces, exempt):
    """Bounds of the distance on each piece (pair): ``(lb, live, dq, qa, qb, ok_ub)``.

    ``lb``: chord distance minus both chord deviations (certified lower
    bound); ``live``: pieces not exempt; ``dq``: true distance between the
    curve points ``qa``, ``qb`` at the chord witnesses (an upper bound where
    ``ok_ub``: the point ``qa`` is not exempt).
    """
    ua0, ua1, ub0, ub1 = pieces
    c0, c1 = pa.eval(ua0), pa.eval(ua1)
    da = pa.delta(ua0, ua1)
    if pb is None:
        d, w_a, w_b = _chords_to(b, c0, c1)
        db = 0.0
    else:
        e0, e1 = pb.eval(ub0), pb.eval(ub1)
        db = pb.delta(ub0, ub1)
        d, w_a, w_b = segment_segment(c0, c1, e0, e1)
    # Distances are never negative, and about a common centre no nearer than
    # the gap between the two polar radius ranges (|A - B| >= ||A - c| - |B - c||):
    # both are certified lower bounds too, and settle in one round the pairs
    # the chords alone would refine down to ``tol`` all along (a spiral on
    # itself, or against its concentric offset).
    lb = np.maximum(d - da - db, _radial_gap(pa, ua0, ua1, b, pb, ub0, ub1))
    if isinstance(pa, SpiralParam) and (pb is None or isinstance(pb, SpiralParam)):
        lb = np.fmax(lb, _mid_arc(pa, b, ua0, ua1, pb, ub0, ub1))
    skip = np.zeros(ua0.size, bool)
    if exempt is not None:
        inside_by, _ = exempt
        skip = inside_by(c0, da) & inside_by(c1, da)
    # upper bounds from genuine curve points at the chord witnesses
    ta = _fraction(w_a, c0, c1)
    qa = pa.eval(ua0 + ta * (ua1 - ua0))
    if pb is None:
        dq, _, qb = _points_to(b, qa)
    else:
        tb = _fraction(w_b, e0, e1)
        qb = pb.eval(ub0 + tb * (ub1 - ub0))
        dq = np.hypot(*(qa - qb).T)
        if isinstance(pa, SpiralParam) and isinstance(pb, SpiralParam) \
                and np.array_equal(pa.c, pb.c):
            ang = pa.th0 + pa.sg * (ua0 + ta * (ua1 - ua0))
            dq, qb = same_angle(qa, ang, dq, qb, pb.eval, pb.th0, pb.sg, pb.U)
    ok_ub = ~skip
    if exempt is not None:
        ok_ub &= ~exempt[1](qa)
    return lb, ~skip, dq, qa, qb, ok_ub


def _mid_arc(pa: SpiralParam, b, u0, u1, pb: SpiralParam | None = None, v0=None, v1=None):
    """:func:`~ccopt.verify.distance.mid_arc.mid_arc_bound` of the pieces ``[u0, u1]``
    of ``pa`` against the exact ``b``, or against the pieces ``[v0, v1]`` of ``pb``."""
    n = np.size(u0)
    arc_a = mid_arc(np.broadcast_to(pa.c, (n, 2)), pa.rho0, pa.b, pa.th0, pa.sg, u0, u1)
    if pb is None:
        return mid_arc_bound(arc_a, element_to=lambda c, R, t, w: arcs_to(b, c, R, t, w))
    return mid_arc_bound(arc_a, mid_arc(np.broadcast_to(pb.c, (n, 2)), pb.rho0, pb.b, pb.th0,
                                        pb.sg, v0, v1))


def _radius_range(p: "SpiralParam", u0, u1):
    """Polar radius range ``(lo, hi)`` of the pieces ``[u0, u1]`` of a spiral or arc."""
    r0 = p.rho0 + p.b * np.asarray(u0, float)
    r1 = p.rho0 + p.b * np.asarray(u1, float)
    return np.minimum(r0, r1), np.maximum(r0, r1)


def _radial_gap(pa: Param, ua0, ua1, b, pb: Param | None, ub0, ub1):
    """A lower bound of the distance of each piece (pair) from the polar radii
    about a shared centre (0 when there is none to use)."""
    if not isinstance(pa, SpiralParam):
        return 0.0
    if pb is None:
        if not isinstance(b, Arc) or tuple(pa.c) != tuple(map(float, b.center)):
            return 0.0
        lo_b = hi_b = float(b.radius)
    elif isinstance(pb, SpiralParam) and np.array_equal(pa.c, pb.c):
        lo_b, hi_b = _radius_range(pb, ub0, ub1)
        lo_a, hi_a = _radius_range(pa, ua0, ua1)
        return np.maximum(np.maximum(np.maximum(lo_a - hi_b, lo_b - hi_a), 0.0),
                          polar_gap(pa, ua0, ua1, pb, ub0, ub1))
    else:
        return 0.0
    lo_a, hi_a = _radius_range(pa, ua0, ua1)
    return np.maximum(np.maximum(lo_a - hi_b, lo_b - hi_a), 0.0)


def _halve(pieces, keep):
    """The kept pieces (pairs), each cut in two halves (a pair in four)."""
    ua0, ua1 = pieces[0][keep], pieces[1][keep]
    mid = 0.5 * (ua0 + ua1)
    if pieces[2] is None:
        return np.concatenate((ua0, mid)), np.concatenate((mid, ua1)), None, None
    ub0, ub1 = pieces[2][keep], pieces[3][keep]
    midb = 0.5 * (ub0 + ub1)
    return (np.concatenate((ua0, ua0, mid, mid)), np.concatenate((mid, mid, ua1, ua1)),
            np.concatenate((ub0, midb, ub0, midb)), np.concatenate((midb, ub1, midb, ub1)))


def _chords(p: Param, n: int):
    u = np.linspace(0.0, p.U, n + 1)
    pts = p.eval(u)
    return pts[:-1], pts[1:], p.delta(u[:-1], u[1:]), u


def _near_chords(middles, points, previous):
    """For each point, the chord (by its middle) of ``middles`` nearest it.

    Exact (k-d tree) while the chords are few; from then on the nearest among
    the chords around the halves of the previous round's choice: both curves'
    chords are halved each round, so that chord's halves are where the
    nearest one went. A k-d tree over a curve offset from the points by many
    chord lengths visits every chord within that offset: quadratic, which the
    local search is not.
    """
    if previous is None or len(points) <= _KD_TREE_CHORDS:
        # deferred: scipy.spatial is only needed when a curved element is measured
        from scipy.spatial import cKDTree
        return np.asarray(cKDTree(middles).query(points, 1)[1], np.intp).reshape(len(points))
    seed = 2 * previous[np.arange(len(points)) // 2]
    cand = np.clip(seed[:, None] + np.arange(-_NEAR_WINDOW, _NEAR_WINDOW + 2), 0,
                   len(middles) - 1)
    d = np.hypot(*(middles[cand] - points[:, None, :]).transpose(2, 0, 1))
    return cand[np.arange(len(points)), np.argmin(d, axis=1)]


def _farthest_from_polyline(q, e0, e1, upper, batch: int = 64) -> np.ndarray:
    """``dist(q, polyline)`` where it matters for the maximum, ``-inf`` elsewhere.

    ``upper`` bounds each point's distance from above; points are measured
    exactly in decreasing order of it until the largest exact distance found
    is at least the next bound, so the maximum of the result is the exact
    maximum over all points.
    """
    out = np.full(len(q), -np.inf)
    order = np.argsort(-upper, kind="stable")
    best = -np.inf
    for s in range(0, len(order), batch):
        idx = order[s:s + batch]
        if upper[idx[0]] <= best:
            break
        out[idx] = _poly_dist(q[idx], e0, e1)
        best = max(best, float(out[idx].max()))
    return out


def _poly_dist(q, e0, e1):
    """Exact distance from points ``q`` to the polyline of chords ``e0 e1``.

    Near chords only, found with a k-d tree of the chord middles: a chord whose
    middle is farther from ``q`` than the best distance found plus the longest
    half chord cannot be nearer, so the candidates within that ball give the
    exact minimum (the brute force was quadratic in the chord count).
    """
    # deferred: scipy.spatial is only needed when a curved element is measured
    from scipy.spatial import cKDTree
    m = e0.shape[0]
    mids = 0.5 * (e0 + e1)
    half = 0.5 * float(np.hypot(*(e1 - e0).T).max()) if m else 0.0
    tree = cKDTree(mids)
    k = min(_NEAR_CHORDS, m)
    dk, ik = tree.query(q, k)
    dk, ik = dk.reshape(len(q), k), ik.reshape(len(q), k)
    rows = np.repeat(np.arange(len(q)), k)
    d = point_segment(q[rows], e0[ik.ravel()], e1[ik.ravel()])[0].reshape(len(q), k)
    best = d.min(axis=1)
    # points whose ball may hold a nearer chord than the k middles found
    more = np.flatnonzero(best + half > dk[:, -1]) if k < m else np.zeros(0, np.intp)
    if more.size:
        balls = tree.query_ball_point(q[more], best[more] + half)
        counts = np.fromiter((len(b) for b in balls), np.intp, more.size)
        idx = np.fromiter((j for b in balls for j in b), np.intp, int(counts.sum()))
        who = np.repeat(more, counts)
        dd = point_segment(q[who], e0[idx], e1[idx])[0]
        np.minimum.at(best, who, dd)
    return best


def max_distance(t, e, tol: float, max_rounds: int = 16, n0: int = 16) -> Bound:
    """Certified bounds of ``max_{q in t} dist(q, e)`` (contact), ``t`` or ``e`` curved.

    ``t`` is cut into ``n`` chords and ``e`` (when curved) into ``n`` chords,
    doubled each round. Upper bound: for each chord of ``t`` the farthest
    distance to the chord of ``e`` nearest its middle (exact: at a chord end,
    distance to a segment being convex) plus both deltas; lower bound: the
    largest distance from a genuine point of ``t`` (chord ends) to the
    polyline of ``e`` minus ``e``'s delta (or the exact distance when ``e`` is
    a line or arc).
    """
    pt = param_of(t)
    e_exact = is_exact(e)
    pe = None if e_exact else param_of(e)
    if isinstance(pt, SpiralParam) and isinstance(e, (Arc, Spiral)):
        radial = farthest_concentric(pt, param_of(e), tol)
        if radial is not None:
            return Bound(radial[0], radial[1], radial[2], None, True, 1)
    n = n0
    lb = -math.inf
    ubv = math.inf
    witness = None
    near = None
    for _ in range(max_rounds):
        c0, c1, dt, _ = _chords(pt, n)
        ends = np.r_[c0, c1[-1:]]
        if e_exact:
            nan = np.full(n, np.nan)
            chords = SegmentArray(np.zeros(n, np.int8), c0, c1, np.full((n, 2), np.nan), nan, nan,
                                  nan, nan)
            earr = SegmentArray.from_segments([e])
            dmax, _, _ = exact_max_distance(chords, np.arange(n), earr, np.zeros(n, np.intp))
            ub_n = float((dmax + dt).max())
            dq = _points_to(e, ends)[0]
            de = 0.0
        else:
            f0, f1, de_arr, _ = _chords(pe, n)
            de = float(de_arr.max())
            mids = 0.5 * (c0 + c1)
            fm = 0.5 * (f0 + f1)
            # a chord of e near each middle of t (any chord keeps ub an upper bound)
            near = _near_chords(fm, mids, near)
            d0 = point_segment(c0, f0[near], f1[near])[0]
            d1 = point_segment(c1, f0[near], f1[near])[0]
            ub_n = float((np.maximum(d0, d1) + dt + de_arr[near]).max())
            # a chord end's distance to e's polyline is at most that to the chord
            # near it: the ends' exact distances are needed only from the top
            upper = np.r_[np.minimum(d0, np.r_[np.inf, d1[:-1]]), d1[-1:]]
            dq = _farthest_from_polyline(ends, f0, f1, upper) - de
        k = int(np.argmax(dq))
        if dq[k] > lb:
            lb = float(dq[k])
            witness = (float(ends[k, 0]), float(ends[k, 1]))
        ubv = min(ubv, ub_n)
        if ubv - lb <= tol or n >= MAX_CHORDS:
            break
        n *= 2
    return Bound(lb, ubv, witness, None, bool(ubv - lb <= tol), n)
