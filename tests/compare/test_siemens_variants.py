"""The SINUMERIK lead families in ``compare``: listed, certified, and each
member chosen as the fastest certified of its set."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import compare
from ccopt.compare.contract import BUILTIN_NAMES, CONTROLLER_NAMES, SIEMENS_NAMES
from ccopt.compare.registry import available
from ccopt.compare.siemens_leads import DISR_FACTORS
from ccopt.program.sinumerik import read_sinumerik


def test_listed_as_builtins_the_style_a_baseline_its_families_not():
    # the style as the program asks is a controller's own path, a baseline of
    # the optimised blends (test_baseline.py); its approach families are
    # parameter searches, as HEIDENHAIN's APPR/DEP families are
    assert set(SIEMENS_NAMES) <= set(available())
    assert set(SIEMENS_NAMES) <= set(BUILTIN_NAMES)
    assert set(SIEMENS_NAMES) & set(CONTROLLER_NAMES) == {"siemens"}


@pytest.fixture(scope="module")
def leadin():
    c = find_case("leadin-inside-line")
    prog = ccopt.read_program(c.program)
    return compare(prog, ["pmac", *SIEMENS_NAMES], limits=ccopt.AxisLimits(c.vmax, c.amax))


def test_every_family_certified_with_its_fastest_member(leadin):
    rows = {r.name: r for r in leadin}
    assert rows["siemens"].status == "ok" and rows["siemens"].figures["certified"]
    for name in SIEMENS_NAMES[1:]:
        row = rows[name]
        assert row.status == "ok" and row.figures["certified"], (name, row.message)
        members = row.info["members"]
        timed = {k: v for k, v in members.items() if isinstance(v, float)}
        assert row.info["chosen"] == min(timed, key=timed.get)
        # the row's cycle time is the chosen member's (planned by the comparison)
        assert row.figures["duration"] == pytest.approx(timed[row.info["chosen"]], rel=1e-6)


def test_quadrant_family_leads_on_an_arc_of_the_chosen_disr(leadin):
    row = {r.name: r for r in leadin}["siemens-g247"]
    disr = float(row.info["chosen"].split("=")[1])
    r = row.toolpath.radius
    assert disr in [f * r for f in DISR_FACTORS["G247"]]
    arcs = [s for s in row.toolpath.segments if s.role.value in ("lead-in", "lead-out")
            and s.kind == "arc"]
    assert len(arcs) == 2
    for s in arcs:
        assert s.geom.radius == pytest.approx(disr) and abs(s.geom.sweep) == pytest.approx(
            math.pi / 2)


def test_an_arc_activation_is_refused_with_the_reason():
    # a SINUMERIK control activates compensation with G0/G1 only
    prog = read_sinumerik("G1 F600 X0 Y-20\nG41 G3 X0 Y0 CR=10\nG1 X20\nG40 X20 Y-20\n",
                          "arc.mpf")
    rows = {r.name: r for r in compare(prog, ["siemens-g147"], radius=1.0)}
    row = rows["siemens-g147"]
    assert row.status == "refused" and "must be linear" in row.message


def test_the_programmed_row_keeps_the_program_s_smooth_approach():
    c = find_case("sinumerik-sar-plate")
    prog = ccopt.read_program(c.program)
    rows = {r.name: r for r in compare(prog, ["pmac", "siemens", "siemens-norm"],
                                       limits=ccopt.AxisLimits(c.vmax, c.amax))}
    arcs = [s for s in rows["siemens"].toolpath.segments
            if s.role.value == "lead-in" and s.kind == "arc"]
    assert len(arcs) == 1 and arcs[0].geom.radius == pytest.approx(5.0)   # G247 DISR=5
    assert not [s for s in rows["siemens-norm"].toolpath.segments
                if s.role.value == "lead-in" and s.kind == "arc"]
