"""The grid follows the turning and curvature inside a segment, so TOPPRA's
profile keeps the axis limits between gridpoints on curves whose turning is
concentrated in a short stretch.

The tolerances are the bounds of :mod:`ccopt.feed.grid` (its docstring
derives them), not fitted to the output. With ``alpha, beta, gamma`` the
grid's budgets per interval (turning, relative change and relative second
variation of ``q''``), each raised by the sampling's margin
``1 + 2 * sample_fraction`` (the grid apportions a sampled piece's measure
linearly), the relative excess of an axis acceleration over its limit is at
most ``E_a = (R_i / 8) e^beta (5 alpha beta + gamma^2)`` with
``R_i = |A|_2 / A_i``, and of an axis velocity at most
``E_v = (alpha / G)^2 / 2 + ((alpha e^beta / G)^2 + alpha beta e^beta / G) / 8``
with ``G = V_i / v_top - alpha``, ``v_top = min(feed, |V|_2)``.
Profiles are sampled every 0.1 ms (10 kHz).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest

from ccopt.feed import AxisLimits, ExactPath, GridOptions, plan_feed
from ccopt.feed.grid import gridpoints, intervals_per_segment
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.toolpath import PathSegment, Role, ToolPath

GRID = GridOptions()
DT = 1e-4

# A quintic that runs 10 mm nearly straight and then turns 90 degrees within
# about 0.1 mm of its end (control points bunched at the corner).
TIGHT = [(0, 0), (5, 0), (9, 0), (10, 0.0), (10.05, 0.05), (10.05, 1.0)]


def budgets(opt: GridOptions = GRID):
    margin = 1.0 + 2.0 * opt.sample_fraction
    return (margin * opt.max_angle, margin * opt.max_curvature_change,
            margin * opt.max_curvature_bend)


def acceleration_bound(a_axis, opt: GridOptions = GRID) -> np.ndarray:
    """``E_a`` of each axis."""
    alpha, beta, gamma = budgets(opt)
    a_axis = np.asarray(a_axis, float)
    R = np.linalg.norm(a_axis) / a_axis
    return R / 8.0 * math.exp(beta) * (5.0 * alpha * beta + gamma ** 2)


def velocity_bound(v_axis, feed: float, opt: GridOptions = GRID) -> np.ndarray:
    """``E_v`` of each axis (where ``G > 0``; an axis with ``V_i / v_top <=
    alpha`` moves too little to reach its limit on a curve)."""
    alpha, beta, _ = budgets(opt)
    v_axis = np.asarray(v_axis, float)
    v_top = min(feed, float(np.linalg.norm(v_axis)))
    G = v_axis / v_top - alpha
    assert np.all(G > 0)
    e = math.exp(beta)
    return (alpha / G) ** 2 / 2.0 + ((alpha * e / G) ** 2 + alpha * beta * e / G) / 8.0


def seg(geom, feed, w0=0.0, w1=0.0):
    return PathSegment(geom, Role.COMPENSATED, None, w0, w1, feed)


def tight_bezier_path(feed: float) -> ToolPath:
    """A line, the tight quintic (tangent to both lines: no stop), a line."""
    curve = BezierCurve(TIGHT)
    return ToolPath((seg(Line((-5.0, 0.0), (0.0, 0.0)), feed), seg(curve, feed),
                     seg(Line((10.05, 1.0), (10.05, 5.0)), feed)))


def spiral_path(feed: float, dw: float = 0.0) -> ToolPath:
    """Two turns of an Archimedean spiral from radius 1 to 50 mm: curvature from
    about 1 to 0.02 per mm (with ``dw``, a helical ramp of that depth)."""
    return ToolPath((seg(Spiral((0.0, 0.0), 1.0, 50.0, 0.0, 4.0 * math.pi), feed, 0.0, dw),))


def sampled_ratios(tp: ToolPath, limits: AxisLimits):
    """Largest sampled ``|a_i| / A_i`` and ``|v_i| / V_i`` of each axis."""
    smp = plan_feed(tp, limits).sample(DT)
    return smp.axis_acceleration_ratio.max(axis=0), smp.axis_velocity_ratio.max(axis=0)


def test_bounds_of_the_defaults():
    """The derived bounds are second order in the budgets and small."""
    assert acceleration_bound([1000.0, 1000.0]) == pytest.approx([6.43e-3] * 2, rel=1e-2)
    assert velocity_bound([100.0, 100.0], 100.0) == pytest.approx([5.06e-3] * 2, rel=1e-2)


def test_tight_bezier_keeps_the_limits_between_gridpoints():
    """The old even grid put a handful of gridpoints in the corner of this curve
    and the profile took 1.13 times the acceleration limit between them."""
    v, a = (100.0, 100.0), (1000.0, 1000.0)
    acc, vel = sampled_ratios(tight_bezier_path(100.0), AxisLimits(v, a))
    assert np.all(acc <= 1.0 + acceleration_bound(a))
    assert np.all(vel <= 1.0 + velocity_bound(v, 100.0))
    assert vel.max() > 0.999 and acc.max() > 0.999      # both limits bind


@pytest.mark.parametrize("dw", [0.0, -20.0], ids=["planar", "helical"])
def test_spiral_keeps_the_limits_between_gridpoints(dw):
    """Curvature from 1 to 0.02 per mm: the old even grid, spaced for the
    outer turn, left 1.3 rad between gridpoints on the inner one and the
    profile took 1.016 times the acceleration limit between them."""
    v, a = (200.0, 200.0, 100.0), (1000.0, 1000.0, 300.0)
    n = 2 if dw == 0.0 else 3
    acc, vel = sampled_ratios(spiral_path(200.0, dw), AxisLimits(v[:n], a[:n]))
    assert np.all(acc <= 1.0 + acceleration_bound(a[:n]))
    assert np.all(vel <= 1.0 + velocity_bound(v[:n], 200.0))
    # both limits bind (the ramp takes 0.2 % of the feed out of the plane)
    assert vel.max() > 0.997 and acc.max() > 0.999


def _interval_figures(path: ExactPath, k: int, gp: np.ndarray, n: int = 257):
    """Per grid interval on segment ``k``, measured on ``n`` points of each
    (independently of the grid's own samples): in-plane turning (radians) and
    ``integral |q'''| / |q''|`` (from differences of ``q''``), with the
    smallest ``|q''|`` of the interval."""
    lo, hi = path.offsets[k], path.offsets[k + 1]
    pts = gp[(gp >= lo) & (gp <= hi)]
    turn, change, kmin = [], [], []
    for a, b in itertools.pairwise(pts):
        s = np.linspace(a, b, n)
        kk = np.full(n, k)
        t = path.eval_segments(kk, s, 1)
        ang = np.unwrap(np.arctan2(t[:, 1], t[:, 0]))
        q2 = path.eval_segments(kk, s, 2)
        kap = np.linalg.norm(q2, axis=1)
        turn.append(np.sum(np.abs(np.diff(ang))))
        change.append(np.sum(np.linalg.norm(np.diff(q2, axis=0), axis=1) / kap[1:]))
        kmin.append(kap.min())
    return np.array(turn), np.array(change), np.array(kmin)


def test_grid_intervals_within_their_budgets():
    """On the tight curve every grid interval turns at most ``max_angle`` and,
    where the curvature is above the floor ``|A|_2 / v_top^2`` (so it is the
    reference), changes ``q''`` by at most ``max_curvature_change`` of it (both
    with the sampling's margin)."""
    v, a, feed = (100.0, 100.0), (1000.0, 1000.0), 100.0
    path = ExactPath(tight_bezier_path(feed))
    gp = gridpoints(path, v, a, GRID)
    alpha, beta, _ = budgets()
    turn, change, kmin = _interval_figures(path, 1, gp)
    assert turn.max() <= alpha
    assert turn.sum() == pytest.approx(math.pi / 2, rel=1e-6)
    above = kmin >= np.linalg.norm(a) / feed ** 2
    assert above.sum() > 50
    assert change[above].max() <= beta
    # spacing: the braking one (10 mm / 16) where the curve is straight, and
    # at most alpha / kappa where it turns most (kappa about 2.7 per mm)
    lo, hi = path.offsets[1], path.offsets[2]
    pts = gp[(gp >= lo) & (gp <= hi)]
    kap = path.curvature_norm(np.full(pts.size, 1), pts)
    i = int(np.argmax(kap))
    assert pts[1] - pts[0] == pytest.approx(10.0 / GRID.density, rel=0.01)
    assert max(pts[i + 1] - pts[i], pts[i] - pts[i - 1]) <= alpha / kap[i]


def test_max_intervals_caps_only_the_braking_part():
    """A long line is held to ``max_intervals``; the curve keeps the gridpoints
    its turning and curvature need, and so does an arc turning many times."""
    v, a = (100.0, 100.0), (1000.0, 1000.0)
    opt = GridOptions(max_intervals=8)
    tp = ToolPath(tight_bezier_path(100.0).segments
                  + (seg(Line((10.05, 5.0), (10.05, 500.0)), 100.0),
                     seg(Arc((0.05, 5.0), 10.0, 0.0, 40 * math.pi), 100.0)))
    path = ExactPath(tp)
    n = intervals_per_segment(path, v, a, opt)
    free = intervals_per_segment(path, v, a, GridOptions())
    assert n[3] == 8 and free[3] > 8
    assert n[1] > 8 and n[1] >= (math.pi / 2) / opt.max_angle
    assert n[4] == math.ceil(40 * math.pi / opt.max_angle)


def test_lines_and_arcs_grid_as_before():
    """Constant-curvature segments keep the even grid: max(S / ds, turn / max_angle)."""
    v, a = (100.0, 100.0), (1000.0, 1000.0)
    tp = ToolPath((seg(Line((0.0, 0.0), (10.0, 0.0)), 50.0),
                   seg(Arc((10.0, 2.0), 2.0, -math.pi / 2, math.pi), 50.0)))
    path = ExactPath(tp)
    ds = min(50.0 ** 2 / 1000.0, 10.0) / GRID.density
    n = intervals_per_segment(path, v, a, GRID)
    assert n[0] == math.ceil(10.0 / ds)
    assert n[1] == max(math.ceil(2 * math.pi / (min(2.5, 2 * math.pi) / GRID.density)),
                       math.ceil(math.pi / GRID.max_angle))
    gp = gridpoints(path, v, a, GRID)
    assert np.allclose(np.diff(gp[gp <= 10.0]), 10.0 / n[0])


_TINY_CURVE = """
import sys, numpy as np
from ccopt.feed import AxisLimits, ExactPath
from ccopt.feed.grid import gridpoints
from ccopt.toolpath_json import read_toolpath_json
ex = ExactPath(read_toolpath_json(sys.argv[1]))
v, a = AxisLimits((200.0, 200.0), (2000.0, 2000.0)).in_plane(ex.frame, ex.dof)
g = gridpoints(ex, v, a)
k = 24
s0, s1 = ex.offsets[k], ex.offsets[k + 1]
inside = g[(g >= s0) & (g <= s1)]
print(g.size, ex.lengths[k], s0, np.diff(inside).min(), inside.size,
      int(np.isin([s0, s1], g).all()), int(np.all(np.diff(g) > 0)))
"""


def test_a_curve_a_few_hundredths_of_a_micrometre_long_far_along_the_path_is_gridded():
    # tests/feed/data/tiny-blend-path.json: the smoother's path of a generated
    # plate (tests/cam_programs.py seed 163, blocks dropped) with a blend curve
    # 2.7e-8 mm long 245.7 mm along it. The curve sampling halved its pieces
    # down to one unit in the last place of the path position, where a piece's
    # midpoint is its end, and went on halving for ever; a piece is now not
    # halved below 64 such units. Run apart, so that a hang fails the test
    # instead of the suite.
    import subprocess
    import sys
    from pathlib import Path

    data = Path(__file__).parent / "data" / "tiny-blend-path.json"
    out = subprocess.run([sys.executable, "-c", _TINY_CURVE, str(data)], capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    n, length, s0, least, on_curve, ends, increasing = (float(x) for x in out.stdout.split())
    assert length == pytest.approx(2.728e-8, rel=1e-3) and s0 > 245.0      # the premise
    assert ends == 1 and increasing == 1 and on_curve >= 2 and least > 0.0


def test_stretch_lines_space_g2_lines_by_their_stretch():
    """With ``stretch_lines`` a line whose joins keep the curvature takes its
    stretch's length (stop to stop) for the braking part, so it gets
    ``min_intervals`` where its own length gave ``density``; a line beside a
    curvature jump (where the jerk planner caps the speed), a move that is a
    stretch alone, arcs and curves keep their own length.

    The path, worked out here: a 0.2 mm line, a quintic whose three first and
    three last control points are collinear (curvature 0 at both ends: G2
    with both lines), a 0.3 mm line; a 90 degree corner (a stop); a 0.5 mm
    line, a tangent quarter arc of radius 0.1 (a curvature jump of 10/mm at
    both ends), a 0.3 mm line. F50 and 1000 mm/s^2 make the braking length
    2.5 mm, longer than either stretch."""
    v, a = (100.0, 100.0), (1000.0, 1000.0)
    quintic = BezierCurve([(0.0, 0.0), (0.1, 0.0), (0.2, 0.0), (0.3, 0.2), (0.3, 0.3),
                           (0.3, 0.4)])
    tp = ToolPath((seg(Line((-0.2, 0.0), (0.0, 0.0)), 50.0),
                   seg(quintic, 50.0),
                   seg(Line((0.3, 0.4), (0.3, 0.7)), 50.0),
                   seg(Line((0.3, 0.7), (-0.2, 0.7)), 50.0),
                   seg(Arc((-0.2, 0.6), 0.1, math.pi / 2, math.pi / 2), 50.0),
                   seg(Line((-0.3, 0.6), (-0.3, 0.3)), 50.0)))
    path = ExactPath(tp)
    assert np.flatnonzero(path.tangent_break).tolist() == [3]        # the corner alone
    own = intervals_per_segment(path, v, a, GRID)
    by_stretch = intervals_per_segment(path, v, a, replace(GRID, stretch_lines=True))
    braking = 50.0 ** 2 / 1000.0
    span = 0.2 + float(path.lengths[1]) + 0.3              # the first stretch, stop to stop
    assert braking > span
    assert own[0] == own[2] == own[3] == own[5] == GRID.density     # S / (S / density)
    ds = span / GRID.density
    assert by_stretch[0] == max(GRID.min_intervals, math.ceil(0.2 / ds)) == GRID.min_intervals
    assert by_stretch[2] == max(GRID.min_intervals, math.ceil(0.3 / ds))
    assert by_stretch[2] < own[2]
    # beside the arc's curvature jumps, the arc itself, the quintic: their own length
    assert by_stretch[3] == own[3] and by_stretch[5] == own[5]
    assert by_stretch[4] == own[4] and by_stretch[1] == own[1]
