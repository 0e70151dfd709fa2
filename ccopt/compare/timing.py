"""Cycle times of the variants, planned stretch by stretch between stops.

The rule. The feed planners bring the tool to rest (speed 0) at every
tangent break, at every dwell and at both ends of the path
(:func:`ccopt.feed.junction.boundary_speed_caps`; ``compare`` uses no
junction deviation). A profile at rest at a point splits there: TOPPRA's
controllable set at a stop is ``[0, 0]``, so its backward pass cannot carry
a later stretch's braking into an earlier one and its forward pass starts
again from 0, and every segment's gridpoints are its own
(:mod:`ccopt.feed.grid`); the jerk planner cuts at the same stops itself
(:mod:`ccopt.feed.jerk.planner`). So the cycle time of a path is the sum,
over its *stretches* (the runs of segments between consecutive stops), of
each stretch planned from rest to rest, plus its dwells.

A variant changes the reference only at its leads or corners. Its stretches
identical to one of the reference's (the same primitives, ``w``, feeds and
rapid/feed kind, in order: :func:`stretch_key`) take the reference's time,
read off the reference's whole-path profile between the two stops; only the
others are planned, each on its own, and each once per comparison. The same
holds for ``max_acc_ratio`` (the largest sampled axis acceleration over its
limit): the reference's samples inside a shared stretch, a new stretch's own.

What is not shared bit for bit: toppra works in a time unit set by the
path's largest cruise speed (:func:`ccopt.feed.toppra.planner.speed_scale`),
so a stretch planned alone can differ from the same stretch inside the whole
path in the last digits (the tests compare both on a case: within 1e-9
relative); the jerk planner groups stretches into LP windows and stops its
rounds per window, so there the difference is within its round tolerance
(:data:`ccopt.feed.jerk.planner.BHAT_TOL`, on a squared speed).
"""
from __future__ import annotations

import importlib
import pickle
import threading
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

# ccopt.feed loads ExactPath (and toppra, ~2 s) on first use: importing ccopt.compare stays fast
from ccopt import feed as feed_planning
from ccopt.errors import CcoptError
from ccopt.feed import certified_planner, plan_feed
from ccopt.feed.limits import AxisLimits
from ccopt.feed.planners import DEFAULT_TS
from ccopt.geometry import Arc, Line, Spiral
from ccopt.toolpath import Role, ToolPath

if TYPE_CHECKING:
    from ccopt.feed.path import ExactPath

#: Sampling step of ``max_acc_ratio`` (s): fine enough to see a blend's
#: millisecond-scale turn (longer profiles get a coarser one,
#: :meth:`ccopt.feed.FeedProfile.affordable_dt`).
RATIO_DT = 2e-4

#: A stop of the reference profile is found at a knot this close to the
#: stop's path position, relative to the path length (knots at stops are the
#: segment boundaries themselves; this only absorbs rounding of a sum).
STOP_MATCH_REL = 1e-12


def load_planner(limits: AxisLimits) -> None:
    """Import the planner :func:`~ccopt.feed.certified_planner` picks (with toppra, ~0.5 s): a
    parallel comparison does it before it forks its workers, so that each
    does not import it again for its first cycle time."""
    for name in ("ccopt.feed.path", "ccopt.feed.plan", "ccopt.feed.toppra.planner",
                 "ccopt.feed.jerk.planner" if certified_planner(limits) == "jerk" else None):
        if name is not None:
            importlib.import_module(name)


def _geometry_key(g):
    """A value-equal, hashable, picklable key of a primitive (``None``: unknown kind,
    never shared)."""
    if isinstance(g, (Line, Arc, Spiral)):
        return g
    cps = getattr(g, "control_points", None)
    if cps is not None:
        return (type(g).__name__, tuple(map(tuple, cps)))
    return None


def stretch_key(segments) -> tuple | None:
    """What the plan of a run of segments depends on: each one's primitive, ``w``
    at both ends, feed and whether it is a rapid (``None`` when a primitive has
    no value key)."""
    out = []
    for s in segments:
        g = _geometry_key(s.geom)
        if g is None:
            return None
        out.append((g, float(s.w0), float(s.w1),
                    None if s.feed is None else float(s.feed), s.role is Role.RAPID))
    return tuple(out)


