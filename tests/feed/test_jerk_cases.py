"""The jerk planner on every bundled case (issue 18's acceptance).

Limits: each case's own ``v`` and ``a``, and axis jerk ``j = 10 a`` (ramps
of 0.1 s, a hard machine) where the case gives none. Sampled at 10 kHz no
axis exceeds its velocity, acceleration or jerk limit, nor the feed its
programmed F, by more than the certificate's tolerance (0.1 %,
:data:`ccopt.verify.limits.LIMITS_TOL`, which ``run`` certifies these
profiles with; measured: jerk at most 1 + 1.9e-4, feed 1 + 2.8e-4), and
the cycle time lies between TOPPRA's (fewer limits, so never slower) and the
jerk-limited stop baseline's (an S-curve per block, one feasible profile
among those the planner chooses from).
"""
from __future__ import annotations

import pytest

from ccopt.cases import bundled_cases, resolve_input
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.verify.limits import LIMITS_TOL

OVER = 1 + LIMITS_TOL
#: The jerk planner's profile is exact between gridpoints but for the margins its
#: module docstring states; TOPPRA's samples its own way: a relative slack of
#: rounding size on the ordering of cycle times.
ORDER_SLACK = 1e-9

CASES = [c for c in bundled_cases() if c.expect != "error"]


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_jerk_planner_on_bundled_case(case):
    job = resolve_input(case)
    path = ExactPath(job.compensate(job.read()))
    j = job.jmax or tuple(10.0 * a for a in job.amax)
    lim = AxisLimits(job.vmax, job.amax, j=j)
    prof = plan_feed(path, lim, planner="jerk")
    smp = prof.sample(1e-4)
    assert smp.axis_velocity_ratio.max() <= OVER
    assert smp.axis_acceleration_ratio.max() <= OVER
    assert smp.axis_jerk_ratio.max() <= OVER
    assert smp.feed_ratio.max() <= OVER
    toppra = plan_feed(path, AxisLimits(job.vmax, job.amax)).duration
    stop = plan_feed(path, lim, planner="stop").duration
    assert toppra * (1 - ORDER_SLACK) <= prof.duration <= stop * (1 + ORDER_SLACK)


@pytest.mark.slow
def test_straight_interval_speed_peak_within_the_certificates_tolerance():
    # On freeform-hsm's PMAC path (its own jerk limits) the path acceleration falls
    # through 0 inside straight grid intervals, where the speed, and the path jerk
    # with it, peak above both gridpoints: 0.169 % over the jerk limit before such
    # rows were tightened, which failed `ccopt verify --feed` (tolerance 0.1 %) and so
    # the main job on this case. The peak is now covered: within rounding at 10 kHz.
    from ccopt.cases import find_case
    job = resolve_input(find_case("freeform-hsm"))
    path = ExactPath(job.compensate(job.read()))
    prof = plan_feed(path, AxisLimits(job.vmax, job.amax, j=job.jmax), planner="jerk")
    assert prof.sample(1e-4).axis_jerk_ratio.max() <= 1.0 + 1e-4


@pytest.mark.slow
def test_speed_peak_inside_a_line_interval_stays_under_the_feed():
    # sinumerik-sar-plate at F600 (10 mm/s) under j = 10 a: on its 60 mm line the
    # path acceleration fell through 0 between two gridpoints both at the cap
    # (s = 261.2753 and 261.3053), and the speed peaked between them at 1.00112 of
    # the programmed feed, over the certificate's 0.1 %. The peak's closed form
    # b_k + alpha_k^2 h / (alpha_k - alpha_k+1) is below b_k + h alpha_k, which the
    # LP now bounds by the cap on straight intervals.
    from ccopt.cases import find_case
    job = resolve_input(find_case("sinumerik-sar-plate"))
    prog = job.read()
    assert {b.feed for b in prog.blocks if b.feed is not None} >= {10.0}
    path = ExactPath(job.compensate(prog))
    lim = AxisLimits(job.vmax, job.amax, j=tuple(10.0 * a for a in job.amax))
    prof = plan_feed(path, lim, planner="jerk")
    assert prof.sample(1e-4).feed_ratio.max() <= 1.0 + 2e-4
