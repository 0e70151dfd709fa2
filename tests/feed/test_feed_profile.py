"""FeedProfile: parametrisation, samples, active limits, dwells, CSV, corners, errors."""
from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, FeedError, plan_feed
from ccopt.feed.junction import junction_speed
from ccopt.geometry import Arc, Line
from ccopt.program.model import Block, Modal, Motion, Source
from ccopt.toolpath import PathSegment, Role, ToolPath

from _tolerances import TOPPRA_OVER


def block(line):
    return Block(Source("part.pmc", line, 1), Motion.LINE, (0, 0, 0), (1, 0, 0), Modal(), feed=10.0)


def seg(geom, feed=None, w0=0.0, w1=0.0, line=None):
    role = Role.RAPID if feed is None else Role.COMPENSATED
    return PathSegment(geom, role, block(line) if line else None, w0, w1, feed)


def test_profile_equals_toppras_const_accel_parametrizer():
    """The knots and samples are toppra's ParametrizeConstAccel of the same solution."""
    from toppra.parametrizer import ParametrizeConstAccel

    case = find_case("profile")
    path = ExactPath(compensate(ccopt.read_program(case.program), "pmac"))
    prof = plan_feed(path, AxisLimits(case.vmax, case.amax))
    ref = ParametrizeConstAccel(path, prof.s, prof.sd)
    assert ref.duration == pytest.approx(prof.duration, rel=1e-12)
    times = np.linspace(0.0, prof.duration, 397)
    smp = prof.at(times)
    assert np.allclose(smp.position, ref(times, 0), atol=1e-9)
    assert np.allclose(smp.velocity, ref(times, 1), atol=1e-7)
    # accelerations agree except at the instants where one side's constant
    # acceleration switches to the next (toppra and we may pick either side)
    at_knot = np.isin(times, prof.t)
    assert np.allclose(smp.acceleration[~at_knot], ref(times, 2)[~at_knot], atol=1e-6)


def test_samples_and_active_limits_on_a_line():
    # direction (0.6, 0.8): the Y limits bind (v = 50/0.8 = 62.5, a = 400/0.8 = 500)
    tp = ToolPath((seg(Line((0, 0), (60, 80))),))
    prof = plan_feed(tp, AxisLimits((100.0, 50.0), (1000.0, 400.0)))
    smp = prof.sample(1e-3)
    assert smp.t[0] == 0.0 and smp.t[-1] == pytest.approx(prof.duration)
    assert np.all(np.diff(smp.t) > 0)
    assert smp.axes == ("X", "Y")
    names = np.array(smp.active_names)
    cruise = (smp.feed > 62.0) & (smp.tangential_acc == 0.0)
    assert cruise.sum() > 1000 and set(names[cruise]) == {"velocity Y"}
    accel = (smp.t > 0.01) & (smp.t < 0.12)
    assert set(names[accel]) == {"acceleration Y"}
    assert smp.feed.max() == pytest.approx(62.5, rel=1e-6)
    assert np.allclose(np.linalg.norm(smp.velocity, axis=1), smp.feed, atol=1e-9)
    summary = prof.summary()
    assert summary["samples"] == len(smp)
    assert summary["max_axis_vel_ratio"] == pytest.approx(1.0, abs=1e-6)
    assert summary["max_axis_acc_ratio"] == pytest.approx(1.0, abs=1e-6)
    assert summary["gridpoints"] > 0


def test_feed_cap_is_active_where_it_binds():
    tp = ToolPath((seg(Line((0, 0), (100, 0)), feed=20.0),))
    smp = plan_feed(tp, AxisLimits((100.0, 100.0), (1000.0, 1000.0))).sample()
    names = np.array(smp.active_names)
    cruise = (smp.feed > 19.99) & (smp.tangential_acc == 0.0)
    assert cruise.sum() > 4000 and set(names[cruise]) == {"feed"}
    assert smp.feed_ratio.max() <= 1.0 + 1e-12


