"""PMAC compensation with the tool near the size of the contour's features.

Random closed contours from :func:`random_contours.hard_contours` (short
features of 0.3 to 4 tool radii on a polygon's edges: short moves, tight arcs,
sharp bends), cut with CC1 or CC2. What each must give is worked out here
from the programmed geometry alone, independently of ccopt's corner code:

* a concave arc (the tool inside it) of radius at most ``r``: the tool cannot
  follow it, and compensation must refuse the program with an error located
  at such an arc's block;
* otherwise a continuous tool path in which every compensated move ends on
  its element's offset (a line at signed distance ``k r``, an arc about its
  programmed centre at ``R -/+ r``) and starts on it too, except after an
  inside corner whose two offsets do not meet at all (line and circle, or two
  circles, that miss each other): there PMAC's no-intersection rule (Turbo
  PMAC User Manual p.301) ends the incoming move at its nominal offset end
  ``A`` and the outgoing move starts from ``A`` (a diagonal or a spiral to its
  own offset end); every added corner arc has radius ``r`` about its
  programmed corner.

Each test counts what the drawn contours exercised (:mod:`exercised`): the
share checked (a path checked, or the refusal of an arc the tool does not
fit) must be at least 80 %, and each hard case must occur in a stated share
of the contours: a move shorter than ``2 r``, an arc the tool does not fit,
an inside corner without intersection.
"""
from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from ccopt.compensate import compensate
from ccopt.errors import CompensationError
from ccopt.program.model import Motion
from ccopt.tolerances import POINT_EPS, TURN_EPS
from exercised import assert_share
from random_contours import contour_program, hard_contours

#: The product's own tolerances (ccopt.tolerances): points closer than
#: POINT_EPS are one point (relative beyond 1 unit from the origin), and a
#: turn with |t_in x t_out| <= TURN_EPS is a reversal, whose 180-degree arc
#: then ends up to r * TURN_EPS from the next move's start.
def same_point_tol(x) -> float:
    return POINT_EPS * max(1.0, float(np.max(np.abs(x))))


#: Margin of the independent classifications: a corner whose offsets miss (or
#: meet) by less, or an arc within this of the tool's radius, is not counted
#: as either (its outcome is left unchecked).
MARGIN = 1e-7
SHARE = 0.8
#: Least share of the drawn contours with each hard case (measured over runs
#: of 400: short move 78-89 %, arc the tool does not fit 26-40 %, inside
#: corner without intersection 14-26 %; 5-25 % in runs of 60).
CASE_SHARES = {"short move (< 2 r)": 0.5, "arc the tool does not fit": 0.15,
               "inside corner without intersection": 0.05}
QUICK, SLOW = 150, 1000


def _left(v):
    return np.array([-v[1], v[0]])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


class Element:
    """A programmed line or arc, with what its offset is on side ``k`` at ``r``."""

    def __init__(self, blk, k: int, r: float):
        self.blk, self.k, self.r = blk, k, r
        self.p, self.q = np.array(blk.start[:2]), np.array(blk.end[:2])
        self.arc = blk.motion.is_arc
        if self.arc:
            self.c = np.array(blk.center[:2])
            self.R = float(np.hypot(*(self.p - self.c)))
            self.sgn = 1.0 if blk.motion is Motion.ARC_CCW else -1.0
            self.rad = self.R - k * r * self.sgn          # the offset circle's radius
        else:
            self.d = (self.q - self.p) / np.hypot(*(self.q - self.p))

    @property
    def length(self) -> float:
        if not self.arc:
            return float(np.hypot(*(self.q - self.p)))
        return abs(self.blk_sweep()) * self.R

    def blk_sweep(self) -> float:
        a0 = math.atan2(*(self.p - self.c)[::-1])
        a1 = math.atan2(*(self.q - self.c)[::-1])
        return (a1 - a0) % (2 * math.pi) if self.sgn > 0 else -((a0 - a1) % (2 * math.pi))

    def tangent(self, x) -> np.ndarray:
        if not self.arc:
            return self.d
        return self.sgn * _left(x - self.c) / np.hypot(*(x - self.c))

    def offset_point(self, x) -> np.ndarray:
        return x + self.k * self.r * _left(self.tangent(x))

    def off_offset(self, x) -> float:
        """How far ``x`` is from this element's offset line or circle."""
        if not self.arc:
            return abs(_cross(self.d, x - self.p) - self.k * self.r)
        return abs(float(np.hypot(*(x - self.c))) - self.rad)

    @property
    def concave(self) -> bool:
        """The tool inside the arc (its centre on the tool's side)."""
        return self.arc and self.k * self.sgn > 0


