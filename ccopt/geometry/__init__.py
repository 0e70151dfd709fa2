"""Exact 2-D geometry: primitives, offsets, intersections and distances.

Imports nothing else from ccopt (numpy and scipy only). Lengths are in
program units, angles in radians; a signed sweep is counter-clockwise when
positive; "left" is the tangent rotated by +90 degrees.

- :mod:`~ccopt.geometry.angles`: sweep conventions and the inside-the-sweep test.
- :mod:`~ccopt.geometry.primitives`: :class:`Line`, :class:`Arc`,
  :class:`Spiral` (:mod:`~ccopt.geometry.spiral`), evaluated by arc length
  (shared helpers in :mod:`~ccopt.geometry.arclength`).
- :mod:`~ccopt.geometry.offset`: :func:`offset` (raw offset to the left).
- :mod:`~ccopt.geometry.intersect`: :func:`line_line`, :func:`line_circle`,
  :func:`circle_circle`, :func:`intersections`.
- :mod:`~ccopt.geometry.distance`: vectorised closed-form distance kernels
  (:mod:`~ccopt.geometry.point_distance`, :mod:`~ccopt.geometry.curve_distance`,
  on :mod:`~ccopt.geometry.columns`), :func:`distance`, :class:`SegmentArray`,
  :func:`pair_distance`.
"""
from ccopt.geometry.angles import TWO_PI, angle_along, angle_in_sweep, sweep_between, sweep_sign
from ccopt.geometry.distance import (
    KIND_ARC, KIND_LINE, KIND_SPIRAL, SegmentArray, arc_arc, distance, pair_distance,
    point_arc, point_point, point_segment, segment_arc, segment_segment,
)
from ccopt.geometry.intersect import circle_circle, intersections, line_circle, line_line
from ccopt.geometry.curve import BezierCurve
from ccopt.geometry.offset import offset
from ccopt.geometry.primitives import Arc, Line, Point, Primitive, Spiral, translated

__all__ = [
    "translated",
    "TWO_PI", "angle_along", "angle_in_sweep", "sweep_between", "sweep_sign",
    "Arc", "BezierCurve", "Line", "Point", "Primitive", "Spiral",
    "offset",
    "line_line", "line_circle", "circle_circle", "intersections",
    "point_point", "point_segment", "point_arc", "segment_segment", "segment_arc", "arc_arc",
    "distance", "SegmentArray", "pair_distance", "KIND_LINE", "KIND_ARC", "KIND_SPIRAL",
]
