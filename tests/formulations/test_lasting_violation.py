"""An optimised lead blend is not solved when the path it starts from gouges
away from every lead: no blend of the leads can make that path certified, so
the row says so at once (LinuxCNC's crazy-paths spent minutes of IPOPT on
such leads). Gouges *at* a lead are the blends' to remove; they still run
(``test_opt_blends.py::test_leads_stay_local_on_the_fagor_episodes``)."""
from __future__ import annotations

import pytest

import ccopt
from ccopt.compare import compare
from ccopt.compare.contract import BlendProblem

# An outside profile of a 40 x 40 mm square (G41 cut clockwise, lead-in and
# lead-out perpendicular at the middle of the bottom edge) with a notch 1 mm
# wide and 10 mm deep in its top edge (lines 7-9), for a cutter of 3 mm
# diameter: the notch is narrower than the cutter, so any tool path that
# follows it comes within 0.5 mm of one wall, a gouge of at least 1.0 mm,
# 30 mm and more away from the leads.
NOTCH = """G21 G17 G90 G94
G0 X20 Y-10
G41.1 D3 G1 X20 Y0 F600
G1 X0 Y0
G1 X0 Y40
G1 X18 Y40
G1 X18 Y30
G1 X19 Y30
G1 X19 Y40
G1 X40 Y40
G1 X40 Y0
G1 X20 Y0
G40 G1 X20 Y-10
M2
"""


@pytest.fixture(scope="module")
def notch():
    return ccopt.read_text(NOTCH, "notch.ngc", "gcode")


@pytest.mark.parametrize("name", ["opt-casadi", "opt-cvxpy"])
def test_lead_blends_refuse_a_path_that_gouges_away_from_its_leads(notch, name):
    cmp = compare(notch, ["pmac", name], limits=ccopt.AxisLimits((100, 100, 100),
                                                                  (1000, 1000, 1000)))
    ref = cmp["pmac"]
    assert ref.status == "uncertified"
    deepest = max(v.depth for v in ref.certificate.violations if v.kind == "gouge")
    assert deepest >= 1.0 - 1e-9
    row = cmp[name]
    assert row.status == "rejected"
    assert "not certified away from its leads" in row.message
    line = int(row.message.split(" at line ")[1].split(",")[0])
    assert 6 <= line <= 10          # the notch and the edge it cuts into


def test_reference_verdict_is_the_given_certificate(notch):
    ref = ccopt.compensate(notch, "pmac")
    cert = ccopt.verify(ref, notch)
    problem = BlendProblem(notch, ref, reference_certificate=cert)
    assert problem.reference_verdict is cert
    made = BlendProblem(notch, ref).reference_verdict
    assert made.ok == cert.ok and len(made.violations) == len(cert.violations)


def test_smoother_refuses_a_path_that_gouges_on_what_every_blend_keeps(notch):
    # PMAC's path runs down the notch's right wall at x = 19.5 (its walls are at
    # x = 18 and 19): 0.5 mm from the wall x = 19 over the notch's depth, a
    # gouge of 1.0 mm for the 1.5 mm cutter radius, in the middle of a segment
    # 8.5 mm long, which no corner blend within the band (1 % of the radius) reaches
    cmp = compare(notch, ["pmac", "smooth"], limits=ccopt.AxisLimits((100, 100, 100),
                                                                      (1000, 1000, 1000)))
    row = cmp["smooth"]
    assert row.status == "rejected"
    assert "gouges beyond the reach of every blend" in row.message
    depth = float(row.message.split("(gouge ")[1].split()[0])
    assert depth >= 1.0 - 1e-9


def test_siemens_smooth_approach_members_share_their_faults_away_from_the_leads(notch):
    # the family stops at its first member when that member gouges away from its
    # leads, because every member (another DISR) differs only at the leads: here
    # each member's faults away from its leads are checked to be the same ones
    from ccopt.compare.leads import find_leads, outside_leads
    from ccopt.compare.siemens_leads import DISR_FACTORS
    r = 1.5
    for kind, factors in DISR_FACTORS.items():
        seen = []
        for f in factors:
            if f * r <= 0 and kind != "G147":
                continue
            path = ccopt.compensate(notch, "siemens", sar=kind, disr=f * r)
            cert = ccopt.verify(path, notch)
            out = outside_leads(cert.violations, find_leads(path))
            seen.append(sorted((v.kind, v.tool_block, round(v.depth, 9)) for v in out))
        assert seen[0] and all(s == seen[0] for s in seen), kind
    row = compare(notch, ["siemens-g247"], limits=ccopt.AxisLimits((100, 100, 100),
                                                                   (1000, 1000, 1000)))
    row = row["siemens-g247"]
    assert row.status == "rejected" and "every member shares" in row.message
