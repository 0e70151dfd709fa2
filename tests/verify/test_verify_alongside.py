"""The contact check's farthest distance alongside an element, for many pairs
at once (:func:`ccopt.verify.alongside.farthest_clipped`), is the one taken
pair by pair with the open-end machinery it mirrors (the element's
:func:`~ccopt.verify.clearance.end_regions`, the tool segment's
:func:`~ccopt.verify.clearance.clip_pieces` outside them, the exact
:func:`~ccopt.verify.distance.max_distance` of the pieces): the same figure
and witness to the last bit, on the tool paths of generated CAM programs
(straight and pushed into the part) and on an exported noisy ring read back
(arcs whose centres moved by the written decimals: no closed form applies).
Pairs: every tool segment with its own element, and random ones.
"""
from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from cam_programs import cam_program
from ccopt.cases import default_style
from ccopt.compensate import compensate
from ccopt.export import export
from ccopt.program import read_text
from ccopt.verify.alongside import ALONGSIDE_MIN_LENGTH, farthest_clipped
from ccopt.verify.clearance import clip_pieces, end_regions
from ccopt.verify.contour import contour_of
from ccopt.verify.distance import max_distance
from ccopt.verify.rows import SegmentRows
from ccopt.verify.run import SegmentTable
from ccopt.verify.segments import pack

ROOT = Path(__file__).resolve().parents[2]


def farthest_one(tool, E, i: int, j: int):
    """Pair by pair: ``(dmax, witness)`` of tool segment ``i`` against element ``j``."""
    tg, eg = tool.geom(i), E.geom(j)
    pieces = clip_pieces(tg, end_regions(E, j, True, True)) if tg.length > 0.0 else []
    if sum(p.length for p in pieces) <= ALONGSIDE_MIN_LENGTH:
        return math.inf, tuple(map(float, tg.start))
    n = len(pieces)
    dm, q, _ = max_distance(pack(pieces).arr, np.arange(n), pack([eg]).arr, np.zeros(n, np.intp))
    k = int(np.argmax(dm))
    return float(dm[k]), (float(q[k, 0]), float(q[k, 1]))


def bits(x: float) -> bytes:
    return np.float64(x).tobytes()


def assert_same_as_one_by_one(path, contour, seed: int, random_pairs: int):
    rows = SegmentRows.of(path)
    tool, E = rows.tool, contour.elements
    elem = SegmentTable.build(rows, contour).element
    ti, ej = np.flatnonzero(tool.exact), np.flatnonzero(E.exact)
    own = ti[elem[ti] >= 0]
    own = own[E.exact[elem[own]]]
    rng = np.random.default_rng(seed)
    si = np.r_[own, rng.choice(ti, random_pairs)]
    sj = np.r_[elem[own], rng.choice(ej, random_pairs)]
    dmax, wq = farthest_clipped(tool, E, si, sj)
    for k in range(si.size):
        d, w = farthest_one(tool, E, int(si[k]), int(sj[k]))
        got = (bits(dmax[k]), bits(wq[k, 0]), bits(wq[k, 1]))
        assert got == (bits(d), bits(w[0]), bits(w[1])), (k, int(si[k]), int(sj[k]))


@pytest.mark.parametrize("seed", range(6))
def test_generated_programs(seed):
    cp = cam_program(seed)
    text = cp.pushed(0.3 * cp.radius) if seed % 2 else cp.text
    prog = read_text(text, cp.file, cp.dialect, tool_table=cp.tool_table)
    path = compensate(prog, default_style(prog)[0])
    contour = contour_of(prog, toolpath_radius=path.radius)
    assert_same_as_one_by_one(path, contour, seed, 60)


def test_read_back_ring(tmp_path):
    spec = importlib.util.spec_from_file_location("bench_io", ROOT / "bench" / "io.py")
    bench_io = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench_io)
    prog = read_text(bench_io.ring_program(200), "ring.pmc", "pmac")
    res = export(compensate(prog, "pmac"), tmp_path / "ring.pmc", program=prog)
    ctx = res.verdict.context
    assert_same_as_one_by_one(ctx.toolpath, ctx.contour, 7, 60)
