"""The comparison on the bundled cases, built-in variants (no optimiser needed)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import FIGURES, compare
from ccopt.compare.contract import BUILTIN_NAMES


def _run(case):
    c = find_case(case)
    prog = ccopt.read_program(c.program)
    return prog, compare(prog, BUILTIN_NAMES, limits=ccopt.AxisLimits(c.vmax, c.amax))


@pytest.fixture(scope="module")
def pocket():
    return _run("pocket")


@pytest.fixture(scope="module")
def profile():
    return _run("profile")


@pytest.mark.slow
def test_every_variant_listed_with_every_figure(pocket, profile):
    for _, cmp in (pocket, profile):
        doc = cmp.to_json()
        assert [v["name"] for v in doc["variants"]] == list(BUILTIN_NAMES)
        for v in doc["variants"]:
            assert set(FIGURES) <= set(v)
            if v["status"] == "ok":
                assert all(v[k] is not None for k in FIGURES), v["name"]


def test_pocket_reference(pocket):
    prog, cmp = pocket
    pmac = cmp["pmac"]
    # the reference's own TOPPRA time under the case's limits
    c = find_case("pocket")
    d = ccopt.plan_feed(ccopt.compensate(prog, "pmac"), ccopt.AxisLimits(c.vmax, c.amax)).duration
    assert pmac.figures["duration"] == pytest.approx(d, rel=1e-12)
    assert pmac.figures["duration_ratio"] == pytest.approx(1.0)
    assert pmac.figures["certified"] and pmac.figures["min_clearance"] == pytest.approx(3.0)
    # PMAC's inside lead-in meets the contour at a corner: a tangent break
    assert pmac.figures["continuity"] == "G0"
    assert pmac.figures["max_deviation"] == 0.0
    # concave corners R6 with r = 3: tool arcs of radius 3
    assert pmac.figures["max_curvature"] == pytest.approx(1 / 3)


def test_pocket_fagor_g139_is_pmac(pocket):
    # spec: an inside corner at start or end behaves as G138 (PMAC's diagonal), and G136
    # outside corners are PMAC's arcs; the pocket has no shallow outside corner
    _, cmp = pocket
    for name in ("fagor-g138", "fagor-g139-g136"):
        assert cmp[name].figures["length"] == pytest.approx(cmp["pmac"].figures["length"])
        assert cmp[name].figures["duration"] == pytest.approx(cmp["pmac"].figures["duration"])
    # G137 replaces each 90-degree arc about the boss corners (r * pi/2) by two legs of r
    g137 = cmp["fagor-g139-g137"].figures["length"]
    assert g137 - cmp["pmac"].figures["length"] == pytest.approx(2 * (2 * 3.0 - 1.5 * math.pi))


def test_profile_controllers_refuse_arc_leads(profile):
    _, cmp = profile
    # LinuxCNC: the move after G40 must be straight; Fagor: activation must be linear
    assert cmp["linuxcnc"].status == "refused" and "must be straight" in cmp["linuxcnc"].message
    for name in ("fagor-g138", "fagor-g139-g136", "fagor-g139-g137"):
        assert cmp[name].status == "refused" and "must be linear" in cmp[name].message
    for name in ("tangent-arc", "line-arc"):
        assert cmp[name].status == "ok"
    # PMAC's spiral lead-in gouges (below): one meaning of ok (issue 29), its row says why
    assert cmp["pmac"].status == "uncertified" and not cmp["pmac"].figures["certified"]
    assert cmp["pmac"].message.startswith("not certified: gouge failed")


def test_profile_pmac_spiral_lead_gouges(profile):
    # PMAC's CIRCLE lead-in: a spiral about (-10, 15) from radius 10 at (-10, 5) to radius 7
    # at (-3, 15) (spec: radius changes linearly with angle). It comes closer than r = 3
    # to the last contour element, the line X0 from (0, 0) to (0, 15): distance -x.
    _, cmp = profile
    th = np.linspace(-math.pi / 2, 0.0, 200001)
    rho = 10.0 - 3.0 * (th + math.pi / 2) / (math.pi / 2)
    x = -10.0 + rho * np.cos(th)
    y = 15.0 + rho * np.sin(th)
    d = np.where((y >= 0) & (y <= 15), -x, np.inf)
    pmac = cmp["pmac"]
    assert not pmac.figures["certified"]
    assert pmac.figures["min_clearance"] == pytest.approx(float(d.min()), abs=1e-6)
    # the geometric leads replace the spiral and keep the clearance
    for name in ("tangent-arc", "line-arc"):
        assert cmp[name].figures["certified"]
        assert cmp[name].figures["min_clearance"] >= 3.0 - 1e-6


def test_plot_keeps_the_callers_backend(tmp_path):
    """Writing the comparison's plot neither switches matplotlib's backend (a
    notebook's inline figures would stop showing) nor leaves a pyplot figure
    open; the file is a PNG with the programmed contour and both variants."""
    import matplotlib
    import matplotlib.pyplot as plt

    from ccopt.compare.plot import plot_comparison

    c = find_case("leadin-outside-line")
    prog = ccopt.read_program(c.program)
    cmp = compare(prog, ["pmac", "tangent-arc"], limits=ccopt.AxisLimits(c.vmax, c.amax))
    before = matplotlib.get_backend()
    matplotlib.use("svg")                    # any backend other than Agg
    try:
        out = plot_comparison(cmp, tmp_path / "variants.png")
        assert matplotlib.get_backend() == "svg"
        assert plt.get_fignums() == []
    finally:
        matplotlib.use(before)
    data = (tmp_path / "variants.png").read_bytes()
    assert out == str(tmp_path / "variants.png")
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
