"""The curves of many pairs as per-pair arrays, for :mod:`.certified_batch`.

Each pair ``m`` names its curve by an index ``idx[m]`` into a list of objects
(one object is in as many pairs as curves near it): the numbers of each object
are read once and spread to its pairs. :class:`SpiralRows` holds spirals and
arcs by swept angle (:class:`~ccopt.verify.distance.certified.SpiralParam`'s
numbers), :class:`BezierRows` Bezier curves by their own parameter
(:class:`~ccopt.verify.distance.certified.BezierParam`), :class:`ExactRows`
lines and arcs with their closed-form distance kernels. Lengths in program
units, angles in radians (a positive sweep counter-clockwise).
"""
from __future__ import annotations

from itertools import chain
from operator import attrgetter

import numpy as np

from ccopt.geometry import Arc, Line
from ccopt.geometry.columns import put_rows, take_rows, used_rows
from ccopt.geometry.bezier_arclength import bernstein_basis, bezier_points
from ccopt.geometry.distance import (
    arc_arc, point_arc, point_segment, segment_arc, segment_segment,
)
from ccopt.verify.distance.certified import BezierParam

_P0, _P1, _CENTER = attrgetter("p0"), attrgetter("p1"), attrgetter("center")
_RADIUS, _THETA0, _SWEEP = attrgetter("radius"), attrgetter("theta0"), attrgetter("sweep")


def distinct(geoms):
    """``(objects, inverse)``: each object of ``geoms`` once (by identity, in
    order of first appearance) and, per entry, its index among them; a curve
    is in as many pairs as elements near it, and its parameters are made once.
    The identities are sorted as integers (no Python loop over the entries)."""
    n = len(geoms)
    if n == 0:
        return [], np.zeros(0, np.intp)
    ids = np.fromiter(map(id, geoms), np.int64, n)
    _, first, inv = np.unique(ids, return_index=True, return_inverse=True)
    order = np.argsort(first)                 # by first appearance
    rank = np.empty(order.size, np.intp)
    rank[order] = np.arange(order.size)
    return [geoms[i] for i in first[order].tolist()], rank[inv.reshape(-1)]


def used_objects(objs, idx):
    """``(objects, inverse)``: the objects ``objs[i]`` of the indices ``idx``
    (each once) and, per index, its place among them (all of ``objs`` in order
    when ``idx`` is ``None``)."""
    if idx is None:
        return list(objs), np.arange(len(objs))
    used, inv = used_rows(idx, len(objs))
    return [objs[i] for i in used.tolist()], inv.reshape(-1)


class SpiralRows:
    """The :class:`SpiralParam` of many curves as arrays, evaluated per piece's
    pair: curve ``objs[idx[m]]`` for pair ``m`` (``idx`` ``None``: ``objs[m]``)."""

    concentric = True            # the polar radius bounds about a common centre apply

    def __init__(self, objs, idx=None):
        gs, inv = used_objects(objs, idx)
        m = len(gs)
        # SpiralParam's numbers, read off the objects column by column
        arc = [isinstance(g, Arc) for g in gs]
        c = _points(gs, _CENTER)
        rho0 = np.array([g.radius if a else g.rho0 for g, a in zip(gs, arc)], float).reshape(m)
        b = np.array([0.0 if a else g.b for g, a in zip(gs, arc)], float).reshape(m)
        sweep = np.fromiter(map(_SWEEP, gs), float, m)
        self.c, self.rho0, self.b = c[inv], rho0[inv], b[inv]
        self.th0 = np.fromiter(map(_THETA0, gs), float, m)[inv]
        self.sg = np.copysign(1.0, sweep)[inv]
        self.U = np.abs(sweep)[inv]
        #: each pair's curve among the distinct ones (the pairs of one curve
        #: have the same numbers)
        self.obj = inv

    def eval(self, k, u):
        rho = self.rho0[k] + self.b[k] * u
        ang = self.th0[k] + self.sg[k] * u
        out = np.empty((u.size, 2))
        np.multiply(rho, np.cos(ang), out=out[:, 0])
        np.multiply(rho, np.sin(ang), out=out[:, 1])
        out += take_rows(self.c, k)
        return out

    def delta(self, k, u0, u1):
        rho = np.maximum(self.rho0[k] + self.b[k] * u0, self.rho0[k] + self.b[k] * u1)
        d2 = np.sqrt(rho * rho + 4.0 * self.b[k] * self.b[k])
        h = u1 - u0
        return d2 * h * h / 8.0

    def radius_range(self, k, u0, u1):
        r0 = self.rho0[k] + self.b[k] * u0
        r1 = self.rho0[k] + self.b[k] * u1
        return np.minimum(r0, r1), np.maximum(r0, r1)


class BezierRows:
    """The :class:`BezierParam` of many Bezier curves of one degree as arrays,
    evaluated per piece's pair with the same operations as one curve's
    (:func:`~ccopt.verify.distance.certified.bezier_points`, so the same numbers)."""

    concentric = False

    def __init__(self, objs, idx=None):
        gs, inv = used_objects(objs, idx)
        params = [BezierParam(g) for g in gs]
        self.P = np.array([p.P for p in params], float)[inv]        # (m, n + 1, 2)
        self.K = np.array([p.K for p in params], float)[inv]
        self.U = np.ones(inv.size)
        self.n = self.P.shape[1] - 1

    def eval(self, k, u):
        return bezier_points(bernstein_basis(u, self.n), self.P[k])

    def delta(self, k, u0, u1):
        h = u1 - u0
        return self.K[k] * h * h / 8.0


