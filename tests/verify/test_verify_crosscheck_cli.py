"""``ccopt verify --crosscheck``: the registered CVXPY and CasADi formulations
re-derive the certificate's distances; their verdict sets the exit code too."""
from __future__ import annotations

import json

import pytest

from ccopt.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_crosschecks_agree_on_a_clean_case(capsys):
    code, out, err = run(capsys, "verify", "pocket", "--crosscheck")
    assert code == 0, err
    assert "cross-check casadi: agrees" in out
    assert "cross-check cvxpy: agrees" in out


def test_crosschecks_on_the_overcut(capsys):
    # short-move-overcut: the 1 mm step under a 2 mm cutter runs its offset
    # backwards to 1 mm from the first move, a gouge of r - 1 = 1. The CasADi
    # search finds that depth; the SOCPs reproduce the closed forms.
    code, out, _ = run(capsys, "verify", "short-move-overcut", "--crosscheck", "--json")
    assert code == 1                              # the gouge, not the cross-checks
    doc = json.loads(out)
    xs = {x["name"]: x for x in doc["crosschecks"]}
    assert set(xs) == {"casadi", "cvxpy"}
    assert all(x["agree"] for x in xs.values())
    assert xs["casadi"]["deepest_gouge_found"] == pytest.approx(1.0, abs=1e-9)
    assert xs["cvxpy"]["max_abs_difference"] <= 1e-6
    rows = xs["cvxpy"]["rows"]
    assert rows and min(r["closed_form"] for r in rows) == pytest.approx(1.0, abs=1e-12)


@pytest.fixture
def disagreeing_installed(tmp_path, monkeypatch):
    """A cross-check plug-in that always disagrees, as a real distribution."""
    dist = tmp_path / "nay_check-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: nay-check\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text("[ccopt.crosschecks]\nnay = nay_check:crosscheck\n")
    (tmp_path / "nay_check.py").write_text(
        "def crosscheck(certificate):\n"
        "    return {'name': 'nay', 'agree': False, 'summary': 'always disagrees'}\n")
    monkeypatch.syspath_prepend(str(tmp_path))


def test_a_disagreeing_crosscheck_fails_the_run(disagreeing_installed, capsys):
    code, out, _ = run(capsys, "verify", "leadin-inside-line", "--crosscheck")
    assert code == 1
    assert "verification PASSED" in out                    # the certificate itself holds
    assert "cross-check nay: DISAGREES - always disagrees" in out
    # without --crosscheck the plug-in is not run
    code, out, _ = run(capsys, "verify", "leadin-inside-line")
    assert code == 0 and "cross-check" not in out
