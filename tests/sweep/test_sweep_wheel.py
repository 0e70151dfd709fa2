"""The wheel carries the bundled sweep specs (as ``ccopt.bundled_sweeps``) and
an installed wheel finds one by name, with its bundled cases, from any folder."""
from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.slow


def test_wheel_carries_the_bundled_specs(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", str(ROOT),
                    "-w", str(tmp_path)], check=True, cwd=tmp_path, capture_output=True)
    (wheel,) = tmp_path.glob("ccopt-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    specs = sorted(p.name for p in (ROOT / "sweeps").glob("*.toml"))
    assert specs and {f"ccopt/bundled_sweeps/{s}" for s in specs} <= names
    assert {"ccopt/sweep/__init__.py", "ccopt/cli/sweep.py"} <= names
    site, elsewhere = tmp_path / "site", tmp_path / "elsewhere"
    elsewhere.mkdir()
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target",
                    str(site), str(wheel)], check=True, capture_output=True)
    code = ("import ccopt; from ccopt.sweep import load_spec; "
            "from ccopt.sweep.tasks import expand, resolve_programs; "
            "s = load_spec('styles-radii'); print(ccopt.__file__, len(expand(s, resolve_programs(s))))")
    out = subprocess.run([sys.executable, "-c", code], cwd=elsewhere, capture_output=True,
                         text=True, check=True, env=dict(os.environ, PYTHONPATH=str(site)))
    where, count = out.stdout.split()
    assert Path(where).is_relative_to(site) and count == "108"
