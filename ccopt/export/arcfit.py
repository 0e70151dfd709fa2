"""Spirals (and other smooth curves) as chains of circular arcs, with a bound.

G-code has no spiral, so an exported spiral becomes arcs through three points
of the curve (start, middle, end of each piece), split until a **certified**
bound on the distance between the curve and its arc is within ``tol``.

The bound: with ``f(s) = |p(s) - c| - R`` (the radial distance of the curve
from the arc's circle, ``s`` arc length), ``|f''| <= kappa_max + 1/|p - c|``
because ``|p'| = 1`` and ``|p''| = kappa``. Between samples ``h`` apart a
function with ``|f''| <= M`` exceeds the larger sampled ``|f|`` by at most
``M*h^2/8``, so ``max|f| <= max_i |f(s_i)| + M*h^2/8``. For an Archimedean
spiral the curvature ``(rho^2 + 2b^2)/(rho^2 + b^2)^1.5`` decreases as ``rho``
grows, so ``kappa_max`` on a piece is its value at the smaller radius.

Bezier blend curves (:func:`fit_bezier`) use the same bound with a
certified ``kappa_max`` (:func:`ccopt.geometry.curve.curvature_bound`) and
more checks, all on control points, so the bound covers the whole piece and
not only its samples:

* the curve is cut at its inflections first (not at lobes of rounding size,
  such as at a G2 end onto a line: :func:`turning_cuts`), so every piece turns one way,
  and an arc is taken only if it turns that way too;
* the arc's centre ``c`` sees the piece turn monotonically: every Bernstein
  coefficient of ``(p(t) - c) x p'(t)`` has the arc's sign, so each point of
  the piece projects radially into the arc's sweep and each point of the arc
  has a point of the piece on its ray. The radial bound is then a two-sided
  (Hausdorff) distance between piece and arc;
* ``|p - c|`` is bounded below by the projection of the control points on
  the direction from ``c`` to the middle of the piece (convex hull), so the
  ``1/|p - c|`` term needs no sampled radius;
* samples are equal steps of ``t``, at most ``max|p'| / BEZIER_SAMPLES``
  apart in arc length (``max|p'|`` over the hodograph's control points).

A nearly straight piece becomes a line (G1 / LINEAR) on its chord when every
hodograph control point points along the chord (so points project
monotonically onto it) and the distance from the chord,
``min(max_i |(P_i - P_0) x u|, max_i |e_i x u| / 8)`` (``e_i`` the control
points of ``p''``; the distance vanishes at both ends and its second
derivative is bounded by ``|p'' x u|``), is within ``tol``.

Pieces join tangent-continuously within ``angle_tol``: the angle between
each arc's (or line's) end tangents and the curve's at the same points is
at most ``angle_tol``, so the kink between consecutive pieces is at most
twice that. The end points of every piece are points of the curve exactly
(de Casteljau splits), so the chain is continuous up to the rounding of
``c + R (cos, sin)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ccopt.errors import ProgramError
from ccopt.geometry import Arc, BezierCurve, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.program.model import MAX_PROGRAM_COORDINATE
from ccopt.geometry.curve import (
    bernstein,
    cross_bernstein,
    curvature_bound,
    de_casteljau_split,
    hodographs,
    inflections,
)
from ccopt.tolerances import EXPORT_FIT_ANGLE_TOL

#: Samples per piece for the bound (the second-order term shrinks as 1/n^2).
SAMPLES = 32

#: Samples per Bezier piece: its sample spacing is bounded by the largest
#: hodograph control point, not known exactly as on a spiral, so more samples
#: keep the second-order term below the fit error itself.
BEZIER_SAMPLES = 64

#: Default fit tolerance (program units): 0.001 mm, or its inch equivalent.
DEFAULT_TOL = {"mm": 1e-3, "inch": 1e-3 / 25.4}

#: Curvature of a piece whose Bernstein coefficients of ``p' x p''`` are at
#: least this fraction of their largest magnitude on the wrong side counts as
#: one-signed: such pieces end at an inflection, where the cut parameter is the
#: root to the last bit and the coefficient there is rounding. (It is also the
#: size, relative to the whole curve's, below which :func:`turning_cuts` does
#: not cut at a lobe.)
_SIGN_SLACK = 1e-9

#: Floor of a squared coordinate scale: keeps the collinearity test of
#: :func:`circle_through` and the sign test of a Bezier piece defined when all
#: values are zero (the smallest normal-ish float, far below any real length).
_SCALE_FLOOR = 1e-300

#: Three points whose doubled triangle area is at most this fraction of their
#: squared spread are collinear: no circle through them (a few ulps of the
#: products, so that the centre is not pure rounding).
_COLLINEAR_REL = 1e-14

#: A chord whose distance from the tangent line is at most this fraction of its
#: length lies along the tangent: no tangent circle through both ends.
_CHORD_ALONG_TANGENT_REL = 1e-12

#: Largest radius of a fitted arc, program units: a tenth of the reader's
#: coordinate bound, so that the written centre words (I, J, or a CIRCLE's
#: centre) read back, and the arc's ends ``c + R (cos, sin)`` stay within
#: ``R * eps`` ~ 2e-11 of the curve's. A piece that only a flatter arc fits is
#: halved (its halves become lines or arcs).
MAX_ARC_RADIUS = MAX_PROGRAM_COORDINATE / 10.0

#: Angular slack (radians) when testing that a sample's polar angle lies in an
#: arc's sweep: the ends themselves come back from atan2 a few ulps off.
_SWEEP_SLACK = 1e-12


class FitError(ProgramError, ValueError):
    """A spiral or blend curve the fit cannot follow within its piece limit
    (or tolerance), located at the program line of the segment: a
    :class:`ProgramError` (exit 2, ``file:line:col: message``) and still a
    ValueError for the callers that try a looser fit."""


def fit_located(seg, fit, *args):
    """``fit(*args)`` for the tool-path segment ``seg``; a ValueError it raises
    (the piece limit) comes out as a :class:`FitError` at ``seg``'s program line."""
    try:
        return fit(*args)
    except ValueError as exc:
        src = seg.block.source if seg.block is not None else None
        raise FitError(f"{exc} (line {src.line if src else '?'}'s move is long for the fit "
                       "tolerance: give a larger --tol)",
                       src.file if src else "<tool path>", src.line if src else None,
                       src.col if src else None) from None


