"""Benchmark: one sweep serially, and on a Dask LocalCluster of 2 workers.

The sweep is a bundled spec (default ``sweeps/limits-planners.toml``: 4 parts
x 3 machine limits x 3 planners = 36 tasks). Timed, each after a warm-up
(every process has imported toppra and run one task, so import time is not
counted):

- serial: ``ccopt.sweep(spec, serial=True)``, every task in this process;
- direct: the same tasks as plain calls of the task function
  (``ccopt.sweep.execute.run_task``), the floor of any runner;
- 1 worker: ``ccopt.sweep(spec, client=...)`` on a 1-worker LocalCluster
  (the one ``ccopt sweep`` starts), whose excess over ``direct``, per task,
  is the per-task overhead (scatter, submit, pickling, result, table);
  its wall time minus the task time the worker measured is the same
  overhead, less sensitive to load from elsewhere on the machine;
- 2 workers: the same on a 2-worker LocalCluster; speed-up = serial / 2 workers
  (issue 19's target: at least 1.7 on 2 cores).

Prints the times, the speed-up and the overhead per task, and for 2 workers
the tasks and busy seconds per worker: ``busy / (2 x wall)`` near 1 says
Dask keeps both workers busy, and ``task time on the workers / serially``
above 1 says the tasks themselves ran slower side by side (cores or memory
shared with other load). The figures of every run are checked equal to the
serial ones.

    python bench/sweep.py [--spec sweeps/limits-planners.toml] [--repeat 1]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import ccopt  # noqa: E402
from ccopt.sweep import load_spec  # noqa: E402
from ccopt.sweep.engine import open_client  # noqa: E402
from ccopt.sweep.execute import run_task  # noqa: E402
from ccopt.sweep.tasks import expand, resolve_programs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
FIGURES = ["cycle_time", "min_clearance", "path_length"]


def _direct(spec) -> float:
    programs = {p.label: ccopt.read_program(p.file) for p in resolve_programs(spec)}
    tasks = expand(spec, resolve_programs(spec))
    run_task(programs[tasks[0].program], tasks[0].job)  # warm-up
    t0 = time.perf_counter()
    for t in tasks:
        run_task(programs[t.program], t.job)
    return time.perf_counter() - t0


def _warm_worker(spec) -> None:
    programs = resolve_programs(spec)
    task = expand(spec, programs)[0]
    run_task(ccopt.read_program(programs[0].file), task.job)


def _on_cluster(spec, workers: int, repeat: int):
    session = open_client(workers=workers)  # the local cluster ccopt sweep starts
    try:
        session.client.run(_warm_worker, spec)
        times, table = [], None
        for _ in range(repeat):
            t0 = time.perf_counter()
            table = ccopt.sweep(spec, client=session.client, progress=False)
            times.append(time.perf_counter() - t0)
    finally:
        session.close()
    return statistics.median(times), table


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec", default=str(ROOT / "sweeps" / "limits-planners.toml"))
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    spec = load_spec(args.spec)
    n = len(expand(spec, resolve_programs(spec)))
    _warm_worker(spec)
    serial = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        ref = ccopt.sweep(spec, serial=True, progress=False)
        serial.append(time.perf_counter() - t0)
    t_serial = statistics.median(serial)
    t_direct = statistics.median(_direct(spec) for _ in range(args.repeat))
    t_one, one = _on_cluster(spec, 1, args.repeat)
    t_two, two = _on_cluster(spec, 2, args.repeat)
    for table in (one, two):
        assert table[FIGURES].equals(ref[FIGURES]), "figures differ between runners"
    print(f"spec {Path(args.spec).name}: {n} tasks, {int(ref['error'].notna().sum())} failed; "
          f"median of {args.repeat}")
    print(f"direct calls          {t_direct:8.2f} s   {t_direct / n * 1e3:7.1f} ms/task")
    print(f"serial (ccopt.sweep)  {t_serial:8.2f} s   {t_serial / n * 1e3:7.1f} ms/task")
    print(f"LocalCluster 1 worker {t_one:8.2f} s   overhead vs direct "
          f"{(t_one - t_direct) / n * 1e3:7.1f} ms/task; wall minus the worker's task time "
          f"{(t_one - one['task_time'].sum()) / n * 1e3:6.1f} ms/task")
    print(f"LocalCluster 2 workers{t_two:8.2f} s   speed-up vs serial {t_serial / t_two:5.2f}x "
          f"(vs direct {t_direct / t_two:5.2f}x)")
    busy = two.groupby("worker")["task_time"].agg(["count", "sum"])
    print("2 workers: tasks and busy seconds per worker: "
          + ", ".join(f"{int(r['count'])} / {r['sum']:.2f} s" for _, r in busy.iterrows())
          + f"; busy / (2 x wall) = {busy['sum'].sum() / (2 * t_two):.2f}; "
          f"task time on the workers / serially = {two['task_time'].sum() / ref['task_time'].sum():.2f}")


if __name__ == "__main__":
    main()
