"""Worker processes: the one place ccopt starts them.

Three ways to hand work to them, for three shapes of work, over the same
child start (:func:`start_child`, :func:`die_with_parent`), kill
(:func:`kill_processes`) and count (:func:`resolve_workers`, ``--workers``):

- :func:`run_in_workers`: independent jobs known in advance, with progress
  (``ccopt run``'s cases);
- :func:`process_pool`: jobs handed out one at a time as earlier ones finish
  (the comparison's variants and cycle times, :mod:`ccopt.compare.schedule`);
- :func:`run_in_interpreters`: tasks for fresh interpreters fed over pipes
  (the jerk planner's windows, :mod:`ccopt.feed.jerk.windows`).

The sweep's Dask cluster starts its own processes (Dask's), of the size
:func:`resolve_workers` gives. Work that runs in threads of one process
(:func:`map_in_threads`: the jerk planner's windows, HiGHS releases the GIL)
takes as many as :func:`thread_budget` allows, the process's share of the cores.

:func:`run_in_workers` calls ``work(item, progress)`` for every item in
``workers`` child processes and hands back the results in the items' order,
the same as a serial loop would (each item is computed alone, from the same
inputs, by the same code). ``progress(text)`` inside a job reaches the parent
as ``on_progress(index, text)``.

Why processes of our own rather than a library pool: a Ctrl-C must stop the
command within a second. The parent only waits on a queue (a Python wait,
interrupted at once by the KeyboardInterrupt), never on a solver; the
children ignore SIGINT (a solver such as IPOPT may catch it and go on) and
are killed, each with the process group it leads (a job may start its own
workers), as soon as the parent stops waiting for any reason. Temporary
files a killed child leaves behind (``.NAME.ccopt-PID-N.tmp``,
:mod:`ccopt.atomic`) are removed from the folders the caller names.
"""
from __future__ import annotations

import importlib
import multiprocessing
import os
import pickle
import queue
import re
import signal
import subprocess
import sys
import threading
import traceback
from collections import deque
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

from ccopt.errors import CcoptError

#: How often the parent looks at its children while no message comes, seconds
#: (an exit of a child that could not report is noticed within this).
POLL_SECONDS = 0.1

#: How long the parent waits for a killed child to be reaped, seconds.
REAP_SECONDS = 0.5

_TEMP_RE = re.compile(r"\..+\.ccopt-(\d+)-\d+\.tmp")


class WorkerFailed(RuntimeError):
    """A job raised an exception that is not a :class:`ccopt.errors.CcoptError`
    (an internal bug), or its process died; ``child_traceback`` is the child's
    traceback text (empty when it died)."""

    child_traceback = ""


