"""A lead blend's cycle time as the comparison's planner gives it, and the
search that lowers it.

The objective. ``compare`` times a variant with the planner the limits call
for (TOPPRA under v and a, the jerk planner when they carry j, with the
job's ``ts``: :func:`ccopt.feed.certified_planner`), and a blend changes the
path only between the approach point and the host. The planners come to rest
at every tangent break and at both ends of a path, and the speed a profile
has far from a change does not depend on it: a profile that starts at rest
reaches any speed ``v`` within the distance :func:`settle_distance` gives, and
one that ends at rest leaves it within the same distance. So the cycle times
of two blends of one lead differ by exactly the times of the *window* around
the blend (:meth:`LeadTimer.window`: the blend plus :attr:`LeadTimer.reach`
of path on either side) whenever the two profiles meet again inside the
window. ``reach`` is :data:`SETTLE_SPANS` settle distances at the fastest
speed the tool can have there: one for the profile leaving the blend to come
up to that speed, one for the window's end (where the planner brings the
tool to rest), and one between them where the profiles of any two blends
run together. The window is planned by the very planner that times the
variants: no time model stands in for it. (``tests/formulations/
test_lead_timing.py`` checks that window times order blends as whole-path
cycle times do: exactly with TOPPRA, within the jerk planner's own duration
tolerance with it.)

The search. :func:`refine` starts from a model's solution (opt-casadi's or
opt-cvxpy's, a point that keeps the clearance rows) and lowers the window
time with Nelder-Mead over the blend's free control points and end legs
(the join ``sigma`` stays where the model put it), a blend that is not
regular, turns tighter than the curvature bound or comes nearer the contour
than its clearance at the check samples counting as infinitely slow. The
verifier has the last word, as for every blend
(:func:`ccopt_formulations.lead_setup.run_leads`), and the comparison only
keeps a blend whose whole-path cycle time beats the fastest controller's
(:mod:`ccopt.compare.baseline`).
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ccopt.compare.leads import Lead, split_segment, splice
from ccopt.errors import CcoptError
from ccopt.feed import certified_planner, plan_feed
from ccopt.feed.path import ExactPath
from ccopt.geometry import BezierCurve
from ccopt.toolpath import ToolPath

#: The window's reach on either side of a blend, in settle distances (module docstring).
SETTLE_SPANS = 3

#: Planner runs :func:`refine` may spend on one lead by default (Nelder-Mead
#: function evaluations; each plans a window: some 25 ms with TOPPRA, 75-150 ms
#: with the jerk planner). 0: no search, the model's blend as it is. The blend
#: option ``search`` sets it per comparison (``compare(..., options={"search":
#: 48})``). Off by default: on every bundled case the search multiplied the
#: comparison's time (the main job's by four) for gains of a few tenths of a
#: percent (bench/blends.py measures both).
SEARCH_EVALUATIONS = 0

#: Nelder-Mead stops when its simplex is this small relative to ``L0`` and its
#: window times agree to this share: below what the planners resolve, so the
#: budget of planner runs is what ends a search.
SEARCH_XTOL = 1e-9
SEARCH_FTOL = 1e-9

#: Nelder-Mead's first simplex: each free control point moved by this share of
#: the approach distance ``|J - A|``, each end leg by this share of itself.
SIMPLEX_STEP = 0.1


def settle_distance(v: float, a: float, j: float | None) -> float:
    """Distance (units) in which a time-optimal profile goes from rest to speed
    ``v`` (units/s) under tangential acceleration ``a`` (units/s^2) and, when
    given, jerk ``j`` (units/s^3): ``v^2 / (2 a)``, or for the jerk-limited
    S-curve (symmetric in time, so its mean speed is ``v / 2``) ``v T / 2``
    with ``T = v / a + a / j`` when it reaches ``a`` (``v >= a^2 / j``), else
    ``T = 2 sqrt(v / j)``."""
    if v <= 0.0:
        return 0.0
    if j is None:
        return v * v / (2.0 * a)
    T = v / a + a / j if v >= a * a / j else 2.0 * math.sqrt(v / j)
    return 0.5 * v * T


class LeadTimer:
    """Window times (s) of blends of one lead of ``path`` (see the module docstring).

    ``problem``: the :class:`~ccopt.compare.contract.BlendProblem` (its limits
    and ``ts``); ``path``: the path the blend is spliced into; ``lead`` the
    lead of it; ``style`` the variant's name."""

    def __init__(self, problem, path: ToolPath, lead: Lead, style: str):
        limits = problem.limits
        self.path, self.lead, self.style = path, lead, style
        self.limits, self.ts = limits, problem.ts
        self.planner = certified_planner(limits)
        v, a = limits.in_plane(path.plane, 2)
        j = limits.jerk_in_plane(path.plane, 2)
        segs = path.segments
        near = [segs[i] for i in (lead.first, lead.last, lead.host)]
        feeds = [s.feed for s in near if s.feed]
        vmax = float(np.hypot(*v))
        speed = min(max(feeds), vmax) if len(feeds) == len(near) else vmax
        #: Path length (units) on either side of the blend that the window holds.
        self.reach = SETTLE_SPANS * settle_distance(speed, float(np.min(a)),
                                           None if j is None else float(np.min(j)))
        self.evaluations = 0

    def candidate(self, geom, sigma: float) -> ToolPath:
        """The path with the blend ``geom`` joined at ``sigma``."""
        return splice(self.path, self.lead, [geom], sigma, style=self.style)

    def blend_indices(self, cand: ToolPath) -> tuple[int, int]:
        """First and last segment of ``cand`` that the splice made."""
        n_new = len(cand.segments) - len(self.path.segments) + \
            (self.lead.host - self.lead.first if self.lead.kind == "in"
             else self.lead.last - self.lead.host)
        first = self.lead.first if self.lead.kind == "in" else self.lead.host + 1
        return first, first + max(n_new, 1) - 1

    def window(self, cand: ToolPath) -> ToolPath:
        """The blend of ``cand`` with :attr:`reach` of path before and after it (a
        segment cut where the reach ends; a segment that moves the third axis
        is taken whole, never cut)."""
        segs = cand.segments
        b0, b1 = self.blend_indices(cand)
        before, need, i = [], self.reach, b0 - 1
        while i >= 0 and need > 0.0:
            s = segs[i]
            if s.length <= need or s.w0 != s.w1:
                before.append(s)
                need -= s.length
            else:
                before.append(split_segment(s, s.length - need)[1])
                need = 0.0
            i -= 1
        first = i + 1
        after, need, k = [], self.reach, b1 + 1
        while k < len(segs) and need > 0.0:
            s = segs[k]
            if s.length <= need or s.w0 != s.w1:
                after.append(s)
                need -= s.length
            else:
                after.append(split_segment(s, need)[0])
                need = 0.0
            k += 1
        window = before[::-1] + list(segs[b0:b1 + 1]) + after
        dwells = tuple((d - first, sec, blk) for d, sec, blk in cand.dwells
                       if first < d < first + len(window))
        return replace(cand, segments=tuple(window), dwells=dwells)

    def time(self, cand: ToolPath) -> float:
        """Planned time (s) of ``cand``'s window; ``inf`` when the planner refuses it."""
        self.evaluations += 1
        try:
            prof = plan_feed(ExactPath(self.window(cand)), self.limits, planner=self.planner,
                             ts=self.ts)
        except (CcoptError, ValueError):
            return math.inf
        return float(prof.duration)


