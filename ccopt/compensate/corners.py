"""Shared corner machinery of every compensation style.

Notation (docs/compensation.md, 1.3 "Symbols and signs"): ``t`` unit
tangent, ``k = +1`` left / ``-1`` right, offset direction
``o(t) = k * (-t_y, t_x)``, corner turn ``c = t_in x t_out``,
``d = t_in . t_out``. An :class:`Element` is one programmed in-plane move with
its exact geometry; its *carrier* is the curve its offset lies on (an infinite
line or a full circle), which is what corner intersections are computed on.
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from ccopt.compensate import decisions
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line, Spiral, intersect
from ccopt.geometry.angles import TWO_PI, sweep_between
from ccopt.program.model import Block
from ccopt.tolerances import (
    OFFSET_CIRCLE_REL_TOL, POINT_EPS, TOOL_ARC_SAME_RADIUS_REL_TOL, TURN_EPS,
)
from ccopt.toolpath import block_geometry



#: Rounding allowance when counting a sweep's full turns: a sweep of n full
#: turns up to rounding is n turns, not n + 1.
FULL_TURN_SLACK = 1e-9


def perp(t) -> np.ndarray:
    """``t`` rotated by +90 degrees (the left normal)."""
    return np.array([-t[1], t[0]], float)


def offset_dir(t, k: int) -> np.ndarray:
    """``o(t) = k * (-t_y, t_x)``: toward the tool side, unit length."""
    return k * perp(t)


def wrap_pi(a: float) -> float:
    """Angle folded into (-pi, pi]."""
    a = math.fmod(a + math.pi, TWO_PI)
    if a <= 0.0:
        a += TWO_PI
    return a - math.pi


class Corner(str, enum.Enum):
    INSIDE = "inside"
    OUTSIDE = "outside"
    TANGENT = "tangent"
    REVERSAL = "reversal"


@dataclass(frozen=True)
class Turn:
    """The turn between two tangents: cross ``c``, dot ``d``, signed angle ``theta``."""

    c: float
    d: float

    @property
    def theta(self) -> float:
        """Signed turning angle in (-pi, pi], > 0 turning left (counter-clockwise)."""
        return math.atan2(self.c, self.d)


def turn(t_in, t_out) -> Turn:
    return Turn(float(t_in[0] * t_out[1] - t_in[1] * t_out[0]),
                float(t_in[0] * t_out[0] + t_in[1] * t_out[1]))


def classify(k: int, tr: Turn, eps: float = TURN_EPS) -> Corner:
    """Inside ``k*c > eps``, outside ``k*c < -eps``, else tangent (d > 0) or reversal."""
    kc = k * tr.c
    if kc > eps:
        return Corner.INSIDE
    if kc < -eps:
        return Corner.OUTSIDE
    return Corner.TANGENT if tr.d > 0 else Corner.REVERSAL


@dataclass(frozen=True)
class Element:
    """A programmed in-plane move, in plane coordinates, with its exact geometry.

    ``k``/``r`` are the side and radius in force for the block (effective:
    after overrides). ``w0``/``w1`` are the out-of-plane coordinates.
    """

    block: Block
    geom: object
    k: int
    r: float
    w0: float
    w1: float

    @property
    def is_line(self) -> bool:
        return isinstance(self.geom, Line)

    @property
    def start(self) -> np.ndarray:
        return np.asarray(self.geom.start, float)

    @property
    def end(self) -> np.ndarray:
        return np.asarray(self.geom.end, float)

    @property
    def t_start(self) -> np.ndarray:
        return np.asarray(self.geom.start_tangent, float)

    @property
    def t_end(self) -> np.ndarray:
        return np.asarray(self.geom.end_tangent, float)

    @property
    def center(self) -> np.ndarray:
        return np.asarray(self.geom.center, float)

    @property
    def ccw(self) -> bool:
        return self.geom.sweep > 0

    def offset_point(self, at_end: bool, k: int, r: float) -> np.ndarray:
        """``P + r*o(t)`` at the element's start or end."""
        if at_end:
            return self.end + r * offset_dir(self.t_end, k)
        return self.start + r * offset_dir(self.t_start, k)

    def carrier(self, at_end: bool, k: int, r: float):
        """The offset's carrier near one end: ``("line", point, direction)`` or
        ``("circle", centre, radius)``.

        An arc's offset radius is ``R - k*r`` counter-clockwise and ``R + k*r``
        clockwise (docs/compensation.md, 1.4); a radius at or below zero has no tool
        path: CompensationError naming the block.
        """
        if self.is_line:
            t = self.t_end if at_end else self.t_start
            return ("line", self.offset_point(at_end, k, r), t)
        p = self.offset_point(at_end, k, r)
        if isinstance(self.geom, Arc):
            rad = self.geom.radius - k * r * (1.0 if self.ccw else -1.0)
        elif decisions.SPIRAL_CORNER_CARRIER == "circle-through-offset-end":
            rad = float(np.hypot(*(p - self.center)))
        else:  # "tangent-line": the offset's tangent there (parallel to the spiral's)
            return ("line", p, self.t_end if at_end else self.t_start)
        if rad <= POINT_EPS:
            raise concave_error(self, r)
        return ("circle", self.center, rad)

    def check_offset(self, k: int, r: float) -> None:
        """Raise when the arc (or spiral) offset would vanish anywhere."""
        if self.is_line or k == 0 or r == 0.0:
            return
        sgn = 1.0 if self.ccw else -1.0
        if isinstance(self.geom, Arc):
            radii = [self.geom.radius]
        else:
            radii = [self.geom.rho0, self.geom.rho1]
        if min(radii) - k * r * sgn <= POINT_EPS:
            raise concave_error(self, r)


