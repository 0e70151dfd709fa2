"""CasADi/IPOPT cross-check: a worst-case gouge search over the continuous path.

For each of the verifier's nearest (tool segment, contour element) pairs the
search minimises the squared distance between a point of the tool segment
and a point of the element over their continuous parameters ``u, v`` in
``[0, 1]``::

    min_{u, v}  | T(u) - E(v) |^2

Lines are ``p0 + u (p1 - p0)``; arcs and spirals ``c + rho(u) (cos th(u),
sin th(u))`` with ``rho`` linear in ``u`` (an arc has ``rho0 = rho1``), so one
model covers every kind through its parameters (a ``kind`` flag picks the
line or the polar form). All pairs go into one separable NLP (IPOPT solves
them together), started from the verifier's witnesses and from the segment
ends and middles; the smallest distance found per pair is kept. Where the
contour stops (an open end) only the parameter intervals of the tool segment
the verifier counts are searched (bounds on ``u``, :func:`allowed_intervals`).

IPOPT finds local minima, so its distances are upper bounds of the true
minimum: it must never report a deeper gouge (a smaller distance) than the
certificate's certified lower bound allows. :func:`crosscheck` (the
``ccopt.crosschecks`` entry point) reports that, and how close the search
came to the verifier's figures.

The model is built in one function (:func:`gouge_search_model`) and solved
in another (:func:`solve`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.angles import TWO_PI
from ccopt.verify.clearance import exempt_regions, in_regions

#: Parameters per curve: kind (1 line, 0 polar), p0x, p0y, p1x, p1y, cx, cy, rho0, rho1, th0, sweep.
NPAR = 11

#: The search may come below the certified lower bound by at most this (rounding).
SLACK = 1e-9

#: How many of the verifier's nearest pairs are searched.
PAIRS = 200

#: Pairs per NLP (one model, built once and reused; a separable sum).
BLOCK = 16

IPOPT_OPTIONS = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                 "ipopt.tol": 1e-14, "ipopt.max_iter": 200}


def curve_params(g) -> np.ndarray:
    """The ``NPAR`` parameters of a Line, Arc or Spiral."""
    p = np.zeros(NPAR)
    if isinstance(g, Line):
        p[0] = 1.0
        p[1:5] = (*g.p0, *g.p1)
        return p
    if isinstance(g, Arc):
        rho0 = rho1 = g.radius
    elif isinstance(g, Spiral):
        rho0, rho1 = g.rho0, g.rho1
    else:
        raise TypeError(f"the CasADi search takes lines, arcs and spirals, not {type(g).__name__}")
    p[5:11] = (*g.center, rho0, rho1, g.theta0, g.sweep)
    return p


def _point(u, p):
    line = ca.vertcat(p[1] + u * (p[3] - p[1]), p[2] + u * (p[4] - p[2]))
    rho = p[7] + u * (p[8] - p[7])
    th = p[9] + u * p[10]
    polar = ca.vertcat(p[5] + rho * ca.cos(th), p[6] + rho * ca.sin(th))
    return p[0] * line + (1 - p[0]) * polar


@dataclass
class Search:
    """A built NLP for ``n`` pairs: the CasADi solver and its size."""

    solver: ca.Function
    n: int


def gouge_search_model(n: int) -> Search:
    """Separable NLP over ``n`` (tool, element) pairs: variables ``(u_i, v_i)``,
    parameters ``2 * NPAR`` per pair, objective the sum of squared distances."""
    x = ca.SX.sym("x", 2 * n)
    p = ca.SX.sym("p", 2 * NPAR * n)
    f = 0
    for i in range(n):
        pt = p[2 * NPAR * i: 2 * NPAR * i + NPAR]
        pe = p[2 * NPAR * i + NPAR: 2 * NPAR * (i + 1)]
        d = _point(x[2 * i], pt) - _point(x[2 * i + 1], pe)
        f += ca.dot(d, d)
    solver = ca.nlpsol("gouge_search", "ipopt", {"x": x, "p": p, "f": f}, IPOPT_OPTIONS)
    return Search(solver, n)


def solve(search: Search, params: np.ndarray, x0: np.ndarray, lbx=None, ubx=None) -> np.ndarray:
    """Solve from ``x0``; returns ``(n, 2)`` parameters ``(u, v)``."""
    n = search.n
    lbx = np.zeros(2 * n) if lbx is None else lbx
    ubx = np.ones(2 * n) if ubx is None else ubx
    res = search.solver(x0=np.clip(x0, lbx, ubx), p=params, lbx=lbx, ubx=ubx)
    return np.asarray(res["x"], float).reshape(n, 2)


def _eval(p: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Numeric :func:`_point` for rows of parameters ``p`` at ``u``."""
    line = np.empty((u.size, 2))
    line[:, 0] = p[:, 1] + u * (p[:, 3] - p[:, 1])
    line[:, 1] = p[:, 2] + u * (p[:, 4] - p[:, 2])
    rho = p[:, 7] + u * (p[:, 8] - p[:, 7])
    th = p[:, 9] + u * p[:, 10]
    polar = np.empty((u.size, 2))
    polar[:, 0] = p[:, 5] + rho * np.cos(th)
    polar[:, 1] = p[:, 6] + rho * np.sin(th)
    return np.where(p[:, :1] > 0.5, line, polar)


