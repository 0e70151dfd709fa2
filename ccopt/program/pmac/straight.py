"""Runs of straight move lines, the most common lines of a long PMAC program.

A straight move line is ``[LINEAR|RAPID] [X..] [Y..] [Z..]`` with literal
numbers (:data:`~ccopt.program.pmac.lexer.STRAIGHT_LINE_RE`). Consecutive
ones change only the move mode and the position: :func:`run_straight`
executes them in one loop, with the modal state read once, and makes their
blocks together at the end of the run (:func:`_make_blocks`). The
statement-by-statement path (:meth:`~ccopt.program.pmac.statements.Interpreter.statement`)
is the reference: a line this path refuses (an error, a value past the bound,
any other line) ends the run with nothing done for it, and that path runs it.
``run`` is the :class:`~ccopt.program.pmac.statements.Interpreter` whose
state they change. Lengths are program units, feeds units per second, times
seconds.
"""
from __future__ import annotations

import re
from collections import deque
from itertools import repeat

from ccopt.program.blocks import DEFAULT_SETTERS, FIELD_SETTERS, SOURCE_SETTERS
from ccopt.program.model import MAX_PROGRAM_COORDINATE, Block, Motion, Source
from ccopt.program.pmac.lexer import MOVE_MODES

# the same setters as new_block's, and its import-time check of the model
_SET, _DEFAULTS, _SOURCE_SET = FIELD_SETTERS, DEFAULT_SETTERS, SOURCE_SETTERS
_new = object.__new__


def _each(setter, objects: list, values) -> None:
    """``setter(obj, value)`` for each pair, the loop in C (a map drained by a deque)."""
    deque(map(setter, objects, values), 0)


def _make_blocks(run, lines: list[int], cols: list[int], motions: list[Motion],
                 ends: list, start) -> None:
    """Append the blocks of a run of straight moves to ``run.blocks``: the
    moves on ``lines`` (their first axis word at ``cols``) from ``start`` to
    ``ends``, under the modal state in force. Each is the ``Block`` that
    ``Block(source=Source(...), ...)`` makes, every field set, field by field
    for the whole run: the same objects as one block at a time, made faster."""
    count = len(lines)
    sources = list(map(_new, repeat(Source, count)))
    set_file, set_line, set_col = _SOURCE_SET
    _each(set_file, sources, repeat(run.file))
    _each(set_line, sources, lines)
    _each(set_col, sources, cols)
    blocks = list(map(_new, repeat(Block, count)))
    starts = [start]
    starts += ends[:-1]
    if len(set(motions)) == 1:
        feed, move_time = _speed(run, motions[0])
        feeds, times = repeat(feed), repeat(move_time)
    else:
        speeds = [_speed(run, motion) for motion in motions]
        feeds, times = (s[0] for s in speeds), (s[1] for s in speeds)
    markers = run.markers
    surfaces = [markers.get(line) for line in lines] if markers else repeat(None)
    for name, values in (("source", sources), ("motion", motions), ("start", starts),
                         ("end", ends), ("modal", repeat(run.modal())),
                         ("center", repeat(None)), ("feed", feeds), ("move_time", times),
                         ("mcodes", repeat(())), ("surface", surfaces)):
        _each(_SET[name], blocks, values)
    for setter, default in _DEFAULTS:
        _each(setter, blocks, repeat(default))
    run.blocks += blocks


def _speed(run, motion: Motion) -> tuple[float | None, float | None]:
    """``(feed, move_time)`` of a straight move: units/s and s, ``None`` when not given."""
    if motion is Motion.RAPID:
        return None, None
    if run.time_mode:
        return None, run.move_time
    return run.feed, None


def run_straight(run, body: list[tuple[int, str]], first: int,
                 axes_line: re.Pattern, straight_line: re.Pattern) -> int:
    """Execute the straight move lines of ``body`` (``(line number, text)``)
    from index ``first`` on, up to the first line that is not one (neither
    ``axes_line`` nor ``straight_line`` matches it in full) or whose move
    raises an error; the index of that line (``len(body)`` after the last)."""
    axes_match, straight_match = axes_line.fullmatch, straight_line.fullmatch
    bound = MAX_PROGRAM_COORDINATE
    inc = run.incremental
    inc_x, inc_y, inc_z = inc["X"], inc["Y"], inc["Z"]
    # a LINEAR move needs a speed: the feed, or the move time in time mode
    linear_ok = run.time_mode or run.feed is not None
    mode = run.mode
    line_motion, rapid_motion = Motion.LINE, Motion.RAPID
    start = run.pos
    end_x, end_y, end_z = start
    # line numbers, columns, motions and end points of the run's moves
    lines, cols, motions, ends = [], [], [], []
    add_line, add_col, add_motion, add_end = lines.append, cols.append, motions.append, ends.append
    k = first
    for k in range(first, len(body)):
        line, text = body[k]
        if not text:
            continue                    # an empty line (or only a comment) does nothing
        m = axes_match(text)
        if m is not None:
            x, y, z = m.groups()
            line_mode, col = mode, 1
        else:
            m = straight_match(text)
            if m is None:
                break
            line_mode, col, x, y, z = _straight_words(m, mode)
        if line_mode == "LINEAR":
            if not linear_ok:
                break
            motion = line_motion
        elif line_mode == "RAPID":
            motion = rapid_motion
        else:
            break
        # |value| <= bound (which inf is not); written out per axis, as this
        # runs once per line: a loop over the axes is slower
        if x is not None:
            value = float(x)
            if not -bound <= value <= bound:
                break
            new_x = end_x + value if inc_x else value
        elif y is None and z is None:
            break                       # no axis word: a mode alone, or a blank line
        else:
            new_x = end_x
        new_y, new_z = end_y, end_z
        if y is not None:
            value = float(y)
            if not -bound <= value <= bound:
                break
            new_y = end_y + value if inc_y else value
        if z is not None:
            value = float(z)
            if not -bound <= value <= bound:
                break
            new_z = end_z + value if inc_z else value
        if not (-bound <= new_x <= bound and -bound <= new_y <= bound
                and -bound <= new_z <= bound):
            break
        mode = line_mode
        end_x, end_y, end_z = new_x, new_y, new_z
        add_line(line)
        add_col(col)
        add_motion(motion)
        add_end((new_x, new_y, new_z))
    else:
        k = len(body)
    if lines:
        run.mode = mode
        _make_blocks(run, lines, cols, motions, ends, start)
        run.pos = ends[-1]
    return k


def _straight_words(m: re.Match, mode: str) -> tuple[str, int, str | None, str | None,
                                                      str | None]:
    """``(move mode, column of the first axis word, signed X, Y, Z numbers)``
    of a line's match of :data:`~ccopt.program.pmac.lexer.STRAIGHT_LINE_RE`
    (``mode`` when the line writes none, column 0 when it writes no axis)."""
    kw, _, x_sign, x, _, y_sign, y, _, z_sign, z = m.groups()
    first = 2 if x is not None else 5 if y is not None else 8 if z is not None else 0
    # the sign before the digits: float() reads "-0" as -0.0, as negating 0.0 gives
    return (mode if kw is None else MOVE_MODES[kw], m.start(first) + 1 if first else 0,
            None if x is None else x_sign + x, None if y is None else y_sign + y,
            None if z is None else z_sign + z)