def concave_error(el: Element, r: float) -> CompensationError:
    b = el.block
    rad = el.geom.radius if isinstance(el.geom, Arc) else min(el.geom.rho0, el.geom.rho1)
    return CompensationError(
        f"concave arc radius {rad:.6g} is not larger than the cutter radius {r:.6g}: "
        "the tool cannot follow it; use a smaller cutter or a larger arc",
        b.source.file, b.source.line, b.source.col)


def element_of(block: Block, k: int, r: float) -> Element:
    w0 = block.uvw(block.start)[2]
    w1 = block.uvw(block.end)[2]
    return Element(block, block_geometry(block), k, r, w0, w1)


def carrier_intersections(a, b) -> list[np.ndarray]:
    """All intersections of two carriers (infinite lines / full circles)."""
    if a[0] == "line" and b[0] == "line":
        hits = intersect.line_line(a[1], a[1] + a[2], b[1], b[1] + b[2])
        return [np.asarray(h[0], float) for h in hits]
    if a[0] == "line":
        return [np.asarray(h[0], float) for h in intersect.line_circle(a[1], a[1] + a[2], b[1], b[2])]
    if b[0] == "line":
        return [np.asarray(h[0], float) for h in intersect.line_circle(b[1], b[1] + b[2], a[1], a[2])]
    return [np.asarray(h[0], float) for h in intersect.circle_circle(a[1], a[2], b[1], b[2])]


def corner_side(candidates, P, t_in, behind: bool) -> list[np.ndarray]:
    """The candidates strictly behind the corner ``P`` along the incoming
    tangent, ``(x - P) . t_in < 0`` (``behind``), or strictly ahead of it.

    The two candidates of a line/arc or arc/arc reversal mirror each other
    across the normal at ``P``, on which both nominal offset points lie, so
    the nearest-root rule alone ties; the side decides
    (decisions.REVERSAL_INTERSECTION_BEHIND_CORNER).
    """
    P, t_in = np.asarray(P, float), np.asarray(t_in, float)
    sign = -1.0 if behind else 1.0
    return [x for x in candidates if sign * float((np.asarray(x, float) - P) @ t_in) > 0.0]


