"""Arc geometry of ``G2``/``G3`` (LinuxCNC ``interp_arc.cc``).

In the active plane (u, v) with normal w (:data:`~ccopt.program.model.PLANE_AXES`),
an arc's centre comes from centre words (``I J`` in ``G17``, ``K I`` in
``G18``, ``J K`` in ``G19``; offsets from the start under ``G91.1``, absolute
under ``G90.1``) or from a radius ``R`` (``R > 0``: the shorter arc, ``R < 0``:
the longer). ``G2`` is clockwise and ``G3`` counter-clockwise seen looking
down w. ``P`` is the number of turns (``P1`` = the arc itself). Lengths are in
program units, angles in radians.
"""
from __future__ import annotations

import math

import numpy as np

from ccopt import tolerances
from ccopt.geometry.angles import TWO_PI
from ccopt.geometry.columns import math_each
from ccopt.program.gcode.coordinates import rotate_xy, rotation, to_machine
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.units import MM_PER_INCH, output_units
from ccopt.program.gcode.words import fmt
from ccopt.program.model import PLANE_AXES

#: Largest G2/G3 ``P`` (number of turns) ccopt reads: 100. LinuxCNC takes
#: any int (2^31 - 1), but a helix of 100 turns is already a 100 mm bore at
#: a 1 mm pitch or a 50 mm thread single-pointed at 0.5 mm, past the helical
#: and thread milling passes parts need (more turns: several G2 blocks).
#: Every turn costs: ~126 feed grid intervals, its share of the samples of
#: the cycle time, a CIRCLE of its own in a PMAC export (each read back and
#: verified). Measured on a radius-12 helix at F600 (issue 29): 100 turns
#: took ``compare`` 33 s and 3.6 GB and a PMAC export 16 s; 1000 turns a
#: PMAC export 143 s and ``compare`` over 24 GB (killed); ``P10000`` took
#: ``feed`` 34 s and 2 GB before a refusal and ``P2147483647`` asked it for
#: terabytes (exit 3). Beyond it the ``P`` word is a located error.
MAX_ARC_TURNS = 100
#: A P word within this of a whole number is that number of turns.
_TURNS_WHOLE_TOL = 1e-3
#: Radii below this fraction of the arc tolerance are zero (LinuxCNC).
_ZERO_RADIUS_FRACTION = 0.1
#: An R arc whose half chord reaches |R| to this relative rounding is a
#: half circle (the centre is the chord's midpoint).
_SEMICIRCLE_REL_TOL = 1e-12

# Centre words of an arc per plane: (u word, v word), and the word that has no use.
CENTRE_WORDS = {"XY": ("I", "J"), "ZX": ("K", "I"), "YZ": ("J", "K")}
_FORBIDDEN_CENTRE = {"XY": "K", "ZX": "J", "YZ": "I"}
_PLANE_G = {"XY": "G17", "ZX": "G18", "YZ": "G19"}


def arc_tolerance(state: GCodeState) -> float:
    """Absolute arc radius tolerance in program units."""
    tol = tolerances.ARC_RADIUS_ABS_TOL_MM
    return tol / MM_PER_INCH if output_units(state) == "inch" else tol


def is_modal_arc_without_plane_motion(state: GCodeState, L: dict, cur, end) -> bool:
    """G2/G3 still modal, no centre word and no in-plane displacement (the
    Fagor 8070 manual's ``G91 G40 Y0`` after a G03): no arc is asked for,
    so it is a straight move (of zero length in the plane). With a centre
    word or in-plane motion an arc needs its centre, and its absence stays
    an error."""
    iu, iv, _ = PLANE_AXES[state.plane]
    wu, wv = CENTRE_WORDS[state.plane]
    return (not any(w in L for w in (wu, wv, "R", "P"))
            and cur[iu] == end[iu] and cur[iv] == end[iv])


