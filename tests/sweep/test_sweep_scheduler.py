"""``ccopt sweep --scheduler``: a separately started ``dask scheduler`` and
``dask worker`` on localhost (a free port), stopped by the test."""
from __future__ import annotations

import json
import socket
import subprocess
import sys
import time

import pytest

from ccopt.cli import main
from ccopt.sweep import engine

pytestmark = pytest.mark.slow

#: Seconds the scheduler and worker get to come up (the machine may be busy).
START_TIMEOUT = 60

SPEC = """
programs = ["leadin-outside-line", "leadout-inside-line-line"]
[axes]
radius = [1.0, 2.0]
style = ["pmac", "linuxcnc"]
"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def _wait_for_worker(address: str) -> None:
    import distributed  # a dependency of ccopt (sweeps): missing is a failure, not a skip
    with distributed.Client(address, timeout=START_TIMEOUT) as client:
        client.wait_for_workers(1, timeout=START_TIMEOUT)


def test_sweep_through_a_separately_started_scheduler(tmp_path, capsys):
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    procs = []
    try:
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port",
             str(port), "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        time.sleep(1)
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "dask", "worker", address, "--nworkers", "1", "--nthreads",
             "1", "--no-dashboard", "--host", "127.0.0.1"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        _wait_for_worker(address)
        spec = tmp_path / "spec.toml"
        spec.write_text(SPEC)
        out = tmp_path / "out"
        assert main(["sweep", str(spec), "-o", str(out), "--scheduler", address, "--json"]) == 0
        doc = json.loads(capsys.readouterr().out)
        assert doc["tasks"] == doc["computed"] == 8 and doc["failed"] == 0
        assert {r["program"] for r in doc["rows"]} == {"leadin-outside-line",
                                                        "leadout-inside-line-line"}
        assert all(r["ok"] and r["cycle_time"] > 0 for r in doc["rows"])
        assert (out / "results.parquet").is_file() and (out / "spec.toml").read_text() == SPEC
    finally:
        for proc in reversed(procs):
            _stop(proc)


def test_an_unreachable_scheduler_is_bad_input(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(engine, "CONNECT_TIMEOUT", 2)
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC)
    address = f"tcp://127.0.0.1:{_free_port()}"
    assert main(["sweep", str(spec), "-o", str(tmp_path / "out"), "--scheduler", address]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"{address}: cannot connect to the Dask scheduler")
