"""Part surface and air: which fully compensated moves are the part.

(docs/compensation.md section 8.1.) A CAM system writes a profile as a lead
line (G41 on it), a tangent arc in, the closed contour, a tangent arc out and
a lead line out (G40 on it): the arcs in and out are compensated like the
contour but run in air. The verifier decides per fully compensated move
(compensation on for it and the move before):

1. ``--part-lines`` / ``verify(part_lines=...)`` given: the moves written on
   those program lines are part, every other one is air;
2. else a move marked ``(ccopt: part)`` / ``(ccopt: air)`` on its line
   (:mod:`ccopt.program.markers`) is what its marker says;
3. else, with :data:`ccopt.verify.decisions.CLOSED_LOOP_IS_THE_PART`: within
   each run of consecutive fully compensated moves (an *episode*), a closed
   loop (a run of moves whose end returns to its start within ``eps``) is the
   part and the moves before, between and after the loops are leads (air); an
   episode with no closed loop is part throughout, as every compensated move
   was before this rule.

Air moves are no contour elements: nothing is checked against them (no
contact, no side) but their tool segments are checked against the part.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from operator import attrgetter

import numpy as np

from ccopt.errors import ProgramError
from ccopt.program.markers import SURFACE_AIR, SURFACE_PART
from ccopt.verify import decisions

#: Why a fully compensated move was taken as part or air (certificate words).
WHY_LOOP = "closed loop"
WHY_NO_LOOP = "no closed loop in its run of compensated moves: every one is part"
WHY_LEAD_BEFORE = "lead before the closed loop"
WHY_LEAD_AFTER = "lead after the closed loop"
WHY_BETWEEN = "between closed loops"
WHY_ALL = "every compensated move is part (CLOSED_LOOP_IS_THE_PART off)"
WHY_LINES = "in --part-lines"
WHY_NOT_LINES = "not in --part-lines"
WHY_MARK_PART = "marked (ccopt: part)"
WHY_MARK_AIR = "marked (ccopt: air)"
WHY_LEAD_IN = "lead-in: compensation comes on over it"
WHY_LEAD_OUT = "lead-out: compensation goes off over it"
WHY_SIDE_CHANGE = "side-change transition"

_RANGE = re.compile(r"\s*(\d+)\s*(?:-\s*(\d+))?\s*$")


def parse_part_lines(spec) -> tuple[tuple[int, int], ...]:
    """``"A-B[,C-D]"`` (or single lines ``"A"``), or pairs/ints, as inclusive
    ``((A, B), ...)`` program line ranges (1-based). ``ValueError`` saying what
    is wrong otherwise."""
    if isinstance(spec, str):
        out = []
        for part in spec.split(","):
            m = _RANGE.match(part)
            if not m:
                raise ValueError(f"part lines must be A-B[,C-D] (program line numbers), "
                                 f"not {part.strip()!r}")
            a = int(m.group(1))
            b = int(m.group(2)) if m.group(2) else a
            out.append((a, b))
    else:
        out = [(int(x), int(x)) if np.ndim(x) == 0 else (int(x[0]), int(x[1])) for x in spec]
    for a, b in out:
        if a < 1 or b < a:
            raise ValueError(f"part lines {a}-{b}: need 1 <= A <= B")
    if not out:
        raise ValueError("part lines: no range given")
    return tuple(out)


def _ranges_text(ranges) -> str:
    return ",".join(str(a) if a == b else f"{a}-{b}" for a, b in ranges)


def _runs(lines: list[int]) -> list[tuple[int, int]]:
    """Sorted line numbers as runs of consecutive ones."""
    out: list[list[int]] = []
    for x in lines:
        if out and x == out[-1][1] + 1:
            out[-1][1] = x
        else:
            out.append([x, x])
    return [(a, b) for a, b in out]


@dataclass(frozen=True, eq=False)
class Surface:
    """Per in-plane move: ``part`` (True: part surface; only meaningful where
    the move is fully compensated) and ``why`` (a ``WHY_*``, ``""`` for moves
    that are not fully compensated); ``rule``: what decided (``"part-lines"``,
    ``"closed-loop"``, ``"all-compensated"``, with ``"+markers"`` when any move
    was marked)."""

    part: np.ndarray
    why: tuple[str, ...]
    rule: str

    def report(self, moves, compensated: np.ndarray, approaches: dict[int, str]) -> dict:
        """The certificate's ``surface`` entry: the rule, the part and air program
        lines as ranges, and runs of consecutive moves with the same verdict and
        reason: the fully compensated moves, and the ``approaches`` (move index ->
        why: lead-ins, lead-outs, side-change transitions), which are air."""
        # runs found on arrays: a certificate of 100,000 moves has a few runs,
        # so only their ends are looked up in the blocks
        sel = np.asarray(compensated, bool).copy()
        keys = np.fromiter(approaches, np.intp, len(approaches))
        sel[keys] = True
        q = np.flatnonzero(sel)
        part = np.asarray(compensated, bool)[q] & self.part[q]
        why = np.array(self.why, dtype=object)[q]
        why[np.searchsorted(q, keys)] = list(approaches.values())
        new_run = np.ones(q.size, bool)
        new_run[1:] = (np.diff(q) != 1) | (part[1:] != part[:-1]) | (why[1:] != why[:-1])
        first = np.flatnonzero(new_run)
        last = np.r_[first[1:], q.size] - 1
        runs = [{"lines": [moves[q[a]].source.line, moves[q[b]].source.line],
                 "surface": SURFACE_PART if part[a] else SURFACE_AIR, "why": why[a]}
                for a, b in zip(first.tolist(), last.tolist())]
        return {"rule": self.rule,
                "part_lines": [r["lines"] for r in runs if r["surface"] == SURFACE_PART],
                "air_lines": [r["lines"] for r in runs if r["surface"] == SURFACE_AIR],
                "moves": runs}


_SURFACE = attrgetter("surface")


def surface_of(moves, compensated: np.ndarray, start: np.ndarray, end: np.ndarray,
               is_arc: np.ndarray, eps: float, part_lines=None,
               file: str = "<string>") -> Surface:
    """Which of ``moves`` (in-plane, in order; ``start``/``end`` ``(n, 2)``,
    ``is_arc`` per move) are part surface, among the ``compensated`` ones (see
    the module docstring)."""
    n = len(moves)
    part = compensated.copy()
    why = [""] * n
    if part_lines is not None:
        try:
            ranges = parse_part_lines(part_lines)
        except ValueError as exc:
            raise ProgramError(str(exc), file) from None
        lines = np.fromiter((b.source.line for b in moves), np.int64, n)
        inside = np.zeros(n, bool)
        for a, b in ranges:
            inside |= (lines >= a) & (lines <= b)
        part = compensated & inside
        if compensated.any() and not part.any():
            # a mistyped range would leave no part at all, and any path would pass
            have = sorted({int(x) for x in lines[compensated]})
            raise ProgramError(f"part lines {_ranges_text(ranges)} hold no fully compensated "
                               f"move (those are on lines {_ranges_text(_runs(have))})", file)
        for k in np.flatnonzero(compensated):
            why[k] = WHY_LINES if inside[k] else WHY_NOT_LINES
        return Surface(part, tuple(why), "part-lines")
    rule = "all-compensated"
    if decisions.CLOSED_LOOP_IS_THE_PART:
        rule = "closed-loop"
        _loops(compensated, start, end, is_arc, eps, part, why)
    else:
        for k in np.flatnonzero(compensated):
            why[k] = WHY_ALL
    marked = False
    # the marks read in one pass; the loop visits the marked moves only
    marks = list(map(_SURFACE, moves))
    for k in (np.flatnonzero(compensated).tolist() if any(marks) else ()):
        mark = marks[k]
        if mark is not None:
            marked = True
            part[k] = mark == SURFACE_PART
            why[k] = WHY_MARK_PART if part[k] else WHY_MARK_AIR
    return Surface(part, tuple(why), rule + ("+markers" if marked else ""))


def _episodes(compensated: np.ndarray):
    """``(first, last)`` move index of each run of consecutive compensated moves."""
    c = np.r_[False, compensated, False].astype(np.int8)
    d = np.diff(c)
    return zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1)


def _encloses(verts: np.ndarray, arcs: np.ndarray, eps: float) -> bool:
    """A loop through ``verts`` (closed) is a real contour, not a move and its
    retrace or a move shorter than ``eps``: it has an arc, or its polygon an
    area above ``eps`` times its perimeter."""
    if arcs.any():
        return True
    # the shoelace sum of each edge's cross product about the first vertex,
    # summed pairwise by numpy: about the origin, a small loop far from it
    # (a sliver at x = 8000) has products of 1e7 whose rounding alone is an
    # area; and two np.dot calls would cancel two large sums against each
    # other (on a long loop OpenBLAS also runs them in threads that then spin
    # idle, CPU a parallel run's other processes could use)
    x, y = verts[:, 0] - verts[0, 0], verts[:, 1] - verts[0, 1]
    area = 0.5 * abs(float(np.sum(x * np.roll(y, -1) - y * np.roll(x, -1))))
    perimeter = float(np.hypot(*np.diff(np.r_[verts, verts[:1]], axis=0).T).sum())
    return area > eps * perimeter


#: :func:`pairs_within` sweeps at most this many candidates per point before
#: it leaves the search to a k-d tree (points crowded along x: a vertical line).
SWEEP_CANDIDATES_PER_POINT = 8


def pairs_within(pts: np.ndarray, eps: float) -> np.ndarray:
    """``(m, 2)`` index pairs ``(p, q)`` of the points ``pts`` (``(n, 2)``) at
    most ``eps`` apart, as ``scipy.spatial.cKDTree.query_pairs`` finds them
    (``dx**2 + dy**2 <= eps**2``), in no particular order.

    Sorted by x, a point's partners within ``eps`` follow it within ``eps``
    in x: the sweep compares each point with the next ones while that holds,
    one offset at a time for all points together (a contour's vertices have
    one or two such neighbours). Where the points crowd along x it hands over
    to the k-d tree."""
    n = len(pts)
    x, y = pts[:, 0], pts[:, 1]
    order = np.argsort(x, kind="stable")
    xs = x[order]
    e2 = eps * eps
    out_p, out_q = [], []
    live = np.arange(n - 1)
    swept, k = 0, 1
    while live.size:
        j = live + k
        live, j = live[j < n], j[j < n]
        dx = xs[j] - xs[live]
        near = dx * dx <= e2                  # rounding is monotone: past it, all are
        live, j = live[near], j[near]
        swept += live.size
        if swept > SWEEP_CANDIDATES_PER_POINT * n:
            from scipy.spatial import cKDTree   # deferred: 0.3 s on every `import ccopt`
            return cKDTree(pts).query_pairs(eps, output_type="ndarray")
        a, b = order[live], order[j]
        gx, gy = x[a] - x[b], y[a] - y[b]
        close = gx * gx + gy * gy <= e2
        out_p.append(a[close])
        out_q.append(b[close])
        k += 1
    if not out_p:
        return np.zeros((0, 2), np.intp)
    return np.column_stack((np.concatenate(out_p), np.concatenate(out_q)))


def _loops(compensated, start, end, is_arc, eps, part, why) -> None:
    """Mark the innermost closed loops of every episode part and the rest of
    an episode with a loop air (in place).

    A loop is a run of moves from a vertex to its next return within ``eps``
    that encloses something (:func:`_encloses`). Loops nest when a lead comes
    back to its own start: a CAM plate entered at a corner whose tangent arc
    out ends where the arc in began makes the loop lead-in, contour, lead-out
    around the contour's own loop. Only loops holding no other loop are the
    part (the leads are air); loops that overlap without nesting (a contour
    run twice, a loop started at another vertex) are all part."""
    for a, b in _episodes(compensated):
        a, b = int(a), int(b)
        # the episode's vertices: its first start, then every end; a loop is a
        # later vertex back within eps of an earlier one
        verts = np.r_[start[a:a + 1], end[a:b + 1]]
        returns: dict[int, list[int]] = {}
        for p, q in pairs_within(verts, eps):
            p, q = (int(p), int(q)) if p < q else (int(q), int(p))
            returns.setdefault(p, []).append(q)
        # per vertex, its first return that encloses: the smallest loop from it
        cand = []
        for p in sorted(returns):
            for q in sorted(returns[p]):
                if _encloses(verts[p:q], is_arc[a + p:a + q], eps):
                    cand.append((p, q))
                    break
        # innermost: no other candidate lies within [p, q] (each vertex has one
        # candidate, so another one within starts later and returns no later)
        loops, nearest = [], np.inf
        for p, q in reversed(cand):
            if q < nearest:
                loops.append((p, q))
            nearest = min(nearest, q)
        if not loops:
            part[a:b + 1] = True
            why[a:b + 1] = [WHY_NO_LOOP] * (b - a + 1)
            continue
        inner = np.zeros(b - a + 1, bool)
        for p, q in loops:
            inner[p:q] = True
        first = int(np.argmax(inner))
        last = int(inner.size - 1 - np.argmax(inner[::-1]))
        part[a:b + 1] = inner
        k = np.arange(inner.size)
        kinds = np.select([inner, k < first, k > last], [0, 1, 2], 3)
        names = (WHY_LOOP, WHY_LEAD_BEFORE, WHY_LEAD_AFTER, WHY_BETWEEN)
        why[a:b + 1] = [names[x] for x in kinds.tolist()]
