"""Bezier blend curves exported as arcs and lines: certified bound, read back, verified.

The curves are sampled here from the Bernstein definition (``math.comb``),
not through ccopt's Bezier code; distances to the read-back moves use the
closed-form point-to-line and point-to-arc kernels (a read-back spiral, an
arc whose written end radius differs from its start radius by rounding, is
measured as the arc at its start radius plus that difference, an upper
bound). The exported files are read back with ccopt's readers, compensation
off, independently of the exporter's own read-back.
"""
from __future__ import annotations

import importlib
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

import ccopt
from ccopt.cases import find_case
from ccopt.compare import compare
from ccopt.export import export
from ccopt.export.arcfit import fit_bezier, fit_tolerance
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.curve import inflections
from ccopt.geometry.distance import point_arc, point_segment
from ccopt.program import read_program
from ccopt.tolerances import EXPORT_FIT_ANGLE_TOL
from ccopt.toolpath import PathSegment, Role, ToolPath

#: Dense samples of every curve (the brief's figure: 1e5 points).
DENSE = 100_001

#: Cubic control leg for a quarter circle, k = 4/3 (sqrt 2 - 1): the curve
#: meets the circle at both ends and in the middle, and its largest radial
#: error is 2.7253e-4 R (Goldapp 1991; Riskus 2006), at t = 0.5 +- 0.2885.
K_QUARTER = 4.0 / 3.0 * (math.sqrt(2.0) - 1.0)
QUARTER_RADIAL_ERROR = 2.7253e-4


def bezier_points(ctrl, t) -> np.ndarray:
    ctrl = np.asarray(ctrl, float)
    n = len(ctrl) - 1
    t = np.asarray(t, float)[:, None]
    return sum(math.comb(n, i) * t ** i * (1 - t) ** (n - i) * ctrl[i] for i in range(n + 1))


def bezier_turn(ctrl, t) -> np.ndarray:
    """``x'y'' - y'x''`` (the sign of the curvature) by finite differences of
    :func:`bezier_points` (central, step 1e-4: exact for the cubic part)."""
    h = 1e-4
    t = np.clip(np.asarray(t, float), h, 1 - h)
    p0, p1, p2 = bezier_points(ctrl, t - h), bezier_points(ctrl, t), bezier_points(ctrl, t + h)
    d1 = (p2 - p0) / (2 * h)
    d2 = (p2 - 2 * p1 + p0) / (h * h)
    return d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]


def distance_to(pts: np.ndarray, g) -> np.ndarray:
    """Distance from each point to one read-back move (an upper bound for a spiral)."""
    m = len(pts)
    if isinstance(g, Line):
        return point_segment(pts, np.tile(g.p0, (m, 1)), np.tile(g.p1, (m, 1)))[0]
    if isinstance(g, Arc):
        return point_arc(pts, np.tile(g.center, (m, 1)), np.full(m, g.radius),
                         np.full(m, g.theta0), np.full(m, g.sweep))[0]
    assert isinstance(g, Spiral)
    # every point of the spiral is within |rho1 - rho0| of the arc at rho0 on its ray
    return point_arc(pts, np.tile(g.center, (m, 1)), np.full(m, g.rho0),
                     np.full(m, g.theta0), np.full(m, g.sweep))[0] + abs(g.rho1 - g.rho0)


def distance_to_moves(pts: np.ndarray, geoms, reach: float = 0.01) -> np.ndarray:
    """Distance from each point to the nearest move, for points within
    ``reach`` of one (``inf`` for the others): only the points inside a move's
    bounding box grown by ``reach`` are measured against it."""
    best = np.full(len(pts), np.inf)
    for g in geoms:
        x0, y0, x1, y1 = g.bbox()
        near = ((pts[:, 0] >= x0 - reach) & (pts[:, 0] <= x1 + reach)
                & (pts[:, 1] >= y0 - reach) & (pts[:, 1] <= y1 + reach))
        if near.any():
            best[near] = np.minimum(best[near], distance_to(pts[near], g))
    return best


def curve_path(ctrl, feed: float = 10.0) -> ToolPath:
    """A tool path of one blend curve (as a lead-in), in mm."""
    seg = PathSegment(BezierCurve(ctrl), Role.LEAD_IN, None, 0.0, 0.0, feed)
    return ToolPath((seg,), style="test-blend", radius=1.0, units="mm")


