"""Angle bookkeeping shared by the primitives, intersections and distances.

Conventions (radians throughout):

- An arc (or spiral) starts at polar angle ``theta0`` about its centre and
  turns through the signed ``sweep``: ``sweep > 0`` is counter-clockwise,
  ``sweep < 0`` clockwise. ``|sweep|`` may exceed ``2*pi`` (extra turns).
- The direction of a zero sweep is carried by the sign bit of ``0.0`` /
  ``-0.0`` (so a clockwise arc split at its start stays clockwise); see
  :func:`sweep_sign`.
- "Angle along the sweep" of a polar angle ``phi`` is
  ``((phi - theta0) * sign(sweep)) mod 2*pi`` in ``[0, 2*pi)``: how far one
  travels from the start, in the arc's own direction, to first reach ``phi``.
"""
from __future__ import annotations

import math

import numpy as np

TWO_PI = 2.0 * math.pi


def sweep_sign(sweep):
    """+1.0 for counter-clockwise, -1.0 for clockwise; honours ``-0.0``.

    Works on floats and on numpy arrays (elementwise).
    """
    if isinstance(sweep, np.ndarray):
        return np.copysign(1.0, sweep)
    return math.copysign(1.0, sweep)


def angle_along(phi, theta0, sweep):
    """Angle travelled from ``theta0`` in the sweep's direction to first reach ``phi``.

    Returns values in ``[0, 2*pi]`` (``2*pi`` only through rounding of
    ``x mod 2*pi`` for tiny negative ``x``, which every caller treats as
    "just before the start"). Vectorised.
    """
    return np.mod((np.asarray(phi, dtype=float) - theta0) * sweep_sign(np.asarray(sweep, dtype=float)),
                  TWO_PI)


def angle_in_sweep(phi, theta0, sweep):
    """True where polar angle ``phi`` lies on the arc ``(theta0, sweep)``.

    Inclusive at both ends; ``|sweep| >= 2*pi`` contains every angle. A point
    whose angle sits within rounding of an end may be classified either way;
    all distance and intersection kernels also test the arc's end points, so
    the answer they produce is continuous across that boundary.
    """
    sweep = np.asarray(sweep, dtype=float)
    return in_sweep_prepared(phi, theta0, np.copysign(1.0, sweep), np.abs(sweep))


def in_sweep_prepared(phi, theta0, sign, abs_sweep):
    """:func:`angle_in_sweep` with ``sign(sweep)`` and ``|sweep|`` precomputed.

    The angle along the sweep, ``x = (phi - theta0) * sign``, is reduced with
    ``x - 2 pi floor(x / 2 pi)`` (three times cheaper than ``np.mod`` on large
    arrays); rounding can leave it a few ulps below 0 ("at the start",
    counted inside) or at ``2 pi`` ("just before the start", outside unless the
    sweep is full), both of which the end-point candidates make harmless.
    """
    along = (np.asarray(phi, dtype=float) - theta0) * sign
    along -= TWO_PI * np.floor(along * _INV_TWO_PI)
    return (along <= abs_sweep) | (abs_sweep >= TWO_PI)


_INV_TWO_PI = 1.0 / TWO_PI


def sweep_between(theta_start: float, theta_end: float, ccw: bool, turns: int = 0,
                  *, full_if_below: float = 0.0) -> float:
    """Signed sweep from polar angle ``theta_start`` to ``theta_end``.

    ``ccw`` picks the direction. The basic sweep is in ``(0, 2*pi]``
    (negated for clockwise); an angular gap at or below ``full_if_below``
    (radians) means start and end coincide, which G-code reads as a full
    circle, so it becomes ``2*pi``. ``turns`` adds that many extra full turns.
    """
    if turns < 0:
        raise ValueError(f"turns must be >= 0, got {turns}")
    gap = (theta_end - theta_start) if ccw else (theta_start - theta_end)
    gap = math.fmod(gap, TWO_PI)
    if gap < 0.0:
        gap += TWO_PI
    if gap <= full_if_below or TWO_PI - gap <= full_if_below or gap >= TWO_PI:
        gap = TWO_PI
    gap += TWO_PI * turns
    return gap if ccw else -gap


def sweeps_between(theta_start: np.ndarray, theta_end: np.ndarray, ccw: np.ndarray,
                   turns: np.ndarray, full_if_below: np.ndarray) -> np.ndarray:
    """:func:`sweep_between` of each row (arrays of one length; ``ccw`` bool,
    ``turns`` >= 0 as floats): the same operations on each element (``fmod``
    is exact, numpy's as math's)."""
    gap = np.where(ccw, theta_end - theta_start, theta_start - theta_end)
    gap = np.fmod(gap, TWO_PI)
    gap = np.where(gap < 0.0, gap + TWO_PI, gap)
    full = (gap <= full_if_below) | (TWO_PI - gap <= full_if_below) | (gap >= TWO_PI)
    gap = np.where(full, TWO_PI, gap) + TWO_PI * turns
    return np.where(ccw, gap, -gap)
