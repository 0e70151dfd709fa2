"""HEIDENHAIN's APPR/DEP leads as compare variants, against hand-derived
geometry: the pocket case's lead-in reaches the contour at J = (3, 20)
going -Y with the free side left (+X), r = 3 (test_leads_geometric)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import BlendProblem, compare, load
from ccopt.compare.contract import BUILTIN_NAMES, CONTROLLER_NAMES
from ccopt.compare.leads import find_leads
from ccopt.compare.tnc_leads import PARAMETER_FACTORS
from ccopt.feed import certified_planner, plan_feed
from ccopt.geometry import Arc, Line
from ccopt.toolpath import Role, ToolPath

LIMITS = ccopt.AxisLimits(v=[100, 100, 100], a=[1000, 1000, 1000])


@pytest.fixture(scope="module")
def pocket():
    prog = ccopt.read_program(find_case("pocket").program)
    return prog, ccopt.compensate(prog, "pmac")


def _lead_in(path):
    segs = path.segments
    ld = find_leads(path)[0]
    return [s for s in segs[ld.first:ld.host]], segs[ld.host]


def test_the_variants_are_listed_and_heidenhain_is_a_controller():
    for name in ("heidenhain", "heidenhain-lt", "heidenhain-ln", "heidenhain-ct",
                 "heidenhain-lct"):
        assert name in BUILTIN_NAMES
    assert "heidenhain" in CONTROLLER_NAMES and "heidenhain-lt" not in CONTROLLER_NAMES


def test_lt_ln_ct_lead_in_geometry(pocket):
    prog, ref = pocket
    problem = BlendProblem(prog, ref, LIMITS)
    J, t, n = np.array([3.0, 20.0]), np.array([0.0, -1.0]), np.array([1.0, 0.0])
    out = load("heidenhain-lt")(problem)
    lead, host = _lead_in(out.toolpath)
    LEN = out.info["parameters"][0]["parameter"]
    assert LEN in [f * 3.0 for f in PARAMETER_FACTORS]
    # straight from the approach point (20, 20) to PH = J - LEN*t, then along t onto J
    assert lead[0].geom.start == pytest.approx((20.0, 20.0))
    assert lead[-1].geom.start == pytest.approx(tuple(J - LEN * t))
    assert lead[-1].geom.end == pytest.approx(tuple(J)) and host.geom.start == pytest.approx(tuple(J))
    out = load("heidenhain-ln")(problem)
    lead, _ = _lead_in(out.toolpath)
    LEN = out.info["parameters"][0]["parameter"]
    assert lead[-1].geom.start == pytest.approx(tuple(J + LEN * n))
    out = load("heidenhain-ct")(problem)
    lead, _ = _lead_in(out.toolpath)
    R = out.info["parameters"][0]["parameter"]
    arc = lead[-1].geom
    # quarter circle about J + R*n, counter-clockwise (free side left), from J + R*n + R*t
    assert isinstance(arc, Arc) and arc.center == pytest.approx(tuple(J + R * n))
    assert arc.sweep == pytest.approx(math.pi / 2)
    assert arc.start == pytest.approx(tuple(J + R * n - R * t))


def _time(segs, ref):
    part = ToolPath(tuple(segs), plane=ref.plane, style="t", radius=ref.radius, units=ref.units)
    return plan_feed(part, LIMITS, planner=certified_planner(LIMITS)).duration


def test_lt_keeps_the_fastest_certified_member(pocket):
    """Each LT member built here by hand (line to J - LEN*t, line to J), timed
    from rest to rest with the host; the variant's LEN has the least time."""
    prog, ref = pocket
    out = load("heidenhain-lt")(BlendProblem(prog, ref, LIMITS))
    chosen = out.info["parameters"][0]["parameter"]
    _, host = _lead_in(ref)
    J, t = np.array(host.geom.start), np.array(host.geom.start_tangent)
    src = ref.segments[find_leads(ref)[0].first]
    times = {}
    for f in PARAMETER_FACTORS:
        LEN = 3.0 * f
        S = J - LEN * t
        segs = [src.__class__(Line((20.0, 20.0), tuple(S)), Role.LEAD_IN, src.block,
                              src.w0, src.w1, src.feed),
                src.__class__(Line(tuple(S), tuple(J)), Role.LEAD_IN, src.block,
                              src.w1, src.w1, src.feed), host]
        times[LEN] = _time(segs, ref)
    assert times[chosen] == pytest.approx(min(times.values()), rel=1e-6)
    assert ccopt.verify(out.toolpath, prog).ok


