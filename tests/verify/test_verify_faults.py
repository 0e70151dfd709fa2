"""Fault injection on every bundled case (issue 16): each injected fault is
caught, the unmodified paths raise no alarm, the gouge cases keep failing.

The injections (:mod:`faults`) move a cut segment or a shared end point toward
the contour by d in {1e-3, 1e-2, 0.1, r/2}, flip an arc, swap the side, drop
a segment, and push a lead toward the part keeping it connected. Where the
fault is a gouge its depth is known from the geometry (``d``, or at least
``d/2`` for a lead pushed past an open end) and the verifier must report at
least that, at the segments changed.
"""
from __future__ import annotations

from dataclasses import replace

import pytest

import ccopt
from ccopt.cases import bundled_cases
from ccopt.compensate import compensate
from ccopt.errors import CcoptError
from ccopt.toolpath import Role
from ccopt.verify import verify
from faults import (dropped_segments, flipped_arcs, moved_points, moved_segments, pushed_leads)

EPS = 1e-6
#: The faults are checked at the arithmetic's tolerance (no gouge tolerance):
#: every fault deeper than EPS must fail, a 1e-3 one included.
#: test_faults_within_the_default_tolerance_are_warnings covers the default.
EXACT = 0.0
CASES = [c for c in bundled_cases() if c.expect != "error"]
OK = [c for c in CASES if c.expect == "ok"]
GOUGE = [c for c in CASES if c.expect == "gouge"]
#: Depths are asserted to this (rounding of coordinates up to ~100).
DEPTH_TOL = 1e-9


def part_moves(prog, radius):
    """The fully compensated in-plane moves (docs/compensation.md 8.1): on, with
    the move before on the same side (the bundled cases have no closed loop
    with leads, so every one of them is part surface); and the program lines
    of the steady ones among them (same radius as the move before, above 0),
    whose tool segments run at ``r`` from them."""
    out, steady, prev = [], set(), (0, None)
    for b in prog.blocks:
        if not (b.motion.is_move and b.in_plane):
            continue
        k, r = b.modal.side, (b.modal.radius if radius is None else radius)
        if k != 0 and prev[0] == k:
            out.append(b)
            if r == prev[1] and r > 0:
                steady.add(b.source.line)
        prev = (k, r)
    return out, steady


def setup(case):
    """``(program, tool path, part moves, steady lines, largest radius)``."""
    prog = ccopt.read_program(case.program)
    path = compensate(prog, case.style, radius=case.radius)
    blocks, steady = part_moves(prog, case.radius)
    r = max(radius_of(case)(b) for b in blocks)
    return prog, path, blocks, steady, float(r)


def radius_of(case):
    """The cutter radius in force for a block (the case's override, else the program's)."""
    return lambda b: float(b.modal.radius if case.radius is None else case.radius)


def depths_at(cert, segments) -> float:
    g = [v.depth for v in cert.violations_of("gouge") if v.tool_segment in segments]
    return max(g, default=0.0)


