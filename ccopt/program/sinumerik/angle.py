"""A straight line by its angle, ``ANG=`` (Programming Manual Fundamentals
6FC5398-2EP40, "Contour definitions": "Straight line with angle").

``G0``/``G1`` with ``ANG=a`` and one of the plane's two coordinates: the
line leaves the start at ``a`` degrees from the plane's first axis
(counter-clockwise toward the second: ``G17`` X toward Y, ``G18`` Z toward
X, ``G19`` Y toward Z) and ends where it reaches the coordinate written; the
other coordinate is worked out here and handed to the core with it. The
work frame (a turned frame, :mod:`.frames`) is the one the angle is read in.

Refused where they stand: the contour definitions over two or three blocks
(``ANG`` with no coordinate, or with both, and their chamfers and roundings
between: the intersection of the next block's line), an end the line never
reaches (parallel to the axis written) or reaches going backwards (against
``ANG``), and ``ANG`` on a circle.
"""
from __future__ import annotations

import math

from ccopt.program.expr import ExprError
from ccopt.program.gcode.coordinates import to_work
from ccopt.program.gcode.units import input_factor
from ccopt.program.model import PLANE_AXES
from ccopt.tolerances import POINT_EPS

#: |cos| or |sin| of ANG below this: the line runs along the other axis.
PARALLEL = 1e-12


def angle_line(run, bw, letters: dict, g: list) -> None:
    """Write the end coordinate ``ANG`` gives into ``letters`` (see the module
    docstring); nothing without ``ANG``."""
    if "ANG" not in bw.values:
        return
    state = run.state
    value, mode, col = bw.values["ANG"]
    if mode is not None:
        raise ExprError("ANG takes an angle in degrees (ANG=30)", col)
    motion = next((t for t, _ in reversed(g) if t in (0, 10, 20, 30)), state.motion_mode)
    if motion not in (0, 10) or run.motion is not None:
        raise ExprError("ANG gives a straight line (G0 or G1), not a circle", col)
    if input_factor(state) != 1.0:
        raise ExprError("ANG in other units than the program's first (G70/G71 changed): not "
                        "read by ccopt", col)
    iu, iv, _ = PLANE_AXES[state.plane]
    au, av = "XYZ"[iu], "XYZ"[iv]
    given = [a for a in (au, av) if a in letters]
    if len(given) != 1:
        raise ExprError(f"ANG with {'no' if not given else 'both'} {au}/{av}: a contour "
                        "definition over two or three blocks, not read by ccopt (program "
                        "its corner points)", col)
    incremental = any(t == 910 for t, _ in g) or (state.incremental
                                                 and not any(t == 900 for t, _ in g))
    here = to_work(state, state.pos)
    u0, v0 = here[iu], here[iv]
    t = math.radians(value)
    c, s = math.cos(t), math.sin(t)
    a = given[0]
    written = letters[a][0]
    if a == au:
        du = written if incremental else written - u0
        if abs(c) <= PARALLEL:
            raise ExprError(f"ANG={value:g} runs along {av}: it never reaches the {au} "
                            "written", col)
        along = du / c
        dv = along * s
        letters[av] = (dv if incremental else v0 + dv, col)
    else:
        dv = written if incremental else written - v0
        if abs(s) <= PARALLEL:
            raise ExprError(f"ANG={value:g} runs along {au}: it never reaches the {av} "
                            "written", col)
        along = dv / s
        du = along * c
        letters[au] = (du if incremental else u0 + du, col)
    if along < -POINT_EPS:
        raise ExprError(f"the {a} written lies behind the start along ANG={value:g}: the "
                        "line would run against its angle", col)