def test_dwell_adds_its_time_and_holds_still():
    case = find_case("z-plunges")
    path = ExactPath(compensate(ccopt.read_program(case.program), "pmac"))
    assert [d.seconds for d in path.dwells] == [0.1]
    lim = AxisLimits(case.vmax, case.amax)
    for name in ("toppra", "stop", "junction"):
        prof = plan_feed(path, lim, planner=name)
        assert prof.dwell_time == 0.1
        smp = prof.sample(1e-3)
        held = smp.segment < 0
        assert held.sum() == pytest.approx(100, abs=1)
        assert np.ptp(smp.position[held], axis=0).max() == 0.0
        assert set(np.array(smp.active_names)[held]) == {"dwell"}
        # without the dwell the same motion is exactly 0.1 s shorter
        no_dwell = ExactPath(ToolPath(path.toolpath.segments, plane=path.toolpath.plane))
        assert prof.duration - plan_feed(no_dwell, lim, planner=name).duration == \
            pytest.approx(0.1, abs=1e-9)


def test_csv_export(tmp_path):
    tp = ToolPath((seg(Line((0, 0), (10, 0)), feed=20.0, w0=0.0, w1=-2.0, line=4),
                   seg(Line((10, 0), (10, 5)), feed=20.0, w0=-2.0, w1=-2.0, line=5)))
    prof = plan_feed(tp, AxisLimits((100, 100, 30), (1000, 1000, 300)))
    out = tmp_path / "feed.csv"
    prof.to_csv(out, dt=0.002)
    rows = list(csv.reader(io.StringIO(out.read_text())))
    assert rows[0] == ["t", "s", "block", "x", "y", "z", "vx", "vy", "vz", "ax", "ay", "az",
                       "feed", "tangential_acc", "active"]
    smp = prof.sample(0.002)
    assert len(rows) - 1 == len(smp)
    last = rows[-1]
    assert float(last[0]) == pytest.approx(prof.duration, rel=1e-9)
    assert [float(x) for x in last[3:6]] == pytest.approx([10, 5, -2], abs=1e-9)
    assert {r[2] for r in rows[1:]} == {"4", "5"}
    assert not list(tmp_path.glob(".*.tmp"))   # written atomically, nothing left behind


def test_csv_in_chunks_is_the_samples_written_at_once(tmp_path, monkeypatch):
    # to_csv writes CSV_CHUNK samples at a time: chunks of 7 (the last one
    # short, ending at the clipped final instant) give the same file as the
    # samples formatted in one go, with one header
    import ccopt.feed.profile as profile

    tp = ToolPath((seg(Line((0, 0), (10, 0)), feed=20.0, line=4),
                   seg(Line((10, 0), (10, 5)), feed=20.0, line=5)))
    prof = plan_feed(tp, AxisLimits((100, 100, 30), (1000, 1000, 300)))
    whole = prof.sample(0.01).to_csv_text()
    monkeypatch.setattr(profile, "CSV_CHUNK", 7)
    out = tmp_path / "feed.csv"
    prof.to_csv(out, dt=0.01)
    assert (len(whole.splitlines()) - 1) % 7 != 0      # a short last chunk
    assert out.read_text() == whole


def test_junction_deviation_corner_speed_is_grbls():
    """90-degree corner, delta = 0.05: v^2 = a delta sin(t/2) / (1 - sin(t/2)),
    t = 90 deg, a the axis limit along t_out - t_in = (-1, 1)/sqrt(2)."""
    A = (1000.0, 600.0)
    tp = ToolPath((seg(Line((0, 0), (50, 0)), feed=200.0), seg(Line((50, 0), (50, 50)), feed=200.0)))
    delta = 0.05
    a_j = min(A[0], A[1]) * math.sqrt(2)
    sh = math.sqrt(0.5)
    v_corner = math.sqrt(a_j * delta * sh / (1 - sh))
    assert junction_speed([[1, 0]], [[0, 1]], A, delta)[0] == pytest.approx(v_corner, rel=1e-12)
    lim = AxisLimits((100.0, 100.0), A)
    stopped = plan_feed(tp, lim)
    for name in ("toppra", "junction"):
        prof = plan_feed(tp, lim, planner=name, junction_deviation=delta)
        assert prof.speed_at([50.0])[0] == pytest.approx(v_corner, rel=1e-6)
        assert prof.duration < stopped.duration
    assert plan_feed(tp, lim, junction_deviation=delta).duration <= \
        plan_feed(tp, lim, planner="junction", junction_deviation=delta).duration * (1 + 1e-6)
    # a reversal always stops
    back = ToolPath((seg(Line((0, 0), (50, 0)), feed=200.0), seg(Line((50, 0), (20, 0)), feed=200.0)))
    assert plan_feed(back, lim, junction_deviation=delta).speed_at([50.0])[0] == 0.0


