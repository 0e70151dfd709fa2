"""The plug-ins' up-front refusals hold on generated programs (issue 30).

A lead blend (opt-casadi, opt-cvxpy) refuses a start path that gouges away
from every lead, and the smoother one that gouges on what every corner blend
keeps, before any solve (``lead_setup.refuse_lasting``,
``smoother_joins.lasting_gouge``). Here the tests' CAM plates
(``tests/cam_programs.py``) get a rectangular slot cut into the part, as wide
as the cutter's radius and twice as deep, in the middle of their longest
straight contour move but the first and the last: any tool centre inside a
slot of width ``w < 2 r`` is within ``w / 2`` of a wall, a gouge of at least
``r - w / 2 = r / 2``, in segments well away from the leads (a straight move
and its neighbours lie between them). Asserted:

* PMAC's path gouges there by at least ``r / 2``, and every plug-in refuses
  it, saying so (quick: a few seeds; slow: three hundred);
* the refusals are sound: with them switched off, each plug-in's own result
  is still not certified and still gouges in the slot (slow, a few seeds:
  each runs the solvers).
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.compare.contract import BlendProblem, BlendRejected
from ccopt.compare.leads import find_leads, outside_leads
from ccopt.compare.registry import load

from cam_programs import cam_program

PLUG_INS = ("opt-casadi", "opt-cvxpy", "smooth")
LIMITS = ccopt.AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0))
REFUSED = {"opt-casadi": "not certified away from its leads",
           "opt-cvxpy": "not certified away from its leads",
           "smooth": "gouges beyond the reach of every blend"}


def _slotted(seed: int):
    cp = cam_program(seed)
    text, (first, last) = cp.notched(cp.radius, 2.0 * cp.radius)
    prog = ccopt.read_text(text, cp.file, cp.dialect, tool_table=cp.tool_table)
    ref = ccopt.compensate(prog, "pmac")
    cert = ccopt.verify(ref, prog)
    return cp, prog, ref, cert, range(first, last + 1)


def _slot_gouges(violations, slot_lines):
    return [v for v in violations if v.kind == "gouge" and v.element_block in slot_lines]


def check_refused(seed: int) -> None:
    cp, prog, ref, cert, slot = _slotted(seed)
    away = outside_leads(cert.violations, find_leads(ref))
    deepest = max((v.depth for v in _slot_gouges(away, slot)), default=0.0)
    assert deepest >= 0.5 * cp.radius - 1e-9, cp.description
    problem = BlendProblem(prog, ref, LIMITS, reference_certificate=cert)
    for name in PLUG_INS:
        with pytest.raises(BlendRejected, match=REFUSED[name]):
            load(name)(problem)


@pytest.mark.parametrize("seed", [0, 3, 9])
def test_slotted_plates_are_refused(seed):
    check_refused(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 400))
def test_slotted_plates_are_refused_generated(seed):
    check_refused(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 2, 4, 6, 7, 8])
def test_refusals_are_sound(seed, monkeypatch):
    from ccopt_formulations import lead_setup, smoother

    monkeypatch.setattr(lead_setup, "refuse_lasting", lambda problem, leads: None)
    monkeypatch.setattr(smoother, "lasting_gouge", lambda *args: None)
    cp, prog, ref, cert, slot = _slotted(seed)
    problem = BlendProblem(prog, ref, LIMITS, reference_certificate=cert)
    made = 0
    for name in PLUG_INS:
        try:
            out = load(name)(problem)
        except BlendRejected:
            continue                 # no blend at all (seed 6: spiral hosts): nothing to certify
        made += 1
        got = ccopt.verify(out.toolpath, prog)
        assert not got.ok, (cp.description, name)
        deepest = max((v.depth for v in _slot_gouges(got.violations, slot)), default=0.0)
        assert deepest >= 0.5 * cp.radius - 1e-9, (cp.description, name)
    assert made, cp.description
