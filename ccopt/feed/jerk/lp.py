"""The linear programme of the ``jerk`` planner on one window of gridpoints.

See :mod:`ccopt.feed.jerk.planner` for the formulation. Here: the gridpoint
data (:class:`JerkGrid`), the LP of a window (:class:`WindowLP`, built once
and solved for each speed bound ``bhat`` of the pseudo-jerk rounds), and the
piece durations (:func:`piece_times`).

Unknowns of a window of gridpoints ``0..n``: the squared speeds ``b_k`` and
the path accelerations ``alpha_k = s''`` (``b' = 2 alpha``), scaled by
``B`` (the largest squared speed cap) so the LP sees numbers of order 1.
"""
from __future__ import annotations

import os
import sys
import threading
from dataclasses import dataclass

import highspy
import numpy as np

from ccopt.feed.jerk.columns import Entries, compressed_columns

#: Interval kinds: ``alpha`` linear in ``s``, or a constant-jerk piece from or to rest.
SLINEAR, FROM_REST, TO_REST = 0, 1, 2

#: Objective weights ``h / bhat^(3/2)`` (the linearised time) take ``bhat`` at
#: least this share of the window's largest, so the weights span at most
#: 1e3 and none falls under HiGHS's optimality tolerance (1e-7 relative).
WEIGHT_FLOOR = 1e-2
#: The unit of a ``b`` column is the window's first bound there, but at least
#: this (scaled): HiGHS's feasibility tolerance is absolute, so each column in
#: its own unit makes it relative (see :class:`WindowLP`), down to squared
#: speeds of this share of the scale. Smaller units put HiGHS in numerical
#: trouble (units to 2.5e-9 near a stop: a window of a generated CAM plate,
#: seed 179 of tests/feed/test_jerk_generated.py, ended in an unknown status,
#: by the interior-point method too); with a floor of 1e-6 a squared speed 5e-9 mm
#: from a stop passed its bound by 3.5 % (seed 196); 1e-7 and 1e-8 hold both.
B_UNIT_FLOOR = 1e-8
#: Simplex iterations per gridpoint after which a round's solve counts as run
#: away (then solved once more from scratch by the interior-point method, see
#: :meth:`WindowLP.solve`): about twice the most a solve that converges takes
#: (4.5 per gridpoint, a cold start on freeform-hsm's smoothed path; 3 to 4 on
#: the smoothed CAM plates), since every iteration past it is lost when the
#: run is given up. A warm start that runs away keeps going for minutes: on a
#: smoothed plate of 1,876 gridpoints a cold simplex was still short of the
#: optimum after 139,000 iterations where IPM took 16.
RUNAWAY_ITERATIONS = 8
#: Interior-point iterations allowed to the solve that follows a run-away
#: simplex (their number grows with the logarithm of the accuracy asked, not
#: with the LP's size: 16 on that plate; HiGHS's own cap is effectively none).
IPM_ITERATIONS = 200


@dataclass
class JerkGrid:
    """Gridpoints ``s`` (``N + 1``) and what the LP needs at them.

    ``q1, q2, q3``: ``(2, N + 1, dof)`` one-sided ``q', q'', q'''`` (index 0 the
    left limit, 1 the right); ``kind``: ``(N,)`` interval kinds; ``stop``:
    ``(N + 1,)`` gridpoints where the speed is 0; ``bmax``: ``(N + 1,)`` box
    bound on ``b`` (units^2/s^2); ``amax_t``: bound on ``|alpha|`` or ``inf``;
    ``v, a, j``: axis limits in plane order; ``m1, m2, m3``: ``(T, N, dof)``
    ``q', q'', q'''`` at the fractions :data:`INNER_POINTS` of every interval
    (for the inner jerk rows of :func:`_inner_rows`).
    """

    s: np.ndarray
    q1: np.ndarray
    q2: np.ndarray
    q3: np.ndarray
    kind: np.ndarray
    stop: np.ndarray
    bmax: np.ndarray
    amax_t: float
    a: np.ndarray
    j: np.ndarray
    m1: np.ndarray
    m2: np.ndarray
    m3: np.ndarray
    #: ``(N,)`` intervals of a stretch between two stops that is one straight
    #: segment (no LP there: see :func:`~ccopt.feed.jerk.planner.lone_lines`);
    #: None: every stretch goes to the LP
    lone: np.ndarray | None = None


