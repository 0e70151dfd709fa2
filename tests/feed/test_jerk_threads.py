"""The jerk planner's windows and refinement re-plans solved in threads give,
bit for bit, the profile solved in one thread.

Chains of windows (stop to stop) and the stretches a refinement pass plans
again are independent: each is solved from the same data whichever thread
takes it, and writes only its own gridpoints. Checked on generated CAM
programs (tests/cam_programs.py) in several controller styles and on
bench/feed.py's pockets, whose corner arcs make the planner refine, planned once with
``WORKERS = 1`` and once with two threads; and the threads' budget follows
the process's share of the cores (:func:`ccopt.workers.thread_budget`).
"""
from __future__ import annotations

import importlib.util
import random
import sys
from pathlib import Path

import numpy as np
import pytest

from cam_programs import cam_program
from ccopt import workers as ccopt_workers
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.feed.jerk import windows as jerk_windows
from ccopt.program import read_text
from ccopt.workers import default_workers, run_in_workers, thread_budget

STYLES = ("pmac", "linuxcnc", "fagor", "siemens", "heidenhain")

# bench/feed.py's pockets (loaded by path: "feed" is also a test folder): their
# 0.5 mm corner arcs make every plan refine, so the re-plans run in threads too
_spec = importlib.util.spec_from_file_location(
    "bench_feed_threads", Path(__file__).resolve().parents[2] / "bench" / "feed.py")
bench_feed = importlib.util.module_from_spec(_spec)
sys.modules["bench_feed_threads"] = bench_feed
_spec.loader.exec_module(bench_feed)
POCKET_LIMITS = AxisLimits(bench_feed.LIMITS.v, bench_feed.LIMITS.a, j=bench_feed.JERK)


def _case(seed: int):
    cp = cam_program(seed)
    prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    rng = random.Random(20_000 + seed)
    v, a = rng.uniform(50.0, 300.0), rng.uniform(500.0, 5000.0)
    lim = AxisLimits((v, v), (a, a), j=(a * rng.uniform(5.0, 50.0),) * 2)
    return cp.description, ExactPath(compensate(prog, STYLES[seed % len(STYLES)])), lim


def _pocket(seed: int):
    n = random.Random(seed).randint(20, 80)
    path = ExactPath(compensate(bench_feed.pocket_program(n, seed=seed), "pmac"))
    return f"bench/feed.py pocket of {n} blocks, seed {seed}", path, POCKET_LIMITS


def _same_in_threads(case, monkeypatch) -> dict:
    what, path, lim = case
    monkeypatch.setattr(jerk_windows, "WORKERS", 1)
    one = plan_feed(path, lim, planner="jerk")
    monkeypatch.setattr(jerk_windows, "WORKERS", 2)
    monkeypatch.setattr(ccopt_workers, "default_workers", lambda: 2)   # 2 threads on any machine
    two = plan_feed(path, lim, planner="jerk")
    assert one.info["threads"] == 1 and one.info["workers"] == two.info["workers"] == 1
    for name in ("t", "s", "sd"):
        np.testing.assert_array_equal(getattr(two, name), getattr(one, name), err_msg=what)
    assert two.duration == one.duration, what
    return two.info


@pytest.mark.parametrize("seed", [3, 8])
def test_threads_plan_what_one_thread_plans(seed, monkeypatch):
    info = _same_in_threads(_case(seed), monkeypatch)
    assert info["windows"] >= 1


def test_threads_replan_what_one_thread_replans(monkeypatch):
    info = _same_in_threads(_pocket(1), monkeypatch)
    assert info["threads"] == 2 and info["refined_intervals"] > 0


@pytest.mark.slow
def test_threads_plan_what_one_thread_plans_generated(monkeypatch):
    cases = [_case(seed) for seed in range(100, 130)] + [_pocket(s) for s in range(2, 12)]
    used = refined = 0
    for case in cases:
        info = _same_in_threads(case, monkeypatch)
        used += info["threads"] == 2
        refined += info["threads"] == 2 and info["refined_intervals"] > 0
    # the property was exercised: programs of several chains, and re-plans
    assert used >= 20 and refined >= 10, (used, refined)


def test_thread_budget_outside_a_pool_is_the_cores():
    assert thread_budget() == default_workers()


def _budget(item, progress):
    return thread_budget()


def test_thread_budget_in_a_pool_is_the_process_share():
    """In ``ccopt run --workers N`` each case's process may keep its share of
    the cores busy: N processes on C cores, C // N threads each (at least 1)."""
    got = run_in_workers(_budget, [0, 1], 2)
    assert got == [max(1, default_workers() // 2)] * 2
    assert run_in_workers(_budget, [0], 1) == [default_workers()]


def test_a_failing_task_drops_the_tasks_not_started():
    """A task that raises (as a Ctrl-C would in the waiting thread) ends the
    map once the running tasks end: the ones not yet started never run."""
    import threading
    import time

    started = []
    lock = threading.Lock()

    def task(i):
        with lock:
            started.append(i)
        if i == 0:
            raise KeyboardInterrupt
        time.sleep(0.05)
        return i

    with pytest.raises(KeyboardInterrupt):
        ccopt_workers.map_in_threads(task, list(range(40)), 2)
    assert len(started) < 10, started
