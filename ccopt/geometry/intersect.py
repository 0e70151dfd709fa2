"""Intersections of lines and circles, and of Line/Arc primitives.

Low-level (supporting curves, no range limits):

- :func:`line_line` -- two infinite lines through ``p0, p1`` and ``q0, q1``:
  ``[(point, t, u)]`` with ``point = p0 + t (p1 - p0) = q0 + u (q1 - q0)``;
  empty when parallel (including collinear).
- :func:`line_circle` -- infinite line and full circle: ``[(point, t, theta)]``
  with ``t`` the fraction along ``p0 -> p1`` and ``theta`` the polar angle of
  the point about the centre, in ``(-pi, pi]``; sorted by ``t``; 0, 1
  (tangent) or 2 items.
- :func:`circle_circle` -- two full circles: ``[(point, theta1, theta2)]``,
  polar angles about each centre in ``(-pi, pi]``; with two points the first
  is to the LEFT of the direction ``c1 -> c2``; concentric circles give none.

Tangency: a line whose distance from the centre is within ``tol * R`` of
``R``, or circles whose centre distance is within ``tol * (R1 + R2)`` of
``R1 + R2`` or ``|R1 - R2|``, touch in exactly one point (``tol`` is
:data:`TANGENT_REL_TOL` ``= 1e-12`` by default).

Primitives: :func:`intersections` ``(a, b, extend=False)`` for two
:class:`Line`/:class:`Arc` objects returns ``[(point, sa, sb)]`` sorted by
``sa``, where ``sa`` and ``sb`` are ARC-LENGTH parameters on ``a`` and ``b``
measured from each one's start along its direction of travel (program
units). See its docstring for ``extend=True`` and coincident curves.
"""
from __future__ import annotations

import math

from ccopt.geometry.angles import TWO_PI, angle_along
from ccopt.geometry.primitives import Arc, Line, Spiral

__all__ = ["line_line", "line_circle", "circle_circle", "intersections"]

#: Relative tolerance of tangency and parallelism (``|sin(angle)|``, or a
#: fraction of the radii): a few thousand ulps, so a contact computed from
#: rounded input still counts as the single touching point it is meant to be.
TANGENT_REL_TOL = 1e-12

#: A point within this times the coordinate scale of a primitive's end counts
#: as on the piece and is clamped to the end (rounding of points computed on
#: both pieces; the same relative bound as ``Arc.from_points``).
END_REL_TOL = 1e-9

Point = tuple[float, float]


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def line_line(p0, p1, q0, q1, tol: float = TANGENT_REL_TOL):
    """Intersection of the infinite lines ``p0 p1`` and ``q0 q1``.

    Returns ``[(point, t, u)]`` (fractions along ``p0 -> p1`` and
    ``q0 -> q1``, any real), or ``[]`` when the lines are parallel:
    ``|sin(angle)| <= tol`` or either pair of points coincides.
    """
    p0x, p0y = map(float, p0)
    q0x, q0y = map(float, q0)
    rx, ry = float(p1[0]) - p0x, float(p1[1]) - p0y
    sx, sy = float(q1[0]) - q0x, float(q1[1]) - q0y
    den = _cross(rx, ry, sx, sy)
    scale = math.hypot(rx, ry) * math.hypot(sx, sy)
    if scale == 0.0 or abs(den) <= tol * scale:
        return []
    wx, wy = q0x - p0x, q0y - p0y
    t = _cross(wx, wy, sx, sy) / den
    u = _cross(wx, wy, rx, ry) / den
    return [((p0x + t * rx, p0y + t * ry), t, u)]


def line_circle(p0, p1, c, R, tol: float = TANGENT_REL_TOL):
    """Intersections of the infinite line ``p0 p1`` with the circle ``(c, R)``.

    Returns ``[(point, t, theta)]`` sorted by ``t`` (fraction along
    ``p0 -> p1``); ``theta`` is the point's polar angle about ``c``. A line
    within ``tol * R`` of tangency gives its single touching point (the foot
    of the perpendicular from ``c``). ``[]`` if ``p0 == p1``.
    """
    p0x, p0y = map(float, p0)
    cx, cy = map(float, c)
    R = float(R)
    rx, ry = float(p1[0]) - p0x, float(p1[1]) - p0y
    L = math.hypot(rx, ry)
    if L == 0.0:
        return []
    ex, ey = rx / L, ry / L
    nx, ny = -ey, ex
    gx, gy = cx - p0x, cy - p0y
    along_c = gx * ex + gy * ey             # foot of the centre, length from p0
    h = gx * nx + gy * ny                   # signed distance of the centre from the line
    if abs(h) > R * (1.0 + tol):
        return []
    if abs(abs(h) - R) <= tol * R:
        vx, vy = -h * nx, -h * ny
        return [((cx + vx, cy + vy), along_c / L, math.atan2(vy, vx))]
    w = math.sqrt((R - h) * (R + h))        # half chord, factored to keep digits near tangency
    out = []
    for sgn in (-1.0, 1.0):
        vx = sgn * w * ex - h * nx          # point relative to the centre
        vy = sgn * w * ey - h * ny
        out.append(((p0x + (along_c + sgn * w) * ex, p0y + (along_c + sgn * w) * ey),
                    (along_c + sgn * w) / L, math.atan2(vy, vx)))
    return out


