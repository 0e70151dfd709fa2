"""Intersections: hand-worked cases, tangency, and random on-both-curves checks."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.geometry import Arc, Line, Spiral, circle_circle, intersections, line_circle, line_line

SQ3_2 = math.sqrt(3.0) / 2.0


# --------------------------------------------------------------------------- low level


def test_line_line_hand_worked():
    [(p, t, u)] = line_line((0, 0), (2, 2), (0, 2), (2, 0))
    assert np.allclose(p, (1, 1)) and math.isclose(t, 0.5) and math.isclose(u, 0.5)
    # Infinite lines: the crossing may be outside both pairs of points.
    [(p, t, u)] = line_line((0, 0), (1, 0), (5, 1), (5, 2))
    assert np.allclose(p, (5, 0)) and math.isclose(t, 5.0) and math.isclose(u, -1.0)
    assert line_line((0, 0), (1, 1), (0, 1), (1, 2)) == []          # parallel
    assert line_line((0, 0), (1, 1), (2, 2), (3, 3)) == []          # collinear
    assert line_line((0, 0), (0, 0), (0, 1), (1, 2)) == []          # degenerate


def test_line_circle_hand_worked():
    # Unit circle and the line y = 0.5: x = -+ sqrt(3)/2, sorted along the line.
    res = line_circle((-2, 0.5), (2, 0.5), (0, 0), 1.0)
    assert len(res) == 2
    (p1, t1, th1), (p2, t2, th2) = res
    assert np.allclose(p1, (-SQ3_2, 0.5), atol=1e-15) and np.allclose(p2, (SQ3_2, 0.5), atol=1e-15)
    assert math.isclose(t1, (2 - SQ3_2) / 4) and math.isclose(t2, (2 + SQ3_2) / 4)
    assert math.isclose(th1, 5 * math.pi / 6) and math.isclose(th2, math.pi / 6)
    # Reversed direction: same points, opposite order.
    res = line_circle((2, 0.5), (-2, 0.5), (0, 0), 1.0)
    assert np.allclose(res[0][0], (SQ3_2, 0.5), atol=1e-15)
    # Tangent (y = 1) and tangent within 1e-13 relative: one touching point.
    for y in (1.0, 1.0 + 1e-13, 1.0 - 1e-13):
        [(p, t, th)] = line_circle((-2, y), (2, y), (0, 0), 1.0)
        assert np.allclose(p, (0, 1), atol=1e-12) and math.isclose(th, math.pi / 2)
    assert line_circle((-2, 1.001), (2, 1.001), (0, 0), 1.0) == []
    assert len(line_circle((-2, 0.999), (2, 0.999), (0, 0), 1.0)) == 2


def test_circle_circle_hand_worked():
    # Unit circles centred (0,0) and (1,0) meet at (1/2, +-sqrt(3)/2).
    res = circle_circle((0, 0), 1.0, (1, 0), 1.0)
    assert len(res) == 2
    (p, a1, a2), (q, b1, b2) = res
    assert np.allclose(p, (0.5, SQ3_2)) and np.allclose(q, (0.5, -SQ3_2))   # left of c1->c2 first
    assert math.isclose(a1, math.pi / 3) and math.isclose(a2, 2 * math.pi / 3)
    assert math.isclose(b1, -math.pi / 3) and math.isclose(b2, -2 * math.pi / 3)
    # External and internal tangency.
    [(p, t1, t2)] = circle_circle((0, 0), 1.0, (3, 0), 2.0)
    assert np.allclose(p, (1, 0)) and math.isclose(t1, 0) and math.isclose(abs(t2), math.pi)
    [(p, t1, t2)] = circle_circle((0, 0), 3.0, (1, 0), 2.0)
    assert np.allclose(p, (3, 0)) and t1 == 0 and t2 == 0
    [(p, _, _)] = circle_circle((0, 0), 2.0, (1, 0), 3.0)
    assert np.allclose(p, (-2, 0))
    [(p, _, _)] = circle_circle((0, 0), 1.0, (2 * (1 + 1e-13), 0), 1.0)
    assert np.allclose(p, (1, 0))
    assert circle_circle((0, 0), 1.0, (0, 0), 2.0) == []           # concentric
    assert circle_circle((0, 0), 1.0, (0, 0), 1.0) == []           # identical
    assert circle_circle((0, 0), 1.0, (5, 0), 1.0) == []           # apart
    assert circle_circle((0, 0), 3.0, (0.5, 0), 1.0) == []         # nested


# --------------------------------------------------------------------------- primitives


def test_intersections_line_arc_hand_worked():
    line = Line((-2.0, 0.5), (2.0, 0.5))
    upper = Arc((0, 0), 1.0, 0.0, math.pi)                          # ccw upper half
    hits = intersections(line, upper)
    assert len(hits) == 2
    (p, sa, sb), (q, sa2, sb2) = hits
    assert np.allclose(p, (-SQ3_2, 0.5)) and math.isclose(sa, 2 - SQ3_2)
    assert math.isclose(sb, 5 * math.pi / 6)                         # arc length on a unit arc
    assert np.allclose(q, (SQ3_2, 0.5)) and math.isclose(sb2, math.pi / 6)
    # Swapped arguments swap the parameters.
    swapped = intersections(upper, line)
    assert [h[1] for h in swapped] == sorted([sb, sb2])
    # Lower half: no crossing, but as full circles (extend) the same two points,
    # with arc parameters measured beyond the lower arc's ends.
    lower = Arc((0, 0), 1.0, math.pi, math.pi)
    assert intersections(line, lower) == []
    ext = intersections(line, lower, extend=True)
    assert len(ext) == 2
    (p, _, sb), (q, _, sb2) = ext
    # (-sqrt3/2, 0.5) is pi/6 before the start (angle pi); (sqrt3/2, 0.5) is pi/6 past the end.
    assert math.isclose(sb, -math.pi / 6) and math.isclose(sb2, math.pi + math.pi / 6)
    # A short segment meets nothing, its extension meets both.
    short = Line((-0.1, 0.5), (0.1, 0.5))
    assert intersections(short, upper) == []
    ext = intersections(short, upper, extend=True)
    assert [round(h[1], 12) for h in ext] == [round(0.1 - SQ3_2, 12), round(0.1 + SQ3_2, 12)]


def test_intersections_multiturn_arc_reports_every_pass():
    arc = Arc((0, 0), 1.0, 0.0, 2 * math.pi + 1.0)                   # 1 rad past a full turn
    hits = intersections(Line((0.0, 0.0), (2.0, 0.2)), arc)
    # The ray meets the circle once at angle ~0.0997 rad: passed twice.
    assert len(hits) == 2
    assert math.isclose(hits[0][2] + 2 * math.pi, hits[1][2]) or \
        math.isclose(hits[1][2] + 2 * math.pi, hits[0][2])


def test_intersections_line_line_and_coincident():
    a = Line((0, 0), (4, 0))
    [(p, sa, sb)] = intersections(a, Line((1, -1), (1, 3)))
    assert np.allclose(p, (1, 0)) and math.isclose(sa, 1.0) and math.isclose(sb, 1.0)
    assert intersections(a, Line((5, -1), (5, 3))) == []
    [(p, sa, sb)] = intersections(a, Line((5, -1), (5, 3)), extend=True)
    assert math.isclose(sa, 5.0) and math.isclose(sb, 1.0)
    # Collinear overlap: the overlap's end points.
    hits = intersections(a, Line((3, 0), (6, 0)))
    assert [(h[1], h[2]) for h in hits] == [(3.0, 0.0), (4.0, 1.0)]
    # Shared end point (consecutive path segments).
    [(p, sa, sb)] = intersections(a, Line((4, 0), (5, 2)))
    assert np.allclose(p, (4, 0)) and sa == 4.0 and sb == 0.0


def test_intersections_arc_arc_and_cocircular():
    a = Arc((0, 0), 1.0, 0.0, math.pi)
    b = Arc((1, 0), 1.0, math.pi / 2, math.pi)                       # ccw from (1,1) to (1,-1)
    [(p, sa, sb)] = intersections(a, b)
    assert np.allclose(p, (0.5, SQ3_2))
    assert math.isclose(sa, math.pi / 3) and math.isclose(sb, 2 * math.pi / 3 - math.pi / 2)
    # Co-circular arcs overlapping on [pi/2, pi]: the overlap's ends.
    c = Arc((0, 0), 1.0, math.pi / 2, math.pi)
    hits = intersections(a, c)
    assert len(hits) == 2
    assert np.allclose([h[1] for h in hits], [math.pi / 2, math.pi])
    assert np.allclose([h[2] for h in hits], [0.0, math.pi / 2])
    assert intersections(a, c, extend=True) == []


def test_intersections_reject_spirals():
    with pytest.raises(TypeError):
        intersections(Spiral((0, 0), 1.0, 2.0, 0.0, 1.0), Line((0, 0), (1, 1)))


def _on_line(p, g, tol):
    (x0, y0), (x1, y1) = g.p0, g.p1
    L = g.length
    return abs((x1 - x0) * (p[1] - y0) - (y1 - y0) * (p[0] - x0)) / L <= tol


def _on_circle(p, g, tol):
    return abs(math.hypot(p[0] - g.center[0], p[1] - g.center[1]) - g.radius) <= tol


def _random_prim(rng):
    if rng.random() < 0.5:
        return Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2)))
    return Arc(tuple(rng.uniform(-3, 3, 2)), rng.uniform(0.2, 4), rng.uniform(-7, 7),
               rng.uniform(-8, 8))


@pytest.mark.parametrize("extend", [False, True])
def test_random_intersections_lie_on_both_curves(extend):
    rng = np.random.default_rng(21)
    found = 0
    for _ in range(1500):
        a, b = _random_prim(rng), _random_prim(rng)
        for p, sa, sb in intersections(a, b, extend=extend):
            found += 1
            for g, s in ((a, sa), (b, sb)):
                on = _on_line(p, g, 1e-9) if isinstance(g, Line) else _on_circle(p, g, 1e-9)
                assert on
                if not extend:
                    assert 0.0 <= s <= g.length
                    # The parameter is where the point is on the piece.
                    assert np.allclose(g.point(s), p, atol=1e-9)
                elif isinstance(g, Arc) and not 0.0 <= s <= g.length:
                    # Off the piece: measured the nearer way round the circle.
                    assert abs(g.sweep) < 2 * math.pi
                    assert -(math.pi * g.radius - g.length / 2) - 1e-9 <= s
                    assert s <= math.pi * g.radius + g.length / 2 + 1e-9
                    gap = -s if s < 0 else s - g.length
                    assert gap <= (2 * math.pi * g.radius - g.length) / 2 + 1e-9
                    # Going round the circle by that parameter reaches the point.
                    ang = g.theta0 + math.copysign(1.0, g.sweep) * s / g.radius
                    q = (g.center[0] + g.radius * math.cos(ang), g.center[1] + g.radius * math.sin(ang))
                    assert np.allclose(q, p, atol=1e-9)
                elif isinstance(g, Line):
                    q = np.add(g.p0, np.subtract(g.p1, g.p0) * (s / g.length))
                    assert np.allclose(q, p, atol=1e-9)
    assert found > 500


def test_segment_crossings_agree_with_shapely():
    shapely = pytest.importorskip("shapely")
    rng = np.random.default_rng(22)
    for _ in range(2000):
        a = Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2)))
        b = Line(tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-5, 5, 2)))
        hits = intersections(a, b)
        ref = shapely.intersection(shapely.LineString([a.p0, a.p1]), shapely.LineString([b.p0, b.p1]))
        assert len(hits) == (0 if ref.is_empty else 1)
        if hits:
            assert np.allclose(hits[0][0], (ref.x, ref.y), atol=1e-12)
