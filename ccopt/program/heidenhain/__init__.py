"""Reader for HEIDENHAIN Klartext (conversational) programs, ``.h`` files.

``read_heidenhain(text)`` turns a TNC program into an immutable
:class:`~ccopt.program.model.Program` of dialect ``"heidenhain"``: one block
per executed move or dwell, in absolute machine coordinates, feeds in units
per second. What is read and how (path functions, polar coordinates,
rounding and chamfers, approach and departure, labels and repeats, Q
parameters, cycles) is listed in ``docs/heidenhain.md``; the compensation
rules of the ``heidenhain`` style are in docs/compensation.md.

Modules: :mod:`.lexer` (NC blocks and words), :mod:`.values` (numbers, Q
parameters, FN), :mod:`.args` (a block's words), :mod:`.contour` (plane
geometry: arcs, RND, CHF, APPR/DEP), :mod:`.machine` (modal state, blocks),
:mod:`.moves` (path functions), :mod:`.cycles` (CYCL DEF and calls),
:mod:`.reader` (:func:`read_heidenhain`).
"""
from __future__ import annotations

from ccopt.program.heidenhain.machine import LEADS
from ccopt.program.heidenhain.reader import read_heidenhain

__all__ = ["LEADS", "read_heidenhain"]
