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
from dataclasses import replace

from ccopt.program.gcode.arcs import arc_geometry, is_modal_arc_without_plane_motion
from ccopt.program.gcode.axes import extra_end
from ccopt.program.gcode.codes import Words, classify
from ccopt.program.gcode.cycles import (CYCLE_CODES, P_CYCLES, PECK_CYCLES, RIGID_TAP,
                                        end_series, rigid_tap, run_cycle, set_retract_mode)
from ccopt.program.gcode.coordinates import (check_unrotated_plane, rotation, select_origin,
                                             set_axis_offset, set_origin, to_machine, to_work,
                                             work_offset)
from ccopt.program.gcode.lathe_cycles import (FINISHING, LATHE_CYCLES, ROUGHING,
                                              run_lathe_cycle)
from ccopt.program.gcode.machine_words import (END_CODES, frame_of, record_after_motion,
                                               record_line, with_words)
from ccopt.program.gcode.setup import go_home, is_tool_setup, save_home, set_tool_data
from ccopt.program.gcode.polar import check_polar, has_polar, polar_to_xy
from ccopt.program.gcode.spindle import (CONSTANT_SURFACE_SPEED, PER_REVOLUTION, per_revolution,
                                          set_spindle_mode, set_surface_speed)
from ccopt.program.gcode.state import GCodeState, ProgramEnd
from ccopt.program.gcode.threading import THREADING, threading_cycle
from ccopt.program.gcode.units import (feed_factor, length_factor, output_units,
                                       scale_lengths, set_units)
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, gname
from ccopt.program.markers import surface_marker
from ccopt.program.model import (ENDLESS_MAIN, MAX_PROGRAM_COORDINATE, NOTES, Block, Motion,
                                 Source, out_of_range)

_AXES = "XYZ"
#: Words that make a move: X Y Z and the axes carried along (axes.py).
_MOVE_AXES = "XYZABCUVW@^"
_MOVE_AXIS_SET = frozenset(_MOVE_AXES)
_PLANES = {170: "XY", 180: "ZX", 190: "YZ"}
_TOOL_NUMBER_LIMIT = 2**31  # tool numbers are C ints in LinuxCNC
#: Tool number 0 is LinuxCNC's "no tool": diameter 0 whatever the table says.
NO_TOOL = 0


def execute_words(state: GCodeState, words: Words) -> None:
    """Execute one line's (classified on first use) words."""
    if not words.classified:
        classify(state, words)
        words.classified = True
    gc = words.gcodes
    L = words.letters
    motion = _motion_of(state, gc, L)
    is_arc = motion in (20, 30)
    mcodes = tuple(words.mcodes)
    _check_word_usage(state, gc, L, motion, mcodes)
    record_line(state, gc, L, mcodes)
    first_col = words.first if words.first is not None else 0
    units = gc.get("units")
    if units is not None and state.units is None:
        # the program's first G20/G21 applies to its whole line, F included
        _set_units(state, units)
    _set_feed_and_tool(state, gc, L, mcodes)
    dwell = gc.get("dwell")
    if dwell is not None:
        _dwell(state, dwell, L, mcodes, first_col)
    if units is not None:
        # later changes in RS274NGC's order: after F (which keeps its speed)
        _set_units(state, units)
    L = _lathe_diameter(state, gc, L)
    L = scale_lengths(state, L, gc)
    _set_modes(state, gc, L)
    _set_coordinates(state, gc, L, mcodes, first_col)
    if "machine_coords" in gc:
        _check_machine_coords(state, gc, motion)
    motion_g = gc.get("motion")
    previous_mode = state.motion_mode
    if motion_g is not None:
        state.motion_mode = None if motion_g[0] == 800 else motion_g[0]
    if has_polar(L) and motion is not None:
        check_polar(state, L, "machine_coords" in gc)
        if motion in CYCLE_CODES and state.plane != "XY":
            raise state.error("polar coordinates in a canned cycle need G17 (LinuxCNC reads "
                              "them in the XY plane's cycles only)",
                              min(L[w][1] for w in "@^" if w in L))
        if not (motion in CYCLE_CODES and state.incremental):
            L = polar_to_xy(state, L)      # a G91 cycle turns at every repeat (cycles.py)
    axis = not _MOVE_AXIS_SET.isdisjoint(L)
    gcol = motion_g[1] if motion_g else first_col
    if motion in CYCLE_CODES and (axis or motion_g is not None):
        run_cycle(state, motion, gcol, L, mcodes, first_col, previous_mode, _emit)
    elif motion_g is not None or (motion is not None and axis):
        end_series(state)   # a motion that is not a cycle ends a series of cycles
    if motion in LATHE_CYCLES:
        # G70-G72 (lathe_cycles.py) run with or without axis words
        run_lathe_cycle(state, motion, gcol, L, mcodes, first_col, _emit)
    elif motion == THREADING and (axis or motion_g is not None):
        threading_cycle(state, L, mcodes, Source(*state.where(state.line_no), first_col + 1),
                        gcol, _end_point(state, L, False), _emit)
    elif motion == RIGID_TAP and axis:
        rigid_tap(state, L, mcodes, Source(*state.where(state.line_no), first_col + 1), gcol,
                  _end_point(state, L, False), _emit)
    elif motion not in (None, THREADING) and motion not in CYCLE_CODES and (axis or is_arc):
        _move(state, motion, L, mcodes, first_col, gcol, machine="machine_coords" in gc)
    record_after_motion(state, mcodes)
    if any(m in END_CODES for m in mcodes):
        if 99 in mcodes:
            src = state.where(state.line_no)
            state.meta[ENDLESS_MAIN] = (
                f"{src[0]}:{src[1]}: M99 ends the main program: LinuxCNC's task would run "
                "it again from the start for ever (an endless program); ccopt reads one "
                "pass, as LinuxCNC's stand-alone interpreter does")
        raise ProgramEnd()


