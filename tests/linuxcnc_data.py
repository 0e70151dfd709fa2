"""LinuxCNC's own cutter-compensation test data (``crazy-paths``), kept in
``tests/conformance/linuxcnc`` (source and licence in its README).

A missing copy is a test failure, never a skip.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from ccopt.geometry import Line
from ccopt.tolerances import POINT_EPS
from ccopt.program.model import PLANE_AXES, Motion

CONFORMANCE = Path(__file__).resolve().parent / "conformance" / "linuxcnc"
DATA = CONFORMANCE / "crazy-paths"
#: `expected` prints LinuxCNC's doubles to 4 decimals, within half a unit of
#: the last place (5e-5) of the value it computed; ours lies within a point's
#: rounding (POINT_EPS) of that value, so it may be that much beyond the half
#: unit where LinuxCNC's value is a tie (cam-nisley: -7.80625 by both, one ulp
#: apart, printed -7.8062).
TOL = 5e-5 + POINT_EPS
N_CALLS = 75
_CANON = re.compile(r"\b(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|RIGID_TAP|COMMENT)\((.*)\)\s*$")


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


def canonical_moves(path):
    """The tool path as LinuxCNC canonical moves, in the program's work
    coordinates as LinuxCNC's canon prints them (each block's recorded frame
    offset taken off).

    A ``G33.1`` rigid tap (its feed down and back) is one RIGID_TAP ``[x, y,
    z]``, the bottom. A line of a ``G0`` block is a STRAIGHT_TRAVERSE ``[x, y, z, a, b, c]``
    (``a b c`` the block's A B C, 0 when the program moves none), any other
    line a STRAIGHT_FEED; an arc (or spiral) is ARC_FEED ``[end u, end v,
    centre u, centre v, turn, w]`` with ``turn = sign(sweep) * (number of
    started turns)`` (in-plane coordinates first, as LinuxCNC prints them: in
    G18 an arc's are (Z, X), and a straight move's are always (X, Y, Z)).
    """
    out = []
    down = None                 # the G33.1 line whose feed down came last
    for seg in path.segments:
        g = seg.geom
        frame = seg.block.frame if seg.block is not None else None
        # a G53 move's frame is the system in force: canon prints work coordinates
        work = frame.to_work if frame is not None else (lambda p: p)
        if seg.block is not None and seg.block.cycle == "G33.1":
            # the feed down is canon's one RIGID_TAP; the way back (next) is in it
            if down == seg.block.source:
                down = None
            else:
                out.append(("RIGID_TAP", list(work(seg.end_xyz))))
                down = seg.block.source
            continue
        if isinstance(g, Line):
            kind = "STRAIGHT_TRAVERSE" if seg.block.motion is Motion.RAPID else "STRAIGHT_FEED"
            axes = seg.block.axes
            abc = list(frame.axes_to_work(axes)[:3]) if axes is not None and frame is not None \
                else list(axes[:3]) if axes is not None else [0.0, 0.0, 0.0]
            out.append((kind, list(work(seg.end_xyz)) + abc))
        else:
            iu, iv, iw = PLANE_AXES[seg.plane or "XY"]

            def at(u, v, w):
                p = [0.0, 0.0, 0.0]
                p[iu], p[iv], p[iw] = u, v, w
                q = work(tuple(p))
                return q[iu], q[iv], q[iw]
            eu, ev, ew = at(g.end[0], g.end[1], seg.w1)
            cu, cv, _ = at(g.center[0], g.center[1], seg.w1)
            turns = math.floor(abs(g.sweep) / (2 * math.pi) - 1e-9) + 1
            out.append(("ARC_FEED", [eu, ev, cu, cv, math.copysign(turns, g.sweep), ew]))
    return out


def expected_moves(folder: str) -> list[tuple[str, list[float]]]:
    """The canonical moves of ``CONFORMANCE/folder/expected``, in order."""
    path = CONFORMANCE / folder / "expected"
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    return parse_canon(path.read_text())


def parse_canon(text: str) -> list[tuple[str, list[float]]]:
    """The STRAIGHT_TRAVERSE, STRAIGHT_FEED and ARC_FEED calls of canon output
    ``text`` (an ``expected`` file), in order, with their numbers."""
    items = []
    for line in text.splitlines():
        m = _CANON.search(line)
        if m and m.group(1) != "COMMENT":
            items.append((m.group(1), [float(a) for a in m.group(2).split(",")]))
    return items
