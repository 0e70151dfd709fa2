"""The smoother's joins, blend frames, closed-form blends, exact checks and assembly.

A blend at a join is the degree-7 Bezier curve of :class:`BlendFrame`: G2 end
conditions at ``P0`` (``l_in`` before the join on the incoming segment) and
``P7`` (``l_out`` after it), and two free middle control points. Its
closed form (:func:`initial`) puts ``P0..P3`` equally spaced along the incoming
tangent (legs ``a0 = |V - P0| / 3.5``, ``P2`` lifted by the end curvature as
:func:`ccopt.geometry.bezier.g2_start` says) and ``P4..P7`` likewise along the
outgoing one. At a line-line corner with legs ``l`` its control points are
``V - d_k t0`` (k = 0..3) and ``V + d_k t1`` (mirrored), ``d = l (1, 5/7, 3/7,
1/7)``; at ``t = 1/2`` the Bernstein weights are ``C(7, k)/128``, so ``r(1/2) - V
= (sum_k C(7,k) d_k / 128)(t1 - t0) = (5 l / 32)(t1 - t0)``: it cuts the corner
by ``(5/16) l sin(theta/2)``, and the size that uses the band is known in
closed form (:func:`size_estimate`) and only checked (:func:`exact_ok`).

At a convex corner absorbed from a short corner arc
(:mod:`ccopt_formulations.smoother_chain`) the blend must not cut: it must
keep outside both lines alongside their chords. The *outward* closed form lifts
``P3`` and ``P4`` by ``h = (4/7) l sin(theta/2)`` along the outward bisector
``m = (t0 - t1)/|t0 - t1|``, which puts ``r(1/2)`` on ``V`` (``2 (35/128) h =
(20 l / 128) 2 sin(theta/2)``). Its signed distance outside the incoming line is
then ``(l sin(theta) / 7) sum_k c_k b_k(t)`` with ``c = (0, 0, 0, 2, 1, -3, -5,
-7)``, i.e. ``7 u^3 (10 + 5u - 9u^2 - 5u^3 - u^4) (1-t)^7 (l sin(theta) / 7)``
with ``u = t/(1-t)``: positive for ``t < 1/2``, zero at ``V``; by symmetry the
second half keeps outside the outgoing line. The corner arc's circle is tangent
to both lines and inside both, so the blend keeps out of it too.

Exact checks of a blend (:func:`exact_ok`), at :data:`CHECK_SAMPLES` points:

- clearance to every contour element near the join (exact distances);
- band: every sample within ``delta`` of PMAC's path (exact distances to its
  lines and arcs near the join; the smoother may have moved chords, see
  :mod:`ccopt_formulations.smoother_chain`, so the reference here is PMAC's);
- cover: every reference point the blend cuts off (the join point, or an
  absorbed corner arc) within ``delta`` of the samples (a sampled distance is
  never below the true one);
- curvature: at most :data:`CURVATURE_FACTOR` times ``|turn| / S + max(|k0|,
  |k1|)`` (1/program units), with ``turn`` the angle between the end tangents,
  ``S = l_in + l_out`` and ``k0``, ``k1`` the end curvatures. At a symmetric
  line-line corner the closed form peaks at 1.88 ``|turn| / S`` (3.2 at a
  right angle's 1.5 rad), the outward one at 3.75 (6.4): the bound lets a blend
  curve as a corner of its size needs and refuses hooks (a blend that turns
  back and forth far more than its corner does, as the convex model's blends
  into a convex arc of the tool path did: 39 /mm on ``leadin-inside-line``).
  A one-sided blend (it ends at the join point itself, where the other side
  leaves no room: an open end of the contour, or a reference that is itself
  inside the clearance there, as ``profile``'s spiral leads are) does all its
  turning near that end: it may curve :data:`ONE_SIDED_FACTOR` times as much.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ccopt.compare.contract import deepest
from ccopt.compare.figures import joins as path_joins
from ccopt.compare.leads import split_segment
from ccopt.geometry import Arc, BezierCurve, Line, point_arc, point_segment
from ccopt.geometry.bezier import DIVISION_FLOOR, g2_end, g2_start
from ccopt.geometry.curve import bernstein, derivative_matrix
from ccopt.toolpath import PathSegment, Role, ToolPath
from ccopt_formulations.clearance import (Element, checked_distance, contour_elements,
                                          polyline_distance)

DEGREE = 7
#: Share of a segment a blend may take when another blend uses its other end, and
#: when none does; a chord between two line-line corners nearly all (the verifier's
#: contact rule wants a piece of every chord's tool segment left on PMAC's path).
SHARED = 0.45
ALONE = 0.9
CHORD_SHARE = 0.48
#: Dense samples for the exact acceptance checks of one blend.
CHECK_SAMPLES = 257
#: Curvature bound factor (module docstring), and its multiple for a one-sided
#: blend (module docstring).
CURVATURE_FACTOR = 8.0
ONE_SIDED_FACTOR = 5.0
#: Lifts (in units of the blend size) of the closed form's middle control points
#: tried at a curvature jump, in turn (:func:`initial`).
LIFTS = (0.0, 0.01, 0.02, 0.04, 0.08)
#: Blend size search of the closed form: from the closed-form size, shrink by
#: SHRINK at most SHRINKS times until the checks pass; where the size was a
#: guess (an arc at the join), grow by GROW at most GROWS times while they pass.
SHRINKS = 12
SHRINK = 0.7
GROWS = 4
GROW = 1.4
#: Smallest turn (rad) and curvature jump (1/program units) the first blend size
#: divides by: a join barely broken gets the largest size its segments allow.
MIN_TURN = 1e-3
MIN_JUMP = 1e-9
#: A segment trimmed to at most this length (program units) by the blends at both
#: its ends is gone: the two blends meet.
TRIMMED_AWAY = 1e-12
FEED_ROLES = (Role.LEAD_IN, Role.COMPENSATED, Role.CORNER, Role.LEAD_OUT)


# --------------------------------------------------------------------------- joins


@dataclass
class Join:
    """A non-G2 join at segment boundary ``index`` (between ``index - 1`` and ``index``)."""

    index: int
    kind: str              # "tangent-break" | "curvature-jump"
    angle: float
    jump: float
    lim_in: float = 0.0
    lim_out: float = 0.0
    l_in: float = 0.0
    l_out: float = 0.0
    curve: BezierCurve | None = None
    status: str = "pending"
    info: dict = field(default_factory=dict)


def _line_line(segs, i) -> bool:
    return isinstance(segs[i - 1].geom, Line) and isinstance(segs[i].geom, Line)


def find_joins(path: ToolPath) -> list[Join]:
    """Every join of feed segments that is G0 or G1 (``gap`` joins are left alone)."""
    out = []
    for i, cls, _gap, ang, jump in path_joins(path):
        if cls in ("G0", "G1"):
            out.append(Join(i, "tangent-break" if cls == "G0" else "curvature-jump", ang, jump))
    idx = {j.index for j in out}
    segs = path.segments
    for j in out:
        L_in, L_out = segs[j.index - 1].length, segs[j.index].length
        j.lim_in = _share(segs, idx, j.index - 1) * L_in
        j.lim_out = _share(segs, idx, j.index) * L_out
    return out


def _share(segs, idx, k) -> float:
    if k in idx and (k + 1) in idx:
        chord = _line_line(segs, k) and k + 1 < len(segs) and _line_line(segs, k + 1)
        return CHORD_SHARE if chord else SHARED
    return ALONE


def _cut_size(angle: float, depth: float) -> float:
    """Legs whose line-line closed form cuts the corner of turn ``angle`` by
    ``depth``: ``(5/16) l sin(theta/2) = depth``."""
    return depth / (5.0 / 16.0 * math.sin(max(angle, MIN_TURN) / 2.0))


def _jump_size(jump: float, depth: float) -> float:
    """Legs whose transition into a curvature ``jump`` moves by ``depth``:
    ``l^2 jump / 3 = depth``."""
    return math.sqrt(3.0 * depth / jump)


def size_estimate(jn: Join, delta: float) -> float:
    """A first blend size (legs, program units): at a line-line corner the closed
    form's cut ``(5/16) l sin(theta/2)`` equals ``delta``; a transition into
    curvature ``kappa`` moves by about ``l^2 kappa / 3``."""
    if jn.kind == "tangent-break":
        return _cut_size(jn.angle, delta)
    return _jump_size(max(jn.jump, MIN_JUMP), delta)


def kink_size(jn: Join, depth: float) -> float:
    """A first blend size (legs, program units) at a tiny kink whose blend may
    move ``depth`` towards the part: the smaller of the size whose cut is
    ``depth`` and, where the curvature jumps too (a line meeting a fillet),
    the one whose curvature change moves it ``depth``."""
    cut = _cut_size(jn.angle, depth)
    return min(cut, _jump_size(jn.jump, depth)) if jn.jump > 0.0 else cut


# --------------------------------------------------------------------------- frames


def _end_data(geom, s):
    p = np.asarray(geom.point(float(s)), float)
    t = np.asarray(geom.tangent(float(s)), float)
    k = float(geom.curvature(float(s)))
    return p, t / np.linalg.norm(t), k


@dataclass
class BlendFrame:
    """One blend's fixed data in world coordinates, and the scaling used by the model."""

    P0: np.ndarray
    t0: np.ndarray
    k0: float
    P7: np.ndarray
    t1: np.ndarray
    k1: float
    V: np.ndarray           # the corner of the path being blended (the join point)
    S: float                # scale (l_in + l_out)
    ref_pts: np.ndarray     # dense points of the path being blended near the join (world)
    ref_geoms: list = field(default_factory=list)   # PMAC's primitives near the join
    cover: np.ndarray | None = None                 # PMAC's points the blend cuts off
    outward: bool = False                           # an absorbed convex corner
    one_sided: bool = False                         # ends at the join point

    def controls(self, x) -> np.ndarray:
        """World control points of ``x = [a0, e0, a1, e1, P3x, P3y, P4x, P4y]`` (lengths
        in units of ``S``, points relative to ``V`` in units of ``S``)."""
        x = np.asarray(x, float)
        S = self.S
        start = g2_start(self.P0, self.t0, self.k0, x[0] * S, x[1] * S, DEGREE)
        end = g2_end(self.P7, self.t1, self.k1, x[2] * S, x[3] * S, DEGREE)
        mid = self.V + S * x[4:8].reshape(2, 2)
        return np.vstack([start, mid, end])


