"""Group-0 codes that use the axis words without a motion mode: homing
through stored positions and tool data in the program (LinuxCNC
``convert_home``, ``convert_savehome`` and ``convert_setup_tool`` in
``interp_convert.cc``).

- ``G28``/``G30`` [axes]: a rapid to the axis words' point (the waypoint, in
  the current work coordinates, ``G90``/``G91`` as in force; with no axis
  word the current point: LinuxCNC still sends that traverse), then a rapid
  to the stored position, machine coordinates in ``#5161``-``#5163``
  (``G28``) or ``#5181``-``#5183`` (``G30``): only the axes written go there,
  all three when none is written. Refused with compensation on.
- ``G28.1``/``G30.1`` store the current machine position there. Refused with
  compensation on.
- ``G10 L1 P<tool>`` sets tool data directly, ``G10 L10`` the tool's offsets
  so that the current point gets the given coordinates, ``G10 L11`` the same
  measured in ``G59.3`` (the touch-off fixture): ``R`` is the radius the
  later ``G41``/``G42 D<tool>`` (or the loaded tool) compensates with,
  ``Q`` the lathe orientation. The tool must be in the tool table, as in
  LinuxCNC. Tool length offsets (``X Y Z``) move the tool along its axis
  only, as ``G43`` does, which ccopt does not model: they are read and
  checked, and change no path.
"""
from __future__ import annotations

from ccopt.program.gcode.axes import any_extra, extra_end, home_extra, save_home_extra
from ccopt.program.gcode.coordinates import to_machine, to_work
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.units import length_factor, output_units
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, gname
from ccopt.program.model import Block, Motion, Source

_AXES = "XYZ"
#: ``G28``/``G30`` (tenths) -> parameter of the stored position's X.
HOME_PARAMETER = {280: 5161, 281: 5161, 300: 5181, 301: 5181}
_TOOL_LEVELS = (1, 10, 11)


def is_tool_setup(L: dict) -> bool:
    """``G10`` with ``L1``, ``L10`` or ``L11`` (tool data)."""
    return "L" in L and L["L"][0] in _TOOL_LEVELS


def save_home(state: GCodeState, code: int, col: int) -> None:
    """``G28.1``/``G30.1``: the current machine position, stored."""
    if state.side != 0:
        raise state.error("Cannot set reference point with cutter compensation in effect "
                          f"(LinuxCNC refuses {gname(code)} so): program G40 first", col)
    base = HOME_PARAMETER[code]
    for k in range(3):
        state.params[base + k] = state.pos[k]
    save_home_extra(state, code)


def go_home(state: GCodeState, code: int, L: dict, col: int, waypoint, src: Source,
            mcodes: tuple, emit) -> None:
    """``G28``/``G30``: rapid to ``waypoint`` (machine coordinates of the
    line's axis words), then to the stored position on the axes written."""
    if state.side != 0:
        raise state.error(f"Cannot use {gname(code)} with cutter radius compensation on "
                          "(LinuxCNC refuses it): program G40 first", col)
    base = HOME_PARAMETER[code]
    home = tuple(state.params.get(base + k, 0.0) for k in range(3))
    written = [a in L for a in _AXES]
    any_written = any(written) or any_extra(L)
    if not any_written:
        written = [True, True, True]
    way_extra = extra_end(state, L, False)
    _rapid(state, waypoint, src, mcodes, emit, way_extra)
    if all(written):
        end = home
    else:
        # LinuxCNC mixes the two points in work coordinates
        way, target = to_work(state, waypoint), to_work(state, home)
        end = to_machine(state, [target[k] if written[k] else way[k] for k in range(3)])
    _rapid(state, end, src, (), emit, home_extra(state, code, L, way_extra, any_written))


def _rapid(state: GCodeState, end, src: Source, mcodes: tuple, emit, extra) -> None:
    end = (end[0], end[1], end[2])
    if extra is not None:
        state.extra = list(extra)
    emit(state, Block(src, Motion.RAPID, state.pos, end, state.modal(), mcodes=mcodes))
    state.pos = end
    state.moved = True


def set_tool_data(state: GCodeState, L: dict, col: int) -> None:
    """``G10 L1``/``L10``/``L11 P<tool> [X Y Z] [R] [Q] [I J]``."""
    level = int(L["L"][0])
    if "P" not in L:
        raise state.error(f"G10 L{level} needs P, the tool number", col)
    p, pcol = L["P"]
    if p < 0 or abs(p - round(p)) > WHOLE_NUMBER_TOL:
        raise state.error(f"G10 L{level} P{fmt(p)}: P is a tool number, a whole number >= 0",
                          pcol)
    tool = int(round(p))
    table = state.tool_table
    if table is None or (tool not in table and tool != 0):
        where = "no tool table was given (--tool-table)" if table is None \
            else "it is not in the tool table"
        raise state.error(f"Requested tool {tool} not found in the tool table (LinuxCNC "
                          f"refuses G10 L{level} so): {where}", pcol)
    if not any(w in L for w in "XYZRQIJ"):
        raise state.error(f"G10 L{level} without offsets has no effect: give X Y Z, R, Q, "
                          "I or J", col)
    if "R" in L:
        r, rcol = L["R"]
        factor = length_factor(output_units(state), state.table_units or output_units(state))
        table[tool] = 2.0 * r * factor
    if "Q" in L:
        q, qcol = L["Q"]
        if abs(q - round(q)) > WHOLE_NUMBER_TOL:
            raise state.error(f"Q number in G10 is not an integer: Q{fmt(q)}", qcol)
        if not 0 <= round(q) <= 9:
            raise state.error(f"Invalid tool orientation Q{fmt(q)}: 0 to 9", qcol)
        table.orientation[tool] = int(round(q))

