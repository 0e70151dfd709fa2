"""Spindle speed modes and feeds tied to the spindle: ``G96``/``G97`` and
``G95`` feed per revolution (LinuxCNC ``convert_spindle_mode``,
``convert_feed_mode``; canon ``SET_SPINDLE_MODE`` and the CSS numerator of
``emccanon.cc``).

* ``G97`` (the start-up mode): the spindle turns at ``S`` revolutions per
  minute.
* ``G96 S<v> [D<rpm>]``: constant surface speed, ``v`` metres per minute
  under ``G21`` (feet per minute under ``G20``): at radius ``r`` (``|X|`` in
  work coordinates, the distance from the spindle axis) the spindle turns at
  ``1000 v / (2 pi r)`` (``12 v / (2 pi r)``) revolutions per minute, at most
  ``D``. Without ``D`` at ``X0`` the speed has no bound: refused there.
* ``G95``: F is program units per revolution; the feed is ``F * rpm / 60``
  units per second. ``G33``, ``G33.1`` and ``G76`` move K (or P) per revolution.

A block has one feed. Under ``G96`` a move that changes its radius sees the
spindle speed change along it; the block takes the speed at its largest
radius (the slowest), so its time is an upper bound, and the reader notes it
once (``Program.meta[NOTES]``). A move at one radius (turning along Z, a
thread pass) is exact.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.coordinates import to_work
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.units import input_factor
from ccopt.program.model import NOTES

#: ``G96`` and ``G97`` in tenths.
CONSTANT_SURFACE_SPEED, CONSTANT_RPM = 960, 970
#: ``G95`` in tenths.
PER_REVOLUTION = 950
#: The words that start the note on G96 feed bounds.
_BOUND = "G96 (constant surface speed)"
#: Length units per metre (G21) and per foot (G20) of surface speed.
_PER_SURFACE_UNIT = {"mm": 1000.0, "inch": 12.0}


def set_spindle_mode(state: GCodeState, code: int, L: dict) -> None:
    """``G96 [D]`` or ``G97`` of a line whose ``S`` (if any) is already read."""
    if code == CONSTANT_RPM:
        state.css = None
        return
    max_rpm = abs(L["D"][0]) if "D" in L else None
    state.css = [0.0, max_rpm]
    set_surface_speed(state)


def set_surface_speed(state: GCodeState) -> None:
    """Under ``G96``: the surface speed ``S`` as the radius-times-rpm product it
    keeps, in output units (the units in force when S is given)."""
    if state.css is not None:
        per = _PER_SURFACE_UNIT[state.units or state.out_units or "mm"]
        state.css[0] = per * state.spindle_speed / (2.0 * math.pi) * input_factor(state)


def revolutions_per_minute(state: GCodeState, radius: float, col: int) -> float:
    """The spindle speed at ``radius`` (output units from the spindle axis)."""
    if state.css is None:
        return state.spindle_speed
    product, max_rpm = state.css
    if radius <= 0.0:
        if max_rpm is None:
            raise state.error("G96 (constant surface speed) at X0 without D: the spindle "
                              "speed has no bound there; give the maximum as G96 D<rpm>", col)
        return max_rpm
    rpm = product / radius
    return rpm if max_rpm is None else min(rpm, max_rpm)


def largest_radius(state: GCodeState, start, end, center=None) -> float:
    """The largest distance from the spindle axis (work ``|X|``) along the move
    from ``start`` to ``end`` (machine points); an arc about ``center`` is
    bounded by its centre's distance plus its radius."""
    xa, xb = to_work(state, start)[0], to_work(state, end)[0]
    far = max(abs(xa), abs(xb))
    near = 0.0 if xa * xb < 0.0 else min(abs(xa), abs(xb))    # a move across the axis
    if center is not None:
        c = to_work(state, center)
        far = max(far, abs(c[0]) + math.dist(start, center))
        near = -1.0                                           # an arc: its radius varies
    notes = state.meta.get(NOTES, ())
    if state.css is not None and far != near and not any(_BOUND in n for n in notes):
        file, line = state.where(state.line_no)
        state.meta.setdefault(NOTES, []).append(
            f"{file}:{line}: {_BOUND}: a move that changes its radius is fed at the "
            "spindle speed of its largest radius (the slowest), so its time is an upper "
            "bound")
    return far


def per_revolution(state: GCodeState, per_rev: float, start, end, col: int,
                   center=None) -> float:
    """The feed (output units per second) of a move of ``per_rev`` units per
    spindle revolution from ``start`` to ``end``; refused with the spindle
    stopped (nothing moves)."""
    if state.spindle == "stopped" or not state.spindle_speed > 0:
        raise state.error("feed per spindle revolution with the spindle not turning: start "
                          "it with S and M3 (or M4) first", col)
    rpm = revolutions_per_minute(state, largest_radius(state, start, end, center), col)
    return per_rev * rpm / 60.0

