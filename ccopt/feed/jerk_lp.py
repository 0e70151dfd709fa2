"""The linear programme of the ``jerk`` planner on one window of gridpoints.

See :mod:`ccopt.feed.jerk_planner` for the formulation. Here: the gridpoint
data (:class:`JerkGrid`), the LP of a window for a given speed bound ``bhat``
(:func:`solve_window`), and the piece durations (:func:`piece_times`).

Unknowns of a window of gridpoints ``0..n``: the squared speeds ``b_k`` and
the path accelerations ``alpha_k = s''`` (``b' = 2 alpha``), scaled by
``B`` (the largest squared speed cap) so the LP sees numbers of order 1.
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass

import highspy
import numpy as np
import scipy.sparse as sp

#: Interval kinds: ``alpha`` linear in ``s``, or a constant-jerk piece from or to rest.
SLINEAR, FROM_REST, TO_REST = 0, 1, 2

#: Objective weights ``h / bhat^(3/2)`` (the linearised time) take ``bhat`` at
#: least this share of the window's largest, so the weights span at most
#: 1e3 and none falls under HiGHS's optimality tolerance (1e-7 relative).
WEIGHT_FLOOR = 1e-2


@dataclass
class JerkGrid:
    """Gridpoints ``s`` (``N + 1``) and what the LP needs at them.

    ``q1, q2, q3``: ``(2, N + 1, dof)`` one-sided ``q', q'', q'''`` (index 0 the
    left limit, 1 the right); ``kind``: ``(N,)`` interval kinds; ``stop``:
    ``(N + 1,)`` gridpoints where the speed is 0; ``bmax``: ``(N + 1,)`` box
    bound on ``b`` (units^2/s^2); ``amax_t``: bound on ``|alpha|`` or ``inf``;
    ``v, a, j``: axis limits in plane order.
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


def _interval_rows(g: JerkGrid, i0: int, i1: int, scale: float, bhat: np.ndarray):
    """Sparse rows (COO triplets) and bounds of the equalities, accelerations and
    jerks of the intervals ``i0..i1-1`` (window-local variable indices)."""
    n = i1 - i0
    k = np.arange(n)
    h = np.diff(g.s[i0:i1 + 1])
    kind = g.kind[i0:i1]
    nb = n + 1                                   # b_k at column k, alpha_k at nb + k
    rows, cols, vals, lo, hi = [], [], [], [], []
    r = 0

    def add(rr, cc, vv):
        rows.append(rr)
        cols.append(cc)
        vals.append(vv)

    # equalities: trapezoid (SLINEAR) or the rest pieces' alpha = +-2 b / (3 h)
    lin, fr, to = kind == SLINEAR, kind == FROM_REST, kind == TO_REST
    e = r + k
    add(e[lin], k[lin] + 1, np.ones(lin.sum()))
    add(e[lin], k[lin], -np.ones(lin.sum()))
    add(e[lin], nb + k[lin], -h[lin])
    add(e[lin], nb + k[lin] + 1, -h[lin])
    add(e[fr], nb + k[fr] + 1, np.ones(fr.sum()))
    add(e[fr], k[fr] + 1, -2.0 / (3.0 * h[fr]))
    add(e[to], nb + k[to], np.ones(to.sum()))
    add(e[to], k[to], 2.0 / (3.0 * h[to]))
    lo.append(np.zeros(n))
    hi.append(np.zeros(n))
    r += n
    dof = g.a.size
    sb = np.sqrt(np.maximum(bhat, 0.0) * scale)       # bhat is scaled like b
    for end, side in ((0, 1), (1, 0)):               # interval start (right limits), end (left)
        gi = i0 + k + end
        q1, q2, q3 = g.q1[side, gi], g.q2[side, gi], g.q3[side, gi]
        col_b, col_a = k + end, nb + k + end
        # the moving end supplies the speed of the rest pieces' constant jerk
        mov = np.where(fr, k + 1, np.where(to, k, k + end))
        for i in range(dof):
            # acceleration q' alpha + q'' b (both scaled by `scale`)
            rr = r + k
            add(rr, col_a, q1[:, i] * scale / g.a[i])
            add(rr, col_b, q2[:, i] * scale / g.a[i])
            lo.append(-np.ones(n))
            hi.append(np.ones(n))
            r += n
            # jerk sqrt(bhat) (q''' b + 3 q'' alpha) + sqrt(bhat_m) q' slope
            rr = r + k
            cj = scale / g.j[i]
            add(rr, col_b, sb[col_b] * q3[:, i] * cj)
            add(rr, col_a, sb[col_b] * 3.0 * q2[:, i] * cj)
            slope_b = np.where(lin, 0.0, 2.0 / (9.0 * h * h))
            add(rr, mov, sb[mov] * q1[:, i] * slope_b * cj)
            lin_c = np.where(lin, 1.0 / h, 0.0)
            add(rr, nb + k + 1, sb[col_b] * q1[:, i] * lin_c * cj)
            add(rr, nb + k, -sb[col_b] * q1[:, i] * lin_c * cj)
            lo.append(-np.ones(n))
            hi.append(np.ones(n))
            r += n
    A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(r, 2 * nb))
    return A, np.concatenate(lo), np.concatenate(hi)


