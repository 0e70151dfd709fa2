"""Cycle times by stretches between stops (ccopt.compare.timing), workers and progress.

The stretch rule is checked against the planner's own stop caps, and the
windowed cycle time of each variant against TOPPRA (or the jerk planner) run
on that variant's whole path, planned here independently.
"""
from __future__ import annotations

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import GivenReference, compare
from ccopt.compare.timing import StretchTimes, stops, stretch_key, stretches
from ccopt.feed import ExactPath
from ccopt.feed.junction import boundary_speed_caps

#: toppra's own margin: its forward pass lowers squared speeds by up to 1e-8,
#: "a few 1e-7 of the duration at most" (ccopt.feed.toppra.planner); a stretch
#: planned alone runs in another time unit, so the two agree to that margin.
TOPPRA_MARGIN = 1e-6

VARIANTS = ["pmac", "linuxcnc", "fagor-g139-g137", "tangent-arc", "line-arc"]


def _case(name):
    c = find_case(name)
    return c, ccopt.read_program(c.program)


@pytest.mark.parametrize("name", ["z-plunges", "pocket", "fagor-g136-g138", "leadin-inside-line"])
def test_stops_are_the_planner_zero_speed_caps(name):
    c, prog = _case(name)
    exact = ExactPath(ccopt.compensate(prog, "pmac", radius=c.radius))
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    _, a = limits.in_plane(exact.toolpath.plane, exact.dof)
    caps = boundary_speed_caps(exact, a, None)
    assert list(stops(exact)) == list(np.flatnonzero(caps == 0.0))
    # the stretches tile the path, each between two consecutive stops
    st = stretches(exact)
    assert st[0].s0 == 0.0 and st[-1].s1 == pytest.approx(exact.length, abs=0.0)
    assert all(a.s1 == b.s0 for a, b in zip(st[:-1], st[1:]))


def test_reference_stretch_times_add_up_to_the_whole_path():
    # z-plunges: 3-D moves and a dwell (its seconds are added once)
    c, prog = _case("z-plunges")
    ref = ccopt.compensate(prog, "pmac", radius=c.radius)
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    times, duration, _ = StretchTimes.from_reference(ref, limits)
    whole = ccopt.plan_feed(ref, limits)
    assert duration == whole.duration
    exact = ExactPath(ref)
    dwell = sum(d.seconds for d in exact.dwells)
    assert dwell > 0
    parts = [times.known[stretch_key(exact.segments[s.k0:s.k1])] for s in stretches(exact)]
    assert sum(p[0] for p in parts) + dwell == pytest.approx(whole.duration, rel=1e-12)
    assert times.copy().time(ref)[0] == pytest.approx(whole.duration, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["z-plunges", "leadin-inside-line"])
def test_windowed_variant_time_equals_its_whole_path_time(name):
    c, prog = _case(name)
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    cmp = compare(prog, VARIANTS, limits=limits, radius=c.radius)
    checked = 0
    for row in cmp:
        if row.toolpath is None:
            continue
        whole = ccopt.plan_feed(row.toolpath, limits).duration
        assert row.figures["duration"] == pytest.approx(whole, rel=TOPPRA_MARGIN), row.name
        checked += 1
    assert checked >= 4


@pytest.mark.slow
def test_jerk_limits_give_jerk_planner_cycle_times():
    c, prog = _case("leadin-inside-line")
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=(20000.0, 20000.0))
    cmp = compare(prog, ["pmac", "tangent-arc"], limits=limits, radius=c.radius)
    assert cmp.to_json()["planner"] == "jerk"
    ref = ccopt.compensate(prog, "pmac", radius=c.radius)
    jerk = ccopt.plan_feed(ref, limits, planner="jerk").duration
    toppra = ccopt.plan_feed(ref, limits).duration
    assert cmp["pmac"].figures["duration"] == pytest.approx(jerk, rel=1e-12)
    assert cmp["pmac"].figures["duration"] > toppra      # more limits, more time
    # the lead variant, planned whole by the jerk planner; its windows group the
    # stretches differently, and its rounds stop at BHAT_TOL = 2e-3 on b
    whole = ccopt.plan_feed(cmp["tangent-arc"].toolpath, limits, planner="jerk").duration
    assert cmp["tangent-arc"].figures["duration"] == pytest.approx(whole, rel=2e-3)


def _rows(cmp):
    out = []
    for v in cmp.to_json()["variants"]:
        v = dict(v)
        v.pop("solve_time", None)
        v.get("info", {}).pop("solve_time", None)
        out.append(v)
    return out