def fit_tolerance(tol: float, digits: int) -> float:
    """The fit's share of the export tolerance ``tol`` when numbers are written
    with ``digits`` decimals: room is left for their rounding (centre and end
    points move by up to half a unit of the last digit each)."""
    return max(tol - 4 * 10.0 ** -digits, tol / 2)


@dataclass(frozen=True)
class FittedArc:
    """An arc replacing a piece of curve, and the certified deviation bound."""

    arc: Arc
    bound: float


def circle_through(p0, p1, p2):
    """Centre and radius of the circle through three points, or ``None`` when
    they are (nearly) collinear.

    Computed relative to ``p0``, so a small circle far from the origin keeps
    its accuracy (the absolute formula cancels squared coordinates): the
    three points lie on the result within a few ulps of the radius.
    """
    bx, by = p1[0] - p0[0], p1[1] - p0[1]
    cx, cy = p2[0] - p0[0], p2[1] - p0[1]
    d = 2.0 * (bx * cy - by * cx)
    scale = max(abs(bx), abs(by), abs(cx), abs(cy), _SCALE_FLOOR) ** 2
    if abs(d) <= _COLLINEAR_REL * scale:
        return None
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    ux = (cy * b2 - by * c2) / d
    uy = (bx * c2 - cx * b2) / d
    return (p0[0] + ux, p0[1] + uy), math.hypot(ux, uy)


def _kappa_max_spiral(sp: Spiral) -> float:
    rho = min(sp.rho0, sp.rho1)
    b = sp.b
    return (rho * rho + 2 * b * b) / (rho * rho + b * b) ** 1.5


def _fit_piece(sp: Spiral) -> FittedArc | None:
    L = sp.length
    p0, pm, p1 = sp.point(0.0), sp.point(L / 2), sp.point(L)
    circ = circle_through(tuple(p0), tuple(pm), tuple(p1))
    if circ is None:
        return None
    c, R = circ
    th0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
    th1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    thm = math.atan2(pm[1] - c[1], pm[0] - c[0])
    # The arc turns the way the spiral does; its sweep passes through the middle.
    ccw = sp.sweep > 0
    sweep = (th1 - th0) % TWO_PI if ccw else -((th0 - th1) % TWO_PI)
    mid_along = (thm - th0) % TWO_PI if ccw else (th0 - thm) % TWO_PI
    if mid_along > abs(sweep):
        return None
    s = np.linspace(0.0, L, SAMPLES + 1)
    pts = sp.point(s)
    dist = np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1])
    f = np.abs(dist - R)
    if f.max() > R / 4:
        return None
    # The radial distance is the distance to the arc (not just its circle)
    # when every point projects inside the arc's sweep.
    ang = np.arctan2(pts[:, 1] - c[1], pts[:, 0] - c[0])
    along = np.mod((ang - th0) * (1.0 if ccw else -1.0), TWO_PI)
    inside = (along <= abs(sweep) + _SWEEP_SLACK) | (along >= TWO_PI - _SWEEP_SLACK)
    if not inside.all():
        return None
    h = L / SAMPLES
    M = _kappa_max_spiral(sp) + 1.0 / (R - f.max())
    bound = float(f.max() + M * h * h / 8.0)
    return FittedArc(Arc(c, R, th0, sweep), bound)


