"""``ToolPath``: the exact tool-centre path, segment by segment.

A :class:`ToolPath` is what compensation produces and what feed planning,
verification and export consume. Each :class:`PathSegment` holds one exact
in-plane primitive (``Line``, ``Arc``, ``Spiral`` from :mod:`ccopt.geometry`,
or a parametric blend curve), its :class:`Role`, the source :class:`Block` it
came from, the out-of-plane coordinate ``w`` at its start and end (carried
linearly along the segment, never offset) and its own plane.

In-plane coordinates are the segment plane's ``(u, v)`` (``X, Y`` for G17), see
:data:`ccopt.program.model.PLANE_AXES`. A program may compensate in one plane
and, after ``G40``, in another (LinuxCNC does): every segment knows its plane,
and :attr:`ToolPath.plane` is the first segment's.
"""
from __future__ import annotations

import enum
from dataclasses import dataclass, field, replace
from operator import attrgetter
from typing import Any, Iterator, Sequence

import numpy as np

from ccopt.errors import CompensationError
from ccopt.geometry import Arc, Line, Spiral, translated
from ccopt.geometry.columns import paused_gc
from ccopt.move_geometry import block_geometry, move_rows
from ccopt.program.columns import DWELL_CODE, columns_of
from ccopt.program.model import PLANE_AXES, Block, Motion, Program
from ccopt.tolerances import POINT_EPS


class Role(str, enum.Enum):
    """Why a segment is there."""

    RAPID = "rapid"
    LEAD_IN = "lead-in"
    COMPENSATED = "compensated"
    CORNER = "corner"
    LEAD_OUT = "lead-out"
    UNCOMPENSATED = "uncompensated"


#: ``ToolPath.meta`` key: indices of the segments that are arcs or lines fitted
#: to a spiral or blend curve (an exported path read back), not segments the
#: controller itself makes: e.g. a fitted arc with role ``corner`` is a piece
#: of a blend, not an added corner arc about a programmed corner.
FITTED_PIECES = "fitted_pieces"
#: ``ToolPath.meta`` key: the settings compensation made the path with, what
#: it knew beyond the program: ``{"radius": float | None, "side": int | None}``,
#: the cutter radius and side (+1 left, -1 right) that overrode the program's
#: (``None``: the program's own). With the blocks each segment carries, they
#: give every segment's side and radius in force
#: (:meth:`PathSegment.compensation`); the verifier reads them instead of
#: being told the overrides again, and the JSON schema carries them.
COMPENSATION = "compensation"
#: ``ToolPath.meta`` key: segment index -> corner angle (radians, > 0 turning
#: away from the tool side) of the tool segments that start at the previous
#: move's offset end because the controller took a slight turn as straight on
#: (LinuxCNC below ``LINUXCNC_CONCAVE_CORNER``): such a join gouges by up to
#: ``r (1 - cos angle)`` at an outside turn, and the verifier names it as the
#: cause of a gouge within tolerance.
STRAIGHT_JOINS = "straight_joins"
#: ``ToolPath.meta`` key of a lathe path's controlled-point moves
#: (:mod:`ccopt.compensate.lathe`): ``(segment index, how, du, dv)`` with how
#: ``"whole"``, ``"end"`` (entry), ``"start"`` (exit) or ``"added"`` (the
#: straight move LinuxCNC sends before an entry arc).
TOOL_TIP = "tool_tip"


def machine_point(plane: str, u: float, v: float, w: float) -> tuple[float, float, float]:
    """``(x, y, z)`` of the point with plane coordinates ``(u, v, w)`` in ``plane``."""
    xyz = [0.0, 0.0, 0.0]
    iu, iv, iw = PLANE_AXES[plane]
    xyz[iu], xyz[iv], xyz[iw] = u, v, w
    return (xyz[0], xyz[1], xyz[2])


def plane_point(plane: str, xyz) -> tuple[float, float, float]:
    """``(u, v, w)`` of the machine point ``xyz`` in ``plane``."""
    iu, iv, iw = PLANE_AXES[plane]
    return (float(xyz[iu]), float(xyz[iv]), float(xyz[iw]))