def read_back_moves(out):
    """The feed moves of an exported file, read with ccopt's reader (no rapids)."""
    back = ccopt.programmed_path(read_program(out))
    return [s.geom for s in back.segments if s.role is not Role.RAPID and s.length > 0]


def check_export(ctrl, out, tol=None):
    """Export ``ctrl`` as a path to ``out``, read it back, and check the curve
    against the moves both ways; returns ``(result, moves, deviation)``."""
    res = export(curve_path(ctrl), out, tol=tol)
    tol = res.tolerance
    moves = read_back_moves(out)
    t = np.linspace(0.0, 1.0, DENSE)
    pts = bezier_points(ctrl, t)
    dev = distance_to_moves(pts, moves)
    # every point of the curve within tol of the exported moves, and within
    # the certified fit bound plus the rounding of the written numbers
    assert dev.max() <= tol
    assert dev.max() <= res.roundtrip_error + 1e-12
    assert 0.0 < res.fit_error <= tol
    # ... and every point of the moves near the curve (the bound is two-sided):
    # the nearest dense sample is at most half a sample step further than the curve
    step = float(np.max(np.hypot(*np.diff(pts, axis=0).T)))
    tree = cKDTree(pts)
    for g in moves:
        q = np.asarray(g.point(np.linspace(0.0, g.length, 200)))
        assert tree.query(q)[0].max() <= res.roundtrip_error + step / 2 + 1e-12
    # the moves chain from the curve's start to its end, continuously, and
    # meet each other and the curve's end tangents within twice the angle tolerance
    assert math.dist(moves[0].start, ctrl[0]) <= 1e-6
    assert math.dist(moves[-1].end, ctrl[-1]) <= 1e-6
    kink = 2 * EXPORT_FIT_ANGLE_TOL + 1e-5     # + the rounding of 6 decimals
    for a, b in zip(moves, moves[1:]):
        assert math.dist(a.end, b.start) <= 1e-9
        assert angle(a.end_tangent, b.start_tangent) <= kink
    d0 = bezier_points(ctrl, [0.0, 1e-7])
    d1 = bezier_points(ctrl, [1 - 1e-7, 1.0])
    assert angle(moves[0].start_tangent, d0[1] - d0[0]) <= EXPORT_FIT_ANGLE_TOL + 1e-5
    assert angle(moves[-1].end_tangent, d1[1] - d1[0]) <= EXPORT_FIT_ANGLE_TOL + 1e-5
    return res, moves, float(dev.max())


def angle(u, v) -> float:
    return math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1])


