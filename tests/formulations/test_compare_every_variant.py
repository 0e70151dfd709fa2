"""``ccopt compare`` with every registered variant (built-ins, the optimised
leads and the smoother) on the two realistic parts: each is listed, and each
one that ran has every figure."""
from __future__ import annotations

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import FIGURES, available, compare

pytestmark = pytest.mark.slow  # the quick tier (-m "not slow") leaves these out

OPTIMISED = ("opt-casadi", "opt-cvxpy", "smooth")


@pytest.mark.parametrize("case", ["pocket", "profile"])
def test_every_variant_listed_with_every_figure(case):
    c = find_case(case)
    prog = ccopt.read_program(c.program)
    cmp = compare(prog, limits=ccopt.AxisLimits(c.vmax, c.amax))
    doc = cmp.to_json()
    names = [v["name"] for v in doc["variants"]]
    assert names == available()
    assert set(OPTIMISED) <= set(names)
    for v in doc["variants"]:
        assert set(FIGURES) <= set(v), v["name"]
        if v["status"] == "ok":
            missing = [k for k in FIGURES if v[k] is None]
            assert not missing, (v["name"], missing)
        elif v["status"] == "uncertified":
            # a path the verifier does not certify is not ok (issue 29): profile's
            # PMAC spiral lead-in gouges; its figures are there and it says why
            assert v["certified"] is False and v["message"].startswith("not certified"), v
            assert not [k for k in FIGURES if v[k] is None], v
        else:
            # a controller that refuses the program says why (profile: LinuxCNC
            # and Fagor reject its CIRCLE lead-in and lead-out)
            assert v["status"] == "refused" and v["message"], v
    for name in OPTIMISED:
        row = cmp[name]
        # a row is ok only when its path is certified (issue 29): on profile the
        # smoother keeps PMAC's gouging spiral lead-in (it stays within its band of
        # PMAC's path), so its row is uncertified there and says why
        want = "uncertified" if (case, name) == ("profile", "smooth") else "ok"
        assert row.status == want, (name, row.message)
        # a blend no faster than the fastest certified controller variant is
        # reported as that variant's path (issue 30); its own figures stay in info
        own = row.info.get("optimised")
        fig = own["figures"] if own is not None else row.figures
        assert fig["continuity"] == "G2"
