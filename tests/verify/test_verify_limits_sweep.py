"""Acceptance (issue 16): a parameter sweep over the bundled cases -- cutter
radius in {1, 2}, limits 100/1000 and 50/500 per axis -- has no limits
failure on ccopt's own TOPPRA profiles.

Checked twice: with the public API (plan_feed, verify with the profile), and
through ``ccopt sweep`` on a spec of the same settings. Both also hold the
planner to its limits outright (largest sampled ratio 1 up to toppra's
rounding), not only within the verifier's 1e-3 tolerance: before the planner
checked its intervals inside, 11 tasks of ``sweeps/styles-radii.toml`` and 3
settings here rode 1.0003 times the acceleration limit.
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.cases import bundled_cases
from ccopt.errors import CompensationError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.verify import verify

#: toppra's seidel solver holds its constraints to about 1e-9 relative
ROUNDING = 1e-8

OK_CASES = [c for c in bundled_cases() if c.expect == "ok"]
RADII = (1.0, 2.0)
LIMITS = {"100/1000": (100.0, 1000.0), "50/500": (50.0, 500.0)}


@pytest.mark.slow
def test_no_limits_failure_on_toppra_profiles():
    seen = 0
    for case in OK_CASES:
        prog = ccopt.read_program(case.program)
        for radius in RADII:
            try:
                path = ccopt.compensate(prog, case.style, radius=radius)
            except CompensationError:
                continue                     # a style refusing the radius is no limits failure
            for name, (v, a) in LIMITS.items():
                prof = plan_feed(path, AxisLimits((v,) * 3, (a,) * 3), planner="toppra")
                cert = verify(path, prog, prof, radius=radius)
                lim = cert.check("limits")
                where = (case.name, radius, name)
                assert cert.limits_ok, (where, lim.figure)
                assert lim.figure <= 1.0 + ROUNDING, (where, lim.figure)
                assert lim.figure > 0.99, where   # the plan rides its limits
                seen += 1
    # every ok case at both radii (no style refuses them)
    assert seen == len(OK_CASES) * len(RADII) * len(LIMITS)


@pytest.mark.slow
def test_through_ccopt_sweep(tmp_path):
    names = ", ".join(f'"{c.name}"' for c in OK_CASES)
    spec = tmp_path / "limits.toml"
    spec.write_text(
        f"programs = [{names}]\nplanners = [\"toppra\"]\n[axes]\nradius = [1.0, 2.0]\n"
        "limits = [\n"
        "    { name = \"fast\", v = [100, 100, 100], a = [1000, 1000, 1000] },\n"
        "    { name = \"slow\", v = [50, 50, 50], a = [500, 500, 500] },\n]\n")
    table = ccopt.sweep(str(spec), serial=True, out=tmp_path / "out")
    assert len(table) == len(OK_CASES) * 4
    assert table["error"].isna().all(), table.loc[table["error"].notna(), "error"].tolist()
    assert table["limits_ok"].all()
    assert table["limits_ratio"].max() <= 1.0 + ROUNDING
    assert table["geometry_ok"].all() and table["ok"].all()