@dataclass(frozen=True)
class Stretch:
    """Moving segments ``k0 .. k1 - 1`` of an :class:`ExactPath`, from a stop to the
    next, at path positions ``s0 .. s1``."""

    k0: int
    k1: int
    s0: float
    s1: float


def stops(exact: ExactPath) -> np.ndarray:
    """Indices of the segment boundaries of ``exact`` where the planners stop: both
    ends, every tangent break and every dwell (the zero speed caps of
    :func:`ccopt.feed.junction.boundary_speed_caps` without junction deviation;
    the tests check that they agree)."""
    K = len(exact.segments)
    cut = exact.tangent_break.copy()
    cut[0] = cut[K] = True
    if exact.dwells:
        cut[np.searchsorted(exact.offsets, [d.s for d in exact.dwells])] = True
    return np.flatnonzero(cut)


def stretch_keys(path: ToolPath | ExactPath) -> list:
    """:func:`stretch_key` of each of :func:`stretches` of ``path``, in order."""
    exact = path if isinstance(path, feed_planning.ExactPath) else feed_planning.ExactPath(path)
    return [stretch_key(exact.segments[st.k0:st.k1]) for st in stretches(exact)]


def stretches(exact: ExactPath) -> list[Stretch]:
    """The stretches of ``exact`` between consecutive stops (see the module docstring)."""
    if not exact.segments:
        return []
    cuts = stops(exact)
    return [Stretch(int(i), int(j), float(exact.offsets[i]), float(exact.offsets[j]))
            for i, j in zip(cuts[:-1], cuts[1:]) if j > i]


def _ratio_samples(prof) -> tuple[np.ndarray, np.ndarray]:
    """``(times, axis acceleration over its limit)`` of ``prof`` sampled every
    :data:`RATIO_DT` (or the coarser step a long profile affords,
    :meth:`~ccopt.feed.FeedProfile.affordable_dt`)."""
    return prof.acceleration_ratio_samples(prof.affordable_dt(RATIO_DT))


def _ratio(prof, smp=None) -> float:
    """The largest axis acceleration over its limit in ``prof`` at
    :func:`_ratio_samples` (``smp``: those samples, when the caller has them)."""
    smp = _ratio_samples(prof) if smp is None else smp
    return float(smp[1].max(initial=0.0))


def _cut(exact: ExactPath, prof, smp=None) -> list[tuple[float, float] | None]:
    """``(seconds, max_acc_ratio)`` of each stretch of ``exact`` read off its
    whole-path profile ``prof`` between the stops that bound it (``None``
    where the profile has no stop there); ``smp``: its :func:`_ratio_samples`,
    when the caller has them."""
    smp = _ratio_samples(prof) if smp is None else smp
    times, acc = smp
    at_rest = np.flatnonzero(prof.sd == 0.0)
    rest_s = prof.s[at_rest]                     # non-decreasing, as the knots are
    tol = STOP_MATCH_REL * max(exact.length, 1.0)
    out: list[tuple[float, float] | None] = []
    for st in stretches(exact):
        # the last knot at rest at or before the stretch's start, the first at or after its end
        k0 = int(np.searchsorted(rest_s, st.s0 + tol, side="right")) - 1
        k1 = int(np.searchsorted(rest_s, st.s1 - tol, side="left"))
        if k0 < 0 or k1 >= at_rest.size:
            out.append(None)
            continue
        t0, t1 = float(prof.t[at_rest[k0]]), float(prof.t[at_rest[k1]])
        i0 = int(np.searchsorted(times, t0, side="left"))     # samples with t0 <= t <= t1
        i1 = int(np.searchsorted(times, t1, side="right"))
        out.append((t1 - t0, float(acc[i0:i1].max(initial=0.0))))
    return out


def _unknown_runs(got: list) -> list[list[int]]:
    """The runs of consecutive indices where ``got`` is ``None``."""
    runs: list[list[int]] = []
    for i, g in enumerate(got):
        if g is not None:
            continue
        if runs and runs[-1][-1] == i - 1:
            runs[-1].append(i)
        else:
            runs.append([i])
    return runs