#: An interval gets inner jerk rows where the curvature ``|q''|`` differs
#: between its ends by more than this share of the larger (on a blend curve or
#: a spiral; not on a line or an arc).
CURVATURE_CHANGE = 1e-6
#: Where inside such an interval (fractions of its length) the jerk is also
#: imposed: see :func:`_inner_rows`.
INNER_POINTS = (0.25, 0.5, 0.75)


def _interval_rows(g: JerkGrid, i0: int, i1: int, scale: float, vref: np.ndarray):
    """The constraints of the intervals ``i0..i1-1`` (window-local variable
    indices) as ``(A, lo, hi, jerk, col_lo, col_hi)``: sparse rows (CSC) with
    bounds; the jerk rows ``(rows, at0, at1)`` whose bounds change between
    rounds (see below); and bounds on the columns that single-entry rows come to.

    A jerk row is ``sqrt(bhat_m) * (a linear form in b, alpha) <= J`` with
    ``m`` the row's speed point: the gridpoint itself on an ``SLINEAR``
    interval, the moving end of a rest piece (the row at its stop has its
    other terms on variables fixed at 0). Divided by ``sqrt(bhat_m)`` it
    is a fixed row with bounds ``+-J / sqrt(bhat_m)``; times ``vref_m / J``
    (``vref``: the window's first speed bound, units/s) its coefficients are
    of order 1 and its bounds ``+-vref_m / sqrt(bhat_m)``, which start at 1,
    are all that changes between rounds.

    On a straight interval (``q'' = q''' = 0`` at both ends) every axis's
    jerk row at both ends is a multiple of one row (:func:`_straight_rows`);
    :func:`_assemble` leaves out the rows that add nothing.
    """
    n = i1 - i0
    k = np.arange(n)
    h = np.diff(g.s[i0:i1 + 1])
    kind = g.kind[i0:i1]
    nb = n + 1                                   # b_k at column k, alpha_k at nb + k
    rows, cols, vals = [], [], []

    def add(rr, cc, vv):
        rows.append(rr), cols.append(cc), vals.append(vv)

    lin, fr, to = kind == SLINEAR, kind == FROM_REST, kind == TO_REST
    _equality_rows(add, k, h, nb, lin, fr, to)
    r = n
    q1s, q2s, q3s = g.q1[1, i0:i1], g.q2[1, i0:i1], g.q3[1, i0:i1]          # at starts
    q1e, q2e, q3e = g.q1[0, i0 + 1:i1 + 1], g.q2[0, i0 + 1:i1 + 1], g.q3[0, i0 + 1:i1 + 1]
    straight = (np.all((q2s == 0.0) & (q3s == 0.0) & (q2e == 0.0) & (q3e == 0.0)
                       & (q1s == q1e), axis=1))
    slope_b = np.where(lin, 0.0, 2.0 / (9.0 * h * h))     # rest pieces: sigma = v_m 2 b_m / (9 h^2)
    slope_a = np.where(lin, 1.0 / h, 0.0)                 # SLINEAR: s''' = s' (alpha_k+1 - alpha_k) / h
    mov_of = [np.where(fr, k + 1, np.where(to, k, k + end)) for end in (0, 1)]
    acc_rows, jerk_rows, jerk_at, twin = [], [], [], []
    for end, side in ((0, 1), (1, 0)):               # interval start (right limits), end (left)
        gi = i0 + k + end
        q1, q2, q3 = g.q1[side, gi], g.q2[side, gi], g.q3[side, gi]
        col_b, col_a, mov = k + end, nb + k + end, mov_of[end]
        for i in range(g.a.size):
            # acceleration q' alpha + q'' b (both scaled by `scale`); an interval's
            # end row is its successor's start row where q', q'' are continuous
            add(r + k, col_a, q1[:, i] * scale / g.a[i])
            add(r + k, col_b, q2[:, i] * scale / g.a[i])
            acc_rows.append(r + k)
            if end == 1:
                same = ((g.q1[0, gi, i] == g.q1[1, gi, i]) & (g.q2[0, gi, i] == g.q2[1, gi, i])
                        & (k < n - 1))
                twin.append(r + k[same])
            r += n
            # jerk / s': q''' b + 3 q'' alpha + q' (path jerk / s'), times vref_m / J
            c = ~straight
            rr, kc, mc = r + k[c], k[c], mov[c]
            cj = vref[mc] * scale / g.j[i]
            lc, rc = lin[c], ~lin[c]
            add(rr, col_b[c], q3[c, i] * cj)
            add(rr, col_a[c], 3.0 * q2[c, i] * cj)
            add(rr[lc], nb + kc[lc] + 1, q1[c, i][lc] * slope_a[c][lc] * cj[lc])
            add(rr[lc], nb + kc[lc], -q1[c, i][lc] * slope_a[c][lc] * cj[lc])
            add(rr[rc], mc[rc], q1[c, i][rc] * slope_b[c][rc] * cj[rc])
            jerk_rows.append(rr)
            jerk_at.append(np.stack([mc, mc]))
            r += n
    n_before = sum(x.size for x in jerk_rows)
    r, rise_straight = _straight_rows(add, g, r, k, h, nb, straight, lin, mov_of, q1s, slope_a,
                                      slope_b, vref, scale, jerk_rows, jerk_at)
    r = _inner_rows(add, g, i0, i1, k, h, nb, lin & ~straight, vref, scale, r,
                     jerk_rows, jerk_at)
    rise = np.zeros(sum(x.size for x in jerk_rows))
    rise[n_before:n_before + rise_straight.size] = rise_straight
    return _assemble(n, r, rows, cols, vals, g.stop[i0:i1 + 1], np.concatenate(acc_rows),
                     np.concatenate(twin), np.concatenate(jerk_rows),
                     np.concatenate(jerk_at, axis=1), rise)


