"""The PMAC tool path held as columns (``ToolPath.from_columns``): the public
API of a tool path (iteration, indexing, ``segments``, ``len``, ``planes``,
``start_xyz``/``end_xyz``, pickling, ``dataclasses.replace``) and the same
segments, roles, dwells and ``w`` as the one-segment-at-a-time reference
route, on programs with gaps (Z moves, dwells), corner arcs, arcs and the
automatic lead-out. Expected corner points are worked out here from the
spec's offset rule (``P + r*o(t)``, ``o(t) = k*(-t_y, t_x)``)."""
from __future__ import annotations

import pickle
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings

from ccopt.cases import bundled_cases
from ccopt.compensate import compensate, decisions
from ccopt.compensate.pmac import PmacStyle, assemble
from ccopt.compensate.scan import scan_program
from ccopt.errors import CcoptError
from ccopt.program import read_program, read_text
from ccopt.toolpath import Role
from test_pmac_invariants import closed_contours, contour_program

TOL = 1e-9
Z_PLUNGES = (
    "OPEN PROG 1 CLEAR\nRAPID X-10 Y0 Z5\nLINEAR ABS F20\nCCR2 CC1\nX0 Y0\nZ-2\nDWELL 100\n"
    "X20 Y0\nZ-4\nX20 Y20\nZ-6\nX40 Y20\nCC0\nX50 Y20\nZ5\nCLOSE\n")


def pmac(text: str):
    return read_text(text, "<test>.pmc", "pmac")


def both_routes(prog):
    """The path written as columns (bulk scan, batch joints) and by the
    one-at-a-time reference route (block-by-block scan)."""
    style = PmacStyle()
    fast = assemble(style, scan_program(prog, bulk=True), prog, vectorised=True, columns=True)
    ref = assemble(style, scan_program(prog, bulk=False), prog, vectorised=False)
    return fast, ref


def same_segments(a, b):
    assert len(a) == len(b)
    for s, t in zip(a, b):
        assert (s.kind, s.role, s.plane, s.feed) == (t.kind, t.role, t.plane, t.feed)
        assert s.block is t.block
        assert np.allclose(s.start_xyz, t.start_xyz, atol=TOL)
        assert np.allclose(s.end_xyz, t.end_xyz, atol=TOL)
        if s.kind == "arc":
            assert np.allclose(s.geom.center, t.geom.center, atol=TOL)
            assert s.geom.radius == pytest.approx(t.geom.radius, abs=TOL)
            assert s.geom.sweep == pytest.approx(t.geom.sweep, abs=TOL)


def test_gaps_dwells_and_corner_arcs_as_columns():
    fast, ref = both_routes(pmac(Z_PLUNGES))
    assert fast.columns is not None and ref.columns is None
    # len and planes answer from the columns, before any segment is made
    assert len(fast) == len(ref)
    assert fast.planes == ("XY",)
    assert "segments" not in fast.__dict__
    same_segments(fast.segments, ref.segments)
    assert [(i, t) for i, t, _ in fast.dwells] == [(i, t) for i, t, _ in ref.dwells]
    assert fast.dwells[0][1] == pytest.approx(0.1)
    # CC1 (k = +1), r = 2. Inside corner at (20,0): +X then +Y, both offsets
    # meet at (20,0) + 2*(-1, 1) = (18, 2); the Z-4 plunge runs there.
    plunge = [s for s in fast if s.start_xyz[2] == 0 - 2 and s.end_xyz[2] == -4][0]
    assert np.allclose(plunge.start_xyz, (18.0, 2.0, -2.0), atol=TOL)
    # Outside corner at (20,20): +Y then +X turns right, k = +1: an arc of
    # radius 2 about (20,20) from (18,20) to (20,22), then the Z-6 plunge
    # at (20,22) (decisions.GAP_MOVES_AFTER_CORNER_ARC).
    arc = [s for s in fast if s.role is Role.CORNER][0]
    assert arc.geom.radius == pytest.approx(2.0)
    assert np.allclose(arc.geom.center, (20.0, 20.0), atol=TOL)
    assert np.allclose(arc.start, (18.0, 20.0), atol=TOL)
    assert np.allclose(arc.end, (20.0, 22.0), atol=TOL)
    plunge = [s for s in fast if s.end_xyz[2] == -6][0]
    at = (20.0, 22.0) if decisions.GAP_MOVES_AFTER_CORNER_ARC else (18.0, 20.0)
    assert np.allclose(plunge.start_xyz[:2], at, atol=TOL)


