"""The immutable ``Program``: what a part program asks for, dialect-free.

A reader (``gcode``, ``pmac``) turns text into a :class:`Program`: a tuple of
:class:`Block` objects, one per executed move or dwell, in execution order
(subroutine calls and loops already expanded). Each block carries

* its source location (file, line, column of the first word),
* the motion (rapid, line, clockwise/counter-clockwise arc, dwell),
* start and end in absolute machine coordinates ``(x, y, z)`` in program
  units (mm or inch, see :attr:`Program.units`),
* for arcs, the absolute centre and extra full turns,
* the feed as a tangential speed in program units **per second** (readers
  convert G-code ``F`` per minute, G93 inverse time and PMAC ``F`` here, once),
* the modal state that matters to compensation (:class:`Modal`).

Conventions
-----------
* Plane of compensation: ``"XY"`` (G17, PMAC ``NORMAL K-1``), ``"ZX"`` (G18,
  ``NORMAL J-1``), ``"YZ"`` (G19, ``NORMAL I-1``). In-plane coordinates
  ``(u, v)`` and the normal ``w`` are given by :data:`PLANE_AXES`; arcs turn
  counter-clockwise when seen looking down ``w`` (right-handed ``u, v, w``).
* Side: ``+1`` left (G41, CC1), ``-1`` right (G42, CC2), ``0`` off.
* Angles are radians inside ccopt.
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field, replace
from typing import Iterator

from ccopt.tolerances import POINT_EPS

Vec3 = tuple[float, float, float]

#: In-plane axes (u, v) and normal axis w, as indices into (x, y, z).
PLANE_AXES: dict[str, tuple[int, int, int]] = {
    "XY": (0, 1, 2),
    "ZX": (2, 0, 1),
    "YZ": (1, 2, 0),
}

#: Largest magnitude of a coordinate, centre, centre offset (I J K), radius
#: (R), feed or tool diameter a program may hold, in program units (feeds:
#: units per minute as written, units per second as stored): 1e6, a
#: kilometre in mm (25 km in inches). The largest machine tools travel tens
#: of metres, and a feed of 1e6 mm/min (17 m/s) is beyond any axis. A value
#: past it is a typing error (a missing decimal point, ``X1000000000``), not
#: a part: the feed planner and the comparison take minutes and gigabytes on
#: it (a line to 1e9 took ``ccopt compare`` 24 s and 6.8 GB, issue 29), and
#: near 1e9 the doubles downstream keep too few digits for micrometre
#: checks. The readers refuse it where it is written, as a located error
#: (``part.nc:3:4: X1000000000 is out of range: ...``), so every command
#: stops at once. It was :data:`MAX_COORDINATE` (1e9) until issue 29.
MAX_PROGRAM_COORDINATE = 1e6

#: Largest magnitude of a length, time or rate given on the command line or
#: in a ``case.toml`` (``--radius``, ``--eps``, ``radius = ...``): 1e9.
#: Beyond, the geometry's work and the doubles' precision run out. A
#: program's own values are bounded tighter, by :data:`MAX_PROGRAM_COORDINATE`.
MAX_COORDINATE = 1e9


#: ``Program.meta`` key, True when the reader has itself refused every plane
#: change made while cutter compensation was on, where the plane word stands
#: (the G-code reader, as LinuxCNC's interpreter). A move after such a change
#: may then have compensation on on both sides (``G40``, ``G18``, ``G41``
#: between two moves). Without it the compensation engines judge from the
#: blocks alone and refuse a plane change next to any compensated move.
PLANE_CHANGES_CHECKED = "plane_changes_checked"


#: ``Program.meta`` key: the files a program was read from (the program, its
#: subroutine files, tool table and parameter file), set by
#: :func:`ccopt.program.read_program` (the G-code reader records the
#: subroutine files it read); no output may write over one of them
#: (:mod:`ccopt.atomic`, :func:`ccopt.cases.ReadOptions.read`).
INPUT_FILES = "input_files"


#: What the commands say of a program with no move (:meth:`Program.nothing_to_verify`).
NOTHING_TO_VERIFY = "nothing to verify: the program has no moves"


def out_of_range(value: float) -> bool:
    """``value`` is not finite or beyond :data:`MAX_PROGRAM_COORDINATE` in magnitude
    (a value a program may not hold)."""
    return not abs(value) <= MAX_PROGRAM_COORDINATE


class Motion(str, enum.Enum):
    """What a block does. ``ARC_CW``/``ARC_CCW`` are seen in the block's plane."""

    RAPID = "rapid"
    LINE = "line"
    ARC_CW = "cw"
    ARC_CCW = "ccw"
    DWELL = "dwell"

    @property
    def is_arc(self) -> bool:
        return self in (Motion.ARC_CW, Motion.ARC_CCW)

    @property
    def is_move(self) -> bool:
        return self is not Motion.DWELL


