"""Coordinate systems (LinuxCNC ``convert_coordinate_system``, ``convert_setup``
and ``convert_axis_offsets`` in ``interp_convert.cc``).

A programmed absolute coordinate is in the *work* coordinate system; the
reader keeps every :class:`~ccopt.program.model.Block` in machine coordinates:

    machine = R(rotation) (programmed + axis offset) + G5x origin

lengths in program units, ``R`` the rotation of the active system about Z
(LinuxCNC's ``rotate_and_offset_pos`` in ``emccanon.cc``: the G92/G52
offset is added before the rotation, the origin after). Sign convention as
LinuxCNC's: an origin or offset is where the work zero lies in machine
coordinates.

- ``G54`` .. ``G59.3`` select origin 1 .. 9, kept in parameters
  ``#[5201 + 20 n]`` (X), ``+1`` (Y), ``+2`` (Z); ``#5220`` holds the active
  index. Refused while compensation is on.
- ``G10 L2 P<n> X Y Z R`` sets origin ``n`` (``P0``: the active one) and its
  XY rotation ``R`` (degrees, counter-clockwise, ``#[5210 + 20 n]``);
  ``G10 L20 P<n> ...`` sets the origin so that the current point gets the
  given coordinates (in the system's rotated axes; ``R`` is refused there, as
  LinuxCNC refuses it). Refused for the active system while compensation is
  on. The machine does not move when the active system changes.
- ``G92 X Y Z`` sets the axis offset so that the current point gets the
  given coordinates; ``G52 X Y Z`` sets the offset itself (a local origin).
  Both write ``#5211``-``#5213`` and set ``#5210 = 1``. ``G92.1`` clears the
  offset and its parameters, ``G92.2`` clears the offset and keeps them,
  ``G92.3`` restores the offset from them. Refused while compensation is on.
- ``G53`` moves to machine coordinates for its own line (``G0``/``G1``,
  absolute only, not while compensation is on).

Initial values come from the parameters (e.g. a LinuxCNC parameter file,
:func:`read_var_file`). Only X, Y and Z are read. A rotated system keeps arcs
and compensation in G17: an arc or compensation in G18/G19 while the active
system is rotated is refused (its plane would not be a machine plane).
"""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.program.gcode.axes import any_extra, set_extra_axis_offset, set_extra_origin
from ccopt.program.gcode.state import MAX_PARAMETER, GCodeState
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt

_AXES = "XYZ"
#: ``G54`` .. ``G59.3`` in tenths -> origin index 1 .. 9.
ORIGIN_CODES = {540: 1, 550: 2, 560: 3, 570: 4, 580: 5, 590: 6, 591: 7, 592: 8, 593: 9}
ACTIVE_ORIGIN = 5220     # parameter holding the active origin index
OFFSET_APPLIED = 5210    # 1 while the G92/G52 offset is in force
OFFSET_BASE = 5211       # #5211..#5213: the G92/G52 offset, X Y Z
#: The G92/G52 parameters, first and last: the flag #5210 and #5211-#5219.
G92_PARAMETERS = (5210, 5219)


def origin_base(index: int) -> int:
    """Parameter number of origin ``index``'s X (``#5221`` for G54)."""
    return 5201 + 20 * index


def rotation_parameter(index: int) -> int:
    """Parameter number of origin ``index``'s XY rotation (degrees)."""
    return 5210 + 20 * index


def init_coordinates(state: GCodeState) -> None:
    """Active origin and axis offset from the parameters, as LinuxCNC starts."""
    index = state.params.get(ACTIVE_ORIGIN, 1.0)
    if not (abs(index - round(index)) <= WHOLE_NUMBER_TOL and 1 <= round(index) <= 9):
        raise ProgramError(f"parameter #{ACTIVE_ORIGIN} (active coordinate system) is "
                           f"{fmt(index)}: it must be 1 to 9 (G54 to G59.3)", state.file)
    state.origin_index = int(round(index))
    if state.params.get(OFFSET_APPLIED, 0.0) != 0.0:     # any non-zero, as LinuxCNC
        state.axis_offset = tuple(state.params.get(OFFSET_BASE + k, 0.0) for k in range(3))


