"""The smoothed path's distance from PMAC's, both ways, measured window by window.

:func:`ccopt.compare.figures.max_deviation` bounds the Hausdorff distance
between two paths; on a path of hundreds of blends its cost grows with the
square of the segment count. The smoothed path and PMAC's coincide on every
straight piece a blend leaves of a line, so both can be cut at a common point
of such a piece (its middle): the Hausdorff distance of two unions is at most
the largest over matching windows, and each window is measured by
``max_deviation`` itself. :func:`windowed_deviation` cuts about every
:data:`WINDOW` segments where such a piece lies on PMAC's line.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ccopt.compare.deviation import max_deviation
from ccopt.geometry import Line
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import Role, ToolPath

#: Segments of the smoothed path per window, about.
WINDOW = 40


def _on_line(c, line: Line) -> float | None:
    """Arc length of ``c`` along ``line`` if it lies on it (within ``POINT_EPS``)."""
    p0, p1 = np.asarray(line.p0, float), np.asarray(line.p1, float)
    L = line.length
    if L <= 0:
        return None
    t = (p1 - p0) / L
    s = float((c - p0) @ t)
    if not 0.0 < s < L or float(np.hypot(*(p0 + s * t - c))) > POINT_EPS:
        return None
    return s


def _cuts(path: ToolPath, ref: ToolPath, origin: list):
    """``(k, c, s)``: cut the smoothed path's segment ``k`` and PMAC's segment
    ``origin[k]`` at their common point ``c`` (``s`` along PMAC's)."""
    out, last = [], 0
    segs = path.segments
    for k, seg in enumerate(segs):
        if k - last < WINDOW or seg.role is not Role.COMPENSATED or not isinstance(seg.geom, Line):
            continue
        rg = ref.segments[origin[k]].geom
        if not isinstance(rg, Line) or seg.length <= 2 * POINT_EPS:
            continue
        c = 0.5 * (np.asarray(seg.geom.p0, float) + np.asarray(seg.geom.p1, float))
        s = _on_line(c, rg)
        if s is not None:
            out.append((k, c, s))
            last = k
    return out


def _sub(path: ToolPath, segs) -> ToolPath:
    return ToolPath(tuple(segs), plane=path.plane, style=path.style, radius=path.radius,
                    units=path.units)


def _halves(seg, c):
    g = seg.geom
    return (replace(seg, geom=Line(g.p0, tuple(map(float, c)))),
            replace(seg, geom=Line(tuple(map(float, c)), g.p1)))


def windowed_deviation(path: ToolPath, ref: ToolPath, origin: list) -> tuple[float, float]:
    """``(Hausdorff distance estimate, upper bound)`` between ``path`` and ``ref`` as
    :func:`~ccopt.compare.figures.max_deviation` gives them, window by window
    (module docstring); ``origin[k]``: the index in ``ref`` of the segment that
    ``path``'s segment ``k`` came from (non-decreasing)."""
    cuts = _cuts(path, ref, origin)
    if not cuts:
        return max_deviation(path, ref)
    est = bound = 0.0
    a_new, a_ref, carry_new, carry_ref = 0, 0, [], []
    for k, c, _s in cuts + [(None, None, None)]:
        if k is None:
            new = carry_new + list(path.segments[a_new:])
            old = carry_ref + list(ref.segments[a_ref:])
        else:
            j = origin[k]
            n0, n1 = _halves(path.segments[k], c)
            r0, r1 = _halves(ref.segments[j], c)
            new = carry_new + list(path.segments[a_new:k]) + [n0]
            old = carry_ref + list(ref.segments[a_ref:j]) + [r0]
            carry_new, carry_ref, a_new, a_ref = [n1], [r1], k + 1, j + 1
        e, b = max_deviation(_sub(path, new), _sub(ref, old))
        est, bound = max(est, e), max(bound, b)
    return est, bound