def _motion_of(state: GCodeState, gc: dict, L: dict) -> int | None:
    """The motion (tenths: 0, 10, 20, 30) the line performs, None for none.

    A motion code performs itself; axis words alone repeat the motion mode
    (an error under ``G80``); centre words alone repeat a modal ``G2``/``G3``
    (a full circle).
    """
    axis = not _MOVE_AXIS_SET.isdisjoint(L)
    motion_g = gc.get("motion")
    setting = gc.get("axis_setting")
    length = gc.get("length")
    if setting is None and length is not None and length[0] == DYNAMIC_TOOL_LENGTH:
        setting = length       # G43.1's axis words are the offsets: nothing moves
    if setting is not None:
        # G10, G52, G92 and G43.1 take the line's axis words: nothing moves
        if motion_g is not None and motion_g[0] != 800:
            raise state.error(f"{gname(setting[0])} and {gname(motion_g[0])} both use the "
                              "axis words: put them on separate lines", motion_g[1])
        return None
    if motion_g is not None:
        if motion_g[0] != 800:
            return motion_g[0]
        if axis:
            a = next(a for a in _MOVE_AXES if a in L)
            raise state.error(f"{a} word with G80: G80 cancels motion, so it cannot use "
                              "axis words", L[a][1])
        return None
    if axis:
        if state.motion_mode is None:
            a = next(a for a in _MOVE_AXES if a in L)
            raise state.error(f"{a} word with no motion mode in force: add G0, G1, G2 or G3",
                              L[a][1])
        return state.motion_mode
    if ("I" in L or "J" in L or "K" in L) and state.motion_mode in (20, 30):
        return state.motion_mode
    return None


#: ``G43.1``: a tool length offset given by the line's axis words (LinuxCNC's
#: dynamic tool length offset), recorded as ``G43`` is (it moves nothing).
DYNAMIC_TOOL_LENGTH = 431

#: Motions taking the E word (LinuxCNC ``check_other_codes``): G70 (finishing
#: pass) and G76 (threading), in tenths. M66-M68 take it too; ccopt has no
#: analog I/O.
E_CYCLES = frozenset({FINISHING, THREADING})

#: ``M19``, spindle orientation: it takes ``R`` (angle), ``Q`` (timeout) and
#: ``P`` (direction), which move nothing (LinuxCNC ``check_other_codes``).
ORIENT_SPINDLE = 19


