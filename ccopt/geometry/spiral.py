"""The Archimedean spiral: a circular move whose end radius differs from its start.

:class:`Spiral` has the interface of :mod:`ccopt.geometry.primitives` (evaluated
by arc length ``s`` in program units, see :mod:`ccopt.geometry.arclength`);
its arc length is in closed form (:func:`spiral_arclength`) and the inverse
``s -> swept angle`` is a safeguarded Newton iteration. Angles are radians; a
signed ``sweep`` is counter-clockwise when positive.
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from itertools import repeat

import numpy as np

from ccopt.geometry.angles import sweep_between, sweep_sign, sweeps_between
from ccopt.geometry.columns import math_each, paused_gc
from ccopt.geometry.arclength import (
    END_POINT_REL_TOL, Point, as_point, clip_s, rotate_left, scalar_out, vector_out,
)

__all__ = ["Spiral", "spiral_arclength", "spiral_bboxes", "spiral_end_tangents",
           "spirals_from_polar"]

#: Newton in the swept angle stops once every step is below this fraction of
#: ``|sweep|`` (a few ulps of the angle: nothing smaller is representable).
NEWTON_STEP_REL = 1e-15


def spiral_arclength(phi, rho0: float, b: float):
    """Arc length of ``rho = rho0 + b*phi`` from angle 0 to ``phi >= 0``
    (``rho0`` and ``b`` may be arrays of ``phi``'s shape, one spiral each:
    every element is what the call with its own numbers gives).

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
    S0 = np.sqrt(rho0 * rho0 + b2) if isinstance(b2, np.ndarray) else math.sqrt(rho0 * rho0 + b2)
    rsum = rho + rho0
    first = phi * rsum * (rho * rho + rho0 * rho0 + b2) / (2.0 * (rho * S + rho0 * S0))
    if not isinstance(b, np.ndarray):
        if b == 0.0:
            return first
        return first + 0.5 * b * np.arcsinh(b * phi * rsum / (rho * S0 + rho0 * S))
    with np.errstate(invalid="ignore", divide="ignore"):   # rows of b = 0 take `first`
        rest = 0.5 * b * np.arcsinh(b * phi * rsum / (rho * S0 + rho0 * S))
    return np.where(b == 0.0, first, first + rest)


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
    Arc length is in closed form (see :func:`spiral_arclength`); the inverse
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
        object.__setattr__(self, "center", as_point(self.center))
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
                           float(spiral_arclength(abs(self.sweep), self.rho0, b)))

    @classmethod
    def from_points(cls, start, end, center, ccw: bool, turns: int = 0,
                    tol: float = END_POINT_REL_TOL) -> "Spiral":
        """Spiral from ``start`` to ``end`` about ``center``.

        ``rho0 = |start - center|``, ``rho1 = |end - center|``; ``ValueError``
        if either is ``<= 0``. Equal polar angles of start and end (within
        ``tol * max(1, rho)`` as a length) make one full turn; ``turns`` adds
        extra full turns.
        """
        return cls(*spiral_through(start, end, center, ccw, turns, tol))

    @classmethod
    def many_from_numbers(cls, center: np.ndarray, rho0: np.ndarray, rho1: np.ndarray,
                          theta0: np.ndarray, sweep: np.ndarray) -> list["Spiral"]:
        """The spirals of the numbers ``center`` ``(n, 2)``, ``rho0``,
        ``rho1``, ``theta0`` and ``sweep`` (``(n,)``; those of
        :func:`spirals_from_polar`), their lengths worked out together: with
        that, :meth:`from_points` of many moves, bit for bit; ``ValueError``
        when the constructor refuses one."""
        n = len(rho0)
        rows = np.c_[center, rho0, rho1, theta0, sweep]
        # the checks of __post_init__, row by row
        if not (np.isfinite(rows).all() and (rho0 > 0.0).all() and (rho1 > 0.0).all()
                and ((sweep != 0.0) | (rho0 == rho1)).all()):
            raise ValueError("a spiral's numbers are not valid (see Spiral.from_points)")
        phi = np.abs(sweep)
        b = np.divide(rho1 - rho0, phi, out=np.zeros(n), where=sweep != 0.0)
        # the same operations, element by element, as one spiral's (numpy
        # runs arcsinh with one loop whatever the length; the tests compare)
        length = spiral_arclength(phi, rho0, b)
        with paused_gc():
            spirals = list(map(object.__new__, repeat(cls, n)))
            fields = (list(zip(*center.T.tolist())), rho0.tolist(), rho1.tolist(),
                      theta0.tolist(), sweep.tolist(), b.tolist(), length.tolist())
            for setter, values in zip(_SETTERS, fields):
                deque(map(setter, spirals, values), 0)
        return spirals

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
        return spiral_arclength(phi, self.rho0, self._b)

    def swept_angle(self, s):
        """Swept angle ``phi`` in ``[0, |sweep|]`` at arc length ``s`` (vectorised).

        Newton on ``arclength(phi) - s`` (derivative ``sqrt(rho^2+b^2)``),
        kept inside a shrinking bracket with bisection as the fallback; stops
        when every step is at rounding level (``1e-15 * |sweep|`` plus the
        angle that a few ulps of ``length`` represent), about ``1e-14``
        relative. ``s`` is clipped to
        ``[0, length]``; the ends map exactly to ``0`` and ``|sweep|``.
        """
        s, scalar = clip_s(s, self._length)
        Phi = abs(self.sweep)
        L = self._length
        if L == 0.0:
            return scalar_out(np.zeros(s.size), scalar)
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
            f = spiral_arclength(phi, rho0, b) - s
            # Arc length is increasing in phi: shrink the bracket around the root.
            np.copyto(lo, phi, where=f <= 0.0)
            np.copyto(hi, phi, where=f >= 0.0)
            rho = rho0 + b * phi
            speed = np.sqrt(rho * rho + b * b)
            step = f / speed
            tol = NEWTON_STEP_REL * Phi + eps4L / speed
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
        return scalar_out(phi, scalar)

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
        return vector_out(xy, scalar)

    def tangent(self, s):
        rho, ang, scalar = self._frame(s)
        sg, b = sweep_sign(self.sweep), self._b
        c, sn = np.cos(ang), np.sin(ang)
        n = np.sqrt(rho * rho + b * b)
        xy = np.empty((rho.size, 2))
        xy[:, 0] = (b * c - sg * rho * sn) / n
        xy[:, 1] = (b * sn + sg * rho * c) / n
        return vector_out(xy, scalar)

    def normal(self, s):
        t = self.tangent(np.atleast_1d(np.asarray(s, dtype=float)))
        return vector_out(rotate_left(t), np.ndim(s) == 0)

    def curvature(self, s):
        """Signed curvature ``sign(sweep) (rho^2 + 2 b^2) / (rho^2 + b^2)^1.5``
        (the polar formula with ``rho' = +-b``, ``rho'' = 0``)."""
        rho, _, scalar = self._frame(s)
        b2 = self._b * self._b
        r2 = rho * rho
        k = sweep_sign(self.sweep) * (r2 + 2.0 * b2) / (r2 + b2) ** 1.5
        return scalar_out(k, scalar)

    def d1(self, s):
        return self.tangent(s)

    def d2(self, s):
        scalar = np.ndim(s) == 0
        s1 = np.atleast_1d(np.asarray(s, dtype=float))
        xy = rotate_left(self.tangent(s1)) * np.atleast_1d(self.curvature(s1))[:, None]
        return vector_out(xy, scalar)

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
                    done = np.abs(new - phi) <= NEWTON_STEP_REL * Phi
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


