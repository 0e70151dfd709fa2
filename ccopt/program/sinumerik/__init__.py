"""SINUMERIK 840D part programs (``.mpf`` main programs, ``.spf`` subprograms).

:func:`read_sinumerik` runs a program as the control's interpreter would and
returns a :class:`~ccopt.program.model.Program` of dialect ``"sinumerik"``:
the ISO G-code core (:mod:`ccopt.program.gcode`) executes the moves, units,
feeds and coordinate systems; this package reads the SINUMERIK language
around it — block numbers, jump labels and ``;`` comments (:mod:`.lexer`),
R parameters, ``DEF`` variables and expressions (:mod:`.values`), program
flow (:mod:`.flow`), the words of a block (:mod:`.words`) and their
execution with the tool radius compensation modes (:mod:`.blocks`), and the
circle forms ``CIP``, ``CT`` and ``AR=`` (:mod:`.arcs`). The dialect and its
decisions: ``docs/sinumerik.md``. Anything it does not read is a
:class:`~ccopt.errors.ProgramError` located at file, line and column.
"""
from __future__ import annotations

from ccopt.errors import ProgramError
from ccopt.program.sinumerik.reader import read_sinumerik

__all__ = ["read_sinumerik", "ProgramError"]
