"""Gathering and scattering rows of point arrays
(:func:`ccopt.geometry.columns.take_rows`, :func:`~ccopt.geometry.columns.put_rows`,
issue 34): the same bytes as numpy's ``a[idx]`` and ``a[idx] = rows``, on
the ``(n, 2)`` arrays they are fast for and on the others they hand back to
numpy; every float is kept bit for bit (negative zeros, infinities, NaNs,
subnormals included); and :func:`~ccopt.geometry.columns.used_rows`, the rows
an index array uses as ``np.unique`` with its inverse gives them."""
from __future__ import annotations

import numpy as np
import pytest

from ccopt.geometry.columns import put_rows, take_rows, used_rows

SPECIAL = np.array([0.0, -0.0, np.inf, -np.inf, np.nan, 5e-324, -1e308, 1.5])


def _points(rng, n: int, cols: int = 2) -> np.ndarray:
    a = rng.normal(size=(n, cols)) * 10.0 ** rng.integers(-300, 300, size=(n, cols))
    a.flat[rng.integers(0, a.size, size=a.size // 5)] = rng.choice(SPECIAL, a.size // 5)
    return a


@pytest.mark.parametrize("seed", range(40))
def test_rows_equal_numpy_indexing_bit_for_bit(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(0, 200))
    cols = int(rng.choice([2, 2, 2, 3, 5]))
    a = _points(rng, n, cols)
    if n and rng.random() < 0.3:
        a = a[::2]                      # not C-contiguous rows
    m = a.shape[0]
    kinds = ["sorted", "any", "mask"] + (["repeats"] if m else [])
    for kind in kinds:
        if kind == "mask":
            idx = rng.random(m) < 0.5
            k = int(idx.sum())
        else:
            k = int(rng.integers(0, m + 1)) if kind != "repeats" else int(rng.integers(1, 2 * m + 2))
            idx = rng.choice(m, size=k, replace=kind == "repeats") if m else np.zeros(0, np.intp)
            if kind == "sorted":
                idx = np.sort(idx)
        assert take_rows(a, idx).tobytes() == a[idx].tobytes()
        rows = _points(rng, k, cols)
        want, got = a.copy(), a.copy()
        want[idx] = rows
        put_rows(got, idx, rows)
        assert got.tobytes() == want.tobytes()


def test_put_rows_broadcasts_as_numpy_does():
    a, b = np.zeros((5, 2)), np.zeros((5, 2))
    idx = np.array([0, 3])
    put_rows(a, idx, np.array([1.5, -2.0]))
    b[idx] = np.array([1.5, -2.0])
    put_rows(a, np.array([4]), 7.0)
    b[np.array([4])] = 7.0
    assert a.tobytes() == b.tobytes()


def test_put_rows_with_a_slice_writes_the_slice():
    a = np.zeros((6, 2))
    put_rows(a, slice(1, 4), np.arange(6.0).reshape(3, 2))
    assert a.tolist() == [[0, 0], [0, 1], [2, 3], [4, 5], [0, 0], [0, 0]]


@pytest.mark.parametrize("seed", range(20))
def test_used_rows_is_numpys_unique_with_inverse(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 300))
    idx = rng.integers(0, n, size=int(rng.integers(0, 3 * n)))
    if rng.random() < 0.5:
        idx = np.sort(idx)
    used, inv = used_rows(idx, n)
    want_used, want_inv = np.unique(idx, return_inverse=True)
    assert np.array_equal(used, want_used) and np.array_equal(inv, want_inv.reshape(-1))
    assert used.dtype == np.intp and inv.dtype == np.intp and inv.shape == idx.shape
