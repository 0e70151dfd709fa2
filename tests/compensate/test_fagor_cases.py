"""The ``fagor`` style on the bundled Fagor cases.

Expected geometry is derived here from each case program's points with the
spec's rules (Fagor 8070 style), written out as formulas:

* ``o(t) = k*(-t_y, t_x)`` with ``k = +1`` (G41); ``A = P + r*o(t_in)``,
  ``B = P + r*o(t_out)`` at a programmed corner ``P``;
* G136: an arc of radius ``r`` about ``P`` from ``A`` to ``B``;
* G137 up to 90 degrees: the tangent lines at ``A`` and ``B`` meet at ``X``,
  ``A -> X -> B``; beyond 90 degrees ``A -> A + r*t_in -> B - r*t_out -> B``;
  a piece lying on a compensated line's own offset is part of that line;
* G138: activation straight to ``B``, cancellation straight from ``A``;
  G139: activation to ``A``, transition, ...; cancellation to ``A``,
  transition to ``B``, straight to the programmed end.

Never copied from ccopt's output.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import ccopt
from ccopt.cases import bundled_cases_dir, load_case
from ccopt.compensate import compensate
from ccopt.geometry import Arc, Line
from segment_expect import A as A_, L, check

TOL = 1e-9
R_TOOL = 2.0
K = 1  # G41


def o(t):
    return K * np.array([-t[1], t[0]])


def unit(v):
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def signed_turn(t_in, t_out):
    return math.atan2(t_in[0] * t_out[1] - t_in[1] * t_out[0], float(np.dot(t_in, t_out)))


def meet(A, ta, B, tb):
    """Intersection of the lines A + s*ta and B + u*tb."""
    w = np.asarray(B) - np.asarray(A)
    s = (w[0] * tb[1] - w[1] * tb[0]) / (ta[0] * tb[1] - ta[1] * tb[0])
    return np.asarray(A) + s * np.asarray(ta)


def run_case(name):
    case = load_case(bundled_cases_dir() / name)
    prog = ccopt.read_program(case.program)
    assert case.style == "fagor" and case.radius == R_TOOL
    return prog, compensate(prog, style=case.style, radius=case.radius)


def transition(P, A, B, t_in, t_out, corner, merge_in, merge_out):
    """The outside-corner pieces from A to B (spec rule 2), and where the
    incoming path ends / the outgoing one starts after merging."""
    r = R_TOOL
    if corner == "G136":
        return [A_("corner", P, A, B, signed_turn(t_in, t_out))], A, B
    if np.dot(t_in, t_out) >= 0:                       # up to 90 degrees
        pts = [A, meet(A, t_in, B, t_out), B]
    else:                                              # beyond 90 degrees
        pts = [A, A + r * t_in, B - r * t_out, B]
    end_in, start_out = pts[0], pts[-1]
    if merge_in:
        pts = pts[1:]
        end_in = pts[0]
    if merge_out:
        pts = pts[:-1]
        start_out = pts[-1]
    return [L("corner", a, b) for a, b in zip(pts, pts[1:])], end_in, start_out


def episodes(prog):
    """Per episode: S, P1, the compensated block, Q (from the program's blocks:
    rapid, activation, compensated move, cancellation)."""
    blocks = list(prog.blocks)
    assert len(blocks) == 24
    for i in range(0, 24, 4):
        rapid, lead_in, move, lead_out = blocks[i:i + 4]
        assert lead_in.modal.side == 1 and move.modal.side == 1 and lead_out.modal.side == 0
        yield (np.array(rapid.end[:2]), np.array(lead_in.end[:2]), move, np.array(lead_out.end[:2]))


def expected_case(prog, corner, start_end):
    r = R_TOOL
    out = []
    for S, P1, move, Q in episodes(prog):
        P2 = np.array(move.end[:2])
        is_line = not move.motion.is_arc
        t0 = unit(P1 - S)
        if is_line:
            t1 = t2 = unit(P2 - P1)
        else:
            C = np.array(move.center[:2])          # clockwise: tangent = (p - C) turned -90 deg
            t1 = unit([(P1 - C)[1], -(P1 - C)[0]])
            t2 = unit([(P2 - C)[1], -(P2 - C)[0]])
        t3 = unit(Q - P2)
        A1, B1 = P1 + r * o(t0), P1 + r * o(t1)
        A2, B2 = P2 + r * o(t2), P2 + r * o(t3)
        # activation
        if start_end == "G138":
            seq, start = [L("lead-in", S, B1)], B1
        else:
            pieces, _, start = transition(P1, A1, B1, t0, t1, corner, False, is_line)
            seq = [L("lead-in", S, A1)] + pieces
        # cancellation
        if start_end == "G138":
            tail, end = [L("lead-out", A2, Q)], A2
        else:
            pieces, end, B = transition(P2, A2, B2, t2, t3, corner, is_line, False)
            tail = pieces + [L("lead-out", B, Q)]
        if is_line:
            body = [L("compensated", start, end)]
        else:
            # clockwise with the tool left: outside the arc, radius R + r; the
            # start and end are the offset points at the programmed angles.
            sweep = -math.pi / 2
            body = [A_("compensated", C, start, end, sweep)]
            assert np.hypot(*(start - C)) == pytest.approx(10 + r)
        out += seq + body + tail
    return out


VARIANTS = [("G136", "G138"), ("G136", "G139"), ("G137", "G138"), ("G137", "G139")]


@pytest.mark.parametrize("corner, start_end", VARIANTS)
def test_variant_geometry(corner, start_end):
    prog, path = run_case(f"fagor-{corner.lower()}-{start_end.lower()}")
    check(path, expected_case(prog, corner, start_end))


def test_turning_angles_of_the_cases():
    prog, _ = run_case("fagor-g136-g139")
    angles = []
    for S, P1, move, Q in episodes(prog):
        P2 = np.array(move.end[:2])
        if move.motion.is_arc:
            C = np.array(move.center[:2])
            t1 = unit([(P1 - C)[1], -(P1 - C)[0]])
            t2 = unit([(P2 - C)[1], -(P2 - C)[0]])
        else:
            t1 = t2 = unit(P2 - P1)
        start = -math.degrees(signed_turn(unit(P1 - S), t1))
        end = -math.degrees(signed_turn(t2, unit(Q - P2)))
        angles.append((move.motion.is_arc, round(start, 4), round(end, 4)))
    # right turns (outside for G41) of 60, 120, 170 degrees, line-line then line-arc
    assert angles == [(False, 60, 60), (False, 120, 120), (False, 170, 170),
                      (True, 60, 60), (True, 120, 120), (True, 170, 170)]


def test_g137_inserted_segment_counts_follow_isg_g25():
    """Compensated line->line corners: no segment up to 90 degrees, one beyond;
    at activation/cancellation (not along their offsets) the piece there stays."""
    _, path = run_case("fagor-g137-g139")
    per_episode = []
    for seg in path.segments:
        if seg.role.value == "rapid":
            per_episode.append(0)
        elif seg.role.value == "corner":
            per_episode[-1] += 1
    # line 60: 1 + 1; line 120/170: 2 + 2; arc 60: 2 + 2; arc 120/170: 3 + 3
    assert per_episode == [2, 4, 4, 4, 6, 6]


# -- closest approach to the programmed corner ----------------------------------------
def point_distance(p, geom) -> float:
    p = np.asarray(p, float)
    if isinstance(geom, Line):
        a, b = np.asarray(geom.start), np.asarray(geom.end)
        ab = b - a
        L2 = float(np.dot(ab, ab))
        s = 0.0 if L2 == 0 else min(1.0, max(0.0, float(np.dot(p - a, ab)) / L2))
        return float(np.hypot(*(a + s * ab - p)))
    assert isinstance(geom, Arc)
    c = np.asarray(geom.center)
    ang = math.atan2(p[1] - c[1], p[0] - c[0])
    along = ((ang - geom.theta0) * math.copysign(1, geom.sweep)) % (2 * math.pi)
    if along <= abs(geom.sweep):
        return abs(float(np.hypot(*(p - c))) - geom.radius)
    return min(float(np.hypot(*(np.asarray(geom.start) - p))),
               float(np.hypot(*(np.asarray(geom.end) - p))))


def test_g137_beyond_90_never_closer_than_r_at_start_and_end():
    prog, path = run_case("fagor-g137-g139")
    segs = list(path.segments)
    starts = [i for i, s in enumerate(segs) if s.role.value == "rapid"] + [len(segs)]
    for e, (S, P1, move, Q) in enumerate(episodes(prog)):
        ep = segs[starts[e]:starts[e + 1]]
        near = [s for s in ep if s.role.value in ("corner", "compensated")]
        for P in (P1, np.array(move.end[:2])):
            d = min(point_distance(P, s.geom) for s in near)
            assert d >= R_TOOL - 1e-9, f"episode {e + 1}: {d} < r at {P}"


@pytest.mark.parametrize("deg", [95, 120, 150, 170, 180])
def test_g137_beyond_90_never_closer_than_r_on_a_contour(deg):
    # A compensated zigzag: +X 20, then turn right by deg, 20, turn right by
    # deg ... (G41: every corner outside), then a G2 arc: at every corner the
    # two compensated moves and the transition between them keep r from it.
    pts = [(0.0, 0.0)]
    d = 0.0
    for _ in range(4):
        pts.append((pts[-1][0] + 20 * math.cos(math.radians(d)),
                    pts[-1][1] + 20 * math.sin(math.radians(d))))
        d -= deg
    body = "\n".join(f"G01 X{x:.9f} Y{y:.9f}" for x, y in pts[1:])
    text = (f"G90 G17 F600 G137 G139\nG00 X-20 Y-20\nG41 D1\nG01 X0 Y0\n{body}\n"
            "G91 G02 X0 Y-10 I0 J-5\nG90 G40 G01 X-30 Y-30\n")
    prog = ccopt.read_text(text, "zigzag.nc")
    path = compensate(prog, style="fagor", radius=R_TOOL)
    on = [s for s in path.segments if s.role.value in ("corner", "compensated")]
    comp_blocks = [b for b in prog.blocks if b.modal.side == 1][1:]
    for b_in, b_out in zip(comp_blocks, comp_blocks[1:]):
        # the corner at the end of b_in: its two moves and the transition
        P = np.array(b_in.end[:2])
        near = [s for s in on if s.block in (b_in, b_out)]
        dist = min(point_distance(P, s.geom) for s in near)
        assert dist >= R_TOOL - 1e-9, f"{dist} < r at corner {P}"
    # and the joins really are the G137 construction: corner lines only
    assert {s.kind for s in path.segments if s.role.value == "corner"} == {"line"}


# -- the manual's two cancellation examples -------------------------------------------
def test_seed_arc_then_g40_without_motion():
    # Activation (20,0) -> (0,0) along -X is tangent to the G03 about (0,-20)
    # (start tangent -X): G138 behaviour, it ends at B = (0,0) + 2*o(-X) = (0,-2).
    # The arc (tool left of a CCW arc: inside, radius 18) ends at
    # (-20,-20) + 2*(1,0) = (-18,-20). "G91 G40 Y0" does not move the plane:
    # compensation is cancelled there and the tool goes to the programmed end
    # (-20,-20) in that block; G01 X-20 (incremental) goes on to (-40,-20).
    prog, path = run_case("fagor-seed-arc-cancel")
    check(path, [
        L("lead-in", (20, 0), (0, -2)),
        A_("compensated", (0, -20), (0, -2), (-18, -20), math.pi / 2),
        L("lead-out", (-18, -20), (-20, -20)),
        L("uncompensated", (-20, -20), (-40, -20)),
    ])
    # the move to (-20,-20) is the G40 block's own
    g40 = [s for s in path.segments if s.role.value == "lead-out"][0]
    text = open(load_case(bundled_cases_dir() / "fagor-seed-arc-cancel").program).read()
    assert "G40" in text.splitlines()[g40.block.source.line - 1]


def test_seed_line_then_g40_repeating_the_position():
    # Activation (0,20) -> (0,0) along -Y, then -X: a right turn, outside for
    # G41; default G139/G136: the activation ends at (0,0) + 2*o(-Y) = (2,0),
    # an arc about (0,0) to (0,-2) (clockwise, -90 deg), the line to
    # (-30,-2); "G01 G40 X-30" repeats the position: cancelled in place, the
    # tool goes to (-30,0); then straight to (25,-25) uncompensated.
    prog, path = run_case("fagor-seed-line-cancel")
    check(path, [
        L("lead-in", (0, 20), (2, 0)),
        A_("corner", (0, 0), (2, 0), (0, -2), -math.pi / 2),
        L("compensated", (0, -2), (-30, -2)),
        L("lead-out", (-30, -2), (-30, 0)),
        L("uncompensated", (-30, 0), (25, -25)),
    ])