def circle_circle(c1, R1, c2, R2, tol: float = TANGENT_REL_TOL):
    """Intersections of circles ``(c1, R1)`` and ``(c2, R2)``.

    Returns ``[(point, theta1, theta2)]`` with the polar angles of the point
    about ``c1`` and ``c2``. Two points: the first lies to the left of
    ``c1 -> c2``. Tangent circles (within ``tol * (R1 + R2)``) give one
    point; separate, nested or concentric circles give ``[]``.
    """
    c1x, c1y = map(float, c1)
    c2x, c2y = map(float, c2)
    R1, R2 = float(R1), float(R2)
    gx, gy = c2x - c1x, c2y - c1y
    D = math.hypot(gx, gy)
    rsum = R1 + R2
    if D <= tol * max(R1, R2):
        return []
    ux, uy = gx / D, gy / D
    if abs(D - rsum) <= tol * rsum:
        p = (c1x + R1 * ux, c1y + R1 * uy)
        return [(p, math.atan2(uy, ux), math.atan2(-uy, -ux))]
    if abs(D - abs(R1 - R2)) <= tol * rsum:
        # Internal tangency: the touching point is on the far side of the smaller circle.
        s = 1.0 if R1 >= R2 else -1.0
        p = (c1x + s * R1 * ux, c1y + s * R1 * uy)
        return [(p, math.atan2(s * uy, s * ux), math.atan2(s * uy, s * ux))]
    if D > rsum or D < abs(R1 - R2):
        return []
    a = (D * D + R1 * R1 - R2 * R2) / (2.0 * D)
    h = math.sqrt(max((R1 - a) * (R1 + a), 0.0))
    out = []
    for sgn in (1.0, -1.0):
        vx = a * ux - sgn * h * uy
        vy = a * uy + sgn * h * ux
        px, py = c1x + vx, c1y + vy
        out.append(((px, py), math.atan2(vy, vx), math.atan2(py - c2y, px - c2x)))
    return out


# --------------------------------------------------------------------------- primitives


def _arc_params(arc: Arc, theta: float, extend: bool, eps: float) -> list[float]:
    """Arc-length parameters on ``arc`` of the circle point at polar angle ``theta``.

    On the arc: every pass ``R * (along + 2 pi k) <= length`` (a multi-turn arc
    passes a point more than once), within ``eps`` (length) of either end.
    Off the arc and ``extend``: the nearer way round the supporting circle --
    ``length + R * past_end`` or ``-R * before_start``; off the arc and not
    ``extend``: none.
    """
    R, L = arc.radius, arc.length
    along = float(angle_along(theta, arc.theta0, arc.sweep))
    if TWO_PI - along <= eps / R:           # just before the start is the start
        along = 0.0
    out = []
    k = 0
    while R * (along + TWO_PI * k) <= L + eps:
        out.append(min(R * (along + TWO_PI * k), L))
        k += 1
    if out or not extend:
        return out
    past_end = along - abs(arc.sweep)
    before_start = TWO_PI - along
    return [L + R * past_end] if past_end < before_start else [-R * before_start]


def _line_param(t: float, line: Line, extend: bool, eps: float) -> float | None:
    s = t * line.length
    if extend:
        return s
    if s < -eps or s > line.length + eps:
        return None
    return min(max(s, 0.0), line.length)


def _scale(*objs) -> float:
    """A length scale for tolerances: coordinates, radii and lengths involved."""
    m = 1.0
    for o in objs:
        if isinstance(o, Line):
            m = max(m, abs(o.p0[0]), abs(o.p0[1]), abs(o.p1[0]), abs(o.p1[1]), o.length)
        else:
            m = max(m, abs(o.center[0]), abs(o.center[1]), o.radius)
    return m


def _on_curve(p, g, eps: float) -> list[float]:
    """Arc-length parameters at which point ``p`` lies on ``g`` (within ``eps``)."""
    px, py = p
    if isinstance(g, Line):
        (x0, y0), (x1, y1) = g.p0, g.p1
        L = g.length
        if L == 0.0:
            return [0.0] if math.hypot(px - x0, py - y0) <= eps else []
        ex, ey = (x1 - x0) / L, (y1 - y0) / L
        s = (px - x0) * ex + (py - y0) * ey
        if abs(_cross(ex, ey, px - x0, py - y0)) > eps or s < -eps or s > L + eps:
            return []
        return [min(max(s, 0.0), L)]
    rho = math.hypot(px - g.center[0], py - g.center[1])
    if abs(rho - g.radius) > eps:
        return []
    theta = math.atan2(py - g.center[1], px - g.center[0])
    out = _arc_params(g, theta, False, eps)
    if not out:
        # Within eps of an end point but just outside the sweep by rounding.
        for s, q in ((0.0, g.start), (g.length, g.end)):
            if math.hypot(px - q[0], py - q[1]) <= eps:
                out.append(s)
    return out


