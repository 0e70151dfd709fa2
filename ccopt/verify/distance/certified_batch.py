"""Certified minimum distances of many curve pairs at once.

:func:`ccopt.verify.distance.certified.min_distance` runs one pair's branch and bound
at a time: a program with hundreds of spirals (LinuxCNC's crazy-paths, whose
arcs end a few 1e-7 off their radius) pays a dozen small numpy calls per
round per pair. :func:`min_distances` runs the same branch and bound for
every pair together: each round evaluates the live pieces of all pairs in
one vectorised pass, and each pair keeps its own best upper bound, dropped
lower bound, round count and piece limit. Per pair the pieces, their order
and every number are those of :func:`~ccopt.verify.distance.certified.min_distance`
(the kernels work element by element), so the bounds are the same, bit for
bit (tested).

Pairs covered: a spiral or arc ``a`` (the curved one) against a line or arc
``b`` (exact, with or without an open-end exemption) or a spiral or arc ``b``
(curved); a Bezier curve ``a`` (a blend's, by its own parameter,
:class:`~ccopt.verify.distance.certified.BezierParam`) against a line or arc ``b``
(the smoothed freeform-hsm: 1,556 such pairs, 1.3 s one at a time);
:func:`batchable` says which. Other curves go one at a time.
"""
from __future__ import annotations

import math
from operator import itemgetter
from typing import NamedTuple

import numpy as np

from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.columns import put_rows, take_rows, used_rows
from ccopt.geometry.distance import segment_segment
from ccopt.tolerances import VERIFY_CERTIFIED_MAX_ROUNDS
from ccopt.verify.distance.concentric import polar_gap, same_angle
from ccopt.verify.distance.curve_rows import (
    BezierRows, ExactRows, SpiralRows, asked_once, distinct,
)
from ccopt.verify.distance.mid_arc import mid_arc, mid_arc_bound
from ccopt.verify.distance.certified import (
    FIRST_PIECE_ANGLE, FIRST_PIECES, MAX_PIECES, Bound, _fraction,
    is_bezier, is_exact,
)


#: :func:`batchable_class` of a line, an arc, a spiral, a Bezier curve and any other curve.
LINE, ARC, SPIRAL, BEZIER, OTHER = range(5)


def batchable_class(g) -> int:
    """What :func:`batchable` asks of a primitive: :data:`LINE`, :data:`ARC`,
    :data:`SPIRAL`, :data:`BEZIER` (measured by its Bezier parameter) or :data:`OTHER`."""
    if isinstance(g, Line):
        return LINE
    if isinstance(g, Arc):
        return ARC
    if isinstance(g, Spiral):
        return SPIRAL
    return BEZIER if is_bezier(g) else OTHER


def batchable_by_class(ca, cb):
    """:func:`batchable` from the :func:`batchable_class` of ``a`` and ``b`` (numbers
    or arrays of them): a spiral against a line, arc or spiral, a Bezier curve
    against a line or arc."""
    return ((ca == SPIRAL) & (cb <= SPIRAL)) | ((ca == BEZIER) & (cb <= ARC))


def batchable(a, b) -> bool:
    """True when :func:`min_distances` handles ``(a, b)`` (``a`` curved)."""
    return bool(batchable_by_class(batchable_class(a), batchable_class(b)))


def _family(g):
    """The pairs whose ``a`` share this key run together: spirals and arcs, or
    Bezier curves of one degree."""
    return ("bezier", len(g.control_points) - 1) if is_bezier(g) else ("spiral",)


class BoundArrays(NamedTuple):
    """:class:`~ccopt.verify.distance.certified.Bound` of many pairs as arrays:
    ``lb``, ``ub`` ``(n,)``; witnesses ``wa``, ``wb`` ``(n, 2)`` (NaN rows
    where a pair has none, its ``ub`` infinite); ``converged``, ``pieces``."""

    lb: np.ndarray
    ub: np.ndarray
    wa: np.ndarray
    wb: np.ndarray
    converged: np.ndarray
    pieces: np.ndarray

    @classmethod
    def empty(cls, n: int) -> "BoundArrays":
        return cls(np.full(n, math.inf), np.full(n, math.inf), np.full((n, 2), np.nan),
                   np.full((n, 2), np.nan), np.zeros(n, bool), np.zeros(n, np.int64))

    def put(self, at, other: "BoundArrays") -> None:
        """Rows ``at`` (indices) set to ``other``'s rows, in order."""
        for mine, theirs in zip(self, other):
            mine[at] = theirs

    def bounds(self) -> list[Bound]:
        """Each row as its :class:`Bound` (the same numbers as Python floats)."""
        has = ~np.isinf(self.ub)
        wa, wb = self.wa.tolist(), self.wb.tolist()
        return [Bound(lb, ub, tuple(a) if h else None, tuple(b) if h else None, c, k)
                for lb, ub, a, b, h, c, k in zip(self.lb.tolist(), self.ub.tolist(), wa, wb,
                                                 has.tolist(), self.converged.tolist(),
                                                 self.pieces.tolist())]


