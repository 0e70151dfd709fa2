"""Figures of the comparison on paths built by hand."""
from __future__ import annotations

import math

import pytest

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
    from ccopt.compare.core import _duration
    from ccopt.feed import AxisLimits
    from ccopt.geometry import BezierCurve
    P = [(0, 0), (5, 0), (9, 0), (10, 0.0), (10.05, 0.05), (10.05, 1.0)]
    geoms = (Line((-5, 0), (0, 0)), BezierCurve(P), Line((10.05, 1.0), (10.05, 5)))
    path = ToolPath(tuple(PathSegment(g, Role.COMPENSATED, None, 0.0, 0.0, 50.0) for g in geoms))
    duration, ratio, message = _duration(path, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))
    assert message is None and duration > 0
    assert 0.999 < ratio <= 1.001
