"""SINUMERIK circle forms beyond ``G2``/``G3`` with a centre or ``CR=``
(Programming Manual Fundamentals, "Circular interpolation": "Circle with
opening angle and center point / end point (AR)", "Circular interpolation
with intermediate and end points (CIP)", "Circular interpolation with
tangential transition (CT)").

Each is turned into the ISO form the G-code core executes: ``G2``/``G3``
with the end point and the centre as offsets from the start (``I J K``), so
the arc itself is checked and stored as every other arc. Positions here
are machine coordinates ``(x, y, z)``; the words written are in the work
frame, which a programmable rotation (:mod:`.frames`) turns; ``u, v`` the plane's axes
(:data:`~ccopt.program.model.PLANE_AXES`); angles in degrees as written.
"""
from __future__ import annotations

import math

from ccopt.program.expr import ExprError
from ccopt.program.gcode.arcs import CENTRE_WORDS
from ccopt.program.gcode.coordinates import rotate_xy, rotation, to_machine, to_work
from ccopt.program.gcode.state import GCodeState
from ccopt.program.model import PLANE_AXES, Motion
from ccopt.tolerances import POINT_EPS

#: |cross| / (|a| |b|) below this: three CIP points on one line (no circle).
COLLINEAR_SINE = 1e-9


def end_point(state: GCodeState, L: dict) -> tuple[float, float, float]:
    """Machine coordinates of the X Y Z words ``L`` (absolute in work
    coordinates, or added under ``G91``, along the work axes, which a
    programmable rotation turns)."""
    work = list(to_work(state, state.pos))
    for k, a in enumerate("XYZ"):
        if a in L:
            v = L[a][0]
            work[k] = work[k] + v if state.incremental else v
    return to_machine(state, work)


def set_end_words(state: GCodeState, L: dict, end, col: int) -> None:
    """Write machine point ``end``'s in-plane coordinates as X Y Z words in
    the distance mode in force."""
    here, there = to_work(state, state.pos), to_work(state, end)
    iu, iv, _ = PLANE_AXES[state.plane]
    for k in (iu, iv):
        a = "XYZ"[k]
        value = there[k] - here[k] if state.incremental else there[k]
        L[a] = (value, L[a][1] if a in L else col)


def set_centre_words(state: GCodeState, L: dict, centre_uv, col: int) -> None:
    """The centre ``(u, v)`` (machine) as the plane's centre words: offsets
    from the start along the work axes (the core turns them with a rotated
    system, whose arcs are in G17)."""
    iu, iv, _ = PLANE_AXES[state.plane]
    wu, wv = CENTRE_WORDS[state.plane]
    du, dv = rotate_xy(centre_uv[0] - state.pos[iu], centre_uv[1] - state.pos[iv],
                       -rotation(state))
    L[wu] = (du, col)
    L[wv] = (dv, col)


def centre_of_words(state: GCodeState, L: dict) -> tuple[float, float]:
    """The machine ``(u, v)`` of the centre the plane's centre words give
    (offsets from the start along the work axes; a word not written: 0)."""
    iu, iv, _ = PLANE_AXES[state.plane]
    wu, wv = CENTRE_WORDS[state.plane]
    du, dv = rotate_xy(L[wu][0] if wu in L else 0.0, L[wv][0] if wv in L else 0.0,
                       rotation(state))
    return (state.pos[iu] + du, state.pos[iv] + dv)


def _uv(state: GCodeState, p) -> tuple[float, float]:
    iu, iv, _ = PLANE_AXES[state.plane]
    return (p[iu], p[iv])


def cip(state: GCodeState, L: dict, middle, col: int) -> int:
    """``CIP``: the circle through the start, ``middle`` (machine) and the end
    point; sets the centre words and returns the motion (20 cw, 30 ccw)."""
    s = _uv(state, state.pos)
    m = _uv(state, middle)
    e = _uv(state, end_point(state, L))
    ax, ay = m[0] - s[0], m[1] - s[1]
    bx, by = e[0] - s[0], e[1] - s[1]
    cross = ax * by - ay * bx
    scale = math.hypot(ax, ay) * math.hypot(bx, by)
    if scale <= POINT_EPS ** 2 or abs(cross) <= COLLINEAR_SINE * scale:
        raise ExprError("CIP: the start, intermediate (I1 J1 K1) and end points lie on one "
                        "line or coincide: no circle passes through them", col)
    a2, b2 = ax * ax + ay * ay, bx * bx + by * by
    cu = s[0] + (by * a2 - ay * b2) / (2.0 * cross)
    cv = s[1] + (ax * b2 - bx * a2) / (2.0 * cross)
    set_centre_words(state, L, (cu, cv), col)
    # start -> intermediate -> end turning counter-clockwise: a counter-clockwise arc
    return 30 if cross > 0 else 20


