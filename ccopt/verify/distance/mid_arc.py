"""The middle-arc bound of spiral pieces: a certified lower bound of their
distance to a line, an arc or another spiral's pieces, from the arcs about
their centres at their middle polar radii (:func:`mid_arc_bound`), which
:mod:`.certified` and :mod:`.certified_batch` take beside the chords' bound.

A spiral here is Archimedean: polar radius ``rho0 + b u`` and angle ``th0 + sg
u`` about its centre ``c`` for ``u`` in ``[0, U]`` (:class:`~.certified.SpiralParam`);
lengths in program units, angles in radians, ``sg`` the sweep's sign.
"""
from __future__ import annotations

import numpy as np

from ccopt.geometry import Line
from ccopt.geometry.distance import arc_arc, segment_arc


def arcs_to(g, c, R, theta0, sweep):
    """Distances from arcs ``(c, R, theta0, sweep)`` (row-wise) to an exact primitive ``g``."""
    if isinstance(g, Line):
        return segment_arc(np.asarray(g.p0), np.asarray(g.p1), c, R, theta0, sweep)[0]
    return arc_arc(c, R, theta0, sweep, np.asarray(g.center), g.radius, g.theta0, g.sweep)[0]


def mid_arc(c, rho0, b, th0, sg, u0, u1):
    """The arc about a spiral's centre ``c`` at the middle polar radius of each
    piece ``[u0, u1]`` (polar radius ``rho0 + b u``, angle ``th0 + sg u``), over
    the piece's angles: ``(c, R, theta0, sweep, half)``, ``half`` the largest
    distance of a piece point from the arc point at its angle
    (``|rho(u) - R| <= |rho(u1) - rho(u0)| / 2``)."""
    r0 = rho0 + b * u0
    r1 = rho0 + b * u1
    return c, 0.5 * (r0 + r1), th0 + sg * u0, sg * (u1 - u0), 0.5 * np.abs(r1 - r0)


def mid_arc_bound(arc_a, arc_b=None, element_to=None):
    """A certified lower bound of the distance of spiral pieces, each within
    ``half`` of its :func:`mid_arc` ``arc_a``, to an exact element
    (``element_to(c, R, theta0, sweep)``: its exact distance to arcs) or to
    the pieces of another spiral (``arc_b``): the exact distance of the arcs
    less the halves.

    The chords' bound alone cannot settle a spiral that is nearly at one
    distance from the other all along (a tool's corner arc about the part's
    vertex, its end rounded by an export to a spiral 1e-7 off its radius, is
    at the cutter radius from the edge ending there at every angle): every
    piece stays within ``tol`` of the best and is halved down to a chord
    deviation below ``tol``. This bound is that distance to within the
    pieces' radius change, so only the pieces where they are nearest are
    refined. A NaN distance gives no bound (combine with ``np.fmax``).
    """
    c, R, th, sw, half = arc_a
    if arc_b is None:
        return element_to(c, R, th, sw) - half
    cb, Rb, thb, swb, half_b = arc_b
    return arc_arc(c, R, th, sw, cb, Rb, thb, swb)[0] - half - half_b
