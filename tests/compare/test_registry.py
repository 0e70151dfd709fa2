"""Adding a blend is one module plus one entry point: a toy blend from this folder,
registered through a real distribution's entry_points.txt, appears in ccopt compare."""
from __future__ import annotations

import json
import os
from importlib.metadata import entry_points
from pathlib import Path

import pytest

from ccopt.cli import main
from ccopt.compare import available


@pytest.fixture
def toy_installed(tmp_path, monkeypatch):
    dist = tmp_path / "toy_blend_pkg-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: toy-blend-pkg\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text("[ccopt.blends]\ntoy = toy_blend:toy\n")
    monkeypatch.syspath_prepend(str(tmp_path))                      # the distribution
    monkeypatch.syspath_prepend(str(Path(__file__).resolve().parent))  # its module
    return dist


def test_toy_blend_seen_by_importlib_and_compare(toy_installed, capsys):
    assert "toy" in [ep.name for ep in entry_points(group="ccopt.blends")]
    assert "toy" in available()
    code = main(["compare", "leadin-inside-line", "--variants", "pmac,toy", "--json"])
    out = capsys.readouterr().out
    assert code == 0
    rows = {v["name"]: v for v in json.loads(out)["variants"]}
    assert list(rows) == ["pmac", "toy"]
    toy, pmac = rows["toy"], rows["pmac"]
    assert toy["status"] == "ok" and toy["info"] == {"toy": True}
    # an inside lead-in: PMAC goes straight from the approach point to P + r*o(t_next),
    # so the toy's straight line is the same path, with the same figures
    assert toy["length"] == pytest.approx(pmac["length"], rel=1e-12)
    assert toy["duration"] == pytest.approx(pmac["duration"], rel=1e-9)
    assert toy["certified"] is True and toy["min_clearance"] == pytest.approx(2.0)
    assert toy["max_deviation"] == 0.0
    code = main(["compare", "leadin-inside-line", "--list"])
    assert "toy" in capsys.readouterr().out.split()


def test_without_the_toy_it_is_unknown(capsys):
    assert "toy" not in available()
    code = main(["compare", "leadin-inside-line", "--variants", "toy"])
    err = capsys.readouterr().err
    assert code == 2 and "unknown variant(s) toy" in err and len(err.strip().splitlines()) == 1


def test_a_blend_installed_after_a_search_is_found(tmp_path, monkeypatch):
    # the entry points are searched again when a folder on sys.path changes
    # (blend_entry_points keeps the last search): a distribution added there
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.syspath_prepend(str(Path(__file__).resolve().parent))
    assert "toy" not in available()
    before = tmp_path.stat().st_mtime_ns
    dist = tmp_path / "toy_blend_pkg-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: toy-blend-pkg\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text("[ccopt.blends]\ntoy = toy_blend:toy\n")
    # a folder's time stamp can be coarser than the steps above: a later one, surely
    os.utime(tmp_path, ns=(before + 10**9, before + 10**9))
    assert "toy" in available()
    assert available() == available()