def _inner_rows(add, g: JerkGrid, i0, i1, k, h, nb, moving, vref, scale, r, jerk_rows,
                 jerk_at) -> int:
    """Jerk rows inside every ``SLINEAR`` interval ``moving`` whose curvature
    changes along it (:data:`CURVATURE_CHANGE`), at the fractions
    :data:`INNER_POINTS` of its length; returns the next free row index.

    Why: the axis jerk ``s' (q''' b + 3 q'' alpha + q' alpha')`` is there a
    product of terms that all change along the interval (``q''`` grows from 0
    at a blend's end while ``alpha`` changes), so it bulges between two
    gridpoints that both meet the limit: 0.87 % over it, sampled at 10 kHz,
    on the smoothed ``pocket-chords`` without these rows. At ``x = theta h``
    the model is linear in the unknowns: ``alpha = (1 - theta) alpha_k +
    theta alpha_k+1``, ``b = b_k + h ((2 theta - theta^2) alpha_k + theta^2
    alpha_k+1)``, ``alpha' = (alpha_k+1 - alpha_k) / h``; the speed factor is
    the larger ``bhat`` of the two ends, as on a straight interval."""
    q2s, q2e = g.q2[1, i0:i1], g.q2[0, i0 + 1:i1 + 1]
    ks, ke = np.linalg.norm(q2s, axis=1), np.linalg.norm(q2e, axis=1)
    mid = moving & (np.abs(ke - ks) > CURVATURE_CHANGE * np.maximum(ks, ke))
    km, hm = k[mid], h[mid]
    if km.size == 0:
        return r
    at = np.stack([km, km + 1])
    vmax = np.maximum(vref[km], vref[km + 1]) * scale
    for t, theta in enumerate(INNER_POINTS):
        m1, m2, m3 = g.m1[t, i0:i1][mid], g.m2[t, i0:i1][mid], g.m3[t, i0:i1][mid]
        for i in range(g.a.size):
            cj = vmax / g.j[i]
            rr = r + np.arange(km.size)
            add(rr, km, m3[:, i] * cj)
            add(rr, nb + km, ((2.0 * theta - theta * theta) * hm * m3[:, i]
                              + 3.0 * (1.0 - theta) * m2[:, i] - m1[:, i] / hm) * cj)
            add(rr, nb + km + 1, (theta * theta * hm * m3[:, i] + 3.0 * theta * m2[:, i]
                                  + m1[:, i] / hm) * cj)
            jerk_rows.append(rr), jerk_at.append(at)
            r += km.size
    return r


def _equality_rows(add, k, h, nb, lin, fr, to) -> None:
    """One row per interval ``k``: the trapezoid ``b_k+1 - b_k = h (alpha_k +
    alpha_k+1)`` (``SLINEAR``), or a rest piece's ``alpha = +-2 b / (3 h)`` at
    its moving end."""
    add(k[lin], k[lin] + 1, np.ones(lin.sum()))
    add(k[lin], k[lin], -np.ones(lin.sum()))
    add(k[lin], nb + k[lin], -h[lin])
    add(k[lin], nb + k[lin] + 1, -h[lin])
    add(k[fr], nb + k[fr] + 1, np.ones(fr.sum()))
    add(k[fr], k[fr] + 1, -2.0 / (3.0 * h[fr]))
    add(k[to], nb + k[to], np.ones(to.sum()))
    add(k[to], k[to], 2.0 / (3.0 * h[to]))