def _coincident_overlap(a, b, eps: float):
    """End points of the common part of two coincident curves (collinear lines,
    co-circular arcs): each curve's end points that lie on the other."""
    out = []
    for s_a, p in ((0.0, a.start), (a.length, a.end)):
        for s_b in _on_curve(p, b, eps):
            out.append((p, s_a, s_b))
    for s_b, p in ((0.0, b.start), (b.length, b.end)):
        for s_a in _on_curve(p, a, eps):
            out.append((p, s_a, s_b))
    return out


def _dedupe(hits, eps: float):
    hits = sorted(hits, key=lambda h: (h[1], h[2]))
    out = []
    for h in hits:
        if out and abs(h[1] - out[-1][1]) <= eps and abs(h[2] - out[-1][2]) <= eps:
            continue
        out.append(h)
    return out


def intersections(a, b, extend: bool = False, tol: float = TANGENT_REL_TOL,
                  end_tol: float = END_REL_TOL):
    """All intersections of two :class:`Line`/:class:`Arc` primitives.

    Returns ``[(point, sa, sb)]`` sorted by ``sa``; ``sa``/``sb`` are arc-length
    parameters (program units) on ``a``/``b`` from each one's start, along
    its direction of travel.

    ``extend=False``: only points on both pieces; parameters lie in
    ``[0, length]`` (points within ``end_tol * scale`` of an end are accepted
    and clamped; ``scale`` = the largest of 1, |coordinates|, radii, lengths).
    A multi-turn arc reports one entry per pass through the point.

    ``extend=True``: lines are infinite and arcs full circles. A line's
    parameter is ``t * length`` for any real ``t``. An arc's parameter is
    the one above when the point is on the arc; otherwise it is measured the
    nearer way round the circle from the arc: ``length + R * delta`` when the
    point is ``delta`` radians past the end, or ``-R * delta`` when it is
    ``delta`` radians before the start. So it lies in
    ``[-(pi R - length/2), pi R + length/2]``, and ``< 0`` / ``> length``
    tell "before the start" / "after the end".

    Coincident curves (collinear lines, co-circular arcs) share infinitely
    many points; with ``extend=False`` the end points of their common part
    are returned, with ``extend=True`` nothing. A zero-length line is a point.
    Spirals are not supported (``TypeError``).
    """
    for g in (a, b):
        if isinstance(g, Spiral) or not isinstance(g, (Line, Arc)):
            raise TypeError(f"intersections() takes Line and Arc, not {type(g).__name__}")
    eps = end_tol * _scale(a, b)
    if isinstance(a, Line) and a.length == 0.0:
        return [(a.p0, 0.0, s) for s in _on_curve(a.p0, b, eps)] if not extend else []
    if isinstance(b, Line) and b.length == 0.0:
        return [(b.p0, s, 0.0) for s in _on_curve(b.p0, a, eps)] if not extend else []

    hits = []
    if isinstance(a, Line) and isinstance(b, Line):
        res = line_line(a.p0, a.p1, b.p0, b.p1, tol)
        if not res:
            # Parallel: coincident only if b's ends are on a's line.
            ex, ey = a.direction
            collinear = all(abs(_cross(ex, ey, q[0] - a.p0[0], q[1] - a.p0[1])) <= eps
                            for q in (b.p0, b.p1))
            return _dedupe(_coincident_overlap(a, b, eps), eps) if collinear and not extend else []
        for p, t, u in res:
            sa, sb = _line_param(t, a, extend, eps), _line_param(u, b, extend, eps)
            if sa is not None and sb is not None:
                hits.append((p, sa, sb))
    elif isinstance(a, Line) or isinstance(b, Line):
        line, arc = (a, b) if isinstance(a, Line) else (b, a)
        for p, t, theta in line_circle(line.p0, line.p1, arc.center, arc.radius, tol):
            s_line = _line_param(t, line, extend, eps)
            if s_line is None:
                continue
            for s_arc in _arc_params(arc, theta, extend, eps):
                hits.append((p, s_line, s_arc) if line is a else (p, s_arc, s_line))
    else:
        same_circle = (math.hypot(a.center[0] - b.center[0], a.center[1] - b.center[1]) <= eps
                       and abs(a.radius - b.radius) <= eps)
        if same_circle:
            return [] if extend else _dedupe(_coincident_overlap(a, b, eps), eps)
        for p, th1, th2 in circle_circle(a.center, a.radius, b.center, b.radius, tol):
            for sa in _arc_params(a, th1, extend, eps):
                for sb in _arc_params(b, th2, extend, eps):
                    hits.append((p, sa, sb))
    return _dedupe(hits, eps)

