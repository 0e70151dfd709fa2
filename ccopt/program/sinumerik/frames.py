"""The programmable frame of a SINUMERIK program: ``TRANS`` and ``ATRANS``
(Programming Manual Fundamentals, "Coordinate transformations (frames)").
"""
from __future__ import annotations

from dataclasses import replace

from ccopt.program.expr import ExprError
from ccopt.program.gcode.units import input_factor
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.words import BlockWords


def translate(run: SinumerikRun, bw: BlockWords) -> None:
    """``TRANS X Y Z``: the programmable frame is this translation (axes not
    written: 0; ``TRANS`` alone: none); ``ATRANS``: added to the one in force.
    Kept as the core's axis offset (``machine = work + offset + origin``)."""
    state = run.state
    name, col = bw.frame
    if not replace(bw, frame=None, axes={}, ignored=[]).empty:
        raise ExprError(f"{name} takes its block with X Y Z only", col)
    if state.side != 0:
        raise ExprError(f"cannot change frames ({name}) with tool radius compensation on: "
                        "program G40 first", col)
    offset = [0.0, 0.0, 0.0] if name == "TRANS" else list(state.axis_offset)
    for a, (value, mode, acol) in bw.axes.items():
        k = "XYZ".find(a)
        if k < 0 or mode is not None:
            raise ExprError(f"{name} translates X Y Z by values (not {a}, AC or IC)", acol)
        offset[k] += value * input_factor(state)
    state.axis_offset = (offset[0], offset[1], offset[2])
