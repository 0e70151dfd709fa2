"""A straight line by its angle, ``ANG=`` (Programming Manual Fundamentals
6FC5398-2EP40, "Contour definitions": "Straight line with angle").

``G0``/``G1`` with ``ANG=a`` and one of the plane's two coordinates: the
line leaves the start at ``a`` degrees from the plane's first axis
(counter-clockwise toward the second: ``G17`` X toward Y, ``G18`` Z toward
X, ``G19`` Y toward Z) and ends where it reaches the coordinate written; the
other coordinate is worked out here and handed to the core with it. The
work frame (a turned frame, :mod:`.frames`) is the one the angle is read in.

The contour definition over two blocks (:func:`contour_definition`): a
line with ``ANG=a1`` and no coordinate, then a line with ``ANG=a2`` and its
end point ``P2`` (both coordinates, absolute): the first ends where it meets
the second's line, ``P1 = P0 + t1 d(a1) = P2 - t2 d(a2)`` with ``t1, t2 >
0``; a chamfer or rounding of either block goes at its corner as usual (the
manual's example: ``ANG=140 CHR=7.5``, then ``X80 Z70 ANG=95.824 RND=10``).

Refused where they stand: the three-block definitions and a second block
that is not one (the two blocks follow each other directly, under ``G90``),
an end the line never reaches (parallel to the axis written, or lines that
do not meet ahead), an end reached going backwards, ``ANG`` with both
coordinates alone, and ``ANG`` on a circle.
"""
from __future__ import annotations

import math

from dataclasses import replace

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
    t = math.radians(value)
    # the axis written and the other one, their start coordinates and the
    # line's direction along each
    if given[0] == au:
        a, b, a0, b0, ca, cb = au, av, here[iu], here[iv], math.cos(t), math.sin(t)
    else:
        a, b, a0, b0, ca, cb = av, au, here[iv], here[iu], math.sin(t), math.cos(t)
    written = letters[a][0]
    da = written if incremental else written - a0
    if abs(ca) <= PARALLEL:
        raise ExprError(f"ANG={value:g} runs along {b}: it never reaches the {a} written",
                        col)
    along = da / ca
    db = along * cb
    letters[b] = (db if incremental else b0 + db, col)
    if along < -POINT_EPS:
        raise ExprError(f"the {a} written lies behind the start along ANG={value:g}: the "
                        "line would run against its angle", col)


def contour_definition(run, bw) -> list:
    """The ordinary blocks to run now, ``[(BlockWords, 0-based line)]``: none
    while a contour definition's first block (``ANG``, no coordinate) waits
    for its second; then both, the first given its end point ``P1``."""
    state = run.state
    pending = run.pending_angle
    if pending is None:
        if "ANG" in bw.values and not _plane_words(state, bw) and _is_line(run, bw):
            _plain_distance(state, bw, "the first block of a contour definition")
            run.pending_angle = (bw, state.line_no)
            return []
        return [(bw, state.line_no)]
    first, line = pending
    run.pending_angle = None
    col = bw.values["ANG"][2] if "ANG" in bw.values else bw.first
    iu, iv, _ = PLANE_AXES[state.plane]
    au, av = "XYZ"[iu], "XYZ"[iv]
    if "ANG" not in bw.values or {au, av} - set(bw.axes) or not _is_line(run, bw):
        raise ExprError(f"the contour definition begun by ANG on line {state.where(line)[1]} "
                        f"needs its second block here: a straight line with {au} {av} and "
                        "ANG (ccopt reads two-block definitions)", col)
    _plain_distance(state, bw, "the second block of a contour definition")
    a1, a2 = first.values["ANG"][0], bw.values["ANG"][0]
    here = to_work(state, state.pos)
    p1 = _meet((here[iu], here[iv]), a1, (bw.axes[au][0], bw.axes[av][0]), a2, col)
    acol = first.values["ANG"][2]
    values = {k: v for k, v in first.values.items() if k != "ANG"}
    first = replace(first, axes={**first.axes, au: (p1[0], "AC", acol),
                                 av: (p1[1], "AC", acol)}, values=values)
    second = replace(bw, values={k: v for k, v in bw.values.items() if k != "ANG"})
    return [(first, line), (second, state.line_no)]


def check_between(run, bw) -> None:
    """No call, frame, pole or cycle stands between a contour definition's
    blocks (an ordinary block is checked as its second)."""
    special = (bw.call, bw.passes, bw.frame, bw.pole, bw.cycle, bw.mcall)
    if run.pending_angle is not None and any(x is not None for x in special):
        raise ExprError("the second block of a contour definition (a line with ANG) must "
                        "follow its first directly", bw.first)


def _plane_words(state, bw) -> list[str]:
    iu, iv, _ = PLANE_AXES[state.plane]
    return [a for a in ("XYZ"[iu], "XYZ"[iv]) if a in bw.axes]


def _is_line(run, bw) -> bool:
    motion = next((t for t, _ in reversed(bw.g) if t in (0, 10, 20, 30)),
                  run.state.motion_mode)
    return motion in (0, 10) and run.motion is None and bw.motion is None


def _plain_distance(state, bw, what: str) -> None:
    """Absolute coordinates only, no change of plane or distance mode."""
    col = bw.values["ANG"][2]
    if state.incremental or any(t in (170, 180, 190, 900, 910) for t, _ in bw.g) or any(
            m is not None for _, m, _ in bw.axes.values()):
        raise ExprError(f"{what}: ccopt reads contour definitions under G90, with no plane "
                        "or distance change and no AC/IC in their blocks", col)
    if input_factor(state) != 1.0:
        raise ExprError("ANG in other units than the program's first (G70/G71 changed): not "
                        "read by ccopt", col)


def _meet(p0, a1: float, p2, a2: float, col: int) -> tuple[float, float]:
    """``P1``: the line from ``p0`` at ``a1`` meets the line reaching ``p2`` at
    ``a2``, ahead on both (angles in degrees)."""
    d1 = (math.cos(math.radians(a1)), math.sin(math.radians(a1)))
    d2 = (math.cos(math.radians(a2)), math.sin(math.radians(a2)))
    cross = d1[0] * d2[1] - d1[1] * d2[0]
    if abs(cross) <= PARALLEL:
        raise ExprError(f"ANG={a1:g} and ANG={a2:g} are parallel: the two lines do not meet",
                        col)
    w = (p2[0] - p0[0], p2[1] - p0[1])
    t1 = (w[0] * d2[1] - w[1] * d2[0]) / cross
    t2 = (d1[0] * w[1] - d1[1] * w[0]) / cross
    if t1 <= POINT_EPS or t2 <= POINT_EPS:
        raise ExprError(f"the lines at ANG={a1:g} and ANG={a2:g} meet behind the start or "
                        "beyond the end point: no such contour", col)
    return (p0[0] + t1 * d1[0], p0[1] + t1 * d1[1])
