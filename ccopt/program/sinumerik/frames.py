"""The programmable frame of a SINUMERIK program: ``TRANS``, ``ATRANS``,
``ROT``, ``AROT`` (Programming Manual Fundamentals 6FC5398-2EP40, 2.12
"Coordinate transformations (frames)": 2.12.4 "Zero offset (TRANS, ATRANS)",
2.12.5 "Programmable rotation (ROT, AROT, RPL)").

The frame maps a programmed point ``p`` to ``shift + R(turn) p`` in the
settable frame (``G54``..), ``turn`` in degrees counter-clockwise about Z
(``G17``: the positive ``RPL`` of the manual's figure). ``TRANS`` and ``ROT``
are absolute: each replaces the whole frame (``TRANS X10`` clears a rotation,
``ROT RPL=30`` a translation, ``TRANS``/``ROT`` alone clear both); ``ATRANS``
shifts along the frame's own (rotated) axes, ``AROT`` turns it further about
its own origin. Each stands in a block of its own, with compensation off.

The core keeps the frame as its axis offset and the active system's XY
rotation (``machine = R(turn) (work + offset) + origin``, see
:mod:`ccopt.program.gcode.coordinates`), with ``offset = R(-turn) shift``;
so rotations are read in ``G17`` only (the core's rotated systems are XY),
and a change of settable frame while a rotation is in force is refused (the
core would take the new system's own rotation).
"""
from __future__ import annotations

from dataclasses import replace

from ccopt.program.expr import ExprError
from ccopt.program.gcode.coordinates import ORIGIN_CODES, rotate_xy, rotation_parameter
from ccopt.program.gcode.units import input_factor
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.words import BlockWords

#: The frame instructions ccopt reads.
FRAME_WORDS = ("TRANS", "ATRANS", "ROT", "AROT")


def frame_block(run: SinumerikRun, bw: BlockWords) -> None:
    """Execute a block of ``TRANS``, ``ATRANS``, ``ROT`` or ``AROT``."""
    state = run.state
    name, col = bw.frame
    own = {k: v for k, v in bw.values.items() if k != "RPL"}
    if not replace(bw, frame=None, axes={}, values=own, ignored=[]).empty:
        raise ExprError(f"{name} takes its block with X Y Z{' or RPL' if 'ROT' in name else ''}"
                        " only", col)
    if state.side != 0:
        raise ExprError(f"cannot change frames ({name}) with tool radius compensation on: "
                        "program G40 first", col)
    shift, turn = run.frame_shift, run.frame_turn
    if name in ("TRANS", "ROT"):
        shift, turn = (0.0, 0.0, 0.0), 0.0
    if name in ("TRANS", "ATRANS"):
        if "RPL" in bw.values:
            raise ExprError(f"RPL belongs to ROT and AROT, not {name}", bw.values["RPL"][2])
        d = [0.0, 0.0, 0.0]
        for a, (value, mode, acol) in bw.axes.items():
            k = "XYZ".find(a)
            if k < 0 or mode is not None:
                raise ExprError(f"{name} translates X Y Z by values (not {a}, AC or IC)", acol)
            d[k] = value * input_factor(state)
        dx, dy = rotate_xy(d[0], d[1], turn)
        shift = (shift[0] + dx, shift[1] + dy, shift[2] + d[2])
    else:
        turn += _angle(run, bw, name, col)
    run.frame_shift, run.frame_turn = shift, turn
    _apply(run, col)


def _angle(run: SinumerikRun, bw: BlockWords, name: str, col: int) -> float:
    """The turn of a ``ROT``/``AROT`` block, degrees: ``RPL=`` or ``Z``; a
    turn about X or Y (a frame out of the plane) is refused."""
    for a, (value, mode, acol) in bw.axes.items():
        if a != "Z" or mode is not None:
            raise ExprError(f"{name} {a}..: ccopt turns frames about Z only (G17: {name} "
                            "RPL=<degrees> or Z<degrees>), not out of the plane", acol)
    if "RPL" in bw.values and "Z" in bw.axes:
        raise ExprError(f"{name}: give RPL or Z, not both", bw.values["RPL"][2])
    if "RPL" in bw.values:
        value, mode, rcol = bw.values["RPL"]
        if mode is not None:
            raise ExprError("RPL takes an angle in degrees (RPL=30)", rcol)
        if run.state.plane != "XY":
            raise ExprError(f"{name} RPL in {run.state.plane}: ccopt turns frames in G17 only",
                            rcol)
        return value
    return bw.axes["Z"][0] if "Z" in bw.axes else 0.0


def _apply(run: SinumerikRun, col: int) -> None:
    """The frame as the core's axis offset and the active system's rotation."""
    state = run.state
    shift, turn = run.frame_shift, run.frame_turn
    if turn != 0.0 and state.plane != "XY":
        raise ExprError(f"a rotated frame in {state.plane}: ccopt turns frames in G17 only", col)
    ox, oy = rotate_xy(shift[0], shift[1], -turn)
    state.axis_offset = (ox, oy, shift[2])
    state.params[rotation_parameter(state.origin_index)] = turn


def check_block(run: SinumerikRun, bw: BlockWords) -> None:
    """An ordinary block: no ``RPL`` outside a frame block, no change of
    settable frame (``G54``..``G57``, ``G500``) while the frame is turned."""
    if "RPL" in bw.values:
        raise ExprError("RPL stands in a ROT or AROT block", bw.values["RPL"][2])
    if run.frame_turn != 0.0:
        for tenths, col in bw.g:
            if tenths in ORIGIN_CODES:
                raise ExprError(f"G{tenths // 10 if tenths != 540 else '54/G500'} while the "
                                f"programmable frame is turned ({run.frame_turn:g} deg): "
                                "ccopt keeps a rotation on one settable frame; clear it "
                                "with ROT first", col)
