"""Random Klartext contours, compensated by the ``heidenhain`` style, verified.

Each drawn program is a closed contour around a convex polygon (vertices on
a circle, every corner turning by at most 120 degrees) whose edges are
straight lines, ``CR`` arcs, ``CC`` + ``CP IPA`` arcs, ``CC`` + ``C`` arcs
(bulging out or in by at most 15 degrees) or ``CT`` tangent arcs, with
``RND`` and ``CHF`` at some corners between two lines, run with the tool
outside (``RR`` counter-clockwise, ``RL`` mirrored), entered with one of
``APPR LT/LN/CT/LCT`` and left with one of ``DEP LT/LN/CT/LCT`` from points
in the outer half-planes of the first and last edges. The tool radius is
small against every feature, so every such contour is machinable: the
compensated path must verify (no gouge, contact, side, continuity) with
ccopt's verifier, independently of how it was made.
"""
from __future__ import annotations

from hypothesis import HealthCheck, given, settings

from ccopt import verify
from ccopt.compensate import compensate
from ccopt.program import read_text
from klartext_contours import contours


@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(contours())
def test_random_klartext_contours_verify(text):
    prog = read_text(text, "r.h", "heidenhain")
    path = compensate(prog, style="heidenhain")
    cert = verify(path, prog)
    assert cert.ok, (text, cert.summary())
