"""The smoother's closed-form blends: short corner arcs between chords absorbed into
one outward blend, and every blend's curvature within the stated bound."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

import ccopt
from ccopt.cases import find_case
from ccopt.compare import BlendProblem
from ccopt.geometry import BezierCurve
from ccopt.program import read_text
from ccopt.toolpath import Role
from ccopt_formulations.smoother import smooth

import blend_checks as bc

R_CIRCLE = 20.0
STEP_DEG = 2
RADIUS = 3.0


def _chorded_boss() -> str:
    """The tool outside a circle of radius 20 (a boss), its upper half as LINEAR
    chords of 2 degrees, clockwise with G41 (tool on the left: outside): every
    chord vertex is an outside corner of the tool path, where PMAC adds a corner
    arc of the cutter radius turning by 2 degrees."""
    lines = ["G21 G17 G90 G94", "G0 X-20 Y-10", "G1 F6000", f"G41.1 D{2 * RADIUS:g}",
             "G1 X-20 Y0"]
    for a in range(180 - STEP_DEG, -1, -STEP_DEG):
        x, y = R_CIRCLE * math.cos(math.radians(a)), R_CIRCLE * math.sin(math.radians(a))
        lines.append(f"G1 X{x:.6f} Y{y:.6f}")
    lines += ["G1 X20 Y-10", "G40", "G1 X30 Y-10", "M30", ""]
    return "\n".join(lines)


@pytest.fixture(scope="module")
def boss():
    prog = read_text(_chorded_boss(), "boss.nc")
    ref = ccopt.compensate(prog, "pmac")
    delta = 0.01 * RADIUS
    path, info = smooth(BlendProblem(prog, ref, ccopt.AxisLimits([200, 200], [2000, 2000])),
                        delta)
    return prog, ref, delta, path, info


def _bezier_curvature(curve: BezierCurve, n: int = 4001) -> np.ndarray:
    """|curvature| of a Bezier curve at n parameters, from its control points by de
    Casteljau's derivative rule (independent of the curve class's own methods)."""
    P = np.asarray(curve.control_points, float)
    d = len(P) - 1
    D1 = d * np.diff(P, axis=0)
    D2 = (d - 1) * np.diff(D1, axis=0)
    t = np.linspace(0.0, 1.0, n)[:, None]

    def ev(Q):
        m = len(Q) - 1
        return sum(math.comb(m, i) * t ** i * (1 - t) ** (m - i) * Q[i] for i in range(m + 1))
    a, b = ev(D1), ev(D2)
    return np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) / np.hypot(a[:, 0], a[:, 1]) ** 3


@pytest.mark.slow
def test_boss_corner_arcs_absorbed_and_certified(boss):
    prog, ref, delta, path, info = boss
    # 180/2 chords, so 89 vertices between chords, each an outside corner turning by
    # 2 degrees: its arc's apex is r (1/cos(1 deg) - 1) = 0.46 micrometres inside the
    # corner of the lines, far below the band: every one is absorbed. PMAC's lead-in
    # runs straight to the first offset point and adds one more arc there (after a
    # tangent break, not between two chords): that one stays, blended at its ends.
    arcs = [s for s in ref.segments if s.role is Role.CORNER]
    assert len(arcs) == 180 // STEP_DEG - 1 + 1
    assert info["corners_absorbed"] == 180 // STEP_DEG - 1
    assert info["certificate"].ok
    assert info["joins_blended"] == info["joins_found"]
    left = [s for s in path.segments if s.role is Role.CORNER
            and not isinstance(s.geom, BezierCurve)]
    assert len(left) == 1 and left[0].geom.center == arcs[0].geom.center


@pytest.mark.slow
def test_boss_blends_keep_outside_and_in_the_band(boss):
    prog, ref, delta, path, info = boss
    blends = _chord_blends(path)
    assert len(blends) >= 180 // STEP_DEG - 1         # (and the last chord into Y-10)
    pts = np.vstack([bc.bezier_points(g, 801) for g in blends])
    # no gouge: every point of a blend between two chords at least r from the chords
    # (worked out here; the lead-in's blend passes the contour's open start, which the
    # verifier exempts)
    assert float(bc.dist_to(pts, bc.contour(prog)).min()) >= RADIUS - 1e-9
    # the band: every blend point within delta of PMAC's path, densely sampled
    ref_pts = np.vstack([np.asarray(s.geom.point(np.linspace(0, s.length, max(2, int(
        s.length / 2e-4) + 1))), float) for s in ref.segments
        if s.role in (Role.COMPENSATED, Role.CORNER, Role.LEAD_IN, Role.LEAD_OUT)
        and s.length > 0])
    assert float(cKDTree(ref_pts).query(pts)[0].max()) <= delta
    # an outside corner is not cut: the blend passes within the apex gap of the corner
    # arc's apex (the arc's middle point), outside its circle
    # (the distance to the nearest blend sample is never below the true one)
    near = cKDTree(pts)
    segs = ref.segments
    for a, s, b in zip(segs[:-2], segs[1:-1], segs[2:]):
        if s.role is Role.CORNER and a.role is b.role is Role.COMPENSATED:
            mid = np.asarray(s.geom.point(0.5 * s.length), float)
            assert float(near.query(mid)[0]) <= delta


@pytest.mark.slow
def test_boss_blend_curvature_is_a_corner_not_a_hook(boss):
    _, _, _, path, _ = boss
    # each chord turns by 2 degrees; a blend spans about a chord (0.70 mm) and turns by
    # its corner's 2 degrees: its curvature stays within a few times 2 deg over its
    # length (0.05 /mm), far below the 1/r = 0.33 /mm of PMAC's corner arcs
    for g in _chord_blends(path):
        assert _bezier_curvature(g).max() <= 8 * math.radians(STEP_DEG) / g.length


def _chord_blends(path):
    """The blends between two compensated lines (the chords' corners)."""
    segs = path.segments
    return [s.geom for a, s, b in zip(segs[:-2], segs[1:-1], segs[2:])
            if isinstance(s.geom, BezierCurve) and a.role is Role.COMPENSATED
            and b.role is Role.COMPENSATED]


@pytest.mark.slow
@pytest.mark.parametrize("name", ["leadin-inside-line", "pocket", "pocket-chords"])
def test_blend_curvature_within_the_stated_bound(name):
    # the bound of smoother_joins' docstring: 8 (|turn| / S + max |k_end|), S = l_in +
    # l_out, turn the angle between the blend's end tangents (5 times that for a
    # one-sided blend, l_in or l_out zero)
    c = find_case(name)
    prog = ccopt.read_program(c.program)
    ref = ccopt.compensate(prog, "pmac")
    path, info = smooth(BlendProblem(prog, ref, ccopt.AxisLimits(c.vmax, c.amax)),
                        0.01 * ref.radius)
    assert info["certificate"].ok
    blended = [j for j in info["joins"] if j["status"] == "blended"]
    curves = [s.geom for s in path.segments if isinstance(s.geom, BezierCurve)]
    assert len(curves) == len(blended)
    for j, g in zip(blended, curves):
        P = np.asarray(g.control_points, float)
        t0, t1 = P[1] - P[0], P[-1] - P[-2]
        turn = math.atan2(abs(t0[0] * t1[1] - t0[1] * t1[0]), float(t0 @ t1))
        k = _bezier_curvature(g)
        k_end = max(k[0], k[-1])
        one_sided = min(j["l_in"], j["l_out"]) == 0
        bound = 8 * (turn / (j["l_in"] + j["l_out"]) + k_end) * (5 if one_sided else 1)
        assert k.max() <= bound * (1 + 1e-6)