def fit_arcs(sp: Spiral, tol: float, max_pieces: int = 1 << 16) -> list[FittedArc]:
    """Arcs within ``tol`` of spiral ``sp`` (certified), in order, end to end.

    Consecutive arcs share their end points exactly as points of the spiral
    (up to the arcs' own rounding of ``R*cos``/``R*sin``).
    """
    if tol <= 0:
        raise ValueError("tolerance must be > 0")
    out: list[FittedArc] = []
    stack = [sp]
    while stack:
        piece = stack.pop()
        fit = _fit_piece(piece)
        if fit is not None and fit.bound <= tol:
            out.append(fit)
            continue
        if len(out) + len(stack) >= max_pieces:
            raise ValueError(f"cannot fit the spiral within {tol:g} with {max_pieces} arcs")
        first, second = piece.split(piece.length / 2)
        stack.append(second)
        stack.append(first)
    return out


# --------------------------------------------------------------------------- Bezier curves


@dataclass(frozen=True)
class FittedPiece:
    """A line or arc replacing the piece ``[t0, t1]`` (Bezier parameter) of a curve.

    geom: :class:`Line` or :class:`Arc` from the piece's start to its end.
    bound: certified two-sided distance between piece and ``geom`` (program units).
    t0, t1: the piece's Bezier parameters on the whole curve.
    angle: largest angle (radians) between ``geom``'s end tangents and the
        curve's tangents at the same two points.
    kappa_bound: the certified curvature bound of the piece that went into
        an arc's bound (1/units); 0 for a line, whose bound needs none.
    """

    geom: Line | Arc
    bound: float
    t0: float
    t1: float
    angle: float
    kappa_bound: float


@lru_cache(maxsize=16)
def _sample_basis(n: int) -> np.ndarray:
    return bernstein(np.linspace(0.0, 1.0, BEZIER_SAMPLES + 1), n)


def _angle(u, v) -> float:
    """Angle between two non-zero vectors (radians, in [0, pi])."""
    return math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1])


def _line_piece(Q: np.ndarray, D1: np.ndarray, D2: np.ndarray):
    """``(Line, bound, angle)`` for the chord of the piece ``Q``, or ``None``
    when the piece does not project monotonically onto its chord."""
    chord = Q[-1] - Q[0]
    L = math.hypot(chord[0], chord[1])
    if L == 0.0:
        return None
    u = chord / L
    if not np.all(D1 @ u > 0.0):
        return None
    hull = float(np.max(np.abs((Q[:, 0] - Q[0, 0]) * u[1] - (Q[:, 1] - Q[0, 1]) * u[0])))
    bend = float(np.max(np.abs(D2[:, 0] * u[1] - D2[:, 1] * u[0]))) / 8.0
    ang = max(_angle(D1[0], u), _angle(D1[-1], u))
    return Line(tuple(Q[0]), tuple(Q[-1])), min(hull, bend), ang


def _tangent_circle(Q: np.ndarray, D1: np.ndarray, at_start: bool):
    """``(centre, R, ccw)`` of the circle through both ends of the piece ``Q``
    tangent to it at its start (``at_start``) or its end, or ``None`` when
    the chord is too nearly along that tangent."""
    A, B = (Q[0], Q[-1]) if at_start else (Q[-1], Q[0])
    T = D1[0] if at_start else -D1[-1]          # pointing into the piece
    T = T / math.hypot(T[0], T[1])
    d = B - A
    nrm = np.array([-T[1], T[0]])
    side = float(d @ nrm)
    dd = float(d @ d)
    if abs(side) <= _CHORD_ALONG_TANGENT_REL * math.sqrt(dd):
        return None
    rho = dd / (2.0 * side)                      # signed: > 0 centre to the left of T
    c = A + rho * nrm
    # seen from the piece's start, the circle turns left when its centre is on
    # the left of the forward tangent (at the end, T points backwards)
    ccw = (rho > 0.0) == at_start
    return c, abs(rho), ccw