def segment_kind(geom: Any) -> str:
    """``"line" | "arc" | "spiral" | "curve"`` for a geometry object."""
    if isinstance(geom, Line):
        return "line"
    if isinstance(geom, Arc):
        return "arc"
    if isinstance(geom, Spiral):
        return "spiral"
    return "curve"


@dataclass(frozen=True, slots=True)
class PathSegment:
    """One exact piece of tool-centre path.

    Attributes
    ----------
    geom: the in-plane primitive, parameterised by arc length.
    role: :class:`Role`.
    block: the source block it came from (``None`` only for paths built by
        hand, e.g. in tests or blends not tied to one block).
    w0, w1: out-of-plane coordinate (Z for G17) at start and end.
    feed: tangential speed cap in program units per second, ``None`` for rapids.
    plane: ``"XY" | "ZX" | "YZ"``, the plane of ``geom``'s ``(u, v)``; left
        out (``None``), the block's plane, or without a block the plane of
        the :class:`ToolPath` it is put in.
    """

    geom: Any
    role: Role
    block: Block | None
    w0: float = 0.0
    w1: float = 0.0
    feed: float | None = None
    plane: str | None = None

    def __post_init__(self):
        if self.plane is None and self.block is not None:
            # the plane of the block it came from: every engine's segments
            # follow their block, so they need not say it
            object.__setattr__(self, "plane", self.block.modal.plane)

    @property
    def kind(self) -> str:
        return segment_kind(self.geom)

    @property
    def start(self) -> tuple[float, float]:
        return tuple(float(c) for c in self.geom.start)

    @property
    def end(self) -> tuple[float, float]:
        return tuple(float(c) for c in self.geom.end)

    @property
    def length(self) -> float:
        """In-plane length (program units)."""
        return float(self.geom.length)

    @property
    def start_xyz(self) -> tuple[float, float, float]:
        """Start in machine coordinates ``(x, y, z)`` (program units)."""
        u, v = self.start
        return machine_point(self.plane or "XY", u, v, float(self.w0))

    @property
    def end_xyz(self) -> tuple[float, float, float]:
        """End in machine coordinates ``(x, y, z)`` (program units)."""
        u, v = self.end
        return machine_point(self.plane or "XY", u, v, float(self.w1))

    @classmethod
    def trusted(cls, geom, role: Role, block: Block | None, w0: float, w1: float,
                feed: float | None, plane: str) -> "PathSegment":
        """The segment with every field given, ``plane`` included: the same
        object as the constructor makes, without the frozen dataclass's
        per-field ``__setattr__`` round trips (a column tool path makes its
        segments this way, one per row, when they are first asked for)."""
        obj = object.__new__(cls)
        _set_geom(obj, geom)
        _set_role(obj, role)
        _set_block(obj, block)
        _set_w0(obj, w0)
        _set_w1(obj, w1)
        _set_feed(obj, feed)
        _set_plane(obj, plane)
        return obj

    def compensation(self, overrides: dict | None = None) -> tuple[int, float | None]:
        """``(side, radius)`` in force for this segment's block (+1 left, -1
        right, 0 off; program units), after the ``overrides`` the path was made
        with (:data:`COMPENSATION`); ``(0, 0.0)`` without a block."""
        if self.block is None:
            return 0, 0.0
        o = overrides or {}
        return self.block.compensation_in_force(o.get("radius"), o.get("side"))

    def to_json(self, overrides: dict | None = None) -> dict:
        """The segment as the tool-path JSON schema (docs/commands.md, ``ccopt compensate``):
        in-plane ``start``/``end`` in its ``plane``, machine ``start_xyz``/``end_xyz``;
        ``side`` and ``radius_in_force`` of its block after ``overrides``
        (:meth:`compensation`), and ``surface: "air"`` for the moves
        compensation itself knows are no part surface (rapids, lead-ins,
        lead-outs, uncompensated moves)."""
        out: dict[str, Any] = {
            "kind": self.kind,
            "plane": self.plane,
            "start": list(self.start),
            "end": list(self.end),
            "start_xyz": list(self.start_xyz),
            "end_xyz": list(self.end_xyz),
            "role": self.role.value,
            "block": self.block.source.line if self.block is not None else None,
        }
        if self.w0 != 0.0 or self.w1 != 0.0:
            out["w"] = [self.w0, self.w1]
        g = self.geom
        if isinstance(g, (Arc, Spiral)):
            out["center"] = [float(g.center[0]), float(g.center[1])]
            out["ccw"] = bool(g.sweep > 0)
            out["sweep"] = float(g.sweep)
        if isinstance(g, Arc):
            out["radius"] = float(g.radius)
        elif isinstance(g, Spiral):
            out["radius"] = [float(g.rho0), float(g.rho1)]
        elif out["kind"] == "curve":
            out["control_points"] = [list(map(float, p)) for p in getattr(g, "control_points", ())]
            out["degree"] = int(getattr(g, "degree", 0))
        if self.feed is not None:
            out["feed"] = self.feed
        if self.block is not None:
            k, r = self.compensation(overrides)
            out["side"] = k
            out["radius_in_force"] = r
        if self.role in _AIR_ROLES:
            out["surface"] = "air"
        return out


