"""LinuxCNC's own cutter-compensation test data (``crazy-paths``), kept in
``tests/conformance/linuxcnc`` (source and licence in its README).

A missing copy is a test failure, never a skip.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

CONFORMANCE = Path(__file__).resolve().parent / "conformance" / "linuxcnc"
DATA = CONFORMANCE / "crazy-paths"
TOL = 5e-5  # `expected` prints its figures to 4 decimals
N_CALLS = 75
_CANON = re.compile(r"\b(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|COMMENT)\((.*)\)\s*$")


def data_file(name: str) -> Path:
    path = DATA / name
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path} (kept in the repository "
                    "under tests/conformance/linuxcnc/crazy-paths)")
    return path


def split_calls(items) -> list[list[tuple[str, object]]]:
    """Split ``[(kind, value)]`` into calls at every STRAIGHT_TRAVERSE (every
    call of test.ngc starts with its own G0 and has no other)."""
    calls: list[list[tuple[str, object]]] = []
    for kind, value in items:
        if kind == "STRAIGHT_TRAVERSE" or not calls:
            calls.append([])
        calls[-1].append((kind, value))
    return calls


def expected_calls(comments: bool = False) -> list[list[tuple[str, object]]]:
    """``expected`` split into calls at each STRAIGHT_TRAVERSE (every call of
    test.ngc starts with its own G0 and has no other): ``[(kind, numbers)]``,
    plus ``("COMMENT", text)`` items when ``comments``."""
    items = []
    for line in data_file("expected").read_text().splitlines():
        m = _CANON.search(line)
        if not m:
            continue
        kind, args = m.groups()
        if kind == "COMMENT":
            if comments:
                items.append((kind, args.strip().strip('"')))
        else:
            items.append((kind, [float(a) for a in args.split(",")]))
    return split_calls(items)
