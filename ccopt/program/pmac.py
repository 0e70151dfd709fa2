"""Reader for Delta Tau PMAC / Turbo PMAC motion programs.

``read_pmac(text)`` turns the text of a PMAC download file (or a bare motion
program body) into an immutable :class:`~ccopt.program.model.Program` of
dialect ``"pmac"``: one :class:`~ccopt.program.model.Block` per executed move
(``RAPID`` -> ``Motion.RAPID``, ``LINEAR`` -> ``Motion.LINE``, ``CIRCLE1`` ->
``Motion.ARC_CW``, ``CIRCLE2`` -> ``Motion.ARC_CCW``) and per ``DWELL`` /
``DELAY`` (``Motion.DWELL``).

Manual references below are to the stored manual pages (search corpus
``pages``), cited as

* *PMAC SRM* – PMAC 2 Software Reference, ``manual/delta-tau/pmac-vme/reference-manual-english``;
* *PMAC UM* – PMAC User Manual, ``manual/delta-tau/pmac-vme/user-s-manual-english``;
* *Turbo SRM* – Turbo PMAC/PMAC2 Software Reference (``turbo-pmac2-vme/1-reference-manual-english``,
  same pagination in the ``pmac2-pci`` / ``geo-brick-drive`` copies);
* *Turbo UM* – Turbo PMAC User Manual (``turbo-pmac2-vme/1-user-s-manual-english``);
* *QRG* – PMAC Quick Reference Guide (``turbo-clipper/reference-guide-english``).

Units and conventions
---------------------
* Lengths are user units (``Program.units`` is ``"mm"``; PMAC itself has no
  unit word, the axis definitions fix the scale).
* ``F`` is a vector feedrate in length units per *Isx90* ms; *Isx90* defaults
  to 1000 ms, so ``F`` is units **per second** (PMAC SRM p.122, Ix90). The
  reader stores ``Block.feed`` in units per second.
* ``TM``, ``TA``, ``TS``, ``DWELL`` and ``DELAY`` are milliseconds in the
  program and seconds in the :class:`Program`.
* Arcs: ``CIRCLE1`` is clockwise, ``CIRCLE2`` counter-clockwise, "in the
  direction the right fingers curl when the right thumb points along the
  NORMAL vector" (PMAC UM p.177; Turbo SRM p.456), so with the standard
  negative normals (``NORMAL K-1`` / ``J-1`` / ``I-1``) ``CIRCLE1`` is
  :attr:`Motion.ARC_CW` in the plane's (u, v) coordinates of
  :data:`~ccopt.program.model.PLANE_AXES`.

Language rules and the decisions this reader makes
--------------------------------------------------
Buffers (decision). A file with at least one ``OPEN PROG n [CLEAR]`` ...
``CLOSE`` is a *download file*: the program selected by ``program=`` (default:
the first ``OPEN PROG`` in the file) is executed. Opening a program again
without ``CLEAR`` appends to it, a line ``CLEAR`` inside an open buffer erases
what it held so far. Other buffers (``OPEN PLC``, ``OPEN ROT``, kinematics
...) are skipped and listed in ``meta["skipped_buffers"]``. Text outside the
buffers is read as the on-line commands of a download file and runs *before*
the program: P/Q/I/M-variable assignments are executed (so ``P1=5`` before
``OPEN PROG`` sets P1 for the program), ``&n`` selects the coordinate system
whose *Isx* variables apply, ``#n->...`` axis definitions, ``UNDEFINE``,
``DELETE ...`` and ``DEFINE ...`` are recorded in ``meta["online"]`` and
otherwise ignored; anything else outside a buffer is a :class:`ProgramError`.
A file without any ``OPEN`` is read as a bare program body (then ``CLOSE`` is
an error). Lines of the selected program after ``RETURN`` are not executed and
not checked (they are usually subroutines reached by ``GOSUB``, which ccopt
does not follow); other buffers are not checked either.

Statements. Several statements may share a line and need no spaces
(``LINEAR ABS X10 Y20 F5``, ``X10Y20``); PMAC ignores spaces, so ``X 10`` is
``X10``. Comments run from ``;`` to the end of the line. Everything is
case-insensitive. ``N{n}`` / ``O{n}`` labels are ignored.

Moves. The axis words of one line (``X``, ``Y``, ``Z``, centre vector ``I``,
``J``, ``K``, radius ``R``) form one move, executed at the end of the line
(QRG p.49: ``X3 Y4 F50`` runs that very move at F50). So ``F``, ``TM``, ``TA``
and ``TS`` read after axis words still apply to the move being written. A
move-mode, ``ABS``/``INC``, ``CC*``, ``CCR``, ``NORMAL``, ``DWELL``/``DELAY``
or ``RETURN`` statement placed *after* axis words first executes the move
written before it, and acts from the next move on (decision: reading order);
a later ``F`` on the same line then belongs to that next move. Whether a coordinate is absolute
or incremental is taken when the word is read. An axis word twice in one
move is an error. Other axes (``A B C U V W``) are an error: ccopt carries X,
Y, Z only. A move needs at least one of ``X Y Z``.

``{data}`` is a constant (``10``, ``-2.5``, ``.5``, ``$1F``) or a
parenthesised expression (``X(P1+2)``), see :mod:`ccopt.program.expr`; a
variable assignment takes an expression with or without parentheses
(``P1=P2*2+1``). Beside ``+ - * / %`` expressions know the bit-by-bit ``&``
(same precedence as ``*``), ``|`` and ``^`` (same as ``+``), acting on the
fractional bits as well (Turbo SRM p.489), hexadecimal ``$`` constants,
``P(expr)``/``Q(expr)`` indirect references and ``ATAN2``.

Move modes. ``LINEAR``/``LIN``, ``CIRCLE1``/``CIR1``, ``CIRCLE2``/``CIR2``,
``RAPID``/``RPD``; ``SPLINE1``/``SPLINE2``/``PVT`` are "unsupported move
mode". Power-on defaults: ``LINEAR``, ``ABS`` for all axes, ``INC(R)``,
``NORMAL K-1`` (PMAC SRM p.327, p.295; PMAC UM p.177).

Circles (PMAC SRM p.295, PMAC UM p.177). The centre comes from the ``I J K``
vector – from the move start by default / after ``INC(R)``, from the origin
after ``ABS(R)``; plain ``ABS``/``INC`` leave the vector mode alone; an
unwritten component is 0 in either mode (decision), and the component along
the plane normal is ignored (the centre is projected into the move's start
plane). Or from ``R``: positive = the short arc (<= 180 deg), negative = the
long arc (>= 180 deg); ``R`` cannot make a full circle. With ``I J K`` an
in-plane end equal to the start (within ``POINT_EPS``; the end is then
snapped onto the start) is a full circle. An end at another distance from the
centre than the start is a spiral: PMAC "introduces the change linearly"; the
block is kept as an arc with its centre (:meth:`Block.is_spiral`). Errors: a
CIRCLE move with neither vector nor radius (decision; the brief asks for it),
both, ``R`` zero, ``R`` shorter than half the chord (beyond 1e-9 relative;
within it the arc is a half circle), ``R`` with start == end, a centre on the
start or on the end point, ``I J K R`` on a LINEAR or RAPID move.

Planes. ``NORMAL`` sets all three components (unwritten ones are 0; only the
direction matters, Turbo SRM p.456). ``K<0`` alone -> XY, ``J<0`` alone ->
ZX, ``I<0`` alone -> YZ; every other vector is "unsupported NORMAL".

Feed and time (PMAC SRM p.327 LINEAR: the speed "is determined by the most
recent feedrate (F) or move time (TM) command"; p.122 Ix89: power-on is
feedrate mode, Ix89 reports "the most recently executed F or TM"). So the
reader is in move-time mode after ``TM`` until the next ``F`` and vice versa:
a LINEAR/CIRCLE block in feed mode has ``feed`` = F (units/s) and
``move_time`` None, in time mode ``feed`` None and ``move_time`` = TM (s).
PMAC would fall back on *Isx89* when the program never gave F or TM; the
reader does so only when the file assigns *Isx89* itself, otherwise a
LINEAR/CIRCLE move with neither F nor TM is a ProgramError (decision: the
controller's Isx89 is unknown). ``F`` must be > 0 (decision: PMAC UM p.169
says a negative feedrate reverses the motion sense, which no part program
means), ``TM``, ``TA``, ``TS``, ``DWELL``, ``DELAY`` must be >= 0 (``TM0``
means "the acceleration time", Turbo SRM p.476). RAPID blocks have no feed or
move time (jog speeds, PMAC UM p.175).

Dwell and delay. ``DWELL{ms}`` and ``DELAY{ms}`` both give a
:attr:`Motion.DWELL` block at the current point (``dwell`` in seconds). They
differ in PMAC (Turbo SRM p.429; PMAC UM p.215): DWELL decelerates a blended
move to a stop over TA first, runs in real time whatever the time base, and
PMAC computes nothing ahead during it; DELAY is "really a zero-distance move
command of the specified time" that follows the time base and is calculated
through. For path purposes both hold still; the indices of the DELAY blocks
are listed in ``meta["delay_blocks"]``.

Compensation. ``CC1`` left, ``CC2`` right, ``CC0`` off; ``CC3`` (3-D) and
``CC4`` (off without the automatic zero-distance lead-out, Turbo SRM p.419)
are unsupported. ``CCR{data}`` sets the radius; a negative radius flips the
side (spec decision): ``Modal.radius`` = |CCR| and ``Modal.side`` is the
*effective* side = programmed side of the last CC1/CC2 times the sign of
CCR, so a later ``CC1`` under a negative CCR is still right-hand.

Variables (decision). ``P{n}``, ``Q{n}`` (n = 0..8191) are program variables,
unset ones read 0. ``I{n}=`` assignments are recorded in
``meta["i_variables"]``; those that change how the program reads are
honoured for the selected coordinate system *s* (``&s``, default 1): ``I15``
(1 = trigonometry in radians), *Isx87*/*Isx88* (default TA/TS), *Isx89*
(default feedrate), *Isx90* (feedrate time unit); *Isx99* (outside-corner
break cosine) is copied to ``meta["break_cos"]``. Reading an I-variable the
file never set is an error (its value lives in the controller).
``M{n}=``/``M{n}==`` assignments (I/O points) are recorded in
``meta["m_variables"]`` and otherwise ignored. ``M{n}`` without ``=`` is an
M-code call (a jump into PROG 1001 that ccopt cannot see): recorded in
``Block.mcodes`` of the line's move (or ``meta["ignored"]``). ``ATAN2(e)`` is
the four-quadrant arc tangent of ``e`` (sine argument) and ``Q0`` (cosine
argument), as the Turbo SRM mathematical-features section describes it (that
page is not among the stored ones; see the report).

Unsupported (ProgramError naming the command): jumps, loops, conditions,
subroutine calls (``GOTO GOSUB CALL IF WHILE ...``), G/T/D codes (calls into
PROG 1000/1002/1003), ``PSET``, ``HOME``, ``READ``, transformation matrices,
3-D compensation vectors, ``FRAX`` other than the default all-axes set,
``NOFRAX``, I/O commands (``CMD SEND DISPLAY ...``).

Every problem raises :class:`~ccopt.errors.ProgramError` with file, 1-based
line and column.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ccopt.errors import ProgramError
from ccopt.program import expr as _expr
from ccopt.program.expr import (ExprError, Grammar, PMAC_BINARY, PMAC_FUNCTIONS,
                                parse_bracketed)
from ccopt.program.model import PLANE_AXES, Block, Modal, Motion, Program, Source, Vec3
from ccopt.tolerances import POINT_EPS, R_CHORD_REL_TOL

__all__ = ["read_pmac"]

#: Highest P/Q/I/M variable number of a Turbo PMAC.
MAX_VARIABLE = 8191
#: Bits after the binary point used for the bit-by-bit operators.
_FRACTION_BITS = 48

_AXES = "XYZ"
_OTHER_AXES = "ABCUVW"
_VECTORS = "IJK"

_MOVE_MODES = {
    "LINEAR": "LINEAR", "LIN": "LINEAR",
    "CIRCLE1": "CIRCLE1", "CIR1": "CIRCLE1",
    "CIRCLE2": "CIRCLE2", "CIR2": "CIRCLE2",
    "RAPID": "RAPID", "RPD": "RAPID",
}
_UNSUPPORTED_MODES = {"SPLINE1", "SPLINE2", "SPL1", "SPL2", "PVT"}
_UNSUPPORTED = {
    # flow and subroutines
    "GOTO", "GOSUB", "CALL", "IF", "WHILE", "ELSE", "ENDIF", "ENDI", "ENDWHILE", "ENDW",
    "AND", "OR", "STOP", "WAIT", "PRELUDE",
    # I/O and misc
    "READ", "PSET", "HOME", "HOMEZ", "CMD", "COMMAND", "SEND", "SENDS", "SENDP", "SENDC",
    "DISPLAY", "DISP", "ENABLE", "DISABLE", "LOCK", "UNLOCK", "SETPHASE",
    "BLOCKSTART", "BSTART", "BLOCKSTOP", "BSTOP", "NOFRAX", "ADDRESS",
    # transformations, 3-D compensation
    "TSEL", "TINIT", "ADIS", "IDIS", "AROT", "IROT", "NX", "NY", "NZ", "TR", "TX", "TY", "TZ",
}
_KEYWORDS = sorted(
    set(_MOVE_MODES) | _UNSUPPORTED_MODES | _UNSUPPORTED | {
        "ABS", "INC", "DWELL", "DWE", "DELAY", "DLY", "NORMAL", "NRM", "FRAX",
        "RETURN", "RET", "CCR", "CC0", "CC1", "CC2", "CC3", "CC4", "TA", "TS", "TM",
        "OPEN", "CLOSE", "CLEAR", "DEFINE", "DELETE", "UNDEFINE",
    },
    key=len, reverse=True)
_UNSUPPORTED_WHY = ("ccopt reads straight-line motion programs: no jumps, loops, "
                    "conditions, subroutine calls, I/O or coordinate transformations")

_ASSIGN_RE = re.compile(r"([PQIM])(\d+)[ \t]*(==|=|->)")
_INDIRECT_RE = re.compile(r"([PQ])[ \t]*\(")
_VAR_RE = re.compile(r"([PQIM])(\d+)")
_LETTERS_RE = re.compile(r"[A-Z]+")
_HEX_RE = re.compile(r"\$([0-9A-F]+)")
_NUMBER_RE = re.compile(r"(\d+\.?\d*|\.\d+)")
_OPEN_RE = re.compile(r"OPEN[ \t]*([A-Z]*)[ \t]*(\d*)[ \t]*(CLEAR)?[ \t]*$")


def read_pmac(text: str, file: str = "<string>", *, start: Vec3 = (0.0, 0.0, 0.0),
              program: int | None = None) -> Program:
    """Read PMAC / Turbo PMAC motion-program text.

    Parameters
    ----------
    text: the download file or bare program body.
    file: name used in error messages and :attr:`Program.file`.
    start: machine position ``(x, y, z)`` before the first move.
    program: number of the ``OPEN PROG`` buffer to read; default the first
        one in the file (``None`` for a file without ``OPEN``).

    Returns
    -------
    Program with ``dialect="pmac"``; see the module docstring for the rules.

    Raises
    ------
    ProgramError: for any problem in the text, located by line and column.
    """
    try:
        start_t = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ProgramError(f"start must be three numbers (x, y, z), got {start!r}", file) from None
    if len(start_t) != 3 or not all(math.isfinite(v) for v in start_t):
        raise ProgramError(f"start must be three finite numbers (x, y, z), got {start!r}", file)
    return _Reader(file, start_t).read(text, program)  # type: ignore[arg-type]


# ----------------------------------------------------------------------------
@dataclass
class _Pending:
    """Axis words of the move being written on the current line."""

    line: int
    col: int
    axes: dict = field(default_factory=dict)      # "X" -> (value, incremental)
    vector: dict = field(default_factory=dict)    # "I" -> value
    radius: float | None = None
    words: set = field(default_factory=set)


class _Reader:
    def __init__(self, file: str, start: Vec3):
        self.file = file
        self.start = start
        self.pos: list[float] = list(start)
        # modal state (power-on defaults)
        self.mode = "LINEAR"
        self.incremental = {a: False for a in _AXES}
        self.vector_absolute = False
        self.plane = "XY"
        self.feed: float | None = None        # units/s, feed mode
        self.move_time: float | None = None   # s, time mode
        self.time_mode = False
        self.accel_time: float | None = None
        self.scurve_time: float | None = None
        self.programmed_side = 0
        self.radius_sign = 1
        self.radius: float | None = None
        # variables
        self.p: dict[int, float] = {}
        self.q: dict[int, float] = {}
        self.i: dict[int, float] = {}
        self.i_line: dict[int, int] = {}      # line of the last assignment of each I-variable
        self.m: dict[int, float] = {}
        self.coord_system = 1
        self.feed_unit_ms = 1000.0
        self.radians = False
        # output
        self.blocks: list[Block] = []
        self.meta: dict = {"i_variables": {}, "m_variables": {}, "delay_blocks": [],
                           "ignored": [], "online": [], "skipped_buffers": []}
        self.pending: _Pending | None = None
        self.line_mcodes: list[int] = []
        self.in_body = False
        self.finished = False
        self.grammar = self._grammar()

    # -- errors -----------------------------------------------------------
    def error(self, message: str, line: int | None, col: int | None = None) -> ProgramError:
        return ProgramError(message, self.file, line, col)

    # -- top level --------------------------------------------------------
    def read(self, text: str, program: int | None) -> Program:
        lines = self.split(text)
        buffers, order, outside, skipped = self.buffers(lines)
        self.meta["skipped_buffers"] = skipped
        self.meta["programs"] = order
        if buffers is None:
            if program is not None:
                raise self.error(f"program={program} was asked for, but the file has no "
                                 "OPEN PROG ... CLOSE buffer (it is read as a bare program body)",
                                 None)
            body = lines
            self.meta["program"] = None
        else:
            for lineno, line in outside:
                self.online_line(lineno, line)
            if program is None:
                if not order:
                    first_open = next(n for n, line in lines if line.lstrip().startswith("OPEN"))
                    raise self.error("the file opens no PROG buffer (only "
                                     + ", ".join(skipped) + ")", first_open, 1)
                program = order[0]
            if program not in buffers:
                have = ", ".join(f"PROG {n}" for n in order) or "none"
                raise self.error(f"program {program} is not in the file (it has: {have})", None)
            body = buffers[program]
            self.meta["program"] = program
        self.apply_coordinate_system_defaults()
        self.in_body = True
        for lineno, line in body:
            if self.finished:
                break
            self.program_line(lineno, line)
        return Program(blocks=tuple(self.blocks), file=self.file, dialect="pmac", units="mm",
                       start=self.start, meta=self.meta)

    def split(self, text: str) -> list[tuple[int, str]]:
        """(line number, upper-case text without comment) for every line."""
        if not isinstance(text, str):
            raise self.error("program text must be a str", None)
        out = []
        for n, raw in enumerate(text.split("\n"), start=1):
            if raw.endswith("\r"):
                raw = raw[:-1]
            cut = raw.find(";")
            if cut >= 0:
                raw = raw[:cut]
            out.append((n, raw.upper()))
        return out

    def buffers(self, lines):
        """Split the file into PROG buffers and on-line text.

        Returns ``(buffers or None, program order, outside lines, skipped)``;
        ``None`` buffers means "no OPEN at all: a bare program body".
        """
        if not any(line.lstrip().startswith("OPEN") for _, line in lines):
            for n, line in lines:
                if line.strip() == "CLOSE":
                    raise self.error("CLOSE without OPEN (a file without OPEN is read as a "
                                     "bare program body)", n, line.index("CLOSE") + 1)
            return None, [], [], []
        buffers: dict[int, list] = {}
        order: list[int] = []
        outside: list = []
        skipped: list[str] = []
        current: int | None = None      # PROG number being filled
        skipping: str | None = None     # other buffer being skipped
        opened_at = 0
        for n, line in lines:
            stripped = line.strip()
            col = len(line) - len(line.lstrip()) + 1
            if stripped.startswith("OPEN"):
                if current is not None or skipping is not None:
                    raise self.error("OPEN inside an open buffer: CLOSE the buffer opened at "
                                     f"line {opened_at} first", n, col)
                m = _OPEN_RE.match(stripped)
                if not m or not m.group(1):
                    raise self.error("expected OPEN PROG {number} [CLEAR] alone on its line",
                                     n, col)
                kind, number, clear = m.groups()
                opened_at = n
                if kind == "PROG":
                    if not number:
                        raise self.error("OPEN PROG needs a program number", n, col)
                    current = int(number)
                    if current not in buffers:
                        buffers[current] = []
                        order.append(current)
                    if clear:
                        buffers[current] = []
                else:
                    skipping = f"{kind} {number}".strip()
                    skipped.append(skipping)
                continue
            if stripped == "CLOSE":
                current = None
                skipping = None
                continue
            if skipping is not None:
                continue
            if current is not None:
                if stripped == "CLEAR":
                    buffers[current] = []
                else:
                    buffers[current].append((n, line))
            else:
                outside.append((n, line))
        if current is not None or skipping is not None:
            what = f"PROG {current}" if current is not None else skipping
            raise self.error(f"OPEN {what} is never closed: add CLOSE at the end of the buffer",
                             opened_at, 1)
        return buffers, order, outside, skipped

    def apply_coordinate_system_defaults(self) -> None:
        """Honour Isx87/88/89/90/99 of the selected coordinate system, if the file set them."""
        base = 5000 + 100 * self.coord_system
        self.meta["coordinate_system"] = self.coord_system
        if base + 90 in self.i:
            unit = self.i[base + 90]
            if not unit > 0:
                raise self.error(f"I{base + 90}={unit:g}: the feedrate time unit must be > 0 ms",
                                 self.i_line[base + 90])
            self.feed_unit_ms = unit
        if base + 87 in self.i:
            self.accel_time = self.nonnegative(self.i[base + 87], f"I{base + 87}=",
                                               self.i_line[base + 87], None) / 1e3
        if base + 88 in self.i:
            self.scurve_time = self.nonnegative(self.i[base + 88], f"I{base + 88}=",
                                                self.i_line[base + 88], None) / 1e3
        if base + 89 in self.i:
            default = self.i[base + 89]
            if not default > 0:
                raise self.error(f"I{base + 89}={default:g}: the default feedrate must be > 0",
                                 self.i_line[base + 89])
            self.feed = default * 1000.0 / self.feed_unit_ms
        if base + 99 in self.i:
            self.meta["break_cos"] = self.i[base + 99]

    # -- expressions ----------------------------------------------------------
    def _grammar(self) -> Grammar:
        def to_rad(x: float) -> float:
            return x if self.radians else math.radians(x)

        def from_rad(x: float) -> float:
            return x if self.radians else math.degrees(x)

        def asin(x: float) -> float:
            if not -1.0 <= x <= 1.0:
                raise ValueError(f"ASIN argument {x:g} outside [-1, 1]")
            return from_rad(math.asin(x))

        def acos(x: float) -> float:
            if not -1.0 <= x <= 1.0:
                raise ValueError(f"ACOS argument {x:g} outside [-1, 1]")
            return from_rad(math.acos(x))

        def tan(x: float) -> float:
            c = math.cos(to_rad(x))
            if abs(c) < 1e-15:
                raise ValueError(f"TAN of {x:g} is infinite")
            return math.sin(to_rad(x)) / c

        functions = dict(PMAC_FUNCTIONS)
        functions.update({
            "SIN": lambda x: math.sin(to_rad(x)),
            "COS": lambda x: math.cos(to_rad(x)),
            "TAN": tan,
            "ASIN": asin,
            "ACOS": acos,
            "ATAN": lambda x: from_rad(math.atan(x)),
            # Turbo PMAC: the cosine argument of ATAN2 is Q0.
            "ATAN2": lambda x: from_rad(math.atan2(x, self.q.get(0, 0.0))),
        })
        binary = dict(PMAC_BINARY)
        binary.update({
            "&": (3, lambda a, b: _bitwise(a, b, lambda x, y: x & y)),
            "|": (2, lambda a, b: _bitwise(a, b, lambda x, y: x | y)),
            "^": (2, lambda a, b: _bitwise(a, b, lambda x, y: x ^ y)),
        })
        return Grammar("(", ")", binary, functions, variable=self._variable)

    def _variable(self, text: str, pos: int) -> tuple[float, int] | None:
        """Read ``P12``, ``Q(P1+1)``, ``I15``, ``M7`` or a ``$hex`` constant."""
        m = _HEX_RE.match(text, pos)
        if m:
            return _hex_value(m.group(1), pos), m.end()
        m = _INDIRECT_RE.match(text, pos)
        if m:
            number, end = self._indirect_number(text, pos, m)
            table = self.p if m.group(1) == "P" else self.q
            return table.get(number, 0.0), end
        m = _VAR_RE.match(text, pos)
        if not m:
            return None
        kind, number = m.group(1), self._variable_number(m.group(2), m.group(1), pos)
        if kind == "P":
            return self.p.get(number, 0.0), m.end()
        if kind == "Q":
            return self.q.get(number, 0.0), m.end()
        table = self.i if kind == "I" else self.m
        if number not in table:
            raise ExprError(f"{kind}{number} is read but never set in the file: its value lives "
                            "in the controller, which ccopt cannot see", pos)
        return table[number], m.end()

    def _indirect_number(self, text: str, pos: int, m: re.Match) -> tuple[int, int]:
        value, end = parse_bracketed(text, m.end() - 1, self.grammar)
        value = _check_finite_expr(value, pos)
        if abs(value - round(value)) > 1e-9 or not 0 <= round(value) <= MAX_VARIABLE:
            raise ExprError(f"{m.group(1)}({value:g}): the variable number must be an integer "
                            f"0..{MAX_VARIABLE}", pos)
        return int(round(value)), end

    @staticmethod
    def _variable_number(digits: str, kind: str, pos: int) -> int:
        number = int(digits)
        if number > MAX_VARIABLE:
            raise ExprError(f"{kind}{digits}: variable numbers go from 0 to {MAX_VARIABLE}", pos)
        return number

    def expression(self, line: int, text: str, pos: int, *, bare: bool) -> tuple[float, int]:
        """Evaluate an expression at ``pos``; ``bare`` allows no outer parentheses."""
        try:
            if bare:
                # The shared evaluator only exposes bracketed expressions; an
                # assignment's right-hand side may be unbracketed.
                value, end = _expr.parse_expression(text, pos, self.grammar)
            else:
                value, end = parse_bracketed(text, pos, self.grammar)
            return _check_finite_expr(value, pos), end
        except ExprError as exc:
            raise self.error(exc.message, line, exc.col + 1) from None
        except RecursionError:
            raise self.error("expression nested too deeply", line, pos + 1) from None

    def data(self, line: int, text: str, pos: int, what: str) -> tuple[float, int]:
        """``{data}``: a constant (optionally signed, ``$hex`` too) or ``(expression)``."""
        p = _skip(text, pos)
        sign = 1.0
        if p < len(text) and text[p] in "+-":
            sign = -1.0 if text[p] == "-" else 1.0
            p = _skip(text, p + 1)
        if p < len(text) and text[p] == "(":
            value, end = self.expression(line, text, p, bare=False)
            return sign * value, end
        m = _NUMBER_RE.match(text, p) or _HEX_RE.match(text, p)
        if not m:
            found = "end of line" if p >= len(text) else repr(text[p])
            raise self.error(f"{what} needs a value (a number or a (expression)), found {found}",
                             line, min(p, len(text)) + 1)
        try:
            value = float(m.group(1)) if m.re is _NUMBER_RE else _hex_value(m.group(1), p)
        except ExprError as exc:
            raise self.error(exc.message, line, p + 1) from None
        if not math.isfinite(value):
            raise self.error(f"{what}: number too large", line, p + 1)
        return sign * value, m.end()

    def nonnegative(self, value: float, what: str, line: int | None, col: int | None) -> float:
        if value < 0:
            raise self.error(f"{what}{value:g}: must not be negative", line, col)
        return value

    # -- assignments ----------------------------------------------------------
    def assignment(self, line: int, text: str, pos: int) -> int | None:
        """Execute ``P1=...``/``Q(P2)=...``/``I15=...``/``M1==...`` at ``pos``; None if none."""
        m = _ASSIGN_RE.match(text, pos)
        if m:
            kind, op = m.group(1), m.group(3)
            try:
                number = self._variable_number(m.group(2), kind, pos)
            except ExprError as exc:
                raise self.error(exc.message, line, pos + 1) from None
            if op == "->":
                if kind != "M":
                    raise self.error(f"{kind}{number}->: only M-variables take a definition",
                                     line, pos + 1)
                self.meta["ignored"].append({"line": line, "text": text[pos:].strip(),
                                             "why": "M-variable definition"})
                return len(text)
            if op == "==" and kind != "M":
                raise self.error(f"'==' (synchronous assignment) is for M-variables, not "
                                 f"{kind}{number}", line, m.start(3) + 1)
            value, end = self.expression(line, text, m.end(), bare=True)
            self.assign(kind, number, value, line, pos)
            return end
        m = _INDIRECT_RE.match(text, pos)
        if m:
            try:
                number, end = self._indirect_number(text, pos, m)
            except ExprError as exc:
                raise self.error(exc.message, line, exc.col + 1) from None
            except RecursionError:
                raise self.error("expression nested too deeply", line, pos + 1) from None
            eq = _skip(text, end)
            if eq >= len(text) or text[eq] != "=" or text.startswith("==", eq):
                raise self.error(f"{m.group(1)}(...) must be followed by '=' and a value",
                                 line, eq + 1)
            value, end = self.expression(line, text, eq + 1, bare=True)
            self.assign(m.group(1), number, value, line, pos)
            return end
        return None

    def assign(self, kind: str, number: int, value: float, line: int, pos: int) -> None:
        if kind == "P":
            self.p[number] = value
        elif kind == "Q":
            self.q[number] = value
        elif kind == "M":
            self.m[number] = value
            self.meta["m_variables"][number] = value
        else:
            self.i[number] = value
            self.i_line[number] = line
            self.meta["i_variables"][number] = value
            if number == 15:
                self.radians = value != 0
            base = 5000 + 100 * self.coord_system
            if self.in_body and base + 87 <= number <= base + 90:
                if self.blocks:
                    raise self.error(
                        f"I{number} changed after the first move: ccopt does not model changing "
                        f"Isx87..Isx90 while the program runs; set it before OPEN PROG",
                        line, pos + 1)
                self.apply_coordinate_system_defaults()
            elif self.in_body and number == base + 99:
                self.meta["break_cos"] = value

    # -- on-line text of a download file --------------------------------------
    def online_line(self, line: int, text: str) -> None:
        pos = 0
        while True:
            pos = _skip(text, pos)
            if pos >= len(text):
                return
            end = self.assignment(line, text, pos)
            if end is not None:
                pos = end
                continue
            ch = text[pos]
            if ch == "&":
                m = re.compile(r"&[ \t]*(\d+)").match(text, pos)
                if not m or not 1 <= int(m.group(1)) <= 16:
                    raise self.error("'&' needs a coordinate-system number 1..16", line, pos + 1)
                self.coord_system = int(m.group(1))
                self.meta["online"].append({"line": line, "text": m.group(0)})
                pos = m.end()
                continue
            word = _word(text, pos)
            if ch == "#" or word in ("UNDEFINE", "DELETE", "DEFINE"):
                rest = text[pos:].strip()
                m = re.fullmatch(r"DEFINE[ \t]*CCBUF[ \t]*(\d+)", rest)
                if m:
                    self.meta["ccbuf"] = int(m.group(1))
                self.meta["online"].append({"line": line, "text": rest})
                return
            raise self.error(
                f"unexpected {word or ch!r} outside OPEN PROG ... CLOSE: only variable "
                "assignments, &n, #n->..., UNDEFINE, DELETE and DEFINE may stand outside a "
                "program buffer", line, pos + 1)

    # -- program body -----------------------------------------------------------
    def program_line(self, line: int, text: str) -> None:
        self.pending = None
        self.line_mcodes = []
        pos = 0
        while not self.finished:
            pos = _skip(text, pos)
            if pos >= len(text):
                break
            pos = self.statement(line, text, pos)
        self.flush()
        if self.line_mcodes:
            self.meta["ignored"].append({"line": line, "text": " ".join(
                f"M{c}" for c in self.line_mcodes), "why": "M-code call without a move"})
        self.line_mcodes = []

    def statement(self, line: int, text: str, pos: int) -> int:
        ch = text[pos]
        col = pos + 1
        if not ("A" <= ch <= "Z"):
            raise self.error(f"unexpected {ch!r}: expected a command", line, col)
        end = self.assignment(line, text, pos)
        if end is not None:
            return end
        for kw in _KEYWORDS:
            if text.startswith(kw, pos):
                return self.keyword(kw, line, text, pos)
        word = _word(text, pos)
        if len(_LETTERS_RE.match(text, pos).group(0)) > 1:
            hint = ""
            if word.startswith("CIR"):
                hint = ": write CIRCLE1 (clockwise) or CIRCLE2 (counter-clockwise)"
            elif word.startswith("CC"):
                hint = ": ccopt knows CC0, CC1, CC2 and CCR"
            raise self.error(f"unknown command {word!r}{hint}", line, col)
        # single-letter words
        rest = pos + 1
        if ch in _AXES or ch in _VECTORS or ch == "R":
            return self.axis_word(ch, line, text, pos)
        if ch in _OTHER_AXES:
            raise self.error(f"axis {ch} is not supported: ccopt carries X, Y and Z only",
                             line, col)
        if ch == "F":
            value, end = self.data(line, text, rest, "F")
            if not value > 0:
                raise self.error(f"F{value:g}: the feedrate must be positive", line, col)
            self.feed = value * 1000.0 / self.feed_unit_ms
            self.time_mode = False
            return end
        if ch in "NO":
            m = re.compile(r"[NO][ \t]*\d+").match(text, pos)
            if not m:
                raise self.error(f"label {ch} needs a number", line, col)
            return m.end()
        if ch in "PQ":
            raise self.error(f"{_word(text, pos) or ch}: a {ch}-variable on its own is not a "
                             "program statement; write {var}={expression}", line, col)
        if ch == "M":
            value, end = self.data(line, text, rest, "M")
            if value != int(value) or value < 0:
                raise self.error(f"M{value:g}: an M-code must be a non-negative integer",
                                 line, col)
            self.line_mcodes.append(int(value))
            return end
        if ch in "GTD":
            raise self.error(f"{ch}-codes are not supported: PMAC runs them as calls into PROG "
                             f"10x0-10x3 subroutines that ccopt cannot see", line, col)
        raise self.error(f"unknown command {_word(text, pos)!r}", line, col)

    def keyword(self, kw: str, line: int, text: str, pos: int) -> int:
        col = pos + 1
        end = pos + len(kw)
        if kw in _MOVE_MODES:
            self.flush()
            self.mode = _MOVE_MODES[kw]
            return end
        if kw in _UNSUPPORTED_MODES:
            raise self.error(f"unsupported move mode {kw}: ccopt reads LINEAR, CIRCLE1, CIRCLE2 "
                             "and RAPID moves", line, col)
        if kw in _UNSUPPORTED:
            raise self.error(f"unsupported command {kw}: {_UNSUPPORTED_WHY}", line, col)
        if kw in ("ABS", "INC"):
            self.flush()
            return self.abs_inc(kw == "INC", line, text, end)
        if kw in ("TA", "TS", "TM"):
            value, end = self.data(line, text, end, kw)
            value = self.nonnegative(value, kw, line, col) / 1000.0
            if kw == "TA":
                self.accel_time = value
            elif kw == "TS":
                self.scurve_time = value
            else:
                self.move_time = value
                self.time_mode = True
            return end
        if kw in ("DWELL", "DWE", "DELAY", "DLY"):
            self.flush()
            value, end = self.data(line, text, end, kw)
            value = self.nonnegative(value, kw, line, col)
            p = tuple(self.pos)
            if kw in ("DELAY", "DLY"):
                self.meta["delay_blocks"].append(len(self.blocks))
            self.blocks.append(self.block(Source(self.file, line, col), Motion.DWELL, p, p,
                                          dwell=value / 1000.0))
            return end
        if kw in ("CC0", "CC1", "CC2"):
            self.flush()
            self.programmed_side = {"CC0": 0, "CC1": 1, "CC2": -1}[kw]
            return end
        if kw in ("CC3", "CC4"):
            raise self.error(f"{kw} is not supported: ccopt does 2-D compensation with CC0, CC1 "
                             "and CC2", line, col)
        if kw == "CCR":
            self.flush()
            value, end = self.data(line, text, end, "CCR")
            self.radius = abs(value)
            self.radius_sign = -1 if value < 0 else 1
            return end
        if kw in ("NORMAL", "NRM"):
            self.flush()
            return self.normal(line, text, end, col)
        if kw == "FRAX":
            m = re.compile(r"FRAX([ \t]*\([ \t]*([A-Z ,\t]*)\))?").match(text, pos)
            axes = set(re.findall(r"[A-Z]", m.group(2) or "")) if m.group(1) else set()
            if m.group(1) and axes != set("XYZ"):
                raise self.error("FRAX with other feedrate axes than X, Y, Z is not supported "
                                 "(ccopt's feed is the X-Y-Z vector speed)", line, col)
            return m.end()
        if kw in ("RETURN", "RET"):
            self.flush()
            self.finished = True
            return len(text)
        if kw in ("OPEN", "CLOSE", "CLEAR"):
            raise self.error(f"{kw} must stand alone on its line", line, col)
        if kw in ("DEFINE", "DELETE", "UNDEFINE"):
            raise self.error(f"{kw} is an on-line command: put it outside OPEN PROG ... CLOSE",
                             line, col)
        raise AssertionError(kw)  # pragma: no cover - every keyword is handled above

    def abs_inc(self, incremental: bool, line: int, text: str, pos: int) -> int:
        p = _skip(text, pos)
        if p < len(text) and text[p] == "(":
            close = text.find(")", p)
            if close < 0:
                raise self.error("unterminated axis list: missing ')'", line, p + 1)
            names = [s.strip() for s in text[p + 1:close].split(",")]
            for k, name in enumerate(names):
                if name == "R":
                    self.vector_absolute = not incremental
                elif name in _AXES:
                    self.incremental[name] = incremental
                elif name in _OTHER_AXES:
                    pass  # other axes never move in a ccopt program
                else:
                    raise self.error(f"{'INC' if incremental else 'ABS'}(...): expected axis "
                                     f"letters or R, found {name!r}", line, p + 2)
            return close + 1
        for a in _AXES:
            self.incremental[a] = incremental
        return pos

    def normal(self, line: int, text: str, pos: int, col: int) -> int:
        comps = {"I": 0.0, "J": 0.0, "K": 0.0}
        seen = False
        while True:
            p = _skip(text, pos)
            if p < len(text) and text[p] in comps and not text.startswith("INC", p):
                value, pos = self.data(line, text, p + 1, f"NORMAL {text[p]}")
                comps[text[p]] = value
                seen = True
                continue
            break
        if not seen:
            raise self.error("NORMAL needs a vector, e.g. NORMAL K-1", line, col)
        nonzero = [k for k, v in comps.items() if v != 0.0]
        if len(nonzero) == 1 and comps[nonzero[0]] < 0:
            self.plane = {"K": "XY", "J": "ZX", "I": "YZ"}[nonzero[0]]
            return pos
        vec = " ".join(f"{k}{v:g}" for k, v in comps.items())
        raise self.error(f"unsupported NORMAL {vec}: ccopt supports NORMAL K-1 (XY plane), "
                         "J-1 (ZX) and I-1 (YZ)", line, col)

    # -- moves ------------------------------------------------------------------
    def axis_word(self, letter: str, line: int, text: str, pos: int) -> int:
        value, end = self.data(line, text, pos + 1, letter)
        if self.pending is None:
            self.pending = _Pending(line, pos + 1)
        pend = self.pending
        if letter in pend.words:
            raise self.error(f"{letter} is written twice in one move", line, pos + 1)
        pend.words.add(letter)
        if letter in _AXES:
            pend.axes[letter] = (value, self.incremental[letter])
        elif letter in _VECTORS:
            pend.vector[letter] = value
        else:
            pend.radius = value
        return end

    def flush(self) -> None:
        """Execute the move written so far on this line, if any."""
        pend, self.pending = self.pending, None
        if pend is None:
            return
        line, col = pend.line, pend.col
        if not pend.axes:
            raise self.error("a centre vector or radius without an end point: write the end "
                             "point (X, Y, Z) on the same line", line, col)
        start = tuple(self.pos)
        end = list(start)
        for i, a in enumerate(_AXES):
            if a in pend.axes:
                value, inc = pend.axes[a]
                end[i] = start[i] + value if inc else value
        end_t = _finite_point(end, self, line, col, "end point")
        source = Source(self.file, line, col)
        has_centre = bool(pend.vector) or pend.radius is not None
        mcodes = tuple(self.line_mcodes)
        self.line_mcodes = []
        if self.mode == "RAPID":
            if has_centre:
                raise self.error("I/J/K or R on a RAPID move: only CIRCLE moves take a centre",
                                 line, col)
            block = self.block(source, Motion.RAPID, start, end_t, mcodes=mcodes)
        else:
            feed, move_time = self.feed_or_time(line, col)
            if self.mode == "LINEAR":
                if has_centre:
                    raise self.error("I/J/K or R on a LINEAR move: put CIRCLE1 or CIRCLE2 "
                                     "before it", line, col)
                block = self.block(source, Motion.LINE, start, end_t, feed=feed,
                                   move_time=move_time, mcodes=mcodes)
            else:
                end_t, centre = self.circle_centre(pend, start, end_t, line, col)
                motion = Motion.ARC_CW if self.mode == "CIRCLE1" else Motion.ARC_CCW
                block = self.block(source, motion, start, end_t, center=centre, feed=feed,
                                   move_time=move_time, mcodes=mcodes)
        self.blocks.append(block)
        self.pos = list(end_t)

    def feed_or_time(self, line: int, col: int) -> tuple[float | None, float | None]:
        if self.time_mode:
            return None, self.move_time
        if self.feed is None:
            raise self.error(f"{self.mode} move without a speed: give F (units per second) or "
                             "TM (move time in ms) before it", line, col)
        return self.feed, None

    def circle_centre(self, pend: _Pending, start: Vec3, end: Vec3, line: int,
                      col: int) -> tuple[Vec3, Vec3]:
        """Absolute centre of a CIRCLE move (and the end, snapped for a full circle)."""
        iu, iv, iw = PLANE_AXES[self.plane]
        su, sv = start[iu], start[iv]
        eu, ev = end[iu], end[iv]
        if pend.vector and pend.radius is not None:
            raise self.error("give either the centre vector I/J/K or the radius R, not both",
                             line, col)
        if not pend.vector and pend.radius is None:
            raise self.error(f"{self.mode} move without a centre: give the vector I/J/K or "
                             "the radius R", line, col)
        scale = max(1.0, abs(su), abs(sv), abs(eu), abs(ev))
        same = math.hypot(eu - su, ev - sv) <= POINT_EPS * scale
        if pend.radius is not None:
            r = pend.radius
            if r == 0:
                raise self.error("R0: the arc radius must not be zero", line, col)
            if same:
                raise self.error("R cannot make a full circle (PMAC: the end must differ from "
                                 "the start); use the centre vector I/J/K", line, col)
            chord = math.hypot(eu - su, ev - sv)
            half = chord / 2.0
            if abs(r) < half * (1.0 - R_CHORD_REL_TOL):
                raise self.error(f"R{r:g} is too small for the chord {chord:g} from the start "
                                 f"to the end point (|R| must be at least {half:g})", line, col)
            h = math.sqrt(max(0.0, (abs(r) - half) * (abs(r) + half)))
            # Unit normal to the left of the chord start -> end.
            nu, nv = -(ev - sv) / chord, (eu - su) / chord
            ccw = self.mode == "CIRCLE2"
            side = (1.0 if ccw else -1.0) * (1.0 if r > 0 else -1.0)
            cu = (su + eu) / 2.0 + side * h * nu
            cv = (sv + ev) / 2.0 + side * h * nv
        else:
            vec = [pend.vector.get(k, 0.0) for k in _VECTORS]
            if self.vector_absolute:
                cu, cv = vec[iu], vec[iv]
            else:
                cu, cv = su + vec[iu], sv + vec[iv]
            if math.hypot(su - cu, sv - cv) <= POINT_EPS * scale:
                raise self.error("the arc centre is on the start point: the centre vector "
                                 "I/J/K must not be zero (INC(R)) or the start (ABS(R))",
                                 line, col)
            if same:
                end_l = list(end)
                end_l[iu], end_l[iv] = su, sv
                end = tuple(end_l)
            elif math.hypot(eu - cu, ev - cv) <= POINT_EPS * scale:
                raise self.error("the arc centre is on the end point", line, col)
        centre = [0.0, 0.0, 0.0]
        centre[iu], centre[iv], centre[iw] = cu, cv, start[iw]
        return end, _finite_point(centre, self, line, col, "arc centre")

    def block(self, source: Source, motion: Motion, start: Vec3, end: Vec3, **kw) -> Block:
        modal = Modal(plane=self.plane, units="mm",
                      side=self.programmed_side * self.radius_sign,
                      radius=self.radius, accel_time=self.accel_time,
                      scurve_time=self.scurve_time)
        return Block(source=source, motion=motion, start=start, end=end, modal=modal, **kw)


# ----------------------------------------------------------------------------
def _skip(text: str, pos: int) -> int:
    while pos < len(text) and text[pos] in " \t":
        pos += 1
    return pos


def _word(text: str, pos: int) -> str:
    m = re.compile(r"[A-Z][A-Z0-9]*").match(text, pos)
    return m.group(0) if m else ""


def _hex_value(digits: str, pos: int) -> float:
    try:
        value = float(int(digits, 16))
    except OverflowError:
        raise ExprError(f"${digits}: hexadecimal constant too large", pos) from None
    if not math.isfinite(value):  # pragma: no cover - float(int) raises instead
        raise ExprError(f"${digits}: hexadecimal constant too large", pos)
    return value


def _check_finite_expr(value: float, pos: int) -> float:
    if not math.isfinite(value):
        raise ExprError("value is not a finite number (too large?)", pos)
    return value


def _bitwise(a: float, b: float, op) -> float:
    """PMAC bit-by-bit operators on fixed-point values (fractional bits too)."""
    scale = 1 << _FRACTION_BITS
    try:
        ia, ib = round(a * scale), round(b * scale)
    except OverflowError:
        raise ValueError("operand of a bit-by-bit operator too large") from None
    return op(ia, ib) / scale


def _finite_point(p, reader: _Reader, line: int, col: int, what: str) -> Vec3:
    if not all(math.isfinite(v) for v in p):
        raise reader.error(f"{what} is not a finite number (values too large)", line, col)
    return (float(p[0]), float(p[1]), float(p[2]))

