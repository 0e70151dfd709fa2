"""Spirals and arcs about one centre: bounds from polar radius and angle.

A controller's arc whose end is slightly off its radius is a spiral, and the
tool's offset of it is a spiral about the same centre. Their distance is
nearly the radial gap everywhere, which chords reach only when cut to pieces
whose sagitta is below the tolerance: thousands per pair. Here the common
centre gives bounds directly (``SpiralParam``-like arguments: ``c, rho0, b,
th0, sg, U`` and ``eval``; :mod:`ccopt.verify.distance.certified` uses them):

- :func:`same_angle`: an upper bound of the distance from the points at one
  polar angle;
- :func:`polar_gap`: a lower bound for piece pairs from radius and angle;
- :func:`farthest_concentric`: the farthest distance of a tool segment from its
  element in closed form (contact).
"""
from __future__ import annotations

import math

import numpy as np

#: Radians: how far a curve's ends may lie outside another's sweep, and the
#: angle between them read through the other's parameter differ from its own
#: sweep, for :func:`farthest_concentric` (1e-7 to 1e-4 when a controller's arc
#: ends are off their radius; far from a wrap of 2 pi; the bound pays for it).
ANGLE_SLACK = 1e-3

#: How far past the angle where a chord about a common centre reaches the
#: radial gap the concentric bound of :func:`farthest_concentric` looks (a factor).
CHORD_ANGLE_MARGIN = 1.01


def same_angle(qa, ang, dq, qb, eval_b, th0_b, sg_b, U_b):
    """``(dq, qb)`` improved, for spirals about one centre, by the point of ``b``
    at the polar angle ``ang`` of each ``qa`` where ``b`` has one (a genuine
    pair of curve points, so still an upper bound). The chord witnesses of
    two nearly parallel chords sit at their ends, angles apart; the radial
    pair is within ``|b|`` times the pieces' angle of the distance, so a
    spiral against its concentric offset converges in one round instead of
    cutting both into thousands of pieces."""
    u = np.mod((ang - th0_b) * sg_b, 2.0 * math.pi)
    ok = u <= U_b
    q2 = eval_b(np.minimum(u, U_b))
    d2 = np.hypot(*(qa - q2).T)
    better = ok & (d2 < dq)
    return np.where(better, d2, dq), np.where(better[:, None], q2, qb)


def polar_gap(a, ua0, ua1, b, ub0, ub1):
    """A lower bound of the distance of piece pairs of two spirals about one centre,
    from their polar angles as well as their radii (0 where it does not apply).

    With ``D`` the (unwrapped) angle from a point ``q`` of ``b`` to a point ``p``
    of ``a``, ``|p - q|^2 = (rho_p - rho_q)^2 + 4 rho_p rho_q sin^2(D / 2)``.
    Extending ``b``'s radius affinely in its angle, ``|rho_p - rho_q| >= G -
    beta |D|`` where ``G`` is the least ``|rho_a - rho_b|`` at a common angle over
    ``a``'s piece and ``beta = |b_b|`` (radius per radian); and for ``|D| <= x
    <= pi``, ``sin(D/2) >= (D/2) sinc(x/2)``. So ``|p - q|^2 >= max(G - beta |D|,
    0)^2 + C D^2`` (``C = rho_a,min rho_b,min sinc^2(x/2)``), which is at least
    ``G^2 C / (beta^2 + C)`` whatever ``D``. The pieces' angles bound ``|D|``
    by ``x``; pairs with ``x > pi`` get 0. Where the radial-range gap loses
    ``|b| h`` per piece, this loses a relative ``beta^2 / 2C``: a spiral and its
    concentric offset settle without cutting thousands of pieces."""
    ta0, ta1 = a.th0 + a.sg * ua0, a.th0 + a.sg * ua1
    tb0, tb1 = b.th0 + b.sg * ub0, b.th0 + b.sg * ub1
    x = np.maximum(np.abs(np.maximum(ta0, ta1) - np.minimum(tb0, tb1)),
                   np.abs(np.minimum(ta0, ta1) - np.maximum(tb0, tb1)))
    # rho_a - rho_b at a common angle, affine in it: its least |.| over a's piece
    d0 = (a.rho0 + a.b * ua0) - (b.rho0 + b.b * b.sg * (ta0 - b.th0))
    d1 = (a.rho0 + a.b * ua1) - (b.rho0 + b.b * b.sg * (ta1 - b.th0))
    G = np.where(d0 * d1 <= 0.0, 0.0, np.minimum(np.abs(d0), np.abs(d1)))
    lo_a = np.minimum(a.rho0 + a.b * ua0, a.rho0 + a.b * ua1)
    lo_b = np.minimum(b.rho0 + b.b * ub0, b.rho0 + b.b * ub1)
    half = 0.5 * np.minimum(x, math.pi)
    sinc = np.where(half > 0.0, np.sin(half) / np.where(half > 0.0, half, 1.0), 1.0)
    C = np.maximum(lo_a, 0.0) * np.maximum(lo_b, 0.0) * sinc * sinc
    beta = abs(b.b)
    with np.errstate(invalid="ignore", divide="ignore"):
        gap = G * np.sqrt(C / (beta * beta + C))
    return np.where((x <= math.pi) & (C > 0.0), gap, 0.0)