def turn_of_moves(ctrl, moves):
    """For each arc: (its turning sign, the curve's turn at the curve point
    nearest the arc's middle)."""
    t = np.linspace(0.0, 1.0, 20001)
    tree = cKDTree(bezier_points(ctrl, t))
    out = []
    for g in moves:
        if isinstance(g, Line):
            continue
        mid = np.asarray(g.point(g.length / 2)).reshape(1, 2)
        tm = t[tree.query(mid)[1][0]]
        out.append((math.copysign(1.0, g.sweep), float(bezier_turn(ctrl, [tm])[0])))
    return out


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
@pytest.mark.parametrize("R", [1.0, 10.0, 50.0])
def test_quarter_circle_cubic(R, suffix, tmp_path):
    ctrl = [(R, 0.0), (R, K_QUARTER * R), (K_QUARTER * R, R), (0.0, R)]
    # the sampler itself reproduces the published radial error of this cubic
    pts = bezier_points(ctrl, np.linspace(0.0, 1.0, DENSE))
    radial = np.abs(np.hypot(pts[:, 0], pts[:, 1]) - R).max() / R
    assert radial == pytest.approx(QUARTER_RADIAL_ERROR, rel=1e-3)
    res, moves, dev = check_export(ctrl, tmp_path / f"quarter{suffix}")
    # the bound covers the sampled deviation and is within the default 0.001 mm:
    # in the file (the written numbers are rounded to 1e-6) ...
    assert dev <= res.fit_error + 1e-6 <= 1e-3 + 1e-6
    # ... and before rounding, the fitted pieces themselves
    pieces = fit_bezier(BezierCurve(ctrl), fit_tolerance(1e-3, 6))
    assert max(p.bound for p in pieces) == res.fit_error
    exact = distance_to_moves(pts, [p.geom for p in pieces])
    assert exact.max() <= res.fit_error <= 1e-3
    # one way round: all arcs counter-clockwise, as the curve turns
    assert all(sg > 0 for sg, _ in turn_of_moves(ctrl, moves))
    if R == 1.0:
        # 2.7e-4 is within tol. The curve's two end pieces get arcs tangent to
        # it at its ends, so the whole curve is halved first: each half gets
        # the arc through the curve's end, tangent there, and through the
        # curve's middle B(1/2) = R (4 + 3K)/8 (1, 1) = R (sqrt2/2)(1, 1) (for
        # K = 4(sqrt2 - 1)/3, on the circle). Tangent to the circle at its end
        # and through a point of it, that arc is the circle itself; the
        # deviation is the cubic's radial error.
        assert len(moves) == 2
        for m in moves:   # read back from rounded numbers: an arc, or a spiral within 1e-6
            assert m.center == pytest.approx((0.0, 0.0), abs=1e-6)
            assert math.dist(m.start, m.center) == pytest.approx(R, abs=1e-6)
            assert math.dist(m.end, m.center) == pytest.approx(R, abs=1e-6)
        assert moves[0].end == pytest.approx((R * math.sqrt(0.5),) * 2, abs=1e-6)
        assert dev == pytest.approx(QUARTER_RADIAL_ERROR * R, rel=1e-2)
    else:
        # 2.7e-3 mm and more: the circle is out of tolerance, so several arcs
        assert len(moves) > 1


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_s_curve_is_cut_at_its_inflection(suffix, tmp_path):
    # point-symmetric about (6, 0): turns right (clockwise) up to t = 1/2, left after
    ctrl = [(0.0, 0.0), (4.0, 4.0), (8.0, -4.0), (12.0, 0.0)]
    _, moves, _ = check_export(ctrl, tmp_path / f"s{suffix}")
    ends = [m.end for m in moves]
    assert any(math.dist(e, (6.0, 0.0)) <= 1e-6 for e in ends)   # a cut at the inflection
    for m in moves:
        mid = np.asarray(m.point(m.length / 2))
        if isinstance(m, Line):
            continue
        assert (m.sweep < 0) == (mid[0] < 6.0)   # G2 before the inflection, G3 after
    for sg, turn in turn_of_moves(ctrl, moves):
        assert sg * turn > 0
    text = (tmp_path / f"s{suffix}").read_text()
    if suffix == ".nc":
        assert "G2" in text and "G3" in text
    else:
        assert "CIRCLE1" in text and "CIRCLE2" in text


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_nearly_straight_curve_is_one_line(suffix, tmp_path):
    # y(t) = 6e-6 t (1-t): 1.5e-6 from the chord at t = 1/2, tangents within
    # 2e-6 rad of it. Its second derivative is constant, -1.2e-5, so the
    # bound |y''|/8 is exact.
    ctrl = [(0.0, 0.0), (1.0, 2e-6), (2.0, 2e-6), (3.0, 0.0)]
    res, moves, dev = check_export(ctrl, tmp_path / f"line{suffix}")
    assert len(moves) == 1 and isinstance(moves[0], Line)
    assert moves[0].p0 == pytest.approx((0.0, 0.0)) and moves[0].p1 == pytest.approx((3.0, 0.0))
    assert dev == pytest.approx(1.5e-6, rel=1e-6)
    assert res.fit_error == pytest.approx(1.5e-6, rel=1e-9)


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_nearly_straight_s_curve_is_two_lines(suffix, tmp_path):
    # y(t) = 6e-6 t (1-t) (1-2t): an inflection at t = 1/2, (1.5, 0); at most
    # 6e-6 * sqrt(3) / 18 = 5.77e-7 from the chord
    ctrl = [(0.0, 0.0), (1.0, 2e-6), (2.0, -2e-6), (3.0, 0.0)]
    res, moves, dev = check_export(ctrl, tmp_path / f"sline{suffix}")
    assert [type(m) for m in moves] == [Line, Line]
    assert moves[0].p1 == pytest.approx((1.5, 0.0), abs=1e-9)
    assert dev == pytest.approx(6e-6 * math.sqrt(3) / 18, rel=1e-3)
    assert dev <= res.fit_error


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_straight_curve_is_an_exact_line(suffix, tmp_path):
    ctrl = [(0.0, 0.0), (1.0, 1.0), (1.5, 1.5), (3.0, 3.0)]   # collinear, uneven speed
    res = export(curve_path(ctrl), tmp_path / f"straight{suffix}")
    moves = read_back_moves(tmp_path / f"straight{suffix}")
    assert len(moves) == 1 and isinstance(moves[0], Line)
    assert res.fit_error == 0.0 and res.fitted_moves == 1


