"""Atomic file writes: a temporary file in the target folder, fsync, then rename.

Exports and the feed CSV both write through here.

A failure at any point leaves no partial file and never touches an existing
file of the same name (``os.replace`` is atomic on POSIX within a file system).
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ccopt.errors import ProgramError


def write_bytes_atomic(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically; ProgramError naming the file on failure."""
    path = Path(path)
    tmp_name = None
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp",
                                        dir=path.parent or ".")
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp_name, path)
        tmp_name = None
    except OSError as exc:
        raise ProgramError(f"cannot write: {exc.strerror or exc}", str(path)) from None
    finally:
        if tmp_name is not None:
            try:
                os.unlink(tmp_name)
            except OSError:
                pass


def write_text_atomic(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text version of :func:`write_bytes_atomic`."""
    write_bytes_atomic(path, text.encode("utf-8"))
