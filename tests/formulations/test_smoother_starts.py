"""The ``smooth`` variant smooths LinuxCNC's path too and keeps the faster.

The comparison hands the smoother the fastest certified controller path;
where that is not LinuxCNC's and LinuxCNC's path is certified, the variant
also smooths LinuxCNC's (whose entry joins the contour as at a corner,
docs/compensation.md LinuxCNC rules 1 and 2) and keeps the faster certified
result (formulations/smoother_variant.py).

Checked against figures made here independently: each start smoothed on its
own (:func:`ccopt_formulations.smoother.smooth`, from that controller's
compensated path) and planned whole by the certified planner. The row's
cycle time is the smaller of the two (within the jerk planner's difference
between a whole-path plan and the comparison's stretch-by-stretch one), the
row says which path it started from, and it is certified and never slower
than the fastest controller variant (``smooth_row``).
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.compare import BlendProblem
from ccopt.feed import certified_planner, plan_feed
from ccopt_formulations.smoother import smooth

from smoother_checks import LIMITS, program, smooth_row

#: Relative difference allowed between a whole-path plan and the comparison's
#: plan by stretches under the jerk planner (its windows stop their rounds
#: on a squared-speed tolerance; TOPPRA agrees to 1e-9).
PLAN_REL = 1e-6


def _smoothed_time(prog, path, cp) -> float:
    """The smoother's path from ``path`` (certified), planned whole."""
    out, info = smooth(BlendProblem(prog, path, LIMITS, radius=cp.radius), deviation=False,
                       certifiable=True)
    assert info["certificate"].ok, cp.description
    return plan_feed(out, LIMITS, planner=certified_planner(LIMITS)).duration


def _base(row) -> str:
    """The controller path a row started from (PMAC's, the reference, is not named)."""
    return row.info.get("base", "pmac")


def _check(seed: int):
    cp, cmp, row = smooth_row(seed)
    prog = program(seed)[1]
    fastest = cmp[row.figures["fastest_controller"]]
    linuxcnc = cmp["linuxcnc"]
    t_row = row.figures["duration"]
    if fastest.name == "linuxcnc" or linuxcnc.status != "ok":
        # nothing else to start from: the fastest controller's path alone
        assert "started_from" not in row.info and _base(row) == fastest.name
        assert t_row == pytest.approx(_smoothed_time(prog, fastest.toolpath, cp), rel=PLAN_REL)
        return None
    t_given = _smoothed_time(prog, fastest.toolpath, cp)
    t_linuxcnc = _smoothed_time(prog, linuxcnc.toolpath, cp)
    assert t_row == pytest.approx(min(t_given, t_linuxcnc), rel=PLAN_REL), cp.description
    started = row.info.get("started_from")
    if t_linuxcnc < t_given * (1 - 2 * PLAN_REL):
        assert started == "linuxcnc" and row.info["base"] == "linuxcnc"
        assert row.message.startswith("started from linuxcnc's path (a certified controller "
                                      f"variant; the fastest is {fastest.name}'s)")
    elif t_given < t_linuxcnc * (1 - 2 * PLAN_REL):
        assert started is None and _base(row) == fastest.name
    return started


def test_linuxcncs_path_smoothed_is_kept_where_it_is_faster():
    # seed 5 (a 3-gon, arc leads): Fagor's G138 path is the fastest controller
    # variant, LinuxCNC's smoothed the faster (worked out in _check)
    assert _check(5) == "linuxcnc"


def test_the_fastest_path_alone_where_it_is_linuxcncs():
    # seed 1: LinuxCNC's path is the fastest controller variant itself
    assert _check(1) is None


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(30))     # bench/blend_gains.py: 200 plates, (a) and (b)
def test_generated_plates_keep_the_faster_start(seed):
    _check(seed)
