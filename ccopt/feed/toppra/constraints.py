"""Path constraints for toppra, one small object per limit.

Each is a :class:`toppra.constraint.LinearConstraint` in toppra's canonical
form (stage variables ``u = s''`` and ``x = s'^2``), so they combine in a
list like toppra's own and run on toppra's ``seidel`` solver:

- :class:`AxisVelocityConstraint`: ``|q_i'(s)| s' <= v_i``;
- :class:`AxisAccelerationConstraint`: ``|q_i'(s) s'' + q_i''(s) s'^2| <= a_i``,
  discretised by interpolation (each interval checked at both ends with the
  interval's constant ``u``), like toppra's ``JointAccelerationConstraint``
  with ``DiscretizationType.Interpolation``;
- :class:`PathSpeedConstraint`: ``s' <= cap(s)``: the programmed feed (a
  tangential speed, since ``|q'| = 1``), zero where the path must stop;
- :class:`TangentialAccelerationConstraint`: ``|s''| <= a_t``;
- :class:`CentripetalAccelerationConstraint`: ``|q''(s)| s'^2 <= a_n``.

Unlike toppra's joint constraints, these evaluate an
:class:`~ccopt.feed.path.ExactPath` one-sidedly at gridpoints that are
segment boundaries: the interval ending there uses the left limit of
``q'``, ``q''``, the interval starting there the right limit, and a bound on
``x`` at the boundary holds for both sides. With any other toppra path they
fall back to ``path(s, order)``.
"""
from __future__ import annotations

import numpy as np

from ccopt.feed.toppra.library import DiscretizationType, LinearConstraint


def _sided(path, gridpoints, order):
    """``(left, right)`` derivative of ``order`` at ``gridpoints``."""
    if hasattr(path, "eval_sided"):
        return path.eval_sided(gridpoints, order, "left"), path.eval_sided(gridpoints, order, "right")
    q = np.asarray(path(gridpoints, order)).reshape(len(gridpoints), -1)
    return q, q


def _check_dof(constraint, path):
    if path.dof != constraint.dof:
        raise ValueError(f"{type(constraint).__name__}: constraint dof {constraint.dof} != path "
                         f"dof {path.dof}")


def _x_upper_from_speed_limit(qd: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Largest ``x = s'^2`` with ``|q_i'| sqrt(x) <= v_i`` for all ``i``."""
    a = np.abs(qd)
    with np.errstate(divide="ignore"):
        lim = np.where(a > 0.0, (v / np.where(a > 0.0, a, 1.0)) ** 2, np.inf)
    return lim.min(axis=1)


class AxisVelocityConstraint(LinearConstraint):
    """Per-axis velocity limits ``v`` (units/s), in the path's coordinate order."""

    def __init__(self, v):
        super().__init__()
        self.v = np.asarray(v, dtype=float)
        self.dof = self.v.size
        self._format_string = f"    Axis velocity limits: {self.v.tolist()}\n"

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        _check_dof(self, path)
        left, right = _sided(path, gridpoints, 1)
        upper = np.minimum(_x_upper_from_speed_limit(left, self.v),
                           _x_upper_from_speed_limit(right, self.v))
        xbound = np.column_stack([np.zeros_like(upper), upper])
        return None, None, None, None, None, None, xbound


class AxisAccelerationConstraint(LinearConstraint):
    """Per-axis acceleration limits ``a`` (units/s^2), interpolation discretisation.

    For stage ``i`` (interval ``[s_i, s_i+1]``, constant ``u_i``):
    ``|q'(s_i+) u_i + q''(s_i+) x_i| <= a`` and
    ``|q'(s_i+1 -) u_i + q''(s_i+1 -) (x_i + 2 d_i u_i)| <= a``.
    """

    def __init__(self, a):
        super().__init__()
        self.a = np.asarray(a, dtype=float)
        self.dof = self.a.size
        self.identical = True
        self.set_discretization_type(DiscretizationType.Interpolation)
        self._format_string = f"    Axis acceleration limits: {self.a.tolist()}\n"

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        _check_dof(self, path)
        gridpoints = np.asarray(gridpoints, dtype=float)
        d = self.dof
        q1l, q1r = _sided(path, gridpoints, 1)
        q2l, q2r = _sided(path, gridpoints, 2)
        deltas = np.diff(gridpoints)
        N1 = gridpoints.size
        a = np.zeros((N1, 2 * d))
        b = np.zeros((N1, 2 * d))
        a[:, :d] = q1r
        b[:, :d] = q2r
        a[:-1, d:] = q1l[1:] + 2.0 * deltas[:, None] * q2l[1:]
        b[:-1, d:] = q2l[1:]
        a[-1, d:] = a[-1, :d]
        b[-1, d:] = b[-1, :d]
        c = np.zeros_like(a)
        # F [w_start; w_end] <= g with |w| <= a on both blocks.
        eye = np.eye(d)
        F1 = np.vstack([eye, -eye])
        F = np.zeros((4 * d, 2 * d))
        F[:2 * d, :d] = F1
        F[2 * d:, d:] = F1
        g = np.concatenate([self.a, self.a, self.a, self.a])
        return a, b, c, F, g, None, None


class PathSpeedConstraint(LinearConstraint):
    """``s' <= cap`` at each gridpoint (``cap`` an array over the gridpoints, may be inf).

    ``cap`` is built by the planner: the smaller programmed feed of the two
    sides of a gridpoint, ``inf`` on rapids, 0 at stops, a junction speed at
    corners when a junction deviation is allowed.
    """

    def __init__(self, cap, dof: int):
        super().__init__()
        self.cap = np.asarray(cap, dtype=float)
        self.dof = dof
        self._format_string = "    Path speed cap (programmed feed, stops)\n"

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        if len(gridpoints) != self.cap.size:
            raise ValueError("PathSpeedConstraint: cap and gridpoints differ in length")
        upper = np.square(self.cap)
        xbound = np.column_stack([np.zeros_like(upper), upper])
        return None, None, None, None, None, None, xbound


class TangentialAccelerationConstraint(LinearConstraint):
    """``|s''| <= a_t`` (units/s^2): the acceleration along the path."""

    def __init__(self, a_t: float, dof: int):
        super().__init__()
        self.a_t = float(a_t)
        self.dof = dof
        self._format_string = f"    Tangential acceleration limit: {self.a_t}\n"

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        n = len(gridpoints)
        ubound = np.column_stack([np.full(n, -self.a_t), np.full(n, self.a_t)])
        return None, None, None, None, None, ubound, None


class CentripetalAccelerationConstraint(LinearConstraint):
    """``|q''(s)| s'^2 <= a_n`` (units/s^2) on both sides of every gridpoint."""

    def __init__(self, a_n: float, dof: int):
        super().__init__()
        self.a_n = float(a_n)
        self.dof = dof
        self._format_string = f"    Centripetal acceleration limit: {self.a_n}\n"

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        left, right = _sided(path, gridpoints, 2)
        kappa = np.maximum(np.linalg.norm(left, axis=1), np.linalg.norm(right, axis=1))
        with np.errstate(divide="ignore"):
            upper = np.where(kappa > 0.0, self.a_n / np.where(kappa > 0.0, kappa, 1.0), np.inf)
        xbound = np.column_stack([np.zeros_like(upper), upper])
        return None, None, None, None, None, None, xbound
