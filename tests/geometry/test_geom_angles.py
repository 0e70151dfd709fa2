"""Sweep bookkeeping: the inside-the-sweep test, sweeps from end angles, layering."""
from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import ccopt.geometry
from ccopt.geometry import angle_along, angle_in_sweep, sweep_between

TAU = 2.0 * math.pi


@settings(max_examples=400, deadline=None)
@given(theta0=st.floats(-1e3, 1e3), sweep=st.floats(-20, 20), frac=st.floats(0, 1),
       gap=st.floats(1e-6, 1.0))
def test_angle_in_sweep_property(theta0, sweep, frac, gap):
    sg = math.copysign(1.0, sweep)
    # Angles reached by travelling part of the sweep are inside, also shifted by
    # whole turns (kept 1e-9 clear of the ends, where rounding of theta0 +- ...
    # may decide either way and the kernels' end-point candidates take over).
    margin = 1e-9
    if abs(sweep) > 2 * margin:
        inside = theta0 + sg * (margin + frac * (abs(sweep) - 2 * margin))
        assert angle_in_sweep(np.array([inside]), theta0, sweep)[0]
        assert angle_in_sweep(np.array([inside + 6 * TAU, inside - 3 * TAU]), theta0, sweep).all()
    # Angles strictly between the end and the start (going on) are outside,
    # unless the sweep is a full turn or more.
    room = TAU - abs(sweep)
    if room > 2 * gap:
        outside = theta0 + sg * (abs(sweep) + gap + frac * (room - 2 * gap))
        assert not angle_in_sweep(np.array([outside]), theta0, sweep)[0]
    else:
        assert abs(sweep) >= TAU - 2 * gap


def test_angle_in_sweep_hand_worked():
    phi = np.array([0.0, 0.5, 1.0, 1.5, -0.1, math.pi])
    assert list(angle_in_sweep(phi, 0.0, 1.0)) == [True, True, True, False, False, False]
    assert list(angle_in_sweep(phi, 0.0, -1.0)) == [True, False, False, False, True, False]
    assert list(angle_in_sweep(phi, 1.0, -1.0)) == [True, True, True, False, False, False]
    assert angle_in_sweep(phi, 5.0, TAU).all() and angle_in_sweep(phi, 5.0, -7.0).all()
    assert np.allclose(angle_along(np.array([0.5, -0.5]), 0.0, -1.0), [TAU - 0.5, 0.5])


@settings(max_examples=300, deadline=None)
@given(a=st.floats(-math.pi, math.pi), b=st.floats(-math.pi, math.pi), ccw=st.booleans(),
       turns=st.integers(0, 3))
def test_sweep_between_reaches_the_end(a, b, ccw, turns):
    sw = sweep_between(a, b, ccw, turns, full_if_below=1e-12)
    assert (sw > 0) == ccw
    assert TAU * turns < abs(sw) <= TAU * (turns + 1) + 1e-12
    end = a + sw
    assert abs(math.cos(end) - math.cos(b)) <= 1e-9 and abs(math.sin(end) - math.sin(b)) <= 1e-9


def test_sweep_between_full_circle_and_direction():
    assert sweep_between(0.3, 0.3, True) == TAU
    assert sweep_between(0.3, 0.3, False) == -TAU
    assert sweep_between(0.3, 0.3 + 1e-14, True, full_if_below=1e-12) == TAU
    assert math.isclose(sweep_between(0.0, math.pi / 2, False), -1.5 * math.pi)
    assert math.isclose(sweep_between(0.0, math.pi / 2, True, turns=1), 2.5 * math.pi)


def test_geometry_imports_nothing_else_from_ccopt():
    # DESIGN.md layering: ccopt.geometry depends on numpy/scipy only.
    root = Path(ccopt.geometry.__file__).parent
    for path in root.glob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                if name == "ccopt" or name.startswith("ccopt."):
                    assert name.startswith("ccopt.geometry"), f"{path.name} imports {name}"