def origin(state: GCodeState, index: int | None = None) -> tuple[float, float, float]:
    """Origin ``index`` (default: the active one) in machine coordinates."""
    base = origin_base(state.origin_index if index is None else index)
    get = state.params.get
    return (get(base, 0.0), get(base + 1, 0.0), get(base + 2, 0.0))


def work_offset(state: GCodeState) -> tuple[float, float, float]:
    """Machine minus programmed coordinates: active origin plus axis offset
    (of an unrotated system; :func:`to_machine` holds for any)."""
    o, a = origin(state), state.axis_offset
    return (o[0] + a[0], o[1] + a[1], o[2] + a[2])


def rotation(state: GCodeState, index: int | None = None) -> float:
    """XY rotation of system ``index`` (default: the active one), degrees."""
    return state.params.get(rotation_parameter(state.origin_index if index is None
                                               else index), 0.0)


def rotate_xy(x: float, y: float, degrees: float) -> tuple[float, float]:
    """``(x, y)`` turned counter-clockwise by ``degrees`` (LinuxCNC ``rotate``)."""
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    return (x * c - y * s, x * s + y * c)


def to_machine(state: GCodeState, work) -> tuple[float, float, float]:
    """Machine coordinates of the work (programmed) point ``work``."""
    theta = rotation(state)
    if theta == 0.0:
        off = work_offset(state)
        return (work[0] + off[0], work[1] + off[1], work[2] + off[2])
    o, a = origin(state), state.axis_offset
    x, y = rotate_xy(work[0] + a[0], work[1] + a[1], theta)
    return (x + o[0], y + o[1], work[2] + a[2] + o[2])


def to_work(state: GCodeState, machine) -> tuple[float, float, float]:
    """Work (programmed) coordinates of the machine point ``machine``."""
    theta = rotation(state)
    if theta == 0.0:
        off = work_offset(state)
        return (machine[0] - off[0], machine[1] - off[1], machine[2] - off[2])
    o, a = origin(state), state.axis_offset
    x, y = rotate_xy(machine[0] - o[0], machine[1] - o[1], -theta)
    return (x - a[0], y - a[1], machine[2] - o[2] - a[2])


def check_unrotated_plane(state: GCodeState, what: str, col: int) -> None:
    """``what`` (an arc, compensation) only in G17 while the system is rotated."""
    theta = rotation(state)
    if theta != 0.0 and state.plane != "XY":
        raise state.error(f"{what} in the {state.plane} plane of a rotated coordinate system "
                          f"(G5x system {state.origin_index} turned {fmt(theta)} deg about Z) "
                          "is not supported: its plane is not a machine plane; use G17 or "
                          "an unrotated system", col)


def select_origin(state: GCodeState, tenths: int, col: int) -> None:
    """``G54`` .. ``G59.3``."""
    if state.side != 0:
        raise state.error("cannot change coordinate systems with cutter radius "
                          "compensation on: turn it off (G40) first", col)
    index = ORIGIN_CODES[tenths]
    state.origin_index = index
    state.params[ACTIVE_ORIGIN] = float(index)


def set_origin(state: GCodeState, L: dict, col: int) -> None:
    """``G10 L2`` / ``G10 L20``: the origin of coordinate system ``P``."""
    level = L.get("L", (None, col))
    if level[0] not in (2, 20):
        raise state.error(f"G10 L{fmt(level[0]) if level[0] is not None else ''}: ccopt "
                          "reads G10 L1, L10 and L11 (tool data) and L2 and L20 (coordinate "
                          "system origins)", level[1])
    if "P" not in L:
        raise state.error(f"G10 L{level[0]} needs P, the coordinate system (0 for the "
                          "active one, 1 to 9 for G54 to G59.3)", col)
    p, pcol = L["P"]
    if not (abs(p - round(p)) <= WHOLE_NUMBER_TOL and 0 <= round(p) <= 9):
        raise state.error(f"G10 P{fmt(p)}: P must be 0 to 9", pcol)
    index = int(round(p)) or state.origin_index
    if state.side != 0 and index == state.origin_index:
        raise state.error("cannot change the active coordinate system with cutter radius "
                          "compensation on: turn it off (G40) first", col)
    if "R" in L and level[0] == 20:
        raise state.error("R not allowed in G10 L20 (LinuxCNC refuses it): set a rotation "
                          "with G10 L2", L["R"][1])
    base = origin_base(index)
    if level[0] == 20:
        _set_origin_l20(state, index, L)
    else:
        for k, a in enumerate(_AXES):
            if a in L:
                state.params[base + k] = L[a][0]
    set_extra_origin(state, index, L, level[0])
    if "R" in L:
        state.params[rotation_parameter(index)] = L["R"][0]


