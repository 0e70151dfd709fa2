"""Atomic file writes: a temporary file in the target folder, fsync, then rename.

Exports, reports, the feed CSV and the sweep's tables all write through here.

A failure at any point leaves no partial file and never touches an existing
file of the same name (``os.replace`` is atomic on POSIX within a file system).

Files as users expect them:

* **permissions**: a new file gets ``0666 & ~umask``, what any program the
  user runs creates (the temporary file is created with mode 0666 and the
  kernel applies the umask; ``tempfile.mkstemp`` would give 0600);
* **temporary files** are named ``.NAME.ccopt-PID-N.tmp`` beside ``NAME``
  (PID the writing process, N a counter within it). A run killed between
  creating and renaming one leaves it behind; the next write of the same
  ``NAME`` removes every such file whose process no longer runs.

**Inputs are never written over** (issue 29). :func:`refuse_overwriting_inputs`
refuses (a :class:`ProgramError` naming the output, exit 2) an output that
*is* an input: the same file after resolving links (the same device and
inode, so a symlink or a hard link to it counts too). The commands call it
with every file they are about to write before they write the first
(``ccopt run p.pmc -o .`` writes nothing), :func:`ccopt.export.export`
with the files its program was read from. As a backstop, while a command of
the command line runs (:func:`inputs_guarded`, which :func:`ccopt.cli.main`
enters) every file a job's program was read from (the program, subroutine
files, tool table, parameter file: its ``INPUT_FILES``, remembered by
:meth:`ccopt.cases.ReadOptions.read` with :func:`protect_input`), and every
write through this module whose target is one of them is refused before
anything is written. Outside it (the Python API) only the explicit checks
apply, so a session may read a file it exported and export it again.
"""
from __future__ import annotations

import itertools
import os
import re
import stat
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Callable

from ccopt.errors import ProgramError

#: Mode a new output is created with before the umask applies (rw for all, as
#: ``open(..., "w")`` does).
NEW_FILE_MODE = 0o666

_counter = itertools.count()


#: The input files read within :func:`inputs_guarded`: their identity
#: (:func:`_identity`) -> the name they were read by.
_protected: dict[tuple[int, int, int, int], str] = {}
#: How many :func:`inputs_guarded` blocks are open (inputs are remembered when > 0).
_guards = 0


@contextmanager
def inputs_guarded() -> Iterator[None]:
    """Within it, every input file the readers read is remembered
    (:func:`protect_input`) and no write through this module may replace
    one; on the way out the files remembered within are forgotten. Worker
    processes forked within inherit what was remembered."""
    global _guards
    before = dict(_protected)
    _guards += 1
    try:
        yield
    finally:
        _guards -= 1
        _protected.clear()
        _protected.update(before)


def _identity(path: str | os.PathLike) -> tuple[int, int, int, int] | None:
    """``(device, inode, size, mtime ns)`` of the regular file ``path`` (links
    followed), ``None`` when there is none. Size and time keep an inode the
    file system has reused for a new file from matching an input read before."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    if not stat.S_ISREG(st.st_mode):
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def protect_input(path: str | os.PathLike) -> None:
    """Within :func:`inputs_guarded`, remember ``path``, a file just read as
    input: no write through this module may then replace it (nothing happens
    when it is not a file, or outside)."""
    if not _guards:
        return
    key = _identity(path)
    if key is not None:
        _protected[key] = str(path)


def _how(out: str, inp: str) -> str:
    """Why ``out`` is the file ``inp``: the same name, a link, or a hard link."""
    if os.path.islink(out):
        return f"a link to the input {inp}"
    if os.path.realpath(out) == os.path.realpath(inp):
        return f"the input {inp}" if os.path.normpath(out) == os.path.normpath(inp) \
            else f"the input {inp} (the same file by another path)"
    return f"the input {inp} (a hard link to it)"


def refuse_overwriting_inputs(outputs: Iterable[str | os.PathLike | None],
                              inputs: Iterable[str | os.PathLike | None] = ()) -> None:
    """Raise :class:`ProgramError` (exit 2, naming the output) when one of
    ``outputs`` is one of ``inputs`` or an input this process has read
    (:func:`protect_input`, within :func:`inputs_guarded`): the same file once
    links are resolved (same device and inode). ``None`` entries are skipped;
    outputs that do not exist yet replace nothing. Call it with every file a command will write before
    writing the first, so a refusal leaves everything as it was."""
    given = {}
    for p in inputs:
        if p is not None:
            key = _identity(p)
            if key is not None:
                given[key] = str(p)
    known = {**_protected, **given}
    if not known:
        return
    for out in outputs:
        if out is None:
            continue
        key = _identity(out)
        if key is not None and key in known:
            raise ProgramError(f"not written: the output is {_how(str(out), known[key])}, and "
                               "ccopt never writes over its inputs; choose another output name",
                               str(out))


def job_inputs(*jobs) -> list[Path]:
    """The files a :class:`ccopt.cases.Job` reads: its program, tool table,
    parameter file, tool path file and its case's ``case.toml`` (those it has)."""
    files: list[Path] = []
    for job in jobs:
        reading = getattr(job, "reading", None)
        case = getattr(job, "case", None)
        for f in (getattr(job, "program", None), getattr(reading, "tool_table", None),
                  getattr(reading, "var_file", None), getattr(job, "toolpath", None),
                  case.folder / "case.toml" if case is not None else None):
            if f is not None and not isinstance(f, dict):   # a tool table may be a dict
                files.append(Path(f))
    return files


