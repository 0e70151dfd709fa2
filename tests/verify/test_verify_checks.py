"""Limits, continuity and certified (spiral) figures through ``verify``."""
from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.geometry import Arc, Line
from ccopt.program.model import Block, Modal, Motion, Program, Source
from ccopt.toolpath import PathSegment, Role, ToolPath
from ccopt.verify import verify
from ccopt.verify.limits import check_limits


def _blk(line, motion, s, e, k, r, center=None):
    return Block(Source("<t>", line, 1), motion, (s[0], s[1], 0.0), (e[0], e[1], 0.0),
                 Modal(side=k, radius=r),
                 center=None if center is None else (center[0], center[1], 0.0), feed=10.0)


# --------------------------------------------------------------------------- limits


def test_limits_from_duck_typed_samples():
    # two axes, v limits 10 and 20, a limits 100 and 100; the X velocity reaches
    # 12 (ratio 1.2) on samples 3..5, the feed 6 against a cap of 5 on sample 8
    t = np.arange(10) * 0.1
    vel = np.zeros((10, 2))
    vel[3:6, 0] = [11.0, 12.0, 10.5]
    acc = np.zeros((10, 2))
    acc[:, 1] = 50.0
    feed = np.full(10, 4.0)
    feed[8] = 6.0
    smp = SimpleNamespace(t=t, vel=vel, acc=acc, vmax=np.array([10.0, 20.0]),
                          amax=np.array([100.0, 100.0]), feed=feed, feed_cap=np.full(10, 5.0))
    check, viol = check_limits(smp)
    assert not check.ok and check.basis == "sampled"
    assert check.figure == pytest.approx(1.2)
    kinds = sorted((v.kind, v.detail["quantity"]) for v in viol)
    assert kinds == [("feed", "feed"), ("velocity", "U")]
    vx = [v for v in viol if v.kind == "velocity"][0]
    assert vx.depth == pytest.approx(0.2) and vx.detail["samples"] == 3
    assert vx.detail["time"] == pytest.approx(0.4)
    fd = [v for v in viol if v.kind == "feed"][0]
    assert fd.depth == pytest.approx(0.2) and fd.detail["time"] == pytest.approx(0.8)


def test_limits_on_a_planned_profile():
    case = find_case("pocket")
    prog = ccopt.read_program(case.program)
    path = compensate(prog, "pmac")
    prof = plan_feed(ExactPath(path), AxisLimits(v=case.vmax, a=case.amax), planner="toppra")
    cert = verify(path, prog, profile=prof)
    lim = cert.check("limits")
    assert lim.ok and lim.count > 1000
    # the plan rides its limits: the largest ratio is 1 (to rounding)
    assert lim.figure == pytest.approx(1.0, abs=1e-6)
    # the same samples against limits half as large: twice over
    smp = prof.sample(1e-3)
    half = SimpleNamespace(t=smp.t, velocity=smp.velocity, acceleration=smp.acceleration,
                           v_limit=smp.v_limit / 2, a_limit=smp.a_limit / 2, axes=smp.axes,
                           line=smp.line)
    check, viol = check_limits(half)
    assert not check.ok and check.figure == pytest.approx(2.0 * lim.figure, rel=1e-9)
    assert viol and all(v.kind in ("velocity", "acceleration") for v in viol)


def test_no_profile_no_limits_check():
    case = find_case("pocket")
    prog = ccopt.read_program(case.program)
    cert = verify(compensate(prog, "pmac"), prog)
    lim = cert.check("limits")
    assert lim.ok and lim.basis == "not-run" and lim.figure is None


# --------------------------------------------------------------------------- continuity


def test_continuity_gaps_and_tangent_breaks():
    # (0,0)->(10,0) then a quarter arc about (10,5) tangent to it (no break),
    # then a line going straight up from the arc's end (15,5): tangent (0,1) is
    # the arc's end tangent too, no break; then a 90-degree turn left: one break
    segs = [Line((0, 0), (10, 0)), Arc((10, 5), 5.0, -math.pi / 2, math.pi / 2),
            Line((15, 5), (15, 8)), Line((15, 8), (10, 8)), Line((10, 8.5), (0, 8.5))]
    path = ToolPath(tuple(PathSegment(g, Role.UNCOMPENSATED, None) for g in segs))
    prog = Program((), "<t>", "pmac")
    cert = verify(path, prog)
    c = cert.check("continuity")
    assert not c.ok
    gaps = cert.violations_of("gap")
    assert len(gaps) == 1 and gaps[0].tool_segment == 4 and gaps[0].depth == pytest.approx(0.5)
    # breaks: 90 deg at (15,8); 0 deg between the last two (both -x)
    br = c.detail["tangent_breaks_listed"]
    assert [b["tool_segment"] for b in br] == [3]
    assert br[0]["angle_deg"] == pytest.approx(90.0)
    # no contour: nothing else to check
    assert cert.check("gouge").ok and cert.min_clearance is None


