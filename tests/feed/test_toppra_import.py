"""Planning a feed does not load matplotlib.pyplot (toppra imports it only for
plotting helpers), and pyplot works as always afterwards."""
from __future__ import annotations

import subprocess
import sys

CHECK = """
import sys
import ccopt.feed.plan
assert "matplotlib.pyplot" not in sys.modules, "pyplot loaded by the feed planner"
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
    out = subprocess.run([sys.executable, "-c", CHECK], capture_output=True, text=True,
                         check=False)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
