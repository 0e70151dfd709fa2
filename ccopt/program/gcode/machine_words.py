"""The non-motion words a machine needs, recorded where the reader reads them.

ccopt's stages use only the motion, but an exported program must still
change tools, run the spindle and coolant, apply tool length and stop where
the source did. The reader keeps, per line, those words as one text line in
RS274NGC's order of execution (``S``, ``T``, ``M6``, ``M3``-``M5``,
``M7``-``M9``, other M-codes, ``G43 H``/``G49``) and attaches every line read
since the last block to the next block (:attr:`Block.words`); a program stop
(``M0``, ``M1``, ``M60``) runs after its line's motion, so it goes to the
block after. The words after the last block are
``Program.meta[TRAILING_WORDS]`` and the program end as written (``M2``,
``M30`` or the main program's ``M99``) is ``Program.meta[PROGRAM_END]``.

The work coordinate frame of each block (:class:`~ccopt.program.model.Frame`)
is recorded here too, from the state's coordinate systems.
"""
from __future__ import annotations

from ccopt.program.blocks import replace_block
from ccopt.program.gcode.axes import extra_axis_offset, extra_origin
from ccopt.program.gcode.coordinates import origin, rotation
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import fmt, gname
from ccopt.program.model import PROGRAM_END, Block, Frame

#: M-codes that end the program (recorded as :data:`PROGRAM_END`): M99 here
#: is the main program's (a subprogram's returns, fanuc.py).
END_CODES = (2, 30, 99)
#: Program stops: they run after the motion of their line.
STOP_CODES = (0, 1, 60)
#: RS274NGC's execution order of the other M-codes ccopt keeps: tool change,
#: spindle, coolant; any other M-code after them.
_ORDER = {6: 0, 3: 1, 4: 1, 5: 1, 7: 2, 8: 2, 9: 2}


def record_line(state: GCodeState, gc: dict, L: dict, mcodes: tuple) -> None:
    """Record the machine words of one line (before its motion is executed)."""
    parts = []
    if "S" in L:
        parts.append(f"S{fmt(L['S'][0])}")
    if "T" in L:
        parts.append(f"T{fmt(L['T'][0])}")
    keep = sorted((m for m in mcodes if m not in END_CODES + STOP_CODES),
                  key=lambda m: _ORDER.get(m, 3))
    parts += [f"M{m}" for m in keep]
    length = gc.get("length")
    if length is not None:
        # G43 H<tool>; G43.1 with its offsets (its axis words, output units)
        given = [f"{a}{fmt(L[a][0])}" for a in "XYZABCUVW" if a in L] if length[0] == 431 else []
        parts.append(" ".join([gname(length[0]), *given])
                     + (f" H{fmt(L['H'][0])}" if "H" in L else ""))
    if parts:
        state.pending_words.append(" ".join(parts))
    for m in mcodes:
        if m in END_CODES:
            state.meta[PROGRAM_END] = f"M{m}"


def record_after_motion(state: GCodeState, mcodes: tuple) -> None:
    """Program stops of the line, which run after its motion."""
    stops = [f"M{m}" for m in mcodes if m in STOP_CODES]
    if stops:
        state.pending_words.append(" ".join(stops))


def frame_of(state: GCodeState, machine: bool = False) -> Frame:
    """The frame in force (one shared object until it changes)."""
    key = (state.origin_index, origin(state), state.axis_offset, machine, rotation(state))
    if state.extra is not None:
        key += (extra_origin(state), extra_axis_offset(state))
    if state.frame_key != key:
        state.frame_key = key
        state.frame = Frame(*key)
    return state.frame


def with_words(state: GCodeState, block: Block) -> Block:
    """``block`` with the words read since the last block, and its frame (a
    block that already has a frame, a ``G53`` move's, keeps it)."""
    frame = block.frame if block.frame is not None else frame_of(state)
    axes = tuple(state.extra) if state.extra is not None else None
    if state.pending_words:
        words = tuple(state.pending_words)
        state.pending_words.clear()
        return replace_block(block, words=words, frame=frame, axes=axes)
    return replace_block(block, frame=frame, axes=axes)
