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
"""
from __future__ import annotations

import itertools
import os
import re
from pathlib import Path
from typing import Callable

from ccopt.errors import ProgramError

#: Mode a new output is created with before the umask applies (rw for all, as
#: ``open(..., "w")`` does).
NEW_FILE_MODE = 0o666

_counter = itertools.count()


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
    """Write ``data`` to ``path`` atomically; ProgramError naming the file on failure."""
    path = Path(path)
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