def frame(seg_in: PathSegment, seg_out: PathSegment, l_in: float, l_out: float,
          context=None, dense: bool = False) -> BlendFrame:
    """The frame of a blend of legs ``l_in``, ``l_out``; ``context`` = ``(ref_geoms,
    cover, outward)`` of PMAC's path near the join (default: the two segments, the
    join point, not outward); ``dense``: also sample the path near the join (the
    convex model's band)."""
    L_in = seg_in.length
    P0, t0, k0 = _end_data(seg_in.geom, L_in - l_in)
    P7, t1, k1 = _end_data(seg_out.geom, l_out)
    V = np.asarray(seg_out.start, float)
    S = l_in + l_out
    pts = np.zeros((0, 2))
    if dense:
        h = S / 400.0
        a = seg_in.geom.point(np.linspace(max(0.0, L_in - 2.0 * l_in), L_in,
                                          max(2, int(2 * l_in / h) + 1)))
        b = seg_out.geom.point(np.linspace(0.0, min(seg_out.length, 2.0 * l_out),
                                           max(2, int(2 * l_out / h) + 1)))
        pts = np.vstack([a, b])
    geoms, cover, outward = context if context is not None \
        else ([seg_in.geom, seg_out.geom], V[None, :], False)
    return BlendFrame(P0, t0, k0, P7, t1, k1, V, S, pts, list(geoms), np.asarray(cover, float),
                      bool(outward), l_in == 0.0 or l_out == 0.0)