@dataclass(frozen=True, slots=True)
class Source:
    """Where a block came from: file name, 1-based line and column."""

    file: str
    line: int
    col: int = 1

    def __str__(self) -> str:
        return f"{self.file}:{self.line}"


@dataclass(frozen=True, slots=True)
class SmoothApproach:
    """A SINUMERIK smooth approach or retraction (SAR) asked for on its block.

    Attributes
    ----------
    kind: ``"G147"``/``"G148"`` straight line, ``"G247"``/``"G248"`` quadrant,
        ``"G347"``/``"G348"`` semicircle (approach / retraction).
    direction: ``"G140"`` (the compensation side), ``"G141"`` (from/to the
        left), ``"G142"`` (right), ``"G143"`` (by the start or end point's
        side of the contour's tangent).
    infeed: ``"G340"`` (in space: the approach curve may be a helix) or
        ``"G341"`` (the infeed perpendicular to the plane first).
    disr: ``DISR``, program units (line: cutter edge to contour start; arc:
        radius of the tool-centre path).
    discl: ``DISCL`` as a distance above the machining plane (program units),
        or ``None`` when not programmed.
    discl_abs: ``DISCL=AC(..)`` as the machine coordinate along the plane
        normal, or ``None``.
    fad: ``FAD`` as a feed in program units per second, or ``None``.
    feed: the feed of the approach curve (the ``F`` in force, units per
        second: the curve runs at the feed even when the block is ``G0``), or
        ``None`` (the block's).
    infeed_feed: the feed of the moves P0 -> P3, the one in force before the
        block (``None``: rapid, when ``G0`` was in force).
    """

    kind: str
    direction: str = "G140"
    infeed: str = "G340"
    disr: float = 0.0
    discl: float | None = None
    discl_abs: float | None = None
    fad: float | None = None
    feed: float | None = None
    infeed_feed: float | None = None

    @property
    def approach(self) -> bool:
        return self.kind in ("G147", "G247", "G347")


@dataclass(frozen=True, slots=True)
class SiemensModes:
    """SINUMERIK 840D compensation modes in force for a block (the
    ``sinumerik`` reader sets them; other readers leave ``Modal.siemens``
    ``None``, which the ``siemens`` style reads as the defaults).

    Attributes
    ----------
    corner: ``"G450"`` transition circle (default) or ``"G451"`` intersection.
    disc: ``DISC`` 0..100 (deforms the G450 circle toward the intersection).
    approach: ``"NORM"`` (default), ``"KONT"``, ``"KONTT"`` or ``"KONTC"``.
    bottleneck: ``"CDON"`` or ``"CDOF"`` (default) as programmed.
    sar: the smooth approach or retraction of this block, else ``None``.
    """

    corner: str = "G450"
    disc: float = 0.0
    approach: str = "NORM"
    bottleneck: str = "CDOF"
    sar: SmoothApproach | None = None