def _set_origin_l20(state: GCodeState, index: int, L: dict) -> None:
    """``G10 L20``: the origin of system ``index`` such that the current point
    gets the given coordinates in it (rotated as the system is)."""
    base = origin_base(index)
    old = origin(state, index)
    theta = rotation(state, index)
    a = state.axis_offset
    if theta == 0.0:
        for k, letter in enumerate(_AXES):
            if letter in L:
                current = state.pos[k] - old[k] - a[k]
                state.params[base + k] = old[k] + current - L[letter][0]
        return
    # LinuxCNC's convert_setup: the current point in system ``index``
    cx, cy = rotate_xy(state.pos[0] - old[0], state.pos[1] - old[1], -theta)
    cx, cy = cx - a[0], cy - a[1]
    x = L["X"][0] if "X" in L else cx
    y = L["Y"][0] if "Y" in L else cy
    ox, oy = rotate_xy(cx + a[0], cy + a[1], theta)
    nx, ny = rotate_xy(x + a[0], y + a[1], theta)
    state.params[base] = old[0] + ox - nx
    state.params[base + 1] = old[1] + oy - ny
    if "Z" in L:
        state.params[base + 2] = state.pos[2] - a[2] - L["Z"][0]


def set_axis_offset(state: GCodeState, tenths: int, L: dict, col: int) -> None:
    """``G92``, ``G92.1``, ``G92.2``, ``G92.3`` and ``G52``."""
    if state.side != 0:
        raise state.error("cannot change axis offsets with cutter radius compensation on: "
                          "turn it off (G40) first", col)
    offset = list(state.axis_offset)
    set_extra_axis_offset(state, tenths, L)   # before #5210 changes
    if tenths in (920, 520):
        if not any(a in L for a in _AXES) and not any_extra(L):
            raise state.error(f"G{fmt(tenths / 10)} needs at least one axis word", col)
        if rotation(state) == 0.0:
            o = origin(state)
            here = tuple(state.pos[k] - o[k] for k in range(3))   # work + offset
        else:
            # the current point before the rotation (work + offset) stays put
            w = to_work(state, state.pos)
            here = tuple(w[k] + offset[k] for k in range(3))
        for k, a in enumerate(_AXES):
            if a in L:
                value = L[a][0]
                offset[k] = value if tenths == 520 else here[k] - value
        state.params[OFFSET_APPLIED] = 1.0
        for k in range(3):
            state.params[OFFSET_BASE + k] = offset[k]
    elif tenths in (921, 922):
        state.params[OFFSET_APPLIED] = 0.0
        offset = [0.0, 0.0, 0.0]
        if tenths == 921:
            for k in range(3):
                state.params[OFFSET_BASE + k] = 0.0
    else:  # 923
        state.params[OFFSET_APPLIED] = 1.0
        offset = [state.params.get(OFFSET_BASE + k, 0.0) for k in range(3)]
    state.axis_offset = tuple(offset)


_VAR_LINE = re.compile(r"\s*(\d+)\s+([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(?:[;#].*)?\Z")


def read_var_file(path: str | os.PathLike) -> dict[int, float]:
    """A LinuxCNC parameter file (``linuxcnc.var``): ``NUMBER VALUE`` per line.

    Blank lines are skipped; anything else that is not a parameter number
    (1 .. 5601) and a finite number is a located :class:`ProgramError`.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise ProgramError(f"cannot read parameter file: {exc.strerror or exc}",
                           str(path)) from None
    params: dict[int, float] = {}
    for lineno, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        m = _VAR_LINE.match(line)
        if not m:
            raise ProgramError("a parameter file line is a parameter number and its value, "
                               "e.g. '5221 1.5'", str(path), lineno)
        number, value = int(m.group(1)), float(m.group(2))
        if not 1 <= number <= MAX_PARAMETER or not math.isfinite(value):
            raise ProgramError(f"parameter #{number} = {m.group(2)}: numbers run from 1 to "
                               f"{MAX_PARAMETER} and values must be finite",
                               str(path), lineno)
        params[number] = value
    return params
