"""The smoother: G2 within the band, certified, and its cycle time."""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import BlendProblem
from ccopt.feed import feed_limited_time
from ccopt.geometry import BezierCurve
from ccopt.program import read_text
from ccopt.toolpath import Role
from ccopt_formulations.smoother import smooth

import blend_checks as bc


def _smoothed_case(name: str):
    """The bundled case smoothed at delta = 1 % of its cutter radius, under its limits."""
    c = find_case(name)
    prog = ccopt.read_program(c.program)
    ref = ccopt.compensate(prog, "pmac")
    limits = ccopt.AxisLimits(c.vmax, c.amax)
    delta = 0.01 * ref.radius
    path, info = smooth(BlendProblem(prog, ref, limits), delta)
    return prog, ref, limits, delta, path, info


@pytest.fixture(scope="module")
def pocket():
    return _smoothed_case("pocket")


def _feed_paths(path):
    return [s.geom for s in path.segments
            if s.role in (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)
            and s.length > 0]


def test_pocket_certified_no_gouge(pocket):
    prog, ref, _, _, path, info = pocket
    assert info["certificate"].ok
    assert info["joins_blended"] == info["joins_found"] == 18
    contour = bc.contour(prog)
    for s in path.segments:
        if isinstance(s.geom, BezierCurve):
            pts = bc.bezier_points(s.geom, 2001)[1:-1]
            assert float(np.min(bc.dist_to(pts, contour))) >= ref.radius - 1e-6


def test_pocket_within_the_band(pocket):
    _, ref, _, delta, path, info = pocket
    ref_geoms = _feed_paths(ref)
    new_geoms = _feed_paths(path)
    for s in path.segments:
        if isinstance(s.geom, BezierCurve):
            # the blend is within delta of the reference ...
            pts = bc.bezier_points(s.geom, 2001)
            assert float(np.max(bc.dist_to(pts, ref_geoms))) <= delta
    # ... and every reference point it cut off (the old corner or join) is within delta
    # of the smoothed path: the material a blend leaves is at most delta
    for j in info["joins"]:
        corner = np.asarray(ref.segments[j["segment"]].start)[None, :]
        assert float(bc.dist_to(corner, new_geoms)[0]) <= delta
    assert info["max_deviation_bound"] <= delta


def test_pocket_g2_everywhere(pocket):
    _, _, _, _, path, _ = pocket
    segs = [s for s in path.segments if s.length > 0 and s.role is not Role.RAPID]
    for a, b in zip(segs[:-1], segs[1:]):
        if a.role is Role.UNCOMPENSATED or b.role is Role.UNCOMPENSATED:
            continue                                 # plunge and retract: stops
        gap, ang, jump = bc.join_ok(a.geom, b.geom)
        assert gap <= 1e-9 and ang <= 1e-7 and jump <= 1e-6


def test_pocket_cycle_time(pocket):
    prog, ref, limits, _, path, _ = pocket
    t_ref = ccopt.plan_feed(ref, limits).duration
    prof = ccopt.plan_feed(path, limits)
    t_smooth = prof.duration
    assert t_smooth < t_ref
    assert prof.sample(2e-4).axis_acceleration_ratio.max() <= 1.001
    # What no path this close to the reference can beat: every feed move at its feed
    # with no acceleration limit, the rapid at the axis speeds. The pocket's feed (30 mm/s
    # here) bounds the time from below at ~94 % of PMAC's, so the 10 % is out of
    # reach for any smoothing of this program at these limits; the smoother's time lies
    # between the two.
    lower = feed_limited_time(path, limits)
    assert lower < t_smooth
    assert lower > 0.9 * t_ref


# The same pocket as a CAM system writes it: the R6 corners as LINEAR chords. Each chord
# vertex is an inside corner of the tool path, where PMAC's exact path stops the machine.
# A circular blend of radius rho leaves rho * (1/cos(theta/2) - 1) ~ rho * theta^2 / 8 in
# a corner turning by theta, so within delta = 0.03 of a 6.4 degree turn it could be 19 mm;
# the tool path's chords, 0.34 mm long, hold it to about 1.8 mm here, still above the
# v^2 / a = 0.9 mm that F30 needs at 1000 mm/s^2: the machine keeps its feed there.
CORNERS = [((6, 6), 180, 270), ((54, 6), 270, 360), ((54, 34), 0, 90), ((6, 34), 90, 180)]