#: Roles of segments that are no part surface whatever the program: the tool
#: is moving to or from the contour, or compensation is off.
_AIR_ROLES = frozenset((Role.RAPID, Role.LEAD_IN, Role.LEAD_OUT, Role.UNCOMPENSATED))

# the slots' own descriptors (PathSegment.trusted): no frozen __setattr__
_set_geom, _set_role, _set_block, _set_w0, _set_w1, _set_feed, _set_plane = (
    PathSegment.__dict__[name].__set__
    for name in ("geom", "role", "block", "w0", "w1", "feed", "plane"))

_FEED, _PLANE, _MODAL = attrgetter("feed"), attrgetter("modal.plane"), attrgetter("modal")
#: Row kinds of :class:`SegmentColumns`.
LINE_ROW, ARC_ROW, OBJECT_ROW = 0, 1, 2
#: Role codes of :class:`SegmentColumns` (index into this tuple).
ROLES: tuple[Role, ...] = tuple(Role)
ROLE_CODE = {role: code for code, role in enumerate(ROLES)}


@dataclass(frozen=True, eq=False)
class SegmentColumns:
    """A tool path's segments as columns, one row per segment, in order.

    What compensation of a long program makes: numbers in arrays, no Python
    object per segment; :class:`PathSegment` objects are made from the rows
    when the path's segments are first asked for (:meth:`materialise`).

    Attributes
    ----------
    kind: ``(n,)`` int, :data:`LINE_ROW`, :data:`ARC_ROW` or :data:`OBJECT_ROW`.
    geom: ``(n, 5)`` float, in-plane program units and radians: a line's
        ``(u0, v0, u1, v1, -)``, an arc's ``(cu, cv, radius, theta0, sweep)``
        (``sweep > 0`` counter-clockwise, as :class:`~ccopt.geometry.Arc`);
        unused for object rows.
    objects: row -> geometry object of the :data:`OBJECT_ROW` rows (spirals,
        curves, anything made one at a time).
    role: ``(n,)`` int, index into :data:`ROLES`.
    block: ``(n,)`` int, index into ``blocks`` of the source block (each
        segment's plane is its block's, and its feed unless ``feed`` says).
    blocks: the source blocks (shared with the program, not copied).
    w: ``(n, 2)`` float, out-of-plane coordinate at start and end.
    feed: per row, the feed (program units per second, ``None`` for a rapid)
        where it is not the row's block's: an exported path read back has
        the feeds read back on the computed path's blocks; ``None``: the
        blocks' feeds.

    Rows of lines and arcs must already be valid (finite, radius > 0): the
    maker checks them in bulk.
    """

    kind: np.ndarray
    geom: np.ndarray
    objects: dict
    role: np.ndarray
    block: np.ndarray
    blocks: Sequence[Block]
    w: np.ndarray
    feed: Sequence[float | None] | None = None

    def __len__(self) -> int:
        return int(self.kind.shape[0])

    def materialise(self) -> tuple[PathSegment, ...]:
        """Every row as its :class:`PathSegment`, in order."""
        with paused_gc():       # two objects per row, none in a cycle: see paused_gc
            return self._materialise()

    def _materialise(self) -> tuple[PathSegment, ...]:
        # column by column with map (the loops run in C): the geometries,
        # then the blocks, their feeds and planes, then the segments
        geoms: list = [None] * len(self)
        lines = np.flatnonzero(self.kind == LINE_ROW)
        g = self.geom[lines]
        for q, line in zip(lines.tolist(), map(Line.trusted, g[:, 0].tolist(), g[:, 1].tolist(),
                                                g[:, 2].tolist(), g[:, 3].tolist())):
            geoms[q] = line
        arcs = np.flatnonzero(self.kind == ARC_ROW)
        for q, (a, b, c, d, e) in zip(arcs.tolist(), self.geom[arcs].tolist()):
            geoms[q] = Arc((a, b), c, d, e)
        for q, obj in self.objects.items():
            geoms[q] = obj
        blocks = list(map(self.blocks.__getitem__, self.block.tolist()))
        feeds = map(_FEED, blocks) if self.feed is None else self.feed
        return tuple(map(PathSegment.trusted, geoms, map(ROLES.__getitem__, self.role.tolist()),
                         blocks, self.w[:, 0].tolist(), self.w[:, 1].tolist(),
                         feeds, map(_PLANE, blocks)))

    def planes(self) -> tuple[str, ...]:
        """The rows' planes (their blocks') in the order they first appear."""
        b = self.block
        if b.size < 2 or (b[1:] >= b[:-1]).all():
            # rows in their blocks' order (as compensation makes them): each
            # block's first row is where the index changes
            used = b[np.r_[True, b[1:] != b[:-1]]].tolist() if b.size else []
        else:
            _, first = np.unique(b, return_index=True)
            used = b[np.sort(first)].tolist()
        # the blocks' few distinct modal states, then their planes (map: loops
        # in C; the states come in runs, so only each run's first is looked at)
        modals = list(map(_MODAL, map(self.blocks.__getitem__, used)))
        ids = np.fromiter(map(id, modals), np.int64, len(modals))
        heads = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]]) if len(modals) else ids
        return tuple(dict.fromkeys(modals[q].plane for q in heads.tolist()))


