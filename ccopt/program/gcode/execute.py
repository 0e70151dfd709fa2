"""Executing the words of a line (LinuxCNC ``interp_convert.cc``).

:func:`execute_words` first decides which motion the line performs and
checks that every word has a code to use it (LinuxCNC ``enhance_block`` and
``check_other_codes``), then applies the line in RS274NGC order: feed mode,
feed rate, tool selection and change, dwell, plane, units, cutter
compensation, tool length, distance modes, Fagor corner and start/end modes,
motion mode, the move itself and finally program end. Moves and dwells
become :class:`~ccopt.program.model.Block` objects in the state.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.arcs import arc_geometry, is_modal_arc_without_plane_motion
from ccopt.program.gcode.codes import Words, classify
from ccopt.program.gcode.state import GCodeState, ProgramEnd
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, gname
from ccopt.program.model import MAX_COORDINATE, Block, Motion, Source, out_of_range

_AXES = "XYZ"
_PLANES = {170: "XY", 180: "ZX", 190: "YZ"}
_TOOL_NUMBER_LIMIT = 2**31  # tool numbers are C ints in LinuxCNC


def execute_words(state: GCodeState, words: Words) -> None:
    """Execute one line's (classified on first use) words."""
    if not words.classified:
        classify(state, words)
        words.classified = True
    gc = words.gcodes
    L = words.letters
    motion = _motion_of(state, gc, L)
    is_arc = motion in (20, 30)
    _check_word_usage(state, gc, L, is_arc)
    mcodes = tuple(words.mcodes)
    first_col = words.first if words.first is not None else 0
    _set_feed_and_tool(state, gc, L, mcodes)
    dwell = gc.get("dwell")
    if dwell is not None:
        _dwell(state, dwell, L, mcodes, first_col)
    _set_modes(state, gc, L)
    motion_g = gc.get("motion")
    if motion_g is not None:
        state.motion_mode = None if motion_g[0] == 800 else motion_g[0]
    if motion is not None and (any(a in L for a in _AXES) or is_arc):
        _move(state, motion, L, mcodes, first_col, motion_g[1] if motion_g else first_col)
    if any(m in (2, 30) for m in mcodes):
        raise ProgramEnd()


def _motion_of(state: GCodeState, gc: dict, L: dict) -> int | None:
    """The motion (tenths: 0, 10, 20, 30) the line performs, None for none.

    A motion code performs itself; axis words alone repeat the motion mode
    (an error under ``G80``); centre words alone repeat a modal ``G2``/``G3``
    (a full circle).
    """
    axis = any(a in L for a in _AXES)
    motion_g = gc.get("motion")
    if motion_g is not None:
        if motion_g[0] != 800:
            return motion_g[0]
        if axis:
            a = next(a for a in _AXES if a in L)
            raise state.error(f"{a} word with G80: G80 cancels motion, so it cannot use "
                              "axis words", L[a][1])
        return None
    if axis:
        if state.motion_mode is None:
            a = next(a for a in _AXES if a in L)
            raise state.error(f"{a} word with no motion mode in force: add G0, G1, G2 or G3",
                              L[a][1])
        return state.motion_mode
    if ("I" in L or "J" in L or "K" in L) and state.motion_mode in (20, 30):
        return state.motion_mode
    return None


def _check_word_usage(state: GCodeState, gc: dict, L: dict, is_arc: bool) -> None:
    """Every word needs a code on its line that uses it (LinuxCNC ``check_other_codes``)."""
    comp = gc.get("comp")
    if "D" in L and (comp is None or comp[0] == 400):
        raise state.error("D word with no G41, G42, G41.1 or G42.1 to use it", L["D"][1])
    if "H" in L and (gc.get("length") is None or gc["length"][0] != 430):
        raise state.error("H word with no G43 to use it", L["H"][1])
    for w in "IJK":
        if w in L and not is_arc:
            raise state.error(f"{w} word with no G2 or G3 to use it", L[w][1])
    if "R" in L and not is_arc:
        raise state.error("R word with no G2 or G3 to use it", L["R"][1])
    dwell = gc.get("dwell")
    path = gc.get("path")
    if "P" in L and not (is_arc or dwell or (path and path[0] == 640)):
        raise state.error("P word with no G2, G3, G4 or G64 to use it", L["P"][1])
    if "Q" in L and not (path and path[0] == 640):
        raise state.error("Q word with no G64 to use it", L["Q"][1])
    if dwell and is_arc:
        raise state.error("G4 and G2/G3 on one line would share the P word: put the dwell on "
                          "its own line", dwell[1])