def last_tangent(state: GCodeState, col: int) -> tuple[float, float]:
    """Unit tangent, in the plane, at the end of the last move that moved in it."""
    for b in reversed(state.blocks):
        if b.modal.plane != state.plane or not b.motion.is_move:
            continue
        (u0, v0), (u1, v1) = b.start_uv, b.end_uv
        if b.motion.is_arc:
            cu, cv = b.center_uv
            du, dv = u1 - cu, v1 - cv
            t = (-dv, du) if b.motion is Motion.ARC_CCW else (dv, -du)
        else:
            t = (u1 - u0, v1 - v0)
        n = math.hypot(*t)
        if n > POINT_EPS:
            return (t[0] / n, t[1] / n)
    raise ExprError("CT continues the previous move tangentially, but no move in the "
                    "plane comes before it", col)


def ct(state: GCodeState, L: dict, col: int) -> int | None:
    """``CT``: the arc from the start, tangent to the previous move, to the
    end point. Sets the centre words and returns the motion (20/30), or
    ``None`` when the end lies on the tangent (a straight move)."""
    tx, ty = last_tangent(state, col)
    s = _uv(state, state.pos)
    e = _uv(state, end_point(state, L))
    dx, dy = e[0] - s[0], e[1] - s[1]
    nx, ny = -ty, tx                       # left normal of the tangent
    along = nx * dx + ny * dy
    chord2 = dx * dx + dy * dy
    if chord2 <= POINT_EPS ** 2:
        raise ExprError("CT: the end point is the start point", col)
    if abs(along) <= COLLINEAR_SINE * chord2:
        return None
    rho = chord2 / (2.0 * along)           # signed: > 0 centre on the left (counter-clockwise)
    set_centre_words(state, L, (s[0] + rho * nx, s[1] + rho * ny), col)
    return 30 if rho > 0 else 20


def opening_angle(state: GCodeState, L: dict, motion: int, ar: float, has_centre: bool,
                  col: int) -> None:
    """``AR=``: with the centre words, the end point is the start turned by
    ``ar`` degrees about the centre; with the end point, the centre lies on
    the chord's bisector where the chord subtends ``ar``. Writes the missing
    words."""
    if not 0.0 < ar < 360.0:
        raise ExprError(f"AR={ar:g}: the opening angle must lie between 0 and 360 degrees", col)
    s = _uv(state, state.pos)
    sign = 1.0 if motion == 30 else -1.0
    if has_centre:
        cu, cv = centre_of_words(state, L)
        a = math.radians(sign * ar)
        du, dv = s[0] - cu, s[1] - cv
        eu = cu + du * math.cos(a) - dv * math.sin(a)
        ev = cv + du * math.sin(a) + dv * math.cos(a)
        end = list(state.pos)
        iu, iv, _ = PLANE_AXES[state.plane]
        end[iu], end[iv] = eu, ev
        set_end_words(state, L, end, col)
        return
    e = _uv(state, end_point(state, L))
    dx, dy = e[0] - s[0], e[1] - s[1]
    half = 0.5 * math.hypot(dx, dy)
    if half <= POINT_EPS:
        raise ExprError("AR with an end point: the end point is the start point (give the "
                        "centre for a full circle)", col)
    dist = half / math.tan(math.radians(ar) / 2.0)   # signed: beyond 180 degrees, the other side
    nx, ny = -dy / (2.0 * half), dx / (2.0 * half)
    cu = 0.5 * (s[0] + e[0]) + sign * dist * nx
    cv = 0.5 * (s[1] + e[1]) + sign * dist * ny
    set_centre_words(state, L, (cu, cv), col)
