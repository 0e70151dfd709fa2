"""What the comparison's figures measure of a tool path: which segments (by
role, in the plane), and the curvature along a primitive.

Shared by the figures of a path (:mod:`ccopt.compare.figures`) and its
deviation from a reference (:mod:`ccopt.compare.deviation`).
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry import Arc, Line
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role

#: Segments cut with compensation in force: the part contour's.
CONTOUR_ROLES = (Role.COMPENSATED, Role.CORNER)
#: Segments at the feed: the contour's and the leads.
FEED_ROLES = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)

#: Samples per spiral or curve for curvature figures.
CURVE_SAMPLES = 257


def in_plane(seg) -> bool:
    """Whether ``seg`` moves in the plane (more than :data:`~ccopt.tolerances.POINT_EPS`)."""
    return seg.length > POINT_EPS


def curvature_samples(g) -> np.ndarray:
    """Signed curvature along a primitive (1/units)."""
    if isinstance(g, Line):
        return np.zeros(2)
    if isinstance(g, Arc):
        return np.full(2, math.copysign(1.0 / g.radius, g.sweep))
    s = np.linspace(0.0, g.length, CURVE_SAMPLES)
    return np.atleast_1d(np.asarray(g.curvature(s), float))


def end_curvatures(g) -> tuple[float, float]:
    """Signed curvature at the start and end of a primitive (1/units)."""
    if isinstance(g, Line):
        return 0.0, 0.0
    if isinstance(g, Arc):
        k = math.copysign(1.0 / g.radius, g.sweep)
        return k, k
    return float(g.curvature(0.0)), float(g.curvature(g.length))
