"""``ccopt run`` in worker processes: the same results as one after the
other, and a Ctrl-C that stops everything at once, leaving no partial file."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import ccopt
from ccopt.cli import main

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"

#: what changes from one run to the next whatever the workers: wall times
TIMINGS = ("stage_seconds", "solve_time")


def _without_timings(x):
    if isinstance(x, dict):
        return {k: _without_timings(v) for k, v in x.items() if k not in TIMINGS}
    if isinstance(x, list):
        return [_without_timings(v) for v in x]
    return x


@pytest.mark.slow
def test_two_workers_give_the_serial_results(capsys, tmp_path):
    argv = ["leadin-outside-line", "short-move-overcut", "--variants", "pmac,tangent-arc,linuxcnc",
            "--json"]
    runs = {}
    for n in (1, 2):
        out = tmp_path / f"w{n}"
        code = main(["run", *argv, "-o", str(out), "--workers", str(n)])
        printed, err = capsys.readouterr()
        assert code == 0, err
        runs[n] = (out, json.loads(printed))
    (one, printed1), (two, printed2) = runs[1], runs[2]
    assert printed1["out"] == str(one) and printed2["out"] == str(two)
    assert _without_timings(printed1["cases"]) == _without_timings(printed2["cases"])
    summary = [_without_timings(json.loads((d / "summary.json").read_text())) for d in (one, two)]
    assert summary[0] == summary[1]
    rows = summary[0]["cases"]
    assert [r["name"] for r in rows] == ["leadin-outside-line", "short-move-overcut"]
    # the figures are the ones of the cases, not merely equal: PMAC's short-move
    # overcut comes 1 mm (the 1 mm step under a 2 mm radius) from the contour
    assert rows[1]["min_clearance"] == pytest.approx(1.0, abs=1e-9)
    assert rows[0]["min_clearance"] == pytest.approx(2.0, abs=1e-9)
    assert [v["name"] for v in rows[0]["compare"]] == ["pmac", "tangent-arc", "linuxcnc"]
    # the report's pages and summary.json carry wall times (solve, stages)
    def exported_files(folder):
        return sorted(p.name for p in folder.iterdir()
                      if p.name != "summary.json" and not p.name.endswith(".html"))
    exported = exported_files(one)
    assert exported == exported_files(two)
    assert len(exported) == 12   # six files per case
    for name in exported:
        assert (one / name).read_bytes() == (two / name).read_bytes(), name


def _children(pid: int) -> list[int]:
    try:
        return [int(p) for p in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


def _interrupt(args: list[str], busy_for: float):
    """Run ``ccopt ARGS``, wait until its two workers are up and have computed
    for ``busy_for`` s, send SIGINT: ``(exit code, stderr, seconds it took to
    stop, the workers' pids)``."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-m", "ccopt.cli", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        t0 = time.monotonic()
        while len(_children(proc.pid)) < 2 and time.monotonic() - t0 < 60:
            time.sleep(0.02)
        workers = _children(proc.pid)
        assert len(workers) == 2, "the workers never started"
        time.sleep(busy_for)                 # they are computing now
        assert proc.poll() is None, "finished before it could be interrupted"
        t1 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        stopped = time.monotonic() - t1
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, err, stopped, workers


def _gone(workers: list[int]) -> bool:
    """Whether none of ``workers`` is still running (a zombie is not)."""
    return not [w for w in workers if Path(f"/proc/{w}").exists()
                and "Z" not in Path(f"/proc/{w}/stat").read_text().split()[2]]


@pytest.mark.slow
def test_sigint_stops_run_leaving_no_partial_file(tmp_path):
    out = tmp_path / "out"
    # pocket's comparison alone takes many seconds: both workers are busy when interrupted
    code, err, stopped, workers = _interrupt(["run", "leadin-inside-line", "pocket", "-o",
                                              str(out), "--workers", "2"], 2.0)
    assert code == 130, err          # how soon: bench/stops.py
    assert err.strip() == "ccopt: interrupted"
    assert _gone(workers)
    names = sorted(p.name for p in out.iterdir()) if out.exists() else []
    # no temporary file, no report of a run that did not finish
    assert not [n for n in names if n.endswith(".tmp")], names
    assert "index.html" not in names and "summary.json" not in names
    # what a case wrote before the interrupt is whole
    for name in names:
        f = out / name
        if name.endswith(".json"):
            json.loads(f.read_text())
        elif name.endswith((".nc", ".pmc")):
            ccopt.read_program(f)


@pytest.mark.slow
def test_sigint_stops_a_parallel_comparison():
    # freeform-hsm's comparison keeps both workers on long plans for seconds;
    # a library pool would let each finish its task before the command ends
    code, err, stopped, workers = _interrupt(["compare", "freeform-hsm", "--workers", "2"], 2.5)
    assert code == 130, err          # how soon: bench/stops.py
    assert err.strip() == "ccopt: interrupted"
    assert _gone(workers)