def test_column_path_public_api():
    path = compensate(pmac(Z_PLUNGES), "pmac")
    segs = path.segments
    assert isinstance(segs, tuple) and path.segments is segs       # made once
    assert list(path) == list(segs) and path[3] == segs[3] and path[-1] == segs[-1]
    assert len(path) == len(segs)
    # the reader's tool starts at the origin; the first rapid goes to (-10, 0, 5)
    assert np.allclose(path[0].start_xyz, (0.0, 0.0, 0.0), atol=TOL)
    assert np.allclose(path[0].end_xyz, (-10.0, 0.0, 5.0), atol=TOL)
    assert np.allclose(path[-1].end_xyz, (50.0, 20.0, 5.0), atol=TOL)
    again = pickle.loads(pickle.dumps(path))
    assert again == path and again.dwells[0][1] == pytest.approx(0.1)
    cut = replace(path, segments=segs[:2])
    assert len(cut) == 2 and cut.columns is None and cut.style == "pmac"
    assert path.length == pytest.approx(sum(s.length for s in segs))


def test_arcs_spiral_and_automatic_lead_out_as_columns():
    # A CIRCLE move whose end is off its start radius is a spiral (made one
    # at a time); compensation still on at the end: the automatic
    # zero-distance lead-out returns to the programmed point (10, 10).
    text = ("LINEAR ABS F10\nCCR1 CC1\nX10 Y0\nCIRCLE1 X20 Y10 I0 J10\nLINEAR X20 Y20\n"
            "CIRCLE2 X10 Y20 I-5 J0\nCIRCLE1 X0 Y10 I0 J-10.5\nLINEAR X10 Y10\n")
    fast, ref = both_routes(pmac(text))
    same_segments(fast.segments, ref.segments)
    kinds = [s.kind for s in fast]
    assert "spiral" in kinds and kinds.count("arc") >= 2
    if decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT:
        last = fast[-1]
        assert last.role is Role.LEAD_OUT
        assert np.allclose(last.end, (10.0, 10.0), atol=TOL)


def test_other_plane_as_columns():
    # G18 (NORMAL J-1): in-plane coordinates are (Z, X)
    text = "NORMAL J-1\nLINEAR ABS F10\nCCR1 CC1\nX10 Z0\nX10 Z10\nX0 Z10\nCC0\nX0 Z20\n"
    fast, ref = both_routes(pmac(text))
    assert fast.planes == ref.planes == ("ZX",) and fast.plane == "ZX"
    same_segments(fast.segments, ref.segments)


@settings(max_examples=60, deadline=None)
@given(closed_contours())
def test_random_contours_as_columns_equal_the_reference(contour):
    fast, ref = both_routes(contour_program(*contour))
    assert fast.columns is not None
    same_segments(fast.segments, ref.segments)


def _scans_equal(a, b):
    assert a.blocks == b.blocks and a.plane == b.plane and a.start_uv == b.start_uv
    assert a.k.tolist() == b.k.tolist() and a.r.tolist() == b.r.tolist()
    assert len(a.gaps) == len(b.gaps) == len(a.blocks) + 1
    assert [list(a.gaps[i]) for i in range(len(a.gaps))] == \
        [list(b.gaps[i]) for i in range(len(b.gaps))]


@pytest.mark.parametrize("case", bundled_cases(), ids=lambda c: c.name)
def test_bulk_scan_equals_block_by_block_scan(case):
    prog = read_program(case.program)
    for style in ("pmac", "fagor"):
        try:
            ref = scan_program(prog, style=style, bulk=False)
        except CcoptError as exc:
            with pytest.raises(type(exc)) as again:
                scan_program(prog, style=style, bulk=True)
            assert str(again.value) == str(exc)
            continue
        _scans_equal(scan_program(prog, style=style, bulk=True), ref)


@pytest.mark.parametrize("text", [
    Z_PLUNGES,
    # a TM move (refused while on) and a plane change: the bulk scan hands
    # over to the block-by-block one, which raises, located
    "LINEAR ABS F10\nCCR1 CC1\nX10 Y0\nTM100 X20 Y0\n",
    "LINEAR ABS F10\nX10 Y0\nNORMAL J-1\nX10 Z10\n",
    "LINEAR ABS F10\nCC1\nX10 Y0\nX20 Y0\n",
])
def test_bulk_scan_hands_over_or_agrees(text):
    prog = pmac(text)
    try:
        ref = scan_program(prog, bulk=False)
    except CcoptError as exc:
        with pytest.raises(type(exc)) as again:
            scan_program(prog, bulk=True)
        assert str(again.value) == str(exc) and ":" in str(exc)
        return
    _scans_equal(scan_program(prog, bulk=True), ref)