@dataclass(frozen=True)
class ToolPath:
    """Tool-centre path: exact segments in order, plus dwells.

    Attributes
    ----------
    segments: tuple of :class:`PathSegment`.
    plane: ``"XY" | "ZX" | "YZ"``: the plane of the first segment (each
        segment has its own: :attr:`planes`). A segment that has no plane
        (built by hand, with no block) takes the plane given here.
    style: controller style that produced it (``"programmed"`` for the
        uncompensated programmed path).
    radius: cutter radius used (program units); 0 for the programmed path.
    dwells: ``(segment index before which the dwell happens, seconds, block)``.
    units: ``"mm" | "inch"``.
    """

    segments: tuple[PathSegment, ...]
    plane: str = "XY"
    style: str = "programmed"
    radius: float = 0.0
    dwells: tuple[tuple[int, float, Block], ...] = ()
    units: str = "mm"
    meta: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        segs = self.segments
        if any(s.plane is None for s in segs):
            segs = tuple(s if s.plane is not None else replace(s, plane=self.plane) for s in segs)
            object.__setattr__(self, "segments", segs)
        if segs and segs[0].plane != self.plane:
            object.__setattr__(self, "plane", segs[0].plane)

    @classmethod
    def from_columns(cls, columns: SegmentColumns, *, style: str, radius: float,
                     dwells: tuple = (), units: str = "mm", meta: dict | None = None,
                     plane: str = "XY") -> "ToolPath":
        """The tool path of ``columns`` (every row has a block); its
        :attr:`segments` are made from them on first use. ``plane`` is used
        only when there are no rows (otherwise the first row's block's)."""
        path = object.__new__(cls)
        if len(columns):
            plane = columns.blocks[int(columns.block[0])].modal.plane
        for name, value in (("plane", plane), ("style", style), ("radius", radius),
                            ("dwells", dwells), ("units", units),
                            ("meta", {} if meta is None else meta), ("_columns", columns)):
            object.__setattr__(path, name, value)
        return path

    def __getattr__(self, name: str):
        # Only reached for attributes not set: the segments of a path made
        # from columns, made (once) when first asked for.
        if name == "segments":
            columns = self.__dict__.get("_columns")
            if columns is not None:
                segments = columns.materialise()
                object.__setattr__(self, "segments", segments)
                return segments
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __getstate__(self) -> dict:
        # a column path pickles as its columns (its segments are remade)
        state = dict(self.__dict__)
        if "_columns" in state:
            state.pop("segments", None)
        return state

    @property
    def columns(self) -> SegmentColumns | None:
        """The segments as columns when the path was made from them, else ``None``."""
        return self.__dict__.get("_columns")

    def __iter__(self) -> Iterator[PathSegment]:
        return iter(self.segments)

    def __len__(self) -> int:
        columns = self.__dict__.get("_columns")
        if columns is not None and "segments" not in self.__dict__:
            return len(columns)
        return len(self.segments)

    def __getitem__(self, i):
        return self.segments[i]

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    @property
    def planes(self) -> tuple[str, ...]:
        """The segments' planes in the order they first appear (``(plane,)``
        for a path without segments)."""
        columns = self.__dict__.get("_columns")
        if columns is not None:         # the segments' planes are their rows' blocks'
            return columns.planes() or (self.plane,)
        return tuple(dict.fromkeys(s.plane for s in self.segments)) or (self.plane,)

    @property
    def compensation(self) -> dict | None:
        """The overrides compensation made the path with (:data:`COMPENSATION`),
        ``None`` for a path that does not say (a foreign path, one built by hand)."""
        return self.meta.get(COMPENSATION)

    def to_json(self) -> dict:
        out = {
            "style": self.style,
            "radius": self.radius,
            "plane": self.plane,
            "units": self.units,
        }
        overrides = self.compensation
        if overrides is not None:
            out["overrides"] = {"radius": overrides.get("radius"), "side": overrides.get("side")}
        out["segments"] = [s.to_json(overrides) for s in self.segments]
        return out