def _arc_piece(Q: np.ndarray, D1: np.ndarray, D2: np.ndarray, kappa: float,
               tangent_at: str | None = None):
    """``(Arc, bound, angle)`` for the piece ``Q``, or ``None`` when the
    checks of the module docstring fail: through its start, middle and end,
    or (``tangent_at`` ``"start"``/``"end"``) through both ends and tangent
    to the piece at that end, where the curve meets the next segment."""
    n = len(Q) - 1
    if not math.isfinite(kappa):
        return None
    pm = _sample_basis(n)[BEZIER_SAMPLES // 2] @ Q
    if tangent_at is None:
        circ = circle_through(tuple(Q[0]), tuple(pm), tuple(Q[-1]))
        if circ is None:
            return None
        c, R = circ
        c = np.asarray(c)
        # Orientation of start, middle, end: the way the arc turns.
        e1, e2 = pm - Q[0], Q[-1] - Q[0]
        ccw = e1[0] * e2[1] - e1[1] * e2[0] > 0.0
    else:
        circ = _tangent_circle(Q, D1, tangent_at == "start")
        if circ is None:
            return None
        c, R, ccw = circ
    if R > MAX_ARC_RADIUS:
        return None                      # numerically a line (module docstring)
    sg = 1.0 if ccw else -1.0
    turn = cross_bernstein(D1, D2) * sg
    if turn.min() < -_SIGN_SLACK * max(float(np.abs(turn).max()), _SCALE_FLOOR):
        return None                      # the curve turns the other way somewhere
    if not np.all(cross_bernstein(Q - c, D1) * sg > 0.0):
        return None                      # not monotone about c
    w = pm - c
    w = w / math.hypot(w[0], w[1])
    rho_min = float(np.min((Q - c) @ w))
    if rho_min <= 0.0:
        return None
    vmax = float(np.max(np.hypot(D1[:, 0], D1[:, 1])))
    # Monotone about c, the piece turns through less than its length over
    # rho_min; below 2 pi that is the arc's sweep, not the sweep plus turns.
    if vmax >= TWO_PI * rho_min:
        return None
    pts = _sample_basis(n) @ Q
    f = float(np.max(np.abs(np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1]) - R)))
    h = vmax / BEZIER_SAMPLES
    bound = f + (kappa + 1.0 / rho_min) * h * h / 8.0
    th0 = math.atan2(Q[0, 1] - c[1], Q[0, 0] - c[0])
    th1 = math.atan2(Q[-1, 1] - c[1], Q[-1, 0] - c[0])
    sweep = (th1 - th0) % TWO_PI if ccw else -((th0 - th1) % TWO_PI)
    arc = Arc(tuple(c), R, th0, sweep)
    ang = max(_angle(D1[0], arc.start_tangent), _angle(D1[-1], arc.end_tangent))
    return arc, bound, ang


def _fit_bezier_piece(Q: np.ndarray, tol: float, angle_tol: float,
                      tangent_at: str | None = None):
    """``(geom, bound, angle, kappa_bound)`` for the piece ``Q``, or ``None``.

    The chord when the piece is nearly straight (chord within ``tol``,
    tangent within ``angle_tol``), else the arc through start, middle and end
    (or tangent at ``tangent_at``, see :func:`_arc_piece`) when that is within
    ``tol`` and ``angle_tol`` (checks and bounds: module docstring).
    """
    D1, D2 = hodographs(Q)
    line = _line_piece(Q, D1, D2)
    if line is not None and line[1] <= tol and line[2] <= angle_tol:
        return line[0], line[1], line[2], 0.0
    if tangent_at == "both":
        return None                      # no one arc is tangent at both ends: halve
    kappa = curvature_bound(Q)
    arc = _arc_piece(Q, D1, D2, kappa, tangent_at)
    if arc is not None and arc[1] <= tol and arc[2] <= angle_tol:
        return arc[0], arc[1], arc[2], kappa
    return None