def plan_whole(path: ToolPath | ExactPath, limits: AxisLimits, ts: float | None = None, *,
               with_samples: bool = False):
    """``(profile, max_acc_ratio)`` of the whole path under :func:`~ccopt.feed.certified_planner`
    (``ts``: the jerk planner's interpolation period, s; None: its default);
    ``with_samples``: also the samples the ratio was read at
    (:func:`_ratio_samples`)."""
    prof = plan_feed(path, limits, planner=certified_planner(limits), ts=ts)
    smp = _ratio_samples(prof)
    ratio = _ratio(prof, smp)
    return (prof, ratio, smp) if with_samples else (prof, ratio)


@dataclass
class StretchTimes:
    """Stretch times known so far, by :func:`stretch_key`: ``(seconds, max_acc_ratio)``.

    Built from the reference's whole-path profile (:meth:`from_reference`);
    :meth:`time` plans only the stretches of a path it does not know, with
    ``ts`` (the jerk planner's interpolation period, s; None: its default).
    Plain data: it goes to worker processes.
    """

    limits: AxisLimits
    known: dict = field(default_factory=dict)
    ts: float | None = None

    @classmethod
    def from_reference(cls, reference: ToolPath, limits: AxisLimits, ts: float | None = None,
                       profile=None):
        """``(StretchTimes, duration, max_acc_ratio)``: the reference planned whole
        (its figures are those of the whole-path profile) and cut at its stops.
        ``profile``: that whole-path profile when the caller has it (it must
        be the reference's, under :func:`~ccopt.feed.certified_planner` and ``ts``: see
        :func:`same_plan`), else it is planned here."""
        if profile is not None:
            exact, prof = profile.path, profile
            smp = _ratio_samples(prof)
            ratio = _ratio(prof, smp)
        else:
            exact = feed_planning.ExactPath(reference)
            prof, ratio, smp = plan_whole(exact, limits, ts, with_samples=True)
        out = cls(limits, ts=ts)
        for key, got in zip(stretch_keys(exact), _cut(exact, prof, smp)):
            if key is not None and got is not None:
                out.known[key] = got
        return out, prof.duration, ratio

    def time(self, path: ToolPath) -> tuple[float, float]:
        """``(duration, max_acc_ratio)`` of ``path``: known stretches looked up, the
        others planned (and remembered); dwells added. Raises the planner's
        :class:`~ccopt.errors.CcoptError`.

        Consecutive unknown stretches are planned together, as one path from
        the first one's start to the last one's end, and cut at its stops as
        the reference is: on freeform-hsm, where another controller style
        changes every one of the reference's 302 stretches, one plan instead
        of 302 (the jerk planner then gathers the short stretches into LP
        windows, :data:`~ccopt.feed.jerk.windows.BATCH_POINTS`)."""
        return self.time_partial(path).finish(self)

    def time_partial(self, path: ToolPath, defer=frozenset()) -> "PartialTime":
        """:meth:`time` but for the stretches whose key is in ``defer`` (the
        reference's, before its plan is there): those are neither looked up
        nor planned, and :meth:`PartialTime.finish` reads them off the
        reference's times later. The stretches planned here are those
        :meth:`time` plans with the reference's times known, in the same runs,
        so the figures come out the same."""
        exact = feed_planning.ExactPath(path)
        dwells = float(sum(d.seconds for d in exact.dwells))
        parts = stretches(exact)
        keys = stretch_keys(exact)
        got = [self.known.get(k) if k is not None else None for k in keys]
        pending = [i for i, k in enumerate(keys) if got[i] is None and k is not None
                   and k in defer]
        for i in pending:
            got[i] = _Pending(keys[i])          # not None: no run plans it
        learned = {}
        for run in _unknown_runs(got):
            for i, fig in zip(run, self._plan_run(exact, [parts[i] for i in run])):
                got[i] = fig
                if keys[i] is not None:
                    self.known[keys[i]] = learned[keys[i]] = fig
        return PartialTime(dwells, got, pending, learned)

    def _plan_run(self, exact: ExactPath, run: list[Stretch]) -> list[tuple[float, float]]:
        """``(seconds, max_acc_ratio)`` of each of the consecutive stretches ``run``
        of ``exact`` (:meth:`_plan_run_afresh`), or the figures of a run planned
        before in this process whose :func:`run_signature` is the same: the
        same plan of the same numbers (variants share leads and corners, and
        each starts from the reference's stretch times alone, :meth:`copy`)."""
        key = run_signature(exact, run, self.limits, self.ts)
        with _RUN_PLANS_LOCK:     # a comparison plans its reference in a thread
            got = _RUN_PLANS.get(key) if key is not None else None
            if got is not None:
                _RUN_PLANS.move_to_end(key)
        if got is None:
            got = tuple(self._plan_run_afresh(exact, run))
            if key is not None:
                with _RUN_PLANS_LOCK:
                    _RUN_PLANS[key] = got
                    while len(_RUN_PLANS) > RUN_PLANS_KEPT:
                        _RUN_PLANS.popitem(last=False)
        return list(got)

    def _plan_run_afresh(self, exact: ExactPath, run: list[Stretch]) -> list[tuple[float, float]]:
        """``(seconds, max_acc_ratio)`` of each of the consecutive stretches ``run``
        of ``exact``: planned as one path and cut at its stops, or one by one
        where that path's stops are not the run's (never seen; a safeguard)."""
        def plan(s0: float, s1: float):
            sub = feed_planning.ExactPath(exact.stretch(s0, s1), exact.axes)
            return sub, plan_feed(sub, self.limits, planner=certified_planner(self.limits), ts=self.ts)

        if len(run) > 1:
            sub, prof = plan(run[0].s0, run[-1].s1)
            figs = _cut(sub, prof)
            if len(figs) == len(run) and all(f is not None for f in figs):
                return figs
        return [(prof.duration, _ratio(prof)) for prof in (plan(st.s0, st.s1)[1] for st in run)]

    def copy(self) -> "StretchTimes":
        """A copy to time one variant with: every variant starts from the
        reference's stretches alone, so its figures do not depend on which
        variants ran before it (serial and parallel runs agree)."""
        return StretchTimes(self.limits, dict(self.known), self.ts)


