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
    every = [v for v in cert.to_json()["violations"] if v["kind"] == "gouge"]
    # the plate edge x = 0 is two moves, lines 20 (y 0..15) and 10 (y 15..25),
    # joined at (0, 15) where the loop closes: each lead is reported against
    # both, deepest against the one its witness lies beside
    assert {v["element_block"] for v in every} == {10, 20}
    gouges = [max((v for v in every if v["tool_role"] == role), key=lambda v: v["depth"])
              for role in ("lead-in", "lead-out")]
    assert sorted(v["tool_role"] for v in every) == ["lead-in", "lead-in", "lead-out", "lead-out"]
    for v in gouges:
        # a certified bound: never shallower than the true depth, within eps of it
        assert depth - 1e-9 <= v["depth"] <= depth + 1e-6
        assert abs(v["witness_tool"][0] - x(res.x)) < 1e-4
    lead_in = next(v for v in gouges if v["tool_role"] == "lead-in")
    assert lead_in["witness_tool"][1] == pytest.approx(y, abs=1e-3)
    assert lead_in["tool_block"] == 9
