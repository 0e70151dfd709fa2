"""The axes beyond X Y Z: ``A B C`` (rotary, degrees) and ``U V W`` (linear,
program units), read and carried as LinuxCNC's interpreter carries them.

They take no part in the path ccopt compensates, plans or verifies (the
compensation plane is two of X Y Z): a block keeps their end positions in
machine coordinates (:attr:`~ccopt.program.model.Block.axes`, ``None`` while
the program has moved none of them) so that an export writes them back.
Per axis ``k`` (0 .. 5 for A .. W), as for X Y Z without rotation:

    machine = programmed + origin (``#[5204 + 20 n + k]``)
              + axis offset (``#[5214 + k]`` while ``#5210`` = 1)

``G90``/``G91`` apply, ``G53`` moves in machine coordinates, ``G10 L2/L20``
set the origins, ``G92``/``G52``/``G92.x`` the offsets, ``G28``/``G30`` go
to ``#[5164 + k]``/``#[5184 + k]``. U V W are lengths (``G20``/``G21``
convert them), A B C angles (never converted).
"""
from __future__ import annotations

from ccopt.program.gcode.state import GCodeState
from ccopt.program.model import AXES_USED

EXTRA = "ABCUVW"
_ZERO = (0.0,) * 6
_OFFSET_APPLIED = 5210
_OFFSET_BASE = 5214
_HOME_BASE = {280: 5164, 281: 5164, 300: 5184, 301: 5184}


def any_extra(L: dict) -> bool:
    """The line writes one of A B C U V W."""
    return any(a in L for a in EXTRA)


def extra_origin(state: GCodeState, index: int | None = None) -> tuple[float, ...]:
    """Origin of system ``index`` (default: the active one) on A .. W."""
    base = 5204 + 20 * (state.origin_index if index is None else index)
    return tuple(state.params.get(base + k, 0.0) for k in range(6))


def extra_axis_offset(state: GCodeState) -> tuple[float, ...]:
    """The ``G92``/``G52`` offset in force on A .. W."""
    if state.params.get(_OFFSET_APPLIED, 0.0) == 0.0:     # any non-zero, as LinuxCNC
        return _ZERO
    return tuple(state.params.get(_OFFSET_BASE + k, 0.0) for k in range(6))


def extra_work(state: GCodeState) -> list[float]:
    """The current A .. W in work coordinates."""
    cur = state.extra or [0.0] * 6
    o, a = extra_origin(state), extra_axis_offset(state)
    return [cur[k] - o[k] - a[k] for k in range(6)]


def extra_end(state: GCodeState, L: dict, machine: bool) -> tuple[float, ...] | None:
    """Machine A .. W at the end of a move with words ``L`` (``None`` while
    no extra axis has been moved)."""
    if state.extra is None and not any_extra(L):
        return None
    cur = state.extra or [0.0] * 6
    o, a = extra_origin(state), extra_axis_offset(state)
    end = list(cur)
    used = state.meta.get(AXES_USED, "")
    for k, letter in enumerate(EXTRA):
        if letter in L:
            if letter not in used:
                used = "".join(c for c in EXTRA if c in used or c == letter)
                state.meta[AXES_USED] = used
            v = L[letter][0]
            if machine:
                end[k] = v
            elif state.incremental:
                end[k] = cur[k] + v
            else:
                end[k] = v + o[k] + a[k]
    return tuple(end)


def set_extra_origin(state: GCodeState, index: int, L: dict, level: int) -> None:
    """``G10 L2``/``L20`` words on A .. W for system ``index``."""
    base = 5204 + 20 * index
    if not any_extra(L):
        return
    cur = state.extra or [0.0] * 6
    a = extra_axis_offset(state)
    for k, letter in enumerate(EXTRA):
        if letter in L:
            v = L[letter][0]
            state.params[base + k] = v if level == 2 else cur[k] - a[k] - v


def set_extra_axis_offset(state: GCodeState, tenths: int, L: dict) -> None:
    """``G92``/``G52``/``G92.1`` on A .. W (before X Y Z change ``#5210``)."""
    if tenths == 921:
        for k in range(6):
            state.params[_OFFSET_BASE + k] = 0.0
        return
    if tenths not in (920, 520):
        return
    old = list(extra_axis_offset(state))
    cur = state.extra or [0.0] * 6
    o = extra_origin(state)
    for k, letter in enumerate(EXTRA):
        if letter in L:
            v = L[letter][0]
            old[k] = v if tenths == 520 else cur[k] - o[k] - v
    for k in range(6):
        state.params[_OFFSET_BASE + k] = old[k]


def home_extra(state: GCodeState, code: int, L: dict, waypoint, any_written: bool):
    """Machine A .. W of a ``G28``/``G30`` home move after ``waypoint``."""
    if waypoint is None:
        return None
    base = _HOME_BASE[code]
    return tuple(state.params.get(base + k, 0.0) if (letter in L or not any_written)
                 else waypoint[k] for k, letter in enumerate(EXTRA))


def save_home_extra(state: GCodeState, code: int) -> None:
    """``G28.1``/``G30.1``: the current A .. W stored."""
    base = _HOME_BASE[code]
    cur = state.extra or [0.0] * 6
    for k in range(6):
        state.params[base + k] = cur[k]
