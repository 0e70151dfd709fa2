"""The jerk planner over generated SINUMERIK and HEIDENHAIN plates
(tests/family_programs.py, the controllers' own leads), in every style the
comparison times: PMAC, LinuxCNC, SINUMERIK, HEIDENHAIN and Fagor with
linear (G137) and circular (G136) corners, under limits drawn from the seed.

The properties of tests/feed/test_jerk_generated.py: sampled at 10 kHz no
axis exceeds its velocity, acceleration or jerk limit, nor the path speed
its feed, beyond the certificate's tolerance; the cycle time lies between
TOPPRA's (fewer limits) and the jerk-limited stop baseline's; and no
RuntimeWarning (a NaN or an overflow the planner did not mean).

Found here: the Fagor G137 style's corner line at a near-tangent join of a
6-decimal program is 8.1e-8 mm long and both its ends are tangent breaks,
so the planner stops at both; the grid's least spacing (1e-7) leaves no
gridpoint between them, and the planner refused the path ("two stops one
grid interval apart"). Such a stretch is one straight segment: the exact
S-curve stands in for it (ccopt.feed.jerk.planner.lone_lines).
"""
from __future__ import annotations

import random
import warnings

import numpy as np
import pytest

from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.geometry import Line
from ccopt.program import read_text
from ccopt.verify.limits import LIMITS_TOL
from family_programs import family_program

OVER = 1 + LIMITS_TOL
ORDER_SLACK = 1e-9
STYLES = {"pmac": {}, "linuxcnc": {}, "siemens": {}, "heidenhain": {},
          "fagor-g137": {"start_end": "contour", "corner": "linear"},
          "fagor-g136": {"start_end": "contour", "corner": "circular"}}


def _path(seed: int, dialect: str, style: str) -> ExactPath | None:
    fp = family_program(seed, dialect)
    prog = read_text(fp.text, fp.file, dialect)
    try:
        return ExactPath(compensate(prog, style.split("-")[0], **STYLES[style]))
    except Exception:          # LinuxCNC's concave-corner refusal (test_family_generated)
        assert style == "linuxcnc"
        return None


def _limits(seed: int) -> AxisLimits:
    rng = random.Random(20_000 + seed)
    v, a = rng.uniform(50.0, 300.0), rng.uniform(500.0, 5000.0)
    j = a * rng.uniform(5.0, 50.0)
    return AxisLimits((v, v, v / 2), (a, a, a / 2), j=(j, j, j / 2))


def _check(path: ExactPath, lim: AxisLimits, what) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        prof = plan_feed(path, lim, planner="jerk")
    smp = prof.sample(1e-4)
    for name in ("axis_velocity_ratio", "axis_acceleration_ratio", "axis_jerk_ratio",
                 "feed_ratio"):
        assert getattr(smp, name).max() <= OVER, (what, name, getattr(smp, name).max())
    toppra = plan_feed(path, AxisLimits(lim.v, lim.a)).duration
    stop = plan_feed(path, lim, planner="stop").duration
    assert toppra * (1 - ORDER_SLACK) <= prof.duration <= stop * (1 + ORDER_SLACK), what


def test_a_corner_line_between_two_stops_one_grid_interval_long():
    path = _path(2, "heidenhain", "fagor-g137")
    # the path has a straight segment under twice the grid's least spacing
    # (1e-7) with a tangent break at both ends: a stretch of one interval
    breaks = np.flatnonzero(path.tangent_break)
    tiny = [k for k in range(len(path.segments))
            if isinstance(path.segments[k].geom, Line) and 0.0 < path.lengths[k] < 2e-7
            and k in breaks and k + 1 in breaks]
    assert tiny, "the generated path no longer has the stretch this test is about"
    lim = AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0),
                     j=(20000.0, 20000.0, 10000.0))
    _check(path, lim, "heidenhain seed 2, fagor G137")


@pytest.mark.slow
@pytest.mark.parametrize("dialect", ["sinumerik", "heidenhain"])
def test_jerk_planner_on_generated_family_plates(dialect):
    for seed in range(5):
        for style in STYLES:
            path = _path(seed, dialect, style)
            if path is not None:
                _check(path, _limits(seed), (dialect, seed, style))


def test_a_blend_curve_run_at_rapid_plans_without_a_nan():
    # an optimised lead-out replacing a departure written at rapid (HEIDENHAIN
    # DEP LN then L ... FMAX) is a Bezier curve with no feed: its braking
    # measure met 0 * inf where the curve is straight for a moment (here at its
    # start: its first three control points lie on a line) and warned
    from ccopt.geometry import BezierCurve
    from ccopt.toolpath import PathSegment, Role, ToolPath
    curve = BezierCurve([(10.0, 0.0), (13.0, 0.0), (16.0, 0.0), (20.0, 4.0)])
    segs = (PathSegment(Line((0.0, 0.0), (10.0, 0.0)), Role.COMPENSATED, None, 0.0, 0.0, 50.0),
            PathSegment(curve, Role.LEAD_OUT, None, 0.0, 0.0, None))
    path = ExactPath(ToolPath(segs))
    lim = AxisLimits((200.0, 200.0), (2000.0, 2000.0), j=(20000.0, 20000.0))
    _check(path, lim, "a lead-out curve at rapid")
