"""ccopt.workers: jobs in child processes give what a loop gives, in order,
with their progress; failures come back as they were raised; nothing is left."""
from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from ccopt.errors import ProgramError
from ccopt.workers import WorkerFailed, run_in_workers


def _square_slowly(n: int, progress) -> tuple[int, int]:
    progress(f"squaring {n}")
    time.sleep(0.05 * (3 - n % 3))      # later items finish first
    return n, n * n


def _fail(item, progress):
    kind, folder = item
    # a temporary file as ccopt.atomic names it, left behind by this process
    Path(folder, f".out.nc.ccopt-{os.getpid()}-0.tmp").write_text("partial")
    if kind == "program":
        raise ProgramError("bad word", "part.nc", 3)
    raise ValueError("a bug")


def test_results_in_item_order_with_their_progress():
    heard = []
    items = list(range(6))
    got = run_in_workers(_square_slowly, items, 2,
                         on_progress=lambda i, text: heard.append((i, text)))
    assert got == [(n, n * n) for n in items]
    assert sorted(heard) == [(n, f"squaring {n}") for n in items]


def test_order_is_the_order_taken_and_results_keep_item_order():
    # one worker takes the items exactly in the order given; the results come
    # back indexed as the items were
    done = []
    items = [10, 11, 12, 13]
    got = run_in_workers(_square_slowly, items, 1, on_done=lambda i, r: done.append(i),
                         order=[2, 0, 3, 1])
    assert got == [(n, n * n) for n in items]
    assert done == [2, 0, 3, 1]


def test_run_takes_the_largest_program_first(tmp_path):
    from ccopt.cases import resolve_input
    from ccopt.run import longest_first
    sizes = {"a.nc": 30, "b.nc": 500, "c.nc": 120}
    for name, n in sizes.items():
        (tmp_path / name).write_text("G0 X0\n" + "(pad)\n" * (n // 7))
    jobs = [resolve_input(str(tmp_path / name)) for name in sizes]
    assert longest_first(jobs) == [1, 2, 0]


def test_more_workers_than_items_and_no_items():
    assert run_in_workers(_square_slowly, [4], 8) == [(4, 16)]
    assert run_in_workers(_square_slowly, [], 2) == []


@pytest.mark.parametrize("kind, error, text", [
    ("program", ProgramError, "part.nc:3: bad word"),
    ("bug", WorkerFailed, "ValueError: a bug"),
])
def test_a_failure_is_raised_here_and_its_temp_file_removed(tmp_path, kind, error, text):
    with pytest.raises(error) as exc:
        run_in_workers(_fail, [(kind, str(tmp_path))], 1, temp_folders=[tmp_path])
    assert str(exc.value) == text
    if error is WorkerFailed:
        assert "ValueError: a bug" in exc.value.child_traceback
        assert "_fail" in exc.value.child_traceback
    assert list(tmp_path.iterdir()) == []