def default_workers() -> int:
    """One worker per core this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


#: How many processes of one of ccopt's pools share this machine's cores with
#: this one (1 outside a pool): set as a worker starts (:func:`start_child`).
_POOL_SIZE = 1


def thread_budget() -> int:
    """How many threads a job in this process may keep busy at once: its share
    of the cores (:func:`default_workers` over the processes of the pool it
    is a worker of, at least 1), and 1 in a daemonic process (a Dask worker,
    one of many a machine runs). The jerk planner solves windows in threads
    (HiGHS releases the GIL while it solves); in ``ccopt run --workers 2`` on
    2 cores each case then keeps one core busy, as before."""
    if multiprocessing.current_process().daemon:
        return 1
    return max(1, default_workers() // _POOL_SIZE)


def map_in_threads(fn: Callable[[Any], Any], items: Sequence, threads: int) -> list:
    """``[fn(x) for x in items]``, in ``threads`` threads of this process (in
    order): for work that leaves the GIL (a solver's C code). On any
    exception here (a Ctrl-C, a failed item) the items not started are
    dropped, so it returns as soon as the running ones end."""
    if threads <= 1 or len(items) < 2:
        return [fn(x) for x in items]
    pool = ThreadPoolExecutor(threads)
    try:
        return list(pool.map(fn, items))
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def resolve_workers(workers: int | None) -> int:
    """How many worker processes ``--workers N`` (``workers=`` in the API)
    means: ``N``, or when not given one per core (:func:`default_workers`).
    The commands, the jerk planner's windows and the sweep's local Dask
    cluster all count their workers here."""
    return workers or default_workers()


def die_with_parent(parent: int) -> None:
    """Make this process (a child of process ``parent``) die when its parent
    does, even by SIGKILL or SIGTERM, which give the parent no chance to kill
    its children: Linux's ``PR_SET_PDEATHSIG`` with SIGKILL. Without it a child
    in the middle of a long solve goes on alone until the solve ends. If the
    parent is already gone (it died before this call), exit now. Elsewhere
    (no ``prctl``) nothing is done: the child then ends when it next reads
    from or writes to its parent."""
    try:
        import ctypes        # here: only a child process needs it
        libc = ctypes.CDLL(None, use_errno=True)
        PR_SET_PDEATHSIG = 1
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:
        os._exit(1)


def fork_context():
    """The multiprocessing context of worker processes: fork where there is one
    (the children start at once with the parent's modules, ccopt, numpy and
    the solvers, already imported), elsewhere the platform's default."""
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("fork" if "fork" in methods else None)


def start_child(parent: int, pool_size: int = 1) -> None:
    """What a worker process (a child of process ``parent``, one of
    ``pool_size``) does first: ignore SIGINT (the parent decides, and kills
    it: a solver such as IPOPT may catch the signal and go on), die with its
    parent (:func:`die_with_parent`) and record its share of the cores
    (:func:`thread_budget`)."""
    global _POOL_SIZE
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _POOL_SIZE = max(1, int(pool_size))
    die_with_parent(parent)


def _child(work: Callable, tasks, results, parent: int, pool_size: int = 1) -> None:
    """A worker's loop (a child of process ``parent``, one of ``pool_size``):
    take ``(index, item)`` until ``None``; report progress, results and
    failures on ``results``."""
    start_child(parent, pool_size)
    try:
        os.setpgrp()    # our own group, so the parent can kill what we start with us
    except OSError:
        pass
    while True:
        task = tasks.get()
        if task is None:
            return
        index, item = task

        def progress(text: str, _index=index) -> None:
            results.put(("progress", _index, text))

        try:
            results.put(("done", index, work(item, progress)))
        except BaseException as exc:  # noqa: BLE001 - reported to the parent, which raises it
            results.put(("error", index, _portable(exc)))


def _portable(exc: BaseException) -> BaseException:
    """``exc`` if it survives pickling (a CcoptError, say), else a WorkerFailed
    with its traceback text."""
    if isinstance(exc, CcoptError):
        try:
            pickle.loads(pickle.dumps(exc))
            return exc
        except Exception:  # noqa: BLE001 - anything unpicklable is carried as text
            pass
    failed = WorkerFailed(f"{type(exc).__name__}: {exc}")
    failed.child_traceback = "".join(traceback.format_exception(exc)).rstrip()
    return failed


def kill_processes(procs: Sequence) -> None:
    """Kill every child process (``multiprocessing`` processes) and the process
    group it leads, if any, and reap them."""
    for p in procs:
        if p.pid is None:
            continue
        for kill in (lambda pid: os.killpg(pid, signal.SIGKILL),
                     lambda pid: os.kill(pid, signal.SIGKILL)):
            try:
                kill(p.pid)
            except (OSError, AttributeError):
                continue
    for p in procs:
        p.join(REAP_SECONDS)


def remove_temps_of(pids: Iterable[int], folders: Iterable[Path]) -> list[Path]:
    """Remove the temporary files (``.NAME.ccopt-PID-N.tmp``) that processes
    ``pids`` left in ``folders``; returns what was removed."""
    pids = {int(p) for p in pids}
    removed = []
    for folder in folders:
        try:
            names = os.listdir(folder)
        except OSError:
            continue
        for name in names:
            m = _TEMP_RE.fullmatch(name)
            if m and int(m.group(1)) in pids:
                try:
                    os.unlink(Path(folder) / name)
                    removed.append(Path(folder) / name)
                except OSError:
                    pass
    return removed


def run_in_workers(work: Callable[[Any, Callable[[str], None]], Any], items: Sequence,
                   workers: int, on_progress: Callable[[int, str], None] | None = None,
                   on_done: Callable[[int, Any], None] | None = None,
                   temp_folders: Sequence[Path] = (),
                   order: Sequence[int] | None = None) -> list:
    """``[work(item, progress) for item in items]``, computed by ``workers``
    child processes (at most one per item).

    ``order``: the indices of ``items`` in the order the workers take them
    (default: as given); the results keep the order of ``items``. Giving the
    longest jobs first keeps both workers busy to the end (a long job taken
    last leaves the other worker idle for its whole length).

    ``work`` and the results cross process boundaries: ``work`` must be a
    module-level function (or picklable) when the platform cannot fork, and
    results must pickle. An exception in a job is raised here once every job
    has been stopped (the first one, by item order); so is KeyboardInterrupt.
    Whatever way this returns, no child is left running and their temporary
    files in ``temp_folders`` are gone.
    """
    if not items:
        return []
    ctx = fork_context()
    tasks, results = ctx.Queue(), ctx.Queue()
    for index in (order if order is not None else range(len(items))):
        tasks.put((index, items[index]))
    n = max(1, min(workers, len(items)))
    for _ in range(n):
        tasks.put(None)
    procs = [ctx.Process(target=_child, args=(work, tasks, results, os.getpid(), n),
                         daemon=False)
             for _ in range(n)]
    out: dict[int, Any] = {}
    errors: dict[int, BaseException] = {}
    try:
        for p in procs:
            p.start()
        while len(out) + len(errors) < len(items):
            try:
                kind, index, value = results.get(timeout=POLL_SECONDS)
            except queue.Empty:
                if not any(p.is_alive() for p in procs):
                    raise WorkerFailed("a worker process died (killed, or out of memory) "
                                       "before it reported its case") from None
                continue
            if kind == "progress":
                if on_progress:
                    on_progress(index, value)
            elif kind == "done":
                out[index] = value
                if on_done:
                    on_done(index, value)
            else:
                errors[index] = value
                break
    finally:
        kill_processes(procs)
        remove_temps_of([p.pid for p in procs if p.pid], temp_folders)
        tasks.close()
        results.close()
    if errors:
        raise errors[min(errors)]
    return [out[i] for i in range(len(items))]


@contextmanager
def process_pool(workers: int):
    """A ``concurrent.futures`` pool of ``workers`` processes for jobs handed
    out one at a time (``pool.submit``), each process started by
    :func:`start_child` and forked where the platform can (they start with
    ccopt and its libraries loaded, :func:`fork_context`). Left normally,
    after every job is done; on a Ctrl-C or an error, at once: the workers
    killed (a library pool lets each finish its task first, seconds on a
    long plan)."""
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=fork_context(),
                               initializer=start_child, initargs=(os.getpid(), workers))
    done = False
    try:
        yield pool
        done = True
    finally:
        if not done:
            kill_processes(list((getattr(pool, "_processes", None) or {}).values()))
        pool.shutdown(wait=done, cancel_futures=True)


