"""Generated SINUMERIK plates: star-shaped polygons cut with G41 or G42,
entered and left at the middle of the first edge, with chamfers and
roundings drawn at their corners (:func:`generated_plate`). Shared by the
corner tests (tests/compensate/test_sinumerik_corner_properties.py) and the
frame tests (tests/program/test_sinumerik_frames.py)."""
from __future__ import annotations

import math
import random

#: Every corner turns by at least this (radians), so that a chamfer's two
#: corners (half the turn each) stay beyond LinuxCNC's "straight on"
#: tolerance of 0.05 rad, within which it steps across an outside corner
#: (a gouge of r (1 - cos(turn/2)), LinuxCNC's own behaviour: docs/compensation.md).
MIN_TURN = 0.12


def _polygon(rng: random.Random) -> list[tuple[float, float]]:
    while True:
        n = rng.randint(4, 8)
        gaps = [rng.uniform(0.6, 1.4) for _ in range(n)]
        a, angles = 0.0, []
        for g in gaps:
            angles.append(a)
            a += g / sum(gaps) * 2 * math.pi
        pts = [(r * math.cos(t), r * math.sin(t))
               for r, t in zip((rng.uniform(30, 60) for _ in range(n)), angles)]
        edges = [math.dist(pts[i], pts[(i + 1) % n]) for i in range(n)]
        if min(edges) >= 8 and all(MIN_TURN <= abs(_turn(pts, i)) <= math.radians(120)
                                   for i in range(n)):
            return pts


def _unit(p, q):
    d = math.dist(p, q)
    return ((q[0] - p[0]) / d, (q[1] - p[1]) / d)


def turn3(a, p, b) -> float:
    """The turning angle at ``p`` from ``a -> p`` to ``p -> b`` (radians,
    left turns positive)."""
    t1, t2 = _unit(a, p), _unit(p, b)
    return math.atan2(t1[0] * t2[1] - t1[1] * t2[0], t1[0] * t2[0] + t1[1] * t2[1])


def _turn(pts, i) -> float:
    return turn3(pts[i - 1], pts[i], pts[(i + 1) % len(pts)])


def _element(rng, a, p, b, tool: float, side: int):
    """The element drawn at corner ``p`` (``None``: sharp)."""
    phi = abs(turn3(a, p, b))
    room = 0.4 * min(math.dist(a, p), math.dist(p, b))
    # the tool meets the corner from inside when it turns toward the tool
    inside = (turn3(a, p, b) > 0) == (side == 41)
    kind = rng.choice((None, "RND", "RND", "CHR", "CHF", "RNDM"))
    if kind in ("RND", "RNDM"):
        low, high = (1.2 * tool if inside else 0.2), min(room / math.tan(phi / 2), 20.0)
        return (kind, rng.uniform(low, high)) if high > low else None
    if kind == "CHR":
        return (kind, rng.uniform(0.2, 1.0) * room)
    if kind == "CHF":
        return (kind, rng.uniform(0.2, 1.0) * room * 2 * math.cos(phi / 2))
    return None


def generated_plate(seed: int):
    """``(text, seq, corners)``: the program, the contour's points in the
    order cut (from the middle of the first edge round to it again) and,
    per index of ``seq``, the element drawn there ``(kind, size)`` (``None``:
    a sharp corner)."""
    rng = random.Random(seed)
    pts = _polygon(rng)
    tool = rng.uniform(0.5, 3.0)
    side = rng.choice((41, 42))          # counter-clockwise: G41 inside, G42 outside
    dec = rng.choice((3, 4, 6, 10))
    f = lambda v: f"{v:.{dec}f}"         # noqa: E731
    mid = ((pts[0][0] + pts[1][0]) / 2, (pts[0][1] + pts[1][1]) / 2)
    # the points as written, so that the checks use the program's own corners
    seq = [tuple(float(f(c)) for c in p) for p in [mid, *pts[1:], pts[0], mid]]
    corners = {i: _element(rng, seq[i - 1], seq[i], seq[i + 1], tool, side)
               for i in range(1, len(seq) - 1)}
    t0 = _unit(pts[0], pts[1])
    away = 1.0 if side == 42 else -1.0   # right of the first edge is outside
    start = (mid[0] + away * 10 * t0[1], mid[1] - away * 10 * t0[0])
    lines = ["G17 G71 G90 G94", f"$TC_DP6[1,1]={tool:.6f}", "T1 D1",
             f"G0 X{f(start[0])} Y{f(start[1])} Z5", "G1 Z-2 F300",
             f"G{side} G1 X{f(mid[0])} Y{f(mid[1])} F900"]
    modal = False
    for i, p in enumerate(seq[1:], start=1):
        c = corners.get(i)
        if c is not None and c[0] == "RNDM":
            words, modal = f" RNDM={c[1]:.6f}", True
        elif modal:
            words, modal = " RNDM=0" + ("" if c is None else f" {c[0]}={c[1]:.6f}"), False
        else:
            words = "" if c is None else f" {c[0]}={c[1]:.6f}"
        lines.append(f"X{f(p[0])} Y{f(p[1])}{words}")
    if modal:
        lines.append("RNDM=0")
    lines += [f"G40 G1 X{f(start[0])} Y{f(start[1])}", "G0 Z5", "M30"]
    return "\n".join(lines) + "\n", seq, corners