def test_tolerance_in_inches_is_the_mm_default(tmp_path):
    ctrl = [(0.0, 0.0), (0.2, 0.1), (0.4, 0.0)]
    seg = PathSegment(BezierCurve(ctrl), Role.LEAD_IN, None, 0.0, 0.0, 1.0)
    res = export(ToolPath((seg,), units="inch"), tmp_path / "in.nc")
    assert res.tolerance == pytest.approx(0.001 / 25.4)
    assert 0.0 < res.fit_error <= res.tolerance
    assert "G20" in (tmp_path / "in.nc").read_text()


def test_a_nearly_straight_piece_is_never_a_huge_arc():
    """Found by the property below (random profile): a curve running down and
    back along x = 0 was fitted with an arc of radius 1.86e6, whose end came
    back 1.04e-9 off the curve and whose centre words would be beyond the
    reader's coordinate bound. Arcs stay within MAX_ARC_RADIUS; the pieces
    still end on the curve and stay within their bounds."""
    from ccopt.export.arcfit import MAX_ARC_RADIUS
    ctrl = np.array([(0.0, 12.75), (0.0, 0.0), (0.0, 2.0), (6.103515625e-05, 0.0)])
    pieces = fit_bezier(BezierCurve(ctrl), 0.01)
    for p in pieces:
        ends = bezier_points(ctrl, [p.t0, p.t1])
        assert math.dist(p.geom.start, ends[0]) <= 1e-9
        assert math.dist(p.geom.end, ends[1]) <= 1e-9
        assert getattr(p.geom, "radius", 0.0) <= MAX_ARC_RADIUS and p.bound <= 0.01
        q = bezier_points(ctrl, np.linspace(p.t0, p.t1, 2001))
        assert distance_to(q, p.geom).max() <= p.bound * (1 + 1e-9) + 1e-10


def speed_range(ctrl: np.ndarray) -> tuple[float, float]:
    """The least and the largest speed ``|B'(t)|`` over ``0 <= t <= 1`` of the
    Bezier curve ``ctrl``, exactly: at the ends and where ``|B'|^2`` (a
    polynomial) is stationary. Sampling misses a near-cusp (the speed near 0
    over a stretch of 1e-9 in t), where the tangent turns by up to pi: no
    piece there meets the angle bound, and fit_bezier says so (ValueError)."""
    from numpy.polynomial import Polynomial
    m = len(ctrl) - 2                                  # degree of the hodograph
    hod = (m + 1) * np.diff(ctrl, axis=0)
    t, u = Polynomial([0.0, 1.0]), Polynomial([1.0, -1.0])
    sx, sy = (sum(float(c) * math.comb(m, i) * t ** i * u ** (m - i) for i, c in enumerate(col))
              for col in hod.T)
    s2 = sx * sx + sy * sy
    at = [0.0, 1.0] + [r.real for r in s2.deriv().roots()
                       if abs(r.imag) <= 1e-12 and 0.0 <= r.real <= 1.0]
    speeds = np.sqrt(np.maximum(s2(np.asarray(at)), 0.0))
    return float(speeds.min()), float(speeds.max())


regular_curves = st.integers(min_value=2, max_value=6).flatmap(
    lambda n: st.lists(st.tuples(st.floats(-20, 20), st.floats(-20, 20)),
                       min_size=n + 1, max_size=n + 1))


