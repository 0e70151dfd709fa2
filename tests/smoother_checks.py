"""Checks of a smoothed path shared by the smoother's tests: the limits they
time under, a generated plate's comparison with its smoother row held to the
comparison's promise and started from the faster of two controller paths,
whether two paths lie within a band of each other
(dense samples), and the joins left without curvature continuity near given
points."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

import ccopt
from ccopt.compare import BlendProblem, compare
from ccopt.compare.baseline import SAME_TIME_REL
from ccopt.compare.contract import CONTROLLER_NAMES
from ccopt.compare.figures import joins
from ccopt.feed import certified_planner, plan_feed
from ccopt.program import read_text
from ccopt.toolpath import Role
from ccopt_formulations.smoother import smooth

from cam_programs import cam_program

#: Limits (b) of issue 30: mm/s, mm/s^2, mm/s^3 per axis.
LIMITS = ccopt.AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0),
                          j=(20000.0, 20000.0, 10000.0))
#: Spacing (mm) of the samples for the band check (a sampled distance is at
#: most half a spacing above the true one).
SPACING = 2e-4



def program(seed: int):
    """``(cam_program(seed), the program read)``."""
    cp = cam_program(seed)
    return cp, read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)


def smooth_row(seed: int):
    """``(cp, comparison, smooth row)`` of the generated plate ``seed``: the
    controller variants and the smoother under :data:`LIMITS` in 2 workers,
    the smoother row asserted certified and no slower than the fastest
    certified controller variant (relative ``SAME_TIME_REL``)."""
    cp, prog = program(seed)
    cmp = compare(prog, list(CONTROLLER_NAMES) + ["smooth"], limits=LIMITS,
                  radius=cp.radius, workers=2)
    timed = [r for r in cmp if r.name in CONTROLLER_NAMES and r.status == "ok"]
    best = min(timed, key=lambda r: r.figures["duration"])
    row = cmp["smooth"]
    assert row.status == "ok" and row.certificate.ok, (cp.description, row.message)
    assert row.figures["duration"] <= best.figures["duration"] * (1 + SAME_TIME_REL), \
        cp.description
    return cp, cmp, row


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


def faster_start_holds(seed: int, got) -> str | None:
    """The ``smooth`` row of plate ``seed``'s comparison ``got`` (as
    :func:`smooth_row` gives it) started from the faster of the fastest
    controller's path and LinuxCNC's, each smoothed on its own and planned
    whole here (the row's cycle time the smaller, within :data:`PLAN_REL`),
    and says which; returns ``row.info["started_from"]``."""
    cp, cmp, row = got
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


def _samples(path, spacing: float) -> np.ndarray:
    feed = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)
    pts = []
    for s in path.segments:
        if s.role in feed and s.length > 0:
            n = max(2, int(np.ceil(s.length / spacing)) + 1)
            pts.append(np.asarray(s.geom.point(np.linspace(0.0, s.length, n)), float)
                       .reshape(-1, 2))
    return np.vstack(pts)


def within_band(path, ref, delta: float) -> bool:
    """Each path within ``delta`` of the other, on dense samples of both."""
    a, b = _samples(path, SPACING), _samples(ref, SPACING)
    return bool(cKDTree(b).query(a)[0].max() <= delta + SPACING
                and cKDTree(a).query(b)[0].max() <= delta + SPACING)


def unsmooth_joins_near(path, points, within: float = 1e-3) -> list:
    """Joins of ``path`` that are not curvature continuous (G0 or G1) within
    ``within`` of any of ``points``."""
    if not points:
        return []
    tree = cKDTree(np.asarray(points, float))
    bad = []
    for i, cls, _gap, _ang, _jump in joins(path):
        if cls in ("G0", "G1") and tree.query(path.segments[i].start)[0] <= within:
            bad.append((i, cls))
    return bad
