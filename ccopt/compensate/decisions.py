"""Every decision the controller manuals leave open, in one place.

Each entry names the spec rule it settles (``shared/spec/compensation.md``)
and is used by name in the styles, so changing a decision is changing this
file. Entries marked *[spec decision]* are decided by the spec; entries marked
*[ccopt decision]* are decided here where even the spec is silent.
"""
from __future__ import annotations

import math

import numpy as np

#: [spec decision] A negative radius flips the side (LinuxCNC does this). The
#: readers apply it; the engines see ``radius >= 0`` and the effective side.
NEGATIVE_RADIUS_FLIPS_SIDE = True

#: [spec decision] PMAC ``RAPID`` moves while compensation is on are offset
#: like ``LINEAR`` moves (they keep feed ``None``: they run at axis limits).
PMAC_OFFSET_RAPIDS = True

#: [spec decision] A CIRCLE move whose start and end radii differ is an
#: Archimedean spiral: radius linear in swept angle.
SPIRAL_RADIUS_LINEAR_IN_ANGLE = True

#: [spec decision] Outside corners with ``t_in . t_out >= break_cos`` (Isx99)
#: are "shallow": the offset elements are extended to their intersection.
#: [ccopt decision] When a shallow outside corner's extended offsets do not
#: intersect (possible with an arc), the sharp rule (added arc) is used.
SHALLOW_WITHOUT_INTERSECTION = "arc"


def nearest_root(candidates, a_nominal, b_nominal):
    """[spec decision] Of several intersections of two offset elements, take
    the one nearest the nominal offset points.

    "Nearest" is the smallest sum of distances to ``a_nominal`` (incoming
    element's offset end, ``P + r*o(t_in)``) and ``b_nominal`` (outgoing
    element's offset start, ``P + r*o(t_out)``). Returns ``None`` for no
    candidates.
    """
    best, best_cost = None, math.inf
    a = np.asarray(a_nominal, float)
    b = np.asarray(b_nominal, float)
    for p in candidates:
        p = np.asarray(p, float)
        cost = float(np.hypot(*(p - a)) + np.hypot(*(p - b)))
        if cost < best_cost:
            best, best_cost = p, cost
    return best


#: [spec decision] A radius change (``CCR``) while on is introduced linearly
#: over the next move: the corner before it uses the old radius on both sides,
#: the move runs from its old-radius start point to its new-radius end point
#: (a diagonal for a line, a spiral about the programmed centre for an arc,
#: whose radius is linear in swept angle: ``r(u) = r_old + u*(r_new - r_old)``
#: with ``u`` the fraction of the swept angle).
RADIUS_CHANGE_OVER_NEXT_MOVE = True

#: [spec decision] Side change in a reversal (``CC1`` <-> ``CC2`` where the
#: path turns back on itself): an arc of radius ``r`` about ``P`` (180 degrees,
#: old side, as a line-line reversal) then the change is introduced linearly
#: over the next move.
SIDE_CHANGE_REVERSAL = "arc-then-gradual"

#: [ccopt decision] A lead-in or lead-out whose corner is a full reversal
#: (``|c| <= eps`` and ``d < 0``) is treated as outside: the 180-degree arc.
LEAD_REVERSAL_IS_OUTSIDE = True

#: [ccopt decision] Z-only moves and dwells between two in-plane moves run at
#: the compensated corner point *after* any added corner arc (Turbo PMAC
#: completes the added arc before a full stop, User Manual p.299).
GAP_MOVES_AFTER_CORNER_ARC = True

#: [ccopt decision] Compensated corners involving a programmed spiral use, for
#: the intersection, the circle about the spiral's centre through its offset
#: end point (the manuals do not describe compensated spirals). The spiral
#: itself is then run exactly from corner point to corner point.
SPIRAL_CORNER_CARRIER = "circle-through-offset-end"

#: [ccopt decision] The sweep of a compensated arc is the programmed sweep
#: plus the signed angle changes at its two corner points (measured in
#: (-pi, pi]), so an arc shortened past its start runs backwards (and
#: overcuts, as PMAC does for short moves) and a full circle stays a full
#: circle. PMAC's documented "skipped full circle" artefact for shallow
#: corners on full circles (Turbo User Manual p.299) is not reproduced.
ARC_SWEEP_CONTINUOUS = True

#: [spec decision] ``CC0`` with no following in-plane move, or program end
#: while on: the last move ends at its offset end point and a straight
#: lead-out returns to the programmed point, before the first trailing block
#: that has compensation off (or at the very end).
AUTOMATIC_ZERO_DISTANCE_LEADOUT = True