def initial(fr: BlendFrame, lift: float = 0.0) -> np.ndarray:
    """The closed-form blend's ``x`` (module docstring); ``lift`` (in units of ``S``)
    moves ``P3`` and ``P4`` towards the centre of curvature of the more curved end
    (the inside of an arc the blend runs into: a blend into a concave arc of the
    tool path must turn more sharply than the arc to keep inside its circle)."""
    a0 = max(np.linalg.norm(fr.V - fr.P0) / (DEGREE / 2.0) / fr.S, 0.05)
    a1 = max(np.linalg.norm(fr.P7 - fr.V) / (DEGREE / 2.0) / fr.S, 0.05)
    P3 = (fr.P0 + 3.0 * a0 * fr.S * fr.t0 - fr.V) / fr.S
    P4 = (fr.P7 - 3.0 * a1 * fr.S * fr.t1 - fr.V) / fr.S
    if fr.outward:
        dt = fr.t0 - fr.t1
        gap = float(np.linalg.norm(dt))
        if gap > 0.0:
            # h = (4/7) l sin(theta/2) = (2/7) l |t0 - t1| along m = (t0 - t1)/|t0 - t1|,
            # with l = 3.5 a (scaled)
            up = (2.0 / 7.0) * (DEGREE / 2.0) * min(a0, a1) * dt
            P3, P4 = P3 + up, P4 + up
    if lift:
        k = fr.k1 if abs(fr.k1) >= abs(fr.k0) else fr.k0
        tm = (fr.t0 + fr.t1) / max(float(np.linalg.norm(fr.t0 + fr.t1)), DIVISION_FLOOR)
        inward = math.copysign(lift, k) * np.array([-tm[1], tm[0]])
        P3, P4 = P3 + inward, P4 + inward
    return np.r_[a0, 0.0, a1, 0.0, P3, P4]


