"""Reading a tool path back from ccopt's JSON schema, to verify it.

The schema is what ``ccopt compensate --json`` prints (:meth:`ToolPath.to_json`):
``{"style", "radius", "plane", "units", "segments": [...]}``, each segment with
``kind`` (line|arc|spiral|curve), ``start``, ``end``, ``role``, ``block`` (the
source line of the program block it belongs to, or null), optional ``plane``
(the segment's own, default the file's ``plane``: ``start``/``end`` are in its
``(u, v)``), ``w`` (``[w0, w1]``, the out-of-plane coordinate) and ``feed``;
``start_xyz``/``end_xyz`` (machine coordinates) are written for the reader's
convenience and not read: they follow from ``start``/``end``, ``w`` and
``plane``, which are what a segment is rebuilt from; arcs and spirals
``center``, ``ccw`` and the signed ``sweep`` (radians), arcs ``radius``,
spirals ``radius`` as ``[rho0, rho1]``; curves ``control_points`` (a Bezier
curve of ``degree`` = points - 1). A path ccopt made also says what
compensation knew: ``overrides`` (``{"radius", "side"}``, the cutter radius and
side that replaced the program's, null for the program's own; read back, the
verifier applies them as compensation did) and per segment ``side``,
``radius_in_force`` and ``surface: "air"`` (written for the reader: they follow
from the block and the overrides). Files without them (older ones, other
systems') are read as before and their settings inferred. Another CAM system, a controller log or an
older export written in it can be certified against the program's contour
(``ccopt verify PROGRAM --toolpath FILE.json``).

Every segment is rebuilt exactly (a line from its two points; an arc or a
spiral from its centre, radii, start angle and sweep; a curve from its control
points), and its stated ``start`` and ``end`` must be the rebuilt primitive's
within :data:`END_MATCH_REL_TOL` (relative to the segment's size): a file
whose end point was edited without its arc is refused, not silently read as
the arc. A segment's ``block`` is matched to the program's block of that
source line, the next one in program order (a line an O-word loop runs
several times gives several blocks): the verifier needs it to know which
contour element a move offsets. Bad input is a :class:`ProgramError`
``FILE.json: segment N: message`` (``FILE.json:LINE:COL:`` for JSON syntax).
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from ccopt.errors import ProgramError
from ccopt.geometry import Arc, Line, Spiral
from ccopt.geometry.curve import BezierCurve
from ccopt.program.model import PLANE_AXES, Block, Program
from ccopt.toolpath import COMPENSATION, PathSegment, Role, ToolPath

#: A segment's stated ``start``/``end`` may differ from the rebuilt primitive's by
#: this fraction of ``max(1, size)`` (radius or length): the JSON writer prints
#: floats exactly (shortest repr), so only rounding of the rebuild is absorbed.
END_MATCH_REL_TOL = 1e-9

#: Units the schema knows.
UNITS = ("mm", "inch")

KINDS = ("line", "arc", "spiral", "curve")


class _Reader:
    """One file's segments, with the program whose blocks they refer to."""

    def __init__(self, file: str, program: Program | None, plane: str = "XY"):
        self.file = file
        self.plane = plane            # a segment's plane when it gives none
        self.blocks: list[Block] = list(program.blocks) if program is not None else []
        self.by_line: dict[int, list[int]] = {}
        for i, b in enumerate(self.blocks):
            self.by_line.setdefault(b.source.line, []).append(i)
        self.cursor = 0

    def fail(self, message: str, where: str = "") -> ProgramError:
        return ProgramError(f"{where}{message}", self.file)

    def number(self, value, what: str, where: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(float(value)):
            raise self.fail(f"{what} must be a finite number, not {value!r}", where)
        return float(value)

    def point(self, value, what: str, where: str) -> tuple[float, float]:
        if not isinstance(value, list) or len(value) != 2:
            raise self.fail(f"{what} must be two numbers [u, v], not {value!r}", where)
        return (self.number(value[0], what, where), self.number(value[1], what, where))

    def block(self, line, where: str) -> Block | None:
        """The program block of source line ``line``: the first at or after the
        previous segment's block, else the first of that line."""
        if line is None:
            return None
        if isinstance(line, bool) or not isinstance(line, int):
            raise self.fail(f"'block' must be a source line number or null, not {line!r}", where)
        found = self.by_line.get(line)
        if not found:
            raise self.fail(f"'block' {line}: the program has no move on line {line}", where)
        nxt = [i for i in found if i >= self.cursor]
        self.cursor = nxt[0] if nxt else found[0]
        return self.blocks[self.cursor]

    def geometry(self, seg: dict, kind: str, where: str):
        start = self.point(seg.get("start"), "'start'", where)
        end = self.point(seg.get("end"), "'end'", where)
        try:
            if kind == "line":
                return Line(start, end), 0.0
            if kind == "curve":
                return self._curve(seg, where), 0.0
            center = self.point(seg.get("center"), "'center'", where)
            sweep = self.number(seg.get("sweep"), "'sweep'", where)
            ccw = seg.get("ccw")
            if ccw is not None and ccw is not (sweep > 0):
                raise self.fail(f"'ccw' {ccw} contradicts 'sweep' {sweep}", where)
            theta0 = math.atan2(start[1] - center[1], start[0] - center[0])
            radius = seg.get("radius")
            if kind == "arc":
                r = self.number(radius, "'radius'", where)
                return Arc(center, r, theta0, sweep), r
            if not isinstance(radius, list) or len(radius) != 2:
                raise self.fail(f"a spiral's 'radius' must be [rho0, rho1], not {radius!r}", where)
            rho0, rho1 = (self.number(x, "'radius'", where) for x in radius)
            return Spiral(center, rho0, rho1, theta0, sweep), max(rho0, rho1)
        except ValueError as exc:            # the geometry's own checks (radius > 0, ...)
            raise self.fail(str(exc), where) from None

    def _curve(self, seg: dict, where: str):
        pts = seg.get("control_points")
        if not isinstance(pts, list) or len(pts) < 2:
            raise self.fail("a curve needs 'control_points' (at least two [u, v])", where)
        pts = [self.point(p, "a control point", where) for p in pts]
        degree = seg.get("degree")
        if degree is not None and degree != len(pts) - 1:
            raise self.fail(f"'degree' {degree!r} is not the number of control points - 1 "
                            f"({len(pts) - 1})", where)
        return BezierCurve(tuple(pts))

    def segment(self, seg, k: int) -> PathSegment:
        where = f"segment {k}: "
        if not isinstance(seg, dict):
            raise self.fail(f"a segment must be an object, not {type(seg).__name__}", where)
        kind = seg.get("kind")
        if kind not in KINDS:
            raise self.fail(f"'kind' must be one of {', '.join(KINDS)}, not {kind!r}", where)
        try:
            role = Role(seg.get("role"))
        except ValueError:
            raise self.fail(f"'role' must be one of {', '.join(r.value for r in Role)}, "
                            f"not {seg.get('role')!r}", where) from None
        geom, size = self.geometry(seg, kind, where)
        size = max(size, geom.length, 1.0)
        for name, stated, made in (("start", seg["start"], geom.start), ("end", seg["end"], geom.end)):
            off = math.hypot(float(stated[0]) - made[0], float(stated[1]) - made[1])
            if off > END_MATCH_REL_TOL * size:
                raise self.fail(f"'{name}' ({stated[0]:.9g}, {stated[1]:.9g}) is not the {kind}'s "
                                f"own {name} ({made[0]:.9g}, {made[1]:.9g}): off by {off:.3g}", where)
        w = seg.get("w", [0.0, 0.0])
        if not isinstance(w, list) or len(w) != 2:
            raise self.fail(f"'w' must be [w0, w1], not {w!r}", where)
        w0, w1 = (self.number(x, "'w'", where) for x in w)
        plane = seg.get("plane", self.plane)
        if plane not in PLANE_AXES:
            raise self.fail(f"'plane' must be one of {', '.join(PLANE_AXES)}, not {plane!r}",
                            where)
        feed = seg.get("feed")
        if feed is not None:
            feed = self.number(feed, "'feed'", where)
            if feed <= 0:
                raise self.fail(f"'feed' must be > 0, not {feed!r}", where)
        block = self.block(seg.get("block"), where)
        if block is not None and block.modal.plane != plane:
            raise self.fail(f"'plane' {plane} is not the plane of its block (line "
                            f"{block.source.line}, {block.modal.plane})", where)
        return PathSegment(geom, role, block, w0, w1, feed, plane)


def toolpath_from_json(data: Any, program: Program | None = None,
                       file: str = "<json>") -> ToolPath:
    """The :class:`ToolPath` that ``data`` (the schema's dict) describes, its
    blocks taken from ``program`` (``None``: every ``block`` must be null).

    Raises :class:`ProgramError` naming ``file`` and the segment."""
    reader = _Reader(file, program)
    if not isinstance(data, dict):
        raise reader.fail("a tool path must be a JSON object with 'segments'")
    segs = data.get("segments")
    if not isinstance(segs, list):
        raise reader.fail("'segments' must be a list of segments")
    radius = reader.number(data.get("radius", 0.0), "'radius'", "")
    if radius < 0:
        raise reader.fail(f"'radius' must be >= 0, not {radius!r}")
    plane = data.get("plane", "XY")
    if plane not in PLANE_AXES:
        raise reader.fail(f"'plane' must be one of {', '.join(PLANE_AXES)}, not {plane!r}")
    reader.plane = plane
    default_units = program.units if program is not None else "mm"
    units = data.get("units", default_units)
    if units not in UNITS:
        raise reader.fail(f"'units' must be mm or inch, not {units!r}")
    if program is not None and units != program.units:
        raise reader.fail(f"'units' {units} differ from the program's ({program.units})")
    style = data.get("style", "json")
    if not isinstance(style, str):
        raise reader.fail(f"'style' must be a string, not {style!r}")
    out = tuple(reader.segment(s, k) for k, s in enumerate(segs))
    meta = {}
    if "overrides" in data:
        meta[COMPENSATION] = _overrides(reader, data["overrides"])
    return ToolPath(out, plane=out[0].plane if out else plane, style=style, radius=radius,
                    units=units, meta=meta)


def _overrides(reader: _Reader, value) -> dict:
    """The ``overrides`` object: ``{"radius": number >= 0 | null, "side": 1 | -1 | null}``."""
    if not isinstance(value, dict):
        raise reader.fail(f"'overrides' must be an object with 'radius' and 'side', not {value!r}")
    radius, side = value.get("radius"), value.get("side")
    if radius is not None:
        radius = reader.number(radius, "'overrides' 'radius'", "")
        if radius < 0:
            raise reader.fail(f"'overrides' 'radius' must be >= 0, not {radius!r}")
    if side not in (None, 1, -1) or isinstance(side, bool):
        raise reader.fail(f"'overrides' 'side' must be 1 (left), -1 (right) or null, not {side!r}")
    return {"radius": radius, "side": side}


def read_toolpath_json(path: str | Path, program: Program | None = None) -> ToolPath:
    """Read the tool path in file ``path`` (ccopt's JSON schema); see
    :func:`toolpath_from_json`."""
    name = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ProgramError(f"cannot read the tool path: {exc}", name) from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ProgramError(f"not JSON: {exc.msg}", name, exc.lineno, exc.colno) from None
    return toolpath_from_json(data, program, name)
