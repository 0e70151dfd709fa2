"""A tool path's lines and arcs as columns, and their numbers as written text.

The writers (:mod:`.gcode`, :mod:`.pmacprog`) write most of a long path as
runs of plain lines and arcs, with nothing between them but the moves
themselves; such a run is written from the columns here in one go instead of
move by move. Every number must come out as the move-by-move writer makes
it, to the last bit and the last character: the columns are computed with
the same floating-point operations in the same order as the geometry's own
properties (:attr:`Arc.start <ccopt.geometry.Arc.start>` is ``centre +
radius * math.cos(theta0)``, with ``math.cos``, not numpy's), and rounding
and text are Python's :func:`round` and float formatting, made from the
nearest decimal where that is known without them (:func:`nearest_decimals`)
and asked of Python elsewhere.
"""
from __future__ import annotations

import math
from itertools import chain, repeat
from operator import attrgetter, is_not

import numpy as np

from ccopt.geometry import Arc, Line
from ccopt.geometry.columns import math_each
from ccopt.toolpath import ARC_ROW, LINE_ROW, ToolPath

#: Row kinds of :class:`PlainColumns`: a line, an arc, anything else.
LINE, ARC, OTHER = 0, 1, 2

_GEOM, _W0, _W1, _FEED = attrgetter("geom"), attrgetter("w0"), attrgetter("w1"), attrgetter("feed")
_P1 = attrgetter("p1")
_CENTER, _RADIUS, _THETA0, _SWEEP = (attrgetter("center"), attrgetter("radius"),
                                     attrgetter("theta0"), attrgetter("sweep"))
#: What :func:`fmt_many` writes instead of a number that rounds to nothing.
_ZERO = {"-0": "0", "": "0"}
#: Decimal arithmetic of :func:`nearest_decimals` below this many units of
#: the last decimal: integers and the fraction of each are exact doubles
#: (from 2**52 on, doubles have no fraction).
_EXACT_INTEGERS = 2.0 ** 50
#: The largest power of ten that is an exact double (10**22).
_EXACT_POWERS = 22
#: The largest power of ten that is an int64 (10**18), :func:`_written`'s arithmetic.
_INT64_POWERS = 18
#: A character of :func:`_written` that is no character of the text (0:
#: what a digit, sign or point left out is multiplied to).
_GAP = 0


def nearest_decimals(x: np.ndarray, digits: int) -> tuple[np.ndarray, np.ndarray]:
    """``N``, the integer nearest to ``x * 10**digits`` (ties to even), where
    it is known without decimal conversion, and where that is (``known``).

    The double product is within half an ulp of the exact one, so it has the
    same nearest integer unless a half-integer lies within an ulp of it (a
    tie, or nearly): unknown there, and for numbers too large or not finite."""
    if not 0 <= digits <= _EXACT_POWERS:
        return np.zeros_like(x), np.zeros(x.shape, dtype=bool)
    with np.errstate(invalid="ignore", over="ignore"):
        p = x * 10.0 ** digits
        a = np.abs(p)
        known = (a < _EXACT_INTEGERS) & (np.abs(a - np.floor(a) - 0.5) > np.spacing(a))
    return np.rint(p), known


def fmt_many(values, digits: int = 6) -> list[str]:
    """:func:`ccopt.export.gcode.fmt` of each of ``values``: ``digits``
    decimals, trailing zeros and a bare point removed, ``-0`` written ``0``.

    Python writes the digits of the nearest decimal (:func:`nearest_decimals`):
    where that is known, they are written from it, all at once; any other
    number (and any with no decimals, which ``fmt`` writes its own way) is
    formatted by Python."""
    x = np.asarray(values, dtype=float).reshape(-1)
    near, known = nearest_decimals(x, digits)
    if not 1 <= digits <= _INT64_POWERS:
        known[:] = False
    if known.all():
        return _written(near, digits)
    out = np.empty(x.size, dtype=object)
    out[known] = _written(near[known], digits)
    full = map(format, x[~known].tolist(), repeat(f".{digits}f"))
    text = list(map(str.rstrip, map(str.rstrip, full, repeat("0")), repeat(".")))
    out[~known] = list(map(_ZERO.get, text, text))
    return out.tolist()


