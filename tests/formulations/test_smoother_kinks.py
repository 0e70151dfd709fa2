"""The smoother at the tiny concave kinks CAM fillets leave in the tool path.

A CAM program writes a fillet tangent to its line with a few decimals, so the
line meets the fillet with a turn of a few micro- to milliradians. Where that
corner is concave the controller's tool path has a kink there (a tangent
break: the planners stop), and every blend of it cuts towards the part, by
``(5/16) l sin(theta/2)`` at legs ``l``. Kept to the rounding of the
smoother's checks, no blend longer than a few nanometres passed and the stop
stayed. The smoother may now give up the share of the gouge tolerance a tiny
corner arc's line already may (``APPROACH_SHARE``: a thousandth of it, 1e-6 mm
at the default 1e-3 mm) at a kink small enough that a corner arc of the cutter
radius over its turn stays within it, ``r (1 - cos theta) <= 1e-6``.

Checked here with figures worked out in the test: the controller's path has
such a kink (found from its joins' turns and the cutter radius), the smoothed
path has no join left without curvature continuity there, stays within the band
of the path it smooths, is certified, comes no closer to the part than the
allowance below the cutter radius (the verifier's clearance), and is faster
under jerk limits; over generated plates (slow tier) the comparison's smoother
row is certified, never slower than the fastest controller variant, within
the allowance of that variant's own clearance, and leaves no tiny kink of a
base path that keeps its clearance.
"""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.compare import BlendProblem
from ccopt.compare.figures import joins
from ccopt_formulations.smoother import smooth

from smoother_checks import (LIMITS, faster_start_holds, program, smooth_row,
                             unsmooth_joins_near, within_band)

#: The clearance a blend at a tiny kink may give up: a thousandth of the
#: verifier's default gouge tolerance for mm programs (1e-3 mm).
ALLOWANCE = 1e-3 * 1e-3
#: The verifier's clearance figure on a blend curve is a certified lower bound
#: whose gap is at most a tenth of its point tolerance (mm: 0.1 * 1e-6).
EPS = 1e-7


def _tiny_kinks(path, radius: float) -> list[tuple[float, float]]:
    """The join points of ``path``'s tangent breaks whose turn ``theta`` has
    ``radius (1 - cos theta) <= ALLOWANCE`` (found from the joins' angles)."""
    return [tuple(path.segments[i].start) for i, cls, _gap, ang, _jump in joins(path)
            if cls == "G0" and radius * (1.0 - math.cos(ang)) <= ALLOWANCE]


def test_a_tiny_concave_kink_beside_a_fillet_is_blended():
    # seed 7 (a rectangle, 4 decimals, r 0.255): Fagor's path (G138, the
    # program's own modes, the fastest controller's there) stops at a kink of
    # 1.6e-3 rad where a line meets a fillet on the concave side
    cp, prog = program(7)
    ref = ccopt.compensate(prog, "fagor", radius=cp.radius)
    kinks = _tiny_kinks(ref, cp.radius)
    assert kinks, cp.description                                  # the premise
    delta = 0.01 * cp.radius
    path, info = smooth(BlendProblem(prog, ref, LIMITS), delta)
    assert unsmooth_joins_near(path, kinks, within=1e-6) == []
    cert = info["certificate"]
    assert cert.ok, cert.summary()
    assert cert.min_clearance >= cp.radius - ALLOWANCE - EPS
    assert within_band(path, ref, delta)
    t_ref = ccopt.plan_feed(ref, LIMITS, planner="jerk").duration
    t_smooth = ccopt.plan_feed(path, LIMITS, planner="jerk").duration
    assert t_smooth < t_ref


def test_a_plate_without_tiny_kinks_gives_up_no_clearance():
    # seed 8 (a rectangle, perpendicular leads): its two tangent breaks, the
    # leads' joins, turn by far more than the allowance admits (90 degrees: r
    # (1 - cos theta) = r), so every blend keeps the ordinary checks, kept to
    # rounding: the smoothed path comes no closer to the part than PMAC's does
    cp, prog = program(8)
    ref = ccopt.compensate(prog, "pmac", radius=cp.radius)
    assert _tiny_kinks(ref, cp.radius) == [] and any(
        cls == "G0" for _i, cls, *_ in joins(ref)), cp.description      # the premise
    path, info = smooth(BlendProblem(prog, ref, LIMITS), 0.01 * cp.radius)
    assert not [j for j in info["joins"] if j.get("method") == "closed form at a tiny kink"]
    own = ccopt.verify(ref, prog).min_clearance
    assert info["certificate"].min_clearance >= min(cp.radius, own) - EPS


def _smooth_row_holds(seed: int, got=None) -> None:
    cp, cmp, row = smooth_row(seed) if got is None else got
    if row.info.get("optimised") is not None:             # the base path kept
        return
    base = cmp[row.info.get("base", "pmac")]
    own = min(cp.radius, base.certificate.min_clearance)
    assert row.certificate.min_clearance >= own - ALLOWANCE - EPS, cp.description
    if base.certificate.warnings:                          # the base path gouges already
        return
    kinks = _tiny_kinks(base.toolpath, cp.radius)
    assert unsmooth_joins_near(row.toolpath, kinks, within=1e-6) == [], cp.description


@pytest.mark.parametrize("seed", [31, 38])
def test_generated_plates_with_tiny_kinks_quick(seed):
    _smooth_row_holds(seed)


#: The generated plates whose comparison also checks the smoother's start
#: (tests/formulations/test_smoother_starts.py): one comparison serves both.
STARTS_SEEDS = range(30)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(0, 60))
def test_generated_plates_with_tiny_kinks(seed):
    got = smooth_row(seed)
    _smooth_row_holds(seed, got)
    if seed in STARTS_SEEDS:
        faster_start_holds(seed, got)
