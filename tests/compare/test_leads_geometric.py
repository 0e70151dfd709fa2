"""Leads of PMAC's path and the geometric lead variants, against hand-derived geometry."""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import BlendProblem, load
from ccopt.compare.geometric import line_arc, tangent_arc
from ccopt.compare.leads import find_leads, lead_joins, splice
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role


@pytest.fixture(scope="module")
def pocket():
    prog = ccopt.read_program(find_case("pocket").program)
    return prog, ccopt.compensate(prog, "pmac")


def test_pocket_leads(pocket):
    _, ref = pocket
    lead_in, lead_out = find_leads(ref)
    # lead-in X0 Y20 after the plunge at (20, 20): inside corner with Y6 (t_next = (0, -1)),
    # CC1 left: P + r*o(t_next) = (0, 20) + 3 * (1, 0)
    assert lead_in.kind == "in" and ref.segments[lead_in.first].role is Role.LEAD_IN
    lg = lead_in.geometry(ref)
    assert lg.approach == pytest.approx((20.0, 20.0))
    assert lg.host.start == pytest.approx((3.0, 20.0))
    assert lg.host.start_tangent == pytest.approx((0.0, -1.0))
    assert lg.side == 1                      # the part is right of the tool path (CC1)
    # the lead-out is handed over reversed: approach = its end (20, 20), host the last
    # compensated move (Y20 from Y34) backwards from (3, 20), free side on its right
    lo = lead_out.geometry(ref)
    assert lead_out.kind == "out"
    assert lo.approach == pytest.approx((20.0, 20.0))
    assert lo.host.start == pytest.approx((3.0, 20.0))
    assert lo.host.start_tangent == pytest.approx((0.0, 1.0))
    assert lo.side == -1
    # PMAC's own lead joins: the diagonal into the contour, the contour into the lead-out
    assert lead_joins(ref) == [lead_in.host, lead_out.host + 1]


def test_tangent_arc_pocket(pocket):
    prog, ref = pocket
    lead_in = find_leads(ref)[0]
    geoms = tangent_arc(lead_in.geometry(ref), 3.0)
    line, arc = geoms
    # quarter circle of radius 3 about J + 3*n = (6, 20), from (6, 23) to J = (3, 20)
    assert isinstance(arc, Arc) and arc.radius == pytest.approx(3.0)
    assert arc.center == pytest.approx((6.0, 20.0))
    assert arc.start == pytest.approx((6.0, 23.0), abs=1e-12)
    assert arc.end == pytest.approx((3.0, 20.0), abs=1e-12)
    assert arc.end_tangent == pytest.approx((0.0, -1.0), abs=1e-12)
    assert abs(arc.sweep) == pytest.approx(math.pi / 2)
    assert line.start == pytest.approx((20.0, 20.0)) and line.end == pytest.approx((6.0, 23.0))
    # whole variant: both PMAC diagonals (17 each) replaced by line + quarter circle
    row = load("tangent-arc")(BlendProblem(prog, ref))
    expected = ref.length - 2 * 17.0 + 2 * (math.sqrt(14.0 ** 2 + 3.0 ** 2) + 1.5 * math.pi)
    assert row.toolpath.length == pytest.approx(expected, rel=1e-12)


def test_line_arc_pocket(pocket):
    prog, ref = pocket
    lead_in = find_leads(ref)[0]
    line, arc = line_arc(lead_in.geometry(ref), 3.0)
    # tangent from A = (20, 20) to the circle about C = (6, 20), radius 3, on the side that
    # turns counter-clockwise into J: T = C + 3 (cos a, sin a), cos a = 3/14
    a = math.acos(3.0 / 14.0)
    T = (6.0 + 3.0 * math.cos(a), 20.0 + 3.0 * math.sin(a))
    assert line.end == pytest.approx(T, abs=1e-12)
    assert line.length == pytest.approx(math.sqrt(14.0 ** 2 - 9.0), rel=1e-12)
    assert arc.sweep == pytest.approx(math.pi - a, rel=1e-12)
    assert line.direction == pytest.approx(arc.start_tangent, abs=1e-12)
    assert arc.end_tangent == pytest.approx((0.0, -1.0), abs=1e-12)
    row = load("line-arc")(BlendProblem(prog, ref))
    path = row.toolpath
    assert path.length == pytest.approx(
        ref.length - 34.0 + 2 * (math.sqrt(187.0) + 3.0 * (math.pi - a)), rel=1e-12)
    # the joins the variant made: line -> arc and arc -> contour at both leads, all G1
    from ccopt.compare.figures import path_figures
    fig = path_figures(path, lead_joins(path))
    assert [j["class"] for j in fig["joins"]] == ["G1"] * 4
    assert fig["continuity"] == "G1"


def test_splice_keeps_the_rest(pocket):
    _, ref = pocket
    lead_in = find_leads(ref)[0]
    lg = lead_in.geometry(ref)
    # splice PMAC's own diagonal back in, joined 2 units down the host
    J = np.asarray(lg.host.point(2.0))
    out = splice(ref, lead_in, [Line(lg.approach, tuple(J))], 2.0, style="x")
    assert len(out) == len(ref)
    assert out.segments[lead_in.host].start == pytest.approx(tuple(J))
    assert out.segments[lead_in.host].length == pytest.approx(ref.segments[lead_in.host].length - 2)
    for a, b in zip(out.segments[lead_in.host + 1:], ref.segments[lead_in.host + 1:]):
        assert a.geom == b.geom and a.role is b.role
    assert out.meta["joins"] == [lead_in.host]


def test_construction_errors():
    from ccopt.compare.geometric import ConstructionError
    from ccopt.compare.leads import LeadGeometry
    lg = LeadGeometry((0.5, 1.0), Line((0.0, 0.0), (10.0, 0.0)), 1, 10.0, "in")
    with pytest.raises(ConstructionError):
        line_arc(lg, 1.0)          # approach point inside the lead circle about (0, 1)
    with pytest.raises(ConstructionError):
        tangent_arc(lg, 0.0)
