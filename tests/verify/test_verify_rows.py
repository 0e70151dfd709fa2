"""The verifier reads a path compensation made as columns from its columns
(:class:`ccopt.verify.rows.SegmentRows`, issue 34), without making a segment
object, and must see exactly what it sees in the path's segments.

Properties, over generated CAM plates (:mod:`cam_programs`, PMAC style: the
style that makes column paths), the same plates with an edge dented into the
part (so the certificate lists gouges and contact excesses), and noisy rings
whose PMAC offset folds all round (thousands of violations, corner arcs at
every vertex):

- every array of the rows read from the columns equals, bit for bit, the
  rows read from the materialised segments (packed geometry, bounding boxes,
  roles, heights, blocks, which rows are arcs);
- the certificate of the column path equals, in every figure and every
  violation, the certificate of the same segments in a path made from them
  (no columns): the verifier's two roads agree.

The quick tier runs 6 plates and one ring; the slow tier 150 plates and 6 rings.
"""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from cam_programs import cam_program
from ccopt.compensate.pmac import PmacStyle, assemble
from ccopt.compensate.scan import scan_program
from ccopt.program import read_text
from ccopt.toolpath import ToolPath
from ccopt.verify import verify
from ccopt.verify.rows import SegmentRows

QUICK = range(6)
SLOW = range(6, 156)
DENT = 0.01


def _plate(seed: int, dented: bool):
    """``(program the path is made from, program it is verified against)``:
    dented, the path of the plate with an edge pushed into the part,
    verified against the plate (it gouges by the dent)."""
    cp = cam_program(seed, dialect="pmac")
    prog = read_text(cp.text, f"plate{seed}.pmc", "pmac")
    if not dented:
        return prog, prog
    return read_text(cp.pushed(DENT), f"dented{seed}.pmc", "pmac"), prog


def _ring(seed: int, n: int = 400):
    """A PMAC ring of ``n`` LINEAR moves (radius 20 + 0.3 sin 7 theta, each
    vertex moved up to 0.05 radially): 0.3 mm chords turning by up to 0.35 rad
    under a 2 mm cutter (CC2), so the offset folds and gouges (the shape of
    issue 34's 20,000-block ring, smaller)."""
    rng = random.Random(seed)
    pts = []
    for k in range(n):
        t = 2.0 * math.pi * k / n
        rho = 20.0 + 0.3 * math.sin(7.0 * t) + rng.uniform(-0.05, 0.05)
        pts.append((rho * math.cos(t), rho * math.sin(t)))
    lines = ["CCR2", "F10", "LINEAR", f"X{pts[0][0] + 3:.4f} Y{pts[0][1]:.4f}", "CC2"]
    lines += [f"X{x:.4f} Y{y:.4f}" for x, y in pts[1:] + pts[:1]]
    lines += ["CC0", f"X{pts[0][0] + 3:.4f} Y{pts[0][1]:.4f}"]
    return read_text("\n".join(lines) + "\n", f"ring{seed}.pmc", "pmac")


def _segment_path(path: ToolPath) -> ToolPath:
    """The same segments in a path that has no columns."""
    return ToolPath(tuple(path.segments), plane=path.plane, style=path.style,
                    radius=path.radius, dwells=path.dwells, units=path.units,
                    meta=dict(path.meta))


def _same_rows(a: SegmentRows, b: SegmentRows) -> None:
    for name in ("kind", "p0", "p1", "center", "radius", "radius_end", "theta0", "sweep"):
        np.testing.assert_array_equal(getattr(a.tool.arr, name), getattr(b.tool.arr, name),
                                      err_msg=name, strict=True)
    np.testing.assert_array_equal(a.tool.bbox, b.tool.bbox, strict=True)
    assert a.tool.curved.keys() == b.tool.curved.keys()
    assert all(a.tool.curved[k] is b.tool.curved[k] for k in a.tool.curved)
    for name in ("role", "w0", "w1", "is_arc"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert all(a.block(i) is b.block(i) for i in range(len(a)))
    assert [a.info(i) for i in range(len(a))] == [b.info(i) for i in range(len(b))]


def _check(made, against=None) -> int:
    """Both properties on the PMAC path of ``made`` verified against
    ``against`` (default ``made``); returns the violations and warnings listed."""
    prog = made if against is None else against
    # as columns whatever the program's length (compensate does from 64 moves)
    path = assemble(PmacStyle(), scan_program(made, bulk=True), made, columns=True)
    assert path.columns is not None
    from_columns = SegmentRows.of(path)
    plain = _segment_path(path)
    assert plain.columns is None
    _same_rows(from_columns, SegmentRows.of(plain))
    a, b = verify(path, prog), verify(plain, prog)
    assert a.to_json() == b.to_json()
    assert a.summary() == b.summary()
    return len(a.violations) + len(a.warnings)


@pytest.mark.parametrize("seed", QUICK)
@pytest.mark.parametrize("dented", (False, True))
def test_plates_read_alike(seed, dented):
    listed = _check(*_plate(seed, dented))
    assert listed > 0 or not dented, "the dent is a gouge the certificate lists"


def test_folding_ring_reads_alike():
    assert _check(_ring(0)) > 100


@pytest.mark.slow
@pytest.mark.parametrize("seed", SLOW)
def test_plates_read_alike_slow(seed):
    _check(*_plate(seed, False))
    assert _check(*_plate(seed, True)) > 0


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(1, 7))
def test_folding_rings_read_alike_slow(seed):
    assert _check(_ring(seed)) > 100