#: The environment variable that gives a worker of :func:`run_in_interpreters`
#: its parent's process id.
PARENT_ENV = "CCOPT_WORKER_PARENT"


def interpreter_command(module: str, function: str) -> str:
    """What a worker of :func:`run_in_interpreters` runs (``python -c``):
    :func:`serve_pipe` of ``module.function``."""
    return f"from ccopt.workers import serve_pipe; serve_pipe({module!r}, {function!r})"


def run_in_interpreters(module: str, function: str, tasks: Sequence[tuple],
                        workers: int) -> list:
    """``[module.function(*args) for args in tasks]``, in ``workers`` processes,
    in order.

    Each process runs :func:`serve_pipe` (a fresh interpreter that imports
    only ``module``, never the caller's main script, as ``multiprocessing``'s
    ``spawn`` would), fed one task at a time by a thread of this process, so
    the processes stay evenly loaded. A task a process could not return (it
    could not start, or died) is done here afterwards, so a failure in it
    shows with its own traceback. ``function`` must be a module-level
    function; its arguments and results cross the pipes pickled."""
    call = getattr(importlib.import_module(module), function)
    command = interpreter_command(module, function)
    missing = object()
    results: list = [missing] * len(tasks)
    todo = deque(range(len(tasks)))
    env = dict(os.environ)
    # the ccopt this process runs, first on the path (a source tree, say)
    root = str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in [env.get("PYTHONPATH")] if p])
    env[PARENT_ENV] = str(os.getpid())

    def serve():
        try:
            proc = subprocess.Popen([sys.executable, "-c", command], stdin=subprocess.PIPE,
                                    stdout=subprocess.PIPE, env=env)
        except OSError:
            return
        try:
            while todo:
                try:
                    i = todo.popleft()
                except IndexError:
                    break
                pickle.dump(tasks[i], proc.stdin, protocol=pickle.HIGHEST_PROTOCOL)
                proc.stdin.flush()
                results[i] = pickle.load(proc.stdout)
        except (OSError, EOFError, pickle.UnpicklingError):
            pass                        # that task is done here afterwards
        finally:
            try:
                proc.stdin.close()
            except OSError:
                pass
            proc.wait()

    threads = [threading.Thread(target=serve, daemon=True) for _ in range(workers)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return [r if r is not missing else call(*tasks[i]) for i, r in enumerate(results)]


def serve_pipe(module: str, function: str) -> None:
    """A worker of :func:`run_in_interpreters`: pickled argument tuples on
    stdin, ``module.function``'s results on stdout, until stdin closes.
    Anything else written to the standard output (a solver's banner from C,
    HiGHS's) goes to the standard error, so the result stream stays clean.
    It dies with its parent (:func:`die_with_parent`): a parent killed in
    the middle of a plan leaves no process solving on alone."""
    if os.environ.get(PARENT_ENV):
        die_with_parent(int(os.environ[PARENT_ENV]))
    results = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    call = getattr(importlib.import_module(module), function)
    tasks = sys.stdin.buffer
    while True:
        try:
            args = pickle.load(tasks)
        except EOFError:
            break
        pickle.dump(call(*args), results, protocol=pickle.HIGHEST_PROTOCOL)
        results.flush()
