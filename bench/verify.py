"""Benchmark: ccopt's full certificate on 100,000 tool segments against a
100,000-element contour, and shapely 2's STRtree route on the same pairs.

The contour is a closed wavy ring, tangent continuous, of 25,000 repeats of
line - counter-clockwise arc - line - clockwise arc (100,000 elements, half
of them arcs, every joint tangent), cut with CC1 and r = 0.001 after a
straight lead-in to its start. PMAC compensation gives 100,002 tool segments
(lead-in, 100,000 offsets: lines, arcs of R - r and R + r, lead-out).

Timed, in the same run and in alternating turns (so load from elsewhere on
the machine hits both alike):

- ccopt: ``verify(toolpath, program)``, the whole certificate from the tool
  path and the program (contour extraction, broad phase, exact distances,
  contact, side, continuity);
- shapely: ``STRtree`` over the contour elements as polylines (each arc as
  ``ARC_POINTS`` chords), ``query(tool, predicate="dwithin", distance=reach)``
  with the same reach as ccopt's broad phase, then ``shapely.distance`` on the
  pairs found. The LineStrings are built outside the timed region.

Prints the medians, the ratio ccopt/shapely, the pair counts and both routes'
smallest clearance.

    python bench/verify.py [--units 25000] [--repeat 5]
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ccopt.compensate import compensate  # noqa: E402
from ccopt.geometry import Line  # noqa: E402
from ccopt.program.model import Block, Modal, Motion, Program, Source  # noqa: E402
from ccopt.verify import verify  # noqa: E402
from ccopt.verify.clearance import reach_of  # noqa: E402

RADIUS = 0.001
LINE = 0.004          # line length
R_ARC = 0.008         # arc radius (both bends)
BEND = 0.5            # radians turned by the left bend
ARC_POINTS = 8


def wavy_ring(units: int):
    """Elements of the ring: list of ``(kind, start, end, centre)``, kind 'L', 'CCW', 'CW'."""
    turn_right = BEND - 2 * math.pi / units        # the right bend turns back all but 2 pi / units
    pattern = [("L", LINE, 0.0), ("CCW", R_ARC, BEND), ("L", LINE, 0.0), ("CW", R_ARC, -turn_right)]
    n = 4 * units
    kinds = [pattern[i % 4][0] for i in range(n)]
    # heading at the start of every element, and each element's displacement
    turns = np.tile([0.0, BEND, 0.0, -turn_right], units)
    head = np.r_[0.0, np.cumsum(turns)[:-1]] + math.pi / 2
    disp = np.empty((n, 2))
    is_line = np.tile([True, False, True, False], units)
    disp[is_line] = LINE * np.c_[np.cos(head[is_line]), np.sin(head[is_line])]
    arc = ~is_line
    chord = 2 * R_ARC * np.abs(np.sin(turns[arc] / 2))
    mid_head = head[arc] + turns[arc] / 2
    disp[arc] = chord[:, None] * np.c_[np.cos(mid_head), np.sin(mid_head)]
    start = np.r_[np.zeros((1, 2)), np.cumsum(disp, axis=0)[:-1]]
    end = np.r_[start[1:], np.zeros((1, 2))]        # closed: the last ends at the first's start
    # centre: left of the heading for CCW, right for CW, at R_ARC
    side = np.where(turns > 0, 1.0, -1.0)
    centre = start + R_ARC * side[:, None] * np.c_[-np.sin(head), np.cos(head)]
    return kinds, start, end, centre


def program(units: int) -> Program:
    kinds, start, end, centre = wavy_ring(units)
    on = Modal(side=1, radius=RADIUS)
    # lead-in along the first line's left normal (the tool side), then CC0 and back out
    S = (-(RADIUS + 0.01), 0.0)
    blocks = [Block(Source("bench", 1), Motion.LINE, (*S, 0.0), (0.0, 0.0, 0.0), on, feed=10.0)]
    for i, k in enumerate(kinds):
        s, e = (*start[i], 0.0), (*end[i], 0.0)
        if k == "L":
            blocks.append(Block(Source("bench", i + 2), Motion.LINE, s, e, on, feed=10.0))
        else:
            motion = Motion.ARC_CCW if k == "CCW" else Motion.ARC_CW
            blocks.append(Block(Source("bench", i + 2), motion, s, e, on,
                                center=(*centre[i], 0.0), feed=10.0))
    blocks.append(Block(Source("bench", len(kinds) + 2), Motion.LINE, (0.0, 0.0, 0.0), (*S, 0.0),
                        Modal(side=0, radius=RADIUS), feed=10.0))
    return Program(tuple(blocks), "bench", "pmac")


def polylines(geoms) -> np.ndarray:
    """Each primitive as a shapely LineString (an arc as ARC_POINTS chords)."""
    import shapely  # deferred: optional, only this comparison needs it
    coords, index = [], []
    for i, g in enumerate(geoms):
        if isinstance(g, Line):
            pts = np.array([g.p0, g.p1])
        else:
            pts = g.point(np.linspace(0.0, g.length, ARC_POINTS + 1))
        coords.append(pts)
        index.append(np.full(len(pts), i))
    return shapely.linestrings(np.concatenate(coords), indices=np.concatenate(index))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--units", type=int, default=25_000, help="pattern repeats (4 elements each)")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    import shapely  # deferred: optional, only this comparison needs it

    prog = program(args.units)
    path = compensate(prog, "pmac")
    cert = verify(path, prog)                      # warm-up, and the figures
    contour = cert.context.contour
    n_tool, n_elem = len(path.segments), len(contour)
    print(f"tool segments {n_tool:,}, contour elements {n_elem:,} "
          f"({int((contour.elements.arr.kind == 1).sum()):,} arcs), cutter radius {RADIUS}")
    print(f"certificate: {'PASSED' if cert.ok else 'FAILED'}, min clearance "
          f"{cert.min_clearance:.12g} ({cert.min_clearance_basis}), "
          f"{cert.check('gouge').count:,} pairs in the narrow phase")
    if not cert.ok:
        print(cert.summary())

    tool_ls = polylines([s.geom for s in path.segments])
    elem_ls = polylines([contour.elements.geom(j) for j in range(n_elem)])
    reach = float(reach_of(contour, cert.eps).max())

    def ccopt_run():
        return verify(path, prog)

    def shapely_run():
        tree = shapely.STRtree(elem_ls)
        ti, ej = tree.query(tool_ls, predicate="dwithin", distance=reach)
        d = shapely.distance(tool_ls[ti], elem_ls[ej])
        return ti, ej, d

    out = shapely_run()
    times = {"ccopt": [], "shapely": []}
    for _ in range(args.repeat):
        for name, fn in (("ccopt", ccopt_run), ("shapely", shapely_run)):
            t0 = time.perf_counter()
            res = fn()
            times[name].append(time.perf_counter() - t0)
            if name == "shapely":
                out = res
    ti, ej, d = out
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"shapely: {ti.size:,} pairs within {reach:g}, min distance {d.min():.12g} "
          f"(polylines: arcs as {ARC_POINTS} chords)")
    print(f"median over {args.repeat} runs: ccopt certificate {med['ccopt']:.3f} s, "
          f"shapely STRtree dwithin + distance {med['shapely']:.3f} s")
    print(f"ratio ccopt/shapely {med['ccopt'] / med['shapely']:.2f} "
          f"({'ccopt faster' if med['ccopt'] < med['shapely'] else 'shapely faster'})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
