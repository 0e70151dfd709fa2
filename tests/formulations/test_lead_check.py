"""The optimised leads check each blend on the segments it changed
(:meth:`BlendProblem.check`) instead of certifying the whole path per lead
(:meth:`BlendProblem.accept`): the two must take the same decision, with the
same message, on every candidate the leads actually produce, accepted and
rejected ones (on fagor-g136-g138 the verifier rejects four of the two
variants' 22 candidates; sidechange-reversal's
PMAC host gouges beside the blend, the case ``_beside`` exists for).
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.cases import resolve_input
from ccopt.compare.contract import BlendProblem, BlendRejected
from ccopt.compare.registry import load


def _verdict(call, *args):
    try:
        call(*args)
    except BlendRejected as exc:
        return str(exc)
    return None


@pytest.mark.slow
@pytest.mark.parametrize("case", ["fagor-g136-g138", "sidechange-reversal", "profile"])
def test_local_check_decides_as_the_whole_certificate(case, monkeypatch):
    job = resolve_input(case)
    prog = job.read()
    ref = ccopt.compensate(prog, "pmac", radius=job.radius)
    problem = BlendProblem(prog, ref, job.limits(), radius=job.radius)
    local = BlendProblem.check
    seen = []

    def both(self, toolpath, segments):
        segments = list(segments)
        mine = _verdict(local, self, toolpath, segments)
        whole = _verdict(self.accept, toolpath, segments)
        seen.append((mine, whole))
        if mine is not None:
            raise BlendRejected(mine)

    monkeypatch.setattr(BlendProblem, "check", both)
    for variant in ("opt-casadi", "opt-cvxpy"):
        load(variant)(problem)
    assert seen, "no blend was checked"
    assert all(mine == whole for mine, whole in seen), seen
    if case == "fagor-g136-g138":
        assert any(mine is not None for mine, _ in seen)     # rejections compared too


def test_whole_certificate_of_the_optimised_variant_in_compare():
    # no certificate comes back from the leads now: compare certifies the path once
    job = resolve_input("leadin-inside-line")
    prog = job.read()
    cmp = ccopt.compare.compare(prog, ["pmac", "opt-casadi"], radius=job.radius)
    row = cmp["opt-casadi"]
    assert row.status == "ok"
    again = ccopt.verify(row.toolpath, prog, radius=job.radius)
    assert row.certificate.ok == again.ok
    assert row.figures["min_clearance"] == pytest.approx(again.min_clearance, abs=1e-12)
