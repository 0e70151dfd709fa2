"""Random SINUMERIK contours: the ``siemens`` style keeps the radius.

A star-shaped polygon round the origin (5 to 7 vertices at radius 40..60,
counter-clockwise), each edge after the first a line or an arc bulging
either way written as ``G2``/``G3`` with ``CR=``, with ``I J`` or as ``CIP``
through its middle; ``G41`` or ``G42`` with a radius 0.3..1.5 from
``$TC_DP6``; ``G450``/``G451`` drawn per block; the approach and retraction
drawn from ``NORM``, ``KONT`` and the smooth ones ``G147``/``G247``/``G347``
(``G148``/``G248``/``G348``) with a ``DISR`` of 0.5..2.5, some with ``G341``
and ``DISCL``. The program is written as text, read by the SINUMERIK
reader, compensated as an 840D would, and certified by the verifier:
every tool position at least the radius from the contour, every steady
segment on its side and in contact.
"""
from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ccopt import compensate, verify
from ccopt.program.sinumerik import read_sinumerik


def _f(x: float) -> str:
    # ten decimals: centres and ends written with six make a rounded arc a
    # spiral (start and end radii differ by 1e-7), whose contact check is a
    # conservative bound over the whole segment, G451's extension included
    return f"{x:.10f}"


def _arc_words(p, q, bulge: float, form: str) -> str:
    """The arc from ``p`` to ``q`` whose sagitta is ``|bulge|`` half chords,
    bulging right of ``p -> q`` for ``bulge > 0`` (a counter-clockwise arc
    whose centre lies left of the chord), left for ``bulge < 0``."""
    half = math.dist(p, q) / 2
    sag = abs(bulge) * half
    radius = (half ** 2 + sag ** 2) / (2 * sag)
    m = np.array([(p[0] + q[0]) / 2, (p[1] + q[1]) / 2])
    t = (np.array(q) - np.array(p)) / (2 * half)
    left = np.array([-t[1], t[0]])
    side = 1.0 if bulge > 0 else -1.0
    # bulging right of p -> q (side +1): the centre left of the chord, a
    # counter-clockwise arc; the arc's middle lies on the other side
    centre = m + side * (radius - sag) * left
    middle = m - side * sag * left
    g = "G3" if bulge > 0 else "G2"
    if form == "CR":
        return f"{g} X{_f(q[0])} Y{_f(q[1])} CR={_f(radius)}"
    if form == "IJ":
        return f"{g} X{_f(q[0])} Y{_f(q[1])} I{_f(centre[0] - p[0])} J{_f(centre[1] - p[1])}"
    return f"CIP X{_f(q[0])} Y{_f(q[1])} I1={_f(middle[0])} J1={_f(middle[1])}"


@st.composite
def sinumerik_contours(draw):
    n = draw(st.integers(5, 7))
    gaps = draw(st.lists(st.floats(0.6, 1.4), min_size=n, max_size=n))
    angles = np.cumsum([0.0] + [g / sum(gaps) * 2 * math.pi for g in gaps[:-1]])
    radii = draw(st.lists(st.floats(40.0, 60.0), min_size=n, max_size=n))
    pts = [(rad * math.cos(a), rad * math.sin(a)) for rad, a in zip(radii, angles)]
    bulges = [0.0] + draw(st.lists(st.one_of(st.just(0.0), st.floats(-0.25, -0.05),
                                             st.floats(0.05, 0.25)),
                                   min_size=n - 1, max_size=n - 1))
    forms = draw(st.lists(st.sampled_from(["CR", "IJ", "CIP"]), min_size=n, max_size=n))
    corners = draw(st.lists(st.sampled_from(["G450", "G451"]), min_size=n + 1, max_size=n + 1))
    r = draw(st.floats(0.3, 1.5))
    k = draw(st.sampled_from([1, -1]))
    approach = draw(st.sampled_from(["NORM", "KONT", "G147", "G247", "G347"]))
    retract = draw(st.sampled_from(["NORM", "KONT", "G148", "G248", "G348"]))
    disr = draw(st.floats(0.5, 2.5))
    g341 = draw(st.booleans())
    return pts, bulges, forms, corners, r, k, approach, retract, disr, g341


def program_text(pts, bulges, forms, corners, r, k, approach, retract, disr, g341) -> str:
    p0, p1 = pts[0], pts[1]
    mid = ((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2)
    length = math.dist(p0, p1)
    t = ((p1[0] - p0[0]) / length, (p1[1] - p0[1]) / length)
    o = (-k * t[1], k * t[0])             # the tool side
    start = (mid[0] + (r + 5) * o[0], mid[1] + (r + 5) * o[1])
    side = "G41" if k == 1 else "G42"
    infeed = "G341 DISCL=1" if g341 else "G340"
    lines = [f"$TC_DP6[1,1]={_f(r)}", "N10 G90 G17 G71 T1 D1",
             f"N20 G0 X{_f(start[0])} Y{_f(start[1])} Z0", "N30 G1 F600"]
    if approach.startswith("G"):
        lines.append(f"{side} {approach} G140 {infeed} DISR={_f(disr)} X{_f(mid[0])} "
                     f"Y{_f(mid[1])} Z0")
    else:
        lines.append(f"{side} {approach} {corners[0]} X{_f(mid[0])} Y{_f(mid[1])}")
    lines.append(f"G1 X{_f(p1[0])} Y{_f(p1[1])}")
    n = len(pts)
    for i in range(1, n):
        p, q = pts[i], pts[(i + 1) % n]
        if bulges[i] == 0.0:
            lines.append(f"{corners[i]} G1 X{_f(q[0])} Y{_f(q[1])}")
        else:
            lines.append(f"{corners[i]} " + _arc_words(p, q, bulges[i], forms[i]))
    lines.append(f"{corners[n]} G1 X{_f(mid[0])} Y{_f(mid[1])}")
    if retract.startswith("G"):
        lines.append(f"G40 {retract} {infeed} DISR={_f(disr)} X{_f(start[0])} Y{_f(start[1])}"
                     " Z0")
    else:
        lines.append(f"G40 {retract} X{_f(start[0])} Y{_f(start[1])}")
    lines.append("M30")
    return "\n".join(lines) + "\n"


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(sinumerik_contours())
def test_random_sinumerik_contours_keep_the_radius(drawn):
    text = program_text(*drawn)
    prog = read_sinumerik(text, "random.mpf")
    path = compensate(prog, style="siemens")
    cert = verify(path, prog)
    assert cert.ok, (text, [v for v in cert.violations][:3])
    kinds = [s.role.value for s in path.segments]
    assert "compensated" in kinds
    if drawn[6] in ("G247", "G347"):
        assert any(s.kind == "arc" and s.role.value == "lead-in" for s in path.segments)