def effective_side_radius(block: Block, radius: float | None,
                          side: int | None) -> tuple[int, float]:
    """Side and radius in force for ``block`` after the overrides
    (:meth:`Block.compensation_in_force`; the same for every style).

    Raises :class:`~ccopt.errors.CompensationError` (located at the block)
    when compensation is on with no radius from the program or ``radius``,
    or with a negative one: whether that is an error depends on the
    overrides, so compensation judges it, not the reader.
    """
    k, r = block.compensation_in_force(radius, side)
    if r is None:
        tool = block.modal.tool
        if tool is not None:
            # G41/G42 D<n> names a tool: its diameter is in a tool table
            raise _located(block, f"no cutter radius: compensation is on with tool {tool}, whose "
                              f"diameter is not known: give a LinuxCNC tool table "
                              f"(--tool-table FILE) with tool {tool}, or pass --radius")
        raise _located(block, "cutter compensation is on but no cutter radius is set: program "
                          "CCR{r} (PMAC), a tool D word (G-code), $TC_DP6[t,d]={r} "
                          "(SINUMERIK) or TOOL DEF n R{r} (HEIDENHAIN), or pass --radius")
    if r < 0:
        raise _located(block, f"cutter radius {r:g} is negative")
    return k, r


def _located(block: Block, message: str) -> CompensationError:
    s = block.source
    return CompensationError(message, s.file, s.line, s.col)


