"""Figures of a tool path for the comparison: length, curvature, continuity,
deviation from a reference.

Continuity classes at a join between consecutive in-plane segments:
``"G2"`` (position, tangent and curvature agree), ``"G1"`` (position and
tangent), ``"G0"`` (position only), ``"gap"``. Tolerances: positions
:data:`ccopt.tolerances.VERIFY_EPS`, tangents
:data:`ccopt.tolerances.VERIFY_TANGENT_BREAK` (radians), curvature
:data:`ccopt.tolerances.CURVATURE_TOL` (1/units, relative to ``max(1, |kappa|)``).

Curvature of lines and arcs is exact; spirals and Bezier curves are sampled
(:data:`~ccopt.compare.parts.CURVE_SAMPLES` points, end points included),
which is what a comparison figure needs.

Deviation from a reference path: :mod:`ccopt.compare.deviation`.
"""
from __future__ import annotations

import math

import numpy as np

# the deviation figure, in its own module, named here too
from ccopt.compare.deviation import _shared, max_deviation  # noqa: F401
from ccopt.compare.parts import FEED_ROLES, curvature_samples, end_curvatures
from ccopt.compare.parts import in_plane as _in_plane
from ccopt.tolerances import CURVATURE_TOL, VERIFY_EPS, VERIFY_TANGENT_BREAK
from ccopt.toolpath import ToolPath


_ORDER = {"gap": 0, "G0": 1, "G1": 2, "G2": 3}


def worst(classes) -> str | None:
    classes = list(classes)
    return min(classes, key=_ORDER.__getitem__) if classes else None


def join_class(a, b) -> tuple[str, float, float, float]:
    """``(class, gap, tangent angle, curvature jump)`` of the join ``a`` -> ``b``."""
    gap = math.dist(a.end, b.start)
    ta = np.asarray(a.geom.end_tangent, float)
    tb = np.asarray(b.geom.start_tangent, float)
    ang = math.atan2(abs(ta[0] * tb[1] - ta[1] * tb[0]), float(ta @ tb))
    ka = end_curvatures(a.geom)[1]
    kb = end_curvatures(b.geom)[0]
    jump = abs(kb - ka)
    if gap > VERIFY_EPS:
        return "gap", gap, ang, jump
    if ang > VERIFY_TANGENT_BREAK:
        return "G0", gap, ang, jump
    if jump > CURVATURE_TOL * max(1.0, abs(ka), abs(kb)):
        return "G1", gap, ang, jump
    return "G2", gap, ang, jump


def joins(path: ToolPath, roles=FEED_ROLES) -> list[tuple[int, str, float, float, float]]:
    """Every join between consecutive in-plane segments whose roles are in
    ``roles``: ``(index of the second segment, class, gap, angle, jump)``.
    A segment with no in-plane motion (a plunge) interrupts the path."""
    segs = path.segments
    out = []
    for i in range(1, len(segs)):
        a, b = segs[i - 1], segs[i]
        if a.role in roles and b.role in roles and _in_plane(a) and _in_plane(b):
            out.append((i, *join_class(a, b)))
    return out


def path_figures(path: ToolPath, join_indices=None) -> dict:
    """Length, curvature and continuity figures of ``path``.

    ``join_indices``: the boundaries the variant made (segment index after
    each); ``continuity`` is the worst class among them (``None`` if none),
    ``path_continuity`` the worst over every feed join of the path.
    """
    feed = [s for s in path.segments if s.role in FEED_ROLES and _in_plane(s)]
    kmax = max((float(np.max(np.abs(curvature_samples(s.geom)))) for s in feed), default=0.0)
    all_joins = joins(path)
    g1 = [j for j in all_joins if j[1] in ("G1", "G2")]
    jump = max((j[4] for j in g1), default=0.0)
    by_index = {j[0]: j for j in all_joins}
    mine = [by_index[i] for i in (join_indices or []) if i in by_index]
    return {
        "length": float(path.length),
        "feed_length": float(sum(s.length for s in feed)),
        "max_curvature": kmax,
        "max_curvature_jump": float(jump),
        "tangent_breaks": int(sum(1 for j in all_joins if j[1] in ("G0", "gap"))),
        "continuity": worst(j[1] for j in mine),
        "path_continuity": worst(j[1] for j in all_joins),
        "joins": [{"segment": j[0], "class": j[1], "angle": j[3], "curvature_jump": j[4]}
                  for j in mine],
    }


# --------------------------------------------------------------------------- deviation