def min_distances(pairs, tol: float, caps, exempts=None,
                  max_rounds: int = VERIFY_CERTIFIED_MAX_ROUNDS) -> list[Bound]:
    """:func:`ccopt.verify.distance.certified.min_distance` ``(a, b, tol, cap, exempt)`` of
    every ``(a, b)`` in ``pairs`` (each :func:`batchable`) with ``caps[i]`` and
    ``exempts[i]`` (``None``: no exemption; only with an exact ``b``), at once."""
    return min_distance_arrays(pairs, tol, caps, exempts, max_rounds).bounds()


def min_distance_arrays(pairs, tol: float, caps, exempts=None,
                        max_rounds: int = VERIFY_CERTIFIED_MAX_ROUNDS) -> BoundArrays:
    """:func:`min_distances` as arrays (:class:`BoundArrays`): no object per pair."""
    n = len(pairs)
    # what is asked of each curve once, not once per pair it is in
    a_objs, a_of = distinct(list(map(itemgetter(0), pairs)))
    b_objs, b_of = distinct(list(map(itemgetter(1), pairs)))
    ex_objs, ex_of = [], np.full(n, -1, np.intp)
    if exempts is not None:
        exempts = list(exempts)
        at = [m for m, ex in enumerate(exempts) if ex is not None]
        ex_objs = [exempts[m] for m in at]
        ex_of[at] = np.arange(len(at))
    return min_distance_indexed(a_objs, a_of, b_objs, b_of, tol, caps, ex_objs, ex_of,
                                max_rounds)


def min_distance_indexed(a_objs, a_of, b_objs, b_of, tol: float, caps, ex_objs=(),
                         ex_of=None, max_rounds: int = VERIFY_CERTIFIED_MAX_ROUNDS
                         ) -> BoundArrays:
    """:func:`min_distance_arrays` of the pairs ``(a_objs[a_of[m]], b_objs[b_of[m]])``
    given by index arrays (``a_objs`` and ``b_objs`` may be one list), pair ``m``
    with the exemption ``ex_objs[ex_of[m]]`` (``-1`` or ``ex_of`` ``None``: none):
    the same bounds, with no Python work per pair."""
    a_of, b_of = np.asarray(a_of, np.intp), np.asarray(b_of, np.intp)
    n = a_of.size
    out = BoundArrays.empty(n)
    if not n:
        return out
    ex_of = np.full(n, -1, np.intp) if ex_of is None else np.asarray(ex_of, np.intp)
    answers, inv = asked_once(b_objs, b_of, is_exact)
    curved = ~np.array(answers, bool).reshape(-1)[inv]
    if (curved & (ex_of >= 0)).any():
        raise ValueError("exemptions apply to pairs with an exact second element")
    caps = np.asarray(caps, float)
    families, inv = asked_once(a_objs, a_of, _family)
    keys = list(dict.fromkeys(families))
    key_of = np.array([keys.index(f) for f in families], np.intp)[inv]
    for q, key in enumerate(keys):
        members = np.flatnonzero(key_of == q)      # in pair order, as one at a time
        A = (SpiralRows if key[0] == "spiral" else BezierRows)(a_objs, a_of[members])
        for sel in (np.flatnonzero(~curved[members]), np.flatnonzero(curved[members])):
            if sel.size:
                idx = members[sel]
                out.put(idx, _run(A, (b_objs, b_of[idx]), sel, bool(curved[idx[0]]), tol,
                                  caps[idx], max_rounds, (ex_objs, ex_of[idx])))
    return out


