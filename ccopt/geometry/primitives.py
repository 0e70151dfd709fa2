"""Exact in-plane primitives: :class:`Line`, :class:`Arc` (and :class:`Spiral`).

:class:`Spiral` is defined in :mod:`ccopt.geometry.spiral` and re-exported
here: :data:`Primitive` is any of the three.

Small immutable value objects (frozen, slotted dataclasses; points are tuples
of two floats, so every primitive is hashable) with one shared interface,
evaluated by ARC LENGTH ``s`` in program units:

``length``, ``start``, ``end``, ``start_tangent``, ``end_tangent``,
``point(s)``, ``tangent(s)``, ``normal(s)``, ``curvature(s)``, ``d1(s)``,
``d2(s)``, ``bbox()``, ``split(s)``, ``reversed()``.

Evaluation rules:

- ``s`` may be a scalar or an array. A scalar gives a point of shape ``(2,)``
  (curvature: a float); an array of shape ``(N,)`` gives ``(N, 2)`` (``(N,)``).
- ``s`` is clipped to ``[0, length]``: a primitive is a compact piece of
  path, never implicitly extended (use :mod:`ccopt.geometry.intersect` with
  ``extend=True`` to work with the supporting line or circle).
- ``tangent`` is the unit direction of travel; ``normal`` is the tangent
  rotated by +90 degrees (the LEFT of travel); ``curvature`` is signed,
  positive when the path turns left; ``d1 = dp/ds`` (equal to the tangent)
  and ``d2 = d2p/ds2 = curvature * normal``.
- ``point(length)`` equals ``end`` exactly and ``point(0)`` equals ``start``.

Angles are radians; a signed ``sweep`` is counter-clockwise when positive
(see :mod:`ccopt.geometry.angles`). The shared evaluation helpers are in
:mod:`ccopt.geometry.arclength`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ccopt.geometry.angles import angle_in_sweep, sweep_between, sweep_sign, sweeps_between
from ccopt.geometry.arclength import (
    END_POINT_REL_TOL, Point, as_point, clip_s, rotate_left, scalar_out, vector_out,
)
from ccopt.geometry.columns import math_each
from ccopt.geometry.spiral import Spiral

__all__ = ["Arc", "Line", "Point", "Primitive", "Spiral"]


# --------------------------------------------------------------------------- Line


@dataclass(frozen=True, slots=True)
class Line:
    """Straight segment from ``p0`` to ``p1`` (program units).

    A zero-length line (a move with no in-plane component) is allowed; it has
    no direction, so its tangent, normal and ``d1`` are the zero vector and
    callers that need a direction test ``length`` first.
    """

    p0: Point
    p1: Point
    _length: float = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "p0", as_point(self.p0))
        object.__setattr__(self, "p1", as_point(self.p1))
        if not all(math.isfinite(v) for v in self.p0 + self.p1):
            raise ValueError(f"Line end points must be finite, got {self.p0}, {self.p1}")
        object.__setattr__(self, "_length",
                           math.hypot(self.p1[0] - self.p0[0], self.p1[1] - self.p0[1]))

    @classmethod
    def trusted(cls, x0: float, y0: float, x1: float, y1: float) -> "Line":
        """The line from ``(x0, y0)`` to ``(x1, y1)``, four Python floats the
        caller has already checked finite (an engine's own arrays, checked in
        bulk): the same object as ``Line((x0, y0), (x1, y1))`` without its
        per-segment conversion and checks, which dominate long programs."""
        # the slots' own descriptors: the frozen __setattr__ is not involved
        obj = object.__new__(cls)
        _set_p0(obj, (x0, y0))
        _set_p1(obj, (x1, y1))
        _set_length(obj, math.hypot(x1 - x0, y1 - y0))
        return obj

    @property
    def length(self) -> float:
        return self._length

    @property
    def start(self) -> Point:
        return self.p0

    @property
    def end(self) -> Point:
        return self.p1

    @property
    def direction(self) -> Point:
        """Unit direction of travel ((0, 0) for a zero-length line)."""
        L = self._length
        if L == 0.0:
            return (0.0, 0.0)
        return ((self.p1[0] - self.p0[0]) / L, (self.p1[1] - self.p0[1]) / L)

    @property
    def start_tangent(self) -> Point:
        return self.direction

    @property
    def end_tangent(self) -> Point:
        return self.direction

    def point(self, s):
        s, scalar = clip_s(s, self._length)
        t = s / self._length if self._length > 0.0 else s
        # (1-t) p0 + t p1 hits both end points exactly at t = 0 and t = 1.
        u = 1.0 - t
        xy = np.empty((s.size, 2))
        xy[:, 0] = u * self.p0[0] + t * self.p1[0]
        xy[:, 1] = u * self.p0[1] + t * self.p1[1]
        return vector_out(xy, scalar)

    def tangent(self, s):
        s, scalar = clip_s(s, self._length)
        xy = np.empty((s.size, 2))
        xy[:] = self.direction
        return vector_out(xy, scalar)

    def normal(self, s):
        s, scalar = clip_s(s, self._length)
        tx, ty = self.direction
        xy = np.empty((s.size, 2))
        xy[:] = (-ty, tx)
        return vector_out(xy, scalar)

    def curvature(self, s):
        s, scalar = clip_s(s, self._length)
        return scalar_out(np.zeros(s.size), scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        s, scalar = clip_s(s, self._length)
        return vector_out(np.zeros((s.size, 2)), scalar)

    def bbox(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)``."""
        (x0, y0), (x1, y1) = self.p0, self.p1
        return (min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))

    def split(self, s: float) -> tuple["Line", "Line"]:
        """Two lines meeting at ``point(s)`` (``s`` clipped to ``[0, length]``)."""
        m = tuple(float(v) for v in self.point(float(s)))
        return Line(self.p0, m), Line(m, self.p1)

    def reversed(self) -> "Line":
        return Line(self.p1, self.p0)


