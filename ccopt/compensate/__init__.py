"""Cutter radius compensation: ``Program`` -> ``ToolPath`` as a controller does it.

Styles register in :data:`STYLES` (name -> class taking the style's options);
a new style is one module plus one line here. The shared geometry of corners
lives in :mod:`.corners`, the program scan in :mod:`.scan`, and every
switchable decision the manuals leave open in :mod:`.decisions` (the rules:
docs/compensation.md).
"""
from __future__ import annotations

from typing import Callable

from ccopt.compensate.fagor import FagorStyle
from ccopt.compensate.heidenhain import HeidenhainStyle
from ccopt.compensate.linuxcnc import LinuxcncStyle
from ccopt.compensate.pmac import PmacStyle
from ccopt.compensate.siemens import SiemensStyle
from ccopt.errors import ProgramError
from ccopt.program.model import Program
from ccopt.sides import side_sign
from ccopt.toolpath import COMPENSATION, ToolPath

#: style name -> class taking the style's options as keywords, whose instances
#: have ``compensate(program, radius=, side=) -> ToolPath``.
STYLES: dict[str, Callable[..., object]] = {
    "pmac": PmacStyle,
    "linuxcnc": LinuxcncStyle,
    "fagor": FagorStyle,
    "heidenhain": HeidenhainStyle,
    "siemens": SiemensStyle,
}


def compensate(program: Program, style: str = "pmac", *, radius: float | None = None,
               side: str | int | None = None, **options) -> ToolPath:
    """Tool-centre path of ``program`` as controller ``style`` makes it.

    Parameters
    ----------
    program: the programmed contour with its compensation words.
    style: ``"pmac"`` (reference) or another registered style.
    radius: cutter radius in program units, overriding the program's.
    side: ``"left"``/``"right"`` (or +1/-1) overriding the programmed side
        wherever compensation is on.
    options: style options, e.g. ``break_cos`` (PMAC Isx99, default 0.9998)
        and ``ccbuf`` (Turbo ``DEFINE CCBUF``) for ``pmac``.
    """
    if style not in STYLES:
        raise ProgramError(f"unknown compensation style {style!r}; choose one of "
                           f"{', '.join(sorted(STYLES))}", program.file)
    try:
        side = side_sign(side)
    except ValueError as exc:
        raise ProgramError(str(exc), program.file) from None
    # Controller settings written in a PMAC file (Isx99, DEFINE CCBUF) apply
    # unless the caller overrides them.
    if style == "pmac":
        for key in ("break_cos", "ccbuf"):
            if key not in options and program.meta.get(key) is not None:
                options[key] = program.meta[key]
    try:
        engine = STYLES[style](**options)
    except (TypeError, ValueError) as exc:
        raise ProgramError(f"bad option for style {style}: {exc}", program.file) from None
    path = engine.compensate(program, radius=radius, side=side)
    # what compensation knew beyond the program: recorded, not inferred again
    path.meta[COMPENSATION] = {"radius": None if radius is None else float(radius),
                               "side": None if side is None else int(side)}
    return path


__all__ = ["STYLES", "compensate"]
