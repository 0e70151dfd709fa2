"""Random Klartext contours (a Hypothesis strategy, :func:`contours`): a
convex polygon's edges as lines, CR arcs, CC + CP IPA arcs, CC + C arcs and
CT arcs, RND and CHF at some corners, the tool outside, entered with APPR
and left with DEP (LT, LN, CT, LCT). Shared by the heidenhain style's
properties (tests/compensate/test_heidenhain_properties.py) and the
rotation tests (tests/program/test_heidenhain_rotation.py)."""
from __future__ import annotations

import math

from hypothesis import strategies as st

RADIUS = 40.0


def _fmt(v: float) -> str:
    return f"{v:+.6f}"


@st.composite
def contours(draw):
    n = draw(st.integers(5, 8))
    weights = [draw(st.floats(1.0, 2.0)) for _ in range(n)]
    total = sum(weights)
    ang, a = [], 0.0
    for w in weights:
        ang.append(a)
        a += 2 * math.pi * w / total
    mirror = draw(st.sampled_from([1, -1]))
    pts = [(RADIUS * math.cos(t), mirror * RADIUS * math.sin(t)) for t in ang] + [None]
    pts[-1] = pts[0]
    r = draw(st.sampled_from([0.5, 1.0, 2.0]))
    side = "RR" if mirror > 0 else "RL"
    kinds = ["L"] + [draw(st.sampled_from(["L", "L", "CR", "CP", "C", "CT"]))
                     for _ in range(n - 2)] + ["L"]
    lines = [f"TOOL DEF 1 L+0 R+{r}", "TOOL CALL 1 Z S1000", "L Z+10 R0 FMAX"]
    p0, p1 = pts[0], pts[1]
    t0 = _unit(p1[0] - p0[0], p1[1] - p0[1])
    n0 = (mirror * t0[1], -mirror * t0[0])            # outward normal of the first edge
    ps = (p0[0] + 30 * n0[0] - 20 * t0[0], p0[1] + 30 * n0[1] - 20 * t0[1])
    lines += [f"L X{_fmt(ps[0])} Y{_fmt(ps[1])} R0 FMAX", "L Z-2 R0 F1000"]
    lines.append(_appr(draw, p0, side))
    for i in range(n):
        a_, b_ = pts[i], pts[i + 1]
        lines += _edge(draw, kinds[i], a_, b_, mirror)
        if i + 1 < n and kinds[i] == "L" and kinds[i + 1] == "L":
            lines += _corner(draw, pts[i], pts[i + 1], pts[i + 2])
    lines.append(_dep(draw, pts[-2], p0, mirror))
    lines += ["L Z+10 R0 FMAX", "M30"]
    body = "\n".join(f"{k + 1} {ln}" for k, ln in enumerate(lines))
    return f"0 BEGIN PGM R MM\n{body}\n{len(lines) + 1} END PGM R MM\n"


def _unit(x: float, y: float):
    d = math.hypot(x, y)
    return (x / d, y / d)


def _appr(draw, p0, side: str) -> str:
    kind = draw(st.sampled_from(["LT", "LN", "CT", "LCT"]))
    words = {"LT": f"LEN{draw(st.floats(3, 10)):.3f}", "LN": f"LEN{draw(st.floats(3, 10)):.3f}",
             "CT": f"CCA{draw(st.floats(30, 180)):.3f} R+{draw(st.floats(3, 10)):.3f}",
             "LCT": f"R{draw(st.floats(3, 10)):.3f}"}[kind]
    z = " Z-5" if draw(st.booleans()) else ""
    return f"APPR {kind} X{_fmt(p0[0])} Y{_fmt(p0[1])}{z} {words} {side} F500"


def _dep(draw, before, p0, mirror: int) -> str:
    kind = draw(st.sampled_from(["LT", "LN", "CT", "LCT"]))
    if kind in ("LT", "LN"):
        return f"DEP {kind} LEN{draw(st.floats(3, 10)):.3f} F800"
    if kind == "CT":
        return f"DEP CT CCA{draw(st.floats(30, 180)):.3f} R+{draw(st.floats(3, 10)):.3f} F800"
    t = _unit(p0[0] - before[0], p0[1] - before[1])
    n = (mirror * t[1], -mirror * t[0])
    pn = (p0[0] + 30 * n[0] + 20 * t[0], p0[1] + 30 * n[1] + 20 * t[1])
    return f"DEP LCT X{_fmt(pn[0])} Y{_fmt(pn[1])} R{draw(st.floats(3, 10)):.3f} F800"


def _edge(draw, kind: str, a, b, mirror: int) -> list[str]:
    end = f"X{_fmt(b[0])} Y{_fmt(b[1])}"
    if kind in ("L", "CT"):
        return [f"{kind} {end}"]
    beta = math.radians(draw(st.floats(3, 15))) * draw(st.sampled_from([1, -1]))
    chord = math.hypot(b[0] - a[0], b[1] - a[1])
    radius = chord / (2 * math.sin(abs(beta)))
    # beta > 0 bulges outward: the arc turns the polygon's way (ccw when mirror > 0)
    ccw = (beta > 0) == (mirror > 0)
    dr = "DR+" if ccw else "DR-"
    if kind == "CR":
        return [f"CR {end} R+{radius:.9f} {dr}"]
    t = _unit(b[0] - a[0], b[1] - a[1])
    left = (-t[1], t[0]) if ccw else (t[1], -t[0])
    h = radius * math.cos(beta)
    c = ((a[0] + b[0]) / 2 + h * left[0], (a[1] + b[1]) / 2 + h * left[1])
    cc = f"CC X{c[0]:+.9f} Y{c[1]:+.9f}"
    if kind == "CP":
        ipa = math.degrees(2 * abs(beta)) * (1 if ccw else -1)
        return [cc, f"CP IPA{ipa:+.9f} {dr}"]
    return [cc, f"C {end} {dr}"]


def _corner(draw, a, p, b) -> list[str]:
    what = draw(st.sampled_from(["", "", "RND", "CHF"]))
    if not what:
        return []
    t1, t2 = _unit(p[0] - a[0], p[1] - a[1]), _unit(b[0] - p[0], b[1] - p[1])
    turn = math.acos(max(-1.0, min(1.0, t1[0] * t2[0] + t1[1] * t2[1])))
    room = 0.4 * min(math.hypot(p[0] - a[0], p[1] - a[1]), math.hypot(b[0] - p[0], b[1] - p[1]))
    if what == "RND":
        rho = draw(st.floats(0.2, 1.0)) * room / math.tan(turn / 2)
        return [f"RND R{min(rho, 8.0):.6f}"]
    return [f"CHF {draw(st.floats(0.2, 1.0)) * room:.6f}"]
