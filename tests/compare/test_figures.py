"""Figures of the comparison on paths built by hand."""
from __future__ import annotations

import math

import pytest

from brute_distance import one_sided_deviation
from ccopt.compare.figures import join_class, max_deviation, path_figures
from ccopt.geometry import Arc, Line
from ccopt.toolpath import PathSegment, Role, ToolPath


def seg(g, role=Role.COMPENSATED):
    return PathSegment(g, role, None, 0.0, 0.0, 10.0)


def test_join_classes():
    a = seg(Line((0, 0), (10, 0)))
    corner = seg(Line((10, 0), (10, 5)))
    cls, gap, ang, _ = join_class(a, corner)
    assert cls == "G0" and ang == pytest.approx(math.pi / 2) and gap == 0.0
    # line into a tangent arc of radius 2 (centre above): curvature 0 -> 1/2
    arc = seg(Arc((10, 2), 2.0, -math.pi / 2, math.pi / 2))
    cls, _, ang, jump = join_class(a, arc)
    assert cls == "G1" and ang < 1e-12 and jump == pytest.approx(0.5)
    # an arc into its own continuation: curvature continuous
    arc2 = seg(Arc((10, 2), 2.0, 0.0, math.pi / 2))
    assert join_class(arc, arc2)[0] == "G2"
    assert join_class(a, seg(Line((10.1, 0), (20, 0))))[0] == "gap"


def test_path_figures():
    segs = [seg(Line((0, 0), (10, 0))), seg(Arc((10, 2), 2.0, -math.pi / 2, math.pi / 2)),
            seg(Line((12, 2), (12, 10)))]
    fig = path_figures(ToolPath(tuple(segs)), [1, 2])
    assert fig["max_curvature"] == pytest.approx(0.5)
    assert fig["max_curvature_jump"] == pytest.approx(0.5)
    assert fig["continuity"] == "G1" and fig["path_continuity"] == "G1"
    assert fig["tangent_breaks"] == 0
    assert fig["length"] == pytest.approx(10 + math.pi + 8)


@pytest.mark.parametrize("cut", [0.01, 0.3])
def test_deviation_of_a_cut_corner(cut):
    # reference: a right-angle corner at V = (10, 0); variant: the corner cut by a chord
    # from (10 - c, 0) to (10, c). Hausdorff distance: from V to the chord, c / sqrt(2)
    # (the chord's points are at most c/2 from the reference lines).
    ref = ToolPath((seg(Line((0, 0), (10, 0))), seg(Line((10, 0), (10, 10)))))
    var = ToolPath((seg(Line((0, 0), (10 - cut, 0))), seg(Line((10 - cut, 0), (10, cut)), Role.CORNER),
                    seg(Line((10, cut), (10, 10)))))
    est, bound = max_deviation(var, ref)
    true = cut / math.sqrt(2.0)
    assert est == pytest.approx(true, abs=1e-9)
    assert true <= bound <= true + 1e-3
    assert max_deviation(ref, ref) == (0.0, 0.0)


def test_duration_keeps_the_limits_on_a_tight_curve():
    """A variant's own path is planned as it is: the feed grid follows the turning
    inside curves (:mod:`ccopt.feed.grid`), so a quintic turning 90 degrees in its
    last 0.1 mm keeps the axis limits between gridpoints, sampled every 0.2 ms, to
    the 0.1 % the comparison's tests ask (an even grid on the curve: 1.13)."""
    from ccopt.compare.schedule import _duration
    from ccopt.feed import AxisLimits
    from ccopt.geometry import BezierCurve
    P = [(0, 0), (5, 0), (9, 0), (10, 0.0), (10.05, 0.05), (10.05, 1.0)]
    geoms = (Line((-5, 0), (0, 0)), BezierCurve(P), Line((10.05, 1.0), (10.05, 5)))
    path = ToolPath(tuple(PathSegment(g, Role.COMPENSATED, None, 0.0, 0.0, 50.0) for g in geoms))
    duration, ratio, message = _duration(path, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))
    assert message is None and duration > 0
    assert 0.999 < ratio <= 1.001


def test_deviation_of_a_parabolic_bump():
    # reference: the straight line y = 0 from x = -5 to 15; variant: its middle part
    # [0, 10] replaced by the quadratic Bezier (0, 0), (5, 2), (10, 0), the parabola
    # y = 4 t (1 - t), x = 10 t, whose top (5, 1) is 1 from the line. Every point of
    # the line is at most 1 from the bump (its vertical distance), so the
    # Hausdorff distance is 1.
    from ccopt.geometry import BezierCurve
    left, right = Line((-5, 0), (0, 0)), Line((10, 0), (15, 0))
    ref = ToolPath((seg(left), seg(Line((0, 0), (10, 0))), seg(right)))
    var = ToolPath((seg(left), seg(BezierCurve([(0, 0), (5, 2), (10, 0)]), Role.CORNER),
                    seg(right)))
    h = 1e-3
    est, bound = max_deviation(var, ref, h)
    assert est == pytest.approx(1.0, abs=1e-9)
    assert 1.0 <= bound <= 1.0 + h / 8 + 1e-9


