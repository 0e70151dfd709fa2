"""Independent jobs in worker processes, stoppable at once (``ccopt run``).

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

import multiprocessing
import os
import pickle
import queue
import re
import signal
import traceback
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


def start_child(parent: int) -> None:
    """What a worker process (a child of process ``parent``) does first: ignore
    SIGINT (the parent decides, and kills it: a solver such as IPOPT may catch
    the signal and go on) and die with its parent (:func:`die_with_parent`)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    die_with_parent(parent)


def _child(work: Callable, tasks, results, parent: int) -> None:
    """A worker's loop (a child of process ``parent``): take ``(index, item)``
    until ``None``; report progress, results and failures on ``results``."""
    start_child(parent)
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
    procs = [ctx.Process(target=_child, args=(work, tasks, results, os.getpid()),
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
