"""Geometric lead-in/lead-out variants that need no optimiser.

Both are built on PMAC's compensated path: the lead (see :mod:`.leads`) is
replaced by a construction ending tangent to the host at its start ``J``
(PMAC's first compensated point), on the free side of the path:

- ``tangent-arc``: a quarter circle of radius ``rho`` tangent to the host at
  ``J`` (centre ``C = J + rho*k*n``, ``n`` the host's left normal, ``k`` the
  free side), preceded by a straight move from the approach point to the
  quarter circle's start ``C - rho*t`` (a corner there unless it is in line);
- ``line-arc``: the straight line from the approach point tangent to that
  circle, then the arc from the tangent point to ``J`` (tangent-continuous
  all the way; the arc sweeps whatever the tangent point gives).

``rho`` is the option ``lead_radius`` (program units), by default the cutter
radius. A lead-out is the same construction on the reversed lead.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.compare.leads import LeadGeometry, straight_line
from ccopt.geometry import Arc
from ccopt.geometry.angles import TWO_PI

#: The approach point must lie outside the lead circle by this share of its
#: radius: nearer, the tangent from it is too ill-conditioned to construct.
OUTSIDE_CIRCLE_REL = 1e-9

#: A tangent arc of at most this length (program units) is left out: the
#: tangent point is the join itself (rounding only).
NO_ARC_LENGTH = 1e-12


class ConstructionError(ValueError):
    """The construction does not exist for this lead (e.g. approach point inside the circle)."""


def _frame(lg: LeadGeometry, rho: float):
    J = np.asarray(lg.host.start, float)
    t = np.asarray(lg.host.start_tangent, float)
    n = np.array([-t[1], t[0]])
    C = J + rho * lg.side * n
    return J, t, n, C


def tangent_arc(lg: LeadGeometry, rho: float) -> list:
    """Line to the quarter circle's start, then the quarter circle onto ``J``."""
    if not rho > 0:
        raise ConstructionError(f"lead radius must be > 0, got {rho!r}")
    J, t, _, C = _frame(lg, rho)
    S = C - rho * t
    arc = Arc(tuple(C), rho, math.atan2(-t[1], -t[0]), lg.side * 0.5 * math.pi)
    return [straight_line(lg.approach, S), arc]


def line_arc(lg: LeadGeometry, rho: float) -> list:
    """The tangent from the approach point to the circle, then the arc onto ``J``."""
    if not rho > 0:
        raise ConstructionError(f"lead radius must be > 0, got {rho!r}")
    J, t, _, C = _frame(lg, rho)
    A = np.asarray(lg.approach, float)
    v = A - C
    d = math.hypot(*v)
    if d <= rho * (1.0 + OUTSIDE_CIRCLE_REL):
        raise ConstructionError(f"the approach point is within the lead circle (radius {rho:g}): "
                                "no tangent line")
    alpha = math.acos(rho / d)
    beta = math.atan2(v[1], v[0])
    k = lg.side
    best = None
    for phi in (beta + alpha, beta - alpha):
        T = C + rho * np.array([math.cos(phi), math.sin(phi)])
        u = T - A
        u /= math.hypot(*u)
        tang = k * np.array([-math.sin(phi), math.cos(phi)])
        score = float(u @ tang)
        if best is None or score > best[0]:
            best = (score, phi, T)
    _, phiT, T = best
    phiJ = math.atan2(J[1] - C[1], J[0] - C[0])
    if k > 0:
        sweep = (phiJ - phiT) % TWO_PI
    else:
        sweep = -((phiT - phiJ) % TWO_PI)
    geoms = [straight_line(A, T)]
    if abs(sweep) * rho > NO_ARC_LENGTH:
        geoms.append(Arc(tuple(C), rho, phiT, sweep))
    return geoms