def solve_window(g: JerkGrid, i0: int, i1: int, bhat: np.ndarray, cap: np.ndarray,
                 start: tuple[float, float] | None, scale: float):
    """``(b, alpha)`` of gridpoints ``i0..i1`` maximising the linearised time
    gain under the pseudo-jerk bound ``bhat`` (both scaled by ``1 / scale``),
    with ``b <= cap``; ``start``: fixed scaled ``(b, alpha)`` at ``i0``, or None
    (then ``i0`` is a stop or free as the grid says). ``None`` when infeasible.
    """
    n = i1 - i0
    A, lo, hi = _interval_rows(g, i0, i1, scale, bhat)
    nb = n + 1
    bmax = np.minimum(g.bmax[i0:i1 + 1] / scale, cap)
    stop = g.stop[i0:i1 + 1]
    bmax = np.where(stop, 0.0, bmax)
    a_t = g.amax_t / scale
    lb = np.concatenate([np.zeros(nb), np.where(stop, 0.0, -a_t)])
    ub = np.concatenate([bmax, np.where(stop, 0.0, a_t)])
    if start is not None:
        lb[0], ub[0] = start[0], start[0]
        lb[nb], ub[nb] = start[1], start[1]
    s = g.s[i0:i1 + 1]
    hbar = np.zeros(nb)
    hbar[:-1] += 0.5 * np.diff(s)
    hbar[1:] += 0.5 * np.diff(s)
    floor = WEIGHT_FLOOR * max(float(bhat.max(initial=0.0)), np.finfo(float).tiny)
    w = hbar / np.maximum(bhat, floor) ** 1.5
    w = w / w.max()
    x = _highs_simplex(np.concatenate([-w, np.zeros(nb)]), A.tocsc(), lo, hi, lb, ub)
    if x is None:
        return None
    return np.maximum(x[:nb], 0.0), x[nb:]


_BANNER_SHOWN = []


def _new_highs():
    """A silent ``highspy.Highs``. The first one made in a process prints HiGHS's
    banner on the C-level stdout, before any option can stop it, which would
    spoil ``--json`` output: that one is made with file descriptor 1 pointed at
    the null device."""
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
    return h


def _highs_simplex(c, A, lo, hi, lb, ub) -> np.ndarray | None:
    """``min c x`` with ``lo <= A x <= hi`` (ranged rows) and ``lb <= x <= ub`` by
    HiGHS's simplex (highspy directly: ``scipy.optimize.milp`` runs the MIP
    machinery around it, ten times slower on these LPs); None unless optimal."""
    h = _new_highs()
    h.setOptionValue("solver", "simplex")
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = A.shape[1], A.shape[0]
    lp.col_cost_, lp.col_lower_, lp.col_upper_ = c, lb, ub
    lp.row_lower_, lp.row_upper_ = lo, hi
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_, lp.a_matrix_.index_, lp.a_matrix_.value_ = A.indptr, A.indices, A.data
    h.passModel(lp)
    h.run()
    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        # rare numerical trouble without presolve: once more with it
        h.setOptionValue("presolve", "on")
        h.clearSolver()
        h.run()
    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return None
    return np.asarray(h.getSolution().col_value, dtype=float)


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
