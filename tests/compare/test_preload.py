"""The imports a plug-in blend defers (its ``imports``, :data:`ccopt.compare.
contract.Blend`) are done once, in the comparison's own process, before it
forks the workers that solve the blends: no worker imports cvxpy again."""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from ccopt.compare import registry
from ccopt.compare.registry import load, preload

ROOT = Path(__file__).resolve().parents[2]


def test_preload_calls_each_blends_imports_once_and_leaves_failures_to_the_blend(monkeypatch):
    calls = []

    def imports():
        calls.append(1)

    def broken():
        raise ImportError("no such solver")

    def blend(problem):
        return problem.reference

    blends = {"a": blend, "b": lambda problem: problem.reference, "c": blend}
    blends["b"].imports = blend.imports = imports
    blends["d"] = lambda problem: problem.reference
    blends["d"].imports = broken

    def fake_load(name):
        if name == "missing":
            raise KeyError(name)
        return blends[name]

    monkeypatch.setattr(registry, "load", fake_load)
    preload(["a", "missing", "d", "b", "c"])
    assert calls == [1]


def test_every_cvxpy_blend_declares_its_import():
    from ccopt.stand_ins import import_cvxpy
    for name in ("smooth", "opt-cvxpy"):
        assert load(name).imports is import_cvxpy, name


SCRIPT = textwrap.dedent("""
    import sys
    import ccopt
    from ccopt.compare import compare
    prog = ccopt.read_text(
        "G21 G17 G90\\nG0 X-20 Y-5\\nG42 D1 G1 X-10 Y0 F600\\nG1 X10 Y0\\nG1 X10 Y10\\n"
        "G1 X-10 Y10\\nG1 X-10 Y0\\nG40 G1 X-20 Y-5\\nM30\\n", "plate.ngc", "gcode")
    limits = ccopt.AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0))
    assert "cvxpy" not in sys.modules
    cmp = compare(prog, {variants}, limits=limits, radius=1.0, workers=2)
    assert cmp["smooth"].status == "ok", cmp["smooth"].message
    print("cvxpy here" if "cvxpy" in sys.modules else "cvxpy elsewhere")
""")


@pytest.mark.parametrize("variants", [
    ["pmac", "linuxcnc", "fagor-g138", "smooth", "opt-cvxpy"],   # the controllers in workers
    ["pmac", "linuxcnc", "smooth", "opt-cvxpy"]])    # one controller job: it runs here
def test_a_parallel_comparison_imports_cvxpy_here_before_its_workers(variants):
    """Without the preload the blends' workers import cvxpy and this process
    never does."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", SCRIPT.format(variants=variants)],
                         capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "cvxpy here"