def offsets_miss(a: Element, b: Element) -> float:
    """By how much the offset carriers of ``a`` and ``b`` (infinite line, full
    circle) miss each other: > 0 they do not meet, < 0 they cross."""
    if not a.arc and not b.arc:
        return -1.0 if abs(_cross(a.d, b.d)) > 1e-12 else 1.0
    if a.arc and b.arc:
        d = float(np.hypot(*(a.c - b.c)))
        return max(d - (a.rad + b.rad), abs(a.rad - b.rad) - d)
    line, circ = (a, b) if b.arc else (b, a)
    n = _left(line.d)
    off = line.p + line.k * line.r * n
    return abs(float(np.dot(circ.c - off, n))) - circ.rad


def check_contour(pts, bulges, r, k, seen: Counter) -> str:
    """Compensate one contour and check it; what it exercised (its hard cases
    are counted into ``seen``)."""
    prog = contour_program(pts, bulges, r, k)
    blocks = prog.blocks
    elems = [Element(b, k, r) for b in blocks]
    contour = range(1, len(blocks) - 1)                 # lead-in and lead-out left out
    unfit = {elems[i].blk.source.line for i in contour
             if elems[i].concave and elems[i].R <= r - MARGIN}
    borderline = {elems[i].blk.source.line for i in contour
                  if elems[i].concave and abs(elems[i].R - r) < MARGIN}
    if any(elems[i].length < 2 * r for i in contour):
        seen["short move (< 2 r)"] += 1
    if unfit:
        seen["arc the tool does not fit"] += 1
    try:
        path = compensate(prog, "pmac")
    except CompensationError as exc:
        assert unfit or borderline, f"refused a contour the tool fits: {exc}"
        if not unfit:
            return "borderline arc (not checked)"
        assert exc.line in unfit | borderline, (exc.line, unfit, borderline, str(exc))
        return "refused an arc the tool does not fit"
    assert not unfit, f"compensated although the tool does not fit arcs {sorted(unfit)}"
    segs = list(path.segments)
    for a, b in zip(segs, segs[1:]):
        gap = math.dist(a.end, b.start)
        assert gap <= same_point_tol(a.end) + r * TURN_EPS, \
            (a.block.source.line, b.block.source.line, gap)
    # the corner before each contour element: does it fall back (no intersection)?
    fallback, unsure = set(), set()
    for i in range(2, len(blocks) - 1):
        a, b = elems[i - 1], elems[i]
        ta, tb = a.tangent(a.q), b.tangent(b.p)
        turn = k * _cross(ta, tb)
        if abs(turn) < 1e-6 or float(np.dot(ta, tb)) < -1 + 1e-6:
            unsure.add(i)                               # tangent or reversal: not classified
            continue
        if turn > 0:                                    # inside corner
            miss = offsets_miss(a, b)
            if miss > MARGIN:
                fallback.add(i)
            elif miss > -MARGIN:
                unsure.add(i)
    if fallback:
        seen["inside corner without intersection"] += 1
    index = {id(b): i for i, b in enumerate(blocks)}
    for s in segs:
        i = index[id(s.block)]
        e = elems[i]
        if s.role.value == "corner":
            assert abs(s.geom.radius - r) <= same_point_tol(r)
            assert math.dist(s.geom.center, e.q) <= same_point_tol(e.q)
            continue
        if s.role.value != "compensated" or s.length == 0 or i not in contour:
            continue
        assert e.off_offset(np.array(s.end)) <= same_point_tol(s.end), \
            (e.blk.source.line, "end off the offset", s.end)
        if i in fallback:
            A = elems[i - 1].offset_point(elems[i - 1].q)
            assert math.dist(s.start, A) <= same_point_tol(A), \
                (e.blk.source.line, "not from A", s.start, A)
        elif i not in unsure and i != 1:         # (block 1 starts at the lead-in corner)
            assert e.off_offset(np.array(s.start)) <= same_point_tol(s.start), \
                (e.blk.source.line, "start off the offset", s.start)
    return "path checked"


def run(examples: int):
    tally, seen = Counter(), Counter()

    @settings(max_examples=examples, deadline=None, suppress_health_check=list(HealthCheck))
    @given(hard_contours())
    def one(contour):
        tally[check_contour(*contour, seen)] += 1

    one()
    assert_share("pmac hard contours", tally,
                 {"path checked", "refused an arc the tool does not fit"}, SHARE, examples)
    total = sum(tally.values())
    line = f"pmac hard cases in {total} contours: " + ", ".join(
        f"{case}: {seen[case]} ({seen[case] / total:.0%})" for case in CASE_SHARES)
    print(line)
    for case, share in CASE_SHARES.items():
        assert seen[case] >= share * total, (case, line)


def test_hard_contours():
    run(QUICK)


@pytest.mark.slow
def test_many_hard_contours():
    run(SLOW)