def _concentric_b(A: SpiralRows | BezierRows, B, sel, curved: bool):
    """Per pair: whether ``b`` (of ``B``) shares ``a``'s centre (a polar radius gap
    is then a lower bound, :func:`ccopt.verify.distance.certified._radial_gap`), and
    for an arc ``b`` its radius."""
    n = len(sel)
    if not A.concentric:
        return np.zeros(n, bool), np.zeros(n)
    same = (A.c[sel] == B.c).all(axis=1)
    if curved:
        return same, np.zeros(n)
    arc = ~B.line
    return same & arc, np.where(arc, B.R, 0.0)


def _run(A: SpiralRows | BezierRows, bs, sel, curved: bool, tol: float, caps, max_rounds: int,
         exempts) -> BoundArrays:
    """The branch and bound of the pairs ``(A[sel[m]], b_objs[b_of[m]])`` (``bs``:
    ``(b_objs, b_of)``), all ``b`` exact or all curved; ``exempts``:
    ``(ex_objs, ex_of)`` as :func:`min_distance_indexed` takes them."""
    B = SpiralRows(*bs) if curved else ExactRows(*bs)
    sel = np.asarray(sel)
    n = bs[1].size
    go = np.arange(n)
    out = BoundArrays.empty(n)
    if A.concentric:
        # a whole spiral beyond its cap: nothing to refine (as min_distance)
        whole = _mid_arc(A, sel, B, go, np.zeros(go.size), A.U[sel], np.zeros(go.size),
                         B.U if curved else None)
        beyond = np.flatnonzero(whole >= caps)
        out.lb[beyond], out.converged[beyond] = whole[beyond], True
        go = np.flatnonzero(~(whole >= caps))
    if go.size:
        B_go = B if go.size == n else _rows(B, go)
        out.put(go, _branch_and_bound(A, B_go, sel[go], curved, tol, caps[go], max_rounds,
                                      (exempts[0], exempts[1][go])))
    return out


def _rows(C: SpiralRows | ExactRows, idx):
    """The rows ``idx`` of ``C`` (every attribute of an instance is a per-row array)."""
    sub = object.__new__(type(C))
    sub.__dict__.update({name: take_rows(value, idx) for name, value in vars(C).items()})
    return sub


def _branch_and_bound(A: SpiralRows | BezierRows, B, sel, curved: bool, tol: float, caps,
                      max_rounds: int, exempts) -> BoundArrays:
    """Rounds of bounding and halving the pieces of every pair at once."""
    geo = (A, B, sel, curved) + _concentric_b(A, B, sel, curved)
    pieces, alike = _first(A, B, sel, curved)
    state = _State(len(sel))
    rounds = 0
    while pieces[0].size:
        rounds += 1
        lb, dq, qa, qb, live, ok = _round(geo, pieces, exempts, alike)
        alike = None
        go = state.update(pieces[0], lb, dq, qa, qb, live, ok, tol, caps,
                          rounds >= max_rounds, curved)
        pieces = _halve(*pieces, go, curved)
    return state.bounds(tol, caps)


