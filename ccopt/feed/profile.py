"""``FeedProfile``: motion along the path in time, and its samples.

Every planner (TOPPRA and the baselines) produces the same thing: a path
position ``s(t)`` that is piecewise constant-acceleration in time (exactly
what toppra's ``ParametrizeConstAccel`` builds from a TOPPRA solution, and
what a trapezoid is). A profile is stored as knots

    t[0..M], s[0..M], sd[0..M]   time (s), path position (units), path speed (units/s)
    sdd[0..M-1], segment[0..M-1] path acceleration and path segment of each interval

with ``s[k+1] = s[k] + sd[k] dt + sdd[k] dt^2 / 2`` and ``sd[k+1] = sd[k] + sdd[k] dt``.
A dwell is an interval with ``segment = -1``, zero speed and zero length.

:meth:`FeedProfile.sample` evaluates it at a fixed time step: axis positions,
velocities ``q' s'`` and accelerations ``q'' s'^2 + q' s''`` from the exact
path, the tangential feed ``s'`` (``|q'| = 1``), and which limit is active.

Samples also carry the axis jerk ``q''' s'^3 + 3 q'' s' s'' + q' s'''``, the
value within the piece a sample falls in. A profile of constant-acceleration
pieces has ``s''' = 0`` inside them and an acceleration step at every knot
(an unbounded jerk the samples do not show): its jerk figure is that of the
curvature alone. The ``jerk`` planner and the jerk-limited ``stop`` baseline
produce :class:`~ccopt.feed.jerk.profile.JerkProfile` objects, whose pieces
have bounded ``s'''`` and continuous ``s''`` (see there), so their sampled
jerk is the whole jerk but for the acceleration steps at curvature breaks,
bounded by ``jmax * ts`` (:mod:`ccopt.feed.jerk.planner`).
"""
from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ccopt.atomic import write_with_atomic
from ccopt.feed.errors import FeedError
from ccopt.feed.figures import derivative_bounds, piece_steps, piece_times
from ccopt.feed.limits import AxisLimits
from ccopt.feed.path import ExactPath
from ccopt.tolerances import ACTIVE_RATIO, MAX_FEED_SAMPLES

#: Rounding allowance in ``duration / dt`` when counting sample times, so a
#: duration of exactly n steps gives n + 1 samples, not a short extra step.
_SAMPLE_COUNT_SLACK = 1e-9
#: Samples written at a time by :meth:`FeedProfile.to_csv` (about 20 MB of text).
CSV_CHUNK = 100_000