def _written(near: np.ndarray, digits: int) -> list[str]:
    """The text of the decimals ``near / 10**digits`` (``near``: integers below
    :data:`_EXACT_INTEGERS`; ``digits``: 1 to :data:`_INT64_POWERS`) as ``fmt``
    writes them. Each is a row of characters: sign, every digit, point, line
    end; the sign of a positive number, the leading zeros, the trailing zeros
    of the fraction and a bare point are left as gaps that are taken out."""
    n = near.size
    if n == 0:
        return []
    a = np.abs(near).astype(np.int64)
    places = len(str(int(a.max() // 10 ** digits)))       # digits before the point
    width = places + digits
    figures = np.empty((width, n), dtype=np.uint8)         # digit by digit, column by column
    for k in range(width - 1, -1, -1):
        a, figures[k] = np.divmod(a, 10)
    nonzero = figures != 0
    kept = np.ones((width, n), dtype=bool)
    kept[:places - 1] = np.logical_or.accumulate(nonzero[:places - 1], axis=0)
    kept[places:] = np.logical_or.accumulate(nonzero[:places - 1:-1], axis=0)[::-1]
    chars = (figures + ord("0")) * kept
    rows = np.empty((n, width + 3), dtype=np.uint8)
    rows[:, 0] = (near < 0) * ord("-")
    rows[:, 1:places + 1] = chars[:places].T
    rows[:, places + 1] = kept[places] * ord(".")
    rows[:, places + 2:-1] = chars[places:].T
    rows[:, -1] = ord("\n")
    return rows.tobytes().translate(None, bytes([_GAP])).decode("ascii").split("\n")[:-1]


def rounded(values, digits: int) -> np.ndarray:
    """Python's ``round(x, digits)`` of each of ``values``.

    ``round`` gives the double nearest to the decimal nearest to ``x`` (ties
    to even) with ``digits`` decimals, ``N / 10**digits``: the quotient of
    two exact numbers, which division rounds the same way. Where ``N`` is not
    known (:func:`nearest_decimals`), ``round`` itself is asked."""
    x = np.asarray(values, dtype=float).reshape(-1)
    near, known = nearest_decimals(x, digits)
    out = x.copy()
    if known.any():
        out[known] = near[known] / 10.0 ** digits
    for k in np.flatnonzero(~known).tolist():
        out[k] = round(float(x[k]), digits)
    return out


def polar_points(cx, cy, radius, phi) -> tuple[np.ndarray, np.ndarray]:
    """``centre + radius * (cos phi, sin phi)`` as :class:`Arc` evaluates it."""
    return cx + radius * math_each(math.cos, phi), cy + radius * math_each(math.sin, phi)


def points(pairs, n: int) -> np.ndarray:
    """The ``n`` points ``pairs`` (an iterable of ``(u, v)``) as an ``(n, 2)`` array."""
    return np.fromiter(chain.from_iterable(pairs), float, 2 * n).reshape(n, 2)


def changes(values: list, current) -> list[int]:
    """Where a modal value changes along moves that set ``values`` in turn
    (``None``: a move that leaves it as it is), from ``current`` (``None``:
    none in force): the indices whose value is not ``None`` and differs
    (``!=``) from the last one before it that is, or from ``current``."""
    n = len(values)
    given = np.fromiter(map(is_not, values, repeat(None)), bool, n)
    if not given.any():
        return []
    numbers = np.array(values, dtype=float)          # None -> NaN, never compared
    last = np.maximum.accumulate(np.where(given, np.arange(n), -1))
    before = np.r_[-1, last[:-1]]
    differs = numbers != numbers[np.maximum(before, 0)]
    first = before < 0
    differs[first] = True if current is None else numbers[first] != current
    return np.flatnonzero(given & differs).tolist()


def run_ends(joins: np.ndarray) -> list[int]:
    """For each row ``i``, the first row after it that does not join the run
    before it (``joins`` False), or the number of rows."""
    n = len(joins)
    breaks = np.append(np.flatnonzero(~joins), n)
    return breaks[np.searchsorted(breaks, np.arange(n), side="right")].tolist()


class PlainColumns:
    """The segments of a tool path as columns, for writing runs of lines and arcs.

    Attributes (one row per segment; rows of other kinds hold NaN)
    ----------
    geoms: the segments' geometries; feeds: their feeds (``None``: rapid).
    kind: ``(n,)`` :data:`LINE`, :data:`ARC` or :data:`OTHER` (a geometry of
        exactly type :class:`Line` or :class:`Arc` only).
    start, end: ``(n, 2)`` in-plane start and end points (program units).
    center: ``(n, 2)`` an arc's centre; sweep: ``(n,)`` its signed sweep
        (radians, ``> 0`` counter-clockwise; 0 for lines); length: ``(n,)``
        an arc's length.
    w0, w1: ``(n,)`` out-of-plane coordinate at start and end.

    A path made from columns (:attr:`ToolPath.columns`) gives its numbers
    from them, the ones its segments were made of; any other, from its segments.
    """

    def __init__(self, path: ToolPath):
        segments = path.segments
        n = len(segments)
        self.geoms = list(map(_GEOM, segments))
        self.feeds = list(map(_FEED, segments))
        self.start = np.full((n, 2), np.nan)
        self.end = np.full((n, 2), np.nan)
        self.center = np.full((n, 2), np.nan)
        self.sweep = np.zeros(n)
        self.length = np.full(n, np.nan)
        rows = path.columns
        if rows is not None:
            self.kind = np.select([rows.kind == LINE_ROW, rows.kind == ARC_ROW], [LINE, ARC],
                                  OTHER).astype(np.int8)
            self.w0, self.w1 = rows.w[:, 0].copy(), rows.w[:, 1].copy()
            lines = np.flatnonzero(self.kind == LINE)
            self.end[lines] = rows.geom[lines, 2:4]
            arcs = np.flatnonzero(self.kind == ARC)
            self._arcs(arcs, rows.geom[arcs, :2], *rows.geom[arcs, 2:5].T)
            return
        self.w0 = np.fromiter(map(_W0, segments), float, n)
        self.w1 = np.fromiter(map(_W1, segments), float, n)
        types = list(map(type, self.geoms))
        lines = [i for i, t in enumerate(types) if t is Line]
        arcs = [i for i, t in enumerate(types) if t is Arc]
        self.kind = np.full(n, OTHER, dtype=np.int8)
        self.kind[lines] = LINE
        self.kind[arcs] = ARC
        if lines:
            self.end[lines] = points(map(_P1, map(self.geoms.__getitem__, lines)), len(lines))
        if arcs:
            geoms = list(map(self.geoms.__getitem__, arcs))
            self._arcs(arcs, points(map(_CENTER, geoms), len(geoms)),
                       *(np.fromiter(map(get, geoms), float, len(geoms))
                         for get in (_RADIUS, _THETA0, _SWEEP)))

    def _arcs(self, rows, center, radius, theta0, sweep) -> None:
        """The arcs of ``rows`` from their parameters, as :class:`Arc` evaluates them."""
        self.center[rows] = center
        self.sweep[rows] = sweep
        self.length[rows] = radius * np.abs(sweep)
        self.start[rows] = np.column_stack(polar_points(center[:, 0], center[:, 1], radius,
                                                        theta0))
        # Arc.end: the polar point at theta0 + sweep, the sum taken first
        self.end[rows] = np.column_stack(polar_points(center[:, 0], center[:, 1], radius,
                                                      theta0 + sweep))


__all__ = ["ARC", "LINE", "OTHER", "PlainColumns", "changes", "fmt_many", "nearest_decimals",
           "points", "polar_points", "rounded", "run_ends"]