def arc_geometry(state: GCodeState, motion: int, L: dict, cur, end,
                 gcol: int) -> tuple[tuple[float, float, float], int, float]:
    """Centre ``(x, y, z)``, extra full ``turns`` and path length of the
    ``G2`` (``motion`` 20) or ``G3`` (30) arc from ``cur`` to ``end`` written
    with the words ``L`` (letter -> (value, col)); ``gcol`` locates errors
    that belong to the arc as a whole.

    The centre's w coordinate is the start's; the length of a helix combines
    the in-plane arc length (mean of start and end radius) with the travel
    along w.
    """
    plane = state.plane
    iu, iv, iw = PLANE_AXES[plane]
    gname = "G2" if motion == 20 else "G3"
    has_r = _check_centre_words(state, L, gname, gcol)
    turns = _extra_turns(state, L, gname)
    u0, v0 = cur[iu], cur[iv]
    u1, v1 = end[iu], end[iv]
    tol = arc_tolerance(state)
    if has_r:
        cu, cv = _r_centre(state, motion, L, (u0, v0), (u1, v1), tol, gname)
    else:
        cu, cv = _word_centre(state, L, (u0, v0), (u1, v1), tol, gname, gcol)
    center = [cur[0], cur[1], cur[2]]
    center[iu] = cu
    center[iv] = cv
    if not (math.isfinite(cu) and math.isfinite(cv)):
        raise state.error("arc centre overflows (not a finite number)", gcol)
    r0 = math.hypot(u0 - cu, v0 - cv)
    r1 = math.hypot(u1 - cu, v1 - cv)
    sweep = _sweep(u0 - cu, v0 - cv, u1 - cu, v1 - cv, motion == 30) + TWO_PI * turns
    length = math.hypot(0.5 * (r0 + r1) * sweep, end[iw] - cur[iw])
    return (center[0], center[1], center[2]), turns, length


def _check_centre_words(state: GCodeState, L: dict, gname: str, gcol: int) -> bool:
    """Check the arc gives its centre one way (words of its plane, or R);
    True for an R arc."""
    plane = state.plane
    wu, wv = CENTRE_WORDS[plane]
    bad = _FORBIDDEN_CENTRE[plane]
    if bad in L:
        raise state.error(f"{bad} word with a {gname} arc in the {plane} plane "
                          f"({_PLANE_G[plane]}): give the centre with {wu} and {wv}",
                          L[bad][1])
    has_r = "R" in L
    has_c = wu in L or wv in L
    if has_r and has_c:
        raise state.error(f"{gname} with both R and {wu}/{wv}: give either the radius R or "
                          "the centre offsets", L["R"][1])
    if not has_r and not has_c:
        raise state.error(f"{gname} arc with no centre: give the centre offsets {wu} and {wv} "
                          f"({_PLANE_G[plane]} plane) or a radius R", gcol)
    return has_r


def _extra_turns(state: GCodeState, L: dict, gname: str) -> int:
    """Full turns added to the arc by ``P`` (``P1``, the default, adds none)."""
    if "P" not in L:
        return 0
    p, pcol = L["P"]
    if abs(p - round(p)) > _TURNS_WHOLE_TOL or round(p) < 1:
        raise state.error(f"{gname} P{fmt(p)}: P is the number of turns, a whole number "
                          "from 1", pcol)
    if round(p) > MAX_ARC_TURNS:
        raise state.error(f"{gname} P{fmt(p)}: at most {MAX_ARC_TURNS} turns (P is the number "
                          "of turns; split the helix into several arcs if it really needs more)",
                          pcol)
    return int(round(p)) - 1


def _word_centre(state: GCodeState, L: dict, start_uv, end_uv, tol: float, gname: str,
                 gcol: int) -> tuple[float, float]:
    """Centre (u, v) from the plane's centre words; checks that the start and
    end radii are non-zero and agree within the tolerances."""
    (u0, v0), (u1, v1) = start_uv, end_uv
    wu, wv = CENTRE_WORDS[state.plane]
    if state.arc_incremental:
        du = L[wu][0] if wu in L else 0.0
        dv = L[wv][0] if wv in L else 0.0
        theta = rotation(state)
        if theta != 0.0:
            # offsets along the rotated work axes (arcs are G17 there)
            du, dv = rotate_xy(du, dv, theta)
        cu, cv = u0 + du, v0 + dv
    else:
        if wu not in L or wv not in L:
            missing = wu if wu not in L else wv
            raise state.error(f"G90.1 absolute arc centre needs both {wu} and {wv} "
                              f"({missing} is missing)", gcol)
        # absolute centres are programmed in work coordinates
        iu, iv, iw = PLANE_AXES[state.plane]
        work = [0.0, 0.0, 0.0]
        work[iu], work[iv] = L[wu][0], L[wv][0]
        machine = to_machine(state, work)
        cu, cv = machine[iu], machine[iv]
    r0 = math.hypot(u0 - cu, v0 - cv)
    r1 = math.hypot(u1 - cu, v1 - cv)
    zero = _ZERO_RADIUS_FRACTION * tol
    if r0 < zero or r1 < zero:
        raise state.error(f"{gname} zero-radius arc: the centre lies on the "
                          f"{'start' if r0 < zero else 'end'} point; check "
                          f"{wu}/{wv}", gcol)
    err = abs(r0 - r1)
    if err > tol and err > tolerances.ARC_RADIUS_REL_TOL * max(r0, r1):
        raise state.error(f"inconsistent arc radii: start r={r0:.6g}, end r={r1:.6g} "
                          f"(differ by {err:.3g}, more than {tol:.3g} and "
                          f"{tolerances.ARC_RADIUS_REL_TOL:.3%}): correct the end point "
                          f"or the centre offsets {wu}/{wv}", gcol)
    return cu, cv


