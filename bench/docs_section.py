"""The marked section of a Markdown page that a benchmark script writes: its
figures go into the page between ``<!-- NAME: begin -->`` and
``<!-- NAME: end -->``, so no figure in the docs is typed by hand."""
from __future__ import annotations

import contextlib
import datetime
import io
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def markers(name: str) -> tuple[str, str]:
    """The begin and end markers of section ``name`` (e.g. ``bench/run.py``)."""
    return f"<!-- {name}: begin -->", f"<!-- {name}: end -->"


def write_section(path: Path, name: str, body: str) -> None:
    """Replace section ``name`` of ``path`` by ``body`` (markers kept); append the
    section when the page has none."""
    begin, end = markers(name)
    section = f"{begin}\n{body.strip()}\n{end}"
    text = path.read_text() if path.exists() else ""
    if begin in text and end in text:
        head, _, rest = text.partition(begin)
        _, _, tail = rest.partition(end)
        text = head + section + tail
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    path.write_text(text)


def commit() -> str:
    """This checkout's short commit id (``unknown`` outside git)."""
    proc = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True)
    return proc.stdout.strip() or "unknown"


def now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


#: Iterations of :func:`speed_reference`'s loop (about 10-20 ms of CPU here).
REFERENCE_LOOP = 200_000


def speed_reference() -> float:
    """Milliseconds of CPU time a fixed CPython loop takes in this process
    (median of 5): this host's speed drifts by up to 2x within an hour with
    the load average unchanged (another tenant of the host, not a process
    here), so a section's figures compare with another section's in
    proportion to their references (larger: a slower machine)."""
    def loop() -> float:
        x = 0.0
        for i in range(REFERENCE_LOOP):
            x += (i % 7) * 0.5
        return x
    times = []
    for _ in range(5):
        t = time.process_time()
        loop()
        times.append(time.process_time() - t)
    return statistics.median(times) * 1e3


def machine(load_before: tuple, load_after: tuple, speed: tuple | None = None) -> str:
    """Cores, platform, Python, the load average (1/5/15 min) before and after a
    run and, when given, :func:`speed_reference` before and after it (ms)."""
    def fmt(load):
        return "/".join(f"{x:.2f}" for x in load)
    out = (f"{os.cpu_count()} cores, {platform.platform()}, Python "
           f"{platform.python_version()}; load average (1/5/15 min) {fmt(load_before)} "
           f"before, {fmt(load_after)} after")
    if speed is not None:
        out += (f"; speed reference (bench/docs_section.py: a fixed Python loop, larger is "
                f"slower) {speed[0]:.1f} ms before, {speed[1]:.1f} ms after")
    return out


class _Tee(io.TextIOBase):
    """Writes to the real stdout and keeps a copy."""

    def __init__(self, out):
        self.out, self.kept = out, io.StringIO()

    def write(self, text: str) -> int:
        self.kept.write(text)
        return self.out.write(text)

    def flush(self) -> None:
        self.out.flush()


@contextlib.contextmanager
def printed_section(page: Path | None, name: str, command: str, title: str):
    """Run the body with what it prints kept; with ``page``, write it there as
    section ``name``: ``title`` (a heading), ``command`` with the date, the
    commit and the machine, and the printed figures as they were printed."""
    if page is None:
        yield
        return
    load_before, speed_before = os.getloadavg(), speed_reference()
    tee = _Tee(sys.stdout)
    with contextlib.redirect_stdout(tee):
        yield
    speed = (speed_before, speed_reference())
    write_section(page, name,
                  f"### {title}\n\n`{command}` on {now()}, commit {commit()}: "
                  f"{machine(load_before, os.getloadavg(), speed)}.\n\n"
                  f"```\n{tee.kept.getvalue().rstrip()}\n```")
