"""A sparse matrix as the compressed columns HiGHS takes, built from its entries.

The jerk planner's window LPs (:mod:`ccopt.feed.jerk.lp`) are small and
many (one per window and per local re-plan, thousands on a long program):
building each through ``scipy.sparse`` (a COO matrix, its CSC form, a
product with a diagonal scaling) cost most of a window's set-up. Here the
same arrays come from one sort and a few array operations.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Entries(NamedTuple):
    """A sparse matrix's entries: ``vals`` at ``(rows, cols)`` of ``n_rows`` rows."""

    rows: np.ndarray
    cols: np.ndarray
    vals: np.ndarray
    n_rows: int

    def above(self, other: "Entries") -> "Entries":
        """These rows, then ``other``'s below them."""
        return Entries(np.concatenate([self.rows, other.rows + self.n_rows]),
                       np.concatenate([self.cols, other.cols]),
                       np.concatenate([self.vals, other.vals]), self.n_rows + other.n_rows)


def compressed_columns(rows: np.ndarray, cols: np.ndarray, vals: np.ndarray, n_cols: int,
                       col_scale: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(start, index, value)``: the compressed columns of the matrix whose
    entries are ``vals`` at ``(rows, cols)`` (entries at one place summed in
    the order given), each column ``j`` then times ``col_scale[j]``, exact
    zeros left out, the row indices descending in each column. These are the
    arrays of scipy's ``csc_matrix((vals, (rows, cols))) @ diags(col_scale)``,
    which HiGHS was given before (the same sums and products: at most two
    entries share a place; the rows in the order its product leaves them),
    built without scipy's per-matrix overhead, most of a window's set-up."""
    order = np.lexsort((-rows, cols))
    r, c, v = rows[order], cols[order], vals[order]
    first = np.ones(r.size, bool)
    first[1:] = (r[1:] != r[:-1]) | (c[1:] != c[:-1])
    at = np.flatnonzero(first)
    if at.size < r.size:
        v = np.add.reduceat(v, at)
        r, c = r[at], c[at]
    keep = v != 0.0
    r, c, v = r[keep], c[keep], v[keep]
    start = np.zeros(n_cols + 1, np.int32)
    np.cumsum(np.bincount(c, minlength=n_cols), out=start[1:])
    return start, r.astype(np.int32), v * col_scale[c]