def _check_word_usage(state: GCodeState, gc: dict, L: dict, motion: int | None,
                      mcodes: tuple = ()) -> None:
    """Every word needs a code on its line that uses it (LinuxCNC ``check_other_codes``);
    ``G64 P Q R`` and ``M19 R Q P`` take theirs (path blending and spindle
    orientation, which set no motion ccopt carries)."""
    is_arc = motion in (20, 30)
    orient = ORIENT_SPINDLE in mcodes
    blend = gc.get("path") is not None and gc["path"][0] == 640
    cycle = motion in CYCLE_CODES
    comp = gc.get("comp")
    g7x, roughing = motion in LATHE_CYCLES, motion in ROUGHING   # lathe_cycles.py
    css = gc.get("spindle_mode", (None,))[0] == CONSTANT_SURFACE_SPEED
    if "D" in L and (comp is None or comp[0] == 400) and motion not in PECK_CYCLES and not g7x \
            and not css:
        raise state.error("D word with no G41, G42, G41.1, G42.1, G70, G71, G72, G73, G83 or "
                          "G96 to use it", L["D"][1])
    thread = motion == THREADING
    if "H" in L and not thread and (gc.get("length") is None or gc["length"][0] != 430):
        raise state.error("H word with no G43 to use it", L["H"][1])
    g10 = gc.get("axis_setting", (None,))[0] == 100
    for w in "IJK":
        if w in L and not (is_arc or motion == 870 or thread or (g10 and w != "K")
                           or (motion in (SYNCHRONISED, RIGID_TAP) and w == "K")
                           or (roughing and w == "I")):
            codes = "G2, G3, G33, G33.1 or G87" if w == "K" else "G2, G3 or G87"
            raise state.error(f"{w} word with no {codes} to use it", L[w][1])
    if "R" in L and not (is_arc or cycle or thread or gc.get("axis_setting", (None,))[0] == 100
                         or blend or orient or roughing):
        raise state.error("R word with no G2, G3, G10, G64, M19 or canned cycle to use it",
                          L["R"][1])
    if "E" in L and motion not in E_CYCLES:
        raise state.error("E word with no G70 or G76 to use it", L["E"][1])
    dwell = gc.get("dwell")
    if "P" in L and not (is_arc or dwell or g10 or blend or orient or thread
                         or motion in P_CYCLES or motion == FINISHING):
        raise state.error("P word with no G2, G3, G4, G10, G64, G74, G82, G84, G86, G89 or "
                          "M19 to use it", L["P"][1])
    lathe = comp is not None and comp[0] in (411, 421)
    if "L" in L and not (g10 or lathe or cycle or thread):
        raise state.error("L word with no G10, G41.1, G42.1 or canned cycle to use it",
                          L["L"][1])
    if "Q" in L and not (blend or orient or motion in PECK_CYCLES or g10 or thread or g7x):
        raise state.error("Q word with no G10, G64, G73, G83 or M19 to use it", L["Q"][1])
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
        mode = {930: "inverse", 940: "per_minute", PER_REVOLUTION: "per_revolution"}[fm[0]]
        if mode != state.feed_mode:
            state.feed = None
        state.feed_mode = mode
    if "F" in L:
        f, col = L["F"]
        if f < 0:
            raise state.error(f"negative feed rate F{fmt(f)}: F must be >= 0", col)
        if state.feed_mode != "inverse":      # units per minute or per revolution
            state.feed = f * feed_factor(state)
    if "T" in L:
        t, col = L["T"]
        if not _whole(t):
            raise state.error(f"T{fmt(t)}: the tool number must be a non-negative integer", col)
        state.selected_tool = int(round(t))
    if 6 in mcodes:
        state.loaded_tool = state.selected_tool
    if "S" in L:
        speed, col = L["S"]
        if speed < 0:
            raise state.error(f"negative spindle speed S{fmt(speed)}: S must be >= 0", col)
        state.spindle_speed = speed
        set_surface_speed(state)
    sm = gc.get("spindle_mode")
    if sm is not None:
        set_spindle_mode(state, sm[0], L)
    for m, turning in ((3, "cw"), (4, "ccw"), (5, "stopped")):
        if m in mcodes:
            state.spindle = turning