def _straight_rows(add, g: JerkGrid, r, k, h, nb, straight, lin, mov_of, q1s, slope_a, slope_b,
                   vref, scale, jerk_rows, jerk_at):
    """The one jerk row of each straight interval (rows from ``r``):
    ``cj * slope * (alpha_k+1 - alpha_k)``, or ``cj * slope * b_mov`` on a rest
    piece; ``cj`` takes the axis of largest ``|q_i'| / J_i`` and the larger
    ``bhat`` of the two ends (speed points ``at0``, ``at1``). Returns the next
    free row and each row's rise bound ``Jt h^2`` (``Jt = min_i J_i / |q_i'|``
    the path jerk limit; 0 on rest pieces), see :meth:`WindowLP.peaks_over`."""
    at = np.stack([mov_of[0][straight], mov_of[1][straight]])
    ratio = np.max(np.abs(q1s[straight]) / g.j, axis=1)          # 1 / Jt
    cj = vref[at].max(axis=0) * scale * ratio
    rr = r + np.arange(at.shape[1])
    ks, mov, ls = k[straight], at[0], lin[straight]
    sa, sb = slope_a[straight], slope_b[straight]
    add(rr[ls], nb + ks[ls] + 1, sa[ls] * cj[ls])
    add(rr[ls], nb + ks[ls], -sa[ls] * cj[ls])
    add(rr[~ls], mov[~ls], sb[~ls] * cj[~ls])
    jerk_rows.append(rr), jerk_at.append(at)
    return r + at.shape[1], np.where(ls, h[straight] ** 2 / ratio, 0.0)


def _assemble(n, r, rows, cols, vals, stop, acc_rows, twin, jerk_rows, jerk_at, rise):
    """The matrix of :func:`_interval_rows` without what adds nothing: an
    interval's end acceleration row where ``q'``, ``q''`` are continuous (it is
    the next interval's start row), coefficients of variables fixed at 0
    (stops) and the rows left empty (an axis the path does not move); an
    acceleration row with a single entry becomes a bound on that column."""
    nb = n + 1
    rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
    fixed = np.concatenate([stop, stop])
    keep = (vals != 0.0) & ~fixed[cols]
    dropped = np.zeros(r, bool)
    dropped[twin] = True
    keep &= ~dropped[rows]
    rows, cols, vals = rows[keep], cols[keep], vals[keep]
    # acceleration rows with one entry: |coefficient * x| <= 1 bounds x
    is_acc = np.zeros(r, bool)
    is_acc[acc_rows] = True
    count = np.bincount(rows, minlength=r)
    single = is_acc[rows] & (count[rows] == 1)
    col_hi = np.full(2 * nb, np.inf)
    np.minimum.at(col_hi, cols[single], 1.0 / np.abs(vals[single]))
    rows, cols, vals = rows[~single], cols[~single], vals[~single]
    used = np.zeros(r, bool)
    used[rows] = True
    used[:n] = True                                  # the equalities stay (a row per interval)
    new_index = np.cumsum(used) - 1
    A = Entries(new_index[rows], cols, vals, int(used.sum()))
    kept = used[jerk_rows]
    lo = -np.ones(A.n_rows)
    lo[:n] = 0.0
    jerk = (new_index[jerk_rows[kept]].astype(np.int32), jerk_at[0, kept], jerk_at[1, kept],
            rise[kept])
    return A, lo, -lo, jerk, -col_hi, col_hi


