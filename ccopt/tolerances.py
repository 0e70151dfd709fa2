"""The one place for numerical tolerances (program units unless stated).

Change a tolerance here, never inline.
"""
from __future__ import annotations

#: Two points closer than this are the same point (program units).
POINT_EPS = 1e-9

#: |t_in x t_out| at or below this is "no turn" (tangent or reversal), unitless.
TURN_EPS = 1e-9

#: G-code arcs whose start and end radii differ by more than this are an error
#: (LinuxCNC's default: 0.002 mm absolute or 0.001 relative; we accept either).
ARC_RADIUS_ABS_TOL_MM = 0.002
ARC_RADIUS_REL_TOL = 0.001

#: An R-format arc whose |R| is shorter than half its chord by at most this
#: fraction is read as a half circle (rounding in the program's numbers);
#: shorter still is an error. Both readers' R arcs use it.
R_CHORD_REL_TOL = 1e-9

#: A curvature jump (1/units) at most this times max(1, |kappa|) on either
#: side counts as none: rounding of a G2 join (a blend's end curvature).
CURVATURE_TOL = 1e-6

#: PMAC break point (Isx99): cos of the turn above which an outside corner is
#: "shallow" and the offsets are extended instead of adding an arc.
PMAC_BREAK_COS = 0.9998

#: Default verification tolerance (program units), see ccopt.verify.
VERIFY_EPS = 1e-6

#: Default gouge tolerance of a certificate, per program unit: a gouge, contact
#: excess or wrong-side offset no deeper than this is a warning (listed with
#: its depth, place and cause; verdict "ok within tolerance"), deeper ones
#: fail. 1 micrometre, and 40 microinches (1.016 micrometres) for inch
#: programs: above what a CAM program's written decimals move a point by (at
#: most 5e-4 per coordinate at 3 decimals), far below what a machine holds,
#: far above the rounding of the arithmetic (``VERIFY_EPS``).
GOUGE_TOLERANCE = {"mm": 1e-3, "inch": 4e-5}

#: A compensated arc whose two end points lie within this (relative to
#: max(1, R')) of its offset circle R' is that offset arc, radius exactly R'.
#: Corner intersections with nearly straight arcs (R of thousands of units)
#: lose ~1e-10 to rounding; without this they would read as tiny spirals.
OFFSET_CIRCLE_REL_TOL = 1e-9

#: Verifier: two consecutive tool segments whose tangents differ by more than
#: this angle (radians) are listed as a tangent break (informative, not a fault).
VERIFY_TANGENT_BREAK = 1e-6

#: Verifier: certified bounds (spirals, curves) stop refining once the gap
#: between lower and upper bound is at most this fraction of ``eps``.
VERIFY_CERTIFIED_GAP = 0.1

#: Verifier: at most this many subdivision rounds for a certified bound; a
#: bound not tight by then is reported with its actual gap.
VERIFY_CERTIFIED_MAX_ROUNDS = 40

#: A circular move whose end radius differs from its start radius by more
#: than this (relative to max(1, R)) is a spiral; within it, an arc (the
#: difference is rounding of the written numbers).
SPIRAL_RADIUS_REL_TOL = 1e-9

#: Export: lines and arcs replacing a blend curve meet the curve's tangent
#: within this angle (radians) at their ends, so consecutive ones join with a
#: kink of at most twice it (ccopt.export.arcfit.fit_bezier).
EXPORT_FIT_ANGLE_TOL = 1e-3

#: Export: where the read-back of a path that verifies comes inside the
#: clearance (an arc or line fitted to a curve or spiral strays outwards by up
#: to its bound, where the curve runs at the limit), the curves involved are
#: fitted again with a tolerance this many times smaller than the offending
#: piece's bound, at most EXPORT_REFIT_ROUNDS times (ccopt.export.export).
EXPORT_REFIT_SHRINK = 10.0
EXPORT_REFIT_ROUNDS = 4
#: ... and never below this (program units): the writers' 6 decimals round
#: every number by up to 5e-7, which no tighter fit can beat.
EXPORT_REFIT_MIN_TOL = 1e-7

# -- feed planning (ccopt.feed) --------------------------------------------------

#: Tangent turning between two samples of a curved segment for its budget (rad).
BUDGET_SAMPLE_ANGLE = 0.01

#: Two consecutive segments whose end and start points are further apart than
#: this are not connected: the path must stop there (program units; ccopt.feed).
GAP_EPS = 1e-6

#: Range accepted for every velocity and acceleration limit (program units per
#: second, per second squared). Far outside it the planners' squares of speeds
#: under- or overflow; no machine is there (1e-6 mm/s is 3.6 mm a year).
LIMIT_RANGE = (1e-6, 1e9)

#: Most samples a feed profile is sampled at (``FeedProfile.sample``): 2e7
#: samples of ~20 numbers each take about 3 GB.
MAX_FEED_SAMPLES = 20_000_000

#: A limit counts as active where its ratio |value| / limit is at least this.
ACTIVE_RATIO = 0.99

#: Rounding allowance (relative to the squared speeds involved) when the
#: lower end of a controllable set comes out above its upper end.
CROSSING_TOL = 1e-9

# -- LinuxCNC compensation (ccopt.compensate.linuxcnc) ----------------------------
# LinuxCNC's own constants, kept at LinuxCNC's values so that the ``linuxcnc``
# style makes the tool path LinuxCNC makes (tests/compensate conformance runs
# against its crazy-paths test). Source: LinuxCNC ``src/emc/rs274ngc/``.

#: ``TOLERANCE_CONCAVE_CORNER`` (``interp_internal.hh``), radians: a turn toward
#: or away from the tool side by at most this is "straight on" in
#: ``convert_straight_comp2``/``convert_arc_comp2``: no corner arc, no
#: pull-back (docs/compensation.md, LinuxCNC: a slight turn is straight on).
LINUXCNC_CONCAVE_CORNER = 0.05

#: ``TOLERANCE_EQUAL`` (``interp_internal.hh``), unitless here: in
#: ``convert_arc_comp1`` an entry arc whose chord makes a cosine below this with
#: the arc's normal at its end has no centre (the chord is perpendicular to it).
LINUXCNC_TOLERANCE_EQUAL = 1e-4

#: ``move_endpoint_and_flush`` (``interp_queue.cc``), radians: a queued arc whose
#: end is pulled back to an inside corner may sweep at most this much more
#: than programmed before LinuxCNC reports "Arc move in concave corner cannot
#: be reached by the tool without gouging". This is the literal ``0.001`` of
#: the LinuxCNC source this style was derived from; some later LinuxCNC
#: versions compare against ``.0254`` for mm programs (``.001`` inch) instead.
LINUXCNC_ARC_GROWTH = 0.001

#: A compensated arc whose two ends lie at distances from its centre that
#: differ by at most this (relative to max(1, r)) is an arc of that radius, not
#: a spiral (ccopt.compensate: corners.tool_geometry and batch.tool_segments).
TOOL_ARC_SAME_RADIUS_REL_TOL = 1e-12