def _whole(value: float) -> bool:
    """A non-negative whole number within rounding that fits a tool number."""
    return not (value < 0 or abs(value - round(value)) > WHOLE_NUMBER_TOL
                or value > _TOOL_NUMBER_LIMIT)


def _set_feed_and_tool(state: GCodeState, gc: dict, L: dict, mcodes: tuple) -> None:
    """Feed mode (switching it forgets the feed rate), F, T and ``M6``."""
    fm = gc.get("feed_mode")
    if fm is not None:
        mode = "inverse" if fm[0] == 930 else "per_minute"
        if mode != state.feed_mode:
            state.feed = None
        state.feed_mode = mode
    if "F" in L:
        f, col = L["F"]
        if f < 0:
            raise state.error(f"negative feed rate F{fmt(f)}: F must be >= 0", col)
        if state.feed_mode == "per_minute":
            state.feed = f
    if "T" in L:
        t, col = L["T"]
        if not _whole(t):
            raise state.error(f"T{fmt(t)}: the tool number must be a non-negative integer", col)
        state.selected_tool = int(round(t))
    if 6 in mcodes:
        state.loaded_tool = state.selected_tool


def _dwell(state: GCodeState, dwell: tuple[int, int], L: dict, mcodes: tuple,
           first_col: int) -> None:
    """``G4 P<seconds>``: a dwell block at the current position."""
    if "P" not in L:
        raise state.error("G4 needs the dwell time in seconds as P, e.g. G4 P0.5", dwell[1])
    secs = L["P"][0]
    if secs < 0:
        raise state.error(f"negative dwell time P{fmt(secs)}", L["P"][1])
    _emit(state, Block(Source(state.file, state.line_no + 1, first_col + 1), Motion.DWELL,
                       state.pos, state.pos, state.modal(), dwell=secs, mcodes=mcodes))


def _set_modes(state: GCodeState, gc: dict, L: dict) -> None:
    """Plane, units, compensation, tool length, distance and Fagor modes."""
    plane = gc.get("plane")
    if plane is not None:
        state.plane = _PLANES[plane[0]]
        state.modal_changed()
    units = gc.get("units")
    if units is not None:
        new = "inch" if units[0] == 200 else "mm"
        if state.moved and new != (state.units or "mm"):
            raise state.error(f"{gname(units[0])} changes units after the first move: ccopt "
                              "keeps one unit per program; put G20/G21 before any motion",
                              units[1])
        state.units = new
        state.modal_changed()
    comp = gc.get("comp")
    if comp is not None:
        _compensation(state, comp, L)
    length = gc.get("length")
    if length is not None:
        h = L["H"][0] if "H" in L else None
        state.meta["tool_length"].append((state.line_no + 1, gname(length[0]), h))
    dist = gc.get("distance")
    if dist is not None:
        state.incremental = dist[0] == 910
    adist = gc.get("arc_distance")
    if adist is not None:
        state.arc_incremental = adist[0] == 911
    corner = gc.get("corner")
    if corner is not None:
        state.corner = "circular" if corner[0] == 1360 else "linear"
        state.modal_changed()
    se = gc.get("start_end")
    if se is not None:
        state.start_end = "direct" if se[0] == 1380 else "contour"
        state.modal_changed()


