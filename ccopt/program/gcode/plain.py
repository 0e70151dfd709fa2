"""Runs of plain move lines, the most common lines of a long program.

A plain line is ``[N<n>] [G0|G1] [X<n>] [Y<n>] [Z<n>] [F<n>]`` (those words
in that order, upper case, each a letter directly followed by a literal
number, at least one axis word, blanks only between words;
:data:`PLAIN_LINE`), as CAM programs and ccopt's exports write most lines;
a plain arc line is ``[N<n>] [G2|G3] [X<n>] [Y<n>] [Z<n>] [I<n>] [J<n>]
[F<n>]`` with ``I`` or ``J`` (:data:`ARC_LINE`), taken in the XY plane
(G17) with incremental centres (G91.1, the default), its centre, turns and
checks those of :func:`~ccopt.program.gcode.arcs.arc_geometry`, the line
loop's own function (:func:`~ccopt.program.gcode.arcs.incremental_centres`,
its operations on the run's arcs together).
Consecutive ones change only the motion mode, the feed and the position:
:func:`run_plain` executes them in one loop, with the modal state read
once, and makes their blocks together at the end of the run
(:func:`_make_blocks`).

The line-by-line path (:func:`~ccopt.program.gcode.reader._run_lines`, with
:func:`~ccopt.program.gcode.execute.execute_words`) is the reference: a run
starts only in a state where such a line does nothing but move (no lathe
diameter mode, no unit conversion, feed per minute, no rotated system, no
extra axis moved, no words waiting for a block, no permuted cycle end), and
a line it is not sure of (any other spelling, a value past the bound, a feed
move without a positive feed, the runaway guards' last lines) ends the run
with nothing done for it: that path then runs it, and reports any error.
Lengths are program units, feeds units per minute (``state.feed``) or per
second (blocks).
"""
from __future__ import annotations

import re
from collections import deque
from itertools import repeat

import numpy as np

from ccopt.program.blocks import DEFAULT_SETTERS, FIELD_SETTERS, SOURCE_SETTERS
from ccopt.program.gcode.arcs import incremental_centres
from ccopt.program.gcode.coordinates import rotation, work_offset
from ccopt.program.gcode.machine_words import frame_of
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.units import input_factor
from ccopt.program.model import MAX_PROGRAM_COORDINATE, Block, Motion, Source

# A literal number as words._NUMBER reads it; the pattern's blanks and
# letters after it keep that pattern's look-ahead (no point, no digit after
# blanks) true wherever the whole line matches.
_NUM = r"([+-]?(?:\d+\.?\d*|\.\d+))"
#: A plain line: groups G digit (0 or 1), X, Y, Z and F numbers (None: absent).
PLAIN_LINE = re.compile(rf"(?:N\d+[ \t]*)?(?:G0?([01])[ \t]*)?(?:X{_NUM}[ \t]*)?"
                        rf"(?:Y{_NUM}[ \t]*)?(?:Z{_NUM}[ \t]*)?(?:F{_NUM}[ \t]*)?")
#: ``G1 X.. Y.. Z..``, an export's every feed move (a plain line too), tried
#: first: a lighter pattern, with nothing to decide but the numbers.
FEED_XYZ_LINE = re.compile(rf"G1 X{_NUM} Y{_NUM} Z{_NUM}")
#: A plain arc line: groups G digit (0 to 3), X, Y, Z, I, J and F numbers
#: (None: absent); taken as an arc only with I or J, in an arc mode.
ARC_LINE = re.compile(rf"(?:N\d+[ \t]*)?(?:G0?([0-3])[ \t]*)?(?:X{_NUM}[ \t]*)?"
                      rf"(?:Y{_NUM}[ \t]*)?(?:Z{_NUM}[ \t]*)?(?:I{_NUM}[ \t]*)?"
                      rf"(?:J{_NUM}[ \t]*)?(?:F{_NUM}[ \t]*)?")

_new = object.__new__
#: (setter, default) of the fields a block of a plain move leaves at their
#: defaults (frame and axes are set, the reference's with_words sets them).
_DEFAULTS = tuple((setter, default) for setter, default in DEFAULT_SETTERS
                  if setter not in (FIELD_SETTERS["frame"], FIELD_SETTERS["axes"]))


def _each(setter, objects: list, values) -> None:
    """``setter(obj, value)`` for each pair, the loop in C (a map drained by a deque)."""
    deque(map(setter, objects, values), 0)


def _ready(state: GCodeState) -> bool:
    """A plain line would only move (and set the feed and motion mode): the
    state's modes that change what it does are all at their plain values."""
    return (state.siemens is None and not state.diameter_mode and state.extra is None
            and state.cycle.tool_at is None and not state.pending_words
            and state.feed_mode == "per_minute" and input_factor(state) == 1.0
            and rotation(state) == 0.0)