#: How many plans of runs of stretches (:meth:`StretchTimes._plan_run`) this
#: process keeps, the least recently used dropped first.
RUN_PLANS_KEPT = 256

#: :func:`run_signature` -> the run's ``(seconds, max_acc_ratio)`` per stretch.
_RUN_PLANS: OrderedDict = OrderedDict()
_RUN_PLANS_LOCK = threading.Lock()


def run_signature(exact: ExactPath, run: list[Stretch], limits: AxisLimits,
                  ts: float | None) -> bytes | None:
    """What the plans of the run ``run`` of ``exact`` read, as bytes: the tool
    path from its first stop to its last (each segment's primitive, role,
    ``w`` at both ends, feed and plane; the dwells inside it, by place and
    seconds; the path's plane), the run's stretches by their segments there,
    ``exact``'s axes, the limits and ``ts`` (s). Numbers by their bits
    (pickled), so equal bytes are the same numbers to the last bit (``-0.0``
    is not ``0.0`` here). ``None`` where a primitive has no value key
    (:func:`stretch_key`). Blocks are left out: they only name program lines
    in a planner's refusal, and a refusal is not kept."""
    sub = exact.stretch(run[0].s0, run[-1].s1)
    segments = []
    for seg in sub.segments:
        g = _geometry_key(seg.geom)
        if g is None:
            return None
        segments.append((g, seg.role.value, seg.w0, seg.w1, seg.feed, seg.plane))
    base = run[0].k0
    return pickle.dumps((tuple(segments), tuple(d[:2] for d in sub.dwells), sub.plane,
                         tuple((st.k0 - base, st.k1 - base) for st in run), exact.axes,
                         limits, ts), protocol=pickle.HIGHEST_PROTOCOL)


@dataclass(frozen=True)
class _Pending:
    """A stretch whose time the reference's plan will give (its key)."""

    key: tuple


@dataclass
class PartialTime:
    """A cycle time with some stretches still to read off the reference's plan
    (:meth:`StretchTimes.time_partial`): ``dwells`` (s), ``got`` the stretches'
    ``(seconds, max_acc_ratio)`` in path order, a :class:`_Pending` at the
    indices ``pending``. Plain data: it comes back from worker processes."""

    dwells: float
    got: list
    pending: list
    #: The stretch times planned for it (key -> ``(seconds, max_acc_ratio)``).
    learned: dict = field(default_factory=dict)

    def finish(self, times: StretchTimes) -> tuple[float, float] | None:
        """``(duration, max_acc_ratio)`` with the pending stretches from ``times``
        (the reference's), summed in path order as :meth:`StretchTimes.time`
        does; None when ``times`` lacks one (its stretch is then not the
        reference's after all: time the path again with ``times``)."""
        got = list(self.got)
        for i in self.pending:
            fig = times.known.get(got[i].key)
            if fig is None:
                return None
            got[i] = fig
        total = self.dwells
        total += sum(g[0] for g in got)
        return total, max((g[1] for g in got), default=0.0)