@pytest.mark.parametrize("case", OK, ids=[c.name for c in OK])
def test_unmodified_ok_cases_raise_no_alarm(case):
    prog, path, _, _, _ = setup(case)
    cert = verify(path, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
    assert cert.ok, cert.summary()
    assert cert.violations == ()


@pytest.mark.parametrize("case", GOUGE, ids=[c.name for c in GOUGE])
def test_gouge_cases_keep_failing(case):
    prog, path, _, _, _ = setup(case)
    cert = verify(path, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
    assert not cert.ok
    assert cert.violations_of("gouge")


def _ds(r):
    return (1e-3, 1e-2, 0.1, r / 2)


@pytest.mark.parametrize("case", OK, ids=[c.name for c in OK])
def test_faults_within_the_default_tolerance_are_warnings(case):
    # the default tolerance (1e-3 mm): a cut segment moved 5e-4 toward the
    # contour is a gouge warning at that segment, one moved 2e-3 a gouge
    # failure there (the jumps a moved segment leaves at its ends are gaps,
    # which no tolerance excuses: the path is broken)
    prog, path, _, lines, r = setup(case)
    tol = 1e-3 if prog.units == "mm" else 4e-5
    n = 0
    for d, fails in ((0.5 * tol, False), (2 * tol, True)):
        for name, bad, i in moved_segments(path, d, r, lines):
            cert = verify(bad, prog, radius=case.radius, eps=EPS)
            assert cert.tolerance == tol
            assert cert.check("gouge").ok is not fails, (name, cert.summary())
            listed = cert.violations if fails else cert.warnings
            depth = max([v.depth for v in listed if v.kind == "gouge" and v.tool_segment == i],
                        default=0.0)
            assert depth >= d - DEPTH_TOL, (name, cert.summary())
            assert not cert.ok and cert.verdict == "failed"       # the gaps
            n += 1
    assert n > 0


@pytest.mark.slow
@pytest.mark.parametrize("case", OK, ids=[c.name for c in OK])
def test_moved_cut_segments_and_points_are_caught_at_their_depth(case):
    prog, path, blocks, lines, r = setup(case)
    n = 0
    for d in _ds(r):
        for name, bad, i in moved_segments(path, d, r, lines):
            cert = verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
            assert not cert.ok, name
            assert depths_at(cert, {i}) >= d - DEPTH_TOL, (name, cert.summary())
            n += 1
        for name, bad, pair, dist, blk in moved_points(path, d, lines, blocks):
            # a shared point of the cut lies r from the contour (a little more
            # where a shallow outside corner extends the offsets to meet): moved
            # d nearer, it is d - (dist - r) deep
            rb = radius_of(case)(blk)
            assert rb - DEPTH_TOL <= dist <= rb + 1e-4
            cert = verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
            assert not cert.ok, name
            assert depths_at(cert, set(pair)) >= d - (dist - rb) - DEPTH_TOL, (name, cert.summary())
            n += 1
    assert n > 0


@pytest.mark.slow
@pytest.mark.parametrize("case", OK, ids=[c.name for c in OK])
def test_flipped_arcs_dropped_segments_and_swapped_sides_are_caught(case):
    prog, path, blocks, lines, r = setup(case)
    for name, bad, i in flipped_arcs(path, lines):
        cert = verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
        assert not cert.ok, name
        if path.segments[i].role is Role.COMPENSATED:
            # swept the long way round: it no longer runs alongside its element
            assert any(v.tool_segment == i for v in cert.violations_of("contact")), name
    for name, bad, _ in dropped_segments(path, lines, 10 * EPS):
        assert not verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT).ok, name
    sides = {b.modal.side for b in blocks}
    swapped = 0
    for side, k in (("left", 1), ("right", -1)):
        if sides == {k}:
            continue                    # that side is the program's own everywhere
        try:
            bad = compensate(prog, case.style, radius=case.radius, side=side)
        except CcoptError:
            continue                    # the controller refuses it: nothing to verify
        # a path on the wrong side that does not say it was made so (ccopt's
        # own paths record their overrides and are verified as made)
        bad = replace(bad, meta={})
        cert = verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
        assert not cert.ok, side
        assert not cert.check("side").ok, side
        swapped += 1
    assert swapped >= 1


@pytest.mark.slow
@pytest.mark.parametrize("case", OK, ids=[c.name for c in OK])
def test_leads_pushed_toward_the_part_are_caught(case):
    prog, path, blocks, lines, r = setup(case)
    n = 0
    for d in _ds(r):
        for name, bad, new, _, depth in pushed_leads(path, d, radius_of(case), lines, set(),
                                                     blocks):
            cert = verify(bad, prog, radius=case.radius, eps=EPS, tolerance=EXACT)
            assert not cert.ok, name
            assert depths_at(cert, set(new)) >= depth - DEPTH_TOL, (name, cert.summary())
            n += 1
    assert n > 0