def _peak_cap_rows(g: JerkGrid, i0: int, i1: int, scale: float):
    """``(A, hi)``: one row ``b_k + h alpha_k <= bmax`` (scaled) on every
    ``SLINEAR`` interval of ``i0..i1`` whose box bound ``bmax`` is the same at
    both ends (a feed or velocity cap along a line; on an arc, the feed where
    it binds at both ends, the axis velocity caps changing along it).

    Why: where ``alpha`` falls through 0 inside the interval (``alpha_k > 0 >
    alpha_k+1``) the squared speed peaks there at ``b* = b_k + alpha_k^2 h /
    (alpha_k - alpha_k+1)``, above both gridpoints, which the column bounds on
    ``b`` alone let past the cap (0.11 % over the programmed feed between two
    gridpoints at the cap, on a 60 mm line at F600). With the trapezoid
    ``b_k+1 = b_k + h (alpha_k + alpha_k+1)``, ``b_k + h alpha_k`` equals
    ``b_k+1 - h alpha_k+1`` and bounds ``b*`` (``b* = b_k + alpha_k sigma*``
    with the peak at ``sigma* <= h``); it is at most ``b_k+1`` when ``alpha``
    rises through the interval and at most ``b_k`` when it falls, so the row
    binds only where the speed peaks inside, by at most ``h min(alpha_k,
    -alpha_k+1)`` more than the peak needs."""
    n = i1 - i0
    k = np.arange(n)
    h = np.diff(g.s[i0:i1 + 1])
    bmax0, bmax1 = g.bmax[i0:i1], g.bmax[i0 + 1:i1 + 1]
    stop = g.stop[i0:i1 + 1]
    use = ((g.kind[i0:i1] == SLINEAR) & (bmax0 == bmax1) & np.isfinite(bmax0)
           & ~stop[:-1] & ~stop[1:])
    ks = k[use]
    m = ks.size
    nb = n + 1
    rows = np.concatenate([np.arange(m), np.arange(m)])
    cols = np.concatenate([ks, nb + ks])
    vals = np.concatenate([np.ones(m), h[use]])
    return Entries(rows, cols, vals, m), bmax0[use] / scale