def _compensation(state: GCodeState, comp: tuple[int, int], L: dict) -> None:
    """``G40``/``G41``/``G42`` [``D<tool>``] and ``G41.1``/``G42.1 D<diameter>``:
    side (+1 left, -1 right, 0 off), radius and tool (see docs/gcode.md)."""
    code, col = comp
    state.modal_changed()
    if code == 400:
        state.side = 0
        return
    side = 1 if code in (410, 411) else -1
    if code in (411, 421):
        if "D" not in L:
            raise state.error(f"{gname(code)} needs the tool diameter as D, e.g. "
                              f"{gname(code)} D6", col)
        d = L["D"][0]
        if out_of_range(d):
            raise state.error(f"D{fmt(d)} is out of range: a diameter must lie within "
                              f"+-{MAX_COORDINATE:g}", L["D"][1])
        state.side = -side if d < 0 else side
        state.radius = abs(d) / 2.0
        state.tool = None
        return
    if "D" in L:
        d, dcol = L["D"]
        if not _whole(d):
            raise state.error(f"D{fmt(d)} with {gname(code)} is a tool number: it must be a "
                              "non-negative integer (use G41.1/G42.1 D<diameter> for a "
                              "diameter)", dcol)
        tool = int(round(d))
    else:
        tool = state.loaded_tool
    state.tool = tool
    state.side = side
    diameter = None
    if tool is not None and state.tool_table is not None:
        diameter = state.tool_table.get(tool)
    if diameter is None:
        state.radius = None
    else:
        state.radius = abs(diameter) / 2.0
        if diameter < 0:
            state.side = -side


def _emit(state: GCodeState, block: Block) -> None:
    values = list(block.start) + list(block.end) + list(block.center or ())
    if block.feed is not None:
        values.append(block.feed)
    if not all(math.isfinite(v) for v in values):
        raise state.error("coordinates or feed overflow (not finite numbers): check the "
                          "values on this line", block.source.col - 1)
    if any(out_of_range(v) for v in values):
        # incremental moves add up, and an R arc's centre is computed: check what they make
        raise state.error(f"the move's end point, centre or feed is beyond +-{MAX_COORDINATE:g} "
                          "program units: check the values on this line", block.source.col - 1)
    state.blocks.append(block)


def _move(state: GCodeState, motion: int, L: dict, mcodes: tuple, first_col: int,
          gcol: int) -> None:
    """The move of ``motion`` (tenths) to the axis words' end point (absolute
    or, under ``G91``, incremental); ``gcol`` locates errors of the move."""
    cur = state.pos
    end = list(cur)
    for k, a in enumerate(_AXES):
        if a in L:
            v = L[a][0]
            end[k] = cur[k] + v if state.incremental else v
    end_t = (end[0], end[1], end[2])
    src = Source(state.file, state.line_no + 1, first_col + 1)
    if motion == 0:
        block = Block(src, Motion.RAPID, cur, end_t, state.modal(), mcodes=mcodes)
    elif motion == 10 or is_modal_arc_without_plane_motion(state, L, cur, end_t):
        feed = _feed(state, L, math.dist(cur, end_t), gcol)
        block = Block(src, Motion.LINE, cur, end_t, state.modal(), feed=feed, mcodes=mcodes)
    else:
        center, turns, length = arc_geometry(state, motion, L, cur, end_t, gcol)
        feed = _feed(state, L, length, gcol)
        block = Block(src, Motion.ARC_CCW if motion == 30 else Motion.ARC_CW, cur, end_t,
                      state.modal(), center=center, turns=turns, feed=feed, mcodes=mcodes)
    _emit(state, block)
    state.moved = True
    state.pos = end_t


def _feed(state: GCodeState, L: dict, length: float, col: int) -> float:
    """Feed of a move of ``length`` (program units) in units per second:
    ``F/60`` under ``G94``; under ``G93`` the move takes ``60/F`` seconds."""
    if state.feed_mode == "inverse":
        if "F" not in L:
            raise state.error("G93 inverse time: every G1/G2/G3 move needs its own F word "
                              "(1/minutes for this move)", col)
        f = L["F"][0]
        if f <= 0:
            raise state.error("inverse-time F must be > 0", L["F"][1])
        return length * f / 60.0
    if state.feed is None:
        raise state.error("feed move with no feed rate F: add F<units per minute> on this "
                          "or an earlier line", col)
    if state.feed <= 0:
        raise state.error("feed move with feed rate F0: set F > 0 before this move", col)
    return state.feed / 60.0
