"""Clearance from the contour, element by element, for the blend models.

For a point ``p`` and a contour element with required clearance ``r``, the
distance to the element is exactly one of (by where the foot of ``p`` lies):

- ``LINE``: a line element with the foot inside it: ``n . (p - A) >= r``
  (``n`` the unit normal towards ``p``; linear);
- ``CONCAVE``: an arc element, foot inside its sweep, ``p`` inside its circle:
  ``|p - c| <= R - r`` (a second-order cone);
- ``CONVEX``: the same, ``p`` outside the circle: ``|p - c| >= R + r``;
- ``END``: the foot beyond an end ``E``: ``|p - E| >= r``;
- ``EXEMPT``: the foot beyond an *open* end, where the contour stops (the
  verifier's decision ``OPEN_END_EXEMPTION``, :mod:`ccopt.verify.decisions`:
  such points are not checked against that element). :func:`classify` gives,
  beyond an open end ``E``, the half-plane ``u . p >= u . E`` (``u`` the
  element's direction out of that end: beyond a line's end exactly the exempt
  region; beyond an arc's, the half-plane past the end's radius, which holds
  every exempt point nearer that end), which the CasADi model imposes there
  together with ``|p - E| >= r``; the convex rows leave exempt points free.

:func:`classify` says which, at a given set of points (the models re-classify
at every iterate; on the boundary between two cases both give the same
distance, so switching is continuous). :func:`linear_rows` turns them into
rows ``G . p >= h`` for convex models: ``LINE`` is exact, ``CONVEX`` and
``END`` become the tangent half-plane at the iterate (it lies inside the
feasible set, so it is safe), ``CONCAVE`` is kept as a cone, ``EXEMPT`` is
void.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.spatial import cKDTree

from ccopt.geometry import Arc, Line, angle_in_sweep, distance, point_arc, point_segment
from ccopt.geometry.bezier import DIVISION_FLOOR

LINE, CONCAVE, CONVEX, END, EXEMPT = 0, 1, 2, 3, 4


@dataclass(frozen=True)
class Element:
    """A contour element: ``kind`` (``"line" | "arc" | "other"``), clearance, primitive,
    and whether the contour stops at its start or end (open ends)."""

    kind: str
    clearance: float
    geom: object
    open_start: bool = False
    open_end: bool = False

    @cached_property
    def fine(self) -> np.ndarray:
        """The fine polyline (``(DENSE_SAMPLES, 2)``) an element of another kind is
        measured by, made once per element (a model measures an element at every
        iterate and every sample size)."""
        return _dense(self, DENSE_SAMPLES)

    @cached_property
    def fine_tree(self) -> cKDTree:
        """A k-d tree of :attr:`fine`'s vertices."""
        return cKDTree(self.fine)


def contour_elements(contour) -> list[Element]:
    out = []
    for j in range(len(contour)):
        g = contour.elements.geom(j)
        kind = "line" if isinstance(g, Line) else "arc" if isinstance(g, Arc) else "other"
        out.append(Element(kind, float(contour.clearance[j]), g,
                           bool(contour.open_start[j]), bool(contour.open_end[j])))
    return out


def point_distance(el: Element, p) -> float:
    g = el.geom
    if el.kind in ("line", "arc"):
        return distance(tuple(map(float, p)), g)[0]
    s = np.linspace(0.0, g.length, 257)
    return float(np.min(np.hypot(*(np.asarray(g.point(s)) - np.asarray(p, float)).T)))


def near(elements: list[Element], polyline: np.ndarray, reach: float,
         limit: int | None = None) -> list[Element]:
    """Elements within ``clearance + reach`` of a polyline (nearest first)."""
    found = []
    P = np.asarray(polyline, float)
    for el in elements:
        pts = _dense(el, 65)
        if len(P) == 1:
            d = float(np.min(np.hypot(*(pts - P[0]).T)))
        else:
            d = min(float(np.min(point_segment(pts, a, b)[0])) for a, b in zip(P[:-1], P[1:]))
        d = min(d, min(point_distance(el, q) for q in P))
        if d <= el.clearance + reach:
            found.append((d - el.clearance, el))
    found.sort(key=lambda e: e[0])
    out = [el for _, el in found]
    return out[:limit] if limit else out


def _dense(el: Element, n: int) -> np.ndarray:
    g = el.geom
    return np.asarray(g.point(np.linspace(0.0, g.length, n))).reshape(-1, 2)