def test_plane_zx_uses_the_machine_axes():
    """In G18 (ZX) the in-plane u axis is machine Z: its limits apply."""
    tp = ToolPath((seg(Line((0, 0), (10, 0))),), plane="ZX")   # along u = Z
    lim = AxisLimits((100.0, 100.0, 20.0), (1000.0, 1000.0, 200.0))
    prof = plan_feed(tp, lim)
    assert prof.duration == pytest.approx(10 / 20 + 20 / 200, rel=1e-6)
    assert prof.sample().axes == ("Z", "X")
    with pytest.raises(FeedError, match="axis Z"):
        plan_feed(tp, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))


def test_missing_z_limit_is_a_located_error():
    tp = ToolPath((seg(Line((0, 0), (0, 0)), feed=10.0, w0=0.0, w1=-5.0, line=3),))
    with pytest.raises(FeedError) as exc:
        plan_feed(tp, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))
    assert str(exc.value) == "part.pmc: the path moves axis Z but the limits give only X, Y"


def test_toppra_failure_is_a_located_error(monkeypatch):
    """A failed TOPPRA return code becomes a FeedError naming the block: here
    the controllable sets come out undefined past the middle (as toppra's
    backward pass leaves them on a path it cannot control), so toppra's own
    pass reports the instance not controllable."""
    # the backward pass ccopt runs: StoppingTOPPRA's (toppra's LPs, its own loop)
    from ccopt.feed.toppra.planner import StoppingTOPPRA

    def failing(self, sdmin, sdmax):
        K = np.zeros((self._N + 1, 2))
        K[self._N // 2 + 3] = np.nan
        return K

    monkeypatch.setattr(StoppingTOPPRA, "compute_controllable_sets", failing)
    tp = ToolPath((seg(Line((0, 0), (10, 0)), feed=10.0, line=7),
                   seg(Line((10, 0), (20, 0)), feed=10.0, line=8)))
    with pytest.raises(FeedError) as exc:
        plan_feed(tp, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))
    msg = str(exc.value)
    assert msg.startswith("part.pmc:8: TOPPRA failed") and "not controllable" in msg
    assert "\n" not in msg


def test_path_without_motion():
    dwell = Block(Source("p.pmc", 2, 1), Motion.DWELL, (0, 0, 0), (0, 0, 0), Modal(), dwell=0.3)
    tp = ToolPath((seg(Line((1, 1), (1, 1)), feed=10.0),), dwells=((0, 0.3, dwell),))
    for name in ("toppra", "stop", "junction"):
        prof = plan_feed(tp, AxisLimits((1, 1), (1, 1)), planner=name)
        assert prof.duration == pytest.approx(0.3)


def test_arc_respects_axis_limits_between_gridpoints():
    """A fast full circle limited by the axis accelerations: the sampled
    accelerations stay within them (toppra's feasibility tolerance) although they are imposed at gridpoints only."""
    tp = ToolPath((seg(Arc((0, 0), 5.0, 0.3, 2 * math.pi), feed=500.0),))
    lim = AxisLimits((200.0, 150.0), (2000.0, 900.0))
    smp = plan_feed(tp, lim).sample(1e-4)
    assert smp.axis_acceleration_ratio.max() <= TOPPRA_OVER
    assert smp.axis_velocity_ratio.max() <= TOPPRA_OVER
    # at the top and bottom of the circle the centripetal acceleration is along
    # Y: v^2/R <= 900; at its sides along X: v^2/R <= 2000 (and v <= 150 / 1)
    top = np.abs(smp.position[:, 1]) > 4.999
    side = np.abs(smp.position[:, 0]) > 4.999
    assert top.any() and side.any()
    # (there the Y part of the centripetal acceleration is v^2 |y| / R^2 <= 900)
    cap_top = np.sqrt(900 * 5.0 ** 2 / np.abs(smp.position[top, 1]))
    assert np.all(smp.feed[top] <= cap_top * TOPPRA_OVER)
    assert smp.feed[side].max() > math.sqrt(900 * 5.0) * 1.2