def _budget(state: GCodeState) -> int:
    """Lines that may still execute before a runaway guard raises (the
    guard's line itself is left to the line-by-line path)."""
    n = state.max_executed_lines - state.executed
    if state.in_loop:
        n = min(n, state.max_loop_lines - state.loop_lines)
    return n


def run_plain(state: GCodeState, pc: int) -> int:
    """Execute the plain lines (and empty lines) from ``pc`` (0-based) on, up
    to the first that is not one, or that this loop is not sure to execute
    as the line-by-line path does; the index of that line (``pc``: none)."""
    first = state.lines[pc]
    # arcs as the line loop makes them in G17 with incremental centres
    arc_match = ARC_LINE.fullmatch if state.plane == "XY" and state.arc_incremental else None
    if (PLAIN_LINE.fullmatch(first) is None
            and (arc_match is None or arc_match(first) is None)) or not _ready(state):
        return pc
    bound = MAX_PROGRAM_COORDINATE
    if not all(-bound <= v <= bound for v in state.pos):
        return pc                   # the first block's start: the reference's error
    stop = min(state.region_end(pc), pc + _budget(state))
    run, mode, feed = _moves(state, pc, stop, arc_match)
    if not run[0]:
        return pc                   # empty lines alone: the reference counts them
    at = run[0]
    _finish(state, pc, at[-1] + 1, mode, feed)
    _make_blocks(state, *run)
    return at[-1] + 1


def _moves(state: GCodeState, pc: int, stop: int, arc_match):
    """``((line indexes, motions, feeds (units/s), ends, arc centres), mode, feed)``
    of the plain lines from ``pc`` to ``stop`` or to one left to the line loop.

    The arc lines' centres are worked out together once the lines are read
    (:func:`_arc_centres`); the run then ends before the first arc the line
    loop would refuse, with the modes in force before it."""
    run, mode, feed, arcs = _scan(state, pc, stop, arc_match)
    if arcs:
        refused = _arc_centres(state, run[4], arcs)
        if refused is not None:
            kept, mode, feed = refused
            run = tuple(column[:kept] for column in run)
    return run, mode, feed


def _scan(state: GCodeState, pc: int, stop: int, arc_match):
    """:func:`_moves`' lines with their arc centres not yet known (None) and
    ``arcs``: each arc line's ``((its move's index, mode and feed before
    it, start z), (start x, y, end x, y, centre offsets I, J))``."""
    lines, bound, inc = state.lines, MAX_PROGRAM_COORDINATE, state.incremental
    match, xyz_match = PLAIN_LINE.fullmatch, FEED_XYZ_LINE.fullmatch
    off_x, off_y, off_z = work_offset(state)
    mode, feed = state.motion_mode, state.feed
    end_x, end_y, end_z = state.pos
    at, motions, feeds, ends, arcs = [], [], [], [], []
    line_motion, rapid_motion = Motion.LINE, Motion.RAPID
    for k in range(pc, stop):
        text = lines[k]
        m = xyz_match(text)
        i = j = None
        if m is not None:
            x, y, z = m.groups()
            line_mode, line_feed = 10, feed
        elif not text:
            continue                # an empty line does nothing
        else:
            m = match(text)
            if m is not None:
                g, x, y, z, f = m.groups()
            elif arc_match is not None and (m := arc_match(text)) is not None:
                g, x, y, z, i, j, f = m.groups()
            else:
                break
            if x is None and y is None and z is None:
                break               # no move: a mode or a feed alone (or a full circle)
            line_mode = mode if g is None else 10 * int(g)
            line_feed = feed
            if f is not None:
                value = float(f)
                if not 0.0 <= value <= bound:   # a negative F, past the bound (or inf)
                    break
                line_feed = value * 1.0     # times feed_factor, which _ready made 1
        if i is not None or j is not None:
            if line_mode not in (20, 30):
                break               # centre words on a straight move: the line loop's
            motion = Motion.ARC_CCW if line_mode == 30 else Motion.ARC_CW
        elif line_mode == 10:
            motion = line_motion
        elif line_mode == 0:
            motion = rapid_motion
        else:
            break                   # an arc without centre words, a cycle or G80 in force
        if motion is not rapid_motion and (line_feed is None
                                           or not 0.0 < line_feed / 60.0 <= bound):
            break
        new_x, new_y, new_z = end_x, end_y, end_z
        # written out per axis, as this runs once per line: a loop is slower
        if x is not None:
            value = float(x)
            new_x = end_x + value if inc else value + off_x
            if not (-bound <= value <= bound and -bound <= new_x <= bound):
                break
        if y is not None:
            value = float(y)
            new_y = end_y + value if inc else value + off_y
            if not (-bound <= value <= bound and -bound <= new_y <= bound):
                break
        if z is not None:
            value = float(z)
            new_z = end_z + value if inc else value + off_z
            if not (-bound <= value <= bound and -bound <= new_z <= bound):
                break
        if motion is not line_motion and motion is not rapid_motion:
            du = 0.0 if i is None else float(i)
            dv = 0.0 if j is None else float(j)
            if not (-bound <= du <= bound and -bound <= dv <= bound):
                break
            arcs.append(((len(at), mode, feed, end_z), (end_x, end_y, new_x, new_y, du, dv)))
        mode, feed = line_mode, line_feed
        end_x, end_y, end_z = new_x, new_y, new_z
        at.append(k)
        motions.append(motion)
        feeds.append(None if motion is rapid_motion else feed / 60.0)
        ends.append((new_x, new_y, new_z))
    return (at, motions, feeds, ends, [None] * len(at)), mode, feed, arcs


