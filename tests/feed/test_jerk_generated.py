"""The jerk planner over generated CAM programs (tests/cam_programs.py).

Each program's PMAC path (100 seeds), and the LinuxCNC, Fagor, SINUMERIK
and HEIDENHAIN styles' paths (30 seeds each), are planned under limits
drawn from the seed (v 50-300 mm/s, a 500-5000 mm/s^2, j 5-50 times a,
F600 as the generator writes). Properties, independent of how the planner grids the path:

* sampled at 10 kHz no axis exceeds its velocity, acceleration or jerk limit,
  nor the path speed its programmed feed, by more than the certificate's
  tolerance (:data:`ccopt.verify.limits.LIMITS_TOL`);
* the cycle time lies between TOPPRA's (fewer limits) and the jerk-limited
  stop baseline's (an S-curve per block, a feasible profile).

Before the planner held its squared speeds in their own units and split
curved intervals over the jerk limit (ccopt.feed.jerk.refine), seeds 127
and 155 went 1.0 % and 0.28 % over the jerk limit.
"""
from __future__ import annotations

import random

import pytest

from cam_programs import cam_program
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.program import read_text
from ccopt.verify.limits import LIMITS_TOL

OVER = 1 + LIMITS_TOL
ORDER_SLACK = 1e-9


#: The controller styles whose paths are planned besides PMAC's (each a path
#: the comparison times: their corners and leads differ).
OTHER_STYLES = ("linuxcnc", "fagor", "siemens", "heidenhain")


def _path_and_limits(seed: int, style: str = "pmac"):
    cp = cam_program(seed)
    prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    rng = random.Random(10_000 + seed)
    v, a = rng.uniform(50.0, 300.0), rng.uniform(500.0, 5000.0)
    j = a * rng.uniform(5.0, 50.0)
    return cp.description, ExactPath(compensate(prog, style)), AxisLimits((v, v), (a, a), j=(j, j))


def _check(seed: int, style: str = "pmac") -> None:
    what, path, lim = _path_and_limits(seed, style)
    prof = plan_feed(path, lim, planner="jerk")
    smp = prof.sample(1e-4)
    for name in ("axis_velocity_ratio", "axis_acceleration_ratio", "axis_jerk_ratio",
                 "feed_ratio"):
        assert getattr(smp, name).max() <= OVER, (seed, style, what, name,
                                                  getattr(smp, name).max())
    toppra = plan_feed(path, AxisLimits(lim.v, lim.a)).duration
    stop = plan_feed(path, lim, planner="stop").duration
    assert toppra * (1 - ORDER_SLACK) <= prof.duration <= stop * (1 + ORDER_SLACK), (seed, style,
                                                                                  what)


# 104: a corner arc of sweep 6.5e-8 rad next to a stop, whose gridpoints 3.8e-9 mm
# apart stalled the planner (zero speed away from the stop) on a coarser grid
@pytest.mark.parametrize("seed", [4, 104, 127])
def test_jerk_planner_on_generated_cam_programs_quick(seed):
    _check(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 200))
def test_jerk_planner_on_generated_cam_programs_100(seed):
    _check(seed)


@pytest.mark.parametrize("style", OTHER_STYLES)
def test_jerk_planner_on_other_styles_paths_quick(style):
    _check(101, style)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 130))
@pytest.mark.parametrize("style", OTHER_STYLES)
def test_jerk_planner_on_other_styles_paths(style, seed):
    _check(seed, style)
