"""Running tasks on Dask distributed: the client, the submission, the progress.

With no scheduler address, :func:`open_client` starts a ``LocalCluster`` of
worker processes, one per core by default, one thread each (the planners and
the verifier hold the GIL, so processes, not threads, run in parallel).
With ``tcp://host:8786``, it connects to that cluster; its workers need
ccopt installed. Programs are read once on the client and broadcast, so
each worker receives a program once, not once per task.
"""
from __future__ import annotations

import importlib.util
import sys
import uuid
from dataclasses import dataclass
from typing import Callable

from ccopt.errors import ProgramError
from ccopt.sweep.execute import run_task
from ccopt.sweep.tasks import Task
from ccopt.workers import resolve_workers

#: Seconds to wait for a scheduler given by address before giving up.
CONNECT_TIMEOUT = 30

#: Dask's nannies start workers with MALLOC_TRIM_THRESHOLD_=65536, which turns
#: off glibc's dynamic mmap threshold: every numpy temporary over 128 KiB is
#: then mapped and unmapped again, and a task runs 20-30 % slower (measured on
#: sweeps/variants.toml). The local cluster's workers keep glibc's default.
UNTRIMMED = "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"


@dataclass
class Session:
    """A Dask client and whether this sweep started it (then it closes it)."""

    client: object
    owned: bool
    cluster: object | None = None
    has_dashboard: bool = True

    @property
    def dashboard(self) -> str | None:
        """The dashboard's address, when the cluster serves one."""
        info = getattr(self.client, "scheduler_info", lambda: {})()
        if not (self.has_dashboard and info.get("services", {}).get("dashboard")):
            return None
        return getattr(self.client, "dashboard_link", None)

    def close(self) -> None:
        if self.owned:
            self.client.close()
            if self.cluster is not None:
                self.cluster.close()


def open_client(client=None, scheduler: str | None = None, workers: int | None = None) -> Session:
    """The user's ``client``, a client of ``scheduler``, or a new local cluster."""
    # Deferred: dask and distributed (tornado, msgpack, ...) take a second to
    # import, and only a sweep needs them.
    import dask  # deferred: see above
    from distributed import Client, LocalCluster  # deferred: see above
    if client is not None:
        return Session(client, owned=False)
    if scheduler is not None:
        try:
            return Session(Client(scheduler, timeout=CONNECT_TIMEOUT), owned=True)
        except (OSError, TimeoutError, ValueError) as exc:
            raise ProgramError(f"cannot connect to the Dask scheduler: {exc}", scheduler) from None
    # The dashboard's pages need bokeh; without it, ask for none (its bare
    # HTTP server still answers, so do not print its address either).
    bokeh = importlib.util.find_spec("bokeh") is not None
    with dask.config.set({UNTRIMMED: None}):
        cluster = LocalCluster(n_workers=resolve_workers(workers), threads_per_worker=1,
                               processes=True, dashboard_address=":0" if bokeh else None)
    return Session(Client(cluster), owned=True, cluster=cluster, has_dashboard=bokeh)


class Progress:
    """A live bar on a terminal (tasks done/total, failures, ETA); silent elsewhere."""

    def __init__(self, total: int, enabled: bool | None = None):
        if enabled is None:
            enabled = sys.stderr.isatty()
        self.failed = 0
        self.bar = None
        if enabled and total:
            # Deferred: tqdm is only needed for a bar on a terminal.
            from tqdm import tqdm
            self.bar = tqdm(total=total, unit="task", file=sys.stderr, dynamic_ncols=True,
                            desc="sweep")

    def update(self, row: dict) -> None:
        if row.get("error"):
            self.failed += 1
        if self.bar is not None:
            self.bar.set_postfix(failed=self.failed, refresh=False)
            self.bar.update(1)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _row(task: Task, figures: dict, run: int) -> dict:
    return {"task_id": task.id, "program": task.program, **task.settings, **figures, "run": run}


def run_tasks(session: Session, programs: dict, tasks: list[Task], run: int,
              timeout: float | None, on_row: Callable[[dict], None]) -> None:
    """Submit ``tasks`` and call ``on_row(row)`` as each finishes (any order).

    ``programs``: label -> Program (or the exception met reading it). A task
    whose worker dies becomes a row with that error, like any other failure.
    """
    # Deferred: distributed takes a second to import; only a sweep needs it.
    from distributed import as_completed
    client = session.client
    needed = sorted({t.program for t in tasks})
    # Every worker gets every program (a few kB each): scattered to one worker
    # only, the tasks of a program would queue there for data locality.
    shipped = {label: client.scatter(programs[label], hash=False, broadcast=True)
               for label in needed}
    token = uuid.uuid4().hex[:8]  # keys unique per call, named for the dashboard
    futures = {}
    for t in tasks:
        fut = client.submit(run_task, shipped[t.program], t.job, timeout, pure=False,
                            key=f"ccopt-sweep-{t.id}-{token}")
        futures[fut] = t
    try:
        for fut in as_completed(futures):
            task = futures[fut]
            try:
                figures = fut.result()
            except Exception as exc:  # the worker died or the result could not travel
                figures = {"error": f"{type(exc).__name__}: {exc}"}
            on_row(_row(task, figures, run))
    finally:
        client.cancel(list(futures))


def run_serial(programs: dict, tasks: list[Task], run: int, timeout: float | None,
               on_row: Callable[[dict], None]) -> None:
    """The same tasks one after another in this process (no Dask): for
    benchmarks and for checking the cluster's figures."""
    for t in tasks:
        on_row(_row(t, run_task(programs[t.program], t.job, timeout), run))