class _State:
    """Each pair's best upper bound and its witnesses, the least lower bound of
    its dropped pieces and of its remaining ones, and its piece count."""

    def __init__(self, P: int):
        self.P = P
        self.best = np.full(P, math.inf)
        self.wa = np.full((P, 2), np.nan)
        self.wb = np.full((P, 2), np.nan)
        self.dropped = np.full(P, math.inf)
        self.remaining = np.full(P, math.inf)
        self.npieces = np.zeros(P, np.int64)

    def update(self, pid, lb, dq, qa, qb, live, ok, tol, caps, last: bool, curved: bool):
        """One round of :func:`ccopt.verify.distance.certified.min_distance` for every pair;
        the pieces to halve."""
        P = self.P
        # each pair's smallest genuine dq (its first in piece order on ties, as
        # argmin), by scatter-reductions rather than a sort of all the pieces;
        # fmin skips a NaN as argmin would, and a pair none of whose pieces has
        # a smaller dq than inf is never better than its best anyway
        dqm = np.where(ok, dq, np.inf)
        low = np.full(P, np.inf)
        np.fmin.at(low, pid, dqm)
        hits = np.flatnonzero(dqm == low[pid])
        first = np.full(P, pid.size, np.intp)
        np.minimum.at(first, pid[hits], hits)
        first = first[first < pid.size]
        better = dqm[first] < self.best[pid[first]]
        upd, at = pid[first][better], first[better]
        self.best[upd], self.wa[upd], self.wb[upd] = dq[at], qa[at], qb[at]
        counts = np.bincount(pid, minlength=P)
        present = counts > 0
        self.npieces[present] = counts[present]
        keep = live & (lb < self.best[pid] - tol) & (lb < caps[pid])
        gone = live & ~keep
        np.minimum.at(self.dropped, pid[gone], lb[gone])
        kept = np.bincount(pid[keep], minlength=P)
        self.remaining[present] = math.inf
        np.minimum.at(self.remaining, pid[keep], lb[keep])
        stop = last | (2 * kept * (2 if curved else 1) > MAX_PIECES)
        return keep & ~stop[pid]

    def bounds(self, tol: float, caps) -> BoundArrays:
        best = self.best
        lbv = np.minimum(np.minimum(self.dropped, self.remaining), best)
        with np.errstate(invalid="ignore"):     # inf - inf: a pair wholly exempt
            conv = (best - lbv <= tol) | (lbv >= caps)
        none = np.isinf(best)                   # no witness: NaN rows
        wa, wb = self.wa.copy(), self.wb.copy()
        wa[none], wb[none] = np.nan, np.nan
        return BoundArrays(lbv, best.copy(), wa, wb, np.asarray(conv, bool),
                           self.npieces.copy())


def _round(geo, pieces, exempts, alike=None):
    """Bounds of every live piece (pair): ``(lb, dq, qa, qb, live, ok)`` as
    :func:`ccopt.verify.distance.certified._bound_pieces` gives them (``ok``: ``dq`` is a
    genuine distance outside the pair's exemption); ``alike``: the first pieces'
    :func:`_curve_pieces`, or ``None``."""
    A, B, sel, curved, conc, Rb = geo
    pid, ua0, ua1, ub0, ub1 = pieces
    ka = sel[pid]
    arc_a = None
    if alike is not None:
        # what depends on a's piece alone, once per piece of each distinct curve
        k, u0, u1, at = alike
        c0, c1 = (take_rows(p, at) for p in _ends(A, k, u0, u1))
        da = A.delta(k, u0, u1)[at]
        arc_a = tuple(take_rows(v, at) for v in _mid_arc_of(A, k, u0, u1))
    else:
        c0, c1 = _ends(A, ka, ua0, ua1) if A.concentric else (A.eval(ka, ua0), A.eval(ka, ua1))
        da = A.delta(ka, ua0, ua1)
    if curved:
        e0, e1 = _ends(B, pid, ub0, ub1)
        db = B.delta(pid, ub0, ub1)
        d, w_a, w_b = segment_segment(c0, c1, e0, e1)
    else:
        db = 0.0
        d, w_a, w_b = B.chords_to(pid, c0, c1)
    lb = np.maximum(d - da - db, _radial_gap(A, ka, ua0, ua1, B, pid, ub0, ub1, conc, Rb,
                                             curved))
    if A.concentric:
        lb = np.fmax(lb, _mid_arc(A, ka, B, pid, ua0, ua1, ub0, ub1, arc_a))
    ta = _fraction(w_a, c0, c1)
    qa = A.eval(ka, ua0 + ta * (ua1 - ua0))
    if curved:
        tb = _fraction(w_b, e0, e1)
        qb = B.eval(pid, ub0 + tb * (ub1 - ub0))
        dq = np.hypot(*(qa - qb).T)
        c = np.flatnonzero(conc[pid])
        if c.size:
            k = pid[c]
            ang = A.th0[ka[c]] + A.sg[ka[c]] * (ua0[c] + ta[c] * (ua1[c] - ua0[c]))
            dq[c], qb[c] = same_angle(qa[c], ang, dq[c], qb[c],
                                      lambda u, k=k: B.eval(k, u), B.th0[k], B.sg[k], B.U[k])
    else:
        dq, qb = B.points_to(pid, qa)
    live, ok = _exempt(pid, c0, c1, da, qa, exempts)
    return lb, dq, qa, qb, live, ok


