"""Reader for Delta Tau PMAC / Turbo PMAC motion programs.

``read_pmac(text)`` turns the text of a PMAC download file (or a bare motion
program body) into an immutable :class:`~ccopt.program.model.Program` of
dialect ``"pmac"``: one block per executed ``RAPID``/``LINEAR``/``CIRCLE1``/
``CIRCLE2`` move and per ``DWELL``/``DELAY``. ``F`` is units per second
(*Isx90* = 1000 ms), times are seconds, every problem is a located
:class:`~ccopt.errors.ProgramError`.

The dialect as ccopt reads it — buffers, statements, moves, circles, planes,
feed and time, compensation ``CC0``/``CC1``/``CC2``/``CCR``, variables, what
is unsupported, the decisions taken and the manual pages behind them — is
described in ``docs/pmac.md``.

Modules: :mod:`.lexer` (lines, command words, constants), :mod:`.buffers`
(``OPEN PROG``/``CLOSE``, on-line commands), :mod:`.variables` (P/Q/I/M
variables, ``{data}`` and expressions), :mod:`.moves` (the move of a line,
circle centres), :mod:`.blocks` (the block of a move, made quickly),
:mod:`.statements` (modal state and statement execution), :mod:`.straight`
(runs of straight move lines, the bulk of a long program),
:mod:`.reader` (:func:`read_pmac`).
"""
from __future__ import annotations

from ccopt.program.pmac.reader import read_pmac
from ccopt.program.pmac.variables import MAX_VARIABLE  # noqa: F401 - was pmac.MAX_VARIABLE

__all__ = ["read_pmac"]