def test_deviation_between_translated_curves():
    # the reference's corner is the parabola of the previous test, the variant's the
    # same parabola 0.3 higher, with lines 0.3 apart on both sides. Both parabolas
    # bend with radius 12.5 at their tops (y = 1 - 0.04 (x - 5)^2), far above 0.3,
    # so the tops are 0.3 apart, and no point is farther than 0.3 (its vertical
    # distance) from the other path: the Hausdorff distance is 0.3, on both sides.
    from ccopt.geometry import BezierCurve
    up = 0.3
    P = [(0, 0), (5, 2), (10, 0)]
    ref = ToolPath((seg(Line((-5, 0), (0, 0))), seg(BezierCurve(P), Role.CORNER),
                    seg(Line((10, 0), (15, 0)))))
    var = ToolPath((seg(Line((-5, up), (0, up))),
                    seg(BezierCurve([(x, y + up) for x, y in P]), Role.CORNER),
                    seg(Line((10, up), (15, up)))))
    h = 1e-3
    for a, b in ((var, ref), (ref, var)):
        est, bound = max_deviation(a, b, h)
        assert est == pytest.approx(up, abs=1e-9)
        assert up <= bound <= up + h / 8 + 1e-6


def test_deviation_of_lines_beside_the_reference_lines():
    # the reference: the line y = 0 from x = 0 to 20 in 7 blocks; the variant: the
    # same line 3e-4 higher in 40 blocks (another controller's path beside the
    # reference's, split elsewhere). Every point is 3e-4 from the other path (its
    # vertical distance; the ends lie above each other), so the Hausdorff distance
    # is 3e-4 on both sides, and the bound holds it within h / 8 without sampling
    # the lines every few h (each line's distance to a reference line is convex
    # along it: its ends bound it).
    e, h = 3e-4, 1e-3
    xr = [20.0 * i / 7 for i in range(8)]
    xv = [20.0 * i / 40 for i in range(41)]
    ref = ToolPath(tuple(seg(Line((a, 0.0), (b, 0.0))) for a, b in zip(xr, xr[1:])))
    var = ToolPath(tuple(seg(Line((a, e), (b, e))) for a, b in zip(xv, xv[1:])))
    for a, b in ((var, ref), (ref, var)):
        est, bound = max_deviation(a, b, h)
        assert est == pytest.approx(e, abs=1e-12)
        assert e - 1e-12 <= bound <= e + h / 8 + 1e-12


def test_deviation_skips_a_spiral_both_paths_share_by_value():
    # two styles offset a program's spiral alike, each into its own object: the
    # deviation leaves it out as it leaves out equal lines and arcs, so it is
    # that of the one line that differs, 0.2 (parallel lines 0.2 apart, beside
    # the same spiral end to end). Sampled every h instead, the spiral alone
    # made crazy-paths' heidenhain deviation take 14 s.
    from ccopt.compare.figures import _shared
    from ccopt.geometry import Spiral
    sp = dict(center=(0.0, 0.0), rho0=5.0, rho1=6.0, theta0=0.0, sweep=math.pi)
    a, b = Spiral(**sp), Spiral(**sp)
    assert a is not b and _shared([a], [b]) == [True]
    end = a.end
    ref = ToolPath((seg(a), seg(Line(end, (end[0], end[1] - 10.0)))))
    var = ToolPath((seg(b), seg(Line((end[0] + 0.2, end[1]), (end[0] + 0.2, end[1] - 10.0)))))
    est, bound = max_deviation(var, ref)
    assert est == pytest.approx(0.2, abs=1e-9) and 0.2 <= bound <= 0.2 + 1e-3


