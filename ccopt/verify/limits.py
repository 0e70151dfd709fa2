"""Limits: axis velocity and acceleration, and the programmed feed, from samples.

Works on a :class:`ccopt.feed.FeedProfile` (sampled with ``sample(dt)``) or
on anything shaped like its samples (duck typing, so other planners plug in):

- ``t``: ``(n,)`` times (s);
- ``velocity`` or ``vel``, ``acceleration`` or ``acc``: ``(n, dof)`` axis
  values (units/s, units/s^2);
- ``v_limit`` or ``vmax``, ``a_limit`` or ``amax``: ``(dof,)`` limits;
- optional ``feed`` ``(n,)`` tangential speed with ``feed_cap`` ``(n,)``
  programmed feed (``inf`` on rapids); optional ``axes`` names, ``line``
  ``(n,)`` source lines, ``tangential_acc`` with ``tangential_limit``,
  ``curvature`` with ``centripetal_limit``.

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
                 "axis |velocity|, |acceleration| and feed at most their limits at every sample, "
                 f"within {rel_tol:g} relative (figure: largest |value| / limit)", int(t.size), len(viol),
                 {"largest": worst_name}), viol
