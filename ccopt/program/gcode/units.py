"""Length units (LinuxCNC ``convert_length_units``): ``G20``/``G21`` may change
in the middle of a program; the reader converts every length to one output
unit, the program's first (or the caller's ``units``).

LinuxCNC rescales its whole state (position, offsets, feed, tool data) when
the units change; keeping the state in one output unit and scaling each
line's length words by the factor in force is the same arithmetic. Length
words are ``X Y Z I J K``, ``R`` of an arc, ``D`` of ``G41.1``/``G42.1`` (a
diameter) and ``F`` under ``G94`` (units per minute; it is set before the
line's unit change, as in RS274NGC's order of execution). Tool tables are in
their own units (``table_units``; by default the output unit).
"""
from __future__ import annotations

from ccopt.program.gcode.state import GCodeState

MM_PER_INCH = 25.4
UNITS = ("mm", "inch")
_LENGTH_LETTERS = "XYZIJKUVW@"


def length_factor(from_units: str, to_units: str) -> float:
    """Multiply a length in ``from_units`` by this to get ``to_units``."""
    if from_units == to_units:
        return 1.0
    return MM_PER_INCH if from_units == "inch" else 1.0 / MM_PER_INCH


def input_factor(state: GCodeState) -> float:
    """Output units per unit of the words as written now."""
    return length_factor(state.units or state.out_units or "mm", output_units(state))


def output_units(state: GCodeState) -> str:
    """The unit every length is converted to (fixed by the first G20/G21, or
    the caller's; mm when the program moves before saying)."""
    return state.out_units or state.units or "mm"


def set_units(state: GCodeState, units: str) -> None:
    """``G20``/``G21``: the words that follow are in ``units``; the first
    one fixes the output unit unless the caller did."""
    if state.out_units is None:
        state.out_units = "mm" if state.moved and state.units is None else units
    state.units = units


def scale_lengths(state: GCodeState, L: dict, gcodes: dict) -> dict:
    """``L`` with its length words in output units (positions unchanged)."""
    factor = input_factor(state)
    if factor == 1.0:
        return L
    scaled = dict(L)
    letters = _LENGTH_LETTERS
    setting = gcodes.get("axis_setting")
    tool_data = "L" in L and L["L"][0] in (1, 10, 11)
    motion = gcodes.get("motion")
    mode = motion[0] if motion else state.motion_mode
    if (not (setting and setting[0] == 100) or tool_data) and mode != 760:
        letters += "R"          # G10 L2's R is a rotation in degrees, G76's a degression
    comp = gcodes.get("comp")
    if comp and comp[0] in (411, 421):      # G41.1/G42.1 D is a diameter
        letters += "D"
    if mode in (730, 830):
        letters += "QD"                     # G73/G83 peck depth and clearance
    if mode == 760:
        letters += "PE"                     # G76 pitch and taper length
    for letter in letters:
        if letter in scaled:
            value, col = scaled[letter]
            scaled[letter] = (value * factor, col)
    return scaled


def feed_factor(state: GCodeState) -> float:
    """Output units per written unit for ``F`` (before the line's unit change)."""
    return input_factor(state)