class WindowLP:
    """The LP of the gridpoints ``i0..i1`` of a window, built once and solved
    for each speed bound ``bhat`` of the pseudo-jerk rounds.

    Between rounds only bounds and costs change (the jerk rows' bounds, see
    :func:`_interval_rows`; the caps on ``b``; the objective weights), so one
    ``highspy.Highs`` keeps the model and HiGHS's simplex starts each round
    from the last one's optimal basis. Values are scaled by ``1 / scale``
    (the LP's ``b`` columns further by ``bref``, see the comment in ``__init__``);
    ``bref``: the window's first ``bhat`` (scaled); ``start``: fixed scaled
    ``(b, alpha)`` at ``i0``, or None (then ``i0`` is a stop or free as the
    grid says); ``end`` likewise at ``i1``.
    """

    def __init__(self, g: JerkGrid, i0: int, i1: int, bref: np.ndarray,
                 start: tuple[float, float] | None, scale: float,
                 end: tuple[float, float] | None = None):
        self.nb = nb = i1 - i0 + 1
        self.scale = scale
        self.vref = np.sqrt(np.where(bref > 0.0, bref, 1.0) * scale)     # units/s
        A, lo, hi, jerk, col_lo, col_hi = _interval_rows(g, i0, i1, scale, self.vref)
        A_cap, hi_cap = _peak_cap_rows(g, i0, i1, scale)
        lo = np.concatenate([lo, np.full(hi_cap.size, -np.inf)])
        hi = np.concatenate([hi, hi_cap])
        self.jerk_rows, self.jerk_at0, self.jerk_at1, self.rise = jerk
        self.v_at = np.maximum(self.vref[self.jerk_at0], self.vref[self.jerk_at1])
        self.h = np.diff(g.s[i0:i1 + 1])
        #: jerk rows whose speed factor covers the speed's peak inside their interval
        self.peaked = np.zeros(self.rise.size, bool)
        stop = g.stop[i0:i1 + 1]
        self.bmax = np.where(stop, 0.0, np.minimum(g.bmax[i0:i1 + 1] / scale, col_hi[:nb]))
        a_t = g.amax_t / scale
        lb = np.concatenate([np.zeros(nb), np.where(stop, 0.0, np.maximum(-a_t, col_lo[nb:]))])
        ub = np.concatenate([self.bmax, np.where(stop, 0.0, np.minimum(a_t, col_hi[nb:]))])
        if start is not None:
            lb[0] = ub[0] = self.bmax[0] = start[0]
            lb[nb] = ub[nb] = start[1]
        if end is not None:
            lb[nb - 1] = ub[nb - 1] = self.bmax[nb - 1] = end[0]
            lb[-1] = ub[-1] = end[1]
        self.b_low = lb[:nb].copy()
        self.fixed = lb == ub                  # columns (see _crash)
        # each b column in units of its own first bound (B_UNIT_FLOOR at
        # least): HiGHS's feasibility tolerance is absolute, and near a stop,
        # where b is orders of magnitude below the scale, it let b pass its
        # bound bhat by 2.3 % (bhat is the jerk rows' speed factor, so the
        # jerk went 1 % over its limit: a generated CAM plate, seed 127 of
        # tests/feed/test_jerk_generated.py)
        self.b_unit = np.maximum(np.where(bref[:nb] > 0.0, bref[:nb], 1.0), B_UNIT_FLOOR)
        # the interval rows, then the cap rows; each b column in its unit
        A = A.above(A_cap)
        start, index, value = compressed_columns(A.rows, A.cols, A.vals, 2 * nb,
                                                 np.concatenate([self.b_unit, np.ones(nb)]))
        lb[:nb] /= self.b_unit
        ub[:nb] /= self.b_unit
        s = g.s[i0:i1 + 1]
        self.hbar = np.zeros(nb)
        self.hbar[:-1] += 0.5 * np.diff(s)
        self.hbar[1:] += 0.5 * np.diff(s)
        self.b_cols = np.arange(nb, dtype=np.int32)
        self.highs = _new_highs()
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = 2 * nb, A.n_rows
        lp.col_cost_, lp.col_lower_, lp.col_upper_ = np.zeros(2 * nb), lb, ub
        lp.row_lower_, lp.row_upper_ = lo, hi
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_, lp.a_matrix_.index_, lp.a_matrix_.value_ = start, index, value
        self.highs.passModel(lp)
        self.warm = False

    def solve(self, bhat: np.ndarray, cap: np.ndarray, max_iterations: int | None = None):
        """``(b, alpha)`` (scaled) maximising the linearised time gain under the
        pseudo-jerk bound ``bhat``, with ``b <= cap``; None unless optimal,
        or when HiGHS's simplex would take more than ``max_iterations``
        (then the next call starts from where it stopped). Without
        ``max_iterations`` a run past :data:`RUNAWAY_ITERATIONS` per gridpoint
        (or one in numerical trouble) is solved once more under the same bound
        from the crash basis (:meth:`_crash`), then from scratch by the
        interior-point method (at most :data:`IPM_ITERATIONS`), then None."""
        h, nb = self.highs, self.nb
        b_at = np.maximum(bhat[self.jerk_at0], bhat[self.jerk_at1])
        B = np.maximum(b_at, 0.0) * self.scale
        with np.errstate(divide="ignore", invalid="ignore"):
            B = np.where(self.peaked & (B > 0.0), B + self.rise / np.sqrt(B), B)
            jb = np.where(b_at > 0.0, self.v_at / np.sqrt(B), np.inf)
        h.changeRowsBounds(self.jerk_rows.size, self.jerk_rows, -jb, jb)
        ub = np.maximum(np.minimum(self.bmax, cap), self.b_low)   # a fixed start stays fixed
        h.changeColsBounds(nb, self.b_cols, self.b_low / self.b_unit, ub / self.b_unit)
        floor = WEIGHT_FLOOR * max(float(bhat.max(initial=0.0)), np.finfo(float).tiny)
        w = self.hbar / np.maximum(bhat, floor) ** 1.5
        h.changeColsCost(nb, self.b_cols, -w * self.b_unit / w.max())
        # every run bounded: by max_iterations when asked, else against a run-away
        runaway = int(RUNAWAY_ITERATIONS * nb)
        h.setOptionValue("simplex_iteration_limit",
                         int(max_iterations) if max_iterations is not None else runaway)
        warm = self.warm
        if not warm and CRASH:
            self._crash(ub / self.b_unit)
        h.run()
        if not warm:
            h.setOptionValue("dual_simplex_cost_perturbation_multiplier", WARM_PERTURBATION)
            self.warm = True
        h.setOptionValue("simplex_iteration_limit", highspy.kHighsIInf)
        limited = h.getModelStatus() == highspy.HighsModelStatus.kIterationLimit
        if max_iterations is not None and limited:
            return None
        if h.getModelStatus() != highspy.HighsModelStatus.kOptimal and warm and CRASH:
            # a re-solve that ran away from the last round's basis: first once
            # more from the crash basis, as the window's first solve started
            h.clearSolver()
            self._crash(ub / self.b_unit)
            h.setOptionValue("simplex_iteration_limit", runaway)
            h.run()
            h.setOptionValue("simplex_iteration_limit", highspy.kHighsIInf)
        if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
            # rare numerical trouble, or a simplex that ran away from the last
            # basis: once more, from scratch, by the interior-point method, whose
            # iteration count does not depend on a basis (a cold simplex on such
            # an LP, 1,876 gridpoints of a smoothed plate, ran past 139,000
            # iterations where IPM took 16); its crossover leaves the basis the
            # next round warm-starts from
            h.setOptionValue("solver", "ipm")
            h.setOptionValue("run_crossover", "on")
            h.setOptionValue("ipm_iteration_limit", int(IPM_ITERATIONS))
            h.clearSolver()
            h.run()
            h.setOptionValue("solver", "simplex")
        if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
            return None
        x = np.asarray(h.getSolution().col_value, dtype=float)
        return np.maximum(x[:nb] * self.b_unit, 0.0), x[nb:]

    def _crash(self, b_upper: np.ndarray) -> None:
        """Set the basis the next run starts from: every ``b`` nonbasic at its
        upper bound ``b_upper`` (scaled), every free ``alpha`` basic, the
        equality rows nonbasic and every other row basic; not HiGHS's slack
        basis, from which its dual simplex takes two to three iterations per
        gridpoint.

        Only the ``b`` columns have costs (negative, at their upper bounds), so
        the basic variables' costs are 0, so are the duals, and the basis is
        dual feasible: the dual simplex only mends the rows that ``b`` at its
        cap breaks. Between two gridpoints whose ``alpha`` is fixed (stops, a
        held start or end) the equality rows outnumber the free ``alpha`` by
        one: the ``b`` just before the later one is basic too (or, with no
        free point between them, the row)."""
        nb = self.nb
        col = np.where(np.isfinite(b_upper) & ~self.fixed[:nb], _UPPER, _LOWER)
        col = np.concatenate([col, np.where(self.fixed[nb:], _LOWER, _BASIC)])
        row = np.full(self.highs.getNumRow(), _BASIC)
        row[:nb - 1] = _LOWER                      # the equality rows (see _assemble)
        held = np.flatnonzero(self.fixed[nb:])
        for p, q in zip(held[:-1].tolist(), held[1:].tolist()):
            if q - 1 > p and not self.fixed[q - 1]:
                col[q - 1] = _BASIC
            else:
                row[p] = _BASIC
        if np.count_nonzero(col == _BASIC) + np.count_nonzero(row == _BASIC) != row.size:
            return                                 # not a basis: HiGHS's slack basis
        basis = highspy.HighsBasis()
        basis.col_status = _STATUS[col].tolist()
        basis.row_status = _STATUS[row].tolist()
        basis.valid = True
        self.highs.setBasis(basis)

    def peaks_over(self, b: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """The straight intervals' jerk rows to tighten for the speed's peak
        inside their interval: when any row's path jerk at that peak is over
        its limit, every row (not yet tightened) whose interval has such a peak;
        else none (``b, alpha`` scaled, a solution of :meth:`solve`).

        Where ``alpha`` falls through 0 inside a straight ``SLINEAR``
        interval (``alpha_k > 0 > alpha_k+1``) the squared speed peaks there at
        ``b_k + alpha_k^2 h / (alpha_k - alpha_k+1)``, above both ends, and the
        path jerk ``s' (alpha_k+1 - alpha_k) / h`` with it: 0.17 % over the
        limit on freeform-hsm's PMAC path. Such a row's speed factor is then
        ``B + Jt h^2 / sqrt(B)`` instead of ``B = bhat`` (:meth:`solve`), which
        covers the peak whatever the solution: the rise is at most
        ``|alpha_k+1 - alpha_k| h <= Jt h^2 / sqrt(B)``."""
        k = self.jerk_at0
        lin = (self.rise > 0.0) & (self.jerk_at1 == k + 1)
        a0, a1 = alpha[k] * self.scale, alpha[np.minimum(k + 1, alpha.size - 1)] * self.scale
        hk = self.h[np.minimum(k, self.h.size - 1)]
        fall = lin & (a0 > 0.0) & (a1 < 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            peak = b[k] * self.scale + np.where(fall, a0 * a0 * hk / (a0 - a1), 0.0)
            jt = self.rise / (hk * hk)                            # Jt (rise = Jt h^2)
            over = fall & (np.sqrt(peak) * (a0 - a1) / hk > jt * (1.0 + PEAK_TOL))
        # all the falls once one breaks the limit: tightening only those over it
        # moves the fall to their neighbours, pass after pass (6.2x TOPPRA's CPU
        # per gridpoint against 5x on the 10,000-block pocket of bench/feed.py)
        return fall & ~self.peaked if np.any(over & ~self.peaked) else np.zeros_like(over)


#: Relative excess of a straight interval's path jerk at its inner speed peak
#: that :meth:`WindowLP.peaks_over` lets pass.
PEAK_TOL = 1e-6

_BANNER_SHOWN = []
_BANNER_LOCK = threading.Lock()


#: Whether a window's first solve starts from :meth:`WindowLP._crash`'s basis
#: (and a re-solve that runs away from the last round's basis tries it again
#: before the interior-point method). The optimum is the same LP's: the
#: cycle times agree to the LP's tolerances.
CRASH = True
_LOWER, _BASIC, _UPPER = 0, 1, 2
_STATUS = np.array([highspy.HighsBasisStatus.kLower, highspy.HighsBasisStatus.kBasic,
                    highspy.HighsBasisStatus.kUpper], dtype=object)
#: HiGHS's cost perturbation (its multiplier) in the re-solves from the last
#: round's basis: none. Perturbed costs carry the cold start through
#: degenerate vertices; from a basis that is nearly optimal already they
#: only add a dual phase 1 and a clean-up of the perturbation to each round.
WARM_PERTURBATION = 0.0
#: HiGHS's dual simplex pricing on the window LPs: Devex (1). Its default,
#: steepest edge (2), takes fewer iterations on a cold start but costs more
#: per iteration on these banded LPs, more than it saves
#: (bench/jerk_highs.py measures both on the same plans); the optimum is
#: the same LP's, so the cycle times agree to the LP's tolerances.
DUAL_EDGE_WEIGHTS = 1
#: HiGHS's simplex scaling of the window LPs: 4, "max value" (every row and
#: column divided by a power of 2 near its largest entry), instead of its
#: default 2, equilibration. The window LPs come scaled by construction (each
#: ``b`` column in its own unit, the jerk rows times ``vref / J``, see
#: :class:`WindowLP`); equilibrating them again costs the cold solves more
#: iterations, and on some windows ends them a hair short of the optimum the
#: interior-point method confirms (bench/jerk_highs.py --setting scaling
#: measures both on the same plans).
SIMPLEX_SCALE = 4


def _new_highs():
    """A silent ``highspy.Highs`` running the simplex without presolve, with
    :data:`DUAL_EDGE_WEIGHTS` and :data:`SIMPLEX_SCALE`. The
    first one made in a process prints HiGHS's banner on the C-level stdout,
    before any option can stop it, which would spoil ``--json`` output: that
    one is made with file descriptor 1 pointed at the null device."""
    if _BANNER_SHOWN:
        h = highspy.Highs()
    else:
        with _BANNER_LOCK:           # windows are solved in threads too
            if _BANNER_SHOWN:
                h = highspy.Highs()
            else:
                sys.stdout.flush()
                saved = os.dup(1)
                try:
                    with open(os.devnull, "w") as null:
                        os.dup2(null.fileno(), 1)
                        h = highspy.Highs()
                finally:
                    os.dup2(saved, 1)
                    os.close(saved)
                _BANNER_SHOWN.append(True)
    h.setOptionValue("output_flag", False)
    # presolve finds little to remove in these banded LPs: 20 % faster without
    h.setOptionValue("presolve", "off")
    # highspy directly: scipy.optimize.milp runs the MIP machinery around the
    # simplex, ten times slower on these LPs
    h.setOptionValue("solver", "simplex")
    h.setOptionValue("simplex_dual_edge_weight_strategy", DUAL_EDGE_WEIGHTS)
    h.setOptionValue("simplex_scale_strategy", SIMPLEX_SCALE)
    return h


def piece_times(s: np.ndarray, kind: np.ndarray, b: np.ndarray, alpha: np.ndarray,
                slinear_time) -> np.ndarray:
    """Duration (s) of every interval: ``3 h / v`` for the rest pieces (``v``
    the speed at the moving end), the integral of ``1/sqrt(b)`` for the others."""
    h = np.diff(s)
    v = np.sqrt(np.maximum(b, 0.0))
    with np.errstate(divide="ignore"):
        dt = np.where(kind == FROM_REST, 3.0 * h / v[1:],
                      np.where(kind == TO_REST, 3.0 * h / v[:-1], 0.0))
    lin = kind == SLINEAR
    dt[lin] = slinear_time(b[:-1][lin], alpha[:-1][lin], alpha[1:][lin], h[lin], h[lin])
    return dt
