"""opt-casadi on fagor-g136-g138's hard episodes, one at a time (issue 17: the
leads that once took 500 IPOPT iterations, or came out infeasible or gouging,
and kept PMAC's lead).

Each episode is one contour element with both ends open (G41 activation,
one move, G40 cancellation), cutter radius 2. The figures are worked out here:
the element's own distance formula (a line's perpendicular, an arc's radial
distance) at dense samples of each blend whose foot lies on the element, and
the direction out of an arc's end from its centre and sweep.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.compare import compare
from ccopt.geometry import Arc, BezierCurve
from ccopt.program import read_text
from ccopt_formulations.clearance import EXEMPT, Element, classify, row_margin

import blend_checks as bc

R = 2.0

# episode 3: activation and cancellation turning 170 degrees at a line's ends
LINE_170 = """G90 G17 G21 F600 G136 G138
G00 X219.696155 Y-3.472964
G41 D1
G01 X200 Y0
G01 X220 Y0
G40 G01 X200.303845 Y-3.472964
M30
"""

# episode 5: 120 degrees, the compensated move an arc G2 R10 from (400,0) to (410,-10)
ARC_120 = """G90 G17 G21 F600 G136 G138
G00 X410 Y-17.320508
G41 D1
G01 X400 Y0
G02 X410 Y-10 I0 J-10
G40 G01 X392.679492 Y0
M30
"""


def _blends(text):
    prog = read_text(text, "episode.nc")
    row = compare(prog, ["pmac", "opt-casadi"], radius=R)["opt-casadi"]
    assert row.status == "ok", row.message
    leads = {e["lead"]: e for e in row.info["leads"]}
    assert leads["in"]["status"] == "ok" and leads["out"]["status"] == "ok", leads
    assert row.figures["certified"]
    curves = [s.geom for s in row.toolpath.segments if isinstance(s.geom, BezierCurve)]
    assert len(curves) == 2
    return [bc.bezier_points(g, 4001)[1:-1] for g in curves]


@pytest.mark.slow
def test_line_episode_at_170_degrees_both_leads_optimised():
    # the first guess (a curve along PMAC's diagonal) ran through the band along the
    # line; IPOPT called the model infeasible and PMAC's gouging lead stayed
    for pts in _blends(LINE_170):
        along = (pts[:, 0] > 200.0) & (pts[:, 0] < 220.0)
        assert np.all(np.abs(pts[along, 1]) >= R - 1e-6)


@pytest.mark.slow
def test_arc_episode_at_120_degrees_both_leads_optimised():
    # samples beyond the arc's open start were left free and crossed its end radius
    # inside the band between two samples: a gouge of 0.22 after four rounds
    c = np.array([400.0, -10.0])
    for pts in _blends(ARC_120):
        v = pts - c
        ang = np.degrees(np.arctan2(v[:, 1], v[:, 0]))
        on_sweep = (ang >= 0.0) & (ang <= 90.0)          # the foot lies on the arc
        assert np.all(np.abs(np.hypot(*v[on_sweep].T) - 10.0) >= R - 1e-6)


def test_beyond_an_arcs_open_ends_the_half_plane_past_its_end_radius():
    # arc from (0, 10) clockwise to (10, 0) about the origin: out of its start the
    # direction is -x, out of its end -y (the tangents of the motion, continued)
    arc = Element("arc", R, Arc((0.0, 0.0), 10.0, math.pi / 2, -math.pi / 2),
                  open_start=True, open_end=True)
    p = np.array([[-3.0, 5.0], [5.0, -3.0], [1.0, 1.5]])
    kind, vec, scal = classify(arc, p)
    assert list(kind[:2]) == [EXEMPT, EXEMPT]
    assert np.allclose(vec[0], [-1.0, 0.0]) and scal[0] == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(vec[1], [0.0, -1.0]) and scal[1] == pytest.approx(0.0, abs=1e-12)
    m = row_margin(arc, p)
    # (-3, 5): 3 past the start's radius, sqrt(9 + 25) from the start (0, 10)
    assert m[0] == pytest.approx(min(3.0, math.hypot(3.0, 5.0) - R))
    # (5, -3): 3 past the end's radius, sqrt(25 + 9) from the end (10, 0)
    assert m[1] == pytest.approx(min(3.0, math.hypot(5.0, 3.0) - R))
    # (1, 1.5): inside the sweep, 10 - sqrt(3.25) from the arc
    assert m[2] == pytest.approx(10.0 - math.hypot(1.0, 1.5) - R)
