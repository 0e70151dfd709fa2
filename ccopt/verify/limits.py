"""Limits: axis velocity, acceleration and jerk, and the programmed feed, from samples.

Works on a :class:`ccopt.feed.FeedProfile` (sampled with ``sample(dt)``) or
on anything shaped like its samples (duck typing, so other planners plug in):

- ``t``: ``(n,)`` times (s);
- ``velocity`` or ``vel``, ``acceleration`` or ``acc``: ``(n, dof)`` axis
  values (units/s, units/s^2);
- ``v_limit`` or ``vmax``, ``a_limit`` or ``amax``: ``(dof,)`` limits;
- optional ``feed`` ``(n,)`` tangential speed with ``feed_cap`` ``(n,)``
  programmed feed (``inf`` on rapids); optional ``axes`` names, ``line``
  ``(n,)`` source lines, ``tangential_acc`` with ``tangential_limit``,
  ``curvature`` with ``centripetal_limit``; optional ``j_limit`` or ``jmax``
  ``(dof,)`` axis jerk limits (units/s^3), checked against ``jerk``
  ``(n, dof)`` at the samples when they carry it, and between samples: the
  change of the acceleration from one sample to the next is at most ``J``
  times their time step, so an acceleration step (a trapezoid's switch, which
  the jerk at the samples does not show) fails. A profile planned with an
  interpolation period ``ts`` (``info["ts"]``: the ``jerk`` planner and the
  jerk-limited ``junction`` baseline, which allow a step of ``J ts`` at a
  curvature break, :mod:`ccopt.feed.jerk.planner`) is allowed ``J (dt + ts)``.

A sample fails when ``|value| > limit * (1 + limits_tol)``, a stated relative
tolerance: :data:`LIMITS_TOL` (0.1 %) by default, the certificate's
``limits_tol``. Why not zero: the samples are exact values of the planned
profile, but a profile planned on a grid is only held to its limits at the
gridpoints and within the grid's margin between them (TOPPRA's planner shrinks
its limits by that margin; another planner, a controller's log, or a profile
rounded to a servo period may ride a limit by a few 1e-4), and a machine's
limits are not known to that precision: a 0.015 % excess is no reason to
refuse a path whose geometry is right. The
figure is the largest ratio ``|value| / limit`` over everything checked; the
basis is ``sampled`` (a check at the samples, not between them). Consecutive
failing samples of one quantity are one violation (its worst sample).
"""
from __future__ import annotations

import numpy as np

from ccopt.verify.certificate import NOT_RUN, SAMPLED, Check, Violation

#: Sampling step (s) when a profile with ``sample(dt)`` is given.
SAMPLE_DT = 1e-3

#: Default relative tolerance of the limits check: a sample may exceed its limit
#: by this fraction (0.1 %) before it fails (see the module docstring).
LIMITS_TOL = 1e-3

#: Sample steps (s) shorter than this (a profile's end sampled twice, a
#: rounding apart) are not timed for the jerk between samples: the change of
#: the acceleration across them is rounding, not jerk.
MIN_SAMPLE_STEP = 1e-9

#: At most this many limit violations are listed.
MAX_LISTED = 200


def _get(obj, *names, default=None):
    for n in names:
        if hasattr(obj, n):
            v = getattr(obj, n)
            if v is not None:
                return v
    return default


def samples_of(profile):
    """The samples of ``profile`` (a FeedProfile or already samples)."""
    if hasattr(profile, "sample") and callable(profile.sample) and not hasattr(profile, "velocity"):
        return profile.sample(SAMPLE_DT)
    return profile


def _jerk_quantities(smp, t: np.ndarray, acc: np.ndarray, axes, step_period: float) -> list:
    """The axis jerk against its limit ``J`` (``j_limit`` or ``jmax``), when
    given: the samples' ``jerk`` at each sample (when they carry it), and
    between consecutive samples the change of the acceleration, ``|Delta a|``
    at most ``J (Delta t + step_period)`` (reported at the later sample;
    ``step_period``: the acceleration step a jerk-limited planner allows at a
    curvature break, ``J ts``, else 0)."""
    jlim = _get(smp, "j_limit", "jmax")
    if jlim is None or t.size < 2:
        return []
    jlim = np.asarray(jlim, float)
    out = []
    jerk = _get(smp, "jerk")
    dof = min(jlim.size, acc.shape[1])
    if jerk is not None:
        jerk = np.atleast_2d(np.asarray(jerk, float))
        if jerk.shape[0] != t.size and jerk.shape[1] == t.size:
            jerk = jerk.T
        out += [("jerk", axes[i], np.abs(jerk[:, i]) / jlim[i], jerk[:, i],
                 np.full(t.size, jlim[i])) for i in range(dof)]
    dt = np.diff(t)
    # no change before the first sample, nor over a step too short to time
    span = np.r_[np.inf, np.where(dt > MIN_SAMPLE_STEP, dt + step_period, np.inf)]
    change = np.vstack([np.zeros((1, acc.shape[1])), np.diff(acc, axis=0)])
    for i in range(dof):
        mean = change[:, i] / span                          # units/s^3 between samples
        out.append(("jerk", f"{axes[i]} between samples", np.abs(mean) / jlim[i], mean,
                    np.full(t.size, jlim[i])))
    return out