@pytest.mark.slow
def test_workers_give_the_serial_rows():
    c, prog = _case("leadin-outside-line")
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    names = ["pmac", "linuxcnc", "tangent-arc", "line-arc", "fagor-g138"]
    serial = compare(prog, names, limits=limits, radius=c.radius)
    lines = []
    parallel = compare(prog, names, limits=limits, radius=c.radius, workers=2,
                       progress=lines.append)
    assert _rows(parallel) == _rows(serial)
    assert [v.name for v in parallel] == names
    # one line per variant, the reference's first
    assert lines[0] == "variant 1/5 pmac" and len(lines) == 5


def test_progress_names_each_variant_in_turn():
    c, prog = _case("leadin-outside-line")
    lines = []
    compare(prog, ["pmac", "tangent-arc"], limits=ccopt.AxisLimits(c.vmax, c.amax),
            radius=c.radius, progress=lines.append)
    assert lines == ["variant 1/2 pmac", "variant 2/2 tangent-arc"]


def _jerk_case(name):
    c, prog = _case(name)
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=tuple(10.0 * a for a in c.amax))
    return c, prog, limits


def test_ts_reaches_the_cycle_times():
    # leadin-inside-line has curvature breaks (line to arc), where the jerk
    # planner's acceleration step is at most jmax * ts: ts changes its time
    c, prog, limits = _jerk_case("leadin-inside-line")
    ref = ccopt.compensate(prog, "pmac", radius=c.radius)
    slow = ccopt.plan_feed(ref, limits, planner="jerk", ts=0.001).duration
    fast = ccopt.plan_feed(ref, limits, planner="jerk", ts=0.004).duration
    assert fast < slow * (1 - 1e-3)
    cmp = compare(prog, ["pmac"], limits=limits, radius=c.radius, ts=0.004)
    assert cmp["pmac"].figures["duration"] == pytest.approx(fast, rel=1e-12)


def test_the_callers_reference_plan_is_used_only_when_it_is_the_one_compare_makes(monkeypatch):
    # the caller gives PMAC's path with its plan (GivenReference: ccopt run's pipeline
    # does when the job's path is PMAC's); compare neither compensates nor plans it again
    import ccopt.compare.timing as timing
    c, prog, limits = _jerk_case("leadin-inside-line")
    ref = ccopt.compensate(prog, "pmac", radius=c.radius)
    names = ["pmac", "tangent-arc"]
    plain = compare(prog, names, limits=limits, radius=c.radius)
    own = ccopt.plan_feed(ref, limits, planner="jerk")
    other = ccopt.plan_feed(ref, limits, planner="jerk", ts=0.004)
    calls = []
    real = timing.plan_whole
    monkeypatch.setattr(timing, "plan_whole", lambda *a, **k: calls.append(1) or real(*a, **k))
    reused = compare(prog, names, limits=limits, radius=c.radius,
                     reference=GivenReference(ref, 0.0, own))
    assert calls == []                      # the reference was not planned again
    assert _rows(reused) == _rows(plain)
    # a plan under another ts (or other limits, or of another path object) is not the reference's
    ignored = compare(prog, names, limits=limits, radius=c.radius,
                      reference=GivenReference(ref, 0.0, other))
    assert calls == [1]
    assert _rows(ignored) == _rows(plain)


@pytest.mark.parametrize("workers", [1, 2])
def test_a_variant_with_anothers_path_takes_its_cycle_time_planned_once(monkeypatch, workers):
    # on leadin-inside-line Fagor's G138 and G139 with G136 build the same
    # path (checked here): one plan serves both, serial or in processes
    import ccopt.compare.schedule as core

    c, prog = _case("leadin-inside-line")
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    names = ["fagor-g138", "fagor-g139-g136", "tangent-arc"]
    calls = []
    if workers == 1:  # (a function of a test does not go to a worker process)
        plan = core._duration

        def counted(path, limits, times=None):
            calls.append(path)
            return plan(path, limits, times)

        monkeypatch.setattr(core, "_duration", counted)
    cmp = compare(prog, names, limits=limits, radius=c.radius, workers=workers)
    g138, g139 = cmp["fagor-g138"], cmp["fagor-g139-g136"]
    assert g138.toolpath == g139.toolpath
    assert g138.toolpath != cmp["tangent-arc"].toolpath
    assert g138.figures["duration"] == g139.figures["duration"] > 0.0
    # that cycle time is the path's own, planned whole here
    whole = ccopt.plan_feed(g139.toolpath, limits).duration
    assert g139.figures["duration"] == pytest.approx(whole, rel=TOPPRA_MARGIN)
    if workers == 1:
        assert sum(path == g138.toolpath for path in calls) == 1