def refine(setup, x0: np.ndarray, timer: LeadTimer, feasible,
           evaluations: int = SEARCH_EVALUATIONS):
    """``(x, info)``: the blend of ``setup`` (a
    :class:`~ccopt_formulations.lead_setup.LeadSetup`) with the lowest window
    time :func:`LeadTimer.time` found from ``x0`` in at most ``evaluations``
    planner runs; ``feasible(x) -> bool`` says whether a decision vector is a
    blend at all (regular, within the curvature bound, clear of the contour at
    the samples). ``x0`` itself is returned when nothing faster is found (or
    when ``x0`` is not feasible: nothing to start from)."""
    from scipy.optimize import minimize      # loaded only when a comparison searches

    x0 = np.asarray(x0, float)
    free = np.arange(len(x0) - 1) if setup.sigma_lo == setup.sigma_hi else np.arange(len(x0))
    seen: dict[bytes, float] = {}

    def full(z):
        x = x0.copy()
        x[free] = z
        return x

    def cost(z):
        x = full(z)
        key = x.tobytes()
        if key not in seen:
            if not feasible(x):
                seen[key] = math.inf
            else:
                seen[key] = timer.time(timer.candidate(BezierCurve(setup.controls(x)), float(x[-1])))
        return seen[key]

    t0 = cost(x0[free])
    info = {"window_time_model": t0, "window_time": t0, "planner_runs": 0}
    if not math.isfinite(t0):
        return x0, info
    lo, hi = setup.bounds()
    d = float(np.linalg.norm(setup.host_frame(float(x0[-1]))[0] - setup.A))
    steps = np.full(len(x0), SIMPLEX_STEP * d)
    steps[-3] = SIMPLEX_STEP * x0[-3]             # the end leg a
    simplex = np.vstack([x0[free]] + [x0[free] + np.eye(len(free))[i] * steps[free][i]
                                      for i in range(len(free))])
    res = minimize(cost, x0[free], method="Nelder-Mead",
                   bounds=list(zip(lo[free], hi[free])),
                   options={"maxfev": evaluations, "initial_simplex": simplex,
                            "xatol": SEARCH_XTOL * setup.L0, "fatol": SEARCH_FTOL * t0})
    best = min(seen, key=seen.get)
    info.update(window_time=seen[best], planner_runs=timer.evaluations,
                search_message=str(res.message))
    if seen[best] < t0:
        return np.frombuffer(best, dtype=float).copy(), info
    return x0, info
