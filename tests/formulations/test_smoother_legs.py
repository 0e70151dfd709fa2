"""One leg of a symmetric corner blend grows where the band leaves it room.

The smoother's closed-form search grows both legs of a blend together, so at
a lead's join it stops where the tighter side stops; the other side may
still have room (formulations/smoother_joins.py, ``grow_one_leg``). Checked
on a generated plate (seed 8: a rectangle entered at a corner by
perpendicular leads, LinuxCNC's path the fastest controller variant there)
against the same smoother with symmetric legs only: at both leads' joins one
leg is the symmetric blend's and the other 1.25 or 1.5 times it, the path
is certified and within the band of the path it smooths, and the planner
times it faster under jerk limits.
"""
from __future__ import annotations

import pytest

import ccopt
import ccopt_formulations.smoother_joins as smoother_joins
from ccopt.compare import BlendProblem
from ccopt.feed import certified_planner, plan_feed
from ccopt_formulations.smoother import smooth

from smoother_checks import LIMITS, program, within_band


def _smoothed(prog, ref, cp):
    path, info = smooth(BlendProblem(prog, ref, LIMITS, radius=cp.radius), deviation=False,
                        certifiable=True)
    assert info["certificate"].ok
    lead_joins = {j["segment"]: j for j in info["joins"]
                  if j["kind"] == "tangent-break" and j["angle"] > 1.0}
    return path, lead_joins, plan_feed(path, LIMITS, planner=certified_planner(LIMITS)).duration


def test_a_lead_join_blend_grows_one_leg_and_is_faster(monkeypatch):
    cp, prog = program(8)
    ref = ccopt.compensate(prog, "linuxcnc", radius=cp.radius)
    grown, joins, t_grown = _smoothed(prog, ref, cp)
    monkeypatch.setattr(smoother_joins, "LEG_GROWTH", ())
    symmetric, joins_sym, t_sym = _smoothed(prog, ref, cp)
    assert len(joins) == 2 and joins.keys() == joins_sym.keys()     # the two leads' joins
    for k, j in joins.items():
        s = joins_sym[k]
        assert s["share"] == [1.0, 1.0] and s["l_in"] == s["l_out"]
        assert j["share"] != [1.0, 1.0]
        legs = sorted((j["l_in"], j["l_out"]))
        assert legs[0] == s["l_in"]
        assert legs[1] / legs[0] in (pytest.approx(1.25, rel=1e-12), pytest.approx(1.5, rel=1e-12))
    delta = 0.01 * cp.radius
    assert within_band(grown, ref, delta)
    assert t_grown < t_sym
