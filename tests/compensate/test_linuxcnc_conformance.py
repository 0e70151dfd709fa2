"""LinuxCNC conformance of the ``linuxcnc`` compensation style.

For every one of the 75 subroutine calls of LinuxCNC's own cutter-compensation
torture test (``crazy-paths/test.ngc``: 25 paths x no compensation, right and
left with r = 0.25), the tool path ccopt makes must be the same sequence of
canonical moves LinuxCNC's interpreter prints in ``expected``:
``STRAIGHT_TRAVERSE``/``STRAIGHT_FEED`` (end point) and ``ARC_FEED`` (end
point, centre, turn), every figure within 5e-5 (``expected`` prints 4
decimals).

The data is kept in ``tests/conformance/linuxcnc`` (source and licence in its
README). A missing copy is a failure, not a skip.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from ccopt.compensate import compensate
from ccopt.program.gcode import read_gcode
from linuxcnc_data import N_CALLS, TOL, canonical_moves, data_file, expected_calls, split_calls


def _data(name: str) -> Path:
    return data_file(name)


@pytest.fixture(scope="module")
def program():
    path = _data("test.ngc")
    return read_gcode(path.read_text(), str(path))


@pytest.fixture(scope="module")
def ours(program):
    return split_calls(canonical_moves(compensate(program, style="linuxcnc")))


@pytest.fixture(scope="module")
def theirs():
    return expected_calls()


def _label(k: int) -> str:
    arg = ("0", "-.5 (right, r 0.25)", ".5 (left, r 0.25)")[k % 3]
    return f"call {k} (path {k // 3}, #1 = {arg})"


def test_every_call_is_there(ours, theirs):
    assert len(theirs) == N_CALLS, "expected output should hold 25 paths x 3 radii"
    assert len(ours) == N_CALLS, f"the linuxcnc tool path splits into {len(ours)} calls, want 75"


def _compare(k: int, got, want) -> list[str]:
    """Every difference of one call, as readable lines (empty: identical)."""
    kinds_got = [g[0] for g in got]
    kinds_want = [w[0] for w in want]
    if kinds_got != kinds_want:
        return [f"{_label(k)}: move sequence differs:\n  ccopt    {kinds_got}\n"
                f"  LinuxCNC {kinds_want}"]
    problems = []
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        names = ("end x", "end y") if kind != "ARC_FEED" else (
            "end x", "end y", "centre x", "centre y")
        for q, name in enumerate(names):
            if not abs(a[q] - b[q]) <= TOL:
                problems.append(f"{_label(k)} move {i} ({kind}) {name}: ccopt {a[q]:.6f}, "
                                f"LinuxCNC {b[q]:.4f} (off by {abs(a[q] - b[q]):.2e})")
        if kind == "ARC_FEED" and int(a[4]) != int(b[4]):
            problems.append(f"{_label(k)} move {i} (ARC_FEED) turn: ccopt {int(a[4])}, "
                            f"LinuxCNC {int(b[4])}")
    return problems


@pytest.mark.parametrize("k", range(N_CALLS))
def test_call_matches_linuxcnc(k, ours, theirs):
    assert k < len(ours) and k < len(theirs), f"{_label(k)} missing"
    problems = _compare(k, ours[k], theirs[k])
    assert not problems, "\n".join(problems)


def test_all_calls_match_and_largest_deviation(ours, theirs):
    """One summary: how many calls match, and the largest deviation of any figure."""
    matching, worst, where = 0, 0.0, None
    for k, (got, want) in enumerate(zip(ours, theirs)):
        if _compare(k, got, want):
            continue
        matching += 1
        for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
            for q in range(4 if kind == "ARC_FEED" else 2):
                if abs(a[q] - b[q]) > worst:
                    worst, where = abs(a[q] - b[q]), (k, i)
    print(f"linuxcnc conformance: {matching}/{N_CALLS} calls match, largest deviation "
          f"{worst:.3e} at call/move {where}")
    assert matching == N_CALLS
    assert worst <= TOL


def test_the_spec_example_entry_point(ours):
    """Spec, LinuxCNC rule 2: the left-side entry of the first path is pulled back
    to (-99.7500, -101.0449) by the inside corner that follows it."""
    kind, nums = ours[2][1]
    assert kind == "STRAIGHT_FEED"
    assert nums[0] == pytest.approx(-99.75, abs=TOL)
    assert nums[1] == pytest.approx(-101.0449, abs=TOL)
