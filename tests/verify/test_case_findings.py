"""What the verifier finds on the bundled realistic parts, derived by hand."""
from __future__ import annotations

import math

import pytest
from scipy.optimize import minimize_scalar

import ccopt
from ccopt.cases import bundled_cases_dir, load_case
from ccopt.verify import verify


def test_profile_spiral_leadin_overcuts_the_plate_edge():
    # Lead-in spiral about (-10,15): rho(th) = 10 - 3*(th + pi/2)/(pi/2) for th
    # in [-pi/2, 0]. Its largest x is where d(rho cos th)/dth = 0; the plate
    # edge is x = 0 and r = 3, so the overcut is 3 + x_max.
    def x(th):
        return -10 + (10 - 3 * (th + math.pi / 2) / (math.pi / 2)) * math.cos(th)

    res = minimize_scalar(lambda th: -x(th), bounds=(-math.pi / 2, 0), method="bounded",
                          options={"xatol": 1e-14})
    depth = 3 + x(res.x)
    y = 15 + (10 - 3 * (res.x + math.pi / 2) / (math.pi / 2)) * math.sin(res.x)
    case = load_case(bundled_cases_dir() / "profile")
    assert case.expect == "gouge"
    prog = ccopt.read_program(case.program)
    cert = verify(ccopt.compensate(prog, "pmac"), prog)
    assert not cert.ok
    gouges = [v for v in cert.to_json()["violations"] if v["kind"] == "gouge"]
    roles = sorted(v["tool_role"] for v in gouges)
    assert roles == ["lead-in", "lead-out"]
    for v in gouges:
        # a certified bound: never shallower than the true depth, within eps of it
        assert depth - 1e-9 <= v["depth"] <= depth + 1e-6
        assert abs(v["witness_tool"][0] - x(res.x)) < 1e-4
    lead_in = next(v for v in gouges if v["tool_role"] == "lead-in")
    assert lead_in["witness_tool"][1] == pytest.approx(y, abs=1e-3)
    assert lead_in["tool_block"] == 9
