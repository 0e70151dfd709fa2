"""The verifier's switchable decisions: choices the spec leaves open that
have a real alternative behaviour.

Each flag is read by name where its rule is applied in :mod:`ccopt.verify`,
so changing a decision is changing this file (and the tests that pin it);
``False`` selects the alternative described with it. The verifier's other
decisions have no alternative it could take (which moves are the contour,
side changes as transitions, the clearance over a radius change, checks in
the plane of compensation, contact alongside an element, the corner point
between its moves, corner arcs being the controller's): they are documented
in docs/compensation.md and at the code that applies them.
"""
from __future__ import annotations

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
#: An end where another contour element starts or ends (the closing corner
#: of a loop entered by a lead) is a joint, not open.
#: ``False``: no end is open; every tool position is checked against every
#: element (conservative: the spec's lead-ins and lead-outs then fail).
#: Applied in :func:`ccopt.verify.contour.contour_of` (``Contour.open_start``,
#: ``Contour.open_end``).
OPEN_END_EXEMPTION = True

#: [ccopt decision] Only tool segments made while compensation is in force
#: (lead-in, compensated, corner, lead-out, and the Z-only moves between
#: them) can gouge. Rapids and uncompensated moves run at the programmed
#: points, which are the programmer's own tool-centre positions, not an
#: offset; those that come within the clearance of the contour are listed in
#: the gouge check's detail for information (e.g. a rapid from a machine
#: origin that lies on the contour), not counted as violations.
#: ``False``: every tool segment counts, rapids and uncompensated moves too.
#: Applied in :func:`ccopt.verify.run.verify` (``PairDistances.counted``).
GOUGE_ONLY_WHILE_COMPENSATED = True

#: [ccopt decision] Without an explicit ``radius=`` the verifier takes the
#: radii written in the program; when every compensated block has one and the
#: same radius and the tool path says it was made with another (a
#: ``compensate(radius=...)`` override), the tool path's radius is used and
#: the certificate notes it. (A program that sets no radius at all is always
#: verified with the tool path's.) ``False``: the program's radius is used
#: (such a path then fails against it). Applied in
#: :func:`ccopt.verify.contour.contour_of`.
RADIUS_FROM_TOOLPATH_WHEN_UNIFORM = True

#: [ccopt decision] The part is the closed loop. Within a run of consecutive
#: fully compensated moves, a closed loop (moves whose end returns to the
#: start of the first within ``eps``, enclosing an area) is the part surface
#: and the compensated moves before, between and after the loops are leads in
#: air (a CAM system's tangent arcs in and out): they are no contour elements
#: (no contact or side required of them; their tool segments are checked
#: against the part). Only innermost loops count (a loop holding another, as
#: a lead that returns to its own start makes around the contour, is not
#: part). A run without a closed loop is part throughout.
#: ``--part-lines`` and the ``(ccopt: part)``/``(ccopt: air)`` markers override
#: it. ``False``: every fully compensated move is part (unless marked air).
#: Applied in :func:`ccopt.verify.surface.surface_of`.
CLOSED_LOOP_IS_THE_PART = True

#: [ccopt decision] The open-end exemption is continuous. A tool position
#: past an open end by ``s`` (its distance beyond the end's normal line) is
#: not dropped but held to the end point ``P`` with the clearance less ``s``:
#: ``|q - P| + s >= clearance - eps`` (the forbidden zone past the end is the
#: inside of the parabola with focus ``P`` whose directrix lies one clearance
#: beyond the end; at the normal line it is the full clearance, as alongside).
#: The controllers' own leads approach the end at a slant and pass (PMAC's
#: diagonal lead-in gives up 0.2 of ``s`` at most on the bundled cases); a lead
#: pushed toward the part while staying connected is caught. A line running
#: along the end's normal on the tool side (the tool centre going straight
#: back onto ``P``, Fagor's cancellation in place) is left exempt. Exact for
#: line and arc tool segments; spiral and curve tool segments keep the plain
#: exemption. ``False``: points past an open end are not checked against the
#: element at all. Applied in :func:`ccopt.verify.clearance.pair_distances`.
OPEN_END_TAPER = True