# --------------------------------------------------------------------------- checks


_T = np.linspace(0.0, 1.0, CHECK_SAMPLES)
_B = bernstein(_T, DEGREE)
_B1 = bernstein(_T, DEGREE - 1) @ derivative_matrix(DEGREE, 1)
_B2 = bernstein(_T, DEGREE - 2) @ derivative_matrix(DEGREE, 2)


def ref_distance(geom, pts: np.ndarray) -> np.ndarray:
    """Exact distance from points to a line or arc of PMAC's path (other curves:
    a fine polyline, whose distance is within its chord error of the true one)."""
    if isinstance(geom, Line):
        return point_segment(pts, geom.p0, geom.p1)[0]
    if isinstance(geom, Arc):
        return point_arc(pts, geom.center, geom.radius, geom.theta0, geom.sweep)[0]
    q = np.asarray(geom.point(np.linspace(0.0, geom.length, 513)), float).reshape(-1, 2)
    return polyline_distance(q, pts)


def curvature_bound(fr: BlendFrame) -> float:
    """The blend's curvature bound (module docstring), 1/program units."""
    turn = math.atan2(abs(fr.t0[0] * fr.t1[1] - fr.t0[1] * fr.t1[0]), float(fr.t0 @ fr.t1))
    factor = CURVATURE_FACTOR * (ONE_SIDED_FACTOR if fr.one_sided else 1.0)
    return factor * (turn / fr.S + max(abs(fr.k0), abs(fr.k1)))


def max_curvature(P: np.ndarray) -> float:
    """Largest |curvature| of the Bezier curve ``P`` at the check samples."""
    d1, d2 = _B1 @ P, _B2 @ P
    sp = np.hypot(d1[:, 0], d1[:, 1])
    return float(np.max(np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
                        / np.maximum(sp ** 3, DIVISION_FLOOR)))


