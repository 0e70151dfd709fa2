"""Coordinate systems (LinuxCNC ``convert_coordinate_system``, ``convert_setup``
and ``convert_axis_offsets`` in ``interp_convert.cc``).

A programmed absolute coordinate is in the *work* coordinate system; the
reader keeps every :class:`~ccopt.program.model.Block` in machine coordinates:

    machine = programmed + G5x origin (of the active system) + axis offset

per axis, lengths in program units. Sign convention as LinuxCNC's: an origin
or offset is where the work zero lies in machine coordinates.

- ``G54`` .. ``G59.3`` select origin 1 .. 9, kept in parameters
  ``#[5201 + 20 n]`` (X), ``+1`` (Y), ``+2`` (Z); ``#5220`` holds the active
  index. Refused while compensation is on.
- ``G10 L2 P<n> X Y Z`` sets origin ``n`` (``P0``: the active one);
  ``G10 L20 P<n> ...`` sets it so that the current point gets the given
  coordinates. Refused for the active system while compensation is on.
- ``G92 X Y Z`` sets the axis offset so that the current point gets the
  given coordinates; ``G52 X Y Z`` sets the offset itself (a local origin).
  Both write ``#5211``-``#5213`` and set ``#5210 = 1``. ``G92.1`` clears the
  offset and its parameters, ``G92.2`` clears the offset and keeps them,
  ``G92.3`` restores the offset from them. Refused while compensation is on.
- ``G53`` moves to machine coordinates for its own line (``G0``/``G1``,
  absolute only, not while compensation is on).

Initial values come from the parameters (e.g. a LinuxCNC parameter file,
:func:`read_var_file`). The XY rotation of ``G10 L2 R`` is refused; only X, Y
and Z are read.
"""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.program.gcode.parameters import MAX_PARAMETER
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt

_AXES = "XYZ"
#: ``G54`` .. ``G59.3`` in tenths -> origin index 1 .. 9.
ORIGIN_CODES = {540: 1, 550: 2, 560: 3, 570: 4, 580: 5, 590: 6, 591: 7, 592: 8, 593: 9}
ACTIVE_ORIGIN = 5220     # parameter holding the active origin index
OFFSET_APPLIED = 5210    # 1 while the G92/G52 offset is in force
OFFSET_BASE = 5211       # #5211..#5213: the G92/G52 offset, X Y Z


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
    _check_rotation(state, state.origin_index, None)
    if state.params.get(OFFSET_APPLIED, 0.0) == 1.0:
        state.axis_offset = tuple(state.params.get(OFFSET_BASE + k, 0.0) for k in range(3))


def origin(state: GCodeState, index: int | None = None) -> tuple[float, float, float]:
    """Origin ``index`` (default: the active one) in machine coordinates."""
    base = origin_base(state.origin_index if index is None else index)
    return tuple(state.params.get(base + k, 0.0) for k in range(3))


def work_offset(state: GCodeState) -> tuple[float, float, float]:
    """Machine minus programmed coordinates: active origin plus axis offset."""
    o = origin(state)
    return tuple(o[k] + state.axis_offset[k] for k in range(3))


def select_origin(state: GCodeState, tenths: int, col: int) -> None:
    """``G54`` .. ``G59.3``."""
    if state.side != 0:
        raise state.error("cannot change coordinate systems with cutter radius "
                          "compensation on: turn it off (G40) first", col)
    index = ORIGIN_CODES[tenths]
    _check_rotation(state, index, col)
    state.origin_index = index
    state.params[ACTIVE_ORIGIN] = float(index)


def set_origin(state: GCodeState, L: dict, col: int) -> None:
    """``G10 L2`` / ``G10 L20``: the origin of coordinate system ``P``."""
    level = L.get("L", (None, col))
    if level[0] not in (2, 20):
        raise state.error("G10 is read only as L2 or L20 (coordinate system origins); "
                          "give tool data in a tool table (--tool-table)", level[1])
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
    if "R" in L and L["R"][0] != 0.0:
        raise state.error("G10 R (XY rotation of a coordinate system) is not supported: "
                          "ccopt reads unrotated origins only", L["R"][1])
    base = origin_base(index)
    old = origin(state, index)
    for k, a in enumerate(_AXES):
        if a not in L:
            continue
        if level[0] == 2:
            state.params[base + k] = L[a][0]
        else:
            # the current point, in system ``index``, gets the given value
            current = state.pos[k] - old[k] - state.axis_offset[k]
            state.params[base + k] = old[k] + current - L[a][0]


def set_axis_offset(state: GCodeState, tenths: int, L: dict, col: int) -> None:
    """``G92``, ``G92.1``, ``G92.2``, ``G92.3`` and ``G52``."""
    if state.side != 0:
        raise state.error("cannot change axis offsets with cutter radius compensation on: "
                          "turn it off (G40) first", col)
    offset = list(state.axis_offset)
    if tenths in (920, 520):
        if not any(a in L for a in _AXES):
            raise state.error(f"G{fmt(tenths / 10)} needs at least one axis word", col)
        o = origin(state)
        for k, a in enumerate(_AXES):
            if a in L:
                value = L[a][0]
                offset[k] = value if tenths == 520 else state.pos[k] - o[k] - value
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


def _check_rotation(state: GCodeState, index: int, col: int | None) -> None:
    angle = state.params.get(rotation_parameter(index), 0.0)
    if angle != 0.0:
        message = (f"coordinate system {index} is rotated by {fmt(angle)} deg (parameter "
                   f"#{rotation_parameter(index)}): rotated origins are not supported")
        if col is None:
            raise ProgramError(message, state.file)
        raise state.error(message, col)


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