def _dwell(state: GCodeState, dwell: tuple[int, int], L: dict, mcodes: tuple,
           first_col: int) -> None:
    """``G4 P<seconds>``: a dwell block at the current position."""
    if "P" not in L:
        raise state.error("G4 needs the dwell time in seconds as P, e.g. G4 P0.5", dwell[1])
    secs = L["P"][0]
    if secs < 0:
        raise state.error(f"negative dwell time P{fmt(secs)}", L["P"][1])
    _emit(state, Block(Source(*state.where(state.line_no), first_col + 1), Motion.DWELL,
                       state.pos, state.pos, state.modal(), dwell=secs, mcodes=mcodes))


#: ``Program.meta`` key: the program switched to G7 somewhere.
LATHE_DIAMETER_MODE_USED = "lathe_diameter_mode_used"


def _lathe_diameter(state: GCodeState, gc: dict, L: dict) -> dict:
    """G7/G8, and the X word of a line in diameter mode halved.

    As LinuxCNC's ``read_x`` and ``convert_lathe_diameter_mode`` do: in G7
    every X word (moves, G10, G92 and G52 values, absolute or incremental) is
    a diameter and is halved; a G7 or G8 on the line applies to the line's own
    X. Arc words (I, K, R) are never scaled: they stay radii.
    """
    mode = gc.get("lathe_diameter")
    if mode is not None:
        state.diameter_mode = mode[0] == 70
        if state.diameter_mode:
            # exports hold radii: they say G8 (gcode.write_gcode)
            state.meta[LATHE_DIAMETER_MODE_USED] = True
    if state.diameter_mode and "X" in L:
        value, col = L["X"]
        L = dict(L)
        L["X"] = (value / 2.0, col)
    return L


def _set_units(state: GCodeState, units: tuple[int, int]) -> None:
    set_units(state, "inch" if units[0] == 200 else "mm")
    state.modal_changed()


def _set_modes(state: GCodeState, gc: dict, L: dict) -> None:
    """Plane, compensation, tool length, distance and Fagor modes."""
    plane = gc.get("plane")
    if plane is not None:
        new_plane = _PLANES[plane[0]]
        if new_plane != state.plane and state.side != 0:
            # LinuxCNC's convert_set_plane, which runs before G40 in a block
            raise state.error(f"cannot change planes ({state.plane} to {new_plane}) with "
                              "cutter radius compensation on: program G40 on a line before",
                              plane[1])
        state.plane = new_plane
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
    retract = gc.get("retract")
    if retract is not None:
        set_retract_mode(state, retract)
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
    check_unrotated_plane(state, "cutter radius compensation", col)
    side = 1 if code in (410, 411) else -1
    if code in (411, 421):
        if "D" not in L:
            raise state.error(f"{gname(code)} needs the tool diameter as D, e.g. "
                              f"{gname(code)} D6", col)
        d = L["D"][0]
        if out_of_range(d):
            raise state.error(f"D{fmt(d)} is out of range: a diameter must lie within "
                              f"+-{MAX_PROGRAM_COORDINATE:g}", L["D"][1])
        state.side = -side if d < 0 else side
        state.radius = abs(d) / 2.0
        state.tool = None
        state.orientation = 0
        if "L" in L:
            # G41.1/G42.1 D<d> L<q>: a lathe tool of orientation q (G18 only)
            q, qcol = L["L"]
            if not (_whole(q) and 0 <= q <= 9):
                raise state.error(f"{gname(code)} L{fmt(q)}: the tool orientation must be "
                                  "0 to 9", qcol)
            _check_lathe_plane(state, code, int(round(q)), qcol)
            state.orientation = int(round(q))
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
        if tool is None:
            # LinuxCNC starts with tool 0 ("no tool", diameter 0) in the spindle
            tool = NO_TOOL
            file, line = state.where(state.line_no)
            state.meta.setdefault(NOTES, []).append(
                f"{file}:{line}:{col + 1}: {gname(code)} with no tool loaded and no D word: "
                "LinuxCNC compensates with tool 0, of diameter 0 (no offset); load the tool "
                "(T M6) or give D")
    state.tool = tool
    state.side = side
    orientations = getattr(state.tool_table, "orientation", {})
    state.orientation = orientations.get(tool, 0) if tool not in (None, NO_TOOL) else 0
    _check_lathe_plane(state, code, state.orientation, col)
    diameter = None
    if tool == NO_TOOL:
        # T0 is "no tool" in LinuxCNC: compensating with it offsets by 0
        # (its mill-zchanges test runs G41 D0 with no T0 in the table).
        diameter = 0.0
    elif tool is not None and state.tool_table is not None:
        diameter = state.tool_table.get(tool)
    if diameter is not None and tool != NO_TOOL:
        diameter *= length_factor(state.table_units or output_units(state), output_units(state))
    if diameter is None:
        state.radius = None
    else:
        state.radius = abs(diameter) / 2.0
        if diameter < 0:
            state.side = -side


