"""``AxisLimits``: what the machine can do, per axis and along the path.

Velocities in program units per second, accelerations in program units per
second squared. ``v`` and ``a`` are given in machine axis order ``X, Y[, Z]``
(as in ``case.toml`` ``[limits]``); :meth:`AxisLimits.in_plane` reorders them
into the tool path's plane coordinates ``(u, v[, w])``
(:data:`ccopt.program.model.PLANE_AXES`), or keeps them for a path in several
planes, planned in machine coordinates (:data:`MACHINE_FRAME`).

``j`` (optional) gives per-axis jerk limits in program units per second
cubed, in the same axis order; only the ``jerk`` planner and the jerk-limited
``stop`` baseline use them (:mod:`ccopt.feed.jerk.planner`), and samples
report the jerk against them.

Two optional limits act along the path rather than per axis:

- ``tangential_acc``: bound on ``|d(speed)/dt|``, the acceleration along the
  path;
- ``centripetal_acc``: bound on ``speed^2 * curvature``, the acceleration
  across it (the curvature of the 3-D path, so a helix counts its pitch).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ccopt.program.model import PLANE_AXES
from ccopt.tolerances import LIMIT_RANGE

AXIS_NAMES = ("X", "Y", "Z")

#: The frame of a path whose segments lie in more than one plane: machine
#: coordinates ``(x, y, z)`` (:attr:`ccopt.feed.path.ExactPath.frame`).
MACHINE_FRAME = "XYZ"

#: Machine axis index of each coordinate, per frame: a plane's ``(u, v, w)``
#: (:data:`PLANE_AXES`), or the machine's own.
FRAME_AXES: dict[str, tuple[int, int, int]] = {**PLANE_AXES, MACHINE_FRAME: (0, 1, 2)}


def _positive_tuple(name: str, values) -> tuple[float, ...]:
    try:
        out = tuple(float(x) for x in values)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a list of 2 or 3 numbers (X, Y[, Z]), got {values!r}") from None
    if not 2 <= len(out) <= 3:
        raise ValueError(f"{name} must have 2 or 3 values (X, Y[, Z]), got {len(out)}")
    for axis, x in zip(AXIS_NAMES, out):
        _in_range(f"{name} for {axis}", x)
    return out


def _in_range(what: str, x: float) -> float:
    """``x`` if it is a limit the planners can use (:data:`LIMIT_RANGE`)."""
    lo, hi = LIMIT_RANGE
    if not (math.isfinite(x) and x > 0.0):
        raise ValueError(f"{what} must be a finite number > 0, got {x!r}")
    if not lo <= x <= hi:
        raise ValueError(f"{what} must be between {lo:g} and {hi:g}, got {x!r}")
    return x


def _optional_positive(name: str, value) -> float | None:
    if value is None:
        return None
    return _in_range(name, float(value))


@dataclass(frozen=True)
class AxisLimits:
    """Per-axis velocity and acceleration limits, plus optional path limits.

    Parameters
    ----------
    v: axis velocity limits ``(X, Y[, Z])``, units/s, each ``> 0``.
    a: axis acceleration limits ``(X, Y[, Z])``, units/s^2, each ``> 0``.
    tangential_acc: optional bound on the acceleration along the path, units/s^2.
    centripetal_acc: optional bound on ``speed^2 * curvature``, units/s^2.
    j: optional axis jerk limits ``(X, Y[, Z])``, units/s^3, each ``> 0``.

    ``v`` and ``a`` must have the same length; ``j`` may give fewer axes (X, Y
    for a path in G17 that does not move Z). A third value (Z for G17) is
    needed only when the path moves that axis; :meth:`in_plane` says so.
    """

    v: tuple[float, ...]
    a: tuple[float, ...]
    tangential_acc: float | None = None
    centripetal_acc: float | None = None
    j: tuple[float, ...] | None = None

    def __post_init__(self):
        object.__setattr__(self, "v", _positive_tuple("v", self.v))
        object.__setattr__(self, "a", _positive_tuple("a", self.a))
        if len(self.v) != len(self.a):
            raise ValueError(f"v and a must name the same axes, got {len(self.v)} and "
                             f"{len(self.a)} values")
        if self.j is not None:
            object.__setattr__(self, "j", _positive_tuple("j", self.j))
        object.__setattr__(self, "tangential_acc",
                           _optional_positive("tangential_acc", self.tangential_acc))
        object.__setattr__(self, "centripetal_acc",
                           _optional_positive("centripetal_acc", self.centripetal_acc))

    def in_plane(self, plane: str, dof: int) -> tuple[np.ndarray, np.ndarray]:
        """``(v, a)`` as arrays in plane coordinates ``(u, v[, w])`` of length ``dof``
        (``plane`` :data:`MACHINE_FRAME`: in machine order ``X, Y, Z``).

        ``ValueError`` naming the axis when the path needs a limit that was
        not given (e.g. it moves Z and only X, Y were given).
        """
        idx = FRAME_AXES[plane][:dof]
        missing = [AXIS_NAMES[i] for i in idx if i >= len(self.v)]
        if missing:
            moves = "moves" if dof == 3 and missing == [AXIS_NAMES[FRAME_AXES[plane][2]]] \
                else "uses"
            raise ValueError(f"the path {moves} axis {', '.join(missing)} but the limits give "
                             f"only {', '.join(AXIS_NAMES[:len(self.v)])}")
        return (np.array([self.v[i] for i in idx]), np.array([self.a[i] for i in idx]))

    def jerk_in_plane(self, plane: str, dof: int) -> np.ndarray | None:
        """Jerk limits as an array in plane coordinates (``None`` when not given);
        the same axis checks as :meth:`in_plane`."""
        if self.j is None:
            return None
        self.in_plane(plane, dof)
        idx = FRAME_AXES[plane][:dof]
        missing = [AXIS_NAMES[i] for i in idx if i >= len(self.j)]
        if missing:
            raise ValueError(f"the path uses axis {', '.join(missing)} but the jerk limits give "
                             f"only {', '.join(AXIS_NAMES[:len(self.j)])}")
        return np.array([self.j[i] for i in idx])

    def axis_names(self, plane: str, dof: int) -> tuple[str, ...]:
        """Machine axis names in plane-coordinate order, e.g. ``("Z", "X")`` for ZX."""
        return tuple(AXIS_NAMES[i] for i in FRAME_AXES[plane][:dof])

    def to_json(self) -> dict:
        out: dict = {"v": list(self.v), "a": list(self.a)}
        if self.tangential_acc is not None:
            out["tangential_acc"] = self.tangential_acc
        if self.centripetal_acc is not None:
            out["centripetal_acc"] = self.centripetal_acc
        if self.j is not None:
            out["j"] = list(self.j)
        return out