def spiral_through(start, end, center, ccw: bool, turns: int = 0,
                   tol: float = END_POINT_REL_TOL) -> tuple[Point, float, float, float, float]:
    """``(center, rho0, rho1, theta0, sweep)`` of :meth:`Spiral.from_points`
    (same arguments, same ``ValueError`` for an end point on the centre),
    without making the spiral."""
    start, end, center = as_point(start), as_point(end), as_point(center)
    r0 = math.hypot(start[0] - center[0], start[1] - center[1])
    r1 = math.hypot(end[0] - center[0], end[1] - center[1])
    if r0 <= 0.0 or r1 <= 0.0:
        raise ValueError(
            f"Spiral end points must differ from the centre (rho0={r0}, rho1={r1})")
    th0 = math.atan2(start[1] - center[1], start[0] - center[0])
    th1 = math.atan2(end[1] - center[1], end[0] - center[0])
    rmax = max(r0, r1)
    sweep = sweep_between(th0, th1, ccw, turns, full_if_below=tol * max(1.0, rmax) / rmax)
    return center, r0, r1, th0, sweep


def spirals_from_polar(r0: np.ndarray, r1: np.ndarray, th0: np.ndarray, th1: np.ndarray,
                       ccw: np.ndarray, turns: np.ndarray,
                       tol: float = END_POINT_REL_TOL) -> tuple[np.ndarray, ...]:
    """``(rho0, rho1, theta0, sweep)`` of :func:`spiral_through` of each row,
    from the polar radii and angles of its ends about its centre
    (:func:`~ccopt.geometry.primitives.polar_ends`), ``ccw`` and ``turns`` (as
    floats): the same operations on each element; ``ValueError`` when it
    refuses one (not necessarily the first)."""
    if (r0 <= 0.0).any() or (r1 <= 0.0).any() or (turns < 0).any():
        raise ValueError("a spiral's end point is on its centre, or its turns are negative")
    rmax = np.where(r1 > r0, r1, r0)            # Python's max(r0, r1)
    with np.errstate(invalid="ignore"):
        full_if_below = tol * np.where(rmax > 1.0, rmax, 1.0) / rmax
    return r0, r1, th0, sweeps_between(th0, th1, ccw, turns, full_if_below)