def _check_lathe_plane(state: GCodeState, code: int, orientation: int, col: int) -> None:
    """A lathe tool (orientation 1..8) compensates in ``G18`` only (LinuxCNC)."""
    if orientation not in (0, 9) and state.plane != "ZX":
        raise state.error(f"{gname(code)} with a lathe tool (orientation {orientation}), but "
                          "the plane is not G18", col)


def _emit(state: GCodeState, block: Block) -> None:
    values = list(block.start) + list(block.end) + list(block.center or ())
    if block.feed is not None:
        values.append(block.feed)
    if not all(abs(v) <= MAX_PROGRAM_COORDINATE for v in values):   # NaN compares False
        if not all(math.isfinite(v) for v in values):
            raise state.error("coordinates or feed overflow (not finite numbers): check the "
                              "values on this line", block.source.col - 1)
        # incremental moves add up, and an R arc's centre is computed: check what they make
        raise state.error(f"the move's end point, centre or feed is beyond "
                          f"+-{MAX_PROGRAM_COORDINATE:g} program units: check the values on "
                          "this line", block.source.col - 1)
    tool_at = state.cycle.tool_at
    if tool_at is not None:
        # after a permuted G74/G84 the move starts where the tool is (cycles.py)
        if block.motion is Motion.DWELL:
            block = replace(block, start=tool_at, end=tool_at)
        else:
            block = replace(block, start=tool_at)
            state.cycle.tool_at = None
    state.blocks.append(with_words(state, block))


def _move(state: GCodeState, motion: int, L: dict, mcodes: tuple, first_col: int,
          gcol: int, machine: bool = False) -> None:
    """The move of ``motion`` (tenths) to the axis words' end point (absolute
    in work coordinates, under ``G53`` in machine coordinates, or under
    ``G91`` incremental); ``gcol`` locates errors of the move. Blocks hold
    machine coordinates."""
    cur = state.pos
    end_t = _end_point(state, L, machine)
    src = Source(*state.where(state.line_no), first_col + 1)
    surface = surface_marker(state.lines[state.line_no], "gcode", src.file, src.line)
    if motion == 0:
        block = Block(src, Motion.RAPID, cur, end_t, state.modal(), mcodes=mcodes)
    elif motion == SYNCHRONISED:
        block = Block(src, Motion.LINE, cur, end_t, state.modal(),
                      feed=_synchronised_feed(state, L, cur, end_t, gcol), mcodes=mcodes,
                      per_revolution=L["K"][0])
    elif motion == 10 or is_modal_arc_without_plane_motion(state, L, cur, end_t):
        feed = _feed(state, L, math.dist(cur, end_t), gcol, cur, end_t)
        block = Block(src, Motion.LINE, cur, end_t, state.modal(), feed=feed, mcodes=mcodes)
    else:
        check_unrotated_plane(state, f"{gname(motion)} (an arc)", gcol)
        center, turns, length = arc_geometry(state, motion, L, cur, end_t, gcol)
        feed = _feed(state, L, length, gcol, cur, end_t, center)
        block = Block(src, Motion.ARC_CCW if motion == 30 else Motion.ARC_CW, cur, end_t,
                      state.modal(), center=center, turns=turns, feed=feed, mcodes=mcodes)
    if surface is not None:
        block = replace(block, surface=surface)
    extra = extra_end(state, L, machine)
    if extra is not None:
        state.extra = list(extra)
    if machine:
        block = replace(block, frame=frame_of(state, machine=True))
    _emit(state, block)
    state.moved = True
    state.pos = end_t


