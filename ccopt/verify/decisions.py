"""Every decision the verifier makes that the spec leaves open, in one place.

Each entry is used by name in :mod:`ccopt.verify`, so changing a decision is
changing this file (and the tests that pin it).
"""
from __future__ import annotations

#: [ccopt decision] The *contour* (the part surface the radius offset must
#: respect) is the programmed geometry of every fully compensated in-plane
#: move: compensation on (``CC1``/``CC2``, ``G41``/``G42``) both for the move
#: and for the in-plane move before it. The lead-in (compensation off before
#: the move) and the lead-out (off for the move) are approach moves, not part
#: surface (spec rules 2 and 5 build them to *reach* the contour, diagonally
#: or as a spiral). Rapids and uncompensated moves are not part surface either.
CONTOUR_IS_FULLY_COMPENSATED_MOVES = True

#: [ccopt decision] A move over which a side change is introduced (``CC1``
#: <-> ``CC2``: its side differs from the previous move's) is a *transition*,
#: not part surface: the spec moves the tool from one side of it to the other
#: (spec rule 4, "change through a line / an arc / in reversal"). The tool
#: path along it is still checked against every contour element.
SIDE_CHANGE_MOVE_IS_TRANSITION = True

#: [ccopt decision] A move over which a radius change is introduced (its
#: radius differs from the previous move's, spec rule 4) is part surface with
#: the smaller of the two radii as its required clearance; it has no contact
#: requirement (the spec makes the offset vary linearly along it).
RADIUS_CHANGE_CLEARANCE = "smaller"

#: [ccopt decision] Open ends. Where the contour stops (the start of the first
#: contour element after a lead-in or transition, the end of the last one
#: before a lead-out or transition) the part surface is not defined beyond
#: the element. A tool position whose nearest point on such an element is
#: that open end is *beyond* the element and is not checked against it (it
#: still is against every other element). Exactly: for a line element, the
#: closed half-plane behind the end, normal to the line; for an arc, the
#: closed wedge (about the centre) of polar angles outside the sweep that are
#: nearer to that end. Spiral and curve elements get no such exemption
#: (conservative). Without this rule the spec's own lead-in (a diagonal to
#: ``P + r*o(t_next)``) would "gouge" the start point ``P`` it approaches.
OPEN_END_EXEMPTION = True

#: [ccopt decision] The checks are in the plane of compensation: a tool
#: position counts whatever its out-of-plane coordinate (conservative: a tool
#: above the part is checked as if it were at depth).
IN_PLANE_ONLY = True

#: [ccopt decision] Contact is measured from the tool side, where the tool
#: runs alongside its element: every point of the tool segment of a steady
#: contour element (same side and radius as the move before) whose nearest
#: point on the element is not an end point of it must be within ``r + eps``
#: of the element, and every added corner arc within ``r + eps`` of its
#: corner point ``P``. The places where the spec says the tool cannot touch
#: need no exception by name: at an inside corner the tool stops short of
#: the corner (the trimmed segment stays alongside, at ``r``); at a shallow
#: outside corner the extension past the normal at ``P`` is not alongside;
#: Fagor's G137 straight transitions are corner *lines*, not arcs about
#: ``P``, and are not checked for contact.
CONTACT_ALONGSIDE = True

#: [ccopt decision] Only tool segments made while compensation is in force
#: (lead-in, compensated, corner, lead-out, and the Z-only moves between
#: them) can gouge. Rapids and uncompensated moves run at the programmed
#: points, which are the programmer's own tool-centre positions, not an
#: offset; those that come within the clearance of the contour are listed in
#: the gouge check's detail for information (e.g. a rapid from a machine
#: origin that lies on the contour), not counted as violations.
GOUGE_ONLY_WHILE_COMPENSATED = True

#: [ccopt decision] Continuity: a jump between consecutive tool segments
#: (in-plane and out-of-plane together) larger than ``eps`` fails the check;
#: tangent breaks (inside corners, lead-in diagonals, spec constructions) are
#: listed for information and never fail it.
TANGENT_BREAKS_ARE_INFORMATION = True

#: [ccopt decision] Without an explicit ``radius=`` the verifier takes the
#: radii written in the program; when every compensated block has one and the
#: same radius and the tool path says it was made with another (a
#: ``compensate(radius=...)`` override), the tool path's radius is used and
#: the certificate notes it.
RADIUS_FROM_TOOLPATH_WHEN_UNIFORM = True

#: [ccopt decision] The corner point ``P`` an added corner arc must stay
#: within ``r + eps`` of is the programmed point where the in-plane moves run
#: just before and just after the arc meet, not the end of the block that
#: carries the arc: PMAC and Fagor attach the arc to the incoming move,
#: LinuxCNC to the outgoing one (it emits the arc while converting that
#: block), and the corner is the same point for both. Only when those moves
#: are not consecutive in the program (a move whose tool segment vanished)
#: does the carrier decide (see :func:`ccopt.verify.contact.corner_points`).
#: A corner contact violation is reported at the move ending at ``P``.
CORNER_POINT_BETWEEN_ITS_MOVES = True

#: [ccopt decision] Only the corner arcs a controller adds (about the
#: programmed corner, radius r) are held to the corner contact rule. The arcs
#: and lines an export fits to a blend curve or a spiral (listed in the read-back
#: path's ``meta["fitted_pieces"]``, :data:`ccopt.toolpath.FITTED_PIECES`) keep
#: the role of the curve they replace; a blend that cuts a corner is checked
#: for gouge and continuity like the curve itself, not for touching the corner.
CORNER_ARCS_ARE_THE_CONTROLLERS = True