def _param_of_point(g, w) -> float:
    """Parameter in [0, 1] of the point of ``g`` nearest ``w`` (the verifier's witness)."""
    if isinstance(g, Line):
        r = np.subtract(g.p1, g.p0)
        rr = float(r @ r)
        return float(np.clip(np.dot(np.subtract(w, g.p0), r) / rr, 0, 1)) if rr > 0 else 0.0
    ang = math.atan2(w[1] - g.center[1], w[0] - g.center[0])
    along = ((ang - g.theta0) * math.copysign(1.0, g.sweep)) % TWO_PI
    full = abs(g.sweep)
    if along > full:
        along = full if along - full < TWO_PI - along else 0.0
    return along / full if full > 0 else 0.0


def allowed_intervals(tool_geom, regions, samples: int = 2049) -> list[tuple[float, float]]:
    """Parameter intervals of ``tool_geom`` outside the exempt ``regions``
    (``ccopt.verify.clearance`` form: convex regions ``[(n, c), ...]``,
    ``n . q <= c``, closed, with the verifier's rounding allowance): membership
    on a dense grid, every boundary refined by bisection (all at once)."""
    if not regions:
        return [(0.0, 1.0)]
    p = curve_params(tool_geom)[None, :]

    def inside(u):
        u = np.atleast_1d(np.asarray(u, float))
        return in_regions(regions, _eval(np.repeat(p, u.size, axis=0), u))

    u = np.linspace(0.0, 1.0, samples)
    ins = inside(u)
    k = np.flatnonzero(ins[1:] != ins[:-1])
    lo, hi, a = u[k], u[k + 1], ins[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        same = inside(mid) == a
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    cuts = np.r_[0.0, 0.5 * (lo + hi), 1.0]
    keep = (cuts[1:] > cuts[:-1]) & ~inside(0.5 * (cuts[:-1] + cuts[1:]))
    return [(float(x), float(y)) for x, y in zip(cuts[:-1][keep], cuts[1:][keep])]


@lru_cache(maxsize=4)
def _block_model(n: int) -> Search:
    return gouge_search_model(n)


def search_pairs(tool_geoms, elem_geoms, intervals, starts) -> np.ndarray:
    """Smallest distance found per pair over all starts.

    ``tool_geoms``, ``elem_geoms``: primitives (one pair per row); ``intervals``:
    ``(lo, hi)`` bounds of the tool parameter per row; ``starts``: list of
    ``(n, 2)`` starting ``(u, v)`` (clipped into the bounds). Pairs are solved
    in blocks of :data:`BLOCK` (one cached NLP; the last block padded).
    """
    n = len(tool_geoms)
    pt = np.array([curve_params(g) for g in tool_geoms])
    pe = np.array([curve_params(g) for g in elem_geoms])
    lo = np.c_[np.asarray(intervals)[:, 0], np.zeros(n)]
    hi = np.c_[np.asarray(intervals)[:, 1], np.ones(n)]
    best = np.full(n, np.inf)
    search = _block_model(BLOCK)
    for b0 in range(0, n, BLOCK):
        idx = np.minimum(np.arange(b0, b0 + BLOCK), n - 1)      # pad with the last pair
        params = np.c_[pt[idx], pe[idx]].reshape(-1)
        for x0 in starts:
            x = np.clip(np.asarray(x0, float)[idx], lo[idx], hi[idx])
            uv = solve(search, params, x.reshape(-1), lo[idx].reshape(-1), hi[idx].reshape(-1))
            # IPOPT relaxes bounds slightly (bound_relax_factor): evaluate inside them
            uv = np.clip(uv, lo[idx], hi[idx])
            d = np.hypot(*(_eval(pt[idx], uv[:, 0]) - _eval(pe[idx], uv[:, 1])).T)
            np.minimum.at(best, idx, d)
    return best


def crosscheck(certificate) -> dict:
    """Entry point: IPOPT worst-case gouge search from the certificate's nearest pairs."""
    ctx = certificate.context
    if ctx is None or len(ctx.pairs) == 0:
        return {"name": "casadi", "agree": True, "pairs": 0,
                "summary": "no tool/contour pairs within reach: nothing to search"}
    P = ctx.pairs
    sel = ctx.nearest_pairs(PAIRS)
    C = ctx.contour
    open_elem = C.open_start | C.open_end
    tools, elems, ivals, owner, starts_uv = [], [], [], [], []
    for q in sel:
        i, j = int(P.tool[q]), int(P.elem[q])
        tg, eg = ctx.tool.geom(i), C.elements.geom(j)
        if not (isinstance(tg, (Line, Arc, Spiral)) and isinstance(eg, (Line, Arc, Spiral))):
            continue
        regions = exempt_regions(C, j) if open_elem[j] and isinstance(eg, (Line, Arc)) else []
        for iv in allowed_intervals(tg, regions):
            tools.append(tg)
            elems.append(eg)
            ivals.append(iv)
            owner.append(q)
            starts_uv.append((_param_of_point(tg, P.wt[q]), _param_of_point(eg, P.we[q])))
    if not tools:
        return {"name": "casadi", "agree": True, "pairs": 0, "summary": "no searchable pairs"}
    w = np.asarray(starts_uv)
    iv = np.asarray(ivals)
    m = len(tools)
    mid = 0.5 * (iv[:, 0] + iv[:, 1])
    starts = [w, np.c_[iv[:, 0], np.zeros(m)], np.c_[iv[:, 1], np.ones(m)],
              np.c_[mid, np.full(m, 0.5)], np.c_[iv[:, 0], np.ones(m)],
              np.c_[iv[:, 1], np.zeros(m)]]
    found = search_pairs(tools, elems, iv, starts)
    best = {}
    for q, d in zip(owner, found):
        best[q] = min(best.get(q, math.inf), float(d))
    qs = np.array(sorted(best))
    dfound = np.array([best[q] for q in qs])
    lb = P.d[qs]
    deeper = dfound < lb - SLACK
    worst_gap = float(np.max(lb - dfound))
    fin = np.isfinite(P.ub[qs])
    agreement = float(np.max(np.abs(dfound[fin] - P.ub[qs][fin]))) if fin.any() else 0.0
    margin = dfound - C.clearance[P.elem[qs]]
    deepest = max(0.0, -float(margin.min()))
    if deeper.any():
        summary = (f"IPOPT found {int(deeper.sum())} pairs closer than the certified minimum "
                   f"(by up to {worst_gap:.3g})")
    else:
        summary = (f"IPOPT searched {qs.size} nearest pairs from {len(starts)} starts: deepest "
                   f"gouge found {deepest:.9g}, never below the certified minimum by more than "
                   f"{SLACK:g}")
    return {
        "name": "casadi", "agree": bool(not deeper.any()), "pairs": int(qs.size),
        "deeper_than_certified": int(deeper.sum()),
        "largest_excess_below_bound": worst_gap,
        "max_abs_difference": agreement,
        "deepest_gouge_found": deepest,
        "summary": summary + f"; largest difference from the verifier's distances {agreement:.3g}",
    }