def _restricted(coeffs: np.ndarray, t0: float, t1: float) -> np.ndarray:
    """Bernstein coefficients of the scalar polynomial ``coeffs`` on ``[t0, t1]``
    (in the same parameter, not rescaled): their largest magnitude bounds the
    polynomial's there (convex hull)."""
    c = np.asarray(coeffs, float)[:, None]
    if t0 > 0.0:
        _, c = de_casteljau_split(c, t0)
    if t1 < 1.0:
        c, _ = de_casteljau_split(c, (t1 - t0) / (1.0 - t0))
    return c[:, 0]


def turning_cuts(P) -> list[float]:
    """The inflections of the Bezier ``P`` that bound a real turn, ascending.

    Where a blend joins a line G2, its curvature is zero and the control
    points on the line are collinear only to the rounding of their floats:
    ``p' x p''`` then has a lobe of either sign about ``1e-12`` of the
    parameter long, an inflection to :func:`inflections`. A piece cut there
    is too short for its chord to have a direction: halving it runs into
    the fit's piece limit. Any lobe whose ``|p' x p''|`` stays within
    :data:`_SIGN_SLACK` of the curve's largest (a bound from the Bernstein
    coefficients on the lobe) is not cut at, a genuine but negligible one
    too: it joins its neighbour. The fit stays certified either way: arcs
    are still checked one-signed on each piece (against the piece's own
    largest coefficient, so near such a lobe a piece may need halving down
    to lines), and the bounds come from the checks and samples, not from
    where the curve was cut.
    """
    P = np.asarray(P, float)
    cuts = list(inflections(P))
    if not cuts:
        return cuts
    k = cross_bernstein(*hodographs(P))
    slack = _SIGN_SLACK * float(np.max(np.abs(k)))
    while cuts:
        edges = [0.0, *cuts, 1.0]
        for i in range(len(edges) - 1):
            if float(np.max(np.abs(_restricted(k, edges[i], edges[i + 1])))) <= slack:
                del cuts[i - 1 if i > 0 else 0]   # the cut between the lobe and its neighbour
                break
        else:
            break
    return cuts


def fit_bezier(curve: BezierCurve, tol: float, angle_tol: float = EXPORT_FIT_ANGLE_TOL,
               max_pieces: int = 1 << 14) -> list[FittedPiece]:
    """Lines and arcs within ``tol`` of ``curve`` (certified, two-sided), in order.

    ``tol`` in program units, ``angle_tol`` in radians (the module docstring
    has both bounds). The curve is cut at its inflections; each piece becomes
    a line or an arc (:func:`_fit_bezier_piece`) or is halved (de Casteljau)
    and tried again. Consecutive pieces share their end points exactly; the
    first starts at ``curve.start`` and the last ends at ``curve.end``.
    ``ValueError`` when more than ``max_pieces`` would be needed.
    """
    if tol <= 0 or angle_tol <= 0:
        raise ValueError("tolerances must be > 0")
    P = np.asarray(curve.control_points, float)
    # Cut at the inflections, each cut on what is left of the curve.
    spans: list[tuple[float, float, np.ndarray]] = []
    rest, t_rest = P, 0.0
    for t in turning_cuts(P):
        left, rest = de_casteljau_split(rest, (t - t_rest) / (1.0 - t_rest))
        spans.append((t_rest, t, left))
        t_rest = t
    spans.append((t_rest, 1.0, rest))
    out: list[FittedPiece] = []
    stack = spans[::-1]
    while stack:
        t0, t1, Q = stack.pop()
        # The pieces at the curve's two ends, where it joins its neighbours,
        # get arcs tangent to it there: the exported path turns onto the next
        # segment without a kink, and where a blend meets its segment at the
        # clearance limit (a G2 join, curving away from the part), the arc
        # curves away too instead of crossing the limit by the fit error.
        # A piece holding both ends is a line or is halved.
        ends = (t0 == 0.0, t1 == 1.0)
        fit = _fit_bezier_piece(Q, tol, angle_tol, {(True, True): "both", (True, False): "start",
                                                    (False, True): "end"}.get(ends))
        if fit is not None:
            out.append(FittedPiece(fit[0], fit[1], t0, t1, fit[2], fit[3]))
            continue
        if len(out) + len(stack) >= max_pieces:
            raise ValueError(f"cannot fit the curve within {tol:g} and {angle_tol:g} rad "
                             f"with {max_pieces} pieces")
        left, right = de_casteljau_split(Q)
        tm = 0.5 * (t0 + t1)
        stack.append((tm, t1, right))
        stack.append((t0, tm, left))
    return out
