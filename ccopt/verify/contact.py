"""Contact: wherever the tool runs alongside its element, it reaches it.

(A verifier decision, docs/compensation.md section 8.3.) For the tool segment
``T`` of every *steady* contour element ``e`` (compensated with the same side
and radius as the move before) the largest distance to ``e`` from the points
of ``T`` that lie alongside ``e`` (whose nearest point on ``e`` is not one of
its end points: the band normal to a line, the sector of an arc) must be at
most ``r + eps``. Every added corner arc must stay within ``r + eps`` of its
corner point ``P``: the programmed point where the in-plane moves run before
and after it meet (:func:`corner_points`; the point belongs to both, whichever
block carries the arc).

Alongside ``e`` the distance is ``|signed distance to e's line|`` or
``|rho - R|``, so for a line tool segment against a line element the
largest value is at an end of the part of ``T`` inside the band, and for an
arc concentric with its element it is ``|R_T - R_e|``: both in closed form,
vectorised. Any other line/arc pair (a displaced segment) is cut at the band
boundaries and measured with the exact farthest-point kernel
(:func:`~ccopt.verify.distance.max_distance`), all such pairs at once
(:mod:`ccopt.verify.alongside`); spirals and curves get a certified upper bound over the
whole segment (:func:`~ccopt.verify.distance.max_distance_bound`, conservative). A tool segment
that runs alongside its element over no length at all (it only touches the
band's edge, or it is an arc about the element's centre turning the other
way, e.g. swept 270 degrees the long way round instead of 90) does not run
along it: a violation of infinite depth.

Where the spec says the tool cannot touch (an inside corner, where the tool
stops short of the corner point; a shallow outside corner, where the offsets
are extended past the normal at ``P``) the tool is not alongside the
element, so nothing needs excepting by name. The figure is the largest
excess ``distance - r`` (the "contact gap"); moving a segment away from its
element by ``g`` makes it ``g``. A steady element with no compensated tool
segment at all (the path never runs along it) is not reached: a violation
with infinite depth.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import take_rows
from ccopt.program.model import PLANE_AXES
from ccopt.tolerances import POINT_EPS, VERIFY_CERTIFIED_GAP
from ccopt.toolpath import FITTED_PIECES, Role
from ccopt.verify.alongside import ALONGSIDE_MIN_LENGTH, farthest_clipped
from ccopt.verify.certificate import CERTIFIED, EXACT, Check, Violation
from ccopt.verify.contour import Contour
from ccopt.verify.distance import max_distance_bound, max_distance_to_point
from ccopt.verify.segments import KIND_ARC, KIND_LINE, Packed


def corner_points(rows, contour: Contour, table, ci: np.ndarray):
    """The programmed corner of each corner arc ``ci`` (tool segment indices).

    (A verifier decision, docs/compensation.md section 8.3.) A corner
    arc is run between the tool segments of the two in-plane moves that meet
    at its corner ``P``: ``P`` is the end of the in-plane move run last before
    it and the start of the one run first after it. Which block *carries* the
    arc differs between controllers (PMAC and Fagor the incoming move, LinuxCNC
    the outgoing one: it emits the arc while converting that block), so the
    carrier only decides when the path alone does not: when the moves run
    before and after are not consecutive in the program (a move whose tool
    segment vanished), ``P`` is the carrier's end if its move was run before
    the arc, its start if run after, and otherwise whichever of its two ends
    is nearer the arc's centre.

    Returns ``(P, incoming, outgoing)``: the corner points, ``(len(ci), 2)``, and
    the indices into ``contour.moves`` of the moves ending and starting there
    (-1 where there is none).
    """
    m = ci.size
    P = np.zeros((m, 2))
    q_in = np.full(m, -1, np.intp)
    q_out = np.full(m, -1, np.intp)
    if m == 0:
        return P, q_in, q_out
    n = table.move.size
    idx = np.arange(n)
    run = (table.move >= 0) & ~table.is_role(Role.CORNER)
    # last run segment before / first after each segment (corner arcs are not runs)
    before = np.maximum.accumulate(np.where(run, idx, -1))[ci]
    after = np.minimum.accumulate(np.where(run, idx, n)[::-1])[::-1][ci]
    qa = np.where(before >= 0, table.move[np.maximum(before, 0)], -1)
    qb = np.where(after < n, table.move[np.minimum(after, n - 1)], -1)
    qc = table.move[ci]
    last = len(contour.moves) - 1
    # the moves run before and after are consecutive (the common case), or
    # one of them is the carrier's own
    seq = (qa >= 0) & (qb == qa + 1)
    mine_in = ~seq & (qc >= 0) & (qa == qc)
    mine_out = ~seq & ~mine_in & (qc >= 0) & (qb == qc)
    q_in[seq], q_out[seq] = qa[seq], qb[seq]
    q_in[mine_in] = qc[mine_in]
    q_out[mine_in] = np.where(qc[mine_in] < last, qc[mine_in] + 1, -1)
    q_in[mine_out], q_out[mine_out] = qc[mine_out] - 1, qc[mine_out]
    known = seq | mine_in | mine_out
    # P: the end of the move ending there, else the start of the one starting there
    ending = known & (q_in >= 0)
    P[ending] = contour.move_end[q_in[ending]]
    starting = known & ~ending
    P[starting] = contour.move_start[q_out[starting]]
    i0, j0, _ = PLANE_AXES[contour.plane]
    for q in np.flatnonzero(~known).tolist():
        # the carrier's own move has no tool segment of its own: its end
        # nearer the arc's centre (the two are a whole move apart)
        c = int(qc[q])
        blk = rows.block(int(ci[q]))
        centre = rows.tool.arr.center[int(ci[q])]
        ends = np.array([[blk.start[i0], blk.start[j0]], [blk.end[i0], blk.end[j0]]])
        at_end = bool(np.hypot(*(ends[1] - centre)) <= np.hypot(*(ends[0] - centre)))
        P[q] = ends[1] if at_end else ends[0]
        if c >= 0:
            q_in[q], q_out[q] = (c, c + 1 if c < last else -1) if at_end else (c - 1, c)
    return P, q_in, q_out


def contact_pairs(rows, meta: dict, contour: Contour, lengths: np.ndarray, table):
    """``(steady tool segments, their elements, corner arcs, corner points, corner radii,
    moves ending at the corners, moves starting there)``."""
    steady = _runs_along(table) & table.steady & (table.element >= 0) & (lengths > POINT_EPS)
    si = np.flatnonzero(steady)
    ej = table.element[si]
    cand = np.flatnonzero(table.is_role(Role.CORNER) & (table.r > 0.0))
    # Only the arcs a controller adds are held to the corner rule: arcs fitted
    # to a blend curve or a spiral by an export keep the role of the curve they
    # replace (checked for gouge and continuity like it, not for touching the
    # corner; a verifier decision, docs/compensation.md section 8.3)
    fitted = set(meta.get(FITTED_PIECES, ()))
    keep = (rows.block_index[cand] >= 0) & rows.is_arc[cand]
    if fitted:
        keep &= ~np.isin(cand, np.fromiter(fitted, np.intp, len(fitted)))
    ci = cand[keep].astype(np.intp)
    corner_p, q_in, q_out = corner_points(rows, contour, table, ci)
    return si, ej, ci, corner_p, table.r[ci], q_in, q_out


def _line_line(T, ti, E, ej):
    """Largest distance alongside, line tool segments vs line elements:
    ``(dmax, point, alongside)``."""
    a0, a1 = take_rows(T.p0, ti), take_rows(T.p1, ti)
    p0, p1 = take_rows(E.p0, ej), take_rows(E.p1, ej)
    d = p1 - p0
    L = np.hypot(d[:, 0], d[:, 1])
    t = d / L[:, None]
    s0 = np.einsum("ij,ij->i", a0 - p0, t)
    s1 = np.einsum("ij,ij->i", a1 - p0, t)
    ds = s1 - s0
    flat = ds == 0.0
    den = np.where(flat, 1.0, ds)
    # fractions along T where s = 0 and s = L
    ua = np.where(flat, -np.inf, (0.0 - s0) / den)
    ub = np.where(flat, np.inf, (L - s0) / den)
    lo = np.maximum(np.minimum(ua, ub), 0.0)
    hi = np.minimum(np.maximum(ua, ub), 1.0)
    inband_flat = (s0 >= 0.0) & (s0 <= L)
    lo = np.where(flat, 0.0, lo)
    hi = np.where(flat, 1.0, hi)
    along = np.where(flat, inband_flat, lo <= hi)
    h0 = t[:, 0] * (a0[:, 1] - p0[:, 1]) - t[:, 1] * (a0[:, 0] - p0[:, 0])
    h1 = t[:, 0] * (a1[:, 1] - p0[:, 1]) - t[:, 1] * (a1[:, 0] - p0[:, 0])
    hlo = np.abs(h0 + lo * (h1 - h0))
    hhi = np.abs(h0 + hi * (h1 - h0))
    first = hlo >= hhi
    dmax = np.where(first, hlo, hhi)
    u = np.where(first, lo, hi)
    q = a0 + u[:, None] * (a1 - a0)
    # alongside over a length, not at a single point (a segment that only
    # touches the band's edge does not run along the element)
    along &= (hi - lo) * np.hypot(*(a1 - a0).T) > ALONGSIDE_MIN_LENGTH
    return dmax, q, along


#: Two centres within this times ``max(1, radii)`` are the same centre (an arc
#: tool segment and its element both computed about the programmed centre
#: agree to rounding).
CONCENTRIC_REL = 1e-12


def sweep_overlap(th1, sw1, th2, sw2) -> np.ndarray:
    """Angle (radians) common to the arcs' sweeps ``(th1, sw1)`` and ``(th2, sw2)``
    about one centre, whichever way each turns (vectorised)."""
    a1 = np.where(sw1 >= 0.0, th1, th1 + sw1)
    a2 = np.where(sw2 >= 0.0, th2, th2 + sw2)
    L1 = np.minimum(np.abs(sw1), TWO_PI)
    L2 = np.minimum(np.abs(sw2), TWO_PI)
    d = np.mod(a2 - a1, TWO_PI)
    # interval [0, L1] against [d, d + L2] and its copy one turn back
    first = np.maximum(0.0, np.minimum(L1, d + L2) - d)
    second = np.maximum(0.0, np.minimum(L1, d + L2 - TWO_PI))
    return np.minimum(first + second, L1)


def _arc_arc_concentric(T, ti, E, ej):
    cT, cE = T.center[ti], E.center[ej]
    scale = np.maximum(1.0, np.maximum(T.radius[ti], E.radius[ej]))
    conc = np.hypot(*(cT - cE).T) <= CONCENTRIC_REL * scale
    # angular overlap (same centre, so polar angles compare directly): the middle
    # or an end of one arc inside the other's sweep; the middles make it robust
    # to the rounding of arcs that share their end angles
    thT, swT, thE, swE = T.theta0[ti], T.sweep[ti], E.theta0[ej], E.sweep[ej]
    midT = thT + 0.5 * swT
    # alongside: the arcs overlap over an angle, turning the same way (an arc
    # swept the other way round its centre meets the element's sector at most
    # at its ends)
    along = (sweep_overlap(thT, swT, thE, swE) * T.radius[ti] > ALONGSIDE_MIN_LENGTH) \
        & (np.sign(swT) == np.sign(swE))
    dmax = np.abs(T.radius[ti] - E.radius[ej])
    q = cT + T.radius[ti][:, None] * np.c_[np.cos(midT), np.sin(midT)]
    return dmax, q, conc, along


def check_contact(rows, toolpath, contour: Contour, eps: float, lengths, info, table):
    """``(Check, [Violation])``; ``rows`` are the tool segments
    (:class:`~ccopt.verify.rows.SegmentRows`) of ``toolpath``; ``info(i)`` gives
    ``(block line, role)`` of tool segment ``i``; ``table`` is the run's
    :class:`~ccopt.verify.run.SegmentTable`."""
    tool = rows.tool
    si, ej, ci, cp, cr, c_in, c_out = contact_pairs(rows, toolpath.meta, contour, lengths, table)
    n = si.size
    dmax, wq, exact = farthest_alongside(tool, contour, si, ej, eps)
    gap = dmax - contour.radius[ej]
    # corner arcs
    cgap = np.full(ci.size, -np.inf)
    cq = np.zeros((ci.size, 2))
    if ci.size:
        dd, cq[:] = max_distance_to_point(tool.arr, ci, cp)
        cgap[:] = dd - cr
    viol = []
    for q in np.flatnonzero(gap > eps):
        i, j = int(si[q]), int(ej[q])
        line, role = info(i)
        viol.append(Violation("contact", float(gap[q]), i, line, role, j, contour.element_line(j),
                              (float(wq[q, 0]), float(wq[q, 1])), None,
                              EXACT if exact[q] else CERTIFIED, _contact_detail(dmax[q], contour, j)))
    for q in np.flatnonzero(cgap > eps):
        viol.append(_corner_violation(contour, info, int(ci[q]), float(cgap[q]), cq[q], cp[q],
                                      float(cr[q]), int(c_in[q]), int(c_out[q])))
    unreached = _unreached_elements(contour, table)
    for j in unreached:
        viol.append(Violation("contact", math.inf, None, None, None, int(j),
                              contour.element_line(j), None, None, EXACT,
                              {"reason": "no compensated tool segment runs along this element"}))
    allgap = np.r_[gap, cgap, np.full(unreached.size, math.inf)]
    if allgap.size:
        k = int(np.argmax(allgap))
        basis = EXACT if (k >= n or exact[k]) else CERTIFIED
        figure = float(allgap[k])
    else:
        figure, basis = None, EXACT
    check = Check("contact", not viol, figure, eps, basis, "length",
                  "every steady tool segment runs alongside its element (over a length, "
                  "turning its way) and there within r + eps of it; every corner arc within "
                  "r + eps of its corner point (figure: largest excess over r)",
                  int(n + ci.size), len(viol))
    return check, viol


def farthest_alongside(tool: Packed, contour: Contour, si: np.ndarray, ej: np.ndarray,
                       eps: float):
    """``(dmax, witness, exact)``: for each steady tool segment ``si`` the largest
    distance to its element ``ej`` from its points alongside the element (program
    units), the tool point where it is reached, and whether it is exact (else a
    certified upper bound within a fraction of ``eps``)."""
    T, E = tool.arr, contour.elements.arr
    n = si.size
    dmax = np.full(n, np.nan)
    wq = np.zeros((n, 2))
    exact = tool.exact[si] & contour.elements.exact[ej]
    todo = np.zeros(n, bool)
    kt, ke = T.kind[si], E.kind[ej]
    ll = exact & (kt == KIND_LINE) & (ke == KIND_LINE)
    if ll.any():
        q = np.flatnonzero(ll)
        dm, pts, along = _line_line(T, si[q], E, ej[q])
        dmax[q], wq[q] = dm, pts
        todo[q[~along]] = True
    aa = exact & (kt == KIND_ARC) & (ke == KIND_ARC)
    if aa.any():
        q = np.flatnonzero(aa)
        dm, pts, conc, along = _arc_arc_concentric(T, si[q], E, ej[q])
        ok = conc & along
        dmax[q[ok]], wq[q[ok]] = dm[ok], pts[ok]
        # about the element's centre but turning the other way: not alongside
        wrong_way = conc & (np.sign(T.sweep[si[q]]) != np.sign(E.sweep[ej[q]]))
        dmax[q[wrong_way]], wq[q[wrong_way]] = math.inf, T.p0[si[q[wrong_way]]]
        todo[q[~(ok | wrong_way)]] = True
    todo |= exact & ~(ll | aa)
    q = np.flatnonzero(todo)
    dmax[q], wq[q] = farthest_clipped(tool, contour.elements, si[q], ej[q])
    tol = VERIFY_CERTIFIED_GAP * eps
    for q in np.flatnonzero(~exact):
        b = max_distance_bound(tool.geom(si[q]), contour.elements.geom(ej[q]), tol)
        dmax[q] = b.ub
        wq[q] = b.wa if b.wa is not None else T.p0[si[q]]
    return dmax, wq, exact


def _contact_detail(dmax: float, contour: Contour, j: int) -> dict:
    if math.isinf(dmax):
        return {"reason": "the tool segment never runs alongside its element (no part of it "
                          "lies alongside the element's interior)",
                "radius": float(contour.radius[j])}
    return {"max_distance": float(dmax), "radius": float(contour.radius[j])}


def _corner_violation(contour: Contour, info, i: int, gap: float, q, P, r: float,
                      q_in: int, q_out: int) -> Violation:
    """The contact violation of corner arc ``i`` (farthest point ``q`` from its
    corner point ``P``, ``gap`` beyond ``r``) between moves ``q_in`` and ``q_out``."""
    line, role = info(i)
    # the corner belongs to both moves meeting there; it is reported at the
    # one ending there (the carrier's line is the tool block)
    between = [contour.moves[k].source.line if k >= 0 else None for k in (q_in, q_out)]
    at = between[0] if between[0] is not None else line
    return Violation("contact", gap, i, line, role, None, at,
                     (float(q[0]), float(q[1])), (float(P[0]), float(P[1])),
                     EXACT, {"corner_point": [float(P[0]), float(P[1])],
                             "corner_between_blocks": between, "radius": r})


def _runs_along(table) -> np.ndarray:
    """Tool segments that run along their element: compensated ones, and the
    moves of a pass compensated with radius 0 (``G41.1 D0``, ``G41 D0``),
    which LinuxCNC and ccopt run as the programmed moves themselves."""
    return table.is_role(Role.COMPENSATED) | (table.is_role(Role.UNCOMPENSATED) & (table.r <= 0.0))


def _unreached_elements(contour: Contour, table) -> np.ndarray:
    """Steady elements with no compensated tool segment at all: a path that never
    runs along an element (e.g. the programmed path itself, or a path made for
    another program) does not reach it."""
    has = np.zeros(len(contour), bool)
    own = _runs_along(table) & (table.element >= 0)
    has[table.element[own]] = True
    return np.flatnonzero(contour.steady & ~has)
