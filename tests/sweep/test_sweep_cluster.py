"""Issue 19's acceptance on a real Dask ``LocalCluster`` of 2 worker processes:
one row per task, the figures of the public API called one task at a time,
an invalid setting as a row with its error, and resume computing only the
missing tasks."""
from __future__ import annotations

import shutil

import pandas as pd
import pytest

import ccopt
from ccopt.sweep.tasks import resolve_programs
from ccopt.sweep import load_spec

pytestmark = pytest.mark.slow

PROGRAMS = ["leadin-inside-line", "leadin-outside-line", "leadout-inside-line-line",
            "leadout-outside-line-line"]
SPEC = {"title": "acceptance", "programs": PROGRAMS, "planners": ["toppra", "junction"],
        # "mazak" is no style of ccopt: each of its tasks must be a row with the error
        "axes": {"style": ["pmac", "linuxcnc", "mazak"], "radius": [1.0, 2.0]}}


@pytest.fixture(scope="module")
def client():
    import distributed  # a dependency of ccopt (sweeps): missing is a failure, not a skip
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    cl = distributed.Client(cluster)
    try:
        yield cl
    finally:
        cl.close()
        cluster.close()


@pytest.fixture(scope="module")
def first(client, tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep") / "out"
    table = ccopt.sweep(SPEC, client=client, out=out)
    return table, out


def _by_hand(program: str, style: str, radius: float) -> dict:
    (inp,) = [p for p in resolve_programs(load_spec({"programs": [program]}))]
    prog = ccopt.read_program(inp.file)
    path = ccopt.compensate(prog, style=style, radius=radius)
    limits = ccopt.AxisLimits(v=list(inp.case.vmax), a=list(inp.case.amax))
    prof = ccopt.plan_feed(path, limits)
    cert = ccopt.verify(path, prog, profile=prof, radius=radius)
    return {"cycle_time": prof.duration,
            "cycle_time_junction": ccopt.plan_feed(path, limits, planner="junction").duration,
            "min_clearance": cert.min_clearance, "ok": cert.ok, "path_length": path.length,
            "cutter_radius": path.radius}


def test_one_row_per_task_with_the_api_figures(first, client):
    table, out = first
    assert isinstance(table, pd.DataFrame)
    assert len(table) == 24 == table["task_id"].nunique()
    assert table.attrs["computed"] == 24
    assert sorted(client.scheduler_info()["workers"]) and len(client.scheduler_info()["workers"]) == 2
    for row in table[table["style"] != "mazak"].itertuples():
        assert pd.isna(row.error), row.error
        want = _by_hand(row.program, row.style, row.radius)
        for key, value in want.items():
            assert getattr(row, key) == value, (row.program, row.style, row.radius, key)
    bad = table[table["style"] == "mazak"]
    assert len(bad) == 8
    assert bad["error"].str.contains("unknown compensation style 'mazak'").all()
    assert bad["cycle_time"].isna().all()
    for name in ("results.parquet", "results.csv", "spec.json", "meta.json", "summary.html",
                 "summary.png"):
        assert (out / name).is_file(), name
    assert len(pd.read_csv(out / "results.csv")) == 24


def test_resume_runs_only_the_missing_tasks(first, client, tmp_path):
    table, out = first
    again = tmp_path / "again"
    shutil.copytree(out, again)
    kept = pd.read_parquet(again / "results.parquet")
    dropped = set(kept["task_id"].iloc[[1, 5, 9, 20]])
    kept[~kept["task_id"].isin(dropped)].to_parquet(again / "results.parquet", index=False)
    resumed = ccopt.sweep(SPEC, client=client, out=again)
    assert resumed.attrs["computed"] == 4
    assert list(resumed["task_id"]) == list(table["task_id"])
    assert set(resumed.loc[resumed["run"] == 2, "task_id"]) == dropped
    assert (resumed.loc[resumed["run"] == 1, "task_id"].isin(set(table["task_id"]) - dropped)).all()
    cols = ["cycle_time", "min_clearance", "path_length"]
    pd.testing.assert_frame_equal(resumed[cols], table[cols])
    # nothing missing: nothing runs, not even a cluster
    assert ccopt.sweep(SPEC, out=again).attrs["computed"] == 0