def programmed_path(program: Program) -> ToolPath:
    """The programmed (uncompensated) path of a program as a :class:`ToolPath`.

    Rapids get role ``rapid``, feed moves ``uncompensated``; moves with no
    in-plane component are zero-length lines carrying their ``w`` change.
    A path of columns (:func:`~ccopt.move_geometry.move_rows`): its segments
    are made when first asked for, the same as :func:`programmed_segments`'.
    """
    try:
        rows = move_rows(program)
    except ValueError:
        rows = None         # a move its geometry refuses: the reference says which, and why
    if rows is None:
        return programmed_segments(program)
    kind = np.where(rows.arc, ARC_ROW, LINE_ROW).astype(np.int8)
    kind[list(rows.spirals)] = OBJECT_ROW
    role = np.where(rows.rapid, ROLE_CODE[Role.RAPID],
                    ROLE_CODE[Role.UNCOMPENSATED]).astype(np.int8)
    blocks = program.blocks
    columns = SegmentColumns(kind, rows.geom, rows.spirals, role, rows.move, blocks, rows.w)
    # a dwell comes before the moves after it: as many as moves before it
    dwell_at = np.flatnonzero(columns_of(program).motion_code == DWELL_CODE).tolist()
    dwells = tuple((q - k, blocks[q].dwell, blocks[q]) for k, q in enumerate(dwell_at))
    return ToolPath.from_columns(columns, style="programmed", radius=0.0, dwells=dwells,
                                 units=program.units, plane=_first_plane(program))


def programmed_segments(program: Program) -> ToolPath:
    """:func:`programmed_path` made segment by segment (:func:`block_geometry`
    of each move): the reference, and what reports a move it refuses."""
    segs: list[PathSegment] = []
    dwells: list[tuple[int, float, Block]] = []
    for b in program.blocks:
        if b.motion is Motion.DWELL:
            dwells.append((len(segs), b.dwell, b))
            continue
        role = Role.RAPID if b.motion is Motion.RAPID else Role.UNCOMPENSATED
        w0 = b.uvw(b.start)[2]
        w1 = b.uvw(b.end)[2]
        segs.append(PathSegment(block_geometry(b), role, b, w0, w1, b.feed))
    return ToolPath(tuple(segs), plane=_first_plane(program), style="programmed", radius=0.0,
                    dwells=tuple(dwells), units=program.units)


def _first_plane(program: Program) -> str:
    """The plane of ``program``'s first block, ``"XY"`` without blocks."""
    return program.blocks[0].modal.plane if program.blocks else "XY"


def starts_at_origin(path: ToolPath) -> bool:
    """Whether ``path`` starts at the machine origin, where ccopt's readers (so
    a program read back) take the tool to be before the first move: an export
    then needs no positioning move of its own."""
    if not path.segments:
        return True
    first = path.segments[0]
    return max(abs(first.start[0]), abs(first.start[1]), abs(first.w0)) <= POINT_EPS


def tool_centre_path(path: ToolPath) -> ToolPath:
    """The nose-centre path of a lathe path whose segments carry the
    controlled point (``meta[TOOL_TIP]``); ``path`` itself otherwise. What the
    verifier checks against the part: the nose radius is what cuts."""
    moved = path.meta.get(TOOL_TIP)
    if not moved:
        return path
    segments = list(path.segments)
    for i, how, du, dv in moved:
        seg = segments[i]
        g = seg.geom
        if how == "whole":
            g = translated(g, -du, -dv)
        elif how == "end":
            g = Line(g.p0, (g.p1[0] - du, g.p1[1] - dv))
        elif how == "start":
            g = Line((g.p0[0] - du, g.p0[1] - dv), g.p1)
        else:  # "added": the centre does not move
            g = Line(g.p0, g.p0)
        segments[i] = PathSegment(g, seg.role, seg.block, seg.w0, seg.w1, seg.feed, seg.plane)
    meta = {k: v for k, v in path.meta.items() if k != TOOL_TIP}
    return ToolPath(tuple(segments), plane=path.plane, style=path.style, radius=path.radius,
                    dwells=path.dwells, units=path.units, meta=meta)
