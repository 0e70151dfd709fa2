"""Every switchable decision the controller manuals leave open, in one place.

Each entry names the rule of ``docs/compensation.md`` it settles and is read
by the code that applies that rule, which branches on it: changing a decision
is changing this file. Where a string value is used, the alternatives are
listed. Entries marked *[spec decision]* are the documented rules' reading;
*[ccopt decision]* ones are decided here where the rules are silent.

Decisions the code can take no other way (a negative radius flips the side,
spirals are Archimedean, a radius change is introduced over the next move,
Fagor changes while on follow PMAC, and the LinuxCNC style's facts of
LinuxCNC's own code) are documented in ``docs/compensation.md`` and at the
place that applies them, not switched here.
"""
from __future__ import annotations

import math

import numpy as np

#: [spec decision] PMAC ``RAPID`` moves while compensation is on are offset
#: like ``LINEAR`` moves (they keep feed ``None``: they run at axis limits).
#: ``False``: a rapid runs uncompensated, to its programmed point (the move
#: before it ends as for a lead-out, the move after it is a lead-in).
PMAC_OFFSET_RAPIDS = True

#: [spec decision] Outside corners with ``t_in . t_out >= break_cos`` (Isx99)
#: are "shallow": the offset elements are extended to their intersection.
#: [ccopt decision] When a shallow outside corner's extended offsets do not
#: intersect (possible with an arc), the sharp rule (added arc) is used.
#: Alternative ``"gradual"``: as an inside corner without intersection, the
#: change is introduced over the next move (no arc).
SHALLOW_WITHOUT_INTERSECTION = "arc"


#: [ccopt decision] In a reversal with an arc (rule 3, Turbo p.299) the
#: "inside intersection" is one *behind* the corner along the incoming
#: direction, ``(x - P) . t_in < 0``: the tool stops short on the incoming
#: element and leaves on the outgoing one, which runs back over it. The two
#: candidates of a line/arc or arc/arc reversal mirror each other across the
#: normal at ``P``, on which both nominal offset points lie, so
#: :func:`nearest_root` alone ties and cannot choose. ``False``: the one
#: ahead of the corner (the tool runs past it on the incoming element).
REVERSAL_INTERSECTION_BEHIND_CORNER = True


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


#: [spec decision] Side change in a reversal (``CC1`` <-> ``CC2`` where the
#: path turns back on itself): an arc of radius ``r`` about ``P`` (180 degrees,
#: old side, as a line-line reversal) then the change is introduced linearly
#: over the next move. Alternative ``"gradual"``: no arc, the change alone
#: (the offsets of a reversed move on the other side lie on one line).
SIDE_CHANGE_REVERSAL = "arc-then-gradual"

#: [ccopt decision] A lead-in or lead-out whose corner is a full reversal
#: (``|c| <= eps`` and ``d < 0``) is treated as outside: the 180-degree arc.
#: ``False``: as inside, no arc.
LEAD_REVERSAL_IS_OUTSIDE = True

#: [ccopt decision] Z-only moves and dwells between two in-plane moves run at
#: the compensated corner point *after* any added corner arc (Turbo PMAC
#: completes the added arc before a full stop, User Manual p.299).
#: ``False``: they run where the incoming move ends, before the corner arc.
GAP_MOVES_AFTER_CORNER_ARC = True

#: [ccopt decision] Compensated corners involving a programmed spiral use, for
#: the intersection, the circle about the spiral's centre through its offset
#: end point (the manuals do not describe compensated spirals). The spiral
#: itself is then run exactly from corner point to corner point.
#: Alternative ``"tangent-line"``: the line through the offset point along
#: the spiral's tangent there (the offset curve's tangent).
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
#: that has compensation off (or at the very end). ``False``: the path stays
#: at the offset end point (as LinuxCNC).
AUTOMATIC_ZERO_DISTANCE_LEADOUT = True


# -- LinuxCNC style (ccopt/compensate/linuxcnc.py) ---------------------------------

#: [ccopt decision] Gouge errors found while the queued move is sent (a
#: straight that would run backwards, an arc that would sweep further than
#: programmed) are located at the block being converted, as LinuxCNC reports
#: them; G40 on a line of its own is located at the next motion block (the
#: program model has no block for a line without motion). Alternative
#: ``"queued-block"``: at the block of the queued move that gouges.
LINUXCNC_ERROR_LOCATION = "converting-block"


# -- Fagor 8070 style (ccopt/compensate/fagor.py) -----------------------------------

#: [spec decision, made exact here] G137 linear transition at an outside
#: corner, turning angle up to 90 degrees: the incoming offset's tangent line
#: at ``A = P + r*o(t_in)`` and the outgoing one's at ``B = P + r*o(t_out)``
#: meet at ``X``; the path goes ``A -> X -> B``. Beyond 90 degrees:
#: ``A -> A + r*t_in -> B - r*t_out -> B``. A piece lying on a compensated
#: line's own offset becomes part of that line, so the inserted straight
#: segments are LIN-LIN 0/1, LIN-ARC 1/2, ARC-ARC 2/3 (up to / beyond 90
#: degrees): the ISG/Beckhoff G25 block counts. Activation and cancellation
#: moves are not along their offsets: their piece stays a separate segment.
#: Alternative ``"tangent-lines"``: the same points, every piece a corner
#: segment of its own.
FAGOR_G137_LINEAR_TRANSITION = "tangent-lines-isg-g25"