@settings(max_examples=25, deadline=None)
@given(regular_curves, st.sampled_from([1e-2, 1e-3, 1e-4]))
def test_fit_bound_covers_the_sampled_deviation(ctrl, tol):
    ctrl = np.asarray(ctrl, float)
    t = np.linspace(0.0, 1.0, 2001)
    pts = bezier_points(ctrl, t)
    # regular and not tiny: consecutive samples well apart
    steps = np.hypot(*np.diff(pts, axis=0).T)
    assume(steps.min() > 1e-3 * max(steps.max(), 1e-9) and steps.sum() > 1.0)
    slowest, fastest = speed_range(ctrl)
    assume(slowest > 1e-3 * fastest)
    try:
        curve = BezierCurve(ctrl)
    except ValueError:
        assume(False)
    pieces = fit_bezier(curve, tol)
    assert pieces[0].t0 == 0.0 and pieces[-1].t1 == 1.0
    for a, b in zip(pieces, pieces[1:]):
        assert a.t1 == b.t0
    for p in pieces:
        ends = bezier_points(ctrl, [p.t0, p.t1])
        assert math.dist(p.geom.start, ends[0]) <= 1e-9
        assert math.dist(p.geom.end, ends[1]) <= 1e-9
        assert p.bound <= tol and p.angle <= EXPORT_FIT_ANGLE_TOL
        q = bezier_points(ctrl, np.linspace(p.t0, p.t1, 2001))
        assert distance_to(q, p.geom).max() <= p.bound * (1 + 1e-9) + 1e-10



def test_g2_ends_onto_lines_far_from_the_origin():
    # A smoother's blend of a 6.43 degree chord corner near (57, 39), G2 onto both
    # lines: its first and last three control points lie on the lines, so its
    # curvature is zero at both ends and turns one way (left) in between; the
    # free middle points sit 3e-4 to the left of the lines. In floats the three
    # points are collinear only to rounding, so the curvature's sign at an end is
    # rounding: inflections() finds cuts 1e-11 from an end on some of these, a
    # piece there too short to fit. Every one fits, within its bound, turning left.
    spurious = 0
    for k in range(60):
        a, turn = math.radians(97.0 + 0.37 * k), math.radians(6.43)
        V = np.array([57.1922 + 0.01 * k, 38.7409])
        din = np.array([math.cos(a), math.sin(a)])
        dout = np.array([math.cos(a + turn), math.sin(a + turn)])
        left_in, left_out = np.array([-din[1], din[0]]), np.array([-dout[1], dout[0]])
        h = 0.05
        ctrl = np.array([V - 3 * h * din, V - 2 * h * din, V - h * din,
                         V - 0.3 * h * din + 3e-4 * left_in, V + 0.3 * h * dout + 3e-4 * left_out,
                         V + h * dout, V + 2 * h * dout, V + 3 * h * dout])
        spurious += bool(inflections(ctrl))
        pieces = fit_bezier(BezierCurve(ctrl), fit_tolerance(1e-3, 6))
        assert pieces[0].t0 == 0.0 and pieces[-1].t1 == 1.0
        for p in pieces:
            assert p.bound <= fit_tolerance(1e-3, 6) and p.angle <= EXPORT_FIT_ANGLE_TOL
            q = bezier_points(ctrl, np.linspace(p.t0, p.t1, 201))
            assert distance_to(q, p.geom).max() <= p.bound * (1 + 1e-9) + 1e-10
            if isinstance(p.geom, Arc):
                assert p.geom.sweep > 0
    assert spurious > 0       # the rounding lobes are there to be handled


@pytest.fixture(scope="module")
def optimised():
    """opt-casadi's leads on cases/leadin-inside-line (as tests/formulations build them)."""
    c = find_case("leadin-inside-line")
    prog = ccopt.read_program(c.program)
    cmp = compare(prog, ("pmac", "opt-casadi"), limits=ccopt.AxisLimits(c.vmax, c.amax))
    row = cmp["opt-casadi"]
    assert row.status == "ok", row.message
    return prog, row.toolpath


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_optimised_blend_exports_and_verifies(optimised, suffix, tmp_path):
    from ccopt.verify import verify
    prog, path = optimised
    curves = [s.geom for s in path.segments if isinstance(s.geom, BezierCurve)]
    assert len(curves) == 2                       # the lead-in and the lead-out
    before = verify(path, prog)
    out = tmp_path / f"opt{suffix}"
    res = export(path, out, program=prog)
    assert res.verified == before.ok
    assert before.ok                              # the case's expectation
    assert 0.0 < res.fit_error <= res.roundtrip_error <= res.tolerance == 1e-3
    head = out.read_text().splitlines()[:6]
    assert any("OK" in h for h in head)
    assert any(f"{res.fitted_moves} arcs/lines certified within" in h for h in head)
    # independent read-back: every point of both curves within tol of the moves
    moves = read_back_moves(out)
    for g in curves:
        P = np.asarray(g.control_points)
        pts = bezier_points(P, np.linspace(0.0, 1.0, DENSE))
        assert distance_to_moves(pts, moves).max() <= res.roundtrip_error + 1e-12
    # and the lines and arcs of the original path come back as they were
    # (the straight and corner moves, each within rounding of the written digits)
    for s in path.segments:
        if isinstance(s.geom, (Line, Arc)) and s.length > 0 and s.role is not Role.RAPID:
            q = np.asarray(s.geom.point(np.linspace(0.0, s.length, 101)))
            assert distance_to_moves(q, moves).max() <= 1e-5


