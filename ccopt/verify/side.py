"""Side: the tool is on the programmed side of its element, not just at ``r``.

For the tool segment of every steady contour element with ``r > eps``, the
segment's middle point ``q`` is projected on its element (nearest point ``w``,
exact kernels; a certified nearest point for spirals and curves) and the
signed offset ``k * cross(t(w), q - w)`` must be positive (``k = +1`` left,
``-1`` right; ``t(w)`` the element's unit tangent at ``w``). Within the
element's band it equals the signed distance, so the figure (the smallest
signed offset) is ``r`` on a correct path and ``-r`` on one mirrored onto the
wrong side. A tool segment that does not cross its element (the no-gouge
check makes sure) stays on one side, so its middle point decides for all of it.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Line
from ccopt.geometry.columns import put_rows, take_rows
from ccopt.geometry.distance import point_arc, point_segment
from ccopt.tolerances import POINT_EPS, VERIFY_CERTIFIED_GAP
from ccopt.toolpath import Role
from ccopt.verify.certificate import CERTIFIED, EXACT, Check, Violation
from ccopt.verify.distance import batchable, min_distance, min_distances
from ccopt.verify.contour import Contour
from ccopt.verify.segments import KIND_ARC, KIND_LINE, Packed


def _midpoints(tool: Packed, idx):
    A = tool.arr
    out = np.empty((idx.size, 2))
    k = A.kind[idx]
    # rows by index (take_rows, put_rows): boolean masks are slow on (n, 2) arrays
    ln = np.flatnonzero(k == KIND_LINE)
    put_rows(out, ln, 0.5 * (take_rows(A.p0, idx[ln]) + take_rows(A.p1, idx[ln])))
    ar = np.flatnonzero(k == KIND_ARC)
    if ar.size:
        a = idx[ar]
        ang = A.theta0[a] + 0.5 * A.sweep[a]
        put_rows(out, ar, take_rows(A.center, a)
                 + A.radius[a][:, None] * np.c_[np.cos(ang), np.sin(ang)])
    for q in np.flatnonzero((k != KIND_LINE) & (k != KIND_ARC)):
        g = tool.geom(idx[q])
        out[q] = g.point(0.5 * g.length)
    return out


def _tangent_at(E, j, w):
    """Unit tangent of elements ``j`` at their points ``w``."""
    A = E.arr
    t = np.zeros((j.size, 2))
    k = A.kind[j]
    ln = np.flatnonzero(k == KIND_LINE)
    d = take_rows(A.p1, j[ln]) - take_rows(A.p0, j[ln])
    put_rows(t, ln, d / np.hypot(d[:, 0], d[:, 1])[:, None])
    cur = np.flatnonzero(k != KIND_LINE)
    if cur.size:
        jj = j[cur]
        c = take_rows(A.center, jj)
        v = take_rows(w, cur) - c
        a = np.arctan2(v[:, 1], v[:, 0])
        rho = np.hypot(v[:, 0], v[:, 1])
        sg = np.copysign(1.0, A.sweep[jj])
        # spiral: rho' = b per radian of sweep; b = 0 for arcs
        b = np.where(A.kind[jj] == KIND_ARC, 0.0,
                     (A.radius_end[jj] - A.radius[jj]) / np.where(A.sweep[jj] != 0, np.abs(A.sweep[jj]), 1.0))
        tv = np.c_[b * np.cos(a) - sg * rho * np.sin(a), b * np.sin(a) + sg * rho * np.cos(a)]
        put_rows(t, cur, tv / np.hypot(tv[:, 0], tv[:, 1])[:, None])
    return t


def check_side(tool: Packed, contour: Contour, eps: float, lengths, info, table):
    sel = (table.is_role(Role.COMPENSATED) & table.steady & (table.element >= 0)
           & (lengths > POINT_EPS) & (table.r > eps))
    si = np.flatnonzero(sel)
    ej = table.element[si]
    E = contour.elements
    q = _midpoints(tool, si)
    w = np.zeros_like(q)
    k = E.arr.kind[ej]
    ln = np.flatnonzero(k == KIND_LINE)
    if ln.size:
        a = ej[ln]
        put_rows(w, ln, point_segment(take_rows(q, ln), take_rows(E.arr.p0, a),
                                      take_rows(E.arr.p1, a))[2])
    ar = np.flatnonzero(k == KIND_ARC)
    if ar.size:
        a = ej[ar]
        put_rows(w, ar, point_arc(take_rows(q, ar), take_rows(E.arr.center, a), E.arr.radius[a],
                                  E.arr.theta0[a], E.arr.sweep[a])[2])
    exact = (k == KIND_LINE) | (k == KIND_ARC)
    tol = VERIFY_CERTIFIED_GAP * eps
    # the nearest point of each curved element: spirals and arcs all at once
    items = [(m, E.geom(ej[m]), Line(tuple(q[m]), tuple(q[m]))) for m in np.flatnonzero(~exact)]
    batch = [it for it in items if batchable(it[1], it[2])]
    found = min_distances([(g, p) for _, g, p in batch], tol, [math.inf] * len(batch))
    for (m, _, _), b in zip(batch, found):
        w[m] = b.wa
    for m, g, p in items:
        if not batchable(g, p):
            w[m] = min_distance(g, p, tol).wa
    t = _tangent_at(E, ej, w)
    v = q - w
    signed = contour.side[ej] * (t[:, 0] * v[:, 1] - t[:, 1] * v[:, 0])
    viol = []
    for m in np.flatnonzero(~(signed > 0.0)):
        i, j = int(si[m]), int(ej[m])
        line, role = info(i)
        viol.append(Violation("side", float(-signed[m]), i, line, role, j, contour.element_line(j),
                              (float(q[m, 0]), float(q[m, 1])), (float(w[m, 0]), float(w[m, 1])),
                              EXACT if exact[m] else CERTIFIED,
                              {"programmed_side": "left" if contour.side[j] > 0 else "right",
                               "signed_offset": float(signed[m])}))
    if si.size:
        m = int(np.argmin(signed))
        figure, basis = float(signed[m]), EXACT if exact[m] else CERTIFIED
    else:
        figure, basis = None, EXACT
    return Check("side", not viol, figure, 0.0, basis, "length",
                 "every steady tool segment on the programmed side of its element "
                 "(figure: smallest signed offset, > 0 required)", int(si.size), len(viol)), viol