def test_ts_reaches_the_cycle_times_when_pmac_refuses_the_program(monkeypatch):
    # without a reference every variant is planned whole: with ts all the same
    import ccopt.compare.core as core

    c, prog, limits = _jerk_case("leadin-inside-line")
    real = core.compensate

    def refusing(program, style, **kw):
        if style == core.REFERENCE:
            raise ccopt.CcoptError("refused here")
        return real(program, style, **kw)

    monkeypatch.setattr(core, "compensate", refusing)
    path = ccopt.compensate(prog, "linuxcnc", radius=c.radius)
    for ts in (0.001, 0.004):
        cmp = compare(prog, ["pmac", "linuxcnc"], limits=limits, radius=c.radius, ts=ts)
        assert cmp["pmac"].status == "refused"
        own = ccopt.plan_feed(path, limits, planner="jerk", ts=ts).duration
        assert cmp["linuxcnc"].figures["duration"] == pytest.approx(own, rel=1e-9)
    slow = ccopt.plan_feed(path, limits, planner="jerk", ts=0.001).duration
    assert own < slow * (1 - 1e-3)          # ts does change this path's time


@pytest.mark.parametrize("style", ["linuxcnc", "fagor-g139-g137", "tangent-arc"])
def test_a_cycle_time_planned_before_the_reference_is_the_same(style):
    # a worker that times a variant before the reference is planned plans the
    # stretches it does not share, and takes the shared ones from the
    # reference's plan afterwards: the same figures, bit for bit, as timing it
    # with the reference's stretch times known
    from ccopt.compare.contract import BlendProblem
    from ccopt.compare.variant import solve as _solve
    from ccopt.compare.timing import PartialTime, stretch_keys
    c, prog = _case("freeform-hsm")
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=c.jmax)
    ref = ccopt.compensate(prog, "pmac", radius=c.radius)
    times, _, _ = StretchTimes.from_reference(ref, limits)
    path = _solve(style, BlendProblem(prog, ref, limits, None, {}, c.radius, None)).toolpath
    keys = frozenset(stretch_keys(ref)) - {None}
    part = StretchTimes(limits).time_partial(path, keys)
    assert isinstance(part, PartialTime)
    shared = [i for i, k in enumerate(stretch_keys(path)) if k in keys]
    assert part.pending == shared and shared       # the rapids at least
    assert part.finish(times) == times.copy().time(path)


def test_workers_give_the_serial_rows_when_the_reference_plans_last(monkeypatch):
    # the reference's plan held back: every variant's cycle time is asked first
    import time as clock

    import ccopt.compare.core as core
    c, prog = _case("leadin-inside-line")
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=tuple(10.0 * a for a in c.amax))
    names = ["pmac", "linuxcnc", "tangent-arc", "line-arc", "fagor-g138", "fagor-g139-g136"]
    serial = compare(prog, names, limits=limits, radius=c.radius)
    real = core.reference_times

    def late(*args, **kw):
        clock.sleep(3.0)
        return real(*args, **kw)

    monkeypatch.setattr(core, "reference_times", late)
    parallel = compare(prog, names, limits=limits, radius=c.radius, workers=2)
    assert _rows(parallel) == _rows(serial)


def test_workers_take_the_cycle_time_of_another_styles_path_of_the_same_geometry():
    # on freeform-hsm Fagor's G138 and SINUMERIK's style leave the same
    # geometry from other blocks (checked here): in workers, as in the serial
    # run, the later of the two takes the cycle time planned for the first,
    # but not a planner's refusal naming the first one's lines
    from ccopt.compare.schedule import _of_path, _shares
    c, prog = _case("freeform-hsm")
    fagor = ccopt.compensate(prog, "fagor", radius=c.radius)
    siemens = ccopt.compensate(prog, "siemens", radius=c.radius)
    linuxcnc = ccopt.compensate(prog, "linuxcnc", radius=c.radius)
    assert fagor != siemens
    assert [s.geom for s in fagor.segments] == [s.geom for s in siemens.segments]
    assert [s.block for s in fagor.segments] != [s.block for s in siemens.segments]
    assert _of_path([(linuxcnc, "l"), (fagor, "f")], siemens) == "f"
    assert _of_path([(fagor, "f"), (siemens, "s")], siemens) == "s"     # equal first
    assert _of_path([(linuxcnc, "l")], siemens) is None
    assert _shares((27.0, 1.0, None, {}), fagor, siemens)
    assert not _shares((None, None, "feed: line 12: refused", {}), fagor, siemens)
    assert _shares((None, None, "feed: line 12: refused", {}), siemens, siemens)
    limits = ccopt.AxisLimits(c.vmax, c.amax, j=c.jmax)
    names = ["pmac", "fagor-g138", "siemens"]
    serial = compare(prog, names, limits=limits, radius=c.radius)
    parallel = compare(prog, names, limits=limits, radius=c.radius, workers=2)
    assert _rows(parallel) == _rows(serial)
    assert (parallel["siemens"].figures["duration"]
            == parallel["fagor-g138"].figures["duration"]
            == pytest.approx(ccopt.plan_feed(siemens, limits, planner="jerk").duration,
                             rel=1e-6))