@dataclass(frozen=True, slots=True)
class Modal:
    """Modal state in force for a block, as far as ccopt cares.

    Attributes
    ----------
    plane: ``"XY" | "ZX" | "YZ"``.
    units: ``"mm" | "inch"``.
    side: +1 left (G41/CC1), -1 right (G42/CC2), 0 compensation off.
        A negative programmed radius has already been turned into a side flip
        by the reader (spec: "a negative radius flips the side").
    radius: cutter radius in program units (>= 0), or ``None`` when the
        program never set one (then ``--radius`` must).
    tool: tool number from G-code ``D``/``T`` when the radius comes from a tool
        table, else ``None``.
    corner: Fagor outside-corner transition, ``"circular"`` (G136, default)
        or ``"linear"`` (G137).
    start_end: Fagor activation/cancellation, ``"contour"`` (G139, default)
        or ``"direct"`` (G138).
    accel_time, scurve_time: PMAC ``TA``/``TS`` in seconds (``None`` unset).
    orientation: lathe tool orientation ``Q`` 1..9 (LinuxCNC, in ``G18``) of the
        tool compensating, 0 for a mill tool; kept after ``G40`` as ``radius``.
    siemens: SINUMERIK corner, approach and SAR modes (:class:`SiemensModes`),
        ``None`` for programs of other dialects.
    """

    plane: str = "XY"
    units: str = "mm"
    side: int = 0
    radius: float | None = None
    tool: int | None = None
    corner: str = "circular"
    start_end: str = "contour"
    accel_time: float | None = None
    scurve_time: float | None = None
    orientation: int = 0
    siemens: SiemensModes | None = None


@dataclass(frozen=True, slots=True)
class Frame:
    """The work coordinate frame a G-code block was programmed in, as the
    reader knew it: ``machine = R(rotation) (work + axis_offset) + origin``,
    program units, ``R`` a rotation about Z (``machine = work + offset`` per
    axis when ``rotation`` is 0).

    Attributes
    ----------
    system: the coordinate system in force, 1 .. 9 for ``G54`` .. ``G59.3``.
    origin: that system's origin in machine coordinates (``G10 L2`` or the
        parameter file).
    axis_offset: the ``G92``/``G52`` offset in force.
    machine: the block's end was programmed in machine coordinates (``G53``).
    rotation: the system's XY rotation (``G10 L2 R``), degrees counter-clockwise.
    axes_origin, axes_offset: the origin and ``G92``/``G52`` offset on A B C U V
        W (``machine = work + origin + offset`` per axis), ``None`` while the
        program moves none of them.
    """

    system: int = 1
    origin: Vec3 = (0.0, 0.0, 0.0)
    axis_offset: Vec3 = (0.0, 0.0, 0.0)
    machine: bool = False
    rotation: float = 0.0
    axes_origin: tuple[float, ...] | None = None
    axes_offset: tuple[float, ...] | None = None

    def axes_to_work(self, axes: tuple[float, ...]) -> tuple[float, ...]:
        """Work coordinates of machine A B C U V W ``axes``."""
        if self.axes_origin is None:
            return axes
        o, a = self.axes_origin, self.axes_offset or (0.0,) * 6
        return tuple(axes[k] - o[k] - a[k] for k in range(6))

    def to_work(self, p: Vec3) -> Vec3:
        """Work coordinates of machine point ``p``."""
        o, a = self.origin, self.axis_offset
        if self.rotation == 0.0:
            off = self.offset
            return (p[0] - off[0], p[1] - off[1], p[2] - off[2])
        t = math.radians(self.rotation)
        c, s = math.cos(t), math.sin(t)
        x, y = p[0] - o[0], p[1] - o[1]
        return (x * c + y * s - a[0], -x * s + y * c - a[1], p[2] - o[2] - a[2])

    @property
    def offset(self) -> Vec3:
        """Machine minus work coordinates."""
        o, a = self.origin, self.axis_offset
        return (o[0] + a[0], o[1] + a[1], o[2] + a[2])