def test_array_route_equals_reference_on_hard_contours():
    """The vectorised, column route gives the reference route's path on the
    hard contours too, or the same refusal at the same block."""
    from ccopt.compensate.pmac import PmacStyle, assemble
    from ccopt.compensate.scan import scan_program
    from test_column_path import same_segments
    tally = Counter()

    def route(prog, fast: bool):
        try:
            return assemble(PmacStyle(), scan_program(prog, bulk=fast), prog,
                            vectorised=fast, columns=fast)
        except CompensationError as exc:
            return exc

    @settings(max_examples=QUICK, deadline=None, suppress_health_check=list(HealthCheck))
    @given(hard_contours())
    def one(contour):
        prog = contour_program(*contour)
        fast, ref = route(prog, True), route(prog, False)
        if isinstance(ref, CompensationError) or isinstance(fast, CompensationError):
            assert isinstance(fast, CompensationError) and isinstance(ref, CompensationError), \
                (fast, ref)
            assert (fast.line, str(fast)) == (ref.line, str(ref))
            tally["same refusal"] += 1
            return
        same_segments(fast.segments, ref.segments)
        tally["same path"] += 1

    one()
    assert_share("pmac hard contours, column route", tally, {"same path", "same refusal"},
                 1.0, QUICK)


#: Spacing (program units) of the tool path's samples in the independent gouge
#: check: the clearance to a line or an arc changes by at most the distance
#: moved, so the sampled smallest clearance is at most SAMPLE / 2 above the true.
SAMPLE = 2e-3


def sampled_depth(path, prog, r: float) -> float:
    """``r`` minus the smallest distance from points of the compensated moves and
    corner arcs (every SAMPLE along them) to the programmed contour's elements
    (lead-in and lead-out left out), by the closed-form point distances."""
    from ccopt.geometry.distance import point_arc, point_segment
    pts = np.vstack([s.geom.point(np.linspace(0.0, s.length, max(2, math.ceil(s.length / SAMPLE) + 1)))[:, :2]
                     for s in path.segments
                     if s.length > 0 and s.role.value in ("compensated", "corner")])
    best = np.full(len(pts), np.inf)
    m = len(pts)
    for b in prog.blocks[1:-1]:
        if b.motion.is_arc:
            e = Element(b, 0, 0.0)
            d = point_arc(pts, np.tile(e.c, (m, 1)), np.full(m, e.R),
                          np.full(m, math.atan2(*(e.p - e.c)[::-1])), np.full(m, e.blk_sweep()))[0]
        else:
            d = point_segment(pts, np.tile(b.start[:2], (m, 1)), np.tile(b.end[:2], (m, 1)))[0]
        best = np.minimum(best, d)
    return r - float(best.min())


def certificate_agrees(contour, tally: Counter) -> None:
    """On a hard contour that compensates, the certificate's deepest gouge and a
    dense sampling of the tool path against the contour agree: a sampled gouge
    is certified at least as deep (the samples are points of the path, so their
    depth is a lower bound), and a certified one is found by the samples to
    within half their spacing."""
    from ccopt.verify import verify
    prog = contour_program(*contour)
    try:
        path = compensate(prog, "pmac")
    except CompensationError:
        tally["refused"] += 1
        return
    cert = verify(path, prog)
    # the gouge check's figure: smallest distance - r, exact (a gouge within the
    # certificate's tolerance is a warning, not a violation, with the same figure)
    certified = max(0.0, -cert.check("gouge").figure)
    sampled = sampled_depth(path, prog, contour[2])
    if sampled > cert.eps:
        assert certified >= sampled - 1e-9, (certified, sampled, contour)
        tally["gouge: certified and sampled"] += 1
    else:
        tally["clean: certified and sampled"] += 1
    if certified > cert.eps:
        assert sampled >= certified - SAMPLE / 2 - 1e-9, (certified, sampled, contour)


def _agreement(examples: int) -> None:
    tally = Counter()

    # short arcs of at least 1.05 r: the tool fits every one, so every contour
    # compensates (refusals are the first test's property), gouging or not
    @settings(max_examples=examples, deadline=None, suppress_health_check=list(HealthCheck))
    @given(hard_contours(smallest_arc=1.05))
    def one(contour):
        certificate_agrees(contour, tally)

    one()
    assert_share("pmac hard contours, certificate against samples", tally,
                 {"gouge: certified and sampled", "clean: certified and sampled"}, SHARE, examples)
    assert tally["gouge: certified and sampled"] and tally["clean: certified and sampled"], tally


def test_certificate_agrees_with_samples_on_hard_contours():
    _agreement(30)


@pytest.mark.slow
def test_certificate_agrees_with_samples_on_many_hard_contours():
    _agreement(300)