def test_large_radius_arc_is_planned():
    """A 100 m radius arc at 140 mm/s: in mm/s toppra's seidel solver takes the
    nearly parallel acceleration rows of neighbouring gridpoints for parallel
    and declares the instance uncontrollable; the planner's time unit
    (speed_scale) keeps squared speeds near 1, where its tolerances hold."""
    R, L = 1e5, 200.0
    tp = ToolPath((seg(Line((-50, -R), (0, -R)), feed=140.0),
                   seg(Arc((0, 0), R, -math.pi / 2, L / R), feed=140.0)))
    lim = AxisLimits((150.0, 150.0), (2000.0, 2000.0))
    prof = plan_feed(tp, lim)
    # a straight 250 mm at 140 mm/s and 2000 mm/s^2, the arc all but straight
    assert prof.duration == pytest.approx(250 / 140 + 140 / 2000, rel=1e-4)
    assert prof.info["time_scale"] == pytest.approx(140.0)


def test_plan_feed_arguments():
    tp = ToolPath((seg(Line((0, 0), (10, 0)), feed=10.0),))
    lim = AxisLimits((100.0, 100.0), (1000.0, 1000.0))
    with pytest.raises(ValueError, match="unknown planner"):
        plan_feed(tp, lim, planner="fastest")
    with pytest.raises(TypeError):
        plan_feed(tp, {"v": [1, 1], "a": [1, 1]})
    with pytest.raises(ValueError, match="junction_deviation"):
        plan_feed(tp, lim, junction_deviation=-1.0)
    # an ExactPath can be shared between planners
    path = ExactPath(tp)
    assert plan_feed(path, lim).path is path


def test_a_long_program_is_sampled_within_the_cap(monkeypatch):
    # 1 m at a programmed 1 mm/s: T = L/v + v/a = 1000 s (+1e-3). With the cap
    # lowered to 1e5 samples (the real one, 2e7, is the same code at 3 GB), 1 kHz
    # is 1e6 samples, past it: asking for that is a located error;
    # affordable_dt gives the smallest step within the cap.
    import ccopt.feed.profile as profile
    cap = 100_000
    monkeypatch.setattr(profile, "MAX_FEED_SAMPLES", cap)
    tp = ToolPath((seg(Line((0, 0), (1000, 0)), feed=1.0, line=3),))
    prof = plan_feed(tp, AxisLimits((100.0, 100.0), (1000.0, 1000.0)))
    assert 1000 + 1e-3 <= prof.duration <= (1000 + 1e-3) * (1 + 1e-3)
    with pytest.raises(FeedError, match="use a larger dt"):
        prof.sample(1e-3)
    dt = prof.affordable_dt(1e-3)
    assert dt == pytest.approx(prof.duration / (cap - 2), rel=1e-12)
    assert prof.affordable_dt(1.0) == 1.0                 # a coarse step is kept
    smp = prof.sample(dt)
    assert len(smp) <= cap
    assert smp.feed.max() <= 1.0 * (1 + 1e-9)


@pytest.mark.parametrize("case_name, planner", [("profile", "toppra"), ("z-plunges", "toppra"),
                                                ("freeform-hsm", "toppra"), ("pocket", "jerk")])
def test_acceleration_ratio_samples_are_the_full_samples(case_name, planner):
    """The lean acceleration samples a comparison reads are bit for bit the
    ``axis_acceleration_ratio`` of the full samples at the same times (constant
    acceleration and jerk-limited pieces, 3-D moves, Bezier segments)."""
    case = find_case(case_name)
    path = ExactPath(compensate(ccopt.read_program(case.program), "pmac"))
    amax = case.amax
    lim = AxisLimits(case.vmax, amax, j=tuple(10.0 * a for a in amax)
                     if planner == "jerk" else None)
    prof = plan_feed(path, lim, planner=planner)
    dt = prof.affordable_dt(2e-4)
    times, ratio = prof.acceleration_ratio_samples(dt)
    smp = prof.sample(dt)
    assert np.array_equal(times, smp.t)
    assert np.array_equal(ratio, smp.axis_acceleration_ratio)


def test_acceleration_ratio_samples_without_motion():
    dwell = Block(Source("p.pmc", 2, 1), Motion.DWELL, (0, 0, 0), (0, 0, 0), Modal(), dwell=0.3)
    tp = ToolPath((seg(Line((1, 1), (1, 1)), feed=10.0),), dwells=((0, 0.3, dwell),))
    prof = plan_feed(tp, AxisLimits((1, 1), (1, 1)))
    times, ratio = prof.acceleration_ratio_samples(0.1)
    assert np.array_equal(times, prof.sample(0.1).t)
    assert not ratio.any()