def exact_ok(P: np.ndarray, elements, fr: BlendFrame, delta: float, tol: float):
    """The exact checks of the blend with control points ``P`` (module docstring):
    ``(ok, reason)``."""
    pts = _B @ P
    inner = pts[1:-1]
    for el in elements:
        if np.min(checked_distance(el, inner)) < el.clearance - tol:
            return False, "clearance"
    d = np.full(len(pts), np.inf)
    for g in fr.ref_geoms:
        d = np.minimum(d, ref_distance(g, pts))
    if np.max(d) > delta:
        return False, "band"
    cov = fr.cover
    dc = np.hypot(pts[None, :, 0] - cov[:, None, 0], pts[None, :, 1] - cov[:, None, 1])
    if np.max(np.min(dc, axis=1)) > delta:
        return False, "corner"
    if max_curvature(P) > curvature_bound(fr):
        return False, "curvature"
    return True, "ok"


# --------------------------------------------------------------------------- elements


class ElementIndex:
    """The contour's elements with their bounding boxes, for the elements near a join."""

    def __init__(self, contour):
        self.elements = contour_elements(contour)
        box = []
        for el in self.elements:
            g = el.geom
            if isinstance(g, Line):
                xs, ys = (g.p0[0], g.p1[0]), (g.p0[1], g.p1[1])
                box.append((min(xs), min(ys), max(xs), max(ys)))
            elif isinstance(g, Arc):
                (cx, cy), R = g.center, g.radius
                box.append((cx - R, cy - R, cx + R, cy + R))
            else:
                q = np.asarray(g.point(np.linspace(0.0, g.length, 65)), float).reshape(-1, 2)
                lo, hi = q.min(axis=0), q.max(axis=0)
                box.append((lo[0], lo[1], hi[0], hi[1]))
        self.box = np.asarray(box, float).reshape(-1, 4)
        self.clear = np.array([el.clearance for el in self.elements], float)

    def near(self, V, reach: float) -> list[Element]:
        """Every element whose box comes within ``clearance + reach`` of ``V``."""
        g = self.clear + reach
        x, y = float(V[0]), float(V[1])
        b = self.box
        hit = (b[:, 0] - g <= x) & (x <= b[:, 2] + g) & (b[:, 1] - g <= y) & (y <= b[:, 3] + g)
        return [self.elements[k] for k in np.flatnonzero(hit)]


def contour_inside(V, t0, t1, elements) -> bool:
    """Whether the contour point nearest the corner ``V`` lies on the inside of the
    turn from ``t0`` to ``t1`` (a convex corner of the tool path: PMAC's shallow
    outside corner, its lines extended to meet; the blend must not cut it)."""
    best, foot = math.inf, None
    P = np.asarray(V, float)[None, :]
    for el in elements:
        g = el.geom
        if isinstance(g, Line):
            d, _, q = point_segment(P, g.p0, g.p1)
        elif isinstance(g, Arc):
            d, _, q = point_arc(P, g.center, g.radius, g.theta0, g.sweep)
        else:
            continue
        if float(d[0]) < best:
            best, foot = float(d[0]), q[0]
    return foot is not None and float((foot - P[0]) @ (np.asarray(t1) - np.asarray(t0))) > 0.0


# --------------------------------------------------------------------------- closed form


def closed_blend(fr: BlendFrame, elements, delta: float, tol: float, lifts=(0.0,)):
    """The control points of the first closed-form blend of ``fr`` (lifted by each of
    ``lifts`` in turn, :func:`initial`) that passes the exact checks and is regular
    (its speed at the check samples positive), else ``None`` (the
    :class:`~ccopt.geometry.BezierCurve` is built once, for the size kept)."""
    for lift in lifts:
        P = fr.controls(initial(fr, lift))
        if np.min(np.hypot(*(_B1 @ P).T)) > 0.0 and exact_ok(P, elements, fr, delta, tol)[0]:
            return P
    return None


