"""PMAC rules that had no bundled case: reversals, the automatic lead-out,
Turbo's DEFINE CCBUF, outside lead-out by a CIRCLE move, and the same-side
"no intersection" corner (spec, PMAC section, rules 3, 5 and 6).

Every expected figure is derived here from the spec's formulas
(``o(t) = k*(-t_y, t_x)``; arc offset ``R - r`` for ccw+left or cw+right, else
``R + r``; outside arcs of radius ``r`` about ``P``), never copied from ccopt.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ccopt.compensate import compensate
from ccopt.compensate.pmac import PmacStyle, assemble
from ccopt.compensate.scan import scan_program
from ccopt.program import read_text
from segment_expect import L, A, SP, check

TOL = 1e-9
PI = math.pi


def pmac(text: str):
    return read_text(text, "<test>.pmc", "pmac")


def o(t, k):
    """Spec: offset direction o(t) = k*(-t_y, t_x)."""
    return np.array([-k * t[1], k * t[0]], float)


def off(p, t, k, r):
    """Offset point P + r*o(t)."""
    return tuple(np.asarray(p, float) + r * o(t, k))


def mid(seg):
    g = seg.geom
    return np.asarray(g.point(g.length / 2), float)


# -- rule 3: reversal ---------------------------------------------------------------

def test_reversal_line_to_line_is_a_180_degree_arc_about_p():
    # CC1 (k=+1), r=2, start (0,0).
    # Lead-in (0,0)->(10,0), next +X: tangent -> ends at (10,0)+2*o(+X) = (10,2).
    # Corner (20,0): t_in=(1,0), t_out=(-1,0): c=0, d=-1, reversal, line-line:
    # A = (20,0)+2*o(+X) = (20,2), B = (20,0)+2*o(-X) = (20,-2); the 180-degree
    # arc about P goes round the end of the path (through P + r*t_in = (22,0)),
    # i.e. clockwise from angle pi/2 to -pi/2: sweep -pi.
    # Lead-out corner (10,0): t_in=(-1,0), t_out=(0,-1): c=(-1)(-1)-0=1 >0:
    # inside -> last move ends at (10,0)+2*o(-X) = (10,-2), lead-out to (10,-10).
    path = compensate(pmac("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX20 Y0\nX10 Y0\nCC0\nX10 Y-10\n"),
                      style="pmac")
    check(path, [
        L("lead-in", (0, 0), (10, 2)),
        L("compensated", (10, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (20, -2), -PI),
        L("compensated", (20, -2), (10, -2)),
        L("lead-out", (10, -2), (10, -10)),
    ])
    arc = next(s for s in path.segments if s.role.value == "corner")
    assert arc.geom.radius == pytest.approx(2, abs=TOL)
    assert np.allclose(mid(arc), (22, 0), atol=TOL)


def test_reversal_line_to_arc_without_intersection_is_a_180_degree_arc():
    # CC1, r=2. Line +X to P=(20,0) (offset y=2), then CIRCLE2 (ccw) about
    # (20,-10) (I0 J-10), R=10, from angle pi/2 (tangent (-1,0): a reversal)
    # by +pi/2 to (10,-10). ccw + left: tool toward the centre, offset R-r = 8;
    # the circle |X-(20,-10)| = 8 reaches up to y=-2 and misses y=2: no inside
    # intersection -> 180-degree arc about P from (20,2) to B = P + 2*o((-1,0))
    # = (20,-2) (through (22,0), sweep -pi), then the offset arc of radius 8
    # from (20,-2) (angle pi/2) to the arc's offset end.
    # Lead-out corner (10,-10): arc end tangent (ccw at angle pi) = (0,-1), lead-out
    # to (10,-20) along (0,-1): tangent -> ends at (10,-10)+2*o((0,-1)) = (12,-10).
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X-10 Y0\nLINEAR ABS F10\nCCR2 CC1\nX0 Y0\nX20 Y0\n"
                "CIRCLE2\nX10 Y-10 I0 J-10\nCC0\nLINEAR\nX10 Y-20\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),          # tangent lead-in: (0,0)+2*o(+X)
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (20, -2), -PI),
        A("compensated", (20, -10), (20, -2), (12, -10), PI / 2),
        L("lead-out", (12, -10), (10, -20)),
    ])
    segs = [s for s in path.segments if s.role.value != "rapid"]
    assert np.allclose(mid(segs[2]), (22, 0), atol=TOL)
    assert segs[3].geom.radius == pytest.approx(8, abs=TOL)


# Reversal with an intersection. The centre of an arc that starts (or ends)
# at P along -t_in lies on the normal through P, as do A and B, so the two
# carrier intersections are mirror images about that normal and have the SAME
# cost |X-A|+|X-B|: the nearest-root rule ties. The "inside" intersection of
# spec rule 3 is the one that shortens both moves, i.e. lies behind P along
# the incoming line ((X-P).t_in < 0) / the outgoing line ((X-P).t_out > 0);
# the other one would extend the line past P and make the arc sweep more
# than programmed.
Q5 = 4 * math.sqrt(5)          # sqrt(12^2 - 8^2)
W = math.atan(2 / math.sqrt(5))  # atan(8 / (4*sqrt5))


def test_reversal_line_to_arc_uses_the_inside_intersection():
    # CC1, r=2. Line +X to P=(20,0), offset y=2. CIRCLE1 (cw) about (20,10)
    # (I0 J10), R=10, from angle -pi/2 (tangent (-1,0): reversal) by -pi/2 to
    # (10,10). cw + left: tool away from the centre, offset R+r = 12.
    # y=2 meets |X-(20,10)|=12 at x = 20 +- sqrt(144-64) = 20 +- 4*sqrt5;
    # inside: X = (20 - 4*sqrt5, 2), at angle atan2(-8, -4*sqrt5) = -pi + W.
    # Lead-out corner (10,10): arc end tangent (cw at angle pi) = (0,1), lead-out
    # to (10,20) along (0,1): tangent -> ends at (10,10)+2*o((0,1)) = (8,10),
    # angle pi about (20,10). Tool arc sweep, clockwise from -pi+W to -pi: -W.
    x = (20 - Q5, 2)
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X-10 Y0\nLINEAR ABS F10\nCCR2 CC1\nX0 Y0\nX20 Y0\n"
                "CIRCLE1\nX10 Y10 I0 J10\nCC0\nLINEAR\nX10 Y20\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), x),
        A("compensated", (20, 10), x, (8, 10), -W),
        L("lead-out", (8, 10), (10, 20)),
    ])


def test_reversal_arc_to_line_uses_the_inside_intersection():
    # CC1, r=2. CIRCLE1 (cw) about (20,-10) from (10,-10) (angle pi) by -pi/2 to
    # P=(20,0) (end tangent (1,0)); cw + left: offset R+r = 12. Then the line
    # back to (10,0) (t=(-1,0): reversal), offset y = 0 + 2*o((-1,0))_y = -2.
    # y=-2 meets |X-(20,-10)|=12 at x = 20 +- 4*sqrt5; inside (on the line's
    # own part, (X-P).t_out > 0): X = (20 - 4*sqrt5, -2), angle pi - W.
    # Lead-in (10,-20)->(10,-10) along (0,1), tangent to the arc start (cw at
    # angle pi: (0,1)) -> ends at (10,-10)+2*o((0,1)) = (8,-10), angle pi.
    # Tool arc clockwise from pi to pi - W: sweep -W.
    # Lead-out corner (10,0): t_in=(-1,0), t_out=(0,-1): c=1: inside -> line
    # ends at (10,0)+2*o((-1,0)) = (10,-2).
    x = (20 - Q5, -2)
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X10 Y-20\nLINEAR ABS F10\nCCR2 CC1\nX10 Y-10\n"
                "CIRCLE1\nX20 Y0 I10 J0\nLINEAR\nX10 Y0\nCC0\nX10 Y-10\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (10, -20), (8, -10)),
        A("compensated", (20, -10), (8, -10), x, -W),
        L("compensated", x, (10, -2)),
        L("lead-out", (10, -2), (10, -10)),
    ])


def test_reversal_arc_to_arc_uses_the_inside_intersection():
    # CC1, r=2. CIRCLE1 about (20,-10) from (10,-10) to P=(20,0) (end tangent
    # (1,0)), then CIRCLE1 about (20,10) from P (start tangent (-1,0): reversal)
    # to (10,10). Both cw + left: offsets R+r = 12. The circles of radius 12
    # about (20,-10) and (20,10) meet on y=0 at x = 20 +- sqrt(144-100) =
    # 20 +- 2*sqrt11; inside (shortening both arcs): X = (20 - 2*sqrt11, 0),
    # at angle pi - V about (20,-10) and -pi + V about (20,10), V = atan(10/(2*sqrt11)).
    # Lead-in tangent to the first arc: (10,-10)+2*o((0,1)) = (8,-10) (angle pi);
    # lead-out (10,20) along (0,1), tangent: (10,10)+2*o((0,1)) = (8,10) (angle pi).
    # Sweeps: first arc clockwise pi -> pi-V: -V; second -pi+V -> -pi: -V.
    v = math.atan(10 / (2 * math.sqrt(11)))
    x = (20 - 2 * math.sqrt(11), 0)
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X10 Y-20\nLINEAR ABS F10\nCCR2 CC1\nX10 Y-10\n"
                "CIRCLE1\nX20 Y0 I10 J0\nX10 Y10 I0 J10\nCC0\nLINEAR\nX10 Y20\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (10, -20), (8, -10)),
        A("compensated", (20, -10), (8, -10), x, -v),
        A("compensated", (20, 10), x, (8, 10), -v),
        L("lead-out", (8, 10), (10, 20)),
    ])


# -- rule 5, last bullet: automatic zero-distance lead-out ---------------------------

def test_cc0_followed_only_by_a_z_move():
    # CC1, r=2. Lead-in (0,0)->(10,0), next +Y: c=1 inside -> ends at
    # (10,0)+2*o(+Y) = (8,0). Last move (10,0)->(10,10) ends at its offset end
    # (10,10)+2*o(+Y) = (8,10); the final straight move returns to (10,10).
    # decisions.AUTOMATIC_ZERO_DISTANCE_LEADOUT: the return comes before the
    # first trailing block with compensation off (the Z5 after CC0).
    path = compensate(pmac("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX10 Y10\nCC0\nZ5\n"), style="pmac")
    check(path, [
        L("lead-in", (0, 0), (8, 0)),
        L("compensated", (8, 0), (8, 10)),
        L("lead-out", (8, 10), (10, 10)),
        L("uncompensated", (10, 10), (10, 10)),
    ])
    z = path.segments[-1]
    assert (z.w0, z.w1) == pytest.approx((0, 5), abs=TOL)


def test_cc0_followed_by_nothing():
    path = compensate(pmac("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX10 Y10\nCC0\n"), style="pmac")
    check(path, [
        L("lead-in", (0, 0), (8, 0)),
        L("compensated", (8, 0), (8, 10)),
        L("lead-out", (8, 10), (10, 10)),
    ])


def test_program_end_while_on():
    # CC2 (k=-1), r=2. Lead-in (0,0)->(10,0), next (0,-1): c = 1*(-1) - 0 = -1,
    # k*c = 1 > 0: inside -> ends at (10,0)+2*o((0,-1)) = (10,0)+2*(-1,0) = (8,0).
    # Last move ends at (10,-10)+2*(-1,0) = (8,-10); the Z-3 (still on) runs
    # there; then the final straight move back to (10,-10).
    path = compensate(pmac("LINEAR ABS F10\nCCR2 CC2\nX10 Y0\nX10 Y-10\nZ-3\n"), style="pmac")
    check(path, [
        L("lead-in", (0, 0), (8, 0)),
        L("compensated", (8, 0), (8, -10)),
        L("compensated", (8, -10), (8, -10)),
        L("lead-out", (8, -10), (10, -10)),
    ])
    z = path.segments[2]
    assert (z.w0, z.w1) == pytest.approx((0, -3), abs=TOL)
    assert path.segments[-1].end == pytest.approx((10, -10), abs=TOL)


# -- rule 6: Turbo DEFINE CCBUF -----------------------------------------------------

def zmoves(m: int) -> str:
    return "".join(f"Z{-1 - (q % 2)}\n" for q in range(m))


def ccbuf_program(m: int, define: int | None = None) -> str:
    head = f"DEFINE CCBUF {define}\n" if define is not None else ""
    return (head + "OPEN PROG 1 CLEAR\nLINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX20 Y0\n" + zmoves(m)
            + "X20 Y10\nCC0\nX10 Y10\nCLOSE\n")


def ccbuf_expected(m: int, inside: bool):
    # CC1, r=2. Lead-in (0,0)->(10,0) collinear with the next move: (10,2).
    # Corner P=(20,0): +X then +Y, c = 1: inside. Lead-out corner (20,10): +Y
    # then -X, c = 1: inside -> ends at (20,10)+2*o(+Y) = (18,10).
    P = (20, 0)
    head = [L("lead-in", (0, 0), (10, 2))]
    tail = [L("lead-out", (18, 10), (10, 10))]
    if inside:
        # offsets y=2 and x=18 meet at (18,2); the Z moves run there
        x = (18, 2)
        return head + [L("compensated", (10, 2), x)] + [L("compensated", x, x)] * m + [
            L("compensated", x, (18, 10))] + tail
    # treated as outside: end at A = P + 2*o(+X) = (20,2), arc of radius 2
    # about P turning the same way as the path (left, +pi/2) to
    # B = P + 2*o(+Y) = (18,0); the Z moves after the arc (at B,
    # decisions.GAP_MOVES_AFTER_CORNER_ARC), then the next move from B.
    a, b = off(P, (1, 0), 1, 2), off(P, (0, 1), 1, 2)
    assert np.allclose(a, (20, 2)) and np.allclose(b, (18, 0))
    return head + [L("compensated", (10, 2), a), A("corner", P, a, b, PI / 2)] + [
        L("compensated", b, b)] * m + [L("compensated", b, (18, 10))] + tail


@pytest.mark.parametrize("n, m", [(2, 0), (2, 1), (2, 2), (2, 3), (0, 1), (1, 5)])
def test_ccbuf_option(n, m):
    # at most n Z-only moves: a normal inside corner; more: outside
    path = compensate(pmac(ccbuf_program(m)), style="pmac", ccbuf=n)
    check(path, ccbuf_expected(m, inside=m <= n))


@pytest.mark.parametrize("n, m", [(2, 2), (2, 3), (0, 0), (0, 1)])
def test_ccbuf_written_in_the_file(n, m):
    prog = pmac(ccbuf_program(m, define=n))
    assert prog.meta["ccbuf"] == n
    check(compensate(prog, style="pmac"), ccbuf_expected(m, inside=m <= n))


def test_ccbuf_option_wins_over_the_file():
    prog = pmac(ccbuf_program(3, define=1))
    check(compensate(prog, style="pmac", ccbuf=3), ccbuf_expected(3, inside=True))
    check(compensate(prog, style="pmac"), ccbuf_expected(3, inside=False))


def test_no_ccbuf_means_unlimited_look_ahead():
    check(compensate(pmac(ccbuf_program(7)), style="pmac"), ccbuf_expected(7, inside=True))


def _long_square_program(laps: int, n: int):
    """CC1, r=1, ``laps`` counter-clockwise laps of the square (0,0)-(10,10)
    with ``(7*j) % 5`` Z-only moves at compensated corner ``j``; the expected
    path derived corner by corner."""
    r, k = 1.0, 1
    sq = [(0, 0), (10, 0), (10, 10), (0, 10)]
    moves = [(sq[q % 4], sq[(q + 1) % 4]) for q in range(4 * laps)]
    tan = [tuple((np.subtract(e, s) / 10).tolist()) for s, e in moves]
    lines = ["OPEN PROG 1 CLEAR", "RAPID X-10 Y0", "LINEAR ABS F10", "CCR1 CC1", "X0 Y0"]
    # lead-in (-10,0)->(0,0) collinear with the first move: ends at (0,0)+o(+X)
    exp = [L("lead-in", (-10, 0), (0, 1))]
    cur = (0.0, 1.0)
    ztog = 0
    n_batch_corners = 0
    for j, (s, e) in enumerate(moves):
        lines.append(f"X{e[0]} Y{e[1]}")
        if j == len(moves) - 1:
            # last move (0,10)->(0,0) along (0,-1); lead-out to (0,-10) along
            # (0,-1): tangent -> ends at (0,0)+o((0,-1)) = (1,0)
            end = off(e, tan[j], k, r)
            exp += [L("compensated", cur, end), L("lead-out", end, (0, -10))]
            break
        g = (7 * j) % 5
        n_batch_corners += g == 0
        for _ in range(g):
            ztog ^= 1
            lines.append(f"Z{-1 - ztog}")
        a, b = off(e, tan[j], k, r), off(e, tan[j + 1], k, r)
        if g <= n:
            # every corner turns left by 90 degrees: inside for CC1; the offset
            # lines through A (along t_in) and B (along t_out) meet at
            # P + r*(o(t_in) + o(t_out))
            x = tuple(np.asarray(e, float) + r * (o(tan[j], k) + o(tan[j + 1], k)))
            exp += [L("compensated", cur, x)] + [L("compensated", x, x)] * g
            cur = x
        else:
            exp += [L("compensated", cur, a), A("corner", e, a, b, PI / 2)]
            exp += [L("compensated", b, b)] * g
            cur = b
    lines += ["CC0", "X0 Y-10", "CLOSE"]
    return "\n".join(lines) + "\n", exp, n_batch_corners


class _CountingPmac(PmacStyle):
    batched = 0

    def batch_corners(self, arr, ia):
        out = super().batch_corners(arr, ia)
        self.batched += int(out[0].sum())
        return out


def test_ccbuf_long_program_batch_route_agrees_with_scalar_route():
    n = 2
    text, expected, n_zero_gap = _long_square_program(laps=60, n=n)
    prog = pmac(text)
    style = _CountingPmac(ccbuf=n)
    fast = assemble(style, scan_program(prog), prog, vectorised=True)
    ref = assemble(PmacStyle(ccbuf=n), scan_program(prog), prog, vectorised=False)
    # the vectorised route really decided the gap-free corners
    assert style.batched == n_zero_gap > 40
    check(fast, expected, skip_roles=("rapid",))
    check(ref, expected, skip_roles=("rapid",))
    assert [(s.kind, s.role) for s in fast.segments] == [(s.kind, s.role) for s in ref.segments]
    for a, b in zip(fast.segments, ref.segments):
        assert np.allclose(a.start, b.start, atol=TOL) and np.allclose(a.end, b.end, atol=TOL)
        assert (a.w0, a.w1) == pytest.approx((b.w0, b.w1), abs=TOL)
    # and the public entry points give the same path (option and file routes)
    check(compensate(prog, style="pmac", ccbuf=n), expected)
    check(compensate(pmac(f"DEFINE CCBUF {n}\n" + text), style="pmac"), expected)


# -- rule 5, outside lead-out by a CIRCLE move ----------------------------------------

def test_outside_leadout_circle_is_arc_then_spiral():
    # CC1, r=2. Last compensated move +X to P=(20,0), offset y=2. Lead-out
    # CIRCLE1 (cw) about (10,0) (I-10 J0) from angle 0 by -pi/2 to Q=(10,-10);
    # start tangent (cw at angle 0) = (0,-1): c = 1*(-1) - 0 = -1, k*c < 0:
    # outside. Last move ends at A = P + 2*o(+X) = (20,2); arc of radius 2 about
    # P turning right by pi/2 to B = P + 2*o((0,-1)) = (22,0); then the spiral
    # about (10,0) from B (rho 12, angle 0) to Q (rho 10, angle -pi/2), sweep -pi/2.
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X-10 Y0\nLINEAR ABS F10\nCCR2 CC1\nX0 Y0\nX20 Y0\n"
                "CC0\nCIRCLE1\nX10 Y-10 I-10 J0\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), (20, 2)),
        A("corner", (20, 0), (20, 2), (22, 0), -PI / 2),
        SP("lead-out", (10, 0), (22, 0), (10, -10), -PI / 2),
    ])
    sp = path.segments[-1].geom
    assert (sp.rho0, sp.rho1) == pytest.approx((12, 10), abs=TOL)


def test_outside_leadout_circle_shallow_still_gets_the_arc():
    # "whatever the break angle": lead-out CIRCLE2 (ccw) whose start tangent is
    # t = (39999, -400)/40001, d = 39999/40001 = 0.99995 >= 0.9998 (shallow),
    # a right turn (c = -400/40001 < 0): outside for CC1. Its centre is to the
    # left of t: C = P + R*(400, 39999)/40001 with R = 40.001: (20.4, 39.999);
    # a quarter turn ccw ends at C + (39.999, -0.4) = (60.399, 39.599).
    P = np.array([20.0, 0.0])
    C = np.array([20.4, 39.999])
    R = float(np.hypot(*(C - P)))
    t = np.array([C[1] - P[1], -(C[0] - P[0])]) / R   # start tangent of a ccw arc
    assert t @ (1, 0) > 0.9998
    Q = C + np.array([39.999, -0.4])
    a = off(P, (1, 0), 1, 2)                           # (20,2)
    b = off(P, t, 1, 2)                                # 2 toward the centre
    turn = math.atan2(1 * t[1] - 0 * t[0], t[0])       # signed turn, < 0
    th_b = math.atan2(b[1] - C[1], b[0] - C[0])
    th_q = math.atan2(Q[1] - C[1], Q[0] - C[0])
    prog = pmac("OPEN PROG 1 CLEAR\nRAPID X-10 Y0\nLINEAR ABS F10\nCCR2 CC1\nX0 Y0\nX20 Y0\n"
                "CC0\nCIRCLE2\nX60.399 Y39.599 I0.4 J39.999\nCLOSE\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (-10, 0), (0, 2)),
        L("compensated", (0, 2), a),
        A("corner", tuple(P), a, b, turn),
        SP("lead-out", tuple(C), b, tuple(Q), th_q - th_b),  # b lies on P->C: sweep pi/2
    ])
    assert th_q - th_b == pytest.approx(PI / 2, abs=1e-9)
    sp = path.segments[-1].geom
    assert (sp.rho0, sp.rho1) == pytest.approx((R - 2, R), abs=TOL)


# -- rule 3: same-side corner whose offsets do not intersect ---------------------------

def test_no_intersection_line_to_arc_is_a_spiral():
    # CC1, r=2. Line +X to P=(20,0), offset y=2. CIRCLE2 (ccw) about (17,0)
    # (I-3 J0), R=3, from angle 0 (tangent (0,1): c = 1: inside) by +pi/2 to
    # (17,3). ccw + left: offset R-r = 1; the circle |X-(17,0)|=1 spans
    # y in [-1,1] and misses y=2. So the line ends at its own offset end
    # (20,2) and the arc runs from there to its own offset end: lead-out X7 Y3
    # along -X is tangent to the arc's end tangent (-1,0) -> (17,3)+2*o(-X) =
    # (17,1). Spiral about (17,0) from rho sqrt13 (angle atan2(2,3)) to rho 1
    # (angle pi/2): sweep pi/2 - atan2(2,3).
    prog = pmac("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX20 Y0\nCIRCLE2\nX17 Y3 I-3 J0\n"
                "CC0\nLINEAR\nX7 Y3\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (0, 0), (10, 2)),
        L("compensated", (10, 2), (20, 2)),
        SP("compensated", (17, 0), (20, 2), (17, 1), PI / 2 - math.atan2(2, 3)),
        L("lead-out", (17, 1), (7, 3)),
    ])
    sp = path.segments[2].geom
    assert (sp.rho0, sp.rho1) == pytest.approx((math.sqrt(13), 1), abs=TOL)


def test_no_intersection_arc_to_line_is_a_diagonal():
    # CC1, r=2. Lead-in (10,-3)->(17,-3) along +X, tangent to the CIRCLE2 arc
    # about (17,0) starting at angle -pi/2 (ccw tangent (1,0)): ends at
    # (17,-3)+2*o(+X) = (17,-1). The arc (R=3, offset R-r=1) runs to P=(20,0),
    # end tangent (0,1); the line to (10,0) along -X turns left (c =
    # 0*0 - 1*(-1) = 1): inside; its offset y = -2 misses the circle of radius
    # 1 (y in [-1,1]). So the arc ends at its own offset end (20,0)+2*o(+Y) =
    # (18,0) (an arc of radius 1, sweep pi/2), and the line runs from there to
    # its own offset end: lead-out to (10,-10) along (0,-1): c = 1, inside ->
    # (10,0)+2*o(-X) = (10,-2). Diagonal (18,0)->(10,-2).
    prog = pmac("RAPID X10 Y-3\nLINEAR ABS F10\nCCR2 CC1\nX17 Y-3\nCIRCLE2\nX20 Y0 I0 J3\n"
                "LINEAR\nX10 Y0\nCC0\nX10 Y-10\n")
    path = compensate(prog, style="pmac")
    check(path, [
        L("lead-in", (10, -3), (17, -1)),
        A("compensated", (17, 0), (17, -1), (18, 0), PI / 2),
        L("compensated", (18, 0), (10, -2)),
        L("lead-out", (10, -2), (10, -10)),
    ])