#: ``Program.meta`` key: how the program ends, ``"M2"`` or ``"M30"`` as written
#: (absent: it ends with its text or a ``%``).
PROGRAM_END = "program_end"
#: ``Program.meta`` key: the G-code program's ``(debug, ...)``, ``(msg, ...)``
#: and ``(print, ...)`` messages as it ran, in order: ``{"file", "line",
#: "text", "kind"}`` each (kind ``"debug"``, ``"msg"`` or ``"print"``; debug and
#: print with their parameters' values, as LinuxCNC prints them).
MESSAGES = "messages"
#: ``Program.meta`` key: where the main program ended with ``M99`` (a located
#: sentence): the machine would repeat it for ever; ccopt read one pass.
ENDLESS_MAIN = "endless_main_program"
#: ``Program.meta`` key: the errors a program read with ``keep_going`` (LinuxCNC's
#: ``rs274 -n 0``) went on after, located, in order.
ERRORS_PASSED = "errors_passed"
#: ``Program.meta`` key: located sentences on what the controller does that the
#: program may not mean (a LinuxCNC quirk followed, e.g. G84 in G18 feeding off
#: the hole); the command line prints them as notes.
NOTES = "notes"
#: ``Program.meta`` key: the letters of the axes beyond X Y Z the program
#: writes (``"AB"``), in A B C U V W order (:attr:`Block.axes`).
AXES_USED = "axes_used"
#: ``Program.meta`` key: the machine words after the last block (``M5``, ``M9``
#: before the end), in order (:attr:`Block.words`).
TRAILING_WORDS = "trailing_words"
#: ``Program.meta`` key: the numbered parameters the program was read with
#: (a parameter file's), so that an export is read back in the same frames.
START_PARAMETERS = "start_parameters"


@dataclass(frozen=True, slots=True)
class Block:
    """One executed move or dwell. See the module docstring for conventions.

    Attributes
    ----------
    source: where it is written.
    motion: :class:`Motion`.
    start, end: absolute ``(x, y, z)`` in program units. A dwell has
        ``start == end``.
    center: absolute ``(x, y, z)`` of an arc's centre (only its in-plane
        components matter), else ``None``. For a PMAC CIRCLE move whose end
        lies at another distance from the centre than its start, the block is
        a spiral: see :meth:`is_spiral`.
    turns: extra full turns of an arc (G2/G3 ``P`` minus one), normally 0.
    feed: tangential speed cap, program units per second; ``None`` for rapids
        (run at the axis limits).
    dwell: seconds, for ``Motion.DWELL``.
    move_time: PMAC ``TM`` move time in seconds when the program gave one.
    modal: :class:`Modal` in force for this block.
    mcodes: M codes written on the block (recorded, otherwise ignored).
    surface: ``"part"`` or ``"air"`` when a comment on the block's line says
        so (``(ccopt: part)``, ``; ccopt: air``: :mod:`ccopt.program.markers`),
        else ``None``; read by the verifier.
    cycle: the canned cycle (``"G81"``, ``"G83"``, ...) whose move or dwell this
        is, ``None`` for a programmed move (:mod:`ccopt.program.gcode.cycles`).
    words: the machine's non-motion words that execute before this block,
        one line each in execution order (``"T1 M6"``, ``"S8000 M3"``,
        ``"M8"``, ``"G43 H1"``): tool changes, spindle, coolant, tool length,
        program stops and other M-codes, as the G-code reader read them
        (:mod:`ccopt.program.gcode.machine_words`); an export writes them back.
    frame: the work coordinate frame the block was programmed in (G-code), or
        ``None`` (PMAC: machine coordinates).
    axes: machine positions of A B C U V W at the block's end (degrees for A B
        C, program units for U V W), ``None`` while the program has moved none
        of them: carried for exports, not part of the path
        (:mod:`ccopt.program.gcode.axes`).
    per_revolution: for a move synchronised to the spindle (``G33``, ``G33.1``,
        ``G76``'s cuts), the program units it advances along the path per
        spindle revolution (its ``feed`` is that times the speed in force);
        ``None`` for any other move. An export writes it back (``G33 K``).
    """

    source: Source
    motion: Motion
    start: Vec3
    end: Vec3
    modal: Modal
    center: Vec3 | None = None
    turns: int = 0
    feed: float | None = None
    dwell: float = 0.0
    move_time: float | None = None
    mcodes: tuple[int, ...] = ()
    surface: str | None = None
    cycle: str | None = None
    words: tuple[str, ...] = ()
    frame: Frame | None = None
    axes: tuple[float, ...] | None = None
    per_revolution: float | None = None

    # -- plane helpers -------------------------------------------------
    def uvw(self, p: Vec3) -> tuple[float, float, float]:
        """``p`` in this block's plane coordinates (u, v, w)."""
        i, j, k = PLANE_AXES[self.modal.plane]
        return (p[i], p[j], p[k])

    @property
    def start_uv(self) -> tuple[float, float]:
        u, v, _ = self.uvw(self.start)
        return (u, v)

    @property
    def end_uv(self) -> tuple[float, float]:
        u, v, _ = self.uvw(self.end)
        return (u, v)

    @property
    def center_uv(self) -> tuple[float, float] | None:
        if self.center is None:
            return None
        u, v, _ = self.uvw(self.center)
        return (u, v)

    @property
    def in_plane(self) -> bool:
        """True when the move changes the in-plane coordinates (or is a full circle)."""
        if not self.motion.is_move:
            return False
        if self.motion.is_arc:
            return True
        (u0, v0), (u1, v1) = self.start_uv, self.end_uv
        return math.hypot(u1 - u0, v1 - v0) > 0.0

    def is_spiral(self, tol: float = POINT_EPS) -> bool:
        """An arc whose end radius differs from its start radius by more than
        ``tol`` (program units; default: the end is off the start's circle)."""
        if not self.motion.is_arc or self.center is None:
            return False
        (cu, cv) = self.center_uv
        (u0, v0), (u1, v1) = self.start_uv, self.end_uv
        return abs(math.hypot(u1 - cu, v1 - cv) - math.hypot(u0 - cu, v0 - cv)) > tol

    def compensation_in_force(self, radius: float | None = None,
                              side: int | None = None) -> tuple[int, float | None]:
        """Side ``k`` and cutter radius ``r`` in force for this block, after
        the overrides every style and the verifier apply: ``side`` (+1 left,
        -1 right) replaces the programmed side wherever compensation is on,
        ``radius`` replaces every programmed radius. ``(0, 0.0)`` when off.

        ``r`` is ``None`` when compensation is on and neither the program nor
        ``radius`` gives one. Whether that (or a negative ``radius``) is an
        error is the caller's business: the program itself is valid, only
        compensating it needs a radius (``ccopt.compensate.scan``).
        """
        k = self.modal.side
        if k == 0:
            return 0, 0.0
        if side is not None:
            k = side
        r = radius if radius is not None else self.modal.radius
        return int(k), (None if r is None else float(r))