@pytest.fixture(scope="module")
def smoothed_pocket():
    c = find_case("pocket")
    prog = ccopt.read_program(c.program)
    row = compare(prog, ["smooth"], radius=c.radius)["smooth"]
    assert row.status == "ok", row.message
    return prog, row.toolpath


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_smoothed_pocket_exports_and_verifies(smoothed_pocket, suffix, tmp_path):
    # The smoother's blends run at the clearance limit over part of their
    # length (the R6 corners' curvature-jump blends hug the wall at r = 3):
    # an arc fitted there within the default 0.001 mm may stray outwards by
    # its bound. The export fits those curves again, tighter, until the
    # read-back keeps the clearance; every blend point stays within the
    # reported round-trip error of the written moves.
    from ccopt.verify import verify
    prog, path = smoothed_pocket
    assert verify(path, prog).ok
    out = tmp_path / f"smooth{suffix}"
    res = export(path, out, program=prog)
    assert res.verified is True, res.certificate["violations"][:3]
    assert "verified against the programmed contour: OK" in out.read_text()
    assert res.roundtrip_error <= res.tolerance
    moves = read_back_moves(out)
    for s in path.segments:
        if isinstance(s.geom, BezierCurve):
            pts = bezier_points(np.asarray(s.geom.control_points), np.linspace(0.0, 1.0, 2001))
            assert distance_to_moves(pts, moves).max() <= res.roundtrip_error + 1e-12


def test_refit_rounds_are_each_verified_and_bounded(smoothed_pocket, tmp_path, monkeypatch):
    # A verifier that always finds the read-back gouging at its first fitted
    # move (and the computed path clean): the export refits that curve at
    # most EXPORT_REFIT_ROUNDS times, each tighter by EXPORT_REFIT_SHRINK and
    # never below EXPORT_REFIT_MIN_TOL, writes the last round it verified, and
    # says FAILED. Every write is followed by its own read-back check.
    ex = importlib.import_module("ccopt.export")   # the module (ccopt.export is the function)
    from ccopt.tolerances import EXPORT_REFIT_MIN_TOL, EXPORT_REFIT_ROUNDS

    prog, path = smoothed_pocket
    calls = []

    class Gouge:
        def __init__(self, m):
            self.tool_segment = m

    class Cert:
        def __init__(self, ok, moves):
            self.ok, self.min_clearance = ok, 2.9
            self.moves = moves

        def violations_of(self, kind):
            first = next(i for i, (src, _, b) in enumerate(self.moves) if src >= 0 and b > 0)
            return [Gouge(first)] if kind == "gouge" else []

        def to_json(self):
            return {"ok": self.ok}

    real_readback = ex.readback_path

    def readback(text, fmt, original, moves, file, **kw):
        calls.append(("read", moves))
        return real_readback(text, fmt, original, moves, file, **kw)

    def fake_verify(p, program):
        if p is path:                           # the computed path: clean
            return Cert(True, [])
        return Cert(False, calls[-1][1])        # the read-back just made

    monkeypatch.setattr(ex, "readback_path", readback)
    monkeypatch.setattr(ex, "_verify", fake_verify)
    out = tmp_path / "refit.nc"
    res = ex.export(path, out, program=prog)
    assert res.verified is False
    assert 2 <= len(calls) <= EXPORT_REFIT_ROUNDS + 1
    text = out.read_text()
    assert "verified against the programmed contour: FAILED" in text
    # the file holds the moves of the last verified round (same count)
    assert res.fitted_moves == sum(1 for src, g, b in calls[-1][1]
                                   if src >= 0 and type(g) is not type(path.segments[src].geom))
    # ... and says how tight its fit went, never below the floor
    line = next(n for n in text.splitlines() if "running at the clearance limit" in n)
    tightest = float(line.split("fitted within ")[1].split(" ")[0])
    assert EXPORT_REFIT_MIN_TOL <= tightest < 1e-3