def corner_arc(p, r: float, t_in, t_out, k: int, sweep: float | None = None) -> Arc:
    """Arc of radius ``r`` about the programmed corner ``p`` from ``p + r*o(t_in)``
    turning the same way as the path (by the turn angle, or ``sweep``)."""
    o = offset_dir(t_in, k)
    if sweep is None:
        sweep = turn(t_in, t_out).theta
    return Arc((float(p[0]), float(p[1])), float(r), math.atan2(o[1], o[0]), float(sweep))


def reversal_sweep(k: int) -> float:
    """Sweep of the 180-degree arc around the end of a reversal: it passes
    ahead of the corner, away from the material, so ``-k*pi``."""
    return -k * math.pi


def extra_turns(sweep: float) -> int:
    """Full turns of a programmed sweep beyond its first (radians -> count)."""
    return max(math.ceil(abs(sweep) / TWO_PI - FULL_TURN_SLACK) - 1, 0)


def tool_arc_sweep(theta0: float, sweep: float, th_s: float, th_e: float) -> float:
    """Signed sweep (radians, > 0 counter-clockwise) of a compensated arc from
    polar angle ``th_s`` to ``th_e`` about its programmed centre, the
    programmed arc starting at ``theta0`` and sweeping ``sweep``.

    decisions.ARC_SWEEP_CONTINUOUS: the programmed sweep plus the signed angle
    changes at both ends, each in (-pi, pi] (an arc cut back past its start
    runs backwards). Otherwise from start to end the way the arc turns, in
    (0, 2 pi], plus the programmed extra full turns (G-code's reading of end
    points, which skips a full circle whose start passes its end).
    """
    if decisions.ARC_SWEEP_CONTINUOUS:
        return sweep + wrap_pi(th_e - (theta0 + sweep)) - wrap_pi(th_s - theta0)
    return sweep_between(th_s, th_e, sweep > 0, extra_turns(sweep))


def tool_geometry(el: Element, s, e):
    """The exact tool segment of element ``el`` from tool point ``s`` to ``e``.

    A line gives the straight move ``s -> e`` (a diagonal when they are not on
    one offset line). An arc gives an arc about the programmed centre, or a
    spiral when ``s`` and ``e`` lie at different distances from it; its sweep
    is :func:`tool_arc_sweep`.
    """
    s = np.asarray(s, float)
    e = np.asarray(e, float)
    if el.is_line:
        return Line((float(s[0]), float(s[1])), (float(e[0]), float(e[1])))
    c = el.center
    rs = float(np.hypot(*(s - c)))
    re = float(np.hypot(*(e - c)))
    if rs <= POINT_EPS or re <= POINT_EPS:
        raise CompensationError(
            "a compensated arc would pass through its own centre; "
            "check the radius and the lead-in/lead-out geometry",
            el.block.source.file, el.block.source.line, el.block.source.col)
    g = el.geom
    th_s = math.atan2(s[1] - c[1], s[0] - c[0])
    th_e = math.atan2(e[1] - c[1], e[0] - c[0])
    sweep = tool_arc_sweep(g.theta0, g.sweep, th_s, th_e)
    cc = (float(c[0]), float(c[1]))
    if isinstance(g, Arc):
        on = g.radius - el.k * el.r * (1.0 if g.sweep > 0 else -1.0)
        tol = OFFSET_CIRCLE_REL_TOL * max(1.0, on)
        if on > 0 and abs(rs - on) <= tol and abs(re - on) <= tol:
            return Arc(cc, on, th_s, sweep)
    if abs(re - rs) <= TOOL_ARC_SAME_RADIUS_REL_TOL * max(1.0, rs):
        return Arc(cc, rs, th_s, sweep)
    return Spiral(cc, rs, re, th_s, sweep)