def check_limits(profile, rel_tol: float = LIMITS_TOL):
    """The ``limits`` check of ``profile`` (see the module docstring) and its
    violations; ``rel_tol``: the relative tolerance (dimensionless, >= 0)."""
    if profile is None:
        return Check("limits", True, None, rel_tol, NOT_RUN, "ratio",
                     "no feed profile given"), []
    smp = samples_of(profile)
    t = np.asarray(_get(smp, "t"), float)
    vel = np.atleast_2d(np.asarray(_get(smp, "velocity", "vel"), float))
    acc = np.atleast_2d(np.asarray(_get(smp, "acceleration", "acc"), float))
    vlim = np.asarray(_get(smp, "v_limit", "vmax"), float)
    alim = np.asarray(_get(smp, "a_limit", "amax"), float)
    if vel.shape[0] != t.size and vel.shape[1] == t.size:
        vel, acc = vel.T, acc.T
    dof = vel.shape[1]
    axes = tuple(_get(smp, "axes", default=tuple("UVW"[:dof]) if dof <= 3 else
                      tuple(str(i) for i in range(dof))))
    lines = _get(smp, "line")
    lines = np.asarray(lines) if lines is not None else None
    quantities = []   # (kind, name, ratio array, value array, limit array)
    for i in range(dof):
        quantities.append(("velocity", axes[i], np.abs(vel[:, i]) / vlim[i], vel[:, i],
                           np.full(t.size, vlim[i])))
        quantities.append(("acceleration", axes[i], np.abs(acc[:, i]) / alim[i], acc[:, i],
                           np.full(t.size, alim[i])))
    info = getattr(profile, "info", None)
    step_period = float(info.get("ts", 0.0)) if isinstance(info, dict) else 0.0
    quantities.extend(_jerk_quantities(smp, t, acc, axes, step_period))
    feed = _get(smp, "feed")
    cap = _get(smp, "feed_cap")
    if feed is not None and cap is not None:
        feed = np.asarray(feed, float)
        cap = np.asarray(cap, float)
        fin = np.isfinite(cap) & (cap > 0)
        ratio = np.where(fin, np.abs(feed) / np.where(fin, cap, 1.0), 0.0)
        quantities.append(("feed", "feed", ratio, feed, cap))
    tl = _get(smp, "tangential_limit")
    ta = _get(smp, "tangential_acc")
    if tl is not None and ta is not None:
        ta = np.asarray(ta, float)
        quantities.append(("acceleration", "tangential", np.abs(ta) / tl, ta, np.full(t.size, tl)))
    cl = _get(smp, "centripetal_limit")
    cu = _get(smp, "curvature")
    if cl is not None and cu is not None and feed is not None:
        ca = np.asarray(cu, float) * np.asarray(feed, float) ** 2
        quantities.append(("acceleration", "centripetal", ca / cl, ca, np.full(t.size, cl)))
    worst = 0.0
    worst_name = None
    viol: list[Violation] = []
    for kind, name, ratio, value, limit in quantities:
        if ratio.size == 0:
            continue
        m = float(ratio.max())
        if m > worst:
            worst, worst_name = m, f"{kind} {name}"
        bad = ratio > 1.0 + rel_tol
        if not bad.any():
            continue
        # runs of consecutive failing samples
        edges = np.flatnonzero(np.diff(np.r_[0, bad.astype(np.int8), 0]))
        for a, b in zip(edges[::2], edges[1::2]):
            k = a + int(np.argmax(ratio[a:b]))
            if len(viol) >= MAX_LISTED:
                break
            line = int(lines[k]) if lines is not None and lines[k] >= 0 else None
            viol.append(Violation(kind, float(ratio[k] - 1.0), None, line, None,
                                  basis=SAMPLED,
                                  detail={"quantity": name, "time": float(t[k]),
                                          "value": float(value[k]), "limit": float(limit[k]),
                                          "samples": int(b - a)}))
    return Check("limits", not viol, worst, rel_tol, SAMPLED, "ratio",
                 "axis |velocity|, |acceleration|, |jerk| (when jerk limits are given) and feed "
                 "at most their limits at every sample, "
                 f"within {rel_tol:g} relative (figure: largest |value| / limit)", int(t.size), len(viol),
                 {"largest": worst_name}), viol
