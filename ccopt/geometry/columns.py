"""Column plumbing shared by the vectorised distance kernels.

The kernels of :mod:`ccopt.geometry.point_distance` and
:mod:`ccopt.geometry.curve_distance` work on 1-D float columns (x and y of
each point, each scalar) of one length ``N``, one pair per row, with no
Python loop over pairs. This module broadcasts inputs to such columns
(:func:`columns`), runs a kernel block by block (:func:`run_chunked`),
selects between candidates without branches (:func:`blend`), keeps the
running minimum of candidate pairs with their witnesses (:class:`RunningMin`)
and prepares per-arc quantities once per call (:class:`PreparedArcs`);
:func:`take_rows` and :func:`put_rows` gather and scatter rows of the
``(n, 2)`` point arrays, :func:`used_rows` finds the rows an index array uses;
:func:`math_each` applies a :mod:`math` function element by element.
Lengths are program units, angles radians.
"""
from __future__ import annotations

import gc
from contextlib import contextmanager

import numpy as np

from ccopt.geometry.angles import in_sweep_prepared

def used_rows(idx, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``(used, inverse)`` of indices ``idx`` into ``n`` rows: the rows used,
    ascending, each once, and per index its place among them; what
    ``np.unique(idx, return_inverse=True)`` gives, from a mask of the rows
    instead of a sort of the indices."""
    idx = np.asarray(idx, np.intp).reshape(-1)
    seen = np.zeros(n, bool)
    seen[idx] = True
    used = np.flatnonzero(seen)
    place = np.empty(n, np.intp)
    place[used] = np.arange(used.size)
    return used, place[idx]


def math_each(f, *cols) -> np.ndarray:
    """``f`` (a function of :mod:`math`, e.g. ``math.hypot``) element by
    element over equal-shape float columns, shaped as the first: the bits
    :mod:`math` gives, where numpy's own ufuncs (``np.hypot``, ``np.cos``)
    may differ in the last bit from the scalar code they stand beside."""
    first = np.asarray(cols[0])
    args = (np.asarray(c, float).ravel().tolist() for c in cols)
    return np.fromiter(map(f, *args), float, first.size).reshape(first.shape)


def take_rows(a: np.ndarray, idx) -> np.ndarray:
    """``a[idx]`` for an index array or boolean mask ``idx``, by ``take``: the
    same values, several times faster on a narrow 2-D array (``(n, 2)``
    points), where numpy's fancy indexing takes a slow general road."""
    idx = np.asarray(idx)
    if idx.dtype == bool:
        idx = np.flatnonzero(idx)       # take would read the mask as indices 0 and 1
    return a.take(idx, axis=0)


def put_rows(a: np.ndarray, idx, rows: np.ndarray) -> None:
    """``a[idx] = rows``. For a C-contiguous ``(n, k)`` float ``a`` each row
    is written as one item of ``8 k`` bytes (a complex number for ``k = 2``,
    else raw bytes: its same bytes, no arithmetic), which numpy scatters
    several times faster than the rows of a 2-D array."""
    rows = np.asarray(rows)
    if isinstance(idx, np.ndarray) and a.dtype == np.float64 and a.ndim == 2 \
            and a.flags.c_contiguous and rows.ndim == 2 and rows.shape[1] == a.shape[1] > 0:
        row = np.complex128 if a.shape[1] == 2 else np.dtype((np.void, 8 * a.shape[1]))
        src = np.ascontiguousarray(rows, np.float64)
        a.view(row)[idx, 0] = src.view(row)[:, 0]
    else:
        a[idx] = rows           # anything else as numpy does it (a row broadcast, ...)


@contextmanager
def paused_gc():
    """Pause Python's cyclic garbage collector while a long program's objects
    are built one per block or segment (none of them in a reference cycle).

    Each collection of the oldest generation walks every live object (a
    100,000-block program is some millions), and building 100,000 segments
    set off several: most of the time of building them. Reference counting
    still frees everything as usual; the collector is switched back on (if
    it was on) on the way out, also on an exception.
    """
    was_on = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_on:
            gc.enable()


def columns(points, scalars=()):
    """Broadcast points (``(..., 2)``) and scalars to 1-D columns of one length.

    Returns ``(xs, ys, ss)``: lists of 1-D float arrays (x and y of each point,
    then each scalar), all of length ``N``.
    """
    pts = [np.asarray(p, dtype=float) for p in points]
    for p in pts:
        if p.shape[-1:] != (2,):
            raise ValueError(f"points must have a trailing axis of length 2, got shape {p.shape}")
    cols = [p[..., 0] for p in pts] + [p[..., 1] for p in pts]
    cols += [np.asarray(s, dtype=float) for s in scalars]
    shapes = {c.shape for c in cols}
    if len(shapes) != 1 or cols[0].ndim != 1:
        n = max(c.size for c in cols)
        if all(c.shape == (n,) or c.size == 1 for c in cols):
            # the usual mix, columns and single values (one point against many):
            # a filled column each, a tenth of np.broadcast_arrays' overhead
            cols = [c if c.shape == (n,) else np.full(n, c.reshape(-1)[0]) for c in cols]
        else:
            cols = np.broadcast_arrays(*cols)
            cols = [np.ravel(c) if c.ndim else c.reshape(1) for c in cols]
    k = len(pts)
    return cols[:k], cols[k:2 * k], cols[2 * k:]


#: Pairs per block: temporaries of this many doubles (64 KiB) stay in cache and
#: in the allocator's pool instead of being page-faulted in for every call.
CHUNK = 8192


def run_chunked(kernel, cols):
    """Apply ``kernel(*cols) -> (d, wa, wb)`` block by block over 1-D columns."""
    n = cols[0].shape[0]
    if n <= CHUNK:
        return kernel(*cols)
    d = np.empty(n)
    wa = np.empty((n, 2))
    wb = np.empty((n, 2))
    for i in range(0, n, CHUNK):
        sl = slice(i, i + CHUNK)
        d[sl], wa[sl], wb[sl] = kernel(*(c[sl] for c in cols))
    return d, wa, wb


def stack_xy(x, y):
    """Columns ``x``, ``y`` as rows ``(N, 2)``."""
    out = np.empty((x.shape[0], 2))
    out[:, 0] = x
    out[:, 1] = y
    return out


def norm(x, y):
    """Elementwise length of the vectors ``(x, y)``."""
    # sqrt(x^2 + y^2) is several times faster than np.hypot on large arrays;
    # over/underflow would need coordinates beyond 1e150, far outside any machine.
    return np.sqrt(x * x + y * y)


def blend(dst, src, take):
    """``dst[take] = src[take]`` branch-free: ``take`` is a 0/1 float array.

    Random masks make ``np.where``/``np.copyto(where=)`` mispredict on every
    element; this is a subtract, multiply and add. The result can differ from
    ``src`` by one rounding (``x + (y - x)``), far below any tolerance here.
    ``src`` must be finite where ``take`` is 0.
    """
    tmp = np.subtract(src, dst)
    tmp *= take
    dst += tmp


class RunningMin:
    """Running minimum over candidate pairs, with their witness coordinates.

    Candidates that are not on both curves are offered with ``valid=False``
    and never win; every offered distance and witness must be finite.
    """

    __slots__ = ("d", "ax", "ay", "bx", "by")

    def __init__(self, d, ax, ay, bx, by):
        n = d.shape[0]
        self.d = np.array(d, dtype=float)
        self.ax = np.array(np.broadcast_to(ax, (n,)), dtype=float)
        self.ay = np.array(np.broadcast_to(ay, (n,)), dtype=float)
        self.bx = np.array(np.broadcast_to(bx, (n,)), dtype=float)
        self.by = np.array(np.broadcast_to(by, (n,)), dtype=float)

    def offer(self, d, ax, ay, bx, by, valid=None):
        """Keep the candidate ``d`` with witnesses ``(ax, ay)``, ``(bx, by)`` where it is
        smaller than the best so far (and ``valid``, when given)."""
        better = d < self.d
        if valid is not None:
            better &= valid
        if not better.any():
            return
        take = better.astype(float)
        blend(self.d, d, take)
        blend(self.ax, ax, take)
        blend(self.ay, ay, take)
        blend(self.bx, bx, take)
        blend(self.by, by, take)

    def result(self):
        """``(d, wa, wb)``: the distances and the witness rows ``(N, 2)``."""
        return self.d, stack_xy(self.ax, self.ay), stack_xy(self.bx, self.by)


class PreparedArcs:
    """Per-arc quantities every kernel needs, computed once per call."""

    __slots__ = ("cx", "cy", "R", "th0", "sign", "abs_sweep", "e0x", "e0y", "e1x", "e1y")

    def __init__(self, cx, cy, R, th0, sw):
        self.cx, self.cy, self.R, self.th0 = cx, cy, R, th0
        self.sign = np.copysign(1.0, sw)
        self.abs_sweep = np.abs(sw)
        th1 = th0 + sw
        self.e0x = cx + R * np.cos(th0)
        self.e0y = cy + R * np.sin(th0)
        self.e1x = cx + R * np.cos(th1)
        self.e1y = cy + R * np.sin(th1)

    def contains(self, phi):
        """Is polar angle ``phi`` on the arc (see :func:`angle_in_sweep`)."""
        return in_sweep_prepared(phi, self.th0, self.sign, self.abs_sweep)