def test_compare_rows_on_a_klartext_plate():
    prog = ccopt.read_text(
        "0 BEGIN PGM P MM\n1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n"
        "3 L X-20 Y-20 R0 FMAX\n4 L X+0 Y+0 RL F600\n5 L X+0 Y+40\n6 L X+40 Y+40\n"
        "7 L X+40 Y+0\n8 L X+0 Y+0\n9 L X-20 Y-20 R0\n10 END PGM P MM\n", "p.h", "heidenhain")
    names = ["pmac", "heidenhain", "heidenhain-lt", "heidenhain-ln", "heidenhain-ct",
             "heidenhain-lct"]
    cmp = compare(prog, names, limits=LIMITS)
    rows = {r.name: r for r in cmp}
    assert set(rows) == set(names)
    for name in names:
        assert rows[name].status in ("ok", "rejected", "uncertified")
        assert rows[name].status == "ok" or rows[name].message
    assert rows["heidenhain"].status == "ok"


def _apps(seed: int):
    """Random lead geometries (the host's start ``J``, its tangent, the free
    side, the approach point outside the lead circle) and a radius."""
    from ccopt.compare.leads import LeadGeometry
    rng = np.random.default_rng(seed)
    J = rng.uniform(-50, 50, 2)
    phi = rng.uniform(-math.pi, math.pi)
    t = np.array([math.cos(phi), math.sin(phi)])
    side = int(rng.choice([-1, 1]))
    R = float(rng.uniform(0.3, 8.0))
    n = side * np.array([-t[1], t[0]])
    # the approach point somewhere on the free side, outside the circle about J + R n
    while True:
        A = J + rng.uniform(-4, 4) * R * t + rng.uniform(0.2, 6) * R * n
        if np.linalg.norm(A - (J + R * n)) > 1.05 * R:
            break
    host = Line(tuple(J), tuple(J + 10 * t))
    return LeadGeometry((float(A[0]), float(A[1])), host, side, 600.0, "in"), R


@pytest.mark.parametrize("seed", range(40))
def test_ct_and_lct_are_the_tncs_appr_paths(seed):
    """The CT (CCA 90 degrees) and LCT members are the geometric leads'
    constructions at radius R (tangent-arc, line-arc), which a comparison times
    once; here against the TNC's own APPR construction, as the Klartext reader
    builds it (:func:`ccopt.program.heidenhain.contour.approach`), to 1e-9."""
    from ccopt.compare.tnc_leads import build
    from ccopt.program.heidenhain import contour
    lg, R = _apps(seed)
    J = tuple(lg.host.start)
    for kind in ("CT", "LCT"):
        ph, pieces = contour.approach(kind, lg.approach, J, tuple(lg.host.start_tangent),
                                      lg.side, 0.0, None, R, 90.0 if kind == "CT" else None)
        geoms = build(kind, lg, R)
        assert len(geoms) == 1 + len(pieces), kind
        assert geoms[0].start == pytest.approx(lg.approach, abs=1e-9)
        assert geoms[0].end == pytest.approx(ph, abs=1e-9)
        for g, (_, s, e, c, sweep) in zip(geoms[1:], pieces):
            assert isinstance(g, Arc) and g.center == pytest.approx(c, abs=1e-9)
            assert g.radius == pytest.approx(R, abs=1e-9)
            assert g.start == pytest.approx(s, abs=1e-9) and g.end == pytest.approx(e, abs=1e-9)
            assert g.sweep == pytest.approx(sweep, abs=1e-9)


def test_ct_and_lct_at_the_cutter_radius_are_the_geometric_leads_paths(pocket):
    """Where CT and LCT keep R = the cutter radius (the geometric leads' default
    radius) their paths are tangent-arc's and line-arc's, segment for segment,
    so the comparison times each once; a parallel comparison's rows agree."""
    from ccopt.compare.timing import timed_alike
    prog, _ = pocket
    names = ["pmac", "tangent-arc", "line-arc", "heidenhain-ct", "heidenhain-lct"]
    cmp = compare(prog, names, limits=LIMITS, workers=2)
    r = cmp["pmac"].toolpath.radius
    for geometric_name, tnc_name in (("tangent-arc", "heidenhain-ct"),
                                     ("line-arc", "heidenhain-lct")):
        tnc, geo = cmp[tnc_name], cmp[geometric_name]
        assert tnc.status == geo.status == "ok"
        # the pocket's leads keep R = r (the premise of this test)
        assert [p["parameter"] for p in tnc.info["parameters"]] == [r, r], tnc_name
        assert timed_alike(tnc.toolpath, geo.toolpath), tnc_name
        assert tnc.figures["duration"] == geo.figures["duration"]