def incremental_centres(state: GCodeState, start_uv: np.ndarray, end_uv: np.ndarray,
                        offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centres ``(n, 2)`` of ``n`` arcs in the plane, from ``start_uv`` to
    ``end_uv`` (``(n, 2)``), whose centre words give the incremental
    ``offsets`` ``(n, 2)`` (an absent word: ``0.0``) in a system that is not
    rotated, and whether :func:`arc_geometry` refuses each (its radii
    disagree, the centre is on an end or not finite): each row, bit for bit,
    the centre :func:`_word_centre` and :func:`arc_geometry` give it (the
    same operations, with math's hypot)."""
    tol = arc_tolerance(state)
    with np.errstate(invalid="ignore", over="ignore"):
        centre = start_uv + offsets
        cu, cv = centre[:, 0], centre[:, 1]
        r0 = math_each(math.hypot, start_uv[:, 0] - cu, start_uv[:, 1] - cv)
        r1 = math_each(math.hypot, end_uv[:, 0] - cu, end_uv[:, 1] - cv)
        zero = _ZERO_RADIUS_FRACTION * tol
        err = np.abs(r0 - r1)
        larger = np.where(r1 > r0, r1, r0)      # Python's max(r0, r1)
        refused = ((r0 < zero) | (r1 < zero)
                   | ((err > tol) & (err > tolerances.ARC_RADIUS_REL_TOL * larger))
                   | ~np.isfinite(cu) | ~np.isfinite(cv))
    return centre, refused


def _r_centre(state: GCodeState, motion: int, L: dict, start_uv, end_uv, tol: float,
              gname: str) -> tuple[float, float]:
    """Centre (u, v) of an R-format arc (LinuxCNC ``arc_data_r``): on the
    chord's perpendicular bisector, to the right of the chord for ``G2``
    with ``R > 0`` (or ``G3`` with ``R < 0``), to the left otherwise."""
    (u0, v0), (u1, v1) = start_uv, end_uv
    wu, wv = CENTRE_WORDS[state.plane]
    r, rcol = L["R"]
    if u1 == u0 and v1 == v0:
        raise state.error(f"{gname} R arc ends where it starts: the centre is undefined; "
                          f"use {wu}/{wv} centre offsets for a full circle", rcol)
    if r == 0:
        raise state.error(f"{gname} with R0: the radius must not be zero", rcol)
    ar = abs(r)
    mu, mv = (u0 + u1) / 2.0, (v0 + v1) / 2.0
    half = math.hypot(u1 - mu, v1 - mv)
    if half - ar > tol:
        raise state.error(f"arc radius R{fmt(r)} too small to reach the end point: the "
                          f"chord needs R >= {half:.6g}", rcol)
    if half / ar > 1.0 - _SEMICIRCLE_REL_TOL:
        half = ar  # a semicircle within tolerance
    chord = math.atan2(v1 - v0, u1 - u0)
    if (motion == 20) == (r > 0):
        theta = chord - math.pi / 2.0
    else:
        theta = chord + math.pi / 2.0
    offset = ar * math.cos(math.asin(half / ar))
    return mu + offset * math.cos(theta), mv + offset * math.sin(theta)


def _sweep(du0: float, dv0: float, du1: float, dv1: float, ccw: bool) -> float:
    """Swept angle (radians, > 0) from start to end direction; equal directions: a full turn."""
    a0 = math.atan2(dv0, du0)
    a1 = math.atan2(dv1, du1)
    d = (a1 - a0) if ccw else (a0 - a1)
    d = math.fmod(d, TWO_PI)
    if d <= 0.0:
        d += TWO_PI
    return d
