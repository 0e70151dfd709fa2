"""The wheel stands on its own: a non-editable install carries the bundled
cases, the formulations under their own import name, the licence and
``py.typed``, and finds a bundled case by name from any folder."""
from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", str(ROOT),
                    "-w", str(out)], check=True, cwd=out, capture_output=True)
    (found,) = out.glob("ccopt-*.whl")
    return found


def test_wheel_contents(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    cases = sorted(p.name for p in (ROOT / "cases").iterdir() if (p / "case.toml").is_file())
    assert cases
    for case in cases:
        for f in (ROOT / "cases" / case).iterdir():
            assert f"ccopt/bundled_cases/{case}/{f.name}" in names
    formulations = sorted(p.name for p in (ROOT / "formulations").glob("*.py"))
    assert {f"ccopt_formulations/{f}" for f in formulations} <= names
    assert not any(n.startswith("formulations/") for n in names)
    assert "ccopt/py.typed" in names
    assert any(n.endswith("licenses/LICENSE") for n in names)
    entry_points = next(n for n in names if n.endswith("entry_points.txt"))
    text = zipfile.ZipFile(wheel).read(entry_points).decode()
    assert "ccopt_formulations.blend_casadi:opt_casadi" in text


def test_installed_wheel_finds_a_bundled_case_from_another_folder(wheel, tmp_path):
    site = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target",
                    str(site), str(wheel)], check=True, capture_output=True)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = dict(os.environ, PYTHONPATH=str(site))
    where = subprocess.run([sys.executable, "-c", "import ccopt; print(ccopt.__file__)"],
                           cwd=elsewhere, env=env, capture_output=True, text=True, check=True)
    assert Path(where.stdout.strip()).is_relative_to(site)
    run = subprocess.run(
        [sys.executable, "-c", "import sys; from ccopt.cli import main; sys.exit(main())",
         "run", "leadin-inside-line", "--no-compare", "-o", "out"],
        cwd=elsewhere, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert (elsewhere / "out" / "leadin-inside-line.nc").is_file()
    assert (elsewhere / "out" / "index.html").is_file()