def timed_alike(a: ToolPath, b: ToolPath) -> bool:
    """Whether the planners give ``a`` and ``b`` one cycle time and axis
    acceleration ratio: the same geometry, roles, feeds, out-of-plane
    coordinates and planes of their segments, the same dwells (where and how
    long) and plane. :class:`~ccopt.feed.ExactPath` reads nothing else of a
    tool path, but for the program lines a planner's refusal names
    (:func:`same_timing_message`); the style that made a path is not read,
    so two controller styles that leave the same path get one figure."""
    if a is b:
        return True
    if a.plane != b.plane or len(a.segments) != len(b.segments) or \
            [d[:2] for d in a.dwells] != [d[:2] for d in b.dwells]:
        return False
    return all(x.geom == y.geom and x.role == y.role and x.feed == y.feed and x.w0 == y.w0
               and x.w1 == y.w1 and x.plane == y.plane for x, y in zip(a.segments, b.segments))


def same_timing_message(a: ToolPath, b: ToolPath) -> bool:
    """Whether a planner's message about ``a`` reads the same for ``b``
    (:func:`timed_alike` paths): the same blocks, whose lines it names."""
    return a is b or (all(x.block == y.block for x, y in zip(a.segments, b.segments))
                      and [d[2] for d in a.dwells] == [d[2] for d in b.dwells])


def same_plan(profile, reference: ToolPath, limits: AxisLimits, ts: float | None) -> bool:
    """Whether ``profile`` is the plan :meth:`StretchTimes.from_reference` would
    make of ``reference``: a plan of that very path object (the caller gave
    both, :class:`ccopt.compare.core.GivenReference`; no path is compared
    with another), under these limits, their planner
    (:func:`~ccopt.feed.certified_planner`) and, for the jerk planner,
    interpolation period ``ts`` (None: its default)."""
    if profile is None or profile.planner != certified_planner(limits) or profile.limits != limits:
        return False
    if profile.planner == "jerk" and profile.info.get("ts") != (DEFAULT_TS if ts is None else ts):
        return False
    return profile.path.toolpath is reference


def reference_times(reference: ToolPath, limits: AxisLimits | None, ts: float | None = None,
                    profile: FeedProfile | None = None) -> StretchTimes | None:
    """The reference planned whole (or its ``profile``) and cut at its stops
    (``None`` without limits; none known when the planner refuses the
    reference: each variant is then planned whole and says why)."""
    if limits is None:
        return None
    try:
        return StretchTimes.from_reference(reference, limits, ts, profile)[0]
    except CcoptError:
        return StretchTimes(limits, ts=ts)


def partial_figures(path: ToolPath, limits: AxisLimits, ts: float | None, defer):
    """:func:`duration_figures` before the reference is planned: a
    :class:`PartialTime` whose stretches in ``defer`` (the reference's keys)
    are left to :meth:`PartialTime.finish`, or ``(None, None, message)`` when
    the planner refuses."""
    try:
        return StretchTimes(limits, ts=ts).time_partial(path, defer)
    except CcoptError as exc:
        return None, None, f"feed: {exc}"


def duration_figures(path: ToolPath, limits: AxisLimits | None,
                     times: StretchTimes | None = None):
    """``(duration, max_acc_ratio, message)`` of ``path``: by stretches with
    ``times``, else the whole path planned; ``message`` is the planner's
    refusal (then no figures)."""
    if limits is None:
        return None, None, None
    try:
        if times is not None:
            d, r = times.time(path)
            return d, r, None
        prof, r = plan_whole(path, limits)
        return prof.duration, r, None
    except CcoptError as exc:
        return None, None, f"feed: {exc}"


__all__ = ["RATIO_DT", "PartialTime", "StretchTimes", "Stretch", "duration_figures",
           "partial_figures", "plan_whole",
           "same_plan", "stops", "stretch_key", "stretch_keys", "stretches"]