def _arc_centres(state: GCodeState, centres: list, arcs: list):
    """Put in ``centres`` each arc line's centre ``(x, y, z)`` (``arcs`` as
    :func:`_scan` gives them), as :func:`~ccopt.program.gcode.arcs.arc_geometry`
    gives it; ``(moves kept, mode, feed)`` before the first arc the line loop
    would refuse (its radii disagree, the centre is on an end or past the
    bound: that loop then reads it and says why), None when none is."""
    places, numbers = zip(*arcs)
    rows = np.array(numbers)
    centre, refused = incremental_centres(state, rows[:, :2], rows[:, 2:4], rows[:, 4:])
    bound = MAX_PROGRAM_COORDINATE
    # NaN compares False; the centre's z is the start's, within the bound
    refused |= ~((-bound <= centre) & (centre <= bound)).all(axis=1)
    take = int(np.flatnonzero(refused)[0]) if refused.any() else len(arcs)
    at, _, _, z = zip(*places[:take]) if take else ((),) * 4
    cu, cv = centre[:take, 0].tolist(), centre[:take, 1].tolist()
    deque(map(centres.__setitem__, at, zip(cu, cv, z)), 0)
    return None if take == len(arcs) else places[take][:3]


def _finish(state: GCodeState, pc: int, end: int, mode: int, feed: float | None) -> None:
    """The state after lines ``[pc, end)`` ran as the reference leaves it:
    the guards' counts, the line being executed, the modes a move sets."""
    count = end - pc
    state.executed += count
    if state.in_loop:
        state.loop_lines += count
    state.line_no = end - 1
    state.motion_mode, state.feed = mode, feed
    state.moved = True
    state.cycle.level = None        # a move that is not a cycle ends a series of cycles


def _make_blocks(state: GCodeState, at: list[int], motions: list[Motion], feeds: list,
                 ends: list, centres: list) -> None:
    """Append the blocks of a run of plain moves: the moves on lines ``at``
    (0-based, in the region of ``at[0]``) with ``motions``, ``feeds`` (units
    per second), end points ``ends`` and arc ``centres`` (None for a straight
    move), from the state's position, under the
    modal state and frame in force. Each is the ``Block`` the reference makes
    (``Block(...)``, then :func:`~.machine_words.with_words`'s copy with the
    frame): every field set, field by field for the whole run; each start is
    the previous end's tuple, as the reference's ``state.pos``."""
    count = len(at)
    file, line1 = state.where(at[0])
    shift = line1 - at[0]
    sources = list(map(_new, repeat(Source, count)))
    set_file, set_line, set_col = SOURCE_SETTERS
    _each(set_file, sources, repeat(file))
    _each(set_line, sources, [k + shift for k in at])
    _each(set_col, sources, repeat(1))     # the first word starts the line
    blocks = list(map(_new, repeat(Block, count)))
    starts = [state.pos]
    starts += ends[:-1]
    for setter, default in _DEFAULTS:
        _each(setter, blocks, repeat(default))
    for name, values in (("source", sources), ("motion", motions), ("start", starts),
                         ("end", ends), ("modal", repeat(state.modal())),
                         ("center", centres), ("feed", feeds),
                         ("move_time", repeat(None)), ("mcodes", repeat(())),
                         ("surface", repeat(None)), ("frame", repeat(frame_of(state))),
                         ("axes", repeat(None))):
        _each(FIELD_SETTERS[name], blocks, values)
    state.blocks += blocks
    state.pos = ends[-1]