_set_p0 = Line.__dict__["p0"].__set__
_set_p1 = Line.__dict__["p1"].__set__
_set_length = Line.__dict__["_length"].__set__


# --------------------------------------------------------------------------- Arc


@dataclass(frozen=True, slots=True)
class Arc:
    """Circular arc about ``center`` with ``radius > 0`` (program units).

    It starts at polar angle ``theta0`` and turns through the signed ``sweep``
    (radians, ``> 0`` counter-clockwise, ``|sweep|`` may exceed ``2*pi`` for
    extra turns). Curvature is ``sign(sweep) / radius``.
    """

    center: Point
    radius: float
    theta0: float
    sweep: float
    _length: float = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "center", as_point(self.center))
        object.__setattr__(self, "radius", float(self.radius))
        object.__setattr__(self, "theta0", float(self.theta0))
        object.__setattr__(self, "sweep", float(self.sweep))
        if not (math.isfinite(self.radius) and self.radius > 0.0):
            raise ValueError(f"Arc radius must be finite and > 0, got {self.radius}")
        if not all(math.isfinite(v) for v in (*self.center, self.theta0, self.sweep)):
            raise ValueError("Arc centre and angles must be finite")
        object.__setattr__(self, "_length", self.radius * abs(self.sweep))

    @classmethod
    def from_points(cls, start, end, center, ccw: bool, turns: int = 0,
                    tol: float = END_POINT_REL_TOL) -> "Arc":
        """Arc from ``start`` to ``end`` about ``center``.

        The radius is ``|start - center|``. ``end`` must lie on that circle:
        ``ValueError`` when its radius differs by more than
        ``tol * max(1, radius)``. When ``start`` and ``end`` coincide (their
        angular gap, as a length on the circle, is within the same bound) the
        arc is a full circle, ``sweep = +-2*pi``. ``turns`` adds extra full
        turns (G-code ``P``, minus one).
        """
        return cls(*arc_through(start, end, center, ccw, turns, tol))

    @property
    def length(self) -> float:
        return self._length

    @property
    def ccw(self) -> bool:
        return self.sweep > 0.0 or (self.sweep == 0.0 and math.copysign(1.0, self.sweep) > 0)

    @property
    def theta1(self) -> float:
        """Polar angle of the end point (``theta0 + sweep``, not wrapped)."""
        return self.theta0 + self.sweep

    def _polar(self, phi: float) -> Point:
        return (self.center[0] + self.radius * math.cos(phi),
                self.center[1] + self.radius * math.sin(phi))

    @property
    def start(self) -> Point:
        return self._polar(self.theta0)

    @property
    def end(self) -> Point:
        return self._polar(self.theta0 + self.sweep)

    def _tangent_at(self, phi: float) -> Point:
        sg = sweep_sign(self.sweep)
        return (-sg * math.sin(phi), sg * math.cos(phi))

    @property
    def start_tangent(self) -> Point:
        return self._tangent_at(self.theta0)

    @property
    def end_tangent(self) -> Point:
        return self._tangent_at(self.theta0 + self.sweep)

    def _angles(self, s):
        s, scalar = clip_s(s, self._length)
        if self._length > 0.0:
            # theta0 + sweep * (s / L) lands exactly on theta0 + sweep at s = L.
            phi = self.theta0 + self.sweep * (s / self._length)
        else:
            phi = np.full(s.size, self.theta0)
        return phi, scalar

    def point(self, s):
        phi, scalar = self._angles(s)
        xy = np.empty((phi.size, 2))
        xy[:, 0] = self.center[0] + self.radius * np.cos(phi)
        xy[:, 1] = self.center[1] + self.radius * np.sin(phi)
        return vector_out(xy, scalar)

    def tangent(self, s):
        phi, scalar = self._angles(s)
        sg = sweep_sign(self.sweep)
        xy = np.empty((phi.size, 2))
        xy[:, 0] = -sg * np.sin(phi)
        xy[:, 1] = sg * np.cos(phi)
        return vector_out(xy, scalar)

    def normal(self, s):
        t = self.tangent(np.atleast_1d(np.asarray(s, dtype=float)))
        return vector_out(rotate_left(t), np.ndim(s) == 0)

    def curvature(self, s):
        s, scalar = clip_s(s, self._length)
        return scalar_out(np.full(s.size, sweep_sign(self.sweep) / self.radius), scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        # Centripetal: -(1/R) (cos phi, sin phi), whatever the direction.
        phi, scalar = self._angles(s)
        xy = np.empty((phi.size, 2))
        xy[:, 0] = -np.cos(phi) / self.radius
        xy[:, 1] = -np.sin(phi) / self.radius
        return vector_out(xy, scalar)

    def bbox(self) -> tuple[float, float, float, float]:
        """Exact ``(xmin, ymin, xmax, ymax)``: end points plus every axis
        extreme (polar angle a multiple of pi/2) inside the sweep."""
        (x0, y0), (x1, y1) = self.start, self.end
        xmin, xmax = min(x0, x1), max(x0, x1)
        ymin, ymax = min(y0, y1), max(y0, y1)
        cx, cy = self.center
        R = self.radius
        quarter = np.array([0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi])
        inside = angle_in_sweep(quarter, self.theta0, self.sweep)
        if inside[0]:
            xmax = cx + R
        if inside[1]:
            ymax = cy + R
        if inside[2]:
            xmin = cx - R
        if inside[3]:
            ymin = cy - R
        return (xmin, ymin, xmax, ymax)

    def split(self, s: float) -> tuple["Arc", "Arc"]:
        """Two arcs meeting at ``point(s)`` (``s`` clipped to ``[0, length]``)."""
        s = min(max(float(s), 0.0), self._length)
        first = self.sweep * (s / self._length) if self._length > 0.0 else self.sweep * 0.0
        return (Arc(self.center, self.radius, self.theta0, first),
                Arc(self.center, self.radius, self.theta0 + first, self.sweep - first))

    def reversed(self) -> "Arc":
        return Arc(self.center, self.radius, self.theta0 + self.sweep, -self.sweep)


def arc_through(start, end, center, ccw: bool, turns: int = 0,
                tol: float = END_POINT_REL_TOL) -> tuple[Point, float, float, float]:
    """``(center, radius, theta0, sweep)`` of :meth:`Arc.from_points` (same
    arguments, same ``ValueError``), without making the arc: for makers that
    keep arcs as numbers (a column tool path), which check the result as the
    :class:`Arc` constructor does (finite, radius > 0)."""
    start, end, center = as_point(start), as_point(end), as_point(center)
    R = math.hypot(start[0] - center[0], start[1] - center[1])
    if R <= 0.0:
        raise ValueError(f"Arc start {start} coincides with its centre")
    R_end = math.hypot(end[0] - center[0], end[1] - center[1])
    bound = tol * max(1.0, R)
    if abs(R_end - R) > bound:
        raise ValueError(
            f"Arc end radius {R_end!r} differs from start radius {R!r} by "
            f"{abs(R_end - R):.3g} > {bound:.3g}")
    th0 = math.atan2(start[1] - center[1], start[0] - center[0])
    th1 = math.atan2(end[1] - center[1], end[0] - center[0])
    return center, R, th0, sweep_between(th0, th1, ccw, turns, full_if_below=bound / R)


def polar_ends(start: np.ndarray, end: np.ndarray,
               center: np.ndarray) -> tuple[np.ndarray, ...]:
    """``(r0, r1, theta0, theta1)``: the polar radius and angle (radians) of
    each row's ``start`` and ``end`` (``(n, 2)``) about its ``center``, with
    math's hypot and atan2 of the differences, as the scalar makers of arcs
    and spirals work them out."""
    d0, d1 = start - center, end - center
    return (math_each(math.hypot, d0[:, 0], d0[:, 1]), math_each(math.hypot, d1[:, 0], d1[:, 1]),
            math_each(math.atan2, d0[:, 1], d0[:, 0]), math_each(math.atan2, d1[:, 1], d1[:, 0]))


def arcs_from_polar(r0: np.ndarray, r1: np.ndarray, th0: np.ndarray, th1: np.ndarray,
                    ccw: np.ndarray, turns: np.ndarray,
                    tol: float = END_POINT_REL_TOL) -> tuple[np.ndarray, ...]:
    """``(radius, theta0, sweep)`` of :func:`arc_through` of each row, from
    the polar radii and angles of its ends about its centre
    (:func:`polar_ends`), ``ccw`` and ``turns`` (as
    floats): the same operations on each element; ``ValueError`` when it
    refuses one (not necessarily the first)."""
    bound = tol * np.where(r0 > 1.0, r0, 1.0)       # Python's max(1.0, R)
    if (r0 <= 0.0).any() or (np.abs(r1 - r0) > bound).any() or (turns < 0).any():
        raise ValueError("an arc's start is on its centre, its end off its circle, "
                         "or its turns are negative")
    with np.errstate(invalid="ignore"):
        full_if_below = bound / r0
    return r0, th0, sweeps_between(th0, th1, ccw, turns, full_if_below)


Primitive = Line | Arc | Spiral


def translated(prim: Primitive, du: float, dv: float) -> Primitive:
    """``prim`` moved rigidly by ``(du, dv)`` (lines by their ends, arcs and
    spirals by their centre): the same shape, sweep and length."""
    if isinstance(prim, Line):
        return Line((prim.p0[0] + du, prim.p0[1] + dv), (prim.p1[0] + du, prim.p1[1] + dv))
    return replace(prim, center=(prim.center[0] + du, prim.center[1] + dv))