#: [ccopt decision] G136/G137 in force at a corner is the outgoing block's
#: (the cancellation block's at the end); G138/G139 is the activation block's
#: at the start and the cancellation block's at the end. Alternative
#: ``"incoming-block"`` for G136/G137.
FAGOR_MODAL_OF_CORNER = "outgoing-block"

#: [ccopt decision] A reversal (the path turns back on itself) while Fagor
#: compensation is on is an outside corner of 180 degrees: a half-turn arc
#: (G136) or the G137 construction beyond 90 degrees. ``False``: as an inside
#: corner (the offsets' intersection, or the change over the next move).
FAGOR_REVERSAL_IS_OUTSIDE = True

#: [ccopt decision] The manual describes activation by a straight move only:
#: an arc as the first move in the plane after G41/G42 is an error, like an
#: arc as the cancellation move after G40 (which the manual forbids).
#: ``False``: an arc activates like a straight move (its tool path is then
#: a spiral from the programmed start to the offset end, as a PMAC lead-in).
FAGOR_ARC_ACTIVATION_IS_AN_ERROR = True

#: [ccopt decision] Program end while Fagor compensation is on behaves as a
#: cancellation without motion in the plane (Fagor rule 4): the last move
#: ends at its offset end and the tool goes straight to its programmed end.
#: Alternative ``"stay-at-offset"``: the path ends at the offset end.
FAGOR_PROGRAM_END_WHILE_ON = "cancel-in-place"

#: [ccopt decision] Moves with no in-plane component between two compensated
#: moves run after the corner transition (as PMAC, GAP_MOVES_AFTER_CORNER_ARC).
#: ``False``: before it, where the incoming move ends.
FAGOR_GAP_MOVES_AFTER_TRANSITION = True


# -- HEIDENHAIN TNC style (ccopt/compensate/heidenhain.py) ---------------------------

#: [ccopt decision] M97 at an outside corner whose offsets do not intersect
#: (an arc offset that misses the next element's): the transition arc, as
#: without M97. Alternative ``"gradual"``: as an inside corner without
#: intersection, the change over the next move.
HEIDENHAIN_M97_WITHOUT_INTERSECTION = "arc"

#: [ccopt decision] M98 at an inside corner ("open contour corner"): the
#: manuals say the TNC suspends radius compensation so that both corners are
#: machined completely, and (TNC7) that it extends the tool path by the tool
#: radius and holds the position in the next block. ``"extend-then-next-block"``:
#: the block ends at the end of its offset, ``P + r*o(t_in)``, and the next
#: block runs from there to its own offset end (its offset introduced over
#: it). Alternative ``"straight-to-next-offset"``: a straight move from there
#: to the next block's offset start ``P + r*o(t_out)``.
HEIDENHAIN_M98_OPEN_CORNER = "extend-then-next-block"

#: [ccopt decision] A program (or a run of blocks in one plane) that ends with
#: RL/RR in force, not by DEP or an R0 block: the last element ends at its
#: offset end and a straight move returns to its programmed end
#: (``"return-to-contour"``, PMAC's automatic lead-out). Alternative
#: ``"stay-at-offset"``.
HEIDENHAIN_PROGRAM_END_WHILE_ON = "return-to-contour"


# -- SINUMERIK 840D style (ccopt/compensate/siemens.py) ------------------------------

#: [spec decision] G451 falls back to the G450 transition circle when the path
#: turns by this many degrees or more at an outside corner (machine data
#: MD20210 ``$MC_CUTCOM_CORNER_LIMIT``; the 808D Programming and Operating
#: Manual gives the set angle 100 degrees). The manuals call it the "contour
#: angle" and plot the intersection's overshoot, which grows with the turn,
#: against it: read here as the turning angle.
SIEMENS_CORNER_LIMIT_DEG = 100.0

#: [ccopt decision] G450/G451 and DISC in force at a corner are the outgoing
#: block's ("the transition circle belongs to the next block", Programming
#: Manual 2.10.3): at an approach (KONT) the first contour move's, at a
#: retraction the G40 block's. Alternative ``"incoming-block"``.
SIEMENS_MODAL_OF_CORNER = "outgoing-block"

#: [ccopt decision] A reversal (the path turns back on itself) while SINUMERIK
#: compensation is on is an outside corner of 180 degrees: a half-turn G450
#: circle (G451 falls back to it, the turn being past the corner limit).
#: ``False``: as an inside corner (the offsets' intersection, or the change
#: over the next move).
SIEMENS_REVERSAL_IS_OUTSIDE = True

#: [ccopt decision] A G451 (or DISC=100) outside corner whose offsets do not
#: meet (a line and an arc that miss each other) gets the G450 transition
#: circle. Alternative ``"next-move"``: the change is introduced over the
#: next move, as an inside corner without intersection.
SIEMENS_INTERSECTION_MISSING = "G450"

#: Open points the SINUMERIK style settles as the Fagor engine it runs on
#: (documented in docs/compensation.md, switched by the FAGOR_ entries
#: above): an inside corner whose offsets do not meet introduces the change
#: over the next move; G41 <-> G42 without G40 follows the PMAC side-change
#: rule; a G40 block that does not move in the plane cancels in place;
#: program end while on cancels in place. Bottleneck detection (CDON) is not
#: applied by any style: adjacent offsets are intersected and the verifier
#: reports what gouges.