@dataclass(frozen=True, eq=False)
class FeedSamples:
    """A profile sampled at times ``t`` (arrays over the samples).

    ``position``, ``velocity``, ``acceleration`` are ``(n, dof)`` in plane
    coordinates, named by ``axes`` (machine axis letters, e.g. X, Y, Z).
    ``feed`` is the tangential speed (units/s), ``tangential_acc`` its rate of
    change, ``curvature`` ``|q''|`` (1/units). ``jerk`` ``(n, dof)``: axis
    jerk (units/s^3); ``j_limit``: the axis jerk limits, ``None`` when the
    limits give none. ``active`` indexes
    ``limit_names`` (the largest ratio, if at least :data:`ACTIVE_RATIO`;
    ``"none"`` otherwise, ``"dwell"`` during dwells).
    """

    t: np.ndarray
    s: np.ndarray
    segment: np.ndarray
    line: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    feed: np.ndarray
    tangential_acc: np.ndarray
    curvature: np.ndarray
    feed_cap: np.ndarray
    axes: tuple[str, ...]
    v_limit: np.ndarray
    a_limit: np.ndarray
    tangential_limit: float | None
    centripetal_limit: float | None
    jerk: np.ndarray | None = None
    j_limit: np.ndarray | None = None
    limit_names: tuple[str, ...] = field(init=False)
    active: np.ndarray = field(init=False)

    def __post_init__(self):
        if self.jerk is None:
            object.__setattr__(self, "jerk", np.zeros_like(self.acceleration))
        names, cols = self._ratio_columns()
        ratios = np.column_stack(cols) if cols else np.zeros((self.t.size, 0))
        best = np.argmax(ratios, axis=1)
        top = ratios[np.arange(self.t.size), best]
        names = tuple(names) + ("none", "dwell")
        active = np.where(top >= ACTIVE_RATIO, best, len(names) - 2)
        active = np.where(self.segment < 0, len(names) - 1, active)
        object.__setattr__(self, "limit_names", names)
        object.__setattr__(self, "active", active)

    def __len__(self) -> int:
        return int(self.t.size)

    def _ratio_columns(self):
        names, cols = [], []
        for i, ax in enumerate(self.axes):
            names.append(f"velocity {ax}")
            cols.append(self.axis_velocity_ratio[:, i])
        for i, ax in enumerate(self.axes):
            names.append(f"acceleration {ax}")
            cols.append(self.axis_acceleration_ratio[:, i])
        if self.j_limit is not None:
            for i, ax in enumerate(self.axes):
                names.append(f"jerk {ax}")
                cols.append(self.axis_jerk_ratio[:, i])
        names.append("feed")
        cols.append(self.feed_ratio)
        if self.tangential_limit is not None:
            names.append("tangential acceleration")
            cols.append(np.abs(self.tangential_acc) / self.tangential_limit)
        if self.centripetal_limit is not None:
            names.append("centripetal acceleration")
            cols.append(self.curvature * self.feed ** 2 / self.centripetal_limit)
        return names, cols

    @property
    def axis_velocity_ratio(self) -> np.ndarray:
        """``|v_i| / vmax_i``, shape ``(n, dof)``."""
        return np.abs(self.velocity) / self.v_limit

    @property
    def axis_acceleration_ratio(self) -> np.ndarray:
        """``|a_i| / amax_i``, shape ``(n, dof)``."""
        return np.abs(self.acceleration) / self.a_limit

    @property
    def axis_jerk_ratio(self) -> np.ndarray:
        """``|j_i| / jmax_i``, shape ``(n, dof)``; zeros when no jerk limit is given."""
        if self.j_limit is None:
            return np.zeros_like(self.jerk)
        return np.abs(self.jerk) / self.j_limit

    @property
    def feed_ratio(self) -> np.ndarray:
        """Tangential speed over the programmed feed (0 on rapids and dwells)."""
        return np.where(np.isfinite(self.feed_cap), self.feed / np.where(
            np.isfinite(self.feed_cap) & (self.feed_cap > 0), self.feed_cap, 1.0), 0.0)

    @property
    def active_names(self) -> list[str]:
        return [self.limit_names[i] for i in self.active]

    def to_csv_text(self, header: bool = True) -> str:
        """CSV: ``t, s, block, <axes>, v<axes>, a<axes>[, j<axes>], feed, tangential_acc,
        active``; the jerk columns when the limits give jerk limits (``header``:
        whether the first line names the columns)."""
        ax = [a.lower() for a in self.axes]
        jerk_cols = [f"j{a}" for a in ax] if self.j_limit is not None else []
        names = (["t", "s", "block"] + ax + [f"v{a}" for a in ax] + [f"a{a}" for a in ax]
                 + jerk_cols + ["feed", "tangential_acc", "active"])
        jerk = [self.jerk] if jerk_cols else []
        num = np.column_stack([self.t, self.s, self.position, self.velocity, self.acceleration,
                               *jerk, self.feed, self.tangential_acc])
        buf = io.StringIO()
        if header:
            buf.write(",".join(names) + "\n")
        lines = np.where(self.line >= 0, self.line, 0).astype(str)
        lines = np.where(self.line >= 0, lines, "")
        active = np.array(self.limit_names, dtype=object)[self.active]
        # one format per row (numbers as "%.10g"): a third of the time of
        # formatting every value with np.char.mod and joining them
        row = "%.10g,%.10g,%s," + ",".join(["%.10g"] * (num.shape[1] - 2)) + ",%s\n"
        buf.writelines(row % (r[0], r[1], ln, *r[2:], act)
                       for r, ln, act in zip(num.tolist(), lines.tolist(), active.tolist()))
        return buf.getvalue()


