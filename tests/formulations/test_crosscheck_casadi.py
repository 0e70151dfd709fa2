"""CasADi/IPOPT worst-case gouge search: never deeper than the certified minimum."""
from __future__ import annotations

from dataclasses import replace
from importlib.metadata import entry_points

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import ccopt
from ccopt.cases import bundled_cases, find_case
from ccopt.compensate import compensate
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role
from ccopt.verify import verify
from ccopt.verify.crosschecks import run_crosschecks
from ccopt_formulations import crosscheck_casadi as F
from random_contours import contour_program, contours

CASES = [c for c in bundled_cases() if c.expect != "error"]


def test_registered_as_an_entry_point():
    eps = {e.name: e.value for e in entry_points(group="ccopt.crosschecks")}
    assert eps["casadi"] == "ccopt_formulations.crosscheck_casadi:crosscheck"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_search_never_deeper_than_certified(case):
    prog = ccopt.read_program(case.program)
    cert = verify(compensate(prog, case.style, radius=case.radius), prog, radius=case.radius)
    res = run_crosschecks(cert, names={"casadi"})[0]
    assert res["agree"], res["summary"]
    assert res["deeper_than_certified"] == 0
    assert res["largest_excess_below_bound"] <= F.SLACK
    # it also finds what the verifier found: the deepest gouge, to 1e-6
    worst = max((v.depth for v in cert.violations_of("gouge")), default=0.0)
    assert res["deepest_gouge_found"] == pytest.approx(worst, abs=1e-6)


def test_search_finds_the_short_move_overcut():
    # the step's tool segment reaches (18,1), 1 from the first move's line y = 0
    case = find_case("short-move-overcut")
    prog = ccopt.read_program(case.program)
    cert = verify(compensate(prog, "pmac"), prog)
    res = F.crosscheck(cert)
    assert res["deepest_gouge_found"] == pytest.approx(1.0, abs=1e-9)


def test_model_is_built_then_solved():
    # a line and an arc: (0,-1)-(0,1) against the quarter circle of radius 1
    # about (3,0) from angle pi/2 to pi (its nearest point is (2,0)): distance 2
    from ccopt.geometry import Arc, Line
    ln, arc = Line((0.0, -1.0), (0.0, 1.0)), Arc((3.0, 0.0), 1.0, np.pi / 2, np.pi / 2)
    search = F.gouge_search_model(1)
    p = np.r_[F.curve_params(ln), F.curve_params(arc)]
    uv = F.solve(search, p, np.array([0.9, 0.1]))
    assert uv[0] == pytest.approx([0.5, 1.0], abs=1e-7)


@pytest.mark.slow
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(contours(), st.data())
def test_search_never_deeper_on_random_contours(data, draw):
    # a random clean contour with one tool segment pushed into the part by a
    # random amount: the search must find that gouge and nothing deeper than
    # the certificate allows anywhere
    pts, bulges, r, k = data
    prog = contour_program(pts, bulges, r, k)
    path = compensate(prog, "pmac")
    targets = [i for i, s in enumerate(path.segments)
               if s.role in (Role.COMPENSATED, Role.CORNER) and s.length > 0]
    i = draw.draw(st.sampled_from(targets))
    push = draw.draw(st.floats(0.0, 0.3)) * r
    seg = path.segments[i]
    g = seg.geom
    if seg.role is Role.CORNER:
        g2 = Arc(g.center, g.radius - push, g.theta0, g.sweep)
    elif isinstance(g, Line):
        a, b = np.array(seg.block.start[:2]), np.array(seg.block.end[:2])
        n = np.array([-(b - a)[1], (b - a)[0]]) / np.linalg.norm(b - a)
        shift = -np.sign(np.dot(np.subtract(g.p0, a), n)) * push * n
        g2 = Line(tuple(np.add(g.p0, shift)), tuple(np.add(g.p1, shift)))
    else:
        R_e = float(np.hypot(*np.subtract(seg.block.start[:2], seg.block.center[:2])))
        g2 = Arc(g.center, g.radius + np.sign(R_e - g.radius) * push, g.theta0, g.sweep)
    segs = list(path.segments)
    segs[i] = replace(seg, geom=g2)
    # at the arithmetic's tolerance: a push below the default gouge tolerance
    # (1e-3 mm) must still be a violation the search agrees with
    cert = verify(replace(path, segments=tuple(segs)), prog, tolerance=0.0)
    res = F.crosscheck(cert)
    assert res["agree"] and res["deeper_than_certified"] == 0
    worst = max((v.depth for v in cert.violations_of("gouge")), default=0.0)
    assert res["deepest_gouge_found"] == pytest.approx(worst, abs=1e-6)
    if push > 1e-5:
        assert worst == pytest.approx(push, rel=1e-6)
