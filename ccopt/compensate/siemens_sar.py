"""SINUMERIK smooth approach and retraction (SAR): the sub-moves P0 .. P4.

Programming Manual Fundamentals 6FC5398-2EP40-0BA0, section 2.10.4
"Smooth approach and retraction"; Function Manual W1, section 18.5.4.
In the plane (u, v) with normal w, for an approach on side ``k`` with
radius ``r`` to the contour start ``P4`` whose first element leaves along
the unit tangent ``t``, the tool-centre end point is ``Q = P4 + r*o(t)``:

* ``G147``: a straight line along ``t`` ending at ``Q``, of length
  ``DISR + r`` (DISR is the cutter edge's distance from the contour start).
* ``G247`` / ``G347``: a quadrant / semicircle of radius ``DISR`` (the
  tool-centre path's) ending at ``Q`` tangent to ``t``, centre
  ``C = Q + DISR*s*perp(t)`` turning by ``s*pi/2`` / ``s*pi``; the
  approach side ``s`` is ``k`` (``G140``), +1 (``G141``, left), -1
  (``G142``, right) or the side of ``t`` the start point lies on (``G143``).
* ``G340``: from P0 parallel to the plane to P1 above the curve's start,
  perpendicular to the plane down to P3 at ``DISCL`` above the contour's
  plane (the start's height without DISCL), then the curve to ``Q``: a
  helix when P3 lies above ``Q``.
* ``G341``: P0 -> P1 parallel to the plane, P1 -> P2 down to ``DISCL``,
  P2 -> P3 down to the contour's plane at ``FAD``, then the curve in the plane.

A retraction (``G148``/``G248``/``G348``) is the same construction run
backwards, leaving the contour's end along its last tangent toward the
G40 block's end point P0. The moves P0 -> P3 run at the motion in force
before the block (rapid after G0), the infeed P2 -> P3 at ``FAD`` (else the
feed), the curve at the feed in force (W1 18.5.4: "the movement from P0 to
P3 takes place at the velocity valid before the SAR block"). A SAR the
style's ``sar`` option adds runs P0 -> P3 at the block's own motion.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.compensate.corners import Element, perp
from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line
from ccopt.program.model import Motion, SmoothApproach
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import PathSegment, Role

APPROACH_KINDS = ("G147", "G247", "G347")
#: The turn of the approach curve: none (a line), a quadrant, a semicircle.
_SWEEP = {"G147": 0.0, "G247": math.pi / 2.0, "G347": math.pi}


def retraction_kind(approach: str) -> str:
    """``G147`` -> ``G148`` and so on."""
    return approach[:3] + "8"


def approach_side(direction: str, k: int, t, start_offset) -> int:
    """The side ``s`` (+1 left of ``t``, -1 right) the approach comes from:
    ``G140`` the compensation side ``k``, ``G141`` left, ``G142`` right,
    ``G143`` the side of the tangent the start point lies on
    (``start_offset``: start point minus contour point; on the tangent: ``k``)."""
    if direction == "G141":
        return 1
    if direction == "G142":
        return -1
    if direction == "G143":
        c = float(t[0] * start_offset[1] - t[1] * start_offset[0])
        if abs(c) > POINT_EPS:
            return 1 if c > 0 else -1
    return k if k != 0 else 1


def approach_curve(kind: str, Q, t, s: int, r: float, disr: float):
    """The approach curve ending at ``Q`` tangent to ``t`` (see the module
    docstring): a :class:`Line` or an :class:`Arc`."""
    Q = np.asarray(Q, float)
    t = np.asarray(t, float)
    if _SWEEP[kind[:3] + "7"] == 0.0:
        P3 = Q - (disr + r) * t
        return Line((float(P3[0]), float(P3[1])), (float(Q[0]), float(Q[1])))
    sweep = s * _SWEEP[kind[:3] + "7"]
    C = Q + disr * s * perp(t)
    theta_end = math.atan2(Q[1] - C[1], Q[0] - C[0])
    return Arc((float(C[0]), float(C[1])), float(disr), theta_end - sweep, sweep)


def _reversed(geom):
    if isinstance(geom, Line):
        return Line(geom.end, geom.start)
    return Arc(geom.center, geom.radius, geom.theta0 + geom.sweep, -geom.sweep)


def _point(p) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


def sar_pieces(el: Element, approach: bool, sar: SmoothApproach, contour: dict,
               start, end) -> list[PathSegment]:
    """The tool-path segments of SAR block ``el``: an approach ending at
    ``end`` (the contour's offset start) or a retraction starting at
    ``start`` (the contour's offset end). ``contour[id(el)]`` is the
    contour's tangent there, its side and radius."""
    blk = el.block
    info = contour.get(id(el))
    if info is None:
        s = blk.source
        raise CompensationError(f"{sar.kind}: the smooth {'approach' if approach else 'retraction'}"
                                f" needs a contour move {'after' if approach else 'before'} it "
                                "in the plane", s.file, s.line, s.col)
    t, k, r = info
    t = np.asarray(t, float)
    if approach:
        P0, w0, Q, w4, P = el.start, el.w0, np.asarray(end, float), el.w1, el.end
    else:
        # the retraction is the approach to the contour's end run backwards
        P0, w0, Q, w4, P = el.end, el.w1, np.asarray(start, float), el.w0, el.start
    s = approach_side(sar.direction, k, t, np.asarray(P0, float) - np.asarray(P, float))
    if approach:
        curve = approach_curve(sar.kind, Q, t, s, r, sar.disr)
    else:
        curve = approach_curve(sar.kind, Q, -t, -s, r, sar.disr)
    P3 = np.asarray(curve.start, float)
    top = sar.discl_abs if sar.discl_abs is not None else (
        None if sar.discl is None else w4 + sar.discl)
    if sar.feed is not None or sar.infeed_feed is not None:
        # the reader's: P0 -> P3 at the motion in force before the block, the
        # curve at the feed in force (G1 even when the block says G0)
        fast, feed = sar.infeed_feed, sar.feed
    else:
        fast = None if blk.motion is Motion.RAPID else blk.feed
        feed = blk.feed
    slow = sar.fad if sar.fad is not None else feed
    p0, p3 = _point(P0), _point(P3)
    if sar.infeed == "G340":
        w3 = top if top is not None else w0
        pieces = [(Line(p0, p3), w0, w0, fast), (Line(p3, p3), w0, w3, fast),
                  (curve, w3, w4, feed)]
    else:
        w2 = top if top is not None else w0
        pieces = [(Line(p0, p3), w0, w0, fast), (Line(p3, p3), w0, w2, fast),
                  (Line(p3, p3), w2, w4, slow), (curve, w4, w4, feed)]
    if not approach:
        pieces = [(_reversed(g), b, a, f) for g, a, b, f in reversed(pieces)]
    lead = Role.LEAD_IN if approach else Role.LEAD_OUT
    out = []
    for geom, a, b, feed in pieces:
        if geom.length <= POINT_EPS and abs(b - a) <= POINT_EPS:
            continue
        out.append(PathSegment(geom, Role.RAPID if feed is None else lead, blk, a, b, feed))
    return out
