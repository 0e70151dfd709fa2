"""Gridpoints for TOPPRA on an :class:`~ccopt.feed.path.ExactPath`.

Every segment boundary is a gridpoint (so curvature breaks and tangent
breaks sit exactly on one, evaluated one-sidedly by the constraints), and each
segment gets its own interior points, at least ``min_intervals`` intervals,
so a short segment is never skipped over. Inside a segment the gridpoints are
equally spaced in a measure ``M`` whose density per unit of arc length is the
largest of

1. ``1 / ds``, ``ds = min(braking, S) / density``, where ``S`` is the
   segment length (on a line with no curvature jump at its ends, its
   stretch's with :attr:`GridOptions.stretch_lines`: :func:`stretch_lengths`)
   and ``braking = v^2 / a``, ``v`` the segment's speed cap (feed, or the
   smallest axis velocity limit for rapids) and ``a`` the largest axis
   acceleration limit (or ``ds`` given). TOPPRA's profile is
   piecewise constant-acceleration between gridpoints, so a switch from
   speeding up to cruising (or braking) that falls inside an interval costs
   time, of relative order ``ds^2 / (8 braking S)``; with ``density = 16``
   the worst seen on single moves (without the baselines' switch points,
   which remove it on straight moves) is 5e-4 of the duration, on a short
   move that never cruises. This part alone is capped, at ``max_intervals``
   per segment: it only buys time on long moves;
2. ``kappa_p / max_angle``: the in-plane turning rate of the tangent
   (``kappa_p`` the curvature of the segment's plane geometry, the rate at
   which an arc's ``|sweep|`` accrues);
3. ``|q'''| / (max_curvature_change * kappa_ref)``: the rate of relative
   change of the curvature vector ``q''`` (its length and its direction);
4. ``sqrt(|q''''| / kappa_ref) / max_curvature_bend``: its relative second
   variation, which a curvature peak has where 3 is about zero (``q'''``
   vanishes at the top of the peak);

with ``kappa_ref = max(|q''|, kappa_f)`` and
``kappa_f = min(|A|_2 / v_top^2, max_angle / ds)``: ``v_top = min(feed,
|vmax|_2)`` is the largest path speed the limits allow on the segment and
``|A|_2`` the norm of the axis acceleration limits, so below ``kappa_f`` the
speed, not the curvature, bounds ``|q''| s'^2``. The segment gets
``n = max(min_intervals, ceil(M(S)))`` intervals at equal steps of ``M``:
over every interval (length ``d``) ``d <= ds``, the turning
``Theta <= max_angle``, ``integral |q'''| / kappa_ref <= max_curvature_change``
and ``integral sqrt(|q''''| / kappa_ref) <= max_curvature_bend``. Parts 2 to 4
are never capped: they keep the limits, and grow only with the segment's
turning, the logarithm of its curvature range and its number of curvature
peaks. On an arc all three are its
turning (``|q'''| = kappa^2``, ``|q''''| = kappa^3``), so lines and arcs are
gridded evenly in closed form; any other segment (spiral, Bezier curve, a
researcher's curve) is sampled from its exact derivatives
(:meth:`ExactPath.eval_segments`): ``curve_samples`` equal pieces first, then
every piece whose part 2, 3 or 4 exceeds ``sample_fraction`` of one interval's
budget is halved, until none does. A piece's turning is the larger of the
angle between its end tangents and the trapezoid rule on ``kappa_p``; ``q'''``
and ``q''''`` are first and second differences of ``q''`` between samples.
``M`` is taken linear across a piece, so an interval may take up to
``2 * sample_fraction`` of a budget more than its share (all of a piece's
turning at one end; of second order where the geometry is smooth on the scale
of the samples). A feature that changes none of the measures by
``sample_fraction`` of a budget across one of the first pieces is not seen.

Why (the limits are imposed at gridpoints only): between two gridpoints
TOPPRA's ``u = s''`` is constant and ``x = s'^2`` linear in ``s``, so an axis
acceleration ``a_i(s) = q_i' u + q_i'' x``, checked at both ends, exceeds the
straight line between its end values by at most ``d^2 / 8 max |a_i''|``, with
``a'' = 5 q''' u + q'''' x``. At a gridpoint the tangential part ``|u|`` of
the checked acceleration and its normal part ``|q''| x`` are at most
``|A|_2``, the norm of the axis limits, and ``x kappa_f <= v_top^2 kappa_f <=
|A|_2``; ``x`` is linear and ``kappa_ref`` changes by at most
``e^beta`` across the interval, so there ``x kappa_ref <= |A|_2 e^beta`` and
``d kappa_ref <= alpha e^beta``. Writing ``alpha, beta, gamma`` for the
budgets of parts 2 to 4, and with the densities about constant across an
interval (so ``d |q'''| / kappa_ref <= beta`` and ``d^2 |q''''| / kappa_ref
<= gamma^2`` pointwise), the relative excess of axis ``i`` over its limit
``A_i`` is at most

    E_a = (R_i / 8) e^beta (5 alpha beta + gamma^2),    R_i = |A|_2 / A_i,

of second order in the budgets: 2.8e-3 for the defaults and two equal axes
(6.4e-3 with each budget raised by the sampling's ``2 * sample_fraction``);
the terms seldom align, and profiles stay near 1e-4. On lines and arcs it is
``6 R alpha^2 / 8``, as with the even grid formerly used on every segment
(which put a few gridpoints in a curve's short tight stretch and let the
profile exceed the limits up to 20 times over between them). An axis velocity
``v_i = |q_i'| sqrt(x)`` squared is the product of ``g^2 = q_i'^2`` and the
linear ``x``: above its larger end value by at most the interpolation defect
of ``g^2`` times ``x``, plus ``|Delta g^2| |Delta x| / 4`` where the two
changes nearly cancel (and then at most ``(Delta g / g)^2`` of it), with
``|Delta g| <= alpha``, ``|g'| <= |q''|``, ``|g''| <= |q'''|``, and
``g >= G = V_i / v_top - alpha`` wherever ``v_i`` nears its limit ``V_i``:

    E_v = (alpha / G)^2 / 2 + ((alpha e^beta / G)^2 + alpha beta e^beta / G) / 8,

2.1e-3 for the defaults where ``v_top = V_i`` (5.1e-3 with the sampling's
margin). Segments that move the out-of-plane axis count their turning in the
plane (``kappa_p``, as arcs do): the 3-D tangent changes by no more than that.

:func:`refine` adds further points (the TOPPRA planner adds the baselines'
switch points).

The planner does not rely on these bounds to keep the limits: it checks the
axis accelerations at interior points of every interval too and shrinks them
by the residual between checks (:func:`residual_margins`), and it bounds the
axis velocities by each interval's largest ``|q_j'|``
(:func:`interval_speed_peaks`); see the comment above them. The budgets above
keep that margin small (about 1e-4 on arcs).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ccopt.feed.grading import Ramps, curve_braking, graded_grids
from ccopt.feed.path import ExactPath
from ccopt.tolerances import CURVATURE_TOL

#: Default of :attr:`GridOptions.min_spacing` (program units): extra gridpoints
#: closer than this to one already there add an interval TOPPRA cannot resolve.
MIN_GRID_SPACING = 1e-7


@dataclass(frozen=True)
class GridOptions:
    """How densely to grid the path (see the module docstring).

    ``max_angle`` is in radians; ``max_curvature_change`` and
    ``max_curvature_bend`` are the budgets of parts 3 and 4 (dimensionless:
    on an arc, radians of turning too); ``ds`` and ``min_spacing`` are in
    program units.
    """

    density: float = 16.0
    max_angle: float = 0.05
    max_curvature_change: float = 0.05
    max_curvature_bend: float = 0.05
    min_intervals: int = 4
    max_intervals: int = 2000   # caps the braking-based part only
    ds: float | None = None  # a fixed maximum spacing (units) instead of braking / density
    #: add the baselines' switch points (see ccopt.feed.baselines.baseline_knot_positions)
    baseline_knots: bool = True
    #: extra points closer than this to a gridpoint are dropped (units)
    min_spacing: float = MIN_GRID_SPACING
    #: curves other than lines and arcs: equal pieces sampled first, and the share of
    #: one interval's budget a sampled piece may take
    curve_samples: int = 32
    sample_fraction: float = 0.25
    #: part 1 on a line with no curvature jump at its ends, inside a longer
    #: stretch (stop to stop, :func:`stretch_lengths`): the stretch's length in
    #: place of the segment's
    stretch_lines: bool = False

    def __post_init__(self):
        if not min(self.density, self.max_angle, self.max_curvature_change,
                   self.max_curvature_bend) > 0:
            raise ValueError("density, max_angle, max_curvature_change and max_curvature_bend "
                             "must be > 0")
        if self.min_intervals < 2:
            # two stops one interval apart would pin the speed to zero in between
            raise ValueError("min_intervals must be >= 2")
        if self.max_intervals < self.min_intervals:
            raise ValueError("max_intervals must be >= min_intervals")
        if self.ds is not None and not self.ds > 0:
            raise ValueError("ds must be > 0")
        if self.curve_samples < 1 or not 0 < self.sample_fraction <= 1:
            raise ValueError("curve_samples must be >= 1 and sample_fraction in (0, 1]")


#: Curves: a piece shorter than this fraction of its segment is not halved again
#: (about 2^-36 of it: well past any feature a regular curve can hide).
_MIN_PIECE = 1e-11
#: ... nor one shorter than this many units in the last place of its path
#: positions: below that a piece's midpoint rounds to one of its ends, and
#: the halving would never end (a smoothed plate's blend 2.7e-8 long, 245.7 mm
#: along its path, had pieces one ulp long that kept being halved).
_MIN_PIECE_ULPS = 64


def _spacing(path: ExactPath, v_axis: np.ndarray, a_axis: np.ndarray,
             options: GridOptions, jerk=None) -> np.ndarray:
    """``(ds, n)``: braking-based spacing of each segment (units), at least
    ``S / max_intervals``, and the number of intervals it asks for (at most
    ``max_intervals``; counted from the spacing before the cap, which
    ``S / (S / max_intervals)`` could round above).

    With axis jerk limits ``jerk`` (units/s^3, plane order) the braking
    length is ``v^2 / a_j``, ``a_j = min(a, sqrt(2 |J|_2 v))`` the largest path
    acceleration a jerk-limited profile reaches below the cap ``v`` (as
    :func:`~ccopt.feed.grading.scurve_ramp` bounds it; ``|J|_2`` bounds the
    path jerk on a line in any direction). The spacing keeps what it is for:
    over one interval the squared speed changes by at most ``2 a_j ds``, a
    share ``2 / density`` of its value at the cap, as TOPPRA's grid does
    with ``a``; the jerk planner's rows lose time in proportion to that
    relative change (each end's speed factor bounds the interval's jerk)."""
    S = path.lengths
    if options.ds is not None:
        ds = np.full(S.size, options.ds)
    else:
        v = np.minimum(path.feeds, float(np.min(v_axis)))
        a = float(np.max(a_axis))
        if jerk is not None:
            a = np.minimum(a, np.sqrt(2.0 * float(np.linalg.norm(jerk)) * v))
        span = stretch_lengths(path) if options.stretch_lines else S
        ds = np.minimum(v * v / a, span) / options.density
    n = np.minimum(np.ceil(S / ds), options.max_intervals)
    return np.maximum(ds, S / options.max_intervals), n


def stretch_lengths(path: ExactPath) -> np.ndarray:
    """Per segment of ``path``: the length (units) of the stretch it lies on
    (from a stop to the next: the path's ends, tangent breaks, dwells) where
    it is a line whose joins both keep the curvature (a jump of at most
    :data:`~ccopt.tolerances.CURVATURE_TOL`, or a stop), else its own length.

    Why such a line may take its stretch's: part 1 bounds the relative change
    of the squared speed over an interval, ``2 a ds / v^2`` at most ``2 /
    density``, and the time a speed switch inside an interval costs,
    ``ds^2 / (8 braking)`` per switch; neither depends on how long the segment
    is. On a line nothing else varies between gridpoints (the axis
    acceleration is linear in the path acceleration), and with no curvature
    jump at its ends no speed cap sits there (the jerk planner caps ``b`` at
    a jump, ``|Delta q''| b <= J Ts``; a cap's dip needs the fine spacing of
    the short segments beside it: the chords between Fagor's corner arcs on
    freeform-hsm planned 0.55 % slower without it). So the short lines
    between the G2 blends of a smoothed path get ``min_intervals``, not
    ``density``, intervals each. A move that is a stretch alone keeps its own
    length (it never cruises), and so do arcs and curves."""
    S = path.lengths
    if S.size == 0:
        return S
    stops = np.concatenate([[0.0], path.stop_positions, [path.length]])
    mid = path.offsets[:-1] + 0.5 * S
    k = np.clip(np.searchsorted(stops, mid), 1, stops.size - 1)
    span = stops[k] - stops[k - 1]
    line = path.constant_curvature & (path.uniform_turning == 0.0)
    if not line.any():
        return S
    b = path.offsets[1:-1]                       # the inner joins
    left, right = path.eval_sided(b, 2, "left"), path.eval_sided(b, 2, "right")
    kappa = np.maximum(np.linalg.norm(left, axis=1), np.linalg.norm(right, axis=1))
    smooth = (np.linalg.norm(right - left, axis=1) <= CURVATURE_TOL * np.maximum(1.0, kappa))
    smooth |= path.tangent_break[1:-1]
    smooth = np.concatenate([[True], smooth, [True]])      # the path's ends are stops
    keep = line & smooth[:-1] & smooth[1:]
    return np.where(keep, np.maximum(span, S), S)


def _jerk_of(ramps) -> np.ndarray | None:
    """The axis jerk limits of ``ramps`` (a :class:`~ccopt.feed.grading.Ramps`,
    its first two fields, or None)."""
    return None if ramps is None else Ramps(*ramps).jerk


def _curvature_floor(path: ExactPath, v_axis, a_axis, ds, options: GridOptions) -> np.ndarray:
    """``kappa_f`` of each segment (1/units): see the module docstring."""
    v_top = np.minimum(path.feeds, float(np.linalg.norm(v_axis)))
    return np.minimum(float(np.linalg.norm(a_axis)) / (v_top * v_top), options.max_angle / ds)


def _piece_measures(k, s, tan, q2, kappa_f, ratio):
    """Per pair of consecutive samples (a piece): ``(same, h, turn, change, bend)``.

    ``same``: both samples on one segment (the measures are 0 where not);
    ``h``: length; ``turn``: in-plane turning (radians), the larger of the angle
    between the end tangents ``tan`` and the trapezoid rule on
    ``kappa_p = |q''| / r^2`` over the in-plane length ``r h``; ``change``:
    ``|Delta q''| / kappa_ref``; ``bend``: ``h sqrt(|q''''| / kappa_ref)``,
    ``q''''`` from second differences of ``q''`` at the piece's two samples
    (the larger; the inner one at a segment's ends).
    """
    same = k[1:] == k[:-1]
    h = s[1:] - s[:-1]
    k0 = k[:-1]
    chord = np.arctan2(np.abs(tan[:-1, 0] * tan[1:, 1] - tan[:-1, 1] * tan[1:, 0]),
                       np.einsum("ij,ij->i", tan[:-1], tan[1:]))
    kap = np.linalg.norm(q2, axis=1)
    turn = np.where(same, np.maximum(chord, 0.5 * h * (kap[:-1] + kap[1:]) / ratio[k0]), 0.0)
    kref = np.maximum(np.maximum(kap[:-1], kap[1:]), kappa_f[k0])
    dq2 = q2[1:] - q2[:-1]
    change = np.where(same, np.linalg.norm(dq2, axis=1) / kref, 0.0)
    q3 = dq2 / np.where(same, h, 1.0)[:, None]
    inner = same[1:] & same[:-1]
    q4 = np.where(inner, np.linalg.norm(q3[1:] - q3[:-1], axis=1)
                  / np.where(inner, 0.5 * (h[1:] + h[:-1]), 1.0), 0.0)
    q4_piece = np.maximum(np.r_[0.0, q4], np.r_[q4, 0.0])
    bend = np.where(same, h * np.sqrt(q4_piece / kref), 0.0)
    return same, h, turn, change, bend


def _curve_samples(path: ExactPath, ks: np.ndarray, kappa_f: np.ndarray,
                   options: GridOptions):
    """Adaptive samples of the segments ``ks`` (see the module docstring).

    Returns ``(k, s, h, turn, change, bend)``: the segment and path position
    of every sample, in path order, and the measures of
    :func:`_piece_measures` of every piece.
    """
    n0 = options.curve_samples
    k = np.repeat(ks, n0 + 1)
    s = path.offsets[k] + path.lengths[k] * np.tile(np.arange(n0 + 1) / n0, ks.size)
    ratio = path.in_plane_ratio
    f = options.sample_fraction
    limits = (f * options.max_angle, f * options.max_curvature_change,
              f * options.max_curvature_bend)
    min_piece = np.maximum(_MIN_PIECE * path.lengths,
                           _MIN_PIECE_ULPS * np.spacing(np.abs(path.offsets[1:])))

    def evaluate(kk, ss):
        t = path.eval_in_plane(kk, ss, 1)
        return t / np.linalg.norm(t, axis=1, keepdims=True), path.eval_segments(kk, ss, 2)

    tan, q2 = evaluate(k, s)
    while True:
        same, h, turn, change, bend = _piece_measures(k, s, tan, q2, kappa_f, ratio)
        split = same & (h > min_piece[k[:-1]]) & (
            (turn > limits[0]) | (change > limits[1]) | (bend > limits[2]))
        if not split.any():
            return k, s, h, turn, change, bend
        i = np.flatnonzero(split)
        k_new = k[i]
        s_new = 0.5 * (s[i] + s[i + 1])
        t_new, q2_new = evaluate(k_new, s_new)
        # each new sample goes right after the left end of its piece
        order = np.argsort(np.concatenate([np.arange(k.size), i + 0.5]), kind="stable")
        k = np.concatenate([k, k_new])[order]
        s = np.concatenate([s, s_new])[order]
        tan = np.concatenate([tan, t_new])[order]
        q2 = np.concatenate([q2, q2_new])[order]


def _segment_grids(path: ExactPath, v_axis, a_axis, options: GridOptions, ramps=None):
    """``(n, interior, ds)``: intervals per segment, ``{k: interior gridpoints}``
    (``n[k] - 1`` path positions) of the sampled segments, not evenly spaced,
    and each segment's braking spacing (:func:`_spacing`).
    ``ramps`` as in :func:`gridpoints`: part 1 of ``M`` graded on curves
    whose speed cap is their feed (:func:`~ccopt.feed.grading.curve_braking`)."""
    ds, n = _spacing(path, v_axis, a_axis, options, _jerk_of(ramps))
    step = min(options.max_angle, options.max_curvature_change, options.max_curvature_bend)
    n = np.maximum(n, np.ceil(path.uniform_turning / step))
    n = np.maximum(n, options.min_intervals).astype(int)
    interior: dict[int, np.ndarray] = {}
    ks = np.flatnonzero(~path.constant_curvature)
    if ks.size == 0:
        return n, interior, ds
    kappa_f = _curvature_floor(path, v_axis, a_axis, ds, options)
    k, s, h, turn, change, bend = _curve_samples(path, ks, kappa_f, options)
    if ramps is not None and options.ds is None:
        braking = curve_braking(path, k, s, ds, v_axis, a_axis, ramps)
    else:
        braking = h / ds[k[:-1]]
    dm = np.maximum.reduce([braking, turn / options.max_angle,
                            change / options.max_curvature_change,
                            bend / options.max_curvature_bend])
    dm[k[1:] != k[:-1]] = 0.0
    m = np.concatenate([[0.0], np.cumsum(dm)])
    starts = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
    for a, b in zip(starts, np.r_[starts[1:], k.size]):
        kk = int(k[a])
        mm = m[a:b] - m[a]
        nk = max(options.min_intervals, int(np.ceil(mm[-1])))
        n[kk] = nk
        interior[kk] = np.interp(mm[-1] * np.arange(1, nk) / nk, mm, s[a:b])
    return n, interior, ds


def intervals_per_segment(path: ExactPath, v_axis: np.ndarray, a_axis: np.ndarray,
                          options: GridOptions = GridOptions()) -> np.ndarray:
    """Number of grid intervals on each segment of ``path``."""
    return _segment_grids(path, np.asarray(v_axis, float), np.asarray(a_axis, float),
                          options)[0]


def gridpoints(path: ExactPath, v_axis, a_axis, options: GridOptions = GridOptions(),
               ramps: tuple | None = None) -> np.ndarray:
    """Strictly increasing gridpoints from 0 to ``path.length``, every boundary included.

    ``ramps``: a :class:`~ccopt.feed.grading.Ramps` (or its first two fields,
    ``(tangential_acc, centripetal_acc)``, each ``None`` when not set) for a
    time-optimal planner: lines and arcs are then graded
    (:func:`~ccopt.feed.grading.graded_grids`), with ramp zones under jerk
    limits when it has them. Without it every line and arc is gridded evenly.
    """
    v_axis, a_axis = np.asarray(v_axis, float), np.asarray(a_axis, float)
    n, interior, ds = _segment_grids(path, v_axis, a_axis, options, ramps)
    if ramps is not None:
        for k, inner in graded_grids(path, n, ds, v_axis, a_axis, options, ramps).items():
            n[k] = inner.size + 1
            interior[k] = inner
    k = np.repeat(np.arange(n.size), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    j = np.arange(k.size) - np.repeat(first, n)
    pts = path.offsets[k] + path.lengths[k] * (j / n[k])
    for kk, inner in interior.items():
        pts[first[kk] + 1:first[kk] + n[kk]] = inner
    pts = np.concatenate([pts, path.offsets[-1:]])
    # boundaries exactly (j == 0 gives offsets[k] + 0.0, already exact)
    if np.any(np.diff(pts) <= 0.0):
        pts = np.unique(pts)
    return pts


def refine(points: np.ndarray, extra, min_spacing: float) -> np.ndarray:
    """``points`` plus those of ``extra`` at least ``min_spacing`` from every one of them."""
    extra = np.asarray(extra, dtype=float)
    extra = extra[(extra > points[0]) & (extra < points[-1])]
    if extra.size == 0:
        return points
    i = np.searchsorted(points, extra)
    gap = np.minimum(np.abs(points[np.minimum(i, points.size - 1)] - extra),
                     np.abs(extra - points[np.maximum(i - 1, 0)]))
    extra = np.unique(extra[gap >= min_spacing])
    if extra.size > 1:
        keep = np.r_[True, np.diff(extra) >= min_spacing]
        extra = extra[keep]
    return np.union1d(points, extra)


# -- between gridpoints: interior checks and the residual margin ---------------------
#
# TOPPRA's profile is constant in ``u = s''`` over each interval
# ``[s_i, s_i+1]`` (length ``d``), with ``x = s'^2 = x_i + 2 u (s - s_i)``
# linear. At ``s = s_i + tau d`` an axis acceleration is then
#
#     a_j(tau) = P_j(tau) u + Q_j(tau) x_i,
#     P = q'(s) + 2 tau d q''(s),  Q = q''(s),
#
# linear in the interval's two unknowns, so it can be imposed exactly at any
# interior point, not only at the two ends (toppra's interpolation scheme).
# The planner imposes it at the ends and at INTERIOR_CHECKS; between two
# consecutive checks ``a_j`` exceeds the chord of its checked values by its
# curvature defect ``c_j u + e_j x_i``, ``c`` and ``e`` the defects of ``P``
# and ``Q`` against their chords. Measured at the middle of each stretch
# (where a smooth bump's defect peaks) and bounded over the unknowns by what
# the checks at ``s_i`` allow -- ``|u| <= |A|_2`` and ``|q''| x_i <= |A|_2``
# since ``q'`` is a unit vector normal to ``q''`` (so ``(u, |q''| x)`` is the
# acceleration in the tangent/normal frame, at most the norm of the axis
# limits), and ``x_i`` at most the squared speed cap -- it is the residual
# margin: the relative amount by which the planner shrinks each axis limit on
# that interval so the profile keeps the limit everywhere, not only at the
# checks. On a line ``P`` is constant and ``Q = 0``: no defect, no margin, the
# limits are met exactly. On an arc of turning ``theta`` per interval the
# defect is about ``(5/8) (theta/4)^2 |A|_2 / A_j`` with the checks a quarter
# apart, 1.4e-4 for the default 0.05 rad and two equal axes (against the
# ``(theta)^2 / 8`` = 3e-4 by which the profiles sampled at 1 kHz overshot
# with end checks only, a 11 of 108 false limits failures in
# ``sweeps/styles-radii.toml``). The residual is second order in the spacing,
# so the margin costs ~1e-4 of the time spent accelerating on curves.
#
# Axis velocity ``v_j^2 = q_j'(s)^2 x(s)``, ``x`` linear: ``x`` at both ends of
# an interval at most ``V_j^2 / G_j^2``, ``G_j`` the largest ``|q_j'|`` on the
# interval, keeps ``v_j <= V_j`` all along it. ``G_j`` is the largest of the
# interval's samples (ends, checks, middles) plus the parabola allowance
# ``max |second difference| / 8`` (the most a function with that second
# derivative rises between two samples); on a line it is ``|q_j'|`` exactly.

#: Interior points (fractions of each grid interval) where the planner checks
#: the axis accelerations, besides the interval's two ends.
INTERIOR_CHECKS = np.array([0.25, 0.5, 0.75])

#: The residual margin is the defect measured at the middle of each stretch
#: between checks times this factor: a bump that is not symmetric peaks off its
#: middle, higher than measured there by a fraction of order its skew.
RESIDUAL_SAFETY = 1.25

#: The residual margin never shrinks a limit by more than this fraction (a grid
#: so coarse that it would is far outside GridOptions' budgets).
MAX_RESIDUAL_MARGIN = 0.5


@dataclass(frozen=True, eq=False)
class IntervalSamples:
    """``q'`` and ``q''`` of every grid interval at ``tau`` (fractions of it):
    the end, check and middle points. ``q1``, ``q2``: ``(N, len(tau), dof)``,
    one-sided at the interval's ends (its own segment); ``d``: ``(N,)`` lengths;
    ``checks``: indices into ``tau`` of the ends and the interior checks."""

    tau: np.ndarray
    checks: np.ndarray
    d: np.ndarray
    q1: np.ndarray
    q2: np.ndarray

    @property
    def accel_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """``(P, Q)`` at every sample, ``(N, len(tau), dof)`` each: ``a_j = P_j u + Q_j x_i``."""
        return self.q1 + 2.0 * (self.tau[None, :] * self.d[:, None])[:, :, None] * self.q2, self.q2


def interval_samples(path: ExactPath, gridpoints: np.ndarray) -> IntervalSamples:
    """The :class:`IntervalSamples` of ``path`` on ``gridpoints`` (every
    segment boundary among them, so each interval lies on one segment)."""
    gp = np.asarray(gridpoints, float)
    checks = np.r_[0.0, INTERIOR_CHECKS, 1.0]
    tau = np.sort(np.r_[checks, 0.5 * (checks[1:] + checks[:-1])])
    n, m = gp.size - 1, tau.size
    d = np.diff(gp)
    k = np.repeat(path.locate(gp[:-1], "right"), m)
    s = (gp[:-1, None] + d[:, None] * tau[None, :]).ravel()
    q1, q2 = (q.reshape(n, m, -1) for q in path.eval_orders(k, s, (1, 2)))
    return IntervalSamples(tau, np.searchsorted(tau, checks), d, q1, q2)


def residual_margins(smp: IntervalSamples, a_axis, x_cap) -> np.ndarray:
    """``(N, dof)`` relative margin of each axis acceleration limit on each
    interval (see the comment above); ``a_axis`` the limits, ``x_cap`` ``(N+1,)``
    the largest squared path speed allowed at each gridpoint, in the same units."""
    a_axis = np.asarray(a_axis, float)
    fin = np.isfinite(a_axis)
    norm_a = float(np.linalg.norm(a_axis[fin]))
    P, Q = smp.accel_rows
    c = P[:, 1::2] - 0.5 * (P[:, :-2:2] + P[:, 2::2])
    e = Q[:, 1::2] - 0.5 * (Q[:, :-2:2] + Q[:, 2::2])
    kappa = np.linalg.norm(smp.q2[:, 0], axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        x_max = np.minimum(np.asarray(x_cap, float)[:-1],
                           np.where(kappa > 0, norm_a / kappa, np.inf))
        separate = np.abs(c) * norm_a + np.where(e == 0.0, 0.0, np.abs(e) * x_max[:, None, None])
        joint = np.where(kappa[:, None, None] > 0,
                         np.hypot(c, e / np.where(kappa > 0, kappa, 1.0)[:, None, None]) * norm_a,
                         np.inf)
        defect = np.minimum(separate, joint).max(axis=1)
        m = np.where(fin, RESIDUAL_SAFETY * defect / np.where(fin, a_axis, 1.0), 0.0)
    return np.minimum(np.nan_to_num(m, nan=MAX_RESIDUAL_MARGIN), MAX_RESIDUAL_MARGIN)


def interval_speed_peaks(smp: IntervalSamples) -> np.ndarray:
    """``(N, dof)``: ``G_j``, the largest ``|q_j'|`` on each interval (see the comment above)."""
    g = np.abs(smp.q1)
    allowance = np.abs(g[:, 2:] - 2.0 * g[:, 1:-1] + g[:, :-2]).max(axis=1) / 8.0
    return g.max(axis=1) + allowance
