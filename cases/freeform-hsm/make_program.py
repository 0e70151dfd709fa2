"""Writes freeform-hsm.pmc: a freeform boss as a CAM system writes it for a
high-speed finishing pass (deterministic; run ``python make_program.py``).

The part contour is the closed curve (polar, mm, theta in radians)

    rho(theta) = 40 + 6 cos(3 theta) + 2 sin(5 theta + 0.7)

convex on its lobes and concave between them (smallest radius of curvature
15.5 mm convex, 16.1 mm concave, so a 3 mm cutter fits everywhere; 267 mm
round). It is
written as LINEAR chords, clockwise from theta = 0, whose vertices lie on the
curve (to the 4 written decimals) and which stray from it by at most
CHORD_TOL (greedy: each chord is the longest whose sagitta, measured at dense
samples of the curve, stays within the tolerance). Cutter radius 3, CC1 (tool
left of a clockwise travel: outside the boss), feed 200 mm/s (12 m/min).
"""
from __future__ import annotations

import math
from pathlib import Path

#: CAM chord tolerance (mm): the largest distance of the curve from its chord.
CHORD_TOL = 0.003
#: Samples of theta per radian when measuring a chord's sagitta.
SAMPLES_PER_RAD = 4000
FEED = 200.0
#: Turns (degrees) no vertex may make: between the turn whose outside corner PMAC
#: extends to r / cos(turn / 2) = r + 1e-4 (0.936 degrees at r = 3) and its break
#: angle acos(0.9998) = 1.146 degrees, above which it adds an arc instead (with a margin
#: for the written decimals): the bundled cases keep every extended corner within
#: 1e-4 of the cutter radius (tests/verify/test_verify_faults.py).
AVOIDED_TURN = (0.92, 1.16)


def rho(t: float) -> float:
    return 40.0 + 6.0 * math.cos(3.0 * t) + 2.0 * math.sin(5.0 * t + 0.7)


def point(t: float) -> tuple[float, float]:
    r = rho(t)
    return 50.0 + r * math.cos(t), 50.0 + r * math.sin(t)


def _sagitta(t0: float, t1: float) -> float:
    (x0, y0), (x1, y1) = point(t0), point(t1)
    L = math.hypot(x1 - x0, y1 - y0)
    n = max(2, int(abs(t1 - t0) * SAMPLES_PER_RAD))
    worst = 0.0
    for k in range(1, n):
        x, y = point(t0 + (t1 - t0) * k / n)
        worst = max(worst, abs((x1 - x0) * (y0 - y) - (x0 - x) * (y1 - y0)) / L)
    return worst


def chord_parameters() -> list[float]:
    """Vertex parameters, clockwise: 0, then decreasing to -2 pi."""
    ts = [0.0]
    step = 0.02
    while ts[-1] > -2.0 * math.pi:
        t0 = ts[-1]
        lo, hi = 0.0, step
        while _sagitta(t0, t0 - hi) <= CHORD_TOL and hi < 1.0:
            lo, hi = hi, 2.0 * hi
        for _ in range(30):                   # bisection on the chord's sweep
            mid = 0.5 * (lo + hi)
            if _sagitta(t0, t0 - mid) <= CHORD_TOL:
                lo = mid
            else:
                hi = mid
        t1 = t0 - lo
        if t1 <= -2.0 * math.pi or -2.0 * math.pi - t1 > -0.5 * lo:
            t1 = -2.0 * math.pi                  # close the loop (last chord no longer)
        ts.append(t1)
    return ts


def _written(t: float) -> tuple[float, float]:
    x, y = point(t)
    return round(x, 4), round(y, 4)


def _turn(a, b, c) -> float:
    """Turn (degrees) of the polyline a -> b -> c at b."""
    u = (b[0] - a[0], b[1] - a[1])
    v = (c[0] - b[0], c[1] - b[1])
    return abs(math.degrees(math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1])))


def avoid_turns(ts: list[float]) -> list[float]:
    """``ts`` with a chord split in two (at its middle parameter: both halves keep
    within the tolerance) next to every vertex whose written turn is in
    :data:`AVOIDED_TURN`, the longer of its two chords, until none is."""
    lo, hi = AVOIDED_TURN
    ts = list(ts)
    changed = True
    while changed:
        changed = False
        pts = [_written(t) for t in ts]
        for k in range(1, len(ts) - 1):
            if lo <= _turn(pts[k - 1], pts[k], pts[k + 1]) <= hi:
                i = k - 1 if ts[k - 1] - ts[k] > ts[k] - ts[k + 1] else k
                ts.insert(i + 1, 0.5 * (ts[i] + ts[i + 1]))
                changed = True
                break
    return ts


def program() -> str:
    ts = avoid_turns(chord_parameters())
    x0, y0 = point(0.0)
    lines = [
        "; A freeform boss as CAM output for a high-speed finishing pass: its contour",
        "; rho(theta) = 40 + 6 cos(3 theta) + 2 sin(5 theta + 0.7) about (50, 50), as",
        f"; {len(ts) - 1} LINEAR chords (chord error <= {CHORD_TOL} mm, vertices on the curve to",
        "; 4 decimals; written by make_program.py). Cutter radius 3, CC1 clockwise (tool",
        "; outside), feed 200 mm/s: convex vertices are outside corners of the tool path,",
        "; concave ones inside corners.",
        "OPEN PROG 30 CLEAR",
        f"RAPID X{x0 + 12:.4f} Y{y0 + 12:.4f} Z5",
        f"LINEAR ABS F{FEED:g}",
        "Z-3                   ; plunge",
        "CCR3 CC1",
        f"X{x0:.4f} Y{y0:.4f}     ; lead-in",
    ]
    for t in ts[1:]:
        x, y = point(t)
        lines.append(f"X{x:.4f} Y{y:.4f}")
    lines += ["CC0", f"X{x0 + 12:.4f} Y{y0 - 12:.4f}     ; lead-out", "Z5", "CLOSE", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    Path(__file__).with_name("freeform-hsm.pmc").write_text(program())
