"""feed_limited_time: the time no planner beats, from the feed and the axis speeds."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.cases import bundled_cases
from ccopt.feed import AxisLimits, feed_limited_time, plan_feed
from ccopt.program import read_text

LIMITS = AxisLimits([100.0, 100.0, 30.0], [1000.0, 1000.0, 300.0])


def path_of(text: str):
    return ccopt.programmed_path(read_text(text, "t.nc"))


def test_line_at_its_feed():
    # 100 mm at F600 mm/min = 10 mm/s: 10 s; TOPPRA adds the speeding up and the
    # braking, v / a = 0.01 s in all (each ramp takes v / a and covers half the
    # distance it would at v)
    path = path_of("G21 G90 G94\nG1 X100 F600\n")
    assert feed_limited_time(path, LIMITS) == pytest.approx(10.0, rel=1e-12)
    for planner in ("toppra", "stop", "junction"):
        assert plan_feed(path, LIMITS, planner=planner).duration == pytest.approx(
            10.0 + 10.0 / 1000.0, rel=1e-9)


def test_axis_speed_bounds_a_fast_feed_and_a_rapid():
    # F12000 mm/min = 200 mm/s along X, but X runs at most 100 mm/s: 0.5 s for 50 mm
    path = path_of("G21 G90 G94\nG1 X50 F12000\n")
    assert feed_limited_time(path, LIMITS) == pytest.approx(0.5, rel=1e-12)
    # a rapid to (10, 0, 9): Z at 30 mm/s is the slowest, 0.3 s
    path = path_of("G21 G90 G94\nG0 X10 Z9\n")
    assert feed_limited_time(path, LIMITS) == pytest.approx(0.3, rel=1e-12)


def test_arc_helix_and_dwell():
    # a half circle of radius 5 (length 5 pi) at 10 mm/s, rising 4 in Z: the helix
    # is hypot(5 pi, 4) long; then a 2 s dwell
    path = path_of("G21 G90 G94\nG1 X5 F600\nG3 X-5 Y0 Z4 I-5 J0\nG4 P2\n")
    expect = 0.5 + math.hypot(5 * math.pi, 4.0) / 10.0 + 2.0
    assert feed_limited_time(path, LIMITS) == pytest.approx(expect, rel=1e-12)



def test_full_circle_counts_each_axis_travel():
    # a full circle of radius 10 at F60000 mm/min = 1000 mm/s: the feed alone would
    # allow 20 pi / 1000 = 0.063 s, but X and Y each travel 4 R = 40 mm at 100 mm/s
    path = path_of("G21 G90 G94\nG1 X10 F60000\nG3 X10 Y0 I-10 J0\n")
    circle = feed_limited_time(path, LIMITS) - 10.0 / 100.0
    assert circle == pytest.approx(40.0 / 100.0, rel=1e-12)
    assert plan_feed(path, LIMITS).duration > 0.1 + 0.4


def test_a_negligible_z_move_needs_no_z_limit():
    # 1e-10 mm of Z is below POINT_EPS: the planners leave it out, and so does the floor
    path = path_of("G21 G90 G94\nG1 X10 F600\nG1 Z0.0000000001\n")
    xy = AxisLimits([100.0, 100.0], [1000.0, 1000.0])
    assert feed_limited_time(path, xy) == pytest.approx(1.0, rel=1e-12)
    assert plan_feed(path, xy).duration > 1.0


def test_missing_axis_limit_is_named():
    path = path_of("G21 G90 G94\nG1 X5 Z3 F600\n")
    with pytest.raises(ValueError, match="axis Z"):
        feed_limited_time(path, AxisLimits([100.0, 100.0], [1000.0, 1000.0]))


@pytest.mark.parametrize("case", [c for c in bundled_cases() if c.expect != "error"],
                         ids=lambda c: c.name)
def test_no_planner_beats_it_on_the_cases(case):
    prog = ccopt.read_program(case.program)
    path = ccopt.compensate(prog, case.style, radius=case.radius)
    limits = AxisLimits(case.vmax, case.amax)
    floor = feed_limited_time(path, limits)
    assert floor > 0
    # (no case runs an axis at its limit along a curve, where TOPPRA's gridpoint-only
    # axis limits could take it a fraction of a percent below: see ccopt.feed.bounds)
    for planner in ("toppra", "stop", "junction"):
        assert plan_feed(path, limits, planner=planner).duration >= floor * (1 - 1e-9)