def element_distance(el: Element, pts: np.ndarray) -> np.ndarray:
    """Exact distance from points to an element (other kinds: a fine polyline)."""
    g = el.geom
    if el.kind == "line":
        return point_segment(pts, g.p0, g.p1)[0]
    if el.kind == "arc":
        return point_arc(pts, g.center, g.radius, g.theta0, g.sweep)[0]
    return polyline_distance(el.fine, pts, el.fine_tree)


#: Samples of an element of another kind (a spiral, a Bezier curve) for the
#: fine polyline the models measure it by.
DENSE_SAMPLES = 2049
#: :func:`polyline_distance` measures a point against pieces a block at a time,
#: and only against blocks whose bounding box may hold its nearest point.
PIECE_BLOCK = 64


def polyline_distance(q: np.ndarray, pts: np.ndarray, tree: cKDTree | None = None) -> np.ndarray:
    """Distance from each point of ``pts`` (``(N, 2)``) to the polyline ``q``
    (``(M, 2)``, M >= 2), exact for the polyline; ``tree``: a k-d tree of ``q``'s
    vertices, if the caller keeps one.

    The pieces go in blocks of :data:`PIECE_BLOCK`; a point is measured against a
    block only when the block's bounding box comes no farther from it than the
    point's nearest vertex (an upper bound of its distance), so a point far from
    most of a long curve meets only the blocks around its nearest piece."""
    pts = np.asarray(pts, float).reshape(-1, 2)
    q = np.asarray(q, float).reshape(-1, 2)
    upper = (cKDTree(q) if tree is None else tree).query(pts)[0]
    out = upper.copy()
    for k in range(0, len(q) - 1, PIECE_BLOCK):
        a = q[k:k + PIECE_BLOCK + 1]
        lo, hi = a.min(axis=0), a.max(axis=0)
        gap = np.maximum(np.maximum(lo - pts, pts - hi), 0.0)
        idx = np.flatnonzero(np.hypot(gap[:, 0], gap[:, 1]) < out)
        if len(idx) == 0:
            continue
        d = np.diff(a, axis=0)
        dd = np.einsum("ij,ij->i", d, d)
        dd = np.where(dd > 0.0, dd, 1.0)      # a zero-length piece is its start point
        w = pts[idx, None, :] - a[None, :-1, :]
        t = np.clip(np.einsum("nmj,mj->nm", w, d) / dd, 0.0, 1.0)
        w -= t[..., None] * d[None, :, :]
        out[idx] = np.minimum(out[idx], np.sqrt(np.min(np.einsum("nmj,nmj->nm", w, w), axis=1)))
    return out


def checked_distance(el: Element, pts: np.ndarray) -> np.ndarray:
    """:func:`element_distance`, with ``inf`` where a point is exempt (beyond an open end)."""
    d = element_distance(el, pts)
    if el.open_start or el.open_end:
        d = np.where(classify(el, pts)[0] == EXEMPT, np.inf, d)
    return d


