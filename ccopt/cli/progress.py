"""Progress on a terminal: where a long command is inside its work.

A tqdm bar on stderr (the sweep's bar is tqdm too, :mod:`ccopt.sweep.engine`)
when stdout is a terminal and neither ``--json`` nor ``--quiet`` is given;
nothing otherwise (output to a file or a pipe stays clean). ``ccopt run``
shows the cases done of all and, beside it, each running case's stage
(read, compensate, feed, verify, compare with its variant k of n, export);
``compare``, ``smooth``, ``feed`` and ``verify`` show their stage. Each
level has one counter (cases k/n; variant k/n, or variants k/n done when
workers run them), a stage text too long is cut between words
(:func:`clip`), and a terminal that does not say its width gets a bar of
:data:`FALLBACK_COLUMNS`.
"""
from __future__ import annotations

import argparse
import os
import sys

#: the longest stage text shown per case on the bar, characters
STAGE_WIDTH = 60

#: the bar's width when the terminal does not say its own (a serial console,
#: an emulator that reports 0 columns): a bar of this many columns is drawn
FALLBACK_COLUMNS = 100


def clip(text: str, width: int) -> str:
    """``text`` in at most ``width`` characters, cut between words (never
    inside one) and ending with an ellipsis when cut."""
    if len(text) <= width:
        return text
    cut = text[:width - 1]
    space = cut.rfind(" ")
    if space > 0:
        cut = cut[:space]
    return cut.rstrip(" :,|") + "\u2026"


def terminal_columns() -> int | None:
    """The terminal's width from stderr, ``None`` when it does not say (or says 0)."""
    try:
        columns = os.get_terminal_size(sys.stderr.fileno()).columns
    except (OSError, ValueError, AttributeError):
        return None
    return columns or None


def wanted(args: argparse.Namespace) -> bool:
    """Whether this command shows progress: stdout and stderr on a terminal,
    no ``--json``, no ``--quiet``."""
    if getattr(args, "json", False) or getattr(args, "quiet", False):
        return False
    try:
        return sys.stdout.isatty() and sys.stderr.isatty()
    except (AttributeError, ValueError):   # a replaced or closed stream
        return False


def _bar(total: int | None, desc: str, unit: str):
    # Deferred: tqdm is only needed for a bar on a terminal.
    from tqdm import tqdm
    # no monitor thread: ccopt run forks its workers while the bar is up
    tqdm.monitor_interval = 0
    # a terminal that does not say its width still gets a bar, of a fixed width
    known = terminal_columns() is not None
    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, dynamic_ncols=known,
                ncols=None if known else FALLBACK_COLUMNS, leave=False,
                bar_format=None if total else "{desc} [{elapsed}]{postfix}")


class CasesProgress:
    """``ccopt run``'s bar: cases done of ``labels``, the running cases' stages
    beside it (:class:`ccopt.run.RunProgress`)."""

    def __init__(self, labels: list[str]):
        self.labels = labels
        self.current: dict[int, str] = {}
        self.bar = _bar(len(labels), "cases", "case")

    def stage(self, index: int, text: str) -> None:
        self.current[index] = clip(f"{self.labels[index]}: {text}", STAGE_WIDTH)
        self._show()

    def done(self, index: int, row: dict) -> None:
        self.current.pop(index, None)
        self.bar.update(1)
        self._show()

    def _show(self) -> None:
        self.bar.set_postfix_str(" | ".join(self.current[k] for k in sorted(self.current)))

    def close(self) -> None:
        self.bar.close()


class StageProgress:
    """One command's stage (``read``, ``compensate``, ``compare: variant 3 of
    10 opt-casadi``, ...) on a bar that counts time."""

    def __init__(self, command: str):
        self.bar = _bar(None, command, "")

    def __call__(self, text: str) -> None:
        self.bar.set_postfix_str(clip(text, STAGE_WIDTH * 2))

    def close(self) -> None:
        self.bar.close()


class Silent:
    """No progress: every call does nothing."""

    def __call__(self, text: str) -> None:
        pass

    def stage(self, index: int, text: str) -> None:
        pass

    def done(self, index: int, row: dict) -> None:
        pass

    def close(self) -> None:
        pass


def stage_progress(args: argparse.Namespace, command: str):
    """A :class:`StageProgress` when :func:`wanted`, else :class:`Silent`."""
    return StageProgress(command) if wanted(args) else Silent()


def cases_progress(args: argparse.Namespace, labels: list[str]):
    """A :class:`CasesProgress` when :func:`wanted`, else :class:`Silent`."""
    return CasesProgress(labels) if wanted(args) else Silent()
