"""Raw offset of one primitive (no trimming, no joining).

``offset(seg, d)`` moves ``seg`` by the signed distance ``d`` (program units)
to the LEFT of its direction of travel (``d < 0``: to the right). Corner
handling, trimming and joining belong to :mod:`ccopt.compensate`.

- :class:`Line` -> :class:`Line` translated by ``d * normal``.
- :class:`Arc` -> concentric :class:`Arc` with the same angles and radius
  ``R - d * sign(sweep)`` (for a counter-clockwise arc the left is toward
  the centre), or ``None`` when that radius is ``<= 0``: the tool would have
  to be on the far side of the centre, so the offset path vanishes.
- :class:`Spiral` -> :class:`Spiral` with both ``rho0`` and ``rho1`` changed
  the same way, or ``None`` when either becomes ``<= 0``. This is the RADIAL
  offset that controllers apply to a circular move with unequal radii (the
  tool centre stays on the ray from the programmed centre, at the programmed
  radius plus or minus the cutter radius); it is again exactly an Archimedean
  spiral because the radius stays linear in the swept angle. It is NOT the
  true parallel curve of the spiral: the normal distance between the two
  differs from ``|d|`` by a factor ``rho / sqrt(rho^2 + b^2)``.
"""
from __future__ import annotations

from ccopt.geometry.angles import sweep_sign
from ccopt.geometry.primitives import Arc, Line, Spiral


def offset(seg, d: float):
    """Raw offset of ``seg`` by ``d`` to the left of travel; ``None`` if it vanishes.

    Raises ``ValueError`` for a zero-length line (it has no left side) and
    ``TypeError`` for anything that is not a Line, Arc or Spiral.
    """
    d = float(d)
    if isinstance(seg, Line):
        if seg.length == 0.0:
            raise ValueError("a zero-length Line has no direction to offset from")
        tx, ty = seg.direction
        nx, ny = -ty, tx
        return Line((seg.p0[0] + d * nx, seg.p0[1] + d * ny),
                    (seg.p1[0] + d * nx, seg.p1[1] + d * ny))
    if isinstance(seg, Arc):
        R = seg.radius - d * sweep_sign(seg.sweep)
        if not R > 0.0:
            return None
        return Arc(seg.center, R, seg.theta0, seg.sweep)
    if isinstance(seg, Spiral):
        delta = d * sweep_sign(seg.sweep)
        r0, r1 = seg.rho0 - delta, seg.rho1 - delta
        if not (r0 > 0.0 and r1 > 0.0):
            return None
        if seg.sweep == 0.0:
            # A split-off end point: keep rho0 == rho1 exactly.
            r1 = r0
        return Spiral(seg.center, r0, r1, seg.theta0, seg.sweep)
    raise TypeError(f"offset() takes a Line, Arc or Spiral, not {type(seg).__name__}")


__all__ = ["offset"]
