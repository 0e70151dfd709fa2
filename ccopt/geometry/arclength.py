"""Evaluation by arc length, shared by :class:`~ccopt.geometry.primitives.Line`,
:class:`~ccopt.geometry.primitives.Arc` and :class:`~ccopt.geometry.spiral.Spiral`.

A primitive is evaluated at arc lengths ``s`` (program units): a scalar gives
one point of shape ``(2,)`` (or a float), an array of shape ``(N,)`` gives
``(N, 2)`` (or ``(N,)``); ``s`` is clipped to ``[0, length]``. The helpers
here do that clipping and shaping once for every primitive, and
:data:`END_POINT_REL_TOL` is the one tolerance of the circular moves built
from their end points (``Arc.from_points``, ``Spiral.from_points``).
"""
from __future__ import annotations

import numpy as np

#: A circular move's end point lies on its start's circle, and its start and
#: end coincide (a full turn), within this times ``max(1, radius)`` as a
#: length: well above the rounding of coordinates near 1 (~1e-16), well below
#: any programmed resolution (1e-4 mm and coarser).
END_POINT_REL_TOL = 1e-9

Point = tuple[float, float]


def as_point(p) -> Point:
    """``p`` (any pair of numbers) as a tuple of two floats."""
    x, y = p
    return (float(x), float(y))


def clip_s(s, length: float):
    """``(s clipped to [0, length] as a 1-D array, whether s was a scalar)``."""
    arr = np.asarray(s, dtype=float)
    scalar = arr.ndim == 0
    arr = np.clip(np.atleast_1d(arr), 0.0, length)
    return arr, scalar


def vector_out(xy: np.ndarray, scalar: bool):
    """Rows ``(N, 2)`` as evaluated, or the single point for a scalar ``s``."""
    return xy[0] if scalar else xy


def scalar_out(v: np.ndarray, scalar: bool):
    """Values ``(N,)`` as evaluated, or one float for a scalar ``s``."""
    return float(v[0]) if scalar else v


def rotate_left(xy: np.ndarray) -> np.ndarray:
    """Rotate row vectors by +90 degrees."""
    out = np.empty_like(xy)
    out[:, 0] = -xy[:, 1]
    out[:, 1] = xy[:, 0]
    return out
