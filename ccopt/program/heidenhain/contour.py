"""Plane geometry of Klartext contour elements, approach and departure.

Points are ``(u, v)`` tuples in the plane's coordinates
(:data:`~ccopt.program.model.PLANE_AXES`); angles are radians, positive
counter-clockwise. A *piece* is ``("line", start, end)`` or
``("arc", start, end, centre, sweep)`` (``sweep`` signed, radians).

The approach and departure paths (APPR/DEP LT, LN, CT, LCT) are built for
the tool centre at compensation radius ``r`` on side ``k`` (+1 ``RL``, -1
``RR``): the reader calls them with ``r = 0`` (the program's own path, the
contour), the ``heidenhain`` compensation style with the radius in force
(docs/compensation.md, HEIDENHAIN rule 5). ``n = k * perp(t)`` is the
normal toward the tool side; the first contour point ``PA`` becomes
``PA + r*n`` on the tool centre path.
"""
from __future__ import annotations

import math

from ccopt.geometry import intersect
from ccopt.tolerances import POINT_EPS, R_CHORD_REL_TOL, TURN_EPS

Pt = tuple[float, float]


class GeometryError(ValueError):
    """A construction that has no solution (the reader locates it)."""


def add(a: Pt, b: Pt, s: float = 1.0) -> Pt:
    return (a[0] + s * b[0], a[1] + s * b[1])


def sub(a: Pt, b: Pt) -> Pt:
    return (a[0] - b[0], a[1] - b[1])


def perp(t: Pt) -> Pt:
    return (-t[1], t[0])


def dot(a: Pt, b: Pt) -> float:
    return a[0] * b[0] + a[1] * b[1]


def cross(a: Pt, b: Pt) -> float:
    return a[0] * b[1] - a[1] * b[0]


def norm(a: Pt) -> float:
    return math.hypot(a[0], a[1])


def unit(a: Pt) -> Pt:
    n = norm(a)
    if n <= POINT_EPS:
        raise GeometryError("zero-length direction")
    return (a[0] / n, a[1] / n)


def rotate_about(p: Pt, c: Pt, angle: float) -> Pt:
    d = sub(p, c)
    ca, sa = math.cos(angle), math.sin(angle)
    return (c[0] + d[0] * ca - d[1] * sa, c[1] + d[0] * sa + d[1] * ca)


def polar(cc: Pt, radius: float, angle_deg: float) -> Pt:
    a = math.radians(angle_deg)
    return (cc[0] + radius * math.cos(a), cc[1] + radius * math.sin(a))


# -- tangents of pieces -------------------------------------------------------------
def start_tangent(piece) -> Pt:
    if piece[0] == "line":
        return unit(sub(piece[2], piece[1]))
    _, s, _, c, sweep = piece
    return unit(perp(sub(s, c)) if sweep > 0 else perp(sub(c, s)))


def end_tangent(piece) -> Pt:
    if piece[0] == "line":
        return unit(sub(piece[2], piece[1]))
    _, _, e, c, sweep = piece
    return unit(perp(sub(e, c)) if sweep > 0 else perp(sub(c, e)))


def arc_sweep(s: Pt, e: Pt, c: Pt, ccw: bool, full_if_same: bool = True) -> float:
    """Signed sweep from ``s`` to ``e`` about ``c`` the way the arc turns, in
    (0, 2 pi] (a full turn when they coincide and ``full_if_same``)."""
    a0 = math.atan2(s[1] - c[1], s[0] - c[0])
    a1 = math.atan2(e[1] - c[1], e[0] - c[0])
    d = (a1 - a0) % (2 * math.pi) if ccw else (a0 - a1) % (2 * math.pi)
    if d <= POINT_EPS / max(norm(sub(s, c)), 1.0) and full_if_same:
        d = 2 * math.pi
    return d if ccw else -d