def temp_name(target: Path, pid: int, n: int) -> Path:
    """The temporary file beside ``target`` that process ``pid`` writes as its
    ``n``-th temporary file."""
    return target.with_name(f".{target.name}.ccopt-{pid}-{n}.tmp")


def _pid_alive(pid: int) -> bool:
    """Whether process ``pid`` exists on this machine (signal 0 probes it)."""
    if pid <= 0:
        return False            # 0 and negative pids address process groups, never a writer
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True             # exists, owned by another user
    except OSError:
        return True             # cannot tell: keep the file
    return True


def remove_stale_temps(target: Path) -> list[Path]:
    """Remove the temporary files of ``target`` that dead processes left
    (killed between writing and renaming); returns the removed files.

    Files of live processes (a concurrent writer) and of this process are kept.
    """
    pattern = re.compile(rf"\.{re.escape(target.name)}\.ccopt-(\d+)-\d+\.tmp")
    folder = target.parent
    try:
        names = os.listdir(folder if str(folder) else ".")
    except OSError:
        return []
    removed = []
    for name in names:
        m = pattern.fullmatch(name)
        if m is None:
            continue
        pid = int(m.group(1))
        if pid == os.getpid() or _pid_alive(pid):
            continue
        try:
            os.unlink(folder / name)
            removed.append(folder / name)
        except OSError:
            pass                # gone already, or not ours to remove
    return removed


def _create_temp(target: Path) -> tuple[int, Path]:
    """A new, empty temporary file for ``target``: ``(fd, path)``, mode
    :data:`NEW_FILE_MODE` less the umask."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    while True:
        tmp = temp_name(target, os.getpid(), next(_counter))
        try:
            return os.open(tmp, flags, NEW_FILE_MODE), tmp
        except FileExistsError:
            continue            # left by an earlier process that had our pid: next number


def _unlink_quietly(path: Path | None) -> None:
    if path is not None:
        try:
            os.unlink(path)
        except OSError:
            pass


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically; ProgramError naming the file on
    failure, or when ``path`` is an input (:func:`refuse_overwriting_inputs`)."""
    path = Path(path)
    refuse_overwriting_inputs([path])
    tmp_name = None
    try:
        remove_stale_temps(path)
        fd, tmp_name = _create_temp(path)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp_name, path)
        tmp_name = None
    except OSError as exc:
        raise ProgramError(f"cannot write: {exc.strerror or exc}", str(path)) from None
    finally:
        _unlink_quietly(tmp_name)


def write_text_atomic(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text version of :func:`write_bytes_atomic`."""
    write_bytes_atomic(path, text.encode("utf-8"))


def write_with_atomic(path: str | os.PathLike, write: Callable[[Path], None]) -> None:
    """Atomic write for a library that writes files itself (pandas, matplotlib):
    ``write(tmp)`` fills the temporary file (named and created as above, so it
    has the umask's permissions), then it replaces ``path``.

    Errors of ``write`` other than OSError propagate unchanged; no temporary
    file is left either way.
    """
    path = Path(path)
    refuse_overwriting_inputs([path])
    tmp_name = None
    try:
        remove_stale_temps(path)
        fd, tmp_name = _create_temp(path)
        os.close(fd)
        write(tmp_name)
        os.replace(tmp_name, path)
        tmp_name = None
    except OSError as exc:
        raise ProgramError(f"cannot write: {exc.strerror or exc}", str(path)) from None
    finally:
        _unlink_quietly(tmp_name)