def _end_point(state: GCodeState, L: dict, machine: bool) -> tuple[float, float, float]:
    """Machine coordinates of the axis words' end point: absolute in work
    coordinates, under ``G53`` in machine coordinates, under ``G91``
    incremental along the (possibly rotated) work axes."""
    cur = state.pos
    if not machine and rotation(state) != 0.0:
        work = list(to_work(state, cur))
        for k, a in enumerate(_AXES):
            if a in L:
                work[k] = work[k] + L[a][0] if state.incremental else L[a][0]
        return to_machine(state, work)
    end = list(cur)
    offset = (0.0, 0.0, 0.0) if machine else work_offset(state)
    for k, a in enumerate(_AXES):
        if a in L:
            v = L[a][0]
            end[k] = cur[k] + v if state.incremental else v + offset[k]
    return (end[0], end[1], end[2])


def _set_coordinates(state: GCodeState, gc: dict, L: dict, mcodes: tuple,
                     first_col: int) -> None:
    """``G54``-``G59.3``, then ``G10``/``G28``/``G30``/``G52``/``G92``*, in
    RS274NGC order."""
    coord = gc.get("coord")
    if coord is not None:
        select_origin(state, coord[0], coord[1])
    setting = gc.get("axis_setting")
    if setting is None:
        return
    code, col = setting
    if code == 100:
        if is_tool_setup(L):
            set_tool_data(state, L, col)
        else:
            set_origin(state, L, col)
    elif code in (280, 300):
        end_series(state)
        src = Source(*state.where(state.line_no), first_col + 1)
        go_home(state, code, L, col, _end_point(state, L, False), src, mcodes, _emit)
    elif code in (281, 301):
        save_home(state, code, col)
    else:
        set_axis_offset(state, code, L, col)


def _check_machine_coords(state: GCodeState, gc: dict, motion: int | None) -> None:
    """``G53`` moves in machine coordinates for its line: with ``G0``/``G1``,
    absolute, compensation off (as LinuxCNC requires)."""
    col = gc["machine_coords"][1]
    if motion not in (0, 10):
        raise state.error("G53 needs G0 or G1 (a straight move in machine coordinates)", col)
    if state.incremental:
        raise state.error("G53 is absolute: it cannot be used under G91", col)
    if state.side != 0:
        raise state.error("G53 cannot be used with cutter radius compensation on", col)


#: ``G33``, spindle-synchronised motion, in tenths.
SYNCHRONISED = 330


def _synchronised_feed(state: GCodeState, L: dict, start, end, gcol: int) -> float:
    """``G33 ... K``: a straight move (compensated like ``G1``) at K program
    units per spindle revolution along the path, so ``K * S / 60`` units per
    second (LinuxCNC's ``START_SPEED_FEED_SYNCH``; threading.ngc's 45-degree
    exit scales K by sqrt 2 so that Z keeps the pitch)."""
    if "K" not in L:
        raise state.error("K word missing with G33: K is the distance per spindle "
                          "revolution", gcol)
    if "F" in L:
        raise state.error("F word used with G33: the feed is K per spindle revolution",
                          L["F"][1])
    if state.spindle == "stopped" or not state.spindle_speed > 0:
        raise state.error("Spindle not turning in G33: start it with S and M3 (or M4) first",
                          gcol)
    if not L["K"][0] > 0:
        raise state.error("G33 needs K > 0 (units per revolution)", L["K"][1])
    return per_revolution(state, L["K"][0], start, end, gcol)


def _feed(state: GCodeState, L: dict, length: float, col: int, start, end,
          center=None) -> float:
    """Feed of a move of ``length`` (program units) from ``start`` to ``end``
    (machine points; an arc about ``center``) in units per second: ``F/60``
    under ``G94``; under ``G93`` the move takes ``60/F`` seconds; under
    ``G95`` F per spindle revolution (spindle.py)."""
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
    if state.feed_mode == "per_revolution":
        return per_revolution(state, state.feed, start, end, col, center)
    return state.feed / 60.0