def largest_closed(attempt, start: float, lmax: float, exact_size: bool):
    """The largest size (legs) the closed form passes at: from ``start``, shrink
    by :data:`SHRINK` until ``attempt(l)`` succeeds; when ``start`` was a guess
    (``exact_size`` false) and below ``lmax``, grow by :data:`GROW` while it
    succeeds. What ``attempt`` gave at the size kept, or ``None``."""
    l, best = start, None
    for _ in range(SHRINKS):
        best = attempt(l)
        if best is not None:
            break
        l *= SHRINK
    if best is None:
        return None
    if not exact_size and l == start:
        for _ in range(GROWS):
            if l >= lmax:
                break
            l = min(lmax, l * GROW)
            res = attempt(l)
            if res is None:
                break
            best = res
    return best


def closed_search(jn: Join, closed, shares, start: float, exact: bool, tol: float) -> bool:
    """The largest closed-form blend ``closed(l, share, tol)`` passes, for the
    first of ``shares`` that has one (:func:`largest_closed` from ``start``):
    set on ``jn``, True; else False."""
    lmax = max(jn.lim_in, jn.lim_out)
    for share in shares:
        res = largest_closed(lambda l, share=share: closed(l, share, tol), min(start, lmax),
                             lmax, exact)
        if res is None:
            continue
        try:
            jn.curve = BezierCurve(res[0])
        except ValueError:  # not regular to BezierCurve's finer test: no closed form
            return False
        jn.l_in, jn.l_out = res[1], res[2]
        jn.status, jn.info["method"] = "blended", "closed form"
        jn.info["share"] = list(share)
        return True
    return False


#: Factors one leg of a symmetric closed-form blend at a tangent break is
#: grown by, the other kept, largest first (:func:`grow_one_leg`).
LEG_GROWTH = (1.5, 1.25)


def grow_one_leg(jn: Join, at_legs, tol: float) -> None:
    """Grow one leg of ``jn``'s symmetric closed-form blend, the other kept at
    its size, by the largest factor of :data:`LEG_GROWTH` at which
    ``at_legs(l_in, l_out, tol)`` passes (``(control points, l_in, l_out)``
    or None), on the side that gives the longer blend; set on ``jn`` when
    one does. The symmetric search stops where the tighter side of the band
    stops both legs (at a lead's join, the lead's side or the contour's):
    the other leg may still have room, and a longer blend turns through the
    same angle with less curvature."""
    if jn.info.get("share") != [1.0, 1.0] or jn.curve is None:
        return
    best = None
    for side in (0, 1):
        lim = (jn.lim_in, jn.lim_out)[side]
        for factor in LEG_GROWTH:
            legs = [jn.l_in, jn.l_out]
            legs[side] = min(legs[side] * factor, lim)
            if not legs[side] > (jn.l_in, jn.l_out)[side]:
                break                   # no room on this side
            res = at_legs(legs[0], legs[1], tol)
            if res is not None:
                if best is None or sum(legs) > best[1] + best[2]:
                    best = (res[0], legs[0], legs[1], side, factor)
                break
    if best is None:
        return
    try:
        curve = BezierCurve(best[0])
    except ValueError:      # not regular to BezierCurve's finer test: the symmetric one stays
        return
    jn.curve, jn.l_in, jn.l_out = curve, best[1], best[2]
    jn.info["share"] = [best[4], 1.0] if best[3] == 0 else [1.0, best[4]]


# --------------------------------------------------------------------------- the path


