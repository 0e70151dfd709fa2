"""The arcs of many circular moves worked out together
(:func:`~ccopt.geometry.primitives.arcs_from_polar`, from
:func:`~ccopt.geometry.primitives.polar_ends`, with
:func:`~ccopt.geometry.angles.sweeps_between`) are what
:func:`~ccopt.geometry.primitives.arc_through` gives each, bit for bit, over
seeded random arcs (either way round, full circles and near-full ones, extra
turns, ends at the end-point tolerance), and a row it refuses is refused;
the programmed path's rows of arcs and spirals are then the segments
:func:`~ccopt.move_geometry.block_geometry` makes of each block, also for
centres written as ints."""
from __future__ import annotations

import math
import random
from dataclasses import replace

import numpy as np
import pytest

from ccopt.geometry.angles import sweep_between, sweeps_between
from ccopt.geometry.primitives import arc_through, arcs_from_polar, polar_ends
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Program
from ccopt.toolpath import programmed_path, programmed_segments


def _arcs(seed: int, n: int) -> list[tuple]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        c = (rng.uniform(-500, 500), rng.uniform(-500, 500))
        r = rng.choice((rng.uniform(1e-3, 1.0), rng.uniform(1.0, 200.0)))
        # the end's radius at and about the tolerance 1e-9 * max(1, r)
        r1 = r + rng.choice((0.0, 0.0, 1.0, -1.0)) * rng.choice((0.5e-9, 0.999e-9, 1.001e-9)) \
            * max(1.0, r)
        a0 = rng.uniform(-math.pi, math.pi)
        a1 = a0 + rng.choice((rng.uniform(-6.3, 6.3), 1e-10, 0.0, 2 * math.pi, -1e-12))
        s = (c[0] + r * math.cos(a0), c[1] + r * math.sin(a0))
        e = (c[0] + r1 * math.cos(a1), c[1] + r1 * math.sin(a1))
        out.append((s, e, c, rng.random() < 0.5, rng.choice((0, 0, 0, 1, 3))))
    return out


def _bulk(moves):
    s, e, c, ccw, turns = (np.array(col, float) for col in zip(*moves))
    return arcs_from_polar(*polar_ends(s, e, c), ccw.astype(bool), turns)


@pytest.mark.parametrize("seed", range(3))
def test_many_arcs_are_the_arcs_one_by_one(seed):
    moves = _arcs(seed, 3000)
    kept = []
    for m in moves:
        try:
            kept.append((m, arc_through(*m)))
        except ValueError:
            with pytest.raises(ValueError):     # alone, and among the others
                _bulk([m])
            with pytest.raises(ValueError):
                _bulk([moves[0], m, moves[-1]])
    assert 100 < len(moves) - len(kept) < len(moves) / 2
    radius, theta0, sweep = _bulk([m for m, _ in kept])
    one = [(r, t, w) for _, (_, r, t, w) in kept]
    assert repr(list(zip(radius.tolist(), theta0.tolist(), sweep.tolist()))) == repr(one)


def test_sweeps_are_the_sweeps_one_by_one():
    rng = random.Random(5)
    rows = [(rng.uniform(-4, 4), rng.choice((rng.uniform(-4, 4), 0.0)), rng.random() < 0.5,
             rng.choice((0, 2)), rng.choice((0.0, 1e-9, 1e-3, 0.5))) for _ in range(5000)]
    rows += [(a, a + d, ccw, 0, f) for a in (0.0, 1.0, -3.0) for d in (0.0, 1e-12, -1e-12)
             for ccw in (True, False) for f in (0.0, 1e-9)]
    th0, th1, ccw, turns, full = (np.array(col) for col in zip(*rows))
    got = sweeps_between(th0, th1, ccw.astype(bool), turns.astype(float), full)
    assert repr(got.tolist()) == repr([sweep_between(a, b, c, t, full_if_below=f)
                                       for a, b, c, t, f in rows])


def _path_key(path):
    return [(type(s.geom), repr(s.geom), repr(s.geom.length), repr(getattr(s.geom, "b", None)),
             s.role, repr(s.w0), repr(s.w1)) for s in path.segments]


@pytest.mark.parametrize("seed", range(2))
def test_programmed_rows_are_the_blocks_geometry(seed):
    """Arcs and spirals (an end off the circle by more than the spiral
    tolerance, less than the arc's) read from G-code, and the same blocks
    with their centres written as ints."""
    rng = random.Random(seed)
    lines, x, y = ["G21 G90 G94", "G1 X0 Y0 Z0 F600"], 0.0, 0.0
    for _ in range(300):
        r = rng.uniform(0.5, 40.0)
        a0, sweep = rng.uniform(-math.pi, math.pi), rng.uniform(-6.3, 6.3)
        r1 = r * (1.0 + rng.choice((0.0, 0.0, 1e-6, -1e-5, 1e-4)))
        cx, cy = x - r * math.cos(a0), y - r * math.sin(a0)
        ex, ey = cx + r1 * math.cos(a0 + sweep), cy + r1 * math.sin(a0 + sweep)
        lines.append(f"G{3 if sweep > 0 else 2} X{ex:.7f} Y{ey:.7f} I{cx - x:.7f} "
                     f"J{cy - y:.7f}")
        x, y = round(ex, 7), round(ey, 7)
    prog = read_gcode("\n".join(lines) + "\n", "arcs.ngc")
    rows = programmed_path(prog)
    assert rows.columns is not None and len(rows.columns.objects) > 30
    assert _path_key(rows) == _path_key(programmed_segments(prog))
    # whole-number centres as ints (a program built by hand)
    blocks = tuple(replace(b, center=tuple(int(round(v)) for v in b.center))
                   if b.center is not None else b for b in prog.blocks)
    ints = Program(blocks, file="ints", dialect="gcode", units=prog.units, start=prog.start)
    got = programmed_path(ints)
    assert got.columns is not None
    assert _path_key(got) == _path_key(programmed_segments(ints))