class ExactRows:
    """Lines and arcs ``b`` as arrays (a line's arc fields unused and vice
    versa): element ``objs[idx[m]]`` for pair ``m`` (``idx`` ``None``: ``objs[m]``)."""

    def __init__(self, objs, idx=None):
        gs, inv = used_objects(objs, idx)
        n = len(gs)
        line = np.array([isinstance(g, Line) for g in gs], bool).reshape(n)
        p0 = np.zeros((n, 2))
        p1 = np.zeros((n, 2))
        c = np.zeros((n, 2))
        R = np.ones(n)
        th0 = np.zeros(n)
        sw = np.zeros(n)
        li, ai = np.flatnonzero(line), np.flatnonzero(~line)
        lines, arcs = [gs[i] for i in li.tolist()], [gs[i] for i in ai.tolist()]
        p0[li], p1[li] = _points(lines, _P0), _points(lines, _P1)
        c[ai] = _points(arcs, _CENTER)
        for col, get in ((R, _RADIUS), (th0, _THETA0), (sw, _SWEEP)):
            col[ai] = np.fromiter(map(get, arcs), float, ai.size)
        self.line, self.p0, self.p1 = line[inv], p0[inv], p1[inv]
        self.c, self.R, self.th0, self.sw = c[inv], R[inv], th0[inv], sw[inv]

    def _each_kind(self, k, on_lines, on_arcs, widths):
        """``on_lines(sel, kk)`` on the rows ``sel`` of ``k`` whose element is a
        line (``kk = k[sel]``), ``on_arcs`` on the arcs; the columns they return
        gathered into arrays of ``k``'s length (``widths``: 0 for one value a
        row, 2 for a point). ``sel`` is ``None`` when all rows are of one kind
        (the kernel's columns are then the result, nothing gathered)."""
        ln = self.line[k]
        lines = np.flatnonzero(ln)
        if lines.size in (0, k.size):
            return list((on_lines if lines.size else on_arcs)(None, k))
        out = [np.empty(k.size) if w == 0 else np.empty((k.size, w)) for w in widths]
        for sel, kernel in ((lines, on_lines), (np.flatnonzero(~ln), on_arcs)):
            if sel.size:
                for col, got in zip(out, kernel(sel, k[sel])):
                    put_rows(col, sel, got)
        return out

    def _line(self, kk):
        """``(p0, p1)`` of elements ``kk``."""
        return take_rows(self.p0, kk), take_rows(self.p1, kk)

    def _arc(self, kk):
        """``(c, R, th0, sw)`` of elements ``kk``."""
        return take_rows(self.c, kk), self.R[kk], self.th0[kk], self.sw[kk]

    def chords_to(self, k, c0, c1):
        """``(distance, witness on the chord, witness on the element)`` of chords
        ``c0 -> c1`` to elements ``k``."""
        d, wa, wb = self._each_kind(
            k, lambda sel, kk: segment_segment(_at(c0, sel), _at(c1, sel), *self._line(kk)),
            lambda sel, kk: segment_arc(_at(c0, sel), _at(c1, sel), *self._arc(kk)), (0, 2, 2))
        return d, wa, wb

    def arcs_to(self, k, c, R, th0, sw):
        """Distances from arcs ``(c, R, th0, sw)`` (row-wise) to elements ``k``."""
        def arcs(sel):
            return [_at(a, sel) for a in (c, R, th0, sw)]
        d, = self._each_kind(
            k, lambda sel, kk: segment_arc(*self._line(kk), *arcs(sel))[:1],
            lambda sel, kk: arc_arc(*arcs(sel), *self._arc(kk))[:1], (0,))
        return d

    def points_to(self, k, q):
        """``(distance, nearest point on the element)`` of points ``q`` to elements ``k``."""
        d, wb = self._each_kind(
            k, lambda sel, kk: _dist_and_witness(point_segment(_at(q, sel), *self._line(kk))),
            lambda sel, kk: _dist_and_witness(point_arc(_at(q, sel), *self._arc(kk))), (0, 2))
        return d, wb


def _at(a: np.ndarray, sel) -> np.ndarray:
    """Rows ``sel`` of ``a`` (all of it for ``None``)."""
    return a if sel is None else take_rows(a, sel)


def _points(gs, get) -> np.ndarray:
    """``(len(gs), 2)``: the point ``get`` reads off each object."""
    return np.fromiter(chain.from_iterable(map(get, gs)), float, 2 * len(gs)).reshape(-1, 2)


def _dist_and_witness(r):
    """A point kernel's distance and its witness on the element (its 1st and 3rd results)."""
    return r[0], r[2]


def asked_once(objs, idx, what) -> tuple[list, np.ndarray]:
    """``(answers, inverse)``: ``what`` of each object of the indices ``idx``,
    asked once per object, and per index the place of its object's answer."""
    gs, inv = used_objects(objs, idx)
    return list(map(what, gs)), inv
