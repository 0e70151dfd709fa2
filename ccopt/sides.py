"""The compensation side by name: the one table of ``left``/``right``.

A side is ``+1`` left of the direction of travel (G41, PMAC CC1) and ``-1``
right (G42, CC2), as :mod:`ccopt.program.model` states; a command line, a
case, a sweep spec and the Python API name it ``"left"`` or ``"right"``.
Every module that takes a side by name reads it here (:func:`side_sign`).
"""
from __future__ import annotations

#: side name -> sign (+1 left, -1 right of the direction of travel)
SIDES: dict[str, int] = {"left": 1, "right": -1}

#: the names, in the order a ``--help`` or a message lists them
SIDE_NAMES: tuple[str, ...] = tuple(SIDES)


def side_sign(side: str | int | None) -> int | None:
    """``side`` as a sign: ``"left"``/``+1`` -> 1, ``"right"``/``-1`` -> -1,
    ``None`` (no override) -> ``None``; a ValueError for anything else."""
    if side is None:
        return None
    if isinstance(side, str) and side in SIDES:
        return SIDES[side]
    if not isinstance(side, (str, bool)) and side in (1, -1):
        return int(side)
    raise ValueError(f"side must be left or right, not {side!r}")
