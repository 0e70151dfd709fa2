"""Corner speeds: stop at every tangent break, or grbl's junction deviation.

By default the path stops (speed 0) at every tangent discontinuity, at every
dwell and at the ends. With a junction deviation ``delta`` (program units)
a corner may be taken at the speed grbl allows (``planner.c``,
``plan_buffer_line``): the speed at which a circle of radius ``R`` tangent to
both moves, whose closest point lies ``delta`` from the corner, is followed
with the centripetal acceleration ``a``::

    sin(theta/2) = sqrt((1 - cos_theta) / 2),  cos_theta = -t_in . t_out
    R            = delta * sin(theta/2) / (1 - sin(theta/2))
    v_corner^2   = a * R

with ``a`` the axis acceleration limit along the junction direction
``t_out - t_in`` (grbl's ``limit_value_by_axis_maximum``). This is an
APPROXIMATION, as in grbl: the tool does not follow that circle, it turns the
corner sharply, so the axis velocities jump by ``v_corner * |t_out - t_in|``
at the corner and the sampled accelerations do not contain that impulse.
A reversal (``cos_theta`` near 1) and a dwell always stop.
"""
from __future__ import annotations

import numpy as np

from ccopt.feed.path import ExactPath
from ccopt.tolerances import GAP_EPS

#: grbl's thresholds on cos(theta) for "reversal" and "straight".
REVERSAL_COS = 0.999999
STRAIGHT_COS = -0.999999


def junction_speed(t_in, t_out, a_axis, deviation: float) -> np.ndarray:
    """grbl corner speed (units/s) for unit tangents ``t_in``, ``t_out`` (``(n, dof)``)."""
    t_in = np.atleast_2d(np.asarray(t_in, dtype=float))
    t_out = np.atleast_2d(np.asarray(t_out, dtype=float))
    a_axis = np.asarray(a_axis, dtype=float)
    cos_theta = -np.einsum("ij,ij->i", t_in, t_out)
    j = t_out - t_in
    jn = np.linalg.norm(j, axis=1, keepdims=True)
    j = np.divide(j, jn, out=np.zeros_like(j), where=jn > 0)
    aj = np.abs(j)
    with np.errstate(divide="ignore"):
        a = np.where(aj > 0, a_axis / np.where(aj > 0, aj, 1.0), np.inf).min(axis=1)
    sin_half = np.sqrt(np.clip(0.5 * (1.0 - cos_theta), 0.0, 1.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        v2 = a * deviation * sin_half / (1.0 - sin_half)
    v = np.sqrt(np.where(np.isfinite(v2), v2, np.inf))
    v = np.where(cos_theta > REVERSAL_COS, 0.0, v)
    v = np.where(cos_theta < STRAIGHT_COS, np.inf, v)
    return v


def boundary_speed_caps(path: ExactPath, a_axis, junction_deviation: float | None) -> np.ndarray:
    """Speed cap (units/s) at each of the ``K + 1`` segment boundaries of ``path``.

    ``inf`` where nothing but the neighbouring segments limits the speed
    (tangent-continuous joins), 0 at the ends, at dwells and at tangent
    breaks (or the grbl corner speed there when ``junction_deviation`` is given).
    """
    K = len(path.segments)
    cap = np.full(K + 1, np.inf)
    cap[0] = cap[-1] = 0.0
    brk = np.flatnonzero(path.tangent_break)
    if brk.size:
        if junction_deviation is None or junction_deviation <= 0.0:
            cap[brk] = 0.0
        else:
            t_in = path.end_tangent[brk - 1]
            t_out = path.start_tangent[brk]
            v = junction_speed(t_in, t_out, a_axis, junction_deviation)
            # an actual gap in the path (not just a turn) always stops
            p_end = path.eval_segments(brk - 1, path.offsets[brk], 0)
            p_start = path.eval_segments(brk, path.offsets[brk], 0)
            gap = np.linalg.norm(p_end - p_start, axis=1) > GAP_EPS
            cap[brk] = np.where(gap, 0.0, v)
    if path.dwells:
        at = np.searchsorted(path.offsets, [d.s for d in path.dwells])
        cap[at] = 0.0
    return cap
