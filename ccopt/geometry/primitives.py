"""Exact in-plane primitives: :class:`Line`, :class:`Arc`, :class:`Spiral`.

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
(see :mod:`ccopt.geometry.angles`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ccopt.geometry.angles import angle_in_sweep, sweep_between, sweep_sign

Point = tuple[float, float]


def _as_point(p) -> Point:
    x, y = p
    return (float(x), float(y))


def _s_array(s, length: float):
    """``(clipped s as 1-D array, was_scalar)``."""
    arr = np.asarray(s, dtype=float)
    scalar = arr.ndim == 0
    arr = np.clip(np.atleast_1d(arr), 0.0, length)
    return arr, scalar


def _vec_out(xy: np.ndarray, scalar: bool):
    return xy[0] if scalar else xy


def _scal_out(v: np.ndarray, scalar: bool):
    return float(v[0]) if scalar else v


def _left(xy: np.ndarray) -> np.ndarray:
    """Rotate row vectors by +90 degrees."""
    out = np.empty_like(xy)
    out[:, 0] = -xy[:, 1]
    out[:, 1] = xy[:, 0]
    return out


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
        object.__setattr__(self, "p0", _as_point(self.p0))
        object.__setattr__(self, "p1", _as_point(self.p1))
        if not all(math.isfinite(v) for v in self.p0 + self.p1):
            raise ValueError(f"Line end points must be finite, got {self.p0}, {self.p1}")
        object.__setattr__(self, "_length",
                           math.hypot(self.p1[0] - self.p0[0], self.p1[1] - self.p0[1]))

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
        s, scalar = _s_array(s, self._length)
        t = s / self._length if self._length > 0.0 else s
        # (1-t) p0 + t p1 hits both end points exactly at t = 0 and t = 1.
        u = 1.0 - t
        xy = np.empty((s.size, 2))
        xy[:, 0] = u * self.p0[0] + t * self.p1[0]
        xy[:, 1] = u * self.p0[1] + t * self.p1[1]
        return _vec_out(xy, scalar)

    def tangent(self, s):
        s, scalar = _s_array(s, self._length)
        xy = np.empty((s.size, 2))
        xy[:] = self.direction
        return _vec_out(xy, scalar)

    def normal(self, s):
        s, scalar = _s_array(s, self._length)
        tx, ty = self.direction
        xy = np.empty((s.size, 2))
        xy[:] = (-ty, tx)
        return _vec_out(xy, scalar)

    def curvature(self, s):
        s, scalar = _s_array(s, self._length)
        return _scal_out(np.zeros(s.size), scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        s, scalar = _s_array(s, self._length)
        return _vec_out(np.zeros((s.size, 2)), scalar)

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
        object.__setattr__(self, "center", _as_point(self.center))
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
                    tol: float = 1e-9) -> "Arc":
        """Arc from ``start`` to ``end`` about ``center``.

        The radius is ``|start - center|``. ``end`` must lie on that circle:
        ``ValueError`` when its radius differs by more than
        ``tol * max(1, radius)``. When ``start`` and ``end`` coincide (their
        angular gap, as a length on the circle, is within the same bound) the
        arc is a full circle, ``sweep = +-2*pi``. ``turns`` adds extra full
        turns (G-code ``P``, minus one).
        """
        start, end, center = _as_point(start), _as_point(end), _as_point(center)
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
        sweep = sweep_between(th0, th1, ccw, turns, full_if_below=bound / R)
        return cls(center, R, th0, sweep)

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
        s, scalar = _s_array(s, self._length)
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
        return _vec_out(xy, scalar)

    def tangent(self, s):
        phi, scalar = self._angles(s)
        sg = sweep_sign(self.sweep)
        xy = np.empty((phi.size, 2))
        xy[:, 0] = -sg * np.sin(phi)
        xy[:, 1] = sg * np.cos(phi)
        return _vec_out(xy, scalar)

    def normal(self, s):
        t = self.tangent(np.atleast_1d(np.asarray(s, dtype=float)))
        return _vec_out(_left(t), np.ndim(s) == 0)

    def curvature(self, s):
        s, scalar = _s_array(s, self._length)
        return _scal_out(np.full(s.size, sweep_sign(self.sweep) / self.radius), scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        # Centripetal: -(1/R) (cos phi, sin phi), whatever the direction.
        phi, scalar = self._angles(s)
        xy = np.empty((phi.size, 2))
        xy[:, 0] = -np.cos(phi) / self.radius
        xy[:, 1] = -np.sin(phi) / self.radius
        return _vec_out(xy, scalar)

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


# --------------------------------------------------------------------------- Spiral


def _spiral_arclength(phi, rho0: float, b: float):
    """Arc length of ``rho = rho0 + b*phi`` from angle 0 to ``phi >= 0``.

    ``ds/dphi = sqrt(rho^2 + b^2)``. The textbook antiderivative
    ``F(rho) = [rho*sqrt(rho^2+b^2) + b^2*asinh(rho/|b|)] / (2b)`` loses all
    accuracy as ``b -> 0`` (a difference of two ``rho^2``-sized numbers
    divided by ``b``). Rationalising both differences with
    ``rho - rho0 = b*phi`` gives the same value without cancellation or any
    division by ``b`` (so ``b = 0`` is the circle ``rho0*phi`` exactly)::

        s = phi (rho + rho0)(rho^2 + rho0^2 + b^2) / (2 (rho S + rho0 S0))
            + (b/2) asinh(b phi (rho + rho0) / (rho S0 + rho0 S))

    with ``S = sqrt(rho^2 + b^2)``, ``S0 = sqrt(rho0^2 + b^2)``. Both terms
    are non-negative for either sign of ``b``.
    """
    phi = np.asarray(phi, dtype=float)
    rho = rho0 + b * phi
    b2 = b * b
    S = np.sqrt(rho * rho + b2)
    S0 = math.sqrt(rho0 * rho0 + b2)
    rsum = rho + rho0
    first = phi * rsum * (rho * rho + rho0 * rho0 + b2) / (2.0 * (rho * S + rho0 * S0))
    if b == 0.0:
        return first
    return first + 0.5 * b * np.arcsinh(b * phi * rsum / (rho * S0 + rho0 * S))


@dataclass(frozen=True, slots=True)
class Spiral:
    """Archimedean spiral about ``center``: radius linear in swept angle.

    For ``phi`` in ``[0, |sweep|]`` the point is at polar radius
    ``rho(phi) = rho0 + (rho1 - rho0) * phi / |sweep|`` and polar angle
    ``theta0 + sign(sweep) * phi`` (radians; ``sweep > 0`` counter-clockwise).
    Both radii must be ``> 0`` (so ``rho`` never reaches the centre). This is
    what a controller traces for a circular move whose end radius differs
    from its start radius, and what the radial offset of such a move is.

    ``b = (rho1 - rho0) / |sweep|`` is the radial growth per radian.
    Arc length is in closed form (see :func:`_spiral_arclength`); the inverse
    ``s -> phi`` is a safeguarded vectorised Newton iteration.
    A zero sweep is allowed only with ``rho0 == rho1`` (a point, as produced
    by splitting at an end).
    """

    center: Point
    rho0: float
    rho1: float
    theta0: float
    sweep: float
    _b: float = field(init=False, repr=False, compare=False)
    _length: float = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "center", _as_point(self.center))
        for name in ("rho0", "rho1", "theta0", "sweep"):
            object.__setattr__(self, name, float(getattr(self, name)))
        if not all(math.isfinite(v) for v in (*self.center, self.rho0, self.rho1,
                                                 self.theta0, self.sweep)):
            raise ValueError("Spiral parameters must be finite")
        if self.rho0 <= 0.0 or self.rho1 <= 0.0:
            raise ValueError(f"Spiral radii must be > 0, got rho0={self.rho0}, rho1={self.rho1}")
        if self.sweep == 0.0:
            if self.rho0 != self.rho1:
                raise ValueError("a Spiral with zero sweep must have rho0 == rho1")
            b = 0.0
        else:
            b = (self.rho1 - self.rho0) / abs(self.sweep)
        object.__setattr__(self, "_b", b)
        object.__setattr__(self, "_length",
                           float(_spiral_arclength(abs(self.sweep), self.rho0, b)))

    @classmethod
    def from_points(cls, start, end, center, ccw: bool, turns: int = 0,
                    tol: float = 1e-9) -> "Spiral":
        """Spiral from ``start`` to ``end`` about ``center``.

        ``rho0 = |start - center|``, ``rho1 = |end - center|``; ``ValueError``
        if either is ``<= 0``. Equal polar angles of start and end (within
        ``tol * max(1, rho)`` as a length) make one full turn; ``turns`` adds
        extra full turns.
        """
        start, end, center = _as_point(start), _as_point(end), _as_point(center)
        r0 = math.hypot(start[0] - center[0], start[1] - center[1])
        r1 = math.hypot(end[0] - center[0], end[1] - center[1])
        if r0 <= 0.0 or r1 <= 0.0:
            raise ValueError(
                f"Spiral end points must differ from the centre (rho0={r0}, rho1={r1})")
        th0 = math.atan2(start[1] - center[1], start[0] - center[0])
        th1 = math.atan2(end[1] - center[1], end[0] - center[0])
        rmax = max(r0, r1)
        sweep = sweep_between(th0, th1, ccw, turns, full_if_below=tol * max(1.0, rmax) / rmax)
        return cls(center, r0, r1, th0, sweep)

    # -- scalar properties ---------------------------------------------------

    @property
    def length(self) -> float:
        return self._length

    @property
    def b(self) -> float:
        """Radial growth per radian swept, ``(rho1 - rho0) / |sweep|``."""
        return self._b

    @property
    def ccw(self) -> bool:
        return sweep_sign(self.sweep) > 0

    @property
    def theta1(self) -> float:
        return self.theta0 + self.sweep

    def _polar(self, rho: float, phi_polar: float) -> Point:
        return (self.center[0] + rho * math.cos(phi_polar),
                self.center[1] + rho * math.sin(phi_polar))

    @property
    def start(self) -> Point:
        return self._polar(self.rho0, self.theta0)

    @property
    def end(self) -> Point:
        return self._polar(self.rho1, self.theta0 + self.sweep)

    def _unit_tangent(self, rho: float, ang: float) -> Point:
        sg = sweep_sign(self.sweep)
        b = self._b
        c, s = math.cos(ang), math.sin(ang)
        n = math.hypot(rho, b)
        return ((b * c - sg * rho * s) / n, (b * s + sg * rho * c) / n)

    @property
    def start_tangent(self) -> Point:
        return self._unit_tangent(self.rho0, self.theta0)

    @property
    def end_tangent(self) -> Point:
        return self._unit_tangent(self.rho1, self.theta0 + self.sweep)

    # -- parameter maps ------------------------------------------------------

    def arclength(self, phi):
        """Arc length from the start to swept angle ``phi`` in ``[0, |sweep|]``."""
        return _spiral_arclength(phi, self.rho0, self._b)

    def swept_angle(self, s):
        """Swept angle ``phi`` in ``[0, |sweep|]`` at arc length ``s`` (vectorised).

        Newton on ``arclength(phi) - s`` (derivative ``sqrt(rho^2+b^2)``),
        kept inside a shrinking bracket with bisection as the fallback; stops
        when every step is at rounding level (``1e-15 * |sweep|`` plus the
        angle that a few ulps of ``length`` represent), about ``1e-14``
        relative. ``s`` is clipped to
        ``[0, length]``; the ends map exactly to ``0`` and ``|sweep|``.
        """
        s, scalar = _s_array(s, self._length)
        Phi = abs(self.sweep)
        L = self._length
        if L == 0.0:
            return _scal_out(np.zeros(s.size), scalar)
        rho0, b = self.rho0, self._b
        # Start from the circle-like guess rho0*phi + b*phi^2/2 = s (stable root form),
        # clamped into the bracket; the b^2 term it ignores is what Newton fixes.
        disc = np.maximum(rho0 * rho0 + 2.0 * b * s, 0.0)
        phi = np.clip(2.0 * s / (rho0 + np.sqrt(disc)), 0.0, Phi)
        lo = np.zeros_like(s)
        hi = np.full_like(s, Phi)
        # Rounding in f is a few ulps of L, i.e. about 4 eps L / |dp/dphi| in phi;
        # asking for less than that would never stop.
        eps4L = 4.0 * np.finfo(float).eps * L
        for _ in range(100):
            f = _spiral_arclength(phi, rho0, b) - s
            # Arc length is increasing in phi: shrink the bracket around the root.
            np.copyto(lo, phi, where=f <= 0.0)
            np.copyto(hi, phi, where=f >= 0.0)
            rho = rho0 + b * phi
            speed = np.sqrt(rho * rho + b * b)
            step = f / speed
            tol = 1e-15 * Phi + eps4L / speed
            new = phi - step
            bad = (new < lo) | (new > hi)
            if bad.any():
                new = np.where(bad, 0.5 * (lo + hi), new)
            done = np.abs(new - phi) <= tol
            phi = new
            if done.all():
                break
        phi = np.clip(phi, 0.0, Phi)
        phi[s <= 0.0] = 0.0
        phi[s >= L] = Phi
        return _scal_out(phi, scalar)

    def _frame(self, s):
        """``(rho, polar angle, scalar)`` at arc lengths ``s``."""
        scalar = np.ndim(s) == 0
        phi = np.atleast_1d(self.swept_angle(np.atleast_1d(np.asarray(s, dtype=float))))
        rho = self.rho0 + self._b * phi
        # At the very end use rho1 itself so point(length) == end bit for bit.
        rho[phi == abs(self.sweep)] = self.rho1
        return rho, self.theta0 + sweep_sign(self.sweep) * phi, scalar

    # -- evaluation ----------------------------------------------------------

    def point(self, s):
        rho, ang, scalar = self._frame(s)
        xy = np.empty((rho.size, 2))
        xy[:, 0] = self.center[0] + rho * np.cos(ang)
        xy[:, 1] = self.center[1] + rho * np.sin(ang)
        return _vec_out(xy, scalar)

    def tangent(self, s):
        rho, ang, scalar = self._frame(s)
        sg, b = sweep_sign(self.sweep), self._b
        c, sn = np.cos(ang), np.sin(ang)
        n = np.sqrt(rho * rho + b * b)
        xy = np.empty((rho.size, 2))
        xy[:, 0] = (b * c - sg * rho * sn) / n
        xy[:, 1] = (b * sn + sg * rho * c) / n
        return _vec_out(xy, scalar)

    def normal(self, s):
        t = self.tangent(np.atleast_1d(np.asarray(s, dtype=float)))
        return _vec_out(_left(t), np.ndim(s) == 0)

    def curvature(self, s):
        """Signed curvature ``sign(sweep) (rho^2 + 2 b^2) / (rho^2 + b^2)^1.5``
        (the polar formula with ``rho' = +-b``, ``rho'' = 0``)."""
        rho, _, scalar = self._frame(s)
        b2 = self._b * self._b
        r2 = rho * rho
        k = sweep_sign(self.sweep) * (r2 + 2.0 * b2) / (r2 + b2) ** 1.5
        return _scal_out(k, scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        scalar = np.ndim(s) == 0
        s1 = np.atleast_1d(np.asarray(s, dtype=float))
        xy = _left(self.tangent(s1)) * np.atleast_1d(self.curvature(s1))[:, None]
        return _vec_out(xy, scalar)

    def bbox(self) -> tuple[float, float, float, float]:
        """Exact ``(xmin, ymin, xmax, ymax)``.

        Along the spiral ``dx/dphi`` and ``dy/dphi`` vanish where
        ``h(phi) = sign*theta0 + phi + atan2(rho(phi), b)`` is a multiple of
        ``pi/2`` (``x`` where ``h = pi/2 + k*pi``, ``y`` where ``h = k*pi``);
        ``h`` is strictly increasing (``1 <= h' < 2``), so each multiple has
        at most one root, found by bracketed Newton. The box is taken over
        the end points and those roots.
        """
        Phi = abs(self.sweep)
        pts = [self.start, self.end]
        if Phi > 0.0:
            sg, b, rho0 = sweep_sign(self.sweep), self._b, self.rho0

            def h(phi):
                return sg * self.theta0 + phi + np.arctan2(rho0 + b * phi, b)

            h0, h1 = float(h(0.0)), float(h(Phi))
            half_pi = 0.5 * math.pi
            k = np.arange(math.ceil(h0 / half_pi), math.floor(h1 / half_pi) + 1)
            if k.size:
                target = k * half_pi
                lo = np.zeros(k.size)
                hi = np.full(k.size, Phi)
                phi = np.clip(target - h0, 0.0, Phi)
                for _ in range(100):
                    f = h(phi) - target
                    np.copyto(lo, phi, where=f <= 0.0)
                    np.copyto(hi, phi, where=f >= 0.0)
                    rho = rho0 + b * phi
                    new = phi - f / (1.0 + b * b / (rho * rho + b * b))
                    new = np.where((new < lo) | (new > hi), 0.5 * (lo + hi), new)
                    done = np.abs(new - phi) <= 1e-15 * Phi
                    phi = new
                    if done.all():
                        break
                rho = rho0 + b * phi
                ang = self.theta0 + sg * phi
                pts.extend(zip(self.center[0] + rho * np.cos(ang),
                               self.center[1] + rho * np.sin(ang)))
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        return (float(min(xs)), float(min(ys)), float(max(xs)), float(max(ys)))

    def split(self, s: float) -> tuple["Spiral", "Spiral"]:
        """Two spirals meeting at ``point(s)``; both keep the growth rate ``b``."""
        s = min(max(float(s), 0.0), self._length)
        sg = sweep_sign(self.sweep)
        if s <= 0.0:
            phi, rho_m = 0.0, self.rho0
        elif s >= self._length:
            phi, rho_m = abs(self.sweep), self.rho1
        else:
            phi = float(self.swept_angle(s))
            rho_m = self.rho0 + self._b * phi
        first = sg * phi
        return (Spiral(self.center, self.rho0, rho_m, self.theta0, first),
                Spiral(self.center, rho_m, self.rho1, self.theta0 + first, self.sweep - first))

    def reversed(self) -> "Spiral":
        return Spiral(self.center, self.rho1, self.rho0, self.theta0 + self.sweep, -self.sweep)


Primitive = Line | Arc | Spiral