@dataclass(frozen=True)
class Program:
    """An immutable part program: blocks in execution order.

    Attributes
    ----------
    blocks: tuple of :class:`Block`.
    file: source file name.
    dialect: ``"gcode"``, ``"pmac"`` or ``"sinumerik"``.
    units: ``"mm"`` or ``"inch"`` (of the last unit word; mixed units are an
        error in the readers).
    start: machine position before the first block, ``(x, y, z)``.

    The blocks as arrays, read once and kept with the program, are
    :func:`ccopt.program.columns.columns_of` it.
    """

    blocks: tuple[Block, ...]
    file: str = "<string>"
    dialect: str = "gcode"
    units: str = "mm"
    start: Vec3 = (0.0, 0.0, 0.0)
    meta: dict = field(default_factory=dict, compare=False)

    def __iter__(self) -> Iterator[Block]:
        return iter(self.blocks)

    def __len__(self) -> int:
        return len(self.blocks)

    def __getitem__(self, i):
        return self.blocks[i]

    @property
    def moves(self) -> tuple[Block, ...]:
        return tuple(b for b in self.blocks if b.motion.is_move)

    def nothing_to_verify(self) -> str | None:
        """Why there is nothing to verify (or plan, or export) in this program,
        ``None`` when there is something: an empty program, or one with no
        move (dwells and settings only). The commands say it in so many words
        (``nothing to verify: the program has no moves``) and exit 0, instead
        of a "verification PASSED" over no checks (issue 29)."""
        if not any(b.motion.is_move for b in self.blocks):
            return NOTHING_TO_VERIFY
        return None


def unread(program: Program) -> Program:
    """``program`` as its reader returned it: the same blocks and fields, its
    columns (:func:`ccopt.program.columns.columns_of`) not read yet (benchmarks time each stage from a
    program in that state, as a command reading a file has it)."""
    return replace(program)
