"""Geometry and limits as separate verdicts, and the limits check's stated
relative tolerance (issue 16, build item 3).

A profile whose axis acceleration rides its limit 0.05 % over passes at the
default tolerance (1e-3) and fails at 1e-4; either way the path's geometry
is right, so ``geometry_ok`` holds while ``limits_ok`` follows the tolerance.
A path that gouges is the converse: geometry fails, limits hold.
"""
from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.cli import main
from ccopt.verify import verify
from ccopt.verify.limits import LIMITS_TOL

#: the sample's acceleration over its limit: 0.05 %, between 1e-4 and 1e-3
OVER = 5e-4


def riding_samples(over: float = OVER):
    """Two axes, limits v = (10, 10), a = (100, 100); the X acceleration is
    100 * (1 + over) on samples 4..6, everything else well inside."""
    t = np.arange(10) * 0.01
    vel = np.full((10, 2), 5.0)
    acc = np.zeros((10, 2))
    acc[4:7, 0] = 100.0 * (1.0 + over)
    return SimpleNamespace(t=t, velocity=vel, acceleration=acc, v_limit=np.array([10.0, 10.0]),
                           a_limit=np.array([100.0, 100.0]))


def clean_case():
    case = find_case("leadin-outside-line")
    prog = ccopt.read_program(case.program)
    return prog, ccopt.compensate(prog, case.style)


def test_default_tolerance_is_one_in_a_thousand():
    assert LIMITS_TOL == 1e-3
    prog, path = clean_case()
    cert = verify(path, prog, riding_samples())
    lim = cert.check("limits")
    assert lim.tolerance == 1e-3 and cert.limits_tol == 1e-3
    assert lim.figure == pytest.approx(1.0 + OVER, rel=1e-12)
    assert cert.ok and cert.limits_ok and cert.geometry_ok


def test_a_tighter_tolerance_fails_the_limits_only():
    prog, path = clean_case()
    cert = verify(path, prog, riding_samples(), limits_tol=1e-4)
    assert not cert.ok and not cert.limits_ok and cert.geometry_ok
    (v,) = cert.violations
    assert v.kind == "acceleration" and v.detail["samples"] == 3
    assert v.depth == pytest.approx(OVER, rel=1e-9)
    data = json.loads(json.dumps(cert.to_json()))
    assert (data["ok"], data["geometry_ok"], data["limits_ok"], data["limits_tol"]) == \
        (False, True, False, 1e-4)
    first = cert.summary().splitlines()[0]
    assert first.startswith("verification FAILED (geometry ok, limits FAIL at tolerance 0.0001)")


def test_a_gouge_fails_the_geometry_only():
    # short-move-overcut: PMAC's documented overcut of 1 mm (docs/commands.md)
    case = find_case("short-move-overcut")
    prog = ccopt.read_program(case.program)
    cert = verify(ccopt.compensate(prog, case.style), prog, riding_samples(0.0))
    assert not cert.ok and not cert.geometry_ok and cert.limits_ok
    assert cert.check("gouge").figure == pytest.approx(-1.0, abs=1e-9)
    assert cert.to_json()["geometry_ok"] is False and cert.to_json()["limits_ok"] is True


def test_no_profile_limits_not_run():
    prog, path = clean_case()
    cert = verify(path, prog)
    assert cert.limits_ok and cert.geometry_ok and cert.ok
    assert "(geometry ok, limits not run)" in cert.summary().splitlines()[0]


@pytest.mark.parametrize("bad", [-1e-3, float("inf"), float("nan")])
def test_bad_tolerance_is_refused(bad):
    prog, path = clean_case()
    with pytest.raises(ccopt.ProgramError, match="limits_tol"):
        verify(path, prog, riding_samples(), limits_tol=bad)


def test_cli_feed_and_limits_tol(capsys):
    # TOPPRA's profile rides its limits to rounding: the largest ratio is 1
    code = main(["verify", "leadin-outside-line", "--feed", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["limits_ok"] and data["geometry_ok"] and data["limits_tol"] == 1e-3
    lim = [c for c in data["checks"] if c["name"] == "limits"][0]
    assert lim["basis"] == "sampled" and lim["figure"] == pytest.approx(1.0, abs=1e-6)
    code = main(["verify", "leadin-outside-line", "--feed", "--limits-tol", "0.01"])
    out = capsys.readouterr().out
    assert code == 0 and "(geometry ok, limits ok at tolerance 0.01)" in out
    # half the case's limits on the command line: the profile is planned under them
    code = main(["verify", "leadin-outside-line", "--feed", "--vmax", "25,25,10", "--json"])
    assert code == 0 and json.loads(capsys.readouterr().out)["limits_ok"]


@pytest.mark.parametrize("value", ["-1", "nan", "x"])
def test_cli_bad_limits_tol_is_exit_2(capsys, value):
    with pytest.raises(SystemExit) as exc:
        main(["verify", "leadin-outside-line", "--limits-tol", value])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--limits-tol" in err and len(err.strip().splitlines()) == 1
