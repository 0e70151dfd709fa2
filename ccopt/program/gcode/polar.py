"""LinuxCNC's polar coordinates: ``@`` radius and ``^`` angle in place of X and Y
(``interp_find.cc`` ``find_ends``; ``interp_cycles.cc`` ``convert_cycle_xy``
and ``CYCLE_MACRO``).

The point is in the X/Y plane of the work coordinates whatever the plane,
about the work origin; the angle in degrees, counter-clockwise from +X; the
radius in program units. Under ``G90`` ``@r ^a`` is the point at radius r and
angle a; a word left out keeps the current point's (its radius, its angle).
Under ``G91`` ``@`` adds to the current point's radius and ``^`` turns it
about the origin. A canned cycle under ``G91`` applies them at every repeat
(L), so ``G91 G81 ^60 L6`` drills six holes 60 degrees apart. Refused, as
LinuxCNC refuses them: X or Y on the same line, ``@`` alone at the origin
(no angle to keep), ``G91`` polar motion at the origin, ``G53`` with polar
coordinates.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.coordinates import to_work
from ccopt.program.gcode.state import GCodeState

#: The polar words: radius and angle.
POLAR = "@^"


def has_polar(L: dict) -> bool:
    return "@" in L or "^" in L


def check_polar(state: GCodeState, L: dict, machine: bool) -> None:
    """LinuxCNC's refusals of a line's polar words."""
    col = min(L[w][1] for w in POLAR if w in L)
    if machine:
        raise state.error("Cannot use polar coordinates with G53", col)
    for w in "XY":
        if w in L:
            raise state.error("Cannot specify X or Y words with polar coordinate", L[w][1])


def polar_to_xy(state: GCodeState, L: dict) -> dict:
    """``L`` with its ``@``/``^`` words turned into the X and Y words of the
    same point (absolute under ``G90``, increments under ``G91``); ``L``
    passed :func:`check_polar`."""
    x0, y0, _ = to_work(state, state.pos)
    col = min(L[w][1] for w in POLAR if w in L)
    if state.incremental:
        x, y = turn(state, x0, y0, L, col)
    else:
        if "@" in L and "^" not in L and x0 == 0.0 and y0 == 0.0:
            raise state.error("Must specify angle in polar coordinate if at the origin", col)
        radius = L["@"][0] if "@" in L else math.hypot(x0, y0)
        theta = math.radians(L["^"][0]) if "^" in L else math.atan2(y0, x0)
        x, y = radius * math.cos(theta), radius * math.sin(theta)
    out = {k: v for k, v in L.items() if k not in POLAR}
    out["X"] = ((x - x0) if state.incremental else x, col)
    out["Y"] = ((y - y0) if state.incremental else y, col)
    return out


def turn(state: GCodeState, x: float, y: float, L: dict, col: int) -> tuple[float, float]:
    """The point ``(x, y)`` moved by the ``G91`` polar words of ``L``: its
    radius grown by ``@``, then turned by ``^`` degrees about the origin."""
    if "@" in L:
        if x == 0.0 and y == 0.0:
            raise state.error("Incremental motion with polar coordinates is indeterminate "
                              "when at the origin", col)
        theta = math.atan2(y, x)
        radius = math.hypot(x, y) + L["@"][0]
        x, y = radius * math.cos(theta), radius * math.sin(theta)
    if "^" in L:
        if x == 0.0 and y == 0.0:
            raise state.error("G91 motion with polar coordinates is indeterminate when at "
                              "the origin", col)
        theta = math.atan2(y, x) + math.radians(L["^"][0])
        radius = math.hypot(x, y)
        x, y = radius * math.cos(theta), radius * math.sin(theta)
    return x, y
