"""The certificate's limits check covers the axis jerk, at the samples and
between them, with the same relative tolerance as velocity and acceleration.

Figures derived here:

- an acceleration ramp a(t) = J t sampled every 1 ms changes by J * 1 ms
  between samples, so its jerk is J at and between the samples: within a
  limit of J, over one of J / 1.002 by 0.2 % (more than the 0.1 % tolerance,
  less than a 0.5 % one);
- an acceleration step of 10 units/s^2 between two samples 1 ms apart is a
  jerk of 10,000 between them, whatever the samples' own jerk says (0);
- rest to rest over 50 mm along X with v = 100, a = 1000, j = 20000 the
  S-curve per block has jerk +-20000 in its jerk phases (ratio 1), and
  TOPPRA's trapezoid steps its acceleration from 0 to 1000 between two
  samples 1 ms apart: 1000 / 1e-3 = 50 times the jerk limit.
"""
from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pytest

from ccopt.cli import main
from ccopt.feed import AxisLimits, plan_feed
from ccopt.geometry import Line
from ccopt.toolpath import PathSegment, Role, ToolPath
from ccopt.verify.limits import check_limits

J = 20000.0


def ramp(j_limit, with_jerk=True):
    t = np.arange(0.0, 0.05 + 1e-12, 1e-3)
    acc = np.c_[J * t, np.zeros_like(t)]
    vel = np.c_[0.5 * J * t * t, np.zeros_like(t)]
    jerk = np.c_[np.full_like(t, J), np.zeros_like(t)] if with_jerk else None
    return SimpleNamespace(t=t, velocity=vel, acceleration=acc, jerk=jerk,
                           v_limit=np.array([100.0, 100.0]), a_limit=np.array([1000.0, 1000.0]),
                           j_limit=np.array([j_limit, j_limit]))


def test_jerk_within_its_limit_passes():
    check, viol = check_limits(ramp(J))
    assert check.ok and not viol
    assert check.figure == pytest.approx(1.0, rel=1e-9)


def test_jerk_over_its_limit_fails_beyond_the_tolerance():
    check, viol = check_limits(ramp(J / 1.002))
    assert not check.ok
    assert check.figure == pytest.approx(1.002, rel=1e-9)
    assert {v.kind for v in viol} == {"jerk"}
    assert viol[0].detail["limit"] == pytest.approx(J / 1.002)
    # the same stated tolerance as the other limits: 0.5 % lets 0.2 % pass
    assert check_limits(ramp(J / 1.002), rel_tol=5e-3)[0].ok


def test_jerk_between_samples_from_the_acceleration():
    """Samples without jerk: the ramp's change between samples is the jerk."""
    assert check_limits(ramp(J, with_jerk=False))[0].ok
    check, _ = check_limits(ramp(J / 1.002, with_jerk=False))
    assert not check.ok and check.figure == pytest.approx(1.002, rel=1e-9)


def test_acceleration_step_fails_between_samples():
    t = np.array([0.0, 1e-3, 2e-3, 3e-3])
    acc = np.c_[[0.0, 0.0, 10.0, 10.0], np.zeros(4)]
    smp = SimpleNamespace(t=t, velocity=np.zeros((4, 2)), acceleration=acc, jerk=np.zeros((4, 2)),
                          v_limit=np.ones(2), a_limit=np.full(2, 100.0),
                          j_limit=np.full(2, 9000.0))
    check, viol = check_limits(smp)
    assert not check.ok
    assert check.figure == pytest.approx(10000.0 / 9000.0, rel=1e-9)
    assert viol[0].detail["quantity"] == "U between samples"
    smp.j_limit = np.full(2, 10000.0)
    assert check_limits(smp)[0].ok


def test_planned_profiles_under_jerk_limits():
    tp = ToolPath((PathSegment(Line((0, 0), (50, 0)), Role.COMPENSATED, None, 0.0, 0.0, 1000.0),))
    lim = AxisLimits((100, 100), (1000, 1000), j=(J, J))
    check, _ = check_limits(plan_feed(tp, lim, planner="stop"))
    assert check.ok and check.figure == pytest.approx(1.0, rel=1e-9)
    check, _ = check_limits(plan_feed(tp, lim, planner="toppra"))
    assert not check.ok
    assert check.figure == pytest.approx(1000.0 / 1e-3 / J, rel=1e-6)


def test_verify_feed_certifies_the_jerk_planner_under_jerk_limits(capsys):
    # with --jmax the certificate checks jerk, so `verify --feed` must certify
    # the jerk planner's profile: TOPPRA's (acceleration steps) would fail it
    code = main(["verify", "leadin-inside-line", "--feed", "--jmax", "20000,20000", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0 and doc["limits_ok"]
    limits = next(c for c in doc["checks"] if c["name"] == "limits")
    assert "jerk" in limits["requirement"] and limits["figure"] <= 1.0 + doc["limits_tol"]