# --------------------------------------------------------------------------- certified figures


def test_radius_change_over_an_arc_spiral_figures():
    # CC1: lead-in to (20,-10), a line up to (20,0) with r = 2, a CCW arc R = 20
    # about (0,0) to (0,20) with CCR3 before it (radius 2 -> 3 over the arc: the
    # tool runs the spiral rho = 18 - 2 phi / pi, phi in [0, pi/2]), a line to
    # (-20,20) with r = 3 (tool on y = 17), the lead-out.
    # * Against the arc (clearance min(2, 3) = 2) the spiral's distance is
    #   20 - rho >= 2, reached at its start: certified, no gouge.
    # * Against the line, whose start P = (0,20) is tangent to the arc, the
    #   clearance is 3. With delta = pi/2 - phi, |X - P|^2 = rho^2 + 400 -
    #   40 rho cos(delta), rho = 17 + 2 delta / pi: it dips below 9 just before
    #   the end (the radius is still growing towards 3 while the spiral turns
    #   in): a gouge of 3 - min |X - P| at the line's start.
    from scipy.optimize import minimize_scalar
    blocks = (
        _blk(1, Motion.LINE, (30.0, 0.0), (20.0, -10.0), 1, 2.0),
        _blk(2, Motion.LINE, (20.0, -10.0), (20.0, 0.0), 1, 2.0),
        _blk(3, Motion.ARC_CCW, (20.0, 0.0), (0.0, 20.0), 1, 3.0, center=(0.0, 0.0)),
        _blk(4, Motion.LINE, (0.0, 20.0), (-20.0, 20.0), 1, 3.0),
        _blk(5, Motion.LINE, (-20.0, 20.0), (-20.0, 30.0), 0, 3.0),
    )
    prog = Program(blocks, "<t>", "pmac")
    path = compensate(prog, "pmac")
    spirals = [i for i, s in enumerate(path.segments) if s.kind == "spiral"]
    assert len(spirals) == 1
    cert = verify(path, prog)
    ctx = cert.context
    P = ctx.pairs
    C = ctx.contour
    j_arc = [j for j, b in enumerate(C.blocks) if b.source.line == 3][0]
    j_line = [j for j, b in enumerate(C.blocks) if b.source.line == 4][0]
    assert C.clearance[j_arc] == 2.0 and C.clearance[j_line] == 3.0
    q = np.flatnonzero((P.tool == spirals[0]) & (P.elem == j_arc))
    assert q.size == 1 and not P.exact[q[0]]
    assert P.d[q[0]] <= 2.0 + 1e-12 <= P.ub[q[0]] + 2e-12
    assert P.ub[q[0]] - P.d[q[0]] <= 0.1 * cert.eps

    def dist2(delta):
        rho = 17 + 2 * delta / math.pi
        return rho * rho + 400 - 40 * rho * math.cos(delta)

    res = minimize_scalar(dist2, bounds=(0.0, 0.1), method="bounded", options={"xatol": 1e-14})
    depth = 3 - math.sqrt(res.fun)
    assert depth > 1e-3
    g = cert.violations_of("gouge")
    assert len(g) == 1
    assert g[0].tool_segment == spirals[0] and g[0].element_block == 4
    assert g[0].basis == "certified-bound"
    assert depth - 1e-9 <= g[0].depth <= depth + 0.1 * cert.eps + 1e-9
    assert g[0].witness_contour == pytest.approx((0.0, 20.0), abs=1e-12)


def test_a_bezier_blend_in_the_tool_path_is_bounded():
    # Replace the first corner arc (about P = (-20,0), from (-20,-2) to (-22,0))
    # by the quadratic Bezier with its middle control point at P: B(t) - P =
    # (1-t)^2 (0,-2) + t^2 (-2,0), closest to P at t = 1/2, |B - P| = sqrt(0.5);
    # B_x <= -20 and B_y <= 0, so P is the nearest point of both elements:
    # a certified gouge of 2 - sqrt(0.5).
    from ccopt.geometry.curve import BezierCurve
    case = find_case("leadin-inside-line")
    prog = ccopt.read_program(case.program)
    path = compensate(prog, "pmac")
    i = [k for k, s in enumerate(path.segments) if s.role is Role.CORNER][0]
    arc = path.segments[i].geom
    assert arc.center == pytest.approx((-20.0, 0.0))
    a, b = np.array(arc.start), np.array(arc.end)
    bz = BezierCurve((tuple(a), (-20.0, 0.0), tuple(b)))
    segs = list(path.segments)
    segs[i] = replace(segs[i], geom=bz)
    cert = verify(replace(path, segments=tuple(segs)), prog)
    g = [v for v in cert.violations_of("gouge") if v.tool_segment == i]
    assert g and all(v.basis == "certified-bound" for v in g)
    want = 2.0 - math.sqrt(0.5)
    assert max(v.depth for v in g) == pytest.approx(want, abs=1e-6)
