"""The smoother judged under jerk limits (issue 18 item 5 and its last acceptance item).

On ``pocket-chords`` (jerk ``j = 10 a``, ramps of 0.1 s, as tests/feed/test_jerk_cases.py
takes for cases that give none) and on ``freeform-hsm`` (its own ``[limits] j``), the
smoother at ``delta`` = 1 % of the cutter radius is certified, stays within ``delta`` of
PMAC's path both ways (measured here on dense samples of both paths), and runs at least
20 % faster than PMAC's path under the jerk planner.

Why this holds by construction of the two paths, not by tuning: at every tangent break
(an inside corner of the tool path) PMAC's path stops, and at every curvature jump (an
outside corner's arc meeting a chord) the jerk planner caps the speed at
``sqrt(J Ts / |Delta q''|)`` (``sqrt(20000 * 1e-3 * 3)`` = 7.7 mm/s into a 3 mm corner arc
of ``freeform-hsm``); the smoother's path is curvature continuous, so neither applies.
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial import cKDTree

import ccopt
from ccopt.cases import find_case
from ccopt.compare import BlendProblem
from ccopt.feed import feed_limited_time
from ccopt.geometry import BezierCurve
from ccopt.toolpath import Role
from ccopt.verify.limits import LIMITS_TOL
from ccopt_formulations.smoother import smooth

import blend_checks as bc

#: Spacing (mm) of the samples of both paths for the band check. A sampled distance is
#: never below the true one, so asserting it <= delta is conservative.
SPACING = 2e-4
FEED_ROLES = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)
#: Sampled at 10 kHz no axis exceeds a limit by more than the certificate's tolerance
#: (0.1 %, what `ccopt verify --feed` and `run` hold the jerk planner's profiles to;
#: issue 18's acceptance allowed 0.5 %).
OVER = 1.0 + LIMITS_TOL


def _samples(path) -> np.ndarray:
    """Points of every feed segment of ``path`` at most :data:`SPACING` apart."""
    out = []
    for s in path.segments:
        if s.role not in FEED_ROLES or s.length <= 0:
            continue
        n = max(2, int(np.ceil(s.length / SPACING)) + 1)
        if isinstance(s.geom, BezierCurve):
            # by the curve parameter: a blend's speed in t varies by less than a factor 4
            out.append(bc.bezier_points(s.geom, 4 * n))
        else:
            out.append(np.asarray(s.geom.point(np.linspace(0.0, s.length, n)), float))
    return np.vstack(out)


def _jerk_limits(case):
    j = case.jmax or tuple(10.0 * a for a in case.amax)
    return ccopt.AxisLimits(case.vmax, case.amax, j=j)


def _plan_jerk(path, limits):
    return ccopt.plan_feed(path, limits, planner="jerk")


@pytest.mark.slow
@pytest.mark.parametrize("name", ["pocket-chords", "freeform-hsm"])
def test_smoother_is_20_percent_faster_under_jerk(name):
    # (the jerk planner's overlapping windows once found this path infeasible
    # from lead-in to lead-out; a failing window is now merged with the one
    # before it: planned here with the planner's default windows)
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    ref = ccopt.compensate(prog, "pmac")
    limits = _jerk_limits(case)
    delta = 0.01 * ref.radius
    path, info = smooth(BlendProblem(prog, ref, limits), delta)
    # certified: no gouge, contact, side, continuity
    assert info["certificate"].ok
    assert info["joins_blended"] == info["joins_found"]
    # the band, both ways, measured on the geometry: every point of a blend within delta
    # of PMAC's path, every point of PMAC's path within delta of the smoothed one
    ref_pts, new_pts = _samples(ref), _samples(path)
    blend_pts = np.vstack([bc.bezier_points(s.geom, 801) for s in path.segments
                           if isinstance(s.geom, BezierCurve)])
    assert float(cKDTree(ref_pts).query(blend_pts)[0].max()) <= delta
    assert float(cKDTree(new_pts).query(ref_pts)[0].max()) <= delta
    # no gouge, from the contour itself
    assert float(bc.dist_to(blend_pts, bc.contour(prog)).min()) >= ref.radius - 1e-6
    # under jerk limits: at least 20 % below PMAC's cycle time, within every limit
    t_ref = _plan_jerk(ref, limits).duration
    prof = _plan_jerk(path, limits)
    smp = prof.sample(1e-4)
    assert smp.axis_velocity_ratio.max() <= OVER
    assert smp.axis_acceleration_ratio.max() <= OVER
    # (the blend curves' jerk between the LP's gridpoints too: inner rows, coarser grid)
    assert smp.axis_jerk_ratio.max() <= OVER
    assert prof.duration <= 0.8 * t_ref
    # and no faster than the programmed feed allows along the smoothed path
    assert prof.duration > feed_limited_time(path, limits)


@pytest.mark.slow
def test_smooth_command_reports_jerk_cycle_times(capsys):
    # leadin-inside-line: PMAC's path stops at the lead-in's inside corner, the smoothed
    # one does not; with jerk limits both are planned by the jerk planner as well
    from ccopt.cli import main
    code = main(["smooth", "leadin-inside-line", "--jmax", "5000,5000,2000", "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    doc = json.loads(out)
    t, t_ref, floor = doc["jerk_duration"], doc["pmac_jerk_duration"], doc["feed_floor"]
    # more limits than TOPPRA's: never faster than its cycle time, on either path
    assert t >= doc["duration"] * (1 - 1e-9) and t_ref >= doc["pmac_duration"] * (1 - 1e-9)
    assert floor < t < t_ref
    assert doc["jerk_duration_ratio"] == pytest.approx(t / t_ref, rel=1e-12)
    assert doc["jerk_share_of_gain"] == pytest.approx((t_ref - t) / (t_ref - floor), rel=1e-12)
    assert 0 < doc["jerk_share_of_gain"] < 1
    code = main(["smooth", "leadin-inside-line", "--jmax", "5000,5000,2000"])
    out, _ = capsys.readouterr()
    assert code == 0 and "under jerk limits:" in out and "share of the possible gain" in out
    # without jerk limits, no jerk figures
    assert main(["smooth", "leadin-inside-line", "--json"]) == 0
    assert "jerk_duration" not in json.loads(capsys.readouterr()[0])