def _ends(S: SpiralRows, k, u0, u1):
    """``(S.eval(k, u0), S.eval(k, u1))``, a point that ends one piece and starts
    the next (one curve, the same bits of ``u``: the same point, as the
    evaluation works element by element) evaluated once."""
    n = k.size
    p0 = S.eval(k, u0)
    shared = (k[1:] == k[:-1]) & (u1[:-1].view(np.int64) == u0[1:].view(np.int64))
    from_next = np.flatnonzero(shared)
    own = np.append(np.flatnonzero(~shared), n - 1) if n else from_next
    p1 = np.empty((n, 2))
    put_rows(p1, from_next, take_rows(p0, from_next + 1))
    put_rows(p1, own, S.eval(k[own], u1[own]))
    return p0, p1


def _mid_arc(A: SpiralRows, ka, B: ExactRows | SpiralRows, pid, ua0, ua1, ub0=None, ub1=None,
             arc_a=None):
    """:func:`~ccopt.verify.distance.mid_arc.mid_arc_bound` of spiral pieces
    ``[ua0, ua1]`` of ``A``'s curves ``ka`` (their :func:`_mid_arc_of`, if known:
    ``arc_a``) against ``B``'s elements ``pid``, or against their pieces
    ``[ub0, ub1]`` when ``B`` holds spirals."""
    if arc_a is None:
        arc_a = _mid_arc_of(A, ka, ua0, ua1)
    if isinstance(B, ExactRows):
        return mid_arc_bound(arc_a, element_to=lambda c, R, t, w: B.arcs_to(pid, c, R, t, w))
    return mid_arc_bound(arc_a, mid_arc(take_rows(B.c, pid), B.rho0[pid], B.b[pid], B.th0[pid],
                                        B.sg[pid], ub0, ub1))


def _exempt(pid, c0, c1, da, qa, exempts):
    """``(live, ok)`` of each piece: not skipped as inside its pair's open-end
    exemption by its chord deviation, and its witness outside the exemption
    (all True for pairs without one); ``exempts``: ``(ex_objs, ex_of)``."""
    live = np.ones(pid.size, bool)
    ok = np.ones(pid.size, bool)
    ex_objs, ex_of = exempts
    with_ex = np.flatnonzero(ex_of >= 0)
    if not with_ex.size:
        return live, ok
    order = np.argsort(pid, kind="stable")
    edges = np.searchsorted(pid[order], np.arange(ex_of.size + 1))
    for m, ex in zip(with_ex.tolist(), ex_of[with_ex].tolist()):
        idx = order[edges[m]:edges[m + 1]]
        if idx.size:
            inside_by, contains = ex_objs[ex]
            skip = inside_by(c0[idx], da[idx]) & inside_by(c1[idx], da[idx])
            live[idx] = ~skip
            ok[idx] = ~skip & ~contains(qa[idx])
    return live, ok


def _mid_arc_of(S: SpiralRows, k, u0, u1):
    """:func:`~ccopt.verify.distance.mid_arc.mid_arc` of the pieces ``[u0, u1]``
    of ``S``'s curves ``k``."""
    return mid_arc(take_rows(S.c, k), S.rho0[k], S.b[k], S.th0[k], S.sg[k], u0, u1)


def _piece_counts(C: SpiralRows | BezierRows, k) -> np.ndarray:
    """How many first pieces :func:`~ccopt.verify.distance.certified._first_pieces`
    cuts curve ``k`` of ``C`` into: a spiral (or arc) one per
    :data:`~ccopt.verify.distance.certified.FIRST_PIECE_ANGLE` of sweep, at
    least :data:`~ccopt.verify.distance.certified.FIRST_PIECES`; a Bezier curve
    that many."""
    if isinstance(C, SpiralRows):
        return np.maximum(FIRST_PIECES, np.ceil(C.U[k] / FIRST_PIECE_ANGLE)).astype(np.intp)
    return np.full(np.size(k), FIRST_PIECES, np.intp)


def _cuts(U: np.ndarray, n: np.ndarray, k: np.ndarray):
    """``(u0, u1)`` of piece ``k`` of ``[0, U]`` cut into ``n`` equal pieces, with
    the numbers ``np.linspace(0, U, n + 1)`` gives (``k * step``, the last end
    ``U`` itself)."""
    step = U / n
    return k * step, np.where(k + 1 == n, U, (k + 1) * step)