@pytest.fixture(scope="module")
def pocket_chords():
    return _smoothed_case("pocket-chords")


def test_pocket_chords_program_is_the_pocket_chorded():
    # the case file, checked against the geometry it claims: each R6 corner is 14 LINEAR
    # chords whose ends lie on the arc (to the 4 written decimals) and which stray from
    # it by at most 0.01 mm (the sagitta R - |c - midpoint|)
    prog = ccopt.read_program(find_case("pocket-chords").program)
    lines = [b for b in prog.moves if b.in_plane and not b.motion.is_arc]
    for (cx, cy), a0, a1 in CORNERS:
        def on_arc(p):
            # on the circle, and within 45 degrees of the quadrant's middle direction
            off = (math.degrees(math.atan2(p[1] - cy, p[0] - cx)) - (a0 + a1) / 2 + 180) % 360
            return abs(math.hypot(p[0] - cx, p[1] - cy) - 6.0) <= 1e-4 and abs(off - 180) <= 45.001
        chords = [b for b in lines if on_arc(b.start) and on_arc(b.end)]
        assert len(chords) == 14
        for b in chords:
            mx, my = (b.start[0] + b.end[0]) / 2, (b.start[1] + b.end[1]) / 2
            assert 0 < 6.0 - math.hypot(mx - cx, my - cy) <= 0.01
        # one after the other, from the corner's start angle to its end angle
        for b0, b1 in zip(chords[:-1], chords[1:]):
            assert b0.end == b1.start
        first, last = chords[0].start, chords[-1].end
        for p, a in ((first, a0), (last, a1)):
            assert math.hypot(p[0] - cx - 6 * math.cos(math.radians(a)),
                              p[1] - cy - 6 * math.sin(math.radians(a))) <= 1e-9


def test_pocket_chords_smoother_meets_the_bar(pocket_chords):
    prog, ref, limits, delta, path, info = pocket_chords
    assert info["certificate"].ok
    # 4 corners x 15 chord vertices, the lead-in, the two boss corners, the bulge's two
    # ends and the lead-out: 66 tangent breaks; the bulge's and the boss's curvature jumps
    kinds = [j["kind"] for j in info["joins"]]
    assert kinds.count("tangent-break") == 4 * 15 + 6
    assert all(j["status"] == "blended" for j in info["joins"])
    assert info["max_deviation_bound"] <= delta
    for s in path.segments:
        if isinstance(s.geom, BezierCurve):
            pts = bc.bezier_points(s.geom, 2001)
            assert float(np.max(bc.dist_to(pts, _feed_paths(ref)))) <= delta
            assert float(np.min(bc.dist_to(pts, bc.contour(prog)))) >= ref.radius - 1e-6
    t_ref = ccopt.plan_feed(ref, limits).duration
    prof = ccopt.plan_feed(path, limits)
    assert prof.sample(2e-4).axis_acceleration_ratio.max() <= 1.001
    # the bar: at least 10 % below PMAC's cycle time under the case's limits ...
    assert prof.duration <= 0.9 * t_ref
    # ... and no faster than the feed allows
    assert prof.duration > feed_limited_time(path, limits)


def test_square_pocket_corners():
    # four sharp inside corners of the tool path, no arcs: each becomes a G2 blend
    text = """G21 G17 G90 G94
G0 X10 Y10
G1 F1200
G41.1 D4
G1 X0 Y10
Y0
X20
Y20
X0
Y10
G40
G1 X10
M30
"""
    prog = read_text(text, "square.nc")
    ref = ccopt.compensate(prog, "pmac")
    delta = 0.05
    path, info = smooth(BlendProblem(prog, ref, ccopt.AxisLimits([100, 100], [1000, 1000])),
                        delta)
    assert info["certificate"].ok
    kinds = sorted(j["kind"] for j in info["joins"])
    assert kinds == ["tangent-break"] * 6   # four corners, the lead-in and lead-out joins
    assert all(j["status"] == "blended" for j in info["joins"])
    for j in info["joins"]:
        corner = np.asarray(ref.segments[j["segment"]].start)[None, :]
        d = float(bc.dist_to(corner, _feed_paths(path))[0])
        # within the band, and using it: the search takes the largest blend that fits
        assert 0.5 * delta < d <= delta
