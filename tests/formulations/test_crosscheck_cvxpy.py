"""CVXPY cross-check: SOCP distances against the closed forms, and the entry point."""
from __future__ import annotations

from importlib.metadata import entry_points

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compensate import compensate
from ccopt.geometry.distance import point_segment, segment_segment
from ccopt.verify import verify
from ccopt.verify.crosschecks import available, run_crosschecks
from ccopt_formulations import crosscheck_cvxpy as F


def test_socp_segment_segment_agrees_with_the_closed_form_on_1000_pairs():
    rng = np.random.default_rng(0)
    n = 1000
    a0, a1, b0, b1 = (rng.uniform(-10, 10, (n, 2)) for _ in range(4))
    # a tenth of the pairs cross, a tenth are parallel, a few are points
    b1[:100] = 2 * a0[:100] - b0[:100] + rng.uniform(-0.1, 0.1, (100, 2))
    b1[100:200] = b0[100:200] + (a1[100:200] - a0[100:200]) * 0.5
    a1[200:210] = a0[200:210]
    model = F.segment_segment_model(a0, a1, b0, b1)
    d = F.solve(model)
    assert np.abs(d - segment_segment(a0, a1, b0, b1)[0]).max() <= 1e-6


def test_socp_segment_disk_agrees_with_the_closed_form_on_1000_pairs():
    # distance to a disk = max(0, distance to its centre - R)
    rng = np.random.default_rng(1)
    n = 1000
    a0, a1, c = (rng.uniform(-10, 10, (n, 2)) for _ in range(3))
    R = rng.uniform(0.1, 6.0, n)
    d = F.solve(F.segment_disk_model(a0, a1, c, R))
    want = np.maximum(point_segment(c, a0, a1)[0] - R, 0.0)
    assert np.abs(d - want).max() <= 1e-6
    assert (want == 0).sum() > 50 and (want > 0).sum() > 50


def test_model_and_solver_are_separate():
    m = F.segment_segment_model([[0, 0]], [[1, 0]], [[0, 1]], [[1, 2]])
    assert m.problem.status is None            # built, not solved
    assert F.solve(m, "CLARABEL")[0] == pytest.approx(1.0, abs=1e-9)
    m2 = F.segment_segment_model([[0, 0]], [[1, 0]], [[0, 1]], [[1, 2]])
    assert F.solve(m2, "SCS", eps=1e-9)[0] == pytest.approx(1.0, abs=1e-5)


def test_registered_as_an_entry_point():
    eps = {e.name: e.value for e in entry_points(group="ccopt.crosschecks")}
    assert eps["cvxpy"] == "ccopt_formulations.crosscheck_cvxpy:crosscheck"
    assert "cvxpy" in available()


def test_crosscheck_on_a_case_agrees():
    case = find_case("pocket")
    prog = ccopt.read_program(case.program)
    cert = verify(compensate(prog, "pmac"), prog)
    res = run_crosschecks(cert, names={"cvxpy"})
    assert len(res) == 1 and res[0]["name"] == "cvxpy"
    assert res[0]["agree"] and res[0]["pairs"] > 0
    assert res[0]["max_abs_difference"] <= 1e-6