def farthest_concentric(pt, pe, tol: float):
    """``(lb, ub, witness)`` of ``max dist(q in t, e)`` in closed form, for a
    spiral or arc ``t`` about the centre of ``e`` whose angles lie in ``e``'s
    sweep (to :data:`ANGLE_SLACK`): a tool segment and its element, offset
    radially. ``None`` when that does not apply or the bounds are not within
    ``tol`` (the caller then cuts chords). ``pt``, ``pe``: their parameters.

    Upper bound: each ``q`` is within ``|rho_t - rho_e|`` of the point of ``e``
    at its polar angle, both radii affine in the angle, so the largest is at
    an end of ``t``; a part of ``t`` past ``e``'s end by up to ``delta``
    radians is within ``sqrt((g + |b_t| delta)^2 + rho_t rho_e delta^2)`` of
    that end point (radial gap, and ``2 rho_t rho_e (1 - cos delta)``). Lower bound, at an end ``q`` of ``t`` (a genuine
    point, the witness), with ``g = |rho_q - rho_e|`` at its angle (``e``'s end
    when past it): a point ``p`` of ``e`` ``D`` radians round from it, within
    ``x``, has ``|q - p|^2 = (rho_q - rho_p)^2 + 4 rho_q rho_p sin^2(D/2) >=
    (g - |b_e| D)^2 + C D^2`` (``C = rho_q rho_e,min sinc^2(x/2)``), at least
    ``g sqrt(C / (b_e^2 + C))``; one farther round is at least the chord
    ``2 sqrt(rho_q rho_e,min) sin(x / 2)`` away (when ``e`` sweeps at most
    ``2 pi - x``); ``x`` is chosen just past the angle where the chord reaches
    ``g``, so the chord does not bind."""
    if not np.array_equal(pt.c, pe.c):
        return None
    ends = np.array([0.0, pt.U])
    ang = pt.th0 + pt.sg * ends
    ue = np.mod((ang - pe.th0) * pe.sg, 2.0 * math.pi)
    ue = np.where(ue > pe.U + ANGLE_SLACK, ue - 2.0 * math.pi, ue)   # just before e's start
    over = float(max(0.0, -ue.min(), ue.max() - pe.U))
    # within the slack of e's sweep, and no wrap between the ends (e's parameter
    # runs affinely along t)
    if over > ANGLE_SLACK or abs((ue[1] - ue[0]) - pe.sg * pt.sg * pt.U) > ANGLE_SLACK:
        return None
    rho_t = pt.rho0 + pt.b * ends
    g = np.abs(rho_t - (pe.rho0 + pe.b * np.clip(ue, 0.0, pe.U)))
    # past e's end by up to `over` radians: from e's end point, radially and round
    hi_e = max(pe.rho0, pe.rho0 + pe.b * pe.U)
    ub = float(max(g.max(), math.sqrt((g.max() + abs(pt.b) * over) ** 2
                                      + rho_t.max() * hi_e * over * over)))
    lo_e = min(pe.rho0, pe.rho0 + pe.b * pe.U)
    # the angle where the chord reaches the radial gap, and a little more
    reach = float(g.max() / (2.0 * math.sqrt(rho_t.min() * lo_e)))
    x = min(2.0 * math.pi - pe.U - over, CHORD_ANGLE_MARGIN * 2.0 * math.asin(min(reach, 1.0)))
    if not x > 0.0:
        # t on e (no gap to bound), or e sweeping (nearly) a whole turn
        lbs = np.zeros(2)
        return _bound(pt, ends, lbs, ub, tol)
    chord = 2.0 * np.sqrt(rho_t * lo_e) * math.sin(0.5 * x)
    # within x: |q - p|^2 = (rho_q - rho_p)^2 + 4 rho_q rho_p sin^2(D / 2)
    #   >= max(g - beta |D|, 0)^2 + C D^2 (sin(D/2) >= (D/2) sinc(x/2)), at least
    #   g^2 C / (beta^2 + C) whatever D (polar_gap)
    beta = abs(pe.b)
    C = rho_t * lo_e * (math.sin(0.5 * x) / (0.5 * x)) ** 2
    near = g * np.sqrt(C / (beta * beta + C))
    return _bound(pt, ends, np.minimum(near, chord), ub, tol)


def _bound(pt, ends, lbs, ub: float, tol: float):
    """The bound from the lower bounds ``lbs`` at ``t``'s ends (distances, so at
    least 0) and ``ub``, or ``None`` when they are not within ``tol``."""
    lbs = np.maximum(lbs, 0.0)
    k = int(np.argmax(lbs))
    lb = float(lbs[k])
    if ub - lb > tol:
        return None
    q = pt.eval(ends[k:k + 1])[0]
    return lb, ub, (float(q[0]), float(q[1]))