def spiral_bboxes(center, rho0, rho1, theta0, sweep, b):
    """Start points ``(n, 2)``, end points ``(n, 2)`` and boxes ``(n, 4)``
    ``(xmin, ymin, xmax, ymax)`` of ``n`` spirals given by their numbers
    (arrays of :class:`Spiral`'s fields and ``b``): each row, bit for bit,
    what ``start``, ``end`` and :meth:`Spiral.bbox` of its spiral give (the
    same operations on each element; the tests compare)."""
    cx, cy = center[:, 0], center[:, 1]
    th1 = theta0 + sweep
    start = np.stack([cx + rho0 * np.cos(theta0), cy + rho0 * np.sin(theta0)], axis=1)
    end = np.stack([cx + rho1 * np.cos(th1), cy + rho1 * np.sin(th1)], axis=1)
    box = np.concatenate([start, start], axis=1)
    # taken in bbox's order (start, end, then the extremes by swept angle) with
    # its strict comparisons: Python's min and max keep the first of equals
    for x, y, rows in [(end[:, 0], end[:, 1], slice(None)),
                       *_axis_extremes(center, rho0, theta0, sweep, b)]:
        for col, v, lower in ((0, x, True), (1, y, True), (2, x, False), (3, y, False)):
            kept = box[rows, col]
            box[rows, col] = np.where(v < kept if lower else v > kept, v, kept)
    return start, end, box


def spiral_end_tangents(rho0, rho1, theta0, sweep, b):
    """Unit tangents ``(n, 2)`` at the starts and at the ends of ``n`` spirals
    given by their numbers (arrays, as :func:`spiral_bboxes` takes them): each
    row, bit for bit, its spiral's ``start_tangent`` and ``end_tangent`` (with
    math's cos, sin and hypot, as those use)."""
    sg = np.copysign(1.0, sweep)
    return _unit_tangents(rho0, theta0, sg, b), _unit_tangents(rho1, theta0 + sweep, sg, b)


