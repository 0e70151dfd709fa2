"""``ExactPath.eval_orders``: several derivative orders at the same positions
in one pass (each arc's angle and its cosine and sine, each Bezier curve's
parameter and derivatives computed once) give, bit for bit, what one
evaluation per order gives (issue 34: the planners and the profile sample
ask for orders 1-3, or 0-3, at the same positions).

Over random compensated contours (lines, arcs, plunges: three axes), a
path in two planes (G17, G18), bundled cases' paths and the smoother's path
(Bezier blends), at random positions, at every segment boundary from both
sides, and in every order of the orders asked; and the orders' values
against the geometry worked out here: on an arc, ``q'`` is the unit tangent
``(-sin phi, cos phi)`` turning with the sweep, ``q''`` points at the
centre with length ``1/R``, ``q''' = -q' / R^2``.
"""
from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from _contours import contour_program
from ccopt.cases import make_job
from ccopt.compensate import compensate
from ccopt.feed import ExactPath
from ccopt.geometry import Arc
from ccopt.pipeline import pipeline
from ccopt.program import read_text

ORDERS = (0, 1, 2, 3)


def _positions(path: ExactPath, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """``(segments, positions)``: random positions and every boundary, on the
    segments either side of it."""
    s = rng.uniform(0.0, path.length, 400)
    k = path.locate(s)
    inner = path.offsets[1:-1]
    kb = np.r_[np.arange(len(inner)), np.arange(1, len(inner) + 1)]
    return np.r_[k, kb], np.r_[s, inner, inner]


def _same_alone_and_together(path: ExactPath, seed: int) -> None:
    rng = np.random.default_rng(seed)
    k, s = _positions(path, rng)
    alone = {o: path.eval_segments(k, s, o) for o in ORDERS}
    for n in (2, 3, 4):
        for orders in itertools.permutations(ORDERS, n):
            for o, got in zip(orders, path.eval_orders(k, s, orders)):
                np.testing.assert_array_equal(got, alone[o], strict=True)
    for side in ("left", "right"):
        for o, got in zip((3, 1, 2), path.eval_sided_orders(s, (3, 1, 2), side)):
            np.testing.assert_array_equal(got, path.eval_sided(s, o, side), strict=True)
    one = path.eval_sided_orders(float(s[0]), (0, 2))
    assert [x.shape for x in one] == [(path.dof,), (path.dof,)]


@pytest.mark.parametrize("seed", range(8))
def test_random_contours(seed):
    prog = contour_program(np.random.default_rng(seed))
    path = ExactPath(compensate(prog, "pmac"))
    assert path.dof == 3
    _same_alone_and_together(path, seed)


def test_path_in_two_planes():
    # G17 then G18: each segment's (u, v, w) placed on the machine axes
    text = ("G21 G17 G90 G0 X0 Y0 Z0\nG1 X10 F600\nG2 X20 Y0 I5 J0\nG18\nG1 Z5\n"
            "G3 X30 Z5 I5 K0\nG1 X40\nM2\n")
    path = ExactPath(compensate(read_text(text, "planes.ngc", "gcode"), "linuxcnc"))
    assert path._perm is not None
    _same_alone_and_together(path, 4)


@pytest.mark.parametrize("case", ("pocket", "z-plunges", "leadin-inside-arc",
                                  "sinumerik-sar-plate"))
def test_bundled_paths(case):
    out = pipeline(make_job(case), compare=False)
    _same_alone_and_together(ExactPath(out.path), 1)


def test_smoothed_path_with_bezier_blends():
    out = pipeline(make_job("pocket-chords", variants=("pmac", "smooth")), compare=True)
    row = next(v for v in out.comparison if v.name == "smooth")
    assert row.status == "ok"
    path = ExactPath(row.toolpath)
    assert path._batches, "the smoothed path holds Bezier blends"
    _same_alone_and_together(path, 2)


def test_arc_orders_by_hand():
    prog = contour_program(np.random.default_rng(3), plunge=False)
    path = ExactPath(compensate(prog, "pmac"))
    arcs = [i for i, seg in enumerate(path.segments) if isinstance(seg.geom, Arc)]
    assert arcs
    for i in arcs:
        g = path.segments[i].geom
        sg = math.copysign(1.0, g.sweep)
        u = np.linspace(0.1, 0.9, 5)
        s = path.offsets[i] + u * path.lengths[i]
        q0, q1, q2, q3 = path.eval_orders(np.full(u.size, i), s, ORDERS)
        phi = g.theta0 + g.sweep * u
        ratio = g.length / path.lengths[i]          # in-plane share of the path length
        np.testing.assert_allclose(q0[:, :2], np.c_[g.center[0] + g.radius * np.cos(phi),
                                                    g.center[1] + g.radius * np.sin(phi)],
                                   rtol=0, atol=1e-9)
        np.testing.assert_allclose(q1[:, :2], sg * ratio * np.c_[-np.sin(phi), np.cos(phi)],
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(q2[:, :2], -ratio ** 2 / g.radius
                                   * np.c_[np.cos(phi), np.sin(phi)], rtol=0, atol=1e-12)
        np.testing.assert_allclose(q3[:, :2], -q1[:, :2] * ratio ** 2 / g.radius ** 2,
                                   rtol=1e-12, atol=1e-15)