def _first(A: SpiralRows | BezierRows, B, sel, curved: bool):
    """Every pair's first pieces (pairs of pieces for a curved ``b``): the cuts
    of :func:`~ccopt.verify.distance.certified._first_pieces`, all pairs at
    once, and their :func:`_curve_pieces` (``None`` for Bezier curves)."""
    sel = np.asarray(sel, np.intp)
    m = np.arange(sel.size)
    na = _piece_counts(A, sel)
    nb = _piece_counts(B, m) if curved else np.ones(sel.size, np.intp)
    per = na * nb
    pid = np.repeat(m, per)
    t = np.arange(pid.size) - np.repeat(np.cumsum(per) - per, per)   # index within its pair
    if curved:
        ia, ib = np.divmod(t, nb[pid])
    else:
        ia = t
    ua0, ua1 = _cuts(A.U[sel][pid], na[pid], ia)
    alike = _curve_pieces(A, sel, na, pid, ia) if isinstance(A, SpiralRows) else None
    if not curved:
        return (pid, ua0, ua1, None, None), alike
    ub0, ub1 = _cuts(B.U[pid], nb[pid], ib)
    return (pid, ua0, ua1, ub0, ub1), alike


def _curve_pieces(A: SpiralRows, sel, na, pid, ia):
    """``(k, u0, u1, at)``: the first pieces of each distinct curve of the pairs
    ``sel`` (``k`` a row of ``A`` holding it, ``[u0, u1]`` the piece) and, per
    piece ``ia`` of pair ``pid``, its place among them. The pairs of one curve
    have the same numbers and so the same cuts: what depends on the curve's
    piece alone is the same for each of them."""
    obj = A.obj[sel]
    used, inv = used_rows(obj, A.obj.size)
    pair = np.empty(A.obj.size, np.intp)
    pair[obj] = np.arange(sel.size)     # a pair of each curve (any: they are alike)
    rep = pair[used]
    n = na[rep]
    start = np.cumsum(n) - n
    k = np.repeat(sel[rep], n)
    u0, u1 = _cuts(A.U[k], np.repeat(n, n), np.arange(k.size) - np.repeat(start, n))
    return k, u0, u1, start[inv][pid] + ia


def _radial_gap(A, ka, ua0, ua1, B, pid, ub0, ub1, conc, Rb, curved):
    """:func:`ccopt.verify.distance.certified._radial_gap` of each piece (0 where ``b`` is not
    about ``a``'s centre)."""
    c = conc[pid]
    if not c.any():
        return 0.0
    lo_a, hi_a = A.radius_range(ka, ua0, ua1)
    if curved:
        lo_b, hi_b = B.radius_range(pid, ub0, ub1)
    else:
        lo_b = hi_b = Rb[pid]
    gap = np.maximum(np.maximum(lo_a - hi_b, lo_b - hi_a), 0.0)
    if curved:
        k = np.flatnonzero(c)
        a = _View(A, ka[k])
        b = _View(B, pid[k])
        gap[k] = np.maximum(gap[k], polar_gap(a, ua0[k], ua1[k], b, ub0[k], ub1[k]))
    return np.where(c, gap, 0.0)


class _View:
    """The spiral parameters of each piece's curve, as :func:`polar_gap` reads them."""

    def __init__(self, S: SpiralRows, k):
        self.th0, self.sg, self.rho0, self.b = S.th0[k], S.sg[k], S.rho0[k], S.b[k]


def _halve(pid, ua0, ua1, ub0, ub1, keep, curved: bool):
    """Kept pieces cut in two (pairs in four), in :func:`certified._halve`'s order per pair."""
    pid, ua0, ua1 = pid[keep], ua0[keep], ua1[keep]
    mid = 0.5 * (ua0 + ua1)
    if not curved:
        return (np.concatenate((pid, pid)), np.concatenate((ua0, mid)),
                np.concatenate((mid, ua1)), None, None)
    ub0, ub1 = ub0[keep], ub1[keep]
    midb = 0.5 * (ub0 + ub1)
    return (np.concatenate((pid, pid, pid, pid)), np.concatenate((ua0, ua0, mid, mid)),
            np.concatenate((mid, mid, ua1, ua1)), np.concatenate((ub0, midb, ub0, midb)),
            np.concatenate((midb, ub1, midb, ub1)))
