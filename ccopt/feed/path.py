"""``ExactPath``: a :class:`~ccopt.toolpath.ToolPath` as a toppra geometric path.

The path parameter ``s`` is the arc length along the whole tool path in
program units, measured in 3-D when the out-of-plane axis ``w`` moves: a
segment with in-plane length ``L`` and ``w`` change ``dw`` has length
``S = hypot(L, dw)``, ``w`` runs linearly in in-plane arc length (so a Z
plunge, ``L = 0``, is parameterised by its ``w`` length). With this choice
``|q'(s)| = 1`` everywhere, so the path speed ``ds/dt`` *is* the tangential
feed, and ``|q''(s)|`` is the curvature of the 3-D path.

Positions and derivatives come from the exact primitives
(:mod:`ccopt.geometry`), never from a fit of sampled points::

    q(s)   = (geom.point(l),          w0 + dw * sigma / S)
    q'(s)  = (geom.d1(l) * L / S,     dw / S)
    q''(s) = (geom.d2(l) * (L / S)^2, 0)
    q'''(s) = (d3(l) * (L / S)^3, 0)      (order 3, for the jerk)

``d3`` is exact on lines (0), arcs (``-d1 / R^2``) and curves that give it
(``geom.d3``: Bezier curves); on other curves (spirals) it is the central
difference of ``d2`` over :data:`D3_STEP` of the in-plane length (relative),
one-sided within ``[0, L]`` at the ends.

with ``sigma = s - offset`` the 3-D arc length into the segment and
``l = sigma * L / S`` the in-plane arc length. Lines and arcs are evaluated by
vectorised kernels over all segments at once (the same formulas as
:class:`~ccopt.geometry.Line` and :class:`~ccopt.geometry.Arc`, checked
against them in the tests); spirals and other curves call their own methods.

At a segment boundary the path has two one-sided derivatives. ``__call__``
(what toppra calls) is right-continuous, and :meth:`ExactPath.eval_sided`
gives either side, so the constraints in :mod:`ccopt.feed.toppra.constraints`
evaluate each grid interval with its own segment's derivatives on both of its
ends: a curvature break (line to arc) lies exactly on a gridpoint and each
side is checked with its own curvature.

Segments shorter than :data:`ccopt.tolerances.POINT_EPS` (in 3-D) do not move
the tool and are left out. Coordinates are plane coordinates ``(u, v[, w])``;
``dof`` is 3 only when some segment moves ``w``. A path whose segments lie in
more than one plane (G17, then G18 after G40) is planned in machine
coordinates ``(x, y, z)`` instead (``frame`` :data:`~ccopt.feed.limits.MACHINE_FRAME`,
``dof`` 3): each segment's ``(u, v, w)`` go to its own plane's axes
(:data:`~ccopt.program.model.PLANE_AXES`), so every section is held to the
limits of the axes it moves.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ccopt.feed.limits import MACHINE_FRAME
from ccopt.feed.toppra.library import AbstractGeometricPath
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.bezier_batch import batches_by_degree
from ccopt.geometry.curve import RECENT_INVERSIONS, d2_from, d3_from, unit_tangent
from ccopt.program.model import PLANE_AXES
from ccopt.tolerances import GAP_EPS, POINT_EPS, TURN_EPS
from ccopt.toolpath import Role, ToolPath

_LINE, _ARC, _OTHER = 0, 1, 2

#: Step of the central difference of ``d2`` that gives ``q'''`` on curves other
#: than lines and arcs, relative to the segment's in-plane length: near the cube
#: root of the double precision, where truncation and rounding errors balance.
D3_STEP = 1e-5


@dataclass(frozen=True)
class Dwell:
    """A dwell at path position ``s`` (program units) lasting ``seconds``."""

    s: float
    seconds: float
    line: int | None


class ExactPath(AbstractGeometricPath):
    """The exact tool path, parameterised by (3-D) arc length.

    Attributes (arrays over the ``K`` moving segments, in order)
    ----------
    toolpath: the :class:`ToolPath` it was built from.
    frame: the coordinates: the plane of every segment (``"XY"``, ``"ZX"``,
        ``"YZ"``: ``(u, v[, w])``), or :data:`MACHINE_FRAME` ``(x, y, z)`` for
        a path in several planes; :meth:`AxisLimits.in_plane` takes it.
    segments: the moving :class:`~ccopt.toolpath.PathSegment` objects.
    source_index: index of each in ``toolpath.segments``.
    lengths: 3-D lengths ``S``; ``offsets``: ``K + 1`` cumulative positions.
    feeds: programmed tangential speed cap (units/s), ``inf`` for rapids.
    start_tangent, end_tangent: ``(K, dof)`` unit tangents ``q'``.
    tangent_break: ``(K + 1,)`` True at the interior boundaries where the
        tangent is discontinuous (turn above :data:`TURN_EPS`, a reversal,
        or a gap above :data:`GAP_EPS`); the ends are False.
    dwells: tuple of :class:`Dwell`.

    ``axes``: the coordinates of the path this one is a stretch of,
    ``(machine_frame, dof)`` (:attr:`axes`); ``None``: its own. A stretch
    between two stops, planned alone in the whole path's coordinates, is
    planned as within the whole path: the planners' grids read the slowest
    and largest limits of the path's axes (a stretch that moves no ``w`` of
    a path that does would be gridded with the ``w`` axis's limits left out,
    and come out up to 0.1 % apart).
    """

    def __init__(self, toolpath: ToolPath, axes: tuple[bool, int] | None = None):
        super().__init__()
        self.toolpath = toolpath
        keep, S, L, dw = [], [], [], []
        for i, seg in enumerate(toolpath.segments):
            l_in = float(seg.geom.length)
            d = float(seg.w1) - float(seg.w0)
            s3 = math.hypot(l_in, d)
            if s3 > POINT_EPS:
                keep.append(i)
                S.append(s3)
                L.append(l_in)
                dw.append(d)
        self.segments = tuple(toolpath.segments[i] for i in keep)
        self.source_index = np.array(keep, dtype=int)
        self.lengths = np.array(S, dtype=float)
        self._L = np.array(L, dtype=float)
        self._dw = np.array(dw, dtype=float)
        self._w0 = np.array([float(s.w0) for s in self.segments])
        self._ratio = np.divide(self._L, self.lengths, out=np.zeros(len(S)),
                                where=self.lengths > 0)
        self.offsets = np.concatenate([[0.0], np.cumsum(self.lengths)])
        planes = set(s.plane for s in toolpath.segments)
        machine, dof = (False, 2) if axes is None else axes
        self._perm = None       # (K, 3): machine axis of each segment's (u, v, w)
        if len(planes) > 1 or machine:
            self.frame = MACHINE_FRAME
            self._perm = np.array([PLANE_AXES[s.plane] for s in self.segments], int
                                  ).reshape(-1, 3)
        else:
            self.frame = planes.pop() if planes else toolpath.plane
        self._dof = 3 if self._perm is not None or np.any(self._dw != 0.0) or dof == 3 else 2
        self.feeds = np.array([np.inf if (s.feed is None or s.role is Role.RAPID) else float(s.feed)
                               for s in self.segments])
        self._prepare_kernels()
        K = len(self.segments)
        if K:
            self.start_tangent = self._segment_tangents(at_end=False)
            self.end_tangent = self._segment_tangents(at_end=True)
        else:
            self.start_tangent = self.end_tangent = np.zeros((0, self._dof))
        self.tangent_break = np.zeros(K + 1, dtype=bool)
        self.turn_cos = np.ones(K + 1)
        if K > 1:
            t_in, t_out = self.end_tangent[:-1], self.start_tangent[1:]
            dot = np.einsum("ij,ij->i", t_in, t_out)
            if self._dof == 2:
                cross = np.abs(t_in[:, 0] * t_out[:, 1] - t_in[:, 1] * t_out[:, 0])
            else:
                cross = np.linalg.norm(np.cross(t_in, t_out), axis=1)
            inner = self.offsets[1:-1]
            ends_out = self.eval_segments(np.arange(K - 1), inner, 0)
            starts_in = self.eval_segments(np.arange(1, K), inner, 0)
            gap = np.linalg.norm(ends_out - starts_in, axis=1)
            self.tangent_break[1:-1] = (cross > TURN_EPS) | (dot <= 0.0) | (gap > GAP_EPS)
            self.turn_cos[1:-1] = dot
        self.dwells = self._map_dwells()

    # -- toppra's interface --------------------------------------------------

    @property
    def dof(self) -> int:
        return self._dof

    @property
    def axes(self) -> tuple[bool, int]:
        """``(machine_frame, dof)``: the coordinates a stretch of this path is
        planned in (the constructor's ``axes``)."""
        return self._perm is not None, self._dof

    @property
    def path_interval(self) -> np.ndarray:
        return np.array([0.0, float(self.offsets[-1])])

    @property
    def waypoints(self):
        """``(offsets, positions)`` of the segment boundaries."""
        if not self.segments:
            return None
        return self.offsets, self(self.offsets)

    def __call__(self, path_positions, order: int = 0) -> np.ndarray:
        """Position (``order`` 0), ``q'`` (1) or ``q''`` (2) at arc lengths ``s``.

        Right-continuous at segment boundaries (the last point belongs to the
        last segment). A scalar gives shape ``(dof,)``, an array ``(N, dof)``.
        """
        return self.eval_sided(path_positions, order, "right")

    def get_duration(self) -> float:
        """Length of the path (toppra's C++-era wrappers ask for it)."""
        return float(self.offsets[-1])

    # -- evaluation ----------------------------------------------------------

    @property
    def length(self) -> float:
        return float(self.offsets[-1])

    def locate(self, s, side: str = "right") -> np.ndarray:
        """Segment index of each ``s``; ``side`` picks the segment at a boundary."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        K = len(self.segments)
        if side == "right":
            k = np.searchsorted(self.offsets, s, side="right") - 1
        elif side == "left":
            k = np.searchsorted(self.offsets, s, side="left") - 1
        else:
            raise ValueError(f"side must be 'left' or 'right', not {side!r}")
        return np.clip(k, 0, K - 1)

    def eval_sided(self, s, order: int = 0, side: str = "right") -> np.ndarray:
        """Like ``__call__`` but choosing the ``left`` or ``right`` limit at boundaries."""
        return self.eval_sided_orders(s, (order,), side)[0]

    def eval_sided_orders(self, s, orders, side: str = "right") -> list[np.ndarray]:
        """:meth:`eval_sided` of each of ``orders`` at the same positions, the
        positions located once (:meth:`eval_orders`)."""
        if not self.segments:
            raise ValueError("the path has no motion")
        scalar = np.ndim(s) == 0
        s1 = np.atleast_1d(np.asarray(s, dtype=float))
        outs = self.eval_orders(self.locate(s1, side), s1, orders)
        return [out[0] for out in outs] if scalar else outs

    def eval_segments(self, k, s, order: int = 0) -> np.ndarray:
        """The position or its first, second or third derivative by path length
        (``order`` 0-3) at path positions ``s`` taken on segments ``k``.

        ``s`` is clipped into each segment, so ``s`` at a boundary evaluates
        the end of segment ``k`` exactly whichever side it lies on.
        """
        return self.eval_orders(k, s, (order,))[0]

    def eval_orders(self, k, s, orders) -> list[np.ndarray]:
        """:meth:`eval_segments` of each of ``orders`` at the same positions, in
        one pass: the positions' offsets into their segments, each arc's angle,
        cosine and sine, and each Bezier curve's parameter and derivatives are
        computed once for all the orders. Each result is the one
        :meth:`eval_segments` gives for its order alone, bit for bit (the same
        arithmetic on the same arrays)."""
        for order in orders:
            if order not in (0, 1, 2, 3):
                raise ValueError(f"order must be 0, 1, 2 or 3, not {order!r}")
        k = np.asarray(k, dtype=int)
        s = np.asarray(s, dtype=float)
        sigma = np.clip(s - self.offsets[k], 0.0, self.lengths[k])
        lam = sigma * self._ratio[k]
        outs = [np.empty((s.size, self._dof)) for _ in orders]
        kind = self._kind[k]
        sel = np.flatnonzero(kind == _LINE)
        if sel.size:
            for out, order in zip(outs, orders):
                out[sel, :2] = self._line_kernel(k[sel], lam[sel], order)
        sel = np.flatnonzero(kind == _ARC)
        if sel.size:
            for out, q in zip(outs, self._arc_kernel(k[sel], lam[sel], orders)):
                out[sel, :2] = q
        sel = np.flatnonzero(kind == _OTHER)
        if sel.size and self._batches:
            bez = self._bezier[k[sel]]
            for b in range(len(self._batches)):
                rows = sel[bez == b]
                if rows.size:
                    got = self._bezier_kernel(b, k[rows], lam[rows], orders)
                    for out, order, q in zip(outs, orders, got):
                        out[rows, :2] = q * (self._ratio[k[rows]] ** order)[:, None]
            sel = sel[bez < 0]
        if sel.size:
            ks = k[sel]
            order_idx = np.argsort(ks, kind="stable")
            ks_sorted = ks[order_idx]
            cuts = np.flatnonzero(np.diff(ks_sorted)) + 1
            for grp in np.split(order_idx, cuts):
                kk = int(ks[grp[0]])
                rows = sel[grp]
                for out, order in zip(outs, orders):
                    out[rows, :2] = self._curve_rows(kk, lam[rows], order)
        return [self._placed(out, k, s, sigma, order) for out, order in zip(outs, orders)]

    def _curve_rows(self, kk: int, lam: np.ndarray, order: int) -> np.ndarray:
        """``order`` of segment ``kk``'s curve (one in no batch) at in-plane arc
        lengths ``lam``, by path length."""
        geom = self.segments[kk].geom
        r = self._ratio[kk]
        if order == 0:
            return geom.point(lam)
        if order == 1:
            return geom.d1(lam) * r
        if order == 2:
            return geom.d2(lam) * (r * r)
        if hasattr(geom, "d3"):  # exact where the curve has it (Bezier curves)
            return geom.d3(lam) * r ** 3
        return _d3_by_difference(geom, lam, self._L[kk]) * r ** 3

    def _placed(self, out: np.ndarray, k, s, sigma, order: int) -> np.ndarray:
        """``out`` (its in-plane columns filled) with its ``w`` column, in machine axes."""
        if self._dof == 3:
            if order == 0:
                out[:, 2] = self._w0[k] + self._dw[k] * (sigma / self.lengths[k])
            elif order == 1:
                out[:, 2] = self._dw[k] / self.lengths[k]
            else:
                out[:, 2] = 0.0
        if self._perm is not None:
            # (u, v, w) of each segment's plane to machine (x, y, z)
            placed = np.empty_like(out)
            rows = np.arange(out.shape[0])[:, None]
            placed[rows, self._perm[np.broadcast_to(k, s.shape).reshape(-1)]] = out
            return placed
        return out

    def eval_in_plane(self, k, s, order: int = 0) -> np.ndarray:
        """``(N, 2)``: the in-plane ``(u, v)`` part of :meth:`eval_segments`, in
        each segment's own plane (what turns within the plane)."""
        q = self.eval_segments(k, s, order)
        if self._perm is None:
            return q[:, :2]
        kk = np.broadcast_to(np.asarray(k, dtype=int), np.shape(s)).reshape(-1)
        return np.take_along_axis(q, self._perm[kk][:, :2], axis=1)

    def curvature_norm(self, k, s) -> np.ndarray:
        """``|q''|`` (curvature of the 3-D path, 1/units) at ``s`` on segments ``k``."""
        return np.linalg.norm(self.eval_segments(k, s, 2), axis=1)

    @property
    def in_plane_ratio(self) -> np.ndarray:
        """``(K,)`` in-plane length over 3-D length of each segment, ``L / S`` (1 in the plane)."""
        return self._ratio

    @property
    def constant_curvature(self) -> np.ndarray:
        """``(K,)`` True for segments of constant curvature, whose turning is spread
        evenly along them: lines, arcs, and segments with no in-plane motion."""
        return (self._kind != _OTHER) | (self._L == 0.0)

    @property
    def uniform_turning(self) -> np.ndarray:
        """``(K,)`` in-plane turning (radians) of the constant-curvature segments:
        ``|sweep|`` for arcs, 0 for lines, and 0 for every other segment (whose
        turning is not uniform: see :mod:`ccopt.feed.grid`)."""
        return np.where(self._kind == _ARC, np.abs(self._sweep), 0.0)

    def turning(self, k: int) -> float:
        """Total turning of the tangent along segment ``k`` (radians), for grid density."""
        geom = self.segments[k].geom
        if isinstance(geom, Line):
            return 0.0
        if isinstance(geom, (Arc, Spiral)):
            return abs(geom.sweep)
        s = np.linspace(0.0, float(geom.length), 257)
        kappa = np.abs(np.asarray(geom.curvature(s), dtype=float))
        trapezoid = getattr(np, "trapezoid", None) or np.trapz  # numpy 2 renamed it
        return float(trapezoid(kappa, s))

    def block_line(self, s: float) -> int | None:
        """Source line of the block the path is in at ``s`` (``None`` if unknown)."""
        if not self.segments:
            return None
        blk = self.segments[int(self.locate(s)[0])].block
        return blk.source.line if blk is not None else None

    @property
    def source_file(self) -> str:
        for seg in self.toolpath.segments:
            if seg.block is not None:
                return seg.block.source.file
        for _, _, blk in self.toolpath.dwells:
            return blk.source.file
        return "<toolpath>"

    def stretch(self, s0: float, s1: float) -> ToolPath:
        """The tool path from position ``s0`` to ``s1`` (stops or ends, so
        segment boundaries; each taken as the nearest one), with the dwells
        strictly inside it."""
        k0, k1 = self.boundary(s0), self.boundary(s1)
        i0, i1 = int(self.source_index[k0]), int(self.source_index[k1 - 1]) + 1
        tp = self.toolpath
        dwells = tuple((before - i0, seconds, blk) for before, seconds, blk in tp.dwells
                       if i0 < before < i1)
        return replace(tp, segments=tp.segments[i0:i1], dwells=dwells)

    def boundary(self, s: float) -> int:
        """Index of the segment boundary nearest ``s``."""
        k = int(np.searchsorted(self.offsets, s))
        if k > 0 and (k == self.offsets.size or s - self.offsets[k - 1] < self.offsets[k] - s):
            k -= 1
        return k

    @property
    def stop_positions(self) -> np.ndarray:
        """Interior path positions where the path must stop: tangent breaks and dwells."""
        pos = set(self.offsets[self.tangent_break].tolist())
        pos.update(d.s for d in self.dwells)
        return np.array(sorted(pos), dtype=float)

    # -- internals -----------------------------------------------------------

    def _prepare_kernels(self) -> None:
        K = len(self.segments)
        self._kind = np.full(K, _OTHER, dtype=np.int8)
        self._p0 = np.zeros((K, 2))
        self._p1 = np.zeros((K, 2))
        self._dir = np.zeros((K, 2))
        self._c = np.zeros((K, 2))
        self._R = np.ones(K)
        self._th0 = np.zeros(K)
        self._sweep = np.zeros(K)
        self._sg = np.ones(K)
        for i, seg in enumerate(self.segments):
            g = seg.geom
            if type(g) is Line:
                self._kind[i] = _LINE
                self._p0[i], self._p1[i], self._dir[i] = g.p0, g.p1, g.direction
            elif type(g) is Arc:
                self._kind[i] = _ARC
                self._c[i], self._R[i] = g.center, g.radius
                self._th0[i], self._sweep[i] = g.theta0, g.sweep
                self._sg[i] = 1.0 if g.sweep > 0 or (g.sweep == 0 and math.copysign(1, g.sweep) > 0) \
                    else -1.0
        self._prepare_beziers()

    def _prepare_beziers(self) -> None:
        """The Bezier curves among the segments in batches, one per degree
        (:class:`~ccopt.geometry.bezier_batch.BezierBatch`): ``_bezier[k]`` is
        segment ``k``'s batch number (-1: none) and ``_bezier_row[k]`` its row."""
        self._bezier, self._bezier_row, self._batches = batches_by_degree(
            [seg.geom for seg in self.segments])
        self._recent_t: dict = {}

    def _bezier_kernel(self, b: int, k, lam, orders) -> list[np.ndarray]:
        """Points or derivatives (each of ``orders``) by in-plane arc length of
        the Bezier segments ``k`` (all in batch ``b``), as their curves' own
        methods give them."""
        batch, rows = self._batches[b], self._bezier_row[k]
        # toppra and the jerk planner ask for several orders (and both sides) at
        # the same positions one after the other: the inversions are kept
        key = (b, rows.tobytes(), lam.tobytes())
        t = self._recent_t.get(key)
        if t is None:
            t = batch.t_of_s(rows, lam)
            if len(self._recent_t) >= RECENT_INVERSIONS:
                self._recent_t.pop(next(iter(self._recent_t)))   # the oldest
            self._recent_t[key] = t
        top = max(orders)
        # each derivative of r as the batch gives it, whichever orders are asked
        r = batch.derivatives(rows, t, top) if top > 0 else []
        out = []
        for order in orders:
            if order == 0:
                out.append(batch.at("P", rows, t))
            elif order == 1:
                out.append(unit_tangent(r[0]))
            elif order == 2:
                out.append(d2_from(r[0], r[1]))
            else:
                out.append(d3_from(r[0], r[1], r[2]))
        return out

    def _line_kernel(self, k, lam, order):
        # Same formulas as Line.point/d1/d2: (1-t) p0 + t p1 hits both ends exactly.
        if order == 0:
            Lk = self._L[k]
            t = np.divide(lam, Lk, out=np.zeros_like(lam), where=Lk > 0)[:, None]
            return (1.0 - t) * self._p0[k] + t * self._p1[k]
        if order == 1:
            return self._dir[k] * self._ratio[k][:, None]
        return np.zeros((k.size, 2))   # q'' and q''' of a line

    def _arc_kernel(self, k, lam, orders) -> list[np.ndarray]:
        # Same formulas as Arc.point/d1/d2 (phi = theta0 + sweep * l / L); the
        # angle, its cosine and its sine once for all the orders asked.
        Lk = self._L[k]
        phi = self._th0[k] + self._sweep[k] * np.divide(lam, Lk, out=np.zeros_like(lam),
                                                         where=Lk > 0)
        c, s = np.cos(phi), np.sin(phi)
        outs = []
        for order in orders:
            out = np.empty((k.size, 2))
            if order == 0:
                out[:, 0] = self._c[k, 0] + self._R[k] * c
                out[:, 1] = self._c[k, 1] + self._R[k] * s
            elif order == 1:
                f = self._sg[k] * self._ratio[k]
                out[:, 0] = -f * s
                out[:, 1] = f * c
            elif order == 3:
                # d3 = -d1 / R^2 on a circle
                f = -self._sg[k] * self._ratio[k] ** 3 / self._R[k] ** 2
                out[:, 0] = -f * s
                out[:, 1] = f * c
            else:
                f = self._ratio[k] ** 2 / self._R[k]
                out[:, 0] = -c * f
                out[:, 1] = -s * f
            outs.append(out)
        return outs

    def _segment_tangents(self, at_end: bool) -> np.ndarray:
        k = np.arange(len(self.segments))
        s = self.offsets[1:] if at_end else self.offsets[:-1]
        t = self.eval_segments(k, s, 1)
        n = np.linalg.norm(t, axis=1, keepdims=True)
        return np.divide(t, n, out=np.zeros_like(t), where=n > 0)

    def _map_dwells(self) -> tuple[Dwell, ...]:
        out = []
        for before, seconds, blk in self.toolpath.dwells:
            # first kept segment at or after the toolpath index ``before``
            j = int(np.searchsorted(self.source_index, before, side="left"))
            out.append(Dwell(float(self.offsets[j]), float(seconds),
                             blk.source.line if blk is not None else None))
        return tuple(out)


def _d3_by_difference(geom, lam: np.ndarray, length: float) -> np.ndarray:
    """``d(d2)/dl`` of a plane curve at in-plane arc lengths ``lam`` by central
    differences over :data:`D3_STEP` of ``length`` (one-sided at the ends)."""
    h = D3_STEP * max(length, POINT_EPS)
    lo = np.clip(lam - h, 0.0, length)
    hi = np.clip(lam + h, 0.0, length)
    span = np.where(hi > lo, hi - lo, 1.0)[:, None]
    return (np.asarray(geom.d2(hi)).reshape(-1, 2) - np.asarray(geom.d2(lo)).reshape(-1, 2)) / span
