"""Planning a feed does not load matplotlib.pyplot or scipy.interpolate (toppra
imports them only for plotting helpers and its own spline paths), and both work
as always afterwards."""
from __future__ import annotations

import subprocess
import sys

CHECK = """
import sys
import ccopt.feed.plan
assert "matplotlib.pyplot" not in sys.modules, "pyplot loaded by the feed planner"
assert "matplotlib" not in sys.modules, "matplotlib loaded by the feed planner"
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import toppra.algorithm.algorithm as algorithm
fig, ax = plt.subplots()
assert type(fig).__name__ == "Figure"
assert algorithm.plt.subplots is plt.subplots   # toppra's stand-in forwards to it
print("ok")
"""


def test_feed_planner_does_not_load_pyplot():
    _runs_ok(CHECK)


CHECK_INTERPOLATE = """
import sys
import numpy as np
import ccopt.feed.plan
assert "scipy.interpolate" not in sys.modules, "scipy.interpolate loaded by the feed planner"
import scipy
import scipy.interpolate as si
assert scipy.interpolate is si and type(si.PPoly).__name__ == "type"
import toppra
# toppra's spline path, built through the stand-in names, is scipy's cubic spline
x = np.linspace(0.0, 1.0, 6)
y = np.column_stack((np.sin(3 * x), x ** 2))
path = toppra.SplineInterpolator(x, y)
s = np.linspace(0.0, 1.0, 11)
assert np.array_equal(path(s), si.CubicSpline(x, y, bc_type="not-a-knot")(s))
print("ok")
"""


def test_feed_planner_does_not_load_scipy_interpolate():
    _runs_ok(CHECK_INTERPOLATE)


CHECK_CVXPY = """
import sys
from ccopt.stand_ins import import_cvxpy
cp = import_cvxpy()
assert "scipy.stats" not in sys.modules, "scipy.stats loaded with cvxpy"
x = cp.Variable(2)
cp.Problem(cp.Minimize(cp.sum_squares(x - [1.0, 2.0]))).solve()
assert abs(x.value[0] - 1.0) < 1e-6 and abs(x.value[1] - 2.0) < 1e-6
# cvxpy's entropy atom, built on scipy.stats' entropy through the stand-in
entropy = sys.modules["cvxpy.atoms.quantum_rel_entr"].entropy
import scipy.stats
assert entropy([0.5, 0.25, 0.25]) == scipy.stats.entropy([0.5, 0.25, 0.25])
print("ok")
"""


def test_cvxpy_loads_without_scipy_stats():
    _runs_ok(CHECK_CVXPY)


def _runs_ok(code: str) -> None:
    """``code`` run in a fresh interpreter prints ``ok``."""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=False)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