def classify(el: Element, p: np.ndarray):
    """``(kind, vec, scal)`` per point (see the module docstring): for ``LINE`` the
    unit normal and ``n . A + r``; for ``CONCAVE``/``CONVEX`` the centre and
    ``R -/+ r``; for ``END`` the end point and ``r``; for ``EXEMPT`` beyond an
    open end ``u`` and ``u . E`` (``u`` the direction out of that end)."""
    p = np.asarray(p, float)
    n = len(p)
    kind = np.full(n, END)
    vec = np.zeros((n, 2))
    scal = np.full(n, el.clearance)
    r = el.clearance
    g = el.geom
    if el.kind == "line":
        A, B = np.asarray(g.p0, float), np.asarray(g.p1, float)
        d = B - A
        L2 = float(d @ d)
        if L2 == 0.0:
            vec[:] = A
            return kind, vec, scal
        t = ((p - A) @ d) / L2
        nl = np.array([-d[1], d[0]]) / math.sqrt(L2)
        sgn = np.where((p - A) @ nl >= 0.0, 1.0, -1.0)
        inside = (t > 0.0) & (t < 1.0)
        kind[inside] = LINE
        vec[inside] = sgn[inside, None] * nl
        scal[inside] = vec[inside] @ A + r
        vec[~inside] = np.where((t[~inside] <= 0.0)[:, None], A, B)
        u = d / math.sqrt(L2)
        if el.open_start:
            m = t <= 0.0
            kind[m], vec[m], scal[m] = EXEMPT, -u, float(-u @ A)
        if el.open_end:
            m = t >= 1.0
            kind[m], vec[m], scal[m] = EXEMPT, u, float(u @ B)
        return kind, vec, scal
    if el.kind == "arc":
        c = np.asarray(g.center, float)
        v = p - c
        rho = np.hypot(v[:, 0], v[:, 1])
        inside = angle_in_sweep(np.arctan2(v[:, 1], v[:, 0]), g.theta0, g.sweep) & (rho > 0)
        conc = inside & (rho < g.radius)
        conv = inside & ~conc
        kind[conc], kind[conv] = CONCAVE, CONVEX
        vec[inside] = c
        scal[conc] = g.radius - r
        scal[conv] = g.radius + r
        e0, e1 = np.asarray(g.start, float), np.asarray(g.end, float)
        near0 = np.hypot(*(p - e0).T) <= np.hypot(*(p - e1).T)
        vec[~inside] = np.where(near0[~inside, None], e0, e1)
        # beyond an open end: the half-plane past the end's radius, u . p >= u . E with
        # u the arc's direction out of that end (every point beyond that end, nearer
        # it than the other end, lies there: it spans 180 degrees from the end's ray)
        u0, u1 = out_directions(el)
        for is_open, m, E, u in ((el.open_start, ~inside & near0, e0, u0),
                                 (el.open_end, ~inside & ~near0, e1, u1)):
            if is_open:
                kind[m], vec[m], scal[m] = EXEMPT, u, float(u @ E)
        return kind, vec, scal
    vec[:] = el.fine[el.fine_tree.query(p)[1]]     # the nearest sample of the fine polyline
    return kind, vec, scal


def out_directions(el: Element):
    """Unit directions ``(u0, u1)`` of a line or arc element out of its start and out
    of its end (the ``vec`` :func:`classify` gives beyond an open end)."""
    g = el.geom
    if el.kind == "line":
        d = np.subtract(g.p1, g.p0) / max(float(g.length), DIVISION_FLOOR)
        return -d, d
    s = math.copysign(1.0, g.sweep)
    t0, t1 = g.theta0, g.theta0 + g.sweep
    return (-s * np.array([-math.sin(t0), math.cos(t0)]),
            s * np.array([-math.sin(t1), math.cos(t1)]))


def exempt_ends(el: Element, vec: np.ndarray) -> np.ndarray:
    """The open end (``(n, 2)``) each exempt point of :func:`classify` lies beyond,
    from its direction ``vec`` out of that end."""
    u0, u1 = out_directions(el)
    at_start = np.hypot(*(vec - u0).T) <= np.hypot(*(vec - u1).T)
    return np.where(at_start[:, None], np.asarray(el.geom.start, float),
                    np.asarray(el.geom.end, float))


def row_margin(el: Element, p: np.ndarray, cases=None) -> np.ndarray:
    """How far each point keeps the models' row of ``el`` (>= 0 kept; units): the
    distance less the clearance, or beyond an open end of a line or an arc the
    smaller of ``u . p - u . E`` and ``|p - E| - r``; ``inf`` beyond an open end of
    another kind (no row). ``cases``: :func:`classify` at ``p``, if known."""
    kind, vec, scal = classify(el, p) if cases is None else cases
    m = element_distance(el, p) - el.clearance
    ex = kind == EXEMPT
    if el.kind in ("line", "arc") and ex.any():
        E = exempt_ends(el, vec[ex])
        m[ex] = np.minimum(np.einsum("ij,ij->i", vec[ex], p[ex]) - scal[ex],
                           np.hypot(*(p[ex] - E).T) - el.clearance)
    else:
        m[ex] = np.inf
    return m


def linear_rows(el: Element, p: np.ndarray):
    """Rows ``G . p >= h`` at points ``p`` (``(n, 2)``, ``(n,)``) and the mask of
    points left to a concave cone (their row is void: ``G = 0, h = -inf``)."""
    kind, vec, scal = classify(el, p)
    n = len(p)
    G = np.zeros((n, 2))
    h = np.full(n, -np.inf)
    m = kind == LINE
    G[m], h[m] = vec[m], scal[m]
    for k in (CONVEX, END):
        m = kind == k
        if m.any():
            u = p[m] - vec[m]
            u /= np.maximum(np.hypot(u[:, 0], u[:, 1]), DIVISION_FLOOR)[:, None]
            G[m] = u
            h[m] = np.einsum("ij,ij->i", u, vec[m]) + scal[m]
    return G, h, kind == CONCAVE, vec, scal