# -- centres ------------------------------------------------------------------------
def centre_from_radius(s: Pt, e: Pt, radius: float, ccw: bool) -> Pt:
    """``CR``: centre of the arc from ``s`` to ``e`` of radius ``|radius|``,
    the short one (up to 180 degrees) for ``radius > 0``, else the long one."""
    chord = norm(sub(e, s))
    if chord <= POINT_EPS:
        raise GeometryError("CR cannot make a full circle: the end point must differ from "
                            "the start (use CC and C)")
    half = chord / 2.0
    if abs(radius) < half * (1.0 - R_CHORD_REL_TOL):
        raise GeometryError(f"R{radius:+g} is too small for the chord {chord:g} "
                            f"(|R| must be at least {half:g})")
    h = math.sqrt(max(0.0, (abs(radius) - half) * (abs(radius) + half)))
    n = perp(unit(sub(e, s)))
    side = (1.0 if ccw else -1.0) * (1.0 if radius > 0 else -1.0)
    mid = ((s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0)
    return add(mid, n, side * h)


def tangent_arc(s: Pt, t: Pt, e: Pt) -> tuple[Pt, bool]:
    """``CT``: centre and turning direction of the arc from ``s`` leaving
    along ``t`` to ``e``."""
    d = sub(e, s)
    n = perp(t)
    h = dot(d, n)
    if abs(h) <= POINT_EPS * max(1.0, norm(d)):
        raise GeometryError("CT: the end point lies on the tangent of the previous element "
                            "(the arc would be a straight line)")
    rho = dot(d, d) / (2.0 * h)
    return add(s, n, rho), rho > 0


# -- rounding and chamfer ---------------------------------------------------------------
def _inside_carrier(piece, at_end: bool, side: Pt, dist: float):
    """The carrier of ``piece`` shifted by ``dist`` toward ``side`` (a unit
    normal at the corner): ``("line", point, dir)`` or ``("circle", c, rho)``."""
    p = piece[2] if at_end else piece[1]
    if piece[0] == "line":
        return ("line", add(p, side, dist), unit(sub(piece[2], piece[1])))
    c = piece[3]
    rho = norm(sub(p, c))
    toward = dot(side, sub(c, p)) > 0
    return ("circle", c, rho - dist if toward else rho + dist)


def _meet(a, b) -> list[Pt]:
    if a[0] == "line" and b[0] == "line":
        hits = intersect.line_line(a[1], add(a[1], a[2]), b[1], add(b[1], b[2]))
    elif a[0] == "line":
        hits = intersect.line_circle(a[1], add(a[1], a[2]), b[1], b[2])
    elif b[0] == "line":
        hits = intersect.line_circle(b[1], add(b[1], b[2]), a[1], a[2])
    else:
        hits = intersect.circle_circle(a[1], a[2], b[1], b[2])
    return [(float(h[0][0]), float(h[0][1])) for h in hits]


def _foot(piece, f: Pt) -> Pt:
    """The point of ``piece``'s carrier nearest ``f`` (where a circle about
    ``f`` tangent to it touches)."""
    if piece[0] == "line":
        s, t = piece[1], unit(sub(piece[2], piece[1]))
        return add(s, t, dot(sub(f, s), t))
    c = piece[3]
    rho = norm(sub(piece[1], c))
    return add(c, unit(sub(f, c)), rho)


def rounding(a, b, radius: float):
    """``RND``: the arc of ``radius`` tangent to ``a`` (arriving at the corner)
    and ``b`` (leaving it). Returns ``(end of a, arc piece, start of b)``."""
    if radius <= 0:
        raise GeometryError("RND: the radius must be positive")
    t_in, t_out = end_tangent(a), start_tangent(b)
    c = cross(t_in, t_out)
    if abs(c) <= TURN_EPS:
        raise GeometryError("RND between tangent or reversing elements: no corner to round")
    s = 1.0 if c > 0 else -1.0
    P = a[2]
    hits = _meet(_inside_carrier(a, True, (s * -t_in[1], s * t_in[0]), radius),
                 _inside_carrier(b, False, (s * -t_out[1], s * t_out[0]), radius))
    if not hits:
        raise GeometryError(f"RND R{radius:g}: no rounding arc fits between the elements")
    f = min(hits, key=lambda h: norm(sub(h, P)))
    ta, tb = _foot(a, f), _foot(b, f)
    for piece, tp, t_dir, first in ((a, ta, t_in, True), (b, tb, t_out, False)):
        if piece[0] == "line":
            along = dot(sub(tp, piece[1]), t_dir)
            if along < -POINT_EPS or along > norm(sub(piece[2], piece[1])) + POINT_EPS:
                raise GeometryError(f"RND R{radius:g} is too large for the elements at the "
                                    "corner")
    return ta, ("arc", ta, tb, f, arc_sweep(ta, tb, f, s > 0, False)), tb


def chamfer(a, b, length: float):
    """``CHF``: the straight cut of side ``length`` between lines ``a`` and ``b``."""
    if a[0] != "line" or b[0] != "line":
        raise GeometryError("CHF: a chamfer goes between two straight lines (L)")
    if length <= 0:
        raise GeometryError("CHF: the chamfer length must be positive")
    if length > norm(sub(a[2], a[1])) + POINT_EPS or length > norm(sub(b[2], b[1])) + POINT_EPS:
        raise GeometryError(f"CHF {length:g} is longer than a line it cuts")
    ta = add(a[2], unit(sub(a[2], a[1])), -length)
    tb = add(b[1], unit(sub(b[2], b[1])), length)
    return ta, ("line", ta, tb), tb


# -- approach and departure ---------------------------------------------------------------
def _tangent_point(c: Pt, radius: float, q: Pt, ccw: bool, leaving: bool) -> Pt:
    """The point ``T`` of the circle (``c``, ``radius``) whose tangent passes
    through ``q``, run the way the circle turns: arriving from ``q``
    (``leaving`` False) or leaving toward it."""
    d = norm(sub(q, c))
    if d <= radius + POINT_EPS:
        raise GeometryError(f"the point ({q[0]:g}, {q[1]:g}) lies inside the circle of radius "
                            f"{radius:g}: no tangent to it (move it further away or use a "
                            "smaller R)")
    phi = math.atan2(q[1] - c[1], q[0] - c[0])
    alpha = math.acos(radius / d)
    for a in (phi + alpha, phi - alpha):
        t = (c[0] + radius * math.cos(a), c[1] + radius * math.sin(a))
        motion = perp(sub(t, c)) if ccw else perp(sub(c, t))
        toward = sub(q, t) if leaving else sub(t, q)
        if dot(motion, toward) > 0:
            return t
    raise GeometryError("no tangent point found")   # pragma: no cover - one always fits


def approach(kind: str, ps: Pt, pa: Pt, t1: Pt, k: int, r: float, length: float | None,
             radius: float | None, cca_deg: float | None):
    """``APPR <kind>`` at radius ``r``: ``(PH, pieces PH -> PA_t)``."""
    n = (k * -t1[1], k * t1[0])
    pa_t = add(pa, n, r)
    if kind in ("LT", "LN"):
        if length is None or length <= 0:
            raise GeometryError(f"APPR {kind}: LEN must be given and positive")
        ph = add(pa_t, t1, -length) if kind == "LT" else add(pa_t, n, length)
        return ph, [("line", ph, pa_t)]
    if radius is None or radius == 0:
        raise GeometryError(f"APPR {kind}: R must be given and not zero")
    if kind == "CT":
        if cca_deg is None or not 0 < cca_deg <= 360:
            raise GeometryError("APPR CT: CCA must be given, 0 < CCA <= 360")
        sign = 1.0 if radius > 0 else -1.0
        c = add(pa_t, n, sign * abs(radius))
        ccw = sign * k > 0
        sweep = math.radians(cca_deg) * (1.0 if ccw else -1.0)
        ph = rotate_about(pa_t, c, -sweep)
        return ph, [("arc", ph, pa_t, c, sweep)]
    if radius < 0:
        raise GeometryError("APPR LCT: R must be positive")
    c = add(pa_t, n, radius)
    ccw = k > 0
    ph = _tangent_point(c, radius, ps, ccw, leaving=False)
    return ph, [("arc", ph, pa_t, c, arc_sweep(ph, pa_t, c, ccw))]


def departure(kind: str, pe: Pt, t_last: Pt, k: int, r: float, length: float | None,
              radius: float | None, cca_deg: float | None, pn: Pt | None):
    """``DEP <kind>`` at radius ``r``: the pieces from ``PE_t`` to ``PN``."""
    n = (k * -t_last[1], k * t_last[0])
    pe_t = add(pe, n, r)
    if kind in ("LT", "LN"):
        if length is None or length <= 0:
            raise GeometryError(f"DEP {kind}: LEN must be given and positive")
        end = add(pe_t, t_last, length) if kind == "LT" else add(pe_t, n, length)
        return [("line", pe_t, end)]
    if radius is None or radius == 0:
        raise GeometryError(f"DEP {kind}: R must be given and not zero")
    if kind == "CT":
        if cca_deg is None or not 0 < cca_deg <= 360:
            raise GeometryError("DEP CT: CCA must be given, 0 < CCA <= 360")
        sign = 1.0 if radius > 0 else -1.0
        c = add(pe_t, n, sign * abs(radius))
        sweep = math.radians(cca_deg) * (1.0 if sign * k > 0 else -1.0)
        return [("arc", pe_t, rotate_about(pe_t, c, sweep), c, sweep)]
    if radius < 0:
        raise GeometryError("DEP LCT: R must be positive")
    if pn is None:
        raise GeometryError("DEP LCT: the end point PN must be given")
    c = add(pe_t, n, radius)
    ccw = k > 0
    t = _tangent_point(c, radius, pn, ccw, leaving=True)
    pieces = [("arc", pe_t, t, c, arc_sweep(pe_t, t, c, ccw))]
    if norm(sub(pn, t)) > POINT_EPS:
        pieces.append(("line", t, pn))
    return pieces
