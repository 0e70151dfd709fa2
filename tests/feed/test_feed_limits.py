"""Limits hold on every bundled case and on random compensated contours.

Sampled at 1 kHz: no axis velocity or acceleration over its limit (the
baselines' closed-form profiles by rounding at most, TOPPRA's by at most
toppra's own feasibility tolerance), the speed is 0 at every tangent
discontinuity (and dwell), the feed never exceeds the programmed F; and the
TOPPRA profile is never slower than either baseline on the same path and
limits.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ccopt
from ccopt.cases import bundled_cases
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _contours import contour_program, random_limits
from _tolerances import OVER

FEED_ROUNDING = 1e-9
#: TOPPRA vs a baseline: toppra's forward pass lowers each squared speed by
#: 1e-8 (toppra.constants.TINY) as a numerical margin. In the planner's time
#: unit (squared cruise speed about 1 on the fastest cut, see
#: ccopt.feed.toppra.planner.speed_scale) slower cuts and the starts from rest
#: feel it more: up to 5e-7 of the duration seen on random contours.
NEVER_SLOWER = 1e-6
PLANNERS = ("toppra", "stop", "junction")

CASES = [c for c in bundled_cases() if c.expect != "error"]


def check_profile(path: ExactPath, prof, dt=1e-3):
    smp = prof.sample(dt)
    over = OVER[prof.planner]
    assert smp.axis_velocity_ratio.max() <= over, prof.planner
    assert smp.axis_acceleration_ratio.max() <= over, prof.planner
    # feed never above the programmed F (rapids: no feed cap)
    assert smp.feed_ratio.max() <= 1 + FEED_ROUNDING, prof.planner
    # ... also exactly at every knot, where the speed peaks between samples
    move = prof.segment >= 0
    caps = path.feeds[prof.segment[move]]
    assert np.all(prof.sd[:-1][move] <= caps * (1 + FEED_ROUNDING))
    assert np.all(prof.sd[1:][move] <= caps * (1 + FEED_ROUNDING))
    # speed 0 at every tangent discontinuity (found here from the geometry)
    breaks = tangent_breaks(path.toolpath)
    assert np.all(prof.speed_at(breaks) == 0.0), (prof.planner, breaks)
    # (each is one of the planner's own stops)
    near = np.min(np.abs(breaks[:, None] - np.asarray(path.stop_positions)[None, :]), axis=1,
                  initial=np.inf)
    assert np.all(near <= 1e-9), (breaks, path.stop_positions)
    # ... and dwell, and at both ends
    stops = np.r_[0.0, path.stop_positions, path.length]
    assert np.all(prof.speed_at(stops) == 0.0), prof.planner
    # ... and the profile has a knot there at which it is at rest
    for s in path.stop_positions:
        at = np.flatnonzero(prof.s == s)
        assert at.size and np.all(prof.sd[at] == 0.0), (prof.planner, s)
    # a dwell holds still for its duration
    if path.dwells:
        assert prof.duration >= prof.dwell_time
        held = (smp.segment < 0)
        assert np.all(smp.feed[held] == 0.0)
    return smp


def tangent_breaks(toolpath, angle=1e-6, gap=1e-9) -> np.ndarray:
    """Arc-length positions (3-D, as the feed path counts them) where two
    consecutive moving segments of ``toolpath`` do not meet tangentially,
    from the primitives' own tangents: in-plane ``geom.tangent`` and the
    out-of-plane slope ``(w1 - w0) / L`` (the third coordinate is linear in
    the in-plane arc length ``L``)."""
    out, pos, prev = [], 0.0, None
    for seg in toolpath.segments:
        L = seg.geom.length
        dw = seg.w1 - seg.w0
        L3 = float(np.hypot(L, dw))
        if L3 <= gap:
            continue
        t0 = np.r_[np.asarray(seg.geom.tangent(0.0)) * L, dw] / L3 if L > 0 else \
            np.array([0.0, 0.0, np.sign(dw)])
        t1 = np.r_[np.asarray(seg.geom.tangent(L)) * L, dw] / L3 if L > 0 else t0
        start = np.r_[seg.start, seg.w0]
        if prev is not None:
            end_prev, t_prev = prev
            jump = float(np.linalg.norm(start - end_prev))
            turn = float(np.arccos(np.clip(t_prev @ t0, -1.0, 1.0)))
            if jump > gap or turn > angle:
                out.append(pos)
        prev = (np.r_[seg.end, seg.w1], t1)
        pos += L3
    return np.asarray(out)


def plan_all(path, limits, **kw):
    return {name: plan_feed(path, limits, planner=name, **kw) for name in PLANNERS}


def check_toppra_fastest(profiles):
    T = profiles["toppra"].duration
    for name in ("stop", "junction"):
        assert T <= profiles[name].duration * (1 + NEVER_SLOWER), \
            f"toppra {T} slower than {name} {profiles[name].duration}"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_bundled_case(case):
    prog = ccopt.read_program(case.program)
    path = ExactPath(compensate(prog, case.style, radius=case.radius))
    limits = AxisLimits(case.vmax, case.amax)
    profiles = plan_all(path, limits)
    for prof in profiles.values():
        check_profile(path, prof)
    check_toppra_fastest(profiles)


@pytest.mark.slow
@settings(max_examples=12, deadline=None)
@given(st.integers(0, 2 ** 32 - 1))
def test_random_compensated_contours(seed):
    rng = np.random.default_rng(seed)
    prog = contour_program(rng)
    path = ExactPath(compensate(prog, "pmac"))
    limits = random_limits(rng)
    profiles = plan_all(path, limits)
    for prof in profiles.values():
        check_profile(path, prof)
    check_toppra_fastest(profiles)


@settings(max_examples=6, deadline=None)
@given(st.integers(0, 2 ** 32 - 1))
def test_random_contours_with_path_limits(seed):
    """The tangential and centripetal limits hold too, in every planner."""
    rng = np.random.default_rng(seed)
    path = ExactPath(compensate(contour_program(rng, plunge=False), "pmac"))
    base = random_limits(rng)
    limits = AxisLimits(base.v[:2], base.a[:2], tangential_acc=float(rng.uniform(100, 800)),
                        centripetal_acc=float(rng.uniform(100, 800)))
    profiles = plan_all(path, limits)
    for prof in profiles.values():
        smp = check_profile(path, prof)
        assert np.abs(smp.tangential_acc).max() <= limits.tangential_acc * OVER[prof.planner]
        assert (smp.curvature * smp.feed ** 2).max() <= limits.centripetal_acc * OVER[prof.planner]
    check_toppra_fastest(profiles)
