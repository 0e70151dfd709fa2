"""Spirals (and other smooth curves) as chains of circular arcs, with a bound.

G-code has no spiral, so an exported spiral becomes arcs through three points
of the curve (start, middle, end of each piece), split until a **certified**
bound on the distance between the curve and its arc is within ``tol``.

The bound: with ``f(s) = |p(s) - c| - R`` (the radial distance of the curve
from the arc's circle, ``s`` arc length), ``|f''| <= kappa_max + 1/|p - c|``
because ``|p'| = 1`` and ``|p''| = kappa``. Between samples ``h`` apart a
function with ``|f''| <= M`` exceeds the larger sampled ``|f|`` by at most
``M*h^2/8``, so ``max|f| <= max_i |f(s_i)| + M*h^2/8``. For an Archimedean
spiral the curvature ``(rho^2 + 2b^2)/(rho^2 + b^2)^1.5`` decreases as ``rho``
grows, so ``kappa_max`` on a piece is its value at the smaller radius.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.geometry import Arc, Spiral

#: Samples per piece for the bound (the second-order term shrinks as 1/n^2).
SAMPLES = 32


@dataclass(frozen=True)
class FittedArc:
    """An arc replacing a piece of curve, and the certified deviation bound."""

    arc: Arc
    bound: float


def circle_through(p0, p1, p2):
    """Centre and radius of the circle through three points, or ``None`` when
    they are (nearly) collinear."""
    ax, ay = p0
    bx, by = p1
    cx, cy = p2
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    scale = max(abs(bx - ax), abs(by - ay), abs(cx - ax), abs(cy - ay), 1e-300) ** 2
    if abs(d) <= 1e-14 * scale:
        return None
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d
    uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d
    return (ux, uy), math.hypot(ax - ux, ay - uy)


def _kappa_max_spiral(sp: Spiral) -> float:
    rho = min(sp.rho0, sp.rho1)
    b = sp.b
    return (rho * rho + 2 * b * b) / (rho * rho + b * b) ** 1.5


def _fit_piece(sp: Spiral) -> FittedArc | None:
    L = sp.length
    p0, pm, p1 = sp.point(0.0), sp.point(L / 2), sp.point(L)
    circ = circle_through(tuple(p0), tuple(pm), tuple(p1))
    if circ is None:
        return None
    c, R = circ
    th0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
    th1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    thm = math.atan2(pm[1] - c[1], pm[0] - c[0])
    # The arc turns the way the spiral does; its sweep passes through the middle.
    ccw = sp.sweep > 0
    sweep = (th1 - th0) % (2 * math.pi) if ccw else -((th0 - th1) % (2 * math.pi))
    mid_along = (thm - th0) % (2 * math.pi) if ccw else (th0 - thm) % (2 * math.pi)
    if mid_along > abs(sweep):
        return None
    s = np.linspace(0.0, L, SAMPLES + 1)
    pts = sp.point(s)
    dist = np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1])
    f = np.abs(dist - R)
    if f.max() > R / 4:
        return None
    # The radial distance is the distance to the arc (not just its circle)
    # when every point projects inside the arc's sweep.
    ang = np.arctan2(pts[:, 1] - c[1], pts[:, 0] - c[0])
    along = np.mod((ang - th0) * (1.0 if ccw else -1.0), 2 * math.pi)
    inside = (along <= abs(sweep) + 1e-12) | (along >= 2 * math.pi - 1e-12)
    if not inside.all():
        return None
    h = L / SAMPLES
    M = _kappa_max_spiral(sp) + 1.0 / (R - f.max())
    bound = float(f.max() + M * h * h / 8.0)
    return FittedArc(Arc(c, R, th0, sweep), bound)


def fit_arcs(sp: Spiral, tol: float, max_pieces: int = 1 << 16) -> list[FittedArc]:
    """Arcs within ``tol`` of spiral ``sp`` (certified), in order, end to end.

    Consecutive arcs share their end points exactly as points of the spiral
    (up to the arcs' own rounding of ``R*cos``/``R*sin``).
    """
    if tol <= 0:
        raise ValueError("tolerance must be > 0")
    out: list[FittedArc] = []
    stack = [sp]
    while stack:
        piece = stack.pop()
        fit = _fit_piece(piece)
        if fit is not None and fit.bound <= tol:
            out.append(fit)
            continue
        if len(out) + len(stack) >= max_pieces:
            raise ValueError(f"cannot fit the spiral within {tol:g} with {max_pieces} arcs")
        first, second = piece.split(piece.length / 2)
        stack.append(second)
        stack.append(first)
    return out
