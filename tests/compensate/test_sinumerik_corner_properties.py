"""Generated SINUMERIK plates with chamfers and roundings at their corners.

Each program is a star-shaped polygon round the origin (4 to 8 vertices at
radius 30..60, counter-clockwise, every edge at least 8 long, every corner
turning by 0.12 rad to 120 degrees), cut with ``G41`` (tool inside) or ``G42``
(outside) at a radius 0.5..3 from ``$TC_DP6``, entered ``NORM`` from a
point off the first edge and left with ``G40``. Each corner but the first
and last gets nothing, ``RND``, ``CHR``, ``CHF`` or, for a run of corners,
``RNDM``; coordinates are written with 3 to 10 decimals. A rounding at a
corner the tool meets from inside has a radius above the tool's (else no
tool could follow it).

Checked for every program:

- the reader's elements, against this file's own construction: a rounding
  of radius ``r`` at a corner turning by ``phi`` touches each edge at
  ``r tan(phi/2)`` from the corner, tangent to both; a chamfer ``CHR=w``
  cuts each edge at ``w``, one ``CHF=h`` is ``h`` long;
- compensated in every controller style (``siemens``, ``pmac``,
  ``linuxcnc``, ``heidenhain``, ``fagor``), the path is certified by the
  verifier (no gouge, contact, side, continuity).

Quick tier: 4 programs; slow tier: 200.
"""
from __future__ import annotations

import math

import pytest

from ccopt import compensate, verify
from ccopt.program.sinumerik import read_sinumerik
from sinumerik_plates import generated_plate, turn3

QUICK = range(4)
SLOW = range(4, 204)
STYLES = ("siemens", "pmac", "linuxcnc", "heidenhain", "fagor")


def _check_elements(prog, seq, corners) -> None:
    """Every drawn element where this file's construction puts it."""
    moves = [b for b in prog.blocks if b.motion.is_move and b.start[2] == b.end[2] == -2.0]
    k = 0                                 # moves[0]: the G41 block to seq[0]
    for i in range(1, len(seq) - 1):
        k += 1                            # the block reaching seq[i]
        c = corners[i]
        if c is None:
            continue
        kind, size = c
        phi = abs(turn3(seq[i - 1], seq[i], seq[i + 1]))
        a, e = moves[k], moves[k + 1]
        leg = {"CHR": size, "CHF": size / (2 * math.cos(phi / 2))}.get(
            kind, size * math.tan(phi / 2))
        assert math.dist(a.end[:2], seq[i]) == pytest.approx(leg, abs=1e-6), (i, kind)
        assert math.dist(e.end[:2], seq[i]) == pytest.approx(leg, abs=1e-6), (i, kind)
        if kind in ("RND", "RNDM"):
            assert e.motion.is_arc
            assert math.dist(e.center[:2], e.start[:2]) == pytest.approx(size, abs=1e-6)
            assert math.dist(e.center[:2], e.end[:2]) == pytest.approx(size, abs=1e-6)
            assert math.dist(e.center[:2], seq[i]) == pytest.approx(size / math.cos(phi / 2),
                                                                    abs=1e-6)
        else:
            assert e.motion.is_move and not e.motion.is_arc
            if kind == "CHF":
                assert math.dist(e.start, e.end) == pytest.approx(size, abs=1e-6)
        k += 1
    assert k == len(moves) - 3            # then the block back to seq[-1] and G40


def _check(seed: int) -> None:
    text, seq, corners = generated_plate(seed)
    prog = read_sinumerik(text, f"corners-{seed}.mpf")
    _check_elements(prog, seq, corners)
    for style in STYLES:
        path = compensate(prog, style=style)
        cert = verify(path, prog)
        assert cert.ok, (seed, style, text, cert.summary())


@pytest.mark.parametrize("seed", QUICK)
def test_generated_corner_plates(seed):
    _check(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", SLOW)
def test_generated_corner_plates_slow(seed):
    _check(seed)
