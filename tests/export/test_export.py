"""Export: round trip through ccopt's own readers, certified spiral fits, atomic writes."""
from __future__ import annotations

import math
import os

import numpy as np
from scipy.spatial import cKDTree
import pytest

import ccopt
from ccopt.cases import bundled_cases
from ccopt.export import export, write_gcode
from ccopt.export.arcfit import fit_arcs
from ccopt import atomic
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.distance import point_arc, point_segment
from ccopt.program import read_program

CASES = [c for c in bundled_cases() if c.expect != "error"]


def pmac_case(name: str):
    return next(c for c in CASES if c.name == name)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_roundtrip_every_case(case, suffix, tmp_path):
    prog = read_program(case.program)
    path = ccopt.compensate(prog, case.style, radius=case.radius)
    out = tmp_path / f"{case.name}{suffix}"
    res = export(path, out)
    assert res.roundtrip_error <= res.tolerance
    # Read the file back independently (compensation off: no CC words) and
    # compare every move with the computed tool path, by sampling each
    # computed segment and measuring its distance to the read-back moves.
    back = ccopt.programmed_path(read_program(out))
    text = out.read_text()
    assert not any(w in text for w in ("G41", "G42", "CC1", "CC2", "CCR"))
    pts = np.vstack([seg.geom.point(np.linspace(0, seg.length, 41))
                     for seg in path.segments if seg.length > 0])
    d = distance_bound(pts, [s.geom for s in back.segments if s.length > 0])
    worst = int(np.argmax(d))
    assert d[worst] <= res.tolerance + 1e-12, (case.name, pts[worst], d[worst])


def distance_bound(pts: np.ndarray, geoms) -> np.ndarray:
    """Distance from each point to the nearest of ``geoms``: exact for lines
    and arcs (closed-form kernels); for a spiral the minimum over 4001 points
    on it, an upper bound of the distance (the right direction for asserting
    it is small)."""
    best = np.full(len(pts), np.inf)
    sampled = []
    for g in geoms:
        m = len(pts)
        if isinstance(g, Line):
            d = point_segment(pts, np.tile(g.p0, (m, 1)), np.tile(g.p1, (m, 1)))[0]
        elif isinstance(g, Arc):
            d = point_arc(pts, np.tile(g.center, (m, 1)), np.full(m, g.radius),
                          np.full(m, g.theta0), np.full(m, g.sweep))[0]
        else:
            sampled.append(g.point(np.linspace(0, g.length, 4001))[:, :2])
            continue
        best = np.minimum(best, d)
    if sampled:
        # the nearest of all the spirals' samples at once (a k-d tree: the same
        # minimum as point by point, without a points x samples matrix per spiral)
        d, _ = cKDTree(np.vstack(sampled)).query(pts[:, :2])
        best = np.minimum(best, d)
    return best


def test_spiral_fit_bound_is_certified():
    # A lead-in spiral from rho 10 to rho 11.5 over a quarter turn: every
    # fitted arc's certified bound must cover the true deviation, measured
    # here by dense sampling of the spiral against each arc's circle.
    sp = Spiral((0.0, 0.0), 10.0, 11.5, math.pi, -math.pi / 2)
    for tol in (1e-2, 1e-3, 1e-5):
        arcs = fit_arcs(sp, tol)
        for fa in arcs:
            assert fa.bound <= tol
            n = 2001
            # sample the spiral piece this arc replaced (its end points lie on it)
            s0_piece = _arclength_of_point(sp, fa.arc.start)
            s1_piece = _arclength_of_point(sp, fa.arc.end)
            pts = sp.point(np.linspace(s0_piece, s1_piece, n))
            dev = np.abs(np.hypot(*(pts - fa.arc.center).T) - fa.arc.radius).max()
            assert dev <= fa.bound + 1e-12
        # consecutive arcs meet
        for a, b in zip(arcs, arcs[1:]):
            assert math.dist(a.arc.end, b.arc.start) < 1e-12
        assert math.dist(arcs[0].arc.start, sp.start) < 1e-12
        assert math.dist(arcs[-1].arc.end, sp.end) < 1e-12


def _arclength_of_point(sp: Spiral, p) -> float:
    # polar angle along the sweep -> arc length (closed form of the spiral)
    ang = math.atan2(p[1] - sp.center[1], p[0] - sp.center[0])
    along = ((ang - sp.theta0) * math.copysign(1.0, sp.sweep)) % (2 * math.pi)
    if along > abs(sp.sweep) + 1e-9:
        along = 0.0 if along > math.pi else abs(sp.sweep)
    return float(sp.arclength(min(along, abs(sp.sweep))))


def test_gcode_has_more_arcs_for_a_tighter_tolerance():
    prog = read_program(pmac_case("profile").program)
    path = ccopt.compensate(prog, "pmac")
    n_coarse = len(write_gcode(path, 1e-2)[1])
    n_fine = len(write_gcode(path, 1e-5)[1])
    assert n_fine > n_coarse


def test_bad_format_and_tolerance(tmp_path):
    path = ccopt.compensate(read_program(pmac_case("leadin-outside-arc").program), "pmac")
    with pytest.raises(ccopt.ProgramError, match="unknown export format"):
        export(path, tmp_path / "x.docx")
    with pytest.raises(ccopt.ProgramError, match="tolerance must be > 0"):
        export(path, tmp_path / "x.nc", tol=0)


def test_failed_write_leaves_no_partial_file_and_keeps_the_old_one(tmp_path, monkeypatch):
    path = ccopt.compensate(read_program(pmac_case("leadin-outside-arc").program), "pmac")
    out = tmp_path / "part.nc"
    out.write_text("GOOD OLD FILE\n")

    real_fdopen = os.fdopen

    class Exploding:
        def __init__(self, fh):
            self.fh = fh

        def __enter__(self):
            return self

        def __exit__(self, *a):
            self.fh.close()
            return False

        def write(self, data):
            self.fh.write(data[: len(data) // 2])   # half the file, then the disk fails
            raise OSError(28, "No space left on device")

        def flush(self):
            pass

        def fileno(self):
            return self.fh.fileno()

    monkeypatch.setattr(atomic.os, "fdopen", lambda fd, mode: Exploding(real_fdopen(fd, mode)))
    with pytest.raises(ccopt.ProgramError, match="No space left"):
        export(path, out)
    monkeypatch.undo()
    assert out.read_text() == "GOOD OLD FILE\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["part.nc"]


def test_read_only_folder_gives_a_located_error(tmp_path):
    if os.geteuid() == 0:
        # root ignores permission bits: make the target a directory instead,
        # which os.replace cannot overwrite with a file
        out = tmp_path / "taken.nc"
        out.mkdir()
    else:
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o500)
        out = ro / "taken.nc"
    path = ccopt.compensate(read_program(pmac_case("leadin-outside-arc").program), "pmac")
    with pytest.raises(ccopt.ProgramError) as err:
        export(path, out)
    assert str(out) in str(err.value)
    leftovers = [p for p in out.parent.iterdir() if p.name.startswith(".taken.nc")]
    assert leftovers == []


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_readback_gets_the_same_verdict(case, tmp_path):
    from ccopt.verify import verify
    prog = read_program(case.program)
    path = ccopt.compensate(prog, case.style, radius=case.radius)
    before = verify(path, prog)
    res = export(path, tmp_path / f"{case.name}.nc", program=prog)
    assert res.verified == before.ok
    # and the verdict is the case's expectation
    assert before.ok == (case.expect == "ok")
    head = (tmp_path / f"{case.name}.nc").read_text().splitlines()[:5]
    assert any(("OK" if before.ok else "FAILED") in h for h in head)
