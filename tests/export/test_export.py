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
    # compare it with the computed tool path both ways: every computed move
    # lies within the tolerance of the file's moves, and every move of the
    # file within the tolerance of the computed path (an extra move in the
    # file fails the second).
    back = ccopt.programmed_path(read_program(out))
    text = out.read_text()
    assert not any(w in text for w in ("G41", "G42", "CC1", "CC2", "CCR"))
    missing, extra = roundtrip_gaps(path, back, res.tolerance)
    assert missing[0] <= res.tolerance + 1e-12, (case.name, "not in the file", missing)
    assert extra[0] <= res.tolerance + 1e-12, (case.name, "in the file only", extra)
    # moves with no in-plane length (plunges, retracts) are not in the
    # distances above: the same ones, end for end, both ways
    assert same_moves(vertical_moves(path), vertical_moves(back), res.tolerance), case.name


def test_roundtrip_check_catches_a_move_the_file_adds(tmp_path):
    # the check of the round trip itself: one extra move in the exported file
    # (out to a point 5 mm off the path and back) is found by the file-to-path
    # direction, which the path-to-file direction cannot see
    case = pmac_case("profile")
    path = ccopt.compensate(read_program(case.program), case.style, radius=case.radius)
    out = tmp_path / "profile.nc"
    res = export(path, out)
    lines = out.read_text().splitlines()
    at = max(i for i, ln in enumerate(lines) if ln.startswith("G1 "))
    back_to = lines[at]
    lines[at + 1:at + 1] = ["G1 X500 Y500", back_to]
    out.write_text("\n".join(lines) + "\n")
    back = ccopt.programmed_path(read_program(out))
    missing, extra = roundtrip_gaps(path, back, res.tolerance)
    assert missing[0] <= res.tolerance
    assert extra[0] > 100.0 and np.allclose(extra[1][:2], (500.0, 500.0))


def roundtrip_gaps(path, back, tol: float):
    """``((d, point), (d, point))``: the largest distance from a point of the
    computed ``path`` to the read-back ``back`` (a move missing from the
    file), and from a point of ``back`` to ``path`` (a move the file adds),
    each with its point. Moves of no in-plane length are left out; curves
    other than lines and arcs are sampled at ``tol / 10`` (an upper bound,
    at most ``tol / 20`` above the distance; measured: at most 0.5 tol)."""
    computed = [seg for seg in path.segments if seg.length > 0]
    read = [seg for seg in back.segments if seg.length > 0]
    out = []
    for these, those, spacing in ((computed, read, None), (read, computed, tol / 10)):
        pts = np.vstack([seg.geom.point(np.linspace(0, seg.length, 41)) for seg in these])
        d = distance_bound(pts, [s.geom for s in those], spacing=spacing)
        worst = int(np.argmax(d))
        out.append((float(d[worst]), pts[worst]))
    return out[0], out[1]


def vertical_moves(path) -> np.ndarray:
    """``(x, y, w0, w1)`` of every move of ``path`` with no in-plane length
    that moves along the third axis."""
    rows = [(*seg.geom.point(0.0)[:2], seg.w0, seg.w1) for seg in path.segments
            if seg.length == 0 and seg.w0 != seg.w1]
    return np.array(rows, float).reshape(-1, 4)


def same_moves(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Whether each row of ``a`` has a row of ``b`` within ``tol`` (each
    coordinate) and each row of ``b`` one of ``a``."""
    if len(a) == 0 or len(b) == 0:
        return len(a) == len(b)
    close = np.all(np.abs(a[:, None, :] - b[None, :, :]) <= tol + 1e-12, axis=2)
    return bool(close.any(axis=1).all() and close.any(axis=0).all())


def distance_bound(pts: np.ndarray, geoms, spacing: float | None = None) -> np.ndarray:
    """Distance from each point to the nearest of ``geoms``: exact for lines
    and arcs (closed-form kernels); for any other curve the minimum over
    points on it (4001, or ``spacing`` apart at most), an upper bound of the
    distance (the right direction for asserting it is small), above it by at
    most half the spacing."""
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
            n = 4001 if spacing is None else max(2, math.ceil(g.length / spacing) + 1)
            sampled.append(g.point(np.linspace(0, g.length, n))[:, :2])
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


@pytest.mark.parametrize("case", ["profile", "sinumerik-sar-plate", "z-plunges"])
def test_header_lines_go_where_each_format_keeps_them(case):
    # an export reads back the text written without its final header and writes
    # the file with it (export.text.with_header, which the writers use): the
    # header's comments right after the opening % (G-code) or first (PMAC),
    # hostile characters made inert, and the rest the text without a header
    from ccopt.export.pmacprog import write_pmac
    from ccopt.export.text import gcode_comment, pmac_comment

    c = pmac_case(case)
    prog = read_program(c.program)
    path = ccopt.compensate(prog, c.style, radius=c.radius)
    header = ["ccopt export (test)", "a (comment) with ; and % inside", "verified: OK"]
    bare = write_gcode(path, 1e-3, [], program=prog)[0].split("\n")
    got = write_gcode(path, 1e-3, header, program=prog)[0].split("\n")
    assert got[:4] == ["%", *map(gcode_comment, header)]
    assert got[2] == "(a [comment] with , and % inside)"
    assert got[4:] == bare[1:]
    bare = write_pmac(path, [])[0].split("\n")
    got = write_pmac(path, header)[0].split("\n")
    assert got[:3] == list(map(pmac_comment, header))
    assert got[1] == "; a (comment) with , and % inside"
    assert got[3:] == bare