def assemble(path: ToolPath, joins: list[Join], style: str = "smooth",
             origin: list | None = None) -> ToolPath:
    """``path`` with every blended join's curve put in; ``meta["joins"]`` lists
    every feed join of the result (the smoother answers for all of them).
    ``origin``, when given, receives for each segment of the result the index of
    the segment of ``path`` it came from (a blend: the segment after its join)."""
    origin = [] if origin is None else origin
    segs = path.segments
    by_index = {j.index: j for j in joins if j.status == "blended"}
    out: list[PathSegment] = []
    new_index = {}
    for i, seg in enumerate(segs):
        j_start = by_index.get(i)
        j_end = by_index.get(i + 1)
        if j_start is not None:
            jb = j_start
            src_in = segs[i - 1]
            feed = min((f for f in (src_in.feed, seg.feed) if f is not None), default=None)
            w = src_in.w1
            out.append(PathSegment(jb.curve, Role.CORNER, src_in.block, w, w, feed))
            origin.append(i)
        s0 = j_start.l_out if j_start is not None else 0.0
        s1 = seg.length - (j_end.l_in if j_end is not None else 0.0)
        g = seg.geom
        if s0 > 0.0 or s1 < seg.length:
            if s1 - s0 <= TRIMMED_AWAY:
                g = None
            else:
                if s1 < seg.length:
                    g = g.split(s1)[0]
                if s0 > 0.0:
                    g = g.split(s0)[1]
        if g is not None:
            L = seg.length
            w0 = seg.w0 + (seg.w1 - seg.w0) * (s0 / L if L else 0.0)
            w1 = seg.w0 + (seg.w1 - seg.w0) * (s1 / L if L else 1.0)
            new_index[i] = len(out)
            out.append(PathSegment(g, seg.role, seg.block, w0, w1, seg.feed))
            origin.append(i)
    dwells = []
    for d, sec, blk in path.dwells:
        k = min((new_index[i] for i in new_index if i >= d), default=len(out))
        dwells.append((k, sec, blk))
    res = ToolPath(tuple(out), plane=path.plane, style=style, radius=path.radius,
                   dwells=tuple(dwells), units=path.units, meta=dict(path.meta))
    res.meta["joins"] = [j[0] for j in path_joins(res)]
    return res



def lasting_gouge(problem, path: ToolPath, reference: ToolPath, origin: list,
                  joins: list[Join]) -> str | None:
    """Why no smoothing of ``path`` (``reference`` with chords chained, its
    segment ``k`` from reference segment ``origin[k]``) can be certified, or
    ``None``.

    A blend at the join before segment ``k`` takes at most ``lim_out`` of that
    segment's arc length from its start, and the one at its end at most that
    join's ``lim_in`` (:func:`find_joins`; the verifier's retries only halve
    them). What lies between is kept by every smoothed path, so a gouge the
    verifier finds there (each piece checked against the whole contour, as
    :meth:`~ccopt.compare.contract.BlendProblem.check` checks a blend's
    segments) is in every result, and its certificate cannot hold. Only asked
    when the reference itself is not certified (``problem.reference_verdict``);
    segments the chaining changed are left out (their pieces are not all kept)."""
    if problem.reference_verdict.ok:
        return None
    start = {jn.index: jn.lim_out for jn in joins}
    end = {jn.index - 1: jn.lim_in for jn in joins}
    pieces = []
    for k, seg in enumerate(path.segments):
        if seg.role not in FEED_ROLES or seg is not reference.segments[origin[k]]:
            continue
        a, b = start.get(k, 0.0), end.get(k, 0.0)
        if a + b >= seg.length:
            continue
        if b > 0.0:
            seg = split_segment(seg, seg.length - b)[0]
        if a > 0.0:
            seg = split_segment(seg, a)[1]
        pieces.append(seg)
    if not pieces:
        return None
    cert = problem.certify(replace(path, segments=tuple(pieces), dwells=()))
    kept = [v for v in cert.violations if v.kind == "gouge"]
    if not kept:
        return None
    return (f"the path it starts from gouges beyond the reach of every blend "
            f"({deepest(kept)}, {len(kept)} violation(s) on what every blend keeps): no "
            f"smoothing within the band can make it certified")