@dataclass(frozen=True, eq=False)
class FeedProfile:
    """Motion along an :class:`ExactPath` in time (see the module docstring).

    Attributes: ``path``, ``limits``, ``planner`` (``"toppra" | "stop" |
    "junction"``), the knot arrays ``t, s, sd, sdd, segment`` and ``info``
    (planner details such as the number of gridpoints).
    """

    path: ExactPath
    limits: AxisLimits
    planner: str
    t: np.ndarray
    s: np.ndarray
    sd: np.ndarray
    sdd: np.ndarray
    segment: np.ndarray
    info: dict = field(default_factory=dict)

    # -- construction --------------------------------------------------------

    @classmethod
    def from_path_velocity(cls, path: ExactPath, limits: AxisLimits, planner: str,
                           gridpoints, sd, info: dict | None = None) -> FeedProfile:
        """Constant acceleration between gridpoints, as toppra's ``ParametrizeConstAccel``.

        ``dt_i = 2 ds_i / (sd_i + sd_i+1)``, ``sdd_i = (sd_i+1^2 - sd_i^2) / (2 ds_i)``.
        """
        s = np.asarray(gridpoints, dtype=float)
        sd = np.asarray(sd, dtype=float)
        ds = np.diff(s)
        denom = sd[:-1] + sd[1:]
        if np.any(denom <= 0.0):
            i = int(np.flatnonzero(denom <= 0.0)[0])
            raise FeedError(f"feed planning stalled: zero speed on both ends of the grid interval "
                            f"at s = {s[i]:.6g} (a segment too short for its gridpoints?)",
                            path.source_file, path.block_line(s[i]))
        dt = 2.0 * ds / denom
        sdd = (sd[1:] ** 2 - sd[:-1] ** 2) / (2.0 * ds)
        seg = path.locate(0.5 * (s[:-1] + s[1:]))
        t = np.concatenate([[0.0], np.cumsum(dt)])
        return cls._build(path, limits, planner, t, s, sd, sdd, seg, info)

    @classmethod
    def from_knots(cls, path: ExactPath, limits: AxisLimits, planner: str, dt, s, sd, sdd,
                   segment, info: dict | None = None) -> FeedProfile:
        """From interval durations ``dt`` and knots ``s``, ``sd`` (``len(dt) + 1``)."""
        t = np.concatenate([[0.0], np.cumsum(np.asarray(dt, dtype=float))])
        return cls._build(path, limits, planner, t, np.asarray(s, float), np.asarray(sd, float),
                          np.asarray(sdd, float), np.asarray(segment, int), info)

    @classmethod
    def _build(cls, path, limits, planner, t, s, sd, sdd, seg, info):
        if path.dwells:
            dt = np.diff(t)
            for d in sorted(path.dwells, key=lambda d: d.s, reverse=True):
                i = int(np.clip(np.searchsorted(s, d.s), 0, s.size - 1))
                s = np.insert(s, i, s[i])
                sd = np.insert(sd, i, 0.0)
                sd[i + 1] = 0.0
                dt = np.insert(dt, i, d.seconds)
                sdd = np.insert(sdd, i, 0.0)
                seg = np.insert(seg, i, -1)
            t = np.concatenate([[0.0], np.cumsum(dt)])
        return cls(path, limits, planner, t, s, sd, sdd, seg, dict(info or {}))

    @classmethod
    def empty(cls, path: ExactPath, limits: AxisLimits, planner: str) -> FeedProfile:
        """The profile of a path with no motion (only its dwells, if any)."""
        return cls._build(path, limits, planner, np.zeros(1), np.zeros(1), np.zeros(1),
                          np.zeros(0), np.zeros(0, dtype=int), {})

    # -- queries -------------------------------------------------------------

    @property
    def duration(self) -> float:
        """Total time (s), dwells included."""
        return float(self.t[-1])

    @property
    def dwell_time(self) -> float:
        return float(sum(d.seconds for d in self.path.dwells))

    def speed_at(self, s) -> np.ndarray:
        """Path speed (units/s) when the tool passes path positions ``s``.

        Within an interval ``sd^2`` is linear in ``s``; at a knot shared by
        two intervals the later one is used (the same value, speed being
        continuous).
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        move = self.segment >= 0
        s0 = self.s[:-1][move]
        s1 = self.s[1:][move]
        v0 = self.sd[:-1][move]
        v1 = self.sd[1:][move]
        a = self.sdd[move]
        if s0.size == 0:
            return np.zeros_like(s)
        i = np.clip(np.searchsorted(s0, s, side="right") - 1, 0, s0.size - 1)
        x = v0[i] ** 2 + 2.0 * a[i] * (np.clip(s, s0[i], s1[i]) - s0[i])
        v = np.sqrt(np.maximum(x, 0.0))
        # at a knot, its own speed (no rounding from the square root)
        v = np.where(s <= s0[i], v0[i], v)
        return np.where(s >= s1[i], v1[i], v)

    def affordable_dt(self, dt: float) -> float:
        """``dt``, or the smallest step that keeps :meth:`sample` within
        :data:`MAX_FEED_SAMPLES` on this profile (for callers that sample for
        a figure, not because a user asked for that step)."""
        return max(dt, self.duration / (MAX_FEED_SAMPLES - 2))

    def sample(self, dt: float = 1e-3) -> FeedSamples:
        """Samples every ``dt`` seconds from 0, plus the final instant.

        :class:`FeedError` when that is more than :data:`MAX_FEED_SAMPLES`
        samples (a larger ``dt`` is needed)."""
        return self.at(self._sample_times(dt))

    def _sample_times(self, dt: float) -> np.ndarray:
        """The times :meth:`sample` takes: every ``dt`` from 0, plus the final instant."""
        n = self.sample_count(dt)
        times = np.arange(n) * dt
        times[-1] = min(times[-1], self.duration)
        return times

    def acceleration_ratio_samples(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """``(times, ratio)``: :meth:`sample` ``(dt)``'s times and its
        ``axis_acceleration_ratio`` (``|a_i| / amax_i``, shape ``(n, dof)``),
        the same figures, with only the derivatives acceleration needs
        evaluated (comparisons read this ratio for every variant)."""
        times = np.clip(self._sample_times(dt), 0.0, self.duration)
        n = times.size
        path = self.path
        _, alim = self.limits.in_plane(path.frame, path.dof)
        if self.sdd.size == 0 or not path.segments:
            return times, np.zeros((n, path.dof))
        s, v, u, _, seg = self.motion(times)
        seg_eval = np.where(seg >= 0, seg, path.locate(s))
        q1, q2 = path.eval_orders(seg_eval, s, (1, 2))
        return times, np.abs(q2 * (v * v)[:, None] + q1 * u[:, None]) / alim

    def longest_block(self) -> tuple[int | None, int | None, str]:
        """Where the profile spends most of its time, to locate a size limit
        (issue 29): ``(line, col, text)`` of the program block whose moves (or
        dwell) take the longest, the text saying how long and which share of
        the duration; ``(None, None, "no program line known")`` without one."""
        path = self.path
        dt = np.diff(self.t)
        seg = np.asarray(self.segment, dtype=int)
        per_block: dict = {}
        moving = seg >= 0
        if moving.any():
            times = np.bincount(seg[moving], weights=dt[moving], minlength=len(path.segments))
            for k in np.flatnonzero(times > 0.0):
                blk = path.segments[int(k)].block
                if blk is not None:
                    per_block[blk.source] = per_block.get(blk.source, 0.0) + float(times[k])
        for _, seconds, blk in path.toolpath.dwells:
            if blk is not None:
                per_block[blk.source] = per_block.get(blk.source, 0.0) + float(seconds)
        if not per_block:
            return None, None, "no program line known"
        src, longest = max(per_block.items(), key=lambda kv: kv[1])
        share = longest / self.duration if self.duration > 0 else 1.0
        return src.line, src.col, (f"line {src.line} alone takes {longest:.6g} s, "
                                   f"{share:.0%} of the time")

    def sample_count(self, dt: float) -> int:
        """How many samples :meth:`sample` ``(dt)`` gives (without making them):
        every ``dt`` from 0 and the final instant. :class:`FeedError` when that
        is more than :data:`MAX_FEED_SAMPLES` (a larger ``dt`` is needed)."""
        if not dt > 0:
            raise ValueError("dt must be > 0")
        T = self.duration
        if T / dt >= MAX_FEED_SAMPLES:
            line, col, what = self.longest_block()
            raise FeedError(f"sampling {T:.6g} s every {dt:g} s takes {T / dt:.3g} samples, more "
                            f"than {MAX_FEED_SAMPLES:g} ({what}): use a larger dt (at least "
                            f"{self.affordable_dt(dt):.3g} s)", self.path.source_file, line, col)
        n = int(np.floor(T / dt + _SAMPLE_COUNT_SLACK)) + 1
        return n + 1 if (n - 1) * dt < T else n

    def motion(self, times: np.ndarray):
        """``(s, sd, sdd, sddd, segment)`` at ``times`` (inside ``[0, duration]``):
        path position, speed, acceleration, jerk and the piece's segment (-1 in
        dwells). Here constant acceleration per piece (``sddd = 0``); profiles
        with other pieces override this."""
        M = self.sdd.size
        idx = np.clip(np.searchsorted(self.t, times, side="right") - 1, 0, M - 1)
        tau = np.clip(times - self.t[idx], 0.0, self.t[idx + 1] - self.t[idx])
        u = self.sdd[idx]
        v = np.maximum(self.sd[idx] + u * tau, 0.0)
        s = np.clip(self.s[idx] + self.sd[idx] * tau + 0.5 * u * tau * tau,
                    self.s[idx], self.s[idx + 1])
        return s, v, u, np.zeros_like(u), self.segment[idx]

    def at(self, times) -> FeedSamples:
        """The profile at the given times (s), clipped to ``[0, duration]``."""
        times = np.clip(np.atleast_1d(np.asarray(times, dtype=float)), 0.0, self.duration)
        M = self.sdd.size
        path = self.path
        dof = path.dof
        axes = self.limits.axis_names(path.frame, dof)
        vlim, alim = self.limits.in_plane(path.frame, dof)
        jlim = self.limits.jerk_in_plane(path.frame, dof)
        n = times.size
        if M == 0 or not path.segments:
            # no motion: the path stands (a dwell alone still takes its time)
            z = np.zeros(n)
            pos = np.zeros((n, dof))
            if path.segments:
                pos[:] = path.eval_segments(np.zeros(1, int), np.zeros(1), 0)[0]
            return FeedSamples(times, z, np.full(n, -1), np.full(n, -1), pos, np.zeros((n, dof)),
                               np.zeros((n, dof)), z, z, z, np.full(n, np.inf), axes, vlim, alim,
                               self.limits.tangential_acc, self.limits.centripetal_acc,
                               np.zeros((n, dof)), jlim)
        s, v, u, w, seg = self.motion(times)
        return self._samples(times, s, v, u, w, seg)

    def _samples(self, times, s, v, u, w, seg) -> FeedSamples:
        """Samples from the motion ``(s, v, u, w, seg)`` at ``times`` (see :meth:`motion`)."""
        path = self.path
        dof = path.dof
        axes = self.limits.axis_names(path.frame, dof)
        vlim, alim = self.limits.in_plane(path.frame, dof)
        jlim = self.limits.jerk_in_plane(path.frame, dof)
        seg_eval = np.where(seg >= 0, seg, path.locate(s))
        q, q1, q2, q3 = path.eval_orders(seg_eval, s, (0, 1, 2, 3))
        vel = q1 * v[:, None]
        acc = q2 * (v * v)[:, None] + q1 * u[:, None]
        jerk = q3 * (v ** 3)[:, None] + q2 * (3.0 * v * u)[:, None] + q1 * w[:, None]
        line = np.array([b.source.line if b is not None else -1
                         for b in (sg.block for sg in path.segments)], dtype=int)
        feed_cap = np.where(seg >= 0, path.feeds[seg_eval], np.inf)
        return FeedSamples(times, s, seg, np.where(seg >= 0, line[seg_eval], -1), q, vel, acc, v,
                           u, np.linalg.norm(q2, axis=1), feed_cap, axes, vlim, alim,
                           self.limits.tangential_acc, self.limits.centripetal_acc, jerk, jlim)

    def figure_samples(self, dt: float = 1e-3) -> tuple[FeedSamples, np.ndarray]:
        """Samples whose maxima are the profile's to :data:`~ccopt.feed.figures.FIGURE_TOL`
        of each limit, and each sample's share of the time (s, summing to the duration).

        Pieces of constant path acceleration (this class's :meth:`motion`) are
        sampled at both ends and at a step set by the geometry and the motion,
        :mod:`ccopt.feed.figures` (the bound is stated there); pieces on curves
        with no derivative bounds, and profiles with other pieces (jerk-limited
        ones override :meth:`motion`), every ``dt`` as :meth:`sample`.
        """
        if (type(self).motion is not FeedProfile.motion or self.sdd.size == 0
                or not self.path.segments):
            smp = self.sample(dt)
            return smp, _time_shares(smp.t)
        path = self.path
        dof = path.dof
        vlim, alim = self.limits.in_plane(path.frame, dof)
        jlim = self.limits.jerk_in_plane(path.frame, dof)
        speed = np.maximum(self.sd[:-1], self.sd[1:])
        steps = piece_steps(self._derivative_bounds(), self.segment, speed, np.abs(self.sdd),
                            float(np.min(vlim)), float(np.min(alim)),
                            None if jlim is None else float(np.min(jlim)),
                            self.limits.centripetal_acc, dt)
        piece, tau = piece_times(self.t, steps)
        if piece.size >= MAX_FEED_SAMPLES:
            line, col, what = self.longest_block()
            raise FeedError(f"the profile's figures need {piece.size:.3g} samples, more than "
                            f"{MAX_FEED_SAMPLES:g} ({what})", self.path.source_file, line, col)
        u = self.sdd[piece]
        v = np.maximum(self.sd[piece] + u * tau, 0.0)
        s = np.clip(self.s[piece] + self.sd[piece] * tau + 0.5 * u * tau * tau,
                    self.s[piece], self.s[piece + 1])
        times = self.t[piece] + tau
        smp = self._samples(times, s, v, u, np.zeros_like(u), self.segment[piece])
        # each step's time, half to either end (a piece's samples cover it exactly)
        share = np.zeros(piece.size)
        inner = np.flatnonzero(piece[1:] == piece[:-1])
        step = np.diff(tau)[inner]
        np.add.at(share, inner, 0.5 * step)
        np.add.at(share, inner + 1, 0.5 * step)
        return smp, share

    def _derivative_bounds(self) -> np.ndarray:
        return derivative_bounds([sg.geom for sg in self.path.segments])

    # -- reports -------------------------------------------------------------

    def summary(self, dt: float = 1e-3, samples: FeedSamples | None = None) -> dict:
        """``duration``, ``samples`` (how many :meth:`sample` ``(dt)`` gives), the
        largest axis velocity, acceleration and jerk ratios ``|value| / limit``
        and feed ratio over the profile (:meth:`figure_samples`: within
        :data:`~ccopt.feed.figures.FIGURE_TOL` of the true maxima, or at the
        ``dt`` samples where no bound is known), ``active_share`` (share of the
        time each limit is the active one, at those samples) and planner
        details. ``samples``: the ``dt`` samples when the caller has them
        (counted, not searched: the figures come from :meth:`figure_samples`)."""
        count = len(samples) if samples is not None else self.sample_count(dt)
        smp, share = self.figure_samples(dt)
        out = {
            "planner": self.planner,
            "duration": self.duration,
            "dwell_time": self.dwell_time,
            "samples": count,
            "dt": dt,
            "max_axis_vel_ratio": float(smp.axis_velocity_ratio.max(initial=0.0)),
            "max_axis_acc_ratio": float(smp.axis_acceleration_ratio.max(initial=0.0)),
            # None when the limits give no jerk limit; the jerk itself always
            "max_axis_jerk_ratio": (float(smp.axis_jerk_ratio.max(initial=0.0))
                                    if smp.j_limit is not None else None),
            "max_axis_jerk": float(np.abs(smp.jerk).max(initial=0.0)),
            "max_feed_ratio": float(smp.feed_ratio.max(initial=0.0)),
            "axes": list(smp.axes),
        }
        names = np.array(smp.limit_names, dtype=object)
        total = float(share.sum())
        if not total > 0.0:
            share, total = np.ones(len(smp)), float(max(len(smp), 1))
        counts = np.bincount(smp.active, weights=share, minlength=len(names))
        out["active_share"] = {str(names[i]): round(float(c) / total, 6)
                               for i, c in enumerate(counts) if c}
        out.update({k: v for k, v in self.info.items() if isinstance(v, (int, float, str))})
        return out

    def to_csv(self, file, dt: float = 1e-3) -> None:
        """Write :meth:`sample` ``(dt)`` as CSV (:meth:`FeedSamples.to_csv_text`),
        atomically, :data:`CSV_CHUNK` samples at a time: the memory it takes
        does not grow with the program's duration (a 23-minute program at
        1 ms, 1.4 million rows, took 1.7 GB made at once)."""
        n = self.sample_count(dt)

        def write(tmp: Path) -> None:
            with open(tmp, "w", encoding="utf-8", newline="") as fh:
                for i in range(0, n, CSV_CHUNK):
                    times = np.arange(i, min(i + CSV_CHUNK, n)) * dt   # as sample() makes them
                    if i + times.size == n:
                        times[-1] = min(times[-1], self.duration)
                    fh.write(self.at(times).to_csv_text(header=i == 0))

        write_with_atomic(file, write)


def _time_shares(t: np.ndarray) -> np.ndarray:
    """Each sample's share of the time (s): half of the step on either side."""
    step = np.diff(t)
    return np.r_[0.5 * step, 0.0] + np.r_[0.0, 0.5 * step]