@pytest.mark.parametrize("kind", ["arc", "spiral"])
def test_deviation_of_an_arc_or_spiral_beside_the_reference_arc(kind):
    # the reference: a quarter circle of radius 5 about the origin; the variant:
    # over the same angles, the arc of radius 5 + 3e-4 about it, or the spiral
    # from radius 5 to 5 + 3e-4 (a CAM arc whose rounded ends make a spiral, and
    # another controller's corner arc, beside the reference's). A point at
    # angle phi of either is its radial gap from the other, at most 3e-4 (at
    # the end, for the spiral): the Hausdorff distance is 3e-4, and the bound
    # holds it to rounding, by radii, centres and angles, without the
    # Lipschitz steps' h / 8.
    from ccopt.geometry import Spiral
    e, h = 3e-4, 1e-3
    ref = ToolPath((seg(Arc((0.0, 0.0), 5.0, 0.0, math.pi / 2)),))
    g = (Arc((0.0, 0.0), 5.0 + e, 0.0, math.pi / 2) if kind == "arc"
         else Spiral(center=(0.0, 0.0), rho0=5.0, rho1=5.0 + e, theta0=0.0, sweep=math.pi / 2))
    var = ToolPath((seg(g),))
    for a, b in ((var, ref), (ref, var)):
        est, bound = max_deviation(a, b, h)
        assert est == pytest.approx(e, abs=1e-9)
        assert e - 1e-9 <= bound <= e + 1e-12


def _samples_of(monkeypatch):
    """Wrap the deviation's sampling: the number of samples of each side."""
    from ccopt.compare import deviation
    counts = []
    along = deviation._along

    def counted(*args):
        out = along(*args)
        counts.append(len(out[1]))
        return out
    monkeypatch.setattr(deviation, "_along", counted)
    return counts


def _brute_deviation(src, dst, n=20_001):
    """The largest distance from ``n`` points of each of ``src``'s primitives to
    ``dst``'s lines and arcs, each measured by its formula (tests/brute_distance.py)."""
    return one_sided_deviation([s.geom for s in src.segments], [s.geom for s in dst.segments],
                               points=n)


def test_deviation_of_a_line_beside_a_shorter_reference_line_and_its_corner(monkeypatch):
    # the reference: a line y = 0 from x = 0 to 30, then its corner arc of radius
    # 2 about (30, 2); the variant: the line 1e-6 higher running on to x = 30.002,
    # past the reference line's end and beside the arc, then the arc e inside.
    # No single reference line holds the variant's line by its ends, but each
    # step whose ends are nearest the reference line is held by them
    # (convexity), so only the steps near the corner are halved: not the whole
    # line down to steps of about h / 4.
    e, h = 1e-6, 1e-3
    ref = ToolPath((seg(Line((0.0, 0.0), (30.0, 0.0))),
                    seg(Arc((30.0, 2.0), 2.0, -math.pi / 2, math.pi / 2))))
    start = math.atan2(e - 2.0, 0.002)          # the arc's angle at the line's end
    var = ToolPath((seg(Line((0.0, e), (30.002, e))),
                    seg(Arc((30.0, 2.0), 2.0 - e, start, -start))))
    counts = _samples_of(monkeypatch)
    est, bound = max_deviation(var, ref, h)
    truth = max(_brute_deviation(var, ref), _brute_deviation(ref, var))
    assert truth - 1e-12 <= est <= bound <= truth + h / 8 + 1e-9
    coarse = 30.002 / (50 * h) + 1
    assert counts[0] < 2 * coarse + 2 * math.pi / (50 * h) + 2    # the Lipschitz steps alone:
    # 30 / (h / 4) samples on the line


def test_deviation_of_a_corner_arc_turning_on_past_the_reference_arc(monkeypatch):
    # the reference: an arc of radius 5.85 about the origin over 2.3 rad, then the
    # line tangent at its end; the variant: the same arc turning 5.8e-5 rad further
    # (another style's corner arc, ending where its own next element begins), so
    # its whole-arc bound counts 5.85 * 5.8e-5 = 3.4e-4 > h / 8 everywhere. The
    # steps within the reference arc's angles are held by the radii at their ends.
    h, rho, th0, sw, extra = 1e-3, 5.85, -2.16, 2.3, 5.8e-5
    end = (rho * math.cos(th0 + sw), rho * math.sin(th0 + sw))
    tangent = (-math.sin(th0 + sw), math.cos(th0 + sw))
    ref = ToolPath((seg(Arc((0.0, 0.0), rho, th0, sw)),
                    seg(Line(end, (end[0] + 3 * tangent[0], end[1] + 3 * tangent[1])))))
    var = ToolPath((seg(Arc((0.0, 0.0), rho, th0, sw + extra)),))
    counts = _samples_of(monkeypatch)
    est, bound = max_deviation(var, ref, h)
    truth = max(_brute_deviation(var, ref), _brute_deviation(ref, var))
    assert truth - 1e-12 <= est <= bound <= truth + h / 8 + 1e-9
    assert counts[0] < 2 * (rho * (sw + extra) / (50 * h) + 1)