def _unit_tangents(rho, ang, sg, b) -> np.ndarray:
    """:meth:`Spiral._unit_tangent` of each row."""
    n = rho.size
    c, s = math_each(math.cos, ang), math_each(math.sin, ang)
    length = math_each(math.hypot, rho, b)
    out = np.empty((n, 2))
    out[:, 0] = (b * c - sg * rho * s) / length
    out[:, 1] = (b * s + sg * rho * c) / length
    return out


def _axis_extremes(center, rho0, theta0, sweep, b) -> list:
    """The points where :meth:`Spiral.bbox` finds ``dx/dphi`` or ``dy/dphi``
    zero, as ``(x, y, rows)`` for ``j = 0, 1, ...``: the ``j``-th such point
    (by swept angle) of each spiral ``rows`` that has one."""
    Phi = np.abs(sweep)
    sg = np.copysign(1.0, sweep)
    sgth = sg * theta0
    half_pi = 0.5 * math.pi
    h0 = sgth + 0.0 + np.arctan2(rho0 + b * 0.0, b)
    h1 = sgth + Phi + np.arctan2(rho0 + b * Phi, b)
    k0 = np.ceil(h0 / half_pi)
    count = np.where(Phi > 0.0, np.floor(h1 / half_pi) + 1.0 - k0, 0.0)
    rows = np.flatnonzero(count > 0.0)
    if not rows.size:
        return []
    count = count[rows].astype(np.intp)
    first = np.cumsum(count) - count        # each spiral's first point in the flat arrays
    spiral = np.repeat(np.arange(rows.size), count)
    j = np.arange(spiral.size) - first[spiral]
    at = rows[spiral]
    phi = _roots((k0[at] + j) * half_pi, h0[at], sgth[at], rho0[at], b[at], Phi[at], spiral)
    rho = rho0[at] + b[at] * phi
    ang = theta0[at] + sg[at] * phi
    x = center[at, 0] + rho * np.cos(ang)
    y = center[at, 1] + rho * np.sin(ang)
    out = []
    for jj in range(int(count.max())):
        m = np.flatnonzero(count > jj)
        out.append((x[first[m] + jj], y[first[m] + jj], rows[m]))
    return out


def _roots(target, h0, sgth, rho0, b, Phi, spiral) -> np.ndarray:
    """Swept angles where ``h`` (see :meth:`Spiral.bbox`) reaches ``target``:
    its bracketed Newton element by element, the elements of each ``spiral``
    stopping together, at the step where all of them are done (as in bbox)."""
    phi = np.clip(target - h0, 0.0, Phi)
    lo = np.zeros(phi.size)
    hi = Phi.copy()
    out = np.empty(phi.size)
    live = np.arange(phi.size)
    for _ in range(100):
        f = sgth + phi + np.arctan2(rho0 + b * phi, b) - target
        lo = np.where(f <= 0.0, phi, lo)
        hi = np.where(f >= 0.0, phi, hi)
        rho = rho0 + b * phi
        new = phi - f / (1.0 + b * b / (rho * rho + b * b))
        new = np.where((new < lo) | (new > hi), 0.5 * (lo + hi), new)
        done = np.abs(new - phi) <= NEWTON_STEP_REL * Phi
        phi = out[live] = new
        going = np.bincount(spiral, ~done)[spiral] > 0
        if not going.any():
            break
        live, phi, lo, hi, target, sgth, rho0, b, Phi, spiral = (
            a[going] for a in (live, phi, lo, hi, target, sgth, rho0, b, Phi, spiral))
    return out


# the slots' own descriptors, in the order Spiral.many_from_numbers sets them
_SETTERS = tuple(Spiral.__dict__[name].__set__
                 for name in ("center", "rho0", "rho1", "theta0", "sweep", "_b", "_length"))
