"""The exact in-plane geometry of a program's moves: one block's
(:func:`block_geometry`), or every move's at once as rows of numbers
(:func:`move_rows`), which :func:`ccopt.toolpath.programmed_path` keeps as a
column path instead of making one object per move.

In-plane coordinates are the block plane's ``(u, v)`` and the out-of-plane
``w`` (:data:`~ccopt.program.model.PLANE_AXES`); program units and radians,
a signed ``sweep`` counter-clockwise when positive. A circular move whose end
radius differs from its start radius is a :class:`~ccopt.geometry.Spiral`:
radius linear in swept angle (an Archimedean spiral, the only spiral ccopt
has; docs/compensation.md, "spiral radius linear in angle").
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import chain
from operator import attrgetter

import numpy as np

from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.primitives import arcs_from_polar, polar_ends
from ccopt.geometry.spiral import spirals_from_polar
from ccopt.program.columns import CCW_CODE, DWELL_CODE, RAPID_CODE, columns_of, triples_column
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.tolerances import SPIRAL_RADIUS_REL_TOL

_START, _END, _CENTER, _TURNS = map(attrgetter, ("start", "end", "center", "turns"))


def is_spiral_move(s, e, c) -> bool:
    """Whether the circular move from ``s`` to ``e`` about ``c`` (in-plane
    points) is a spiral: its end radius differs from its start radius by
    more than ``SPIRAL_RADIUS_REL_TOL * max(1, r0)``."""
    r0 = math.hypot(s[0] - c[0], s[1] - c[1])
    r1 = math.hypot(e[0] - c[0], e[1] - c[1])
    return abs(r1 - r0) > SPIRAL_RADIUS_REL_TOL * max(1.0, r0)


def block_geometry(block: Block, start_uv=None, end_uv=None):
    """Exact in-plane primitive of a programmed block.

    ``start_uv``/``end_uv`` override the block's own in-plane points (used by
    compensation for gradual changes about the programmed centre). A CIRCLE
    move whose end radius differs from its start radius is a :class:`Spiral`
    (:func:`is_spiral_move`).
    """
    s = block.start_uv if start_uv is None else start_uv
    e = block.end_uv if end_uv is None else end_uv
    if block.motion.is_arc:
        c = block.center_uv
        ccw = block.motion is Motion.ARC_CCW
        if is_spiral_move(s, e, c):
            return Spiral.from_points(s, e, c, ccw, turns=block.turns)
        return Arc.from_points(s, e, c, ccw, turns=block.turns)
    return Line(tuple(s), tuple(e))


@dataclass(frozen=True, eq=False)
class MoveRows:
    """Every move (block that is not a dwell) of a program, one row each, in order.

    move: ``(m,)`` int, the block's index in the program.
    rapid: ``(m,)`` bool, the move is a rapid.
    arc: ``(m,)`` bool, the move is an arc (not a spiral) given by its numbers.
    geom: ``(m, 5)`` float: a line's ``(u0, v0, u1, v1, 0)``, an arc's
        ``(cu, cv, radius, theta0, sweep)``; zeros for a spiral.
    spirals: row -> the :class:`Spiral` of the spiral moves.
    w: ``(m, 2)`` float, ``w`` at the move's start and end.

    The lines and arcs are what :func:`block_geometry` makes of their blocks,
    bit for bit, and are checked as the :class:`Line` and :class:`Arc`
    constructors check them (finite, radius > 0).
    """

    move: np.ndarray
    rapid: np.ndarray
    arc: np.ndarray
    geom: np.ndarray
    spirals: dict
    w: np.ndarray


def move_rows(program: Program) -> MoveRows | None:
    """The rows of ``program``'s moves; ``None`` when a block's coordinates
    are not all floats (a program built by hand, with integers: its segments
    keep its ``w`` values as they are written, which rows of floats do not).

    Raises ``ValueError`` when :func:`block_geometry` refuses a move (not
    necessarily the first such move: the caller asks :func:`block_geometry`,
    block by block, which one and why)."""
    blocks = program.blocks
    if not _floats_only(blocks):
        return None
    cols = columns_of(program)
    move = np.flatnonzero(cols.motion_code != DWELL_CODE)
    # each block's (u, v, w) axes, from its run of one modal state
    axes = np.array([PLANE_AXES[cols.modals[q].plane] for q in cols.modal_first.tolist()],
                    np.intp).reshape(-1, 3)
    axes = np.repeat(axes, cols.modal_runs(), axis=0)[move]
    start = np.take_along_axis(cols.start[move], axes, axis=1)
    end = np.take_along_axis(cols.end[move], axes, axis=1)
    geom = np.zeros((move.size, 5))
    geom[:, :2], geom[:, 2:4] = start[:, :2], end[:, :2]
    curved = np.flatnonzero(cols.is_arc[move])
    arc = np.zeros(move.size, bool)
    spirals = {}
    if curved.size:
        curves = _curved_rows(blocks, move[curved], axes[curved], start[curved, :2],
                              end[curved, :2], cols.motion_code[move[curved]] == CCW_CODE)
        if curves is None:
            return None
        arc_rows, arc_numbers, spiral_rows, spiral_list = curves
        arc[curved[arc_rows]] = True
        geom[curved[arc_rows]] = arc_numbers
        geom[curved[spiral_rows]] = 0.0
        spirals = dict(zip(curved[spiral_rows].tolist(), spiral_list))
    _check(geom, arc, spirals)
    rapid = cols.motion_code[move] == RAPID_CODE
    return MoveRows(move, rapid, arc, geom, spirals, np.c_[start[:, 2], end[:, 2]])


def _curved_rows(blocks, qs: np.ndarray, axes: np.ndarray, start: np.ndarray, end: np.ndarray,
                 ccw: np.ndarray):
    """``(arc rows, their numbers (n, 5), spiral rows, their Spirals)`` of
    the circular moves ``blocks[q]`` for ``q`` in ``qs`` (rows of ``qs``),
    from ``start`` to ``end`` (in-plane, ``(n, 2)``), their plane's ``axes``
    and direction ``ccw``: what :func:`block_geometry` makes of each, the
    same operations element by element; ``None`` when a centre coordinate
    is not a number Python's float arithmetic reads as numpy does (an int or
    a float): a program built by hand, the reference's."""
    curved = list(map(blocks.__getitem__, qs.tolist()))
    centres = list(map(_CENTER, curved))
    if not all(issubclass(t, (float, int)) for t in set(map(type, chain.from_iterable(centres)))):
        return None
    centre = np.take_along_axis(triples_column(centres, len(centres)), axes, axis=1)[:, :2]
    turns = np.fromiter(map(_TURNS, curved), float, len(curved))
    r0, r1, th0, th1 = polar_ends(start, end, centre)
    # is_spiral_move of each (Python's max(1.0, r0))
    spiral = np.abs(r1 - r0) > SPIRAL_RADIUS_REL_TOL * np.where(r0 > 1.0, r0, 1.0)
    arc_rows, spiral_rows = np.flatnonzero(~spiral), np.flatnonzero(spiral)
    a = arc_rows
    radius, theta0, sweep = arcs_from_polar(r0[a], r1[a], th0[a], th1[a], ccw[a], turns[a])
    s = spiral_rows
    spiral_list = Spiral.many_from_numbers(centre[s], *spirals_from_polar(
        r0[s], r1[s], th0[s], th1[s], ccw[s], turns[s])) if s.size else []
    return arc_rows, np.c_[centre[a], radius, theta0, sweep], spiral_rows, spiral_list


def _floats_only(blocks) -> bool:
    """Whether every start and end coordinate of ``blocks`` is a float."""
    types = set(map(type, chain.from_iterable(map(_START, blocks))))
    types.update(map(type, chain.from_iterable(map(_END, blocks))))
    return types <= {float}


def _check(geom: np.ndarray, arc: np.ndarray, spirals: dict) -> None:
    """``ValueError`` unless the line rows are finite and the arc rows finite
    with a radius > 0 (what :class:`Line` and :class:`Arc` refuse)."""
    line = ~arc
    line[list(spirals)] = False
    if not np.isfinite(geom[line, :4]).all():
        raise ValueError("a line's end points are not finite")
    a = geom[arc]
    if not (np.isfinite(a).all() and (a[:, 2] > 0.0).all()):
        raise ValueError("an arc's radius, centre or angles are not valid")
