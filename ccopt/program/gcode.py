"""ISO/RS274NGC G-code reader (LinuxCNC dialect, plus Fagor G136-G139).

:func:`read_gcode` runs a part program the way LinuxCNC's interpreter reads
it and returns an immutable :class:`~ccopt.program.model.Program`: one
:class:`~ccopt.program.model.Block` per executed move (``G0`` rapid, ``G1``
line, ``G2``/``G3`` arc) or dwell (``G4``), in execution order, with O-word
subroutines, branches and loops already expanded. Each block points at the
line that wrote it (a move inside a subroutine points at the subroutine's
line, not at the call).

Units and signs
---------------
* Coordinates are absolute ``(x, y, z)`` in program units (mm after ``G21``,
  the default, or inch after ``G20``); nothing is converted between units.
* Feeds are tangential speeds in program units **per second**: ``G94``
  ``F`` (units per minute) becomes ``F/60``; under ``G93`` inverse time a move
  must take ``60/F`` seconds, so its feed is ``length*F/60`` with the exact
  length (a helix combines in-plane arc length ``a`` and the normal travel
  ``dw`` as ``sqrt(a**2 + dw**2)``; an arc whose end radius differs slightly
  from its start radius, within the tolerance, uses the mean radius).
* Arcs follow :data:`~ccopt.program.model.PLANE_AXES`: ``G17`` (u, v) =
  (X, Y) with centre words I, J; ``G18`` (u, v) = (Z, X) with K, I; ``G19``
  (u, v) = (Y, Z) with J, K. ``G2`` is clockwise and ``G3`` counter-clockwise
  seen looking down the plane normal w (Z, Y, X respectively), exactly as
  LinuxCNC's ``convert_arc`` passes the axes to ``ARC_FEED``.
* Compensation side is +1 for ``G41`` (left) and -1 for ``G42`` (right).

Language (case-insensitive; spaces and tabs may appear anywhere between and
inside words, as RS274NGC strips them: ``G 1 X 1 0`` is ``G1 X10``)
---------------------------------------------------------------------------
Words ``G M X Y Z I J K R F P D H T S N Q``; values are numbers, ``#n``,
``#<name>``, ``#[expr]``, ``[expr]`` or unary functions such as
``SIN[30]`` / ``ATAN[a]/[b]`` (evaluated by :mod:`ccopt.program.expr`,
trigonometry in degrees). Comments ``( ... )`` and ``;`` to the end of the
line. ``#n = value`` and ``#<name> = value`` settings take effect after all
the words of their line have been read. O-words: ``sub``/``endsub``/``call``
(with up to 30 ``[arg]``), ``return [v]``, ``if``/``elseif``/``else``/
``endif``, ``do``/``while``, ``while``/``endwhile``, ``repeat``/``endrepeat``,
``break``, ``continue``; labels ``oN`` or ``o<name>``.

G-codes: motion ``G0 G1 G2 G3 G80``; dwell ``G4 P<seconds>``; planes
``G17 G18 G19``; units ``G20 G21``; distance ``G90 G91`` (XYZ) and arc-centre
distance ``G90.1 G91.1`` (IJK, default ``G91.1`` incremental); feed mode
``G93 G94``; compensation ``G40 G41 G42 G41.1 G42.1``; Fagor ``G136``
(corner "circular", default) ``G137`` ("linear"), ``G138`` (start/end
"direct") ``G139`` ("contour", default).

Harmless preamble codes accepted as no-ops (they do not change the path
ccopt computes):

* ``G49`` tool length compensation off, ``G43 [H]`` tool length compensation
  on: it only offsets Z along the tool axis, never the compensation plane;
  each use is recorded in ``Program.meta["tool_length"]`` as
  ``(line, "G43"|"G49", H or None)``.
* ``G80`` cancels the motion mode (axis words then need a new G0-G3).
* ``G54``: work offsets are unknown to ccopt, so coordinates stay program
  coordinates. Other work offsets (``G55``...) are rejected, because
  switching between them would move the path.
* ``G61``, ``G61.1``, ``G64 [P] [Q]``: path-control (blending) modes of the
  trajectory planner; ccopt plans its own feed.
* ``S`` spindle speed, ``T`` tool select, ``M`` codes (recorded in
  ``Block.mcodes``; ``M6`` loads the selected tool; ``M2``/``M30`` end the
  program: nothing after them executes), ``N`` line numbers (first word
  only), a Fanuc program number ``O1234`` alone on a line
  (``Program.meta["program_number"]``), ``%`` lines.

Decisions (each is the one place where that behaviour is decided)
-----------------------------------------------------------------
* Cutter radius: ``G41``/``G42 D<n>`` take tool NUMBER ``n`` (a non-negative
  integer) and radius ``tool_table[n]/2``; without ``D`` they use the tool
  loaded by ``T<n> M6``. With no tool table, or a tool missing from it, the
  radius stays ``None`` and ``Modal.tool`` carries the tool number. With no
  tool loaded at all, both stay ``None``. ``G41.1``/``G42.1 D<d>`` take the
  tool DIAMETER: radius ``|d|/2``; a negative diameter (also from the tool
  table) flips the side; ``D0`` keeps the side with radius 0. ``G40`` keeps
  the last radius and tool in ``Modal`` (side 0). A compensation code while
  compensation is already on is accepted here (LinuxCNC refuses it, PMAC and
  Fagor change side/radius): the compensation style decides.
* ``G0``/``G1`` with no axis word only set the motion mode (no block, no feed
  check); ``G2``/``G3`` with no axis word but a centre is a full circle (as
  LinuxCNC). A move with axis words always makes a block, even of zero
  length (Fagor's cancellation semantics depend on it).
* Arc radii: an I/J/K arc whose end radius differs from its start radius by
  more than ``tolerances.ARC_RADIUS_ABS_TOL_MM`` (scaled by 1/25.4 in inch)
  AND by more than ``ARC_RADIUS_REL_TOL`` relative is an error; the same
  absolute tolerance decides whether an ``R`` is too small for the chord.
  Radii below a tenth of the absolute tolerance are zero (LinuxCNC).
* Feed mode: switching ``G93`` <-> ``G94`` forgets the feed rate (an F must
  follow); LinuxCNC also forgets it on a redundant ``G94``, we do not.
* Units: ``G20``/``G21`` may be repeated, but changing units after the first
  move is an error (ccopt keeps one unit per program).
* Subroutines may be defined before or after the call: an unknown sub is
  looked for forward from the call, as LinuxCNC (2.6 and later) does. A
  definition is registered when execution passes it (it is then skipped).
  Sub definitions cannot be nested. ``#1``..``#30`` are local to a call
  (arguments, then 0), named parameters without a leading underscore are
  local to the sub (or main program) that sets them; ``#<_name>`` are global.
  ``return [v]``/``endsub [v]`` set ``#<_value>`` and ``#<_value_returned>``.
* O-word structures must nest properly and close with the same label; this
  is checked when execution reaches the structure (so text after ``M2`` is
  never checked, as in LinuxCNC).
* Reading an unset numbered parameter gives 0; an unset named parameter is
  an error. Numbered parameters run from 1 to 5601.
* ``%``: a ``%`` line before any code opens the program and the next ``%``
  line ends it; without an opening ``%``, a ``%`` line ends the program. The
  end of the text also ends the program (no ``M2`` needed).
* Runaway guards: more than :data:`MAX_EXECUTED_LINES` executed lines, or
  subroutine calls nested deeper than :data:`MAX_CALL_DEPTH`, are errors
  naming the line.
* Not supported (errors that say so): other axes (A B C U V W), ``L`` and
  ``E`` words, block delete ``/``, canned cycles, ``G10``, ``G28``, ``G53``,
  ``G92``, ``G95``, ``M98``/``M99`` Fanuc subprograms, external sub files,
  ``EXISTS[]``.

Every problem raises :class:`~ccopt.errors.ProgramError` with the file, the
1-based line and (where meaningful) the 1-based column; no other exception
escapes :func:`read_gcode`, whatever the text.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ccopt import tolerances
from ccopt.errors import ProgramError
from ccopt.program.expr import (
    GCODE_BINARY,
    GCODE_FUNCTIONS,
    ExprError,
    Grammar,
    parse_bracketed,
    parse_operand,
)
from ccopt.program.model import PLANE_AXES, Block, Modal, Motion, Program, Source

__all__ = ["read_gcode", "MAX_EXECUTED_LINES", "MAX_CALL_DEPTH"]

#: Executed lines (loops and calls counted each time) before the reader
#: gives up on a runaway program.
MAX_EXECUTED_LINES = 1_000_000
#: Deepest subroutine call nesting accepted.
MAX_CALL_DEPTH = 100
#: Highest numbered parameter (LinuxCNC RS274NGC_MAX_PARAMETERS - 1).
MAX_PARAMETER = 5601
#: Positional parameters #1..#30 local to a call.
SUB_PARAMS = 30
#: Largest G2/G3 P (number of turns), LinuxCNC keeps it in an int.
MAX_ARC_TURNS = 2**31 - 1

MM_PER_INCH = 25.4
_TWO_PI = 2.0 * math.pi

# G-codes ccopt knows, in tenths (G41.1 -> 411), with their modal group.
_G_GROUPS: dict[int, str] = {
    0: "motion", 10: "motion", 20: "motion", 30: "motion", 800: "motion",
    40: "dwell",
    170: "plane", 180: "plane", 190: "plane",
    200: "units", 210: "units",
    400: "comp", 410: "comp", 420: "comp", 411: "comp", 421: "comp",
    430: "length", 490: "length",
    540: "coord",
    610: "path", 611: "path", 640: "path",
    900: "distance", 910: "distance",
    901: "arc_distance", 911: "arc_distance",
    930: "feed_mode", 940: "feed_mode",
    1360: "corner", 1370: "corner",
    1380: "start_end", 1390: "start_end",
}
_KNOWN_G = ("G0 G1 G2 G3 G4 G17 G18 G19 G20 G21 G40 G41 G42 G41.1 G42.1 G43 G49 "
            "G54 G61 G61.1 G64 G80 G90 G91 G90.1 G91.1 G93 G94 G136 G137 G138 G139")
_G_UNSUPPORTED_HINT: dict[int, str] = {
    **{t: "work offsets other than G54 would move the path; ccopt works in program "
          "coordinates: remove it or use G54" for t in (550, 560, 570, 580, 590, 591, 592, 593)},
    950: "feed per revolution is not supported: use G94 (units per minute) or G93",
    100: "G10 (setting offsets/tool data) is not supported: give the tool table to ccopt instead",
    280: "homing moves are not supported", 300: "homing moves are not supported",
    530: "machine-coordinate moves are not supported",
    920: "coordinate offsets (G92) are not supported",
    921: "coordinate offsets are not supported", 922: "coordinate offsets are not supported",
    923: "coordinate offsets are not supported",
}
# M-code modal groups that may not appear twice on a line.
_M_GROUPS: dict[int, str] = {0: "stop", 1: "stop", 2: "stop", 30: "stop", 60: "stop",
                             6: "tool change", 3: "spindle", 4: "spindle", 5: "spindle",
                             7: "coolant", 8: "coolant", 9: "coolant"}

_WORD_LETTERS = set("GMXYZIJKRFPDHTSQ")
_UNSUPPORTED_AXES = set("ABCUVW")
_AXES = "XYZ"
_O_KEYWORDS = ("sub", "endsub", "call", "do", "while", "endwhile", "if", "elseif",
               "else", "endif", "break", "continue", "return", "repeat", "endrepeat")
_OPENERS = {"sub": "endsub", "if": "endif", "do": "while", "while": "endwhile",
            "repeat": "endrepeat"}
_CLOSERS = {"endsub": "sub", "endif": "if", "endwhile": "while", "endrepeat": "repeat"}
# Centre words of an arc per plane: (u word, v word), and the word that has no use.
_CENTRE_WORDS = {"XY": ("I", "J"), "ZX": ("K", "I"), "YZ": ("J", "K")}
_FORBIDDEN_CENTRE = {"XY": "K", "ZX": "J", "YZ": "I"}
_PLANE_G = {"XY": "G17", "ZX": "G18", "YZ": "G19"}
_FUNC_NAMES = sorted(set(GCODE_FUNCTIONS) | {"ATAN"}, key=len, reverse=True)

_LINE_SPLIT = re.compile(r"\r\n|\r|\n")
_BLANKS = re.compile(r"[ \t]*")
# A literal number not followed by a blank and a digit (the common, fast case).
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?![.\d]|[ \t]+[.\d])")


def _fmt(x: float) -> str:
    """A number for a message: short, no trailing zeros."""
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.6g}"


def _gname(tenths: int) -> str:
    return f"G{tenths // 10}" if tenths % 10 == 0 else f"G{tenths // 10}.{tenths % 10}"


def _olabel(label: str) -> str:
    return f"o{label}" if label.isdigit() else f"o<{label}>"


class _Stop(Exception):
    """Program end (M2/M30) reached."""


# ---------------------------------------------------------------------------
# Lexing: comments, characters, N and O words (static, cached per line)
# ---------------------------------------------------------------------------
@dataclass(slots=True)
class _OWord:
    label: str
    keyword: str | None  # None: Fanuc program number "O1234" alone on a line
    col: int             # 0-based column of the 'O'
    rest: int            # position after the keyword


@dataclass(slots=True)
class _Lexed:
    code: str                 # the line with comments turned into spaces
    first: int | None         # 0-based column of the first word (None: no code)
    start: int                # position of the first word after an N word
    oword: _OWord | None = None
    percent: bool = False


def _is_blank(ch: str) -> bool:
    return ch == " " or ch == "\t"


class _Reader:
    """Executes one program text; see :func:`read_gcode`."""

    def __init__(self, text: str, file: str, tool_table, start):
        self.file = file
        self.lines = _LINE_SPLIT.split(text)
        if self.lines and self.lines[-1] == "":
            self.lines.pop()
        self._lexed: dict[int, _Lexed] = {}
        self._match: dict[int, tuple] = {}
        self._constant: dict[int, _Words] = {}
        self.tool_table = tool_table
        self.grammar = Grammar("[", "]", GCODE_BINARY, GCODE_FUNCTIONS, atan2_form=True,
                               variable=self._variable)
        # machine state
        self.pos = start
        self.start = start
        self.blocks: list[Block] = []
        self.moved = False
        self.plane = "XY"
        self.units: str | None = None
        self.incremental = False
        self.arc_incremental = True
        self.feed_mode = "per_minute"
        self.feed: float | None = None      # G94 F, units per minute
        self.motion_mode: int | None = None  # tenths; None = G80
        self.side = 0
        self.radius: float | None = None
        self.tool: int | None = None
        self.selected_tool: int | None = None
        self.loaded_tool: int | None = None
        self.corner = "circular"
        self.start_end = "contour"
        self._modal: Modal | None = None
        self.meta: dict = {"tool_length": []}
        # parameters
        self.params: dict[int, float] = {}
        self.globals: dict[str, float] = {"_value": 0.0, "_value_returned": 0.0}
        # control
        self.subs: dict[str, tuple[int, int]] = {}
        self.frames: list[_Frame] = [_Frame(name=None, return_pc=-1, call_line=-1)]
        self.line_no = 0          # 0-based index of the line being executed
        self.executed = 0
        self.first_line, self.end_line = self._program_span()

    # -- errors ------------------------------------------------------------
    def error(self, message: str, col: int | None = None, line: int | None = None) -> ProgramError:
        """A located error; ``col`` is 0-based (None: unknown), ``line`` 0-based."""
        ln = self.line_no if line is None else line
        return ProgramError(message, self.file, ln + 1, None if col is None else col + 1)

    # -- lexing ------------------------------------------------------------
    def lex(self, i: int) -> _Lexed:
        lx = self._lexed.get(i)
        if lx is None:
            lx = self._lex(i)
            self._lexed[i] = lx
        return lx

    def _lex(self, i: int) -> _Lexed:
        text = self.lines[i]
        code = self._blank_comments(text, i)
        n = len(code)
        p = 0
        while p < n and _is_blank(code[p]):
            p += 1
        if p >= n:
            return _Lexed(code, None, n)
        if code[p] == "%":
            q = p + 1
            while q < n and _is_blank(code[q]):
                q += 1
            if q < n:
                raise self.error("a '%' line must hold nothing else", q, i)
            return _Lexed(code, None, n, percent=True)
        first = p
        if code[p] in "nN":
            q = p + 1
            while q < n and _is_blank(code[q]):
                q += 1
            digits = 0
            while q < n and (code[q].isdigit() or code[q] == "." or _is_blank(code[q])):
                digits += code[q].isdigit()
                q += 1
            if not digits:
                raise self.error("N word (line number) has no number: write e.g. N10", p, i)
            p = q
        lx = _Lexed(code, first, p)
        if p < n and code[p] in "oO":
            lx.oword = self._lex_oword(code, p, i)
        return lx

    def _blank_comments(self, text: str, i: int) -> str:
        """``text`` with comments replaced by spaces (columns kept); checks characters."""
        if "(" not in text and ";" not in text:
            if text.isascii() and text.isprintable():
                return text
        out = list(text)
        opened = -1
        for k, ch in enumerate(text):
            if opened >= 0:
                out[k] = " "
                if ch == ")":
                    opened = -1
                elif ch == "(":
                    raise self.error("'(' inside a comment: comments cannot be nested; "
                                     "remove the inner '('", k, i)
            elif ch == "(":
                opened = k
                out[k] = " "
            elif ch == ";":
                out[k:] = " " * (len(text) - k)
                break
            elif not (ch == "\t" or " " <= ch <= "~"):
                raise self.error(f"character {ch!r} (U+{ord(ch):04X}) is not allowed outside "
                                 "comments: G-code is plain ASCII", k, i)
        if opened >= 0:
            raise self.error("unterminated comment: add ')' to close the '(' opened here",
                             opened, i)
        return "".join(out)

    def _lex_oword(self, code: str, p: int, i: int) -> _OWord:
        n = len(code)
        col = p
        q = p + 1
        while q < n and _is_blank(code[q]):
            q += 1
        if q < n and code[q] == "<":
            end = code.find(">", q)
            if end < 0:
                raise self.error("O-word name has no closing '>'", q, i)
            label = "".join(code[q + 1:end].split()).lower()
            if not label:
                raise self.error("empty O-word name '<>'", q, i)
            q = end + 1
        else:
            digits = []
            while q < n and (code[q].isdigit() or _is_blank(code[q])):
                if code[q].isdigit():
                    digits.append(code[q])
                q += 1
            if not digits:
                raise self.error("O-word needs a number or a <name>, e.g. o100 or o<part>", col, i)
            label = str(int("".join(digits)))
        while q < n and _is_blank(code[q]):
            q += 1
        if q >= n:
            if not label.isdigit():
                raise self.error(f"{_olabel(label)} needs a keyword: sub, endsub, call, if, "
                                 "elseif, else, endif, do, while, endwhile, repeat, endrepeat, "
                                 "break, continue or return", col, i)
            return _OWord(label, None, col, q)
        k = q
        while k < n and ("a" <= code[k].lower() <= "z"):
            k += 1
        keyword = code[q:k].lower()
        if keyword not in _O_KEYWORDS:
            if not keyword:
                raise self.error(f"unexpected {code[q]!r} after {_olabel(label)}: a program number "
                                 "O-word must be alone on its line, a control O-word needs a "
                                 "keyword (sub, call, if, while, ...)", q, i)
            hint = (f" (a program number {_olabel(label).upper()} must be alone on its line)"
                    if label.isdigit() else "")
            raise self.error(f"unknown O-word keyword {keyword!r}{hint}: use sub, endsub, call, "
                             "if, elseif, else, endif, do, while, endwhile, repeat, endrepeat, "
                             "break, continue or return", q, i)
        return _OWord(label, keyword, col, k)

    def _program_span(self) -> tuple[int, int]:
        """Lines ``[first, end)`` that form the program (``%`` handling)."""
        first = 0
        n = len(self.lines)
        i = 0
        while i < n:
            lx = self.lex(i)
            if lx.percent:
                first = i + 1
                break
            if lx.first is not None:
                break
            i += 1
        j = first
        while j < n:
            if "%" in self.lines[j] and self.lex(j).percent:
                return first, j
            j += 1
        return first, n

    # -- parameters --------------------------------------------------------
    @staticmethod
    def _skip(code: str, p: int) -> int:
        return _BLANKS.match(code, p).end()

    def _variable(self, text: str, pos: int):
        if text[pos] != "#":
            return None
        return self._read_parameter(text, pos)

    def _read_parameter(self, code: str, pos: int) -> tuple[float, int]:
        """Value of the parameter reference at ``code[pos] == '#'``."""
        kind, key, end = self._parameter_target(code, pos)
        if kind == "name":
            value = self._get_named(key, pos)
        else:
            value = self.params.get(key, 0.0)
        return value, end

    def _parameter_target(self, code: str, pos: int) -> tuple[str, object, int]:
        """Parse ``#n``, ``#[expr]``, ``##n`` or ``#<name>`` at ``pos``."""
        p = self._skip(code, pos + 1)
        n = len(code)
        if p >= n:
            raise ExprError("'#' needs a parameter number or <name>, e.g. #1 or #<depth>", pos)
        ch = code[p]
        if ch == "<":
            end = code.find(">", p)
            if end < 0:
                raise ExprError("parameter name has no closing '>'", p)
            name = "".join(code[p + 1:end].split()).lower()
            if not name:
                raise ExprError("empty parameter name '#<>'", p)
            return "name", name, end + 1
        if ch.isdigit() or ch == ".":
            value, end = self._read_number(code, p, "#")
        elif ch == "[":
            value, end = parse_bracketed(code, p, self.grammar)
        elif ch == "#":
            value, end = self._read_parameter(code, p)
        else:
            raise ExprError("'#' needs a parameter number or <name>, e.g. #1 or #<depth>", pos)
        if not math.isfinite(value) or abs(value - round(value)) > 1e-4:
            raise ExprError(f"parameter number {_fmt(value)} is not an integer", pos)
        index = int(round(value))
        if not 1 <= index <= MAX_PARAMETER:
            raise ExprError(f"parameter number #{index} out of range: use #1 to #{MAX_PARAMETER}",
                            pos)
        return "index", index, end

    def _get_named(self, name: str, col: int) -> float:
        if not name.startswith("_"):
            local = self.frames[-1].named
            if name in local:
                return local[name]
        elif name in self.globals:
            return self.globals[name]
        raise ExprError(f"named parameter #<{name}> is not set: assign it first "
                        f"(#<{name}> = ...)", col)

    def _set(self, kind: str, key, value: float) -> None:
        if kind == "name":
            if key.startswith("_"):
                self.globals[key] = value
            else:
                self.frames[-1].named[key] = value
        else:
            self.params[key] = value

    # -- values --------------------------------------------------------------
    def _read_number(self, code: str, p: int, letter: str) -> tuple[float, int]:
        """A literal number (sign, digits, one point; blanks allowed inside)."""
        m = _NUMBER.match(code, p)
        if m is not None:
            value = float(m.group())
            if math.isfinite(value):
                return value, m.end()
        n = len(code)
        start = p
        chars = []
        if code[p] in "+-":
            chars.append(code[p])
            p = self._skip(code, p + 1)
        dots = 0
        digits = 0
        while p < n:
            ch = code[p]
            if ch.isdigit():
                chars.append(ch)
                digits += 1
            elif ch == ".":
                dots += 1
                if dots > 1:
                    raise ExprError(f"number with two decimal points after {letter}", p)
                chars.append(ch)
            elif _is_blank(ch):
                # RS274NGC ignores blanks: "X1 0" is X10, but not across another
                # word or a comment (comments are blanked in ``code``).
                q = self._skip(code, p)
                original = self.lines[self.line_no]
                if q < n and (code[q].isdigit() or code[q] == ".") and \
                        original[p:q].strip(" \t") == "":
                    p = q
                    continue
                break
            else:
                break
            p += 1
        if not digits:
            raise ExprError(f"{letter} word has no value: write a number after {letter}", start)
        value = float("".join(chars))
        if not math.isfinite(value):
            raise ExprError(f"number after {letter} is too large", start)
        return value, p

    def _read_value(self, code: str, p: int, letter: str, letter_col: int) -> tuple[float, int]:
        """A word value at ``p``: number, parameter, [expression] or unary function."""
        n = len(code)
        negate = False
        p = self._skip(code, p)
        while p < n and code[p] in "+-":
            q = self._skip(code, p + 1)
            if q < n and (code[q].isdigit() or code[q] == "."):
                break
            if code[p] == "-":
                negate = not negate
            p = q
        if p >= n:
            raise ExprError(f"{letter} word has no value: write a number after {letter}",
                            letter_col)
        ch = code[p]
        if ch.isdigit() or ch in ".+-":
            value, end = self._read_number(code, p, letter)
        elif ch == "[" or ch == "#":
            value, end = parse_operand(code, p, self.grammar)
        elif ch.isalpha():
            up = code[p:p + 5].upper()
            if not any(up.startswith(f) for f in _FUNC_NAMES):
                raise ExprError(f"{letter} word has no value (found {ch!r}): write a number, "
                                "#parameter or [expression] after it", letter_col)
            value, end = parse_operand(code, p, self.grammar)
        else:
            raise ExprError(f"{letter} word has no value (found {ch!r}): write a number, "
                            "#parameter or [expression] after it", letter_col)
        if not math.isfinite(value):
            raise ExprError(f"value of {letter} is not a finite number", p)
        return (-value if negate else value), end

    # -- main loop -----------------------------------------------------------
    def run(self) -> Program:
        pc = self.first_line
        try:
            while pc < self.end_line:
                self.line_no = pc
                self.executed += 1
                if self.executed > MAX_EXECUTED_LINES:
                    raise self.error(f"more than {MAX_EXECUTED_LINES} lines executed: endless "
                                     "loop or runaway recursion? check the loop conditions")
                try:
                    lx = self.lex(pc)
                    if lx.oword is not None:
                        pc = self._exec_oword(pc, lx)
                    else:
                        if lx.first is not None:
                            self._exec_line(lx)
                        pc += 1
                except ExprError as exc:
                    raise self.error(exc.message, exc.col) from None
                except RecursionError:
                    raise self.error("expression or parameter reference nested too deeply") from None
        except _Stop:
            pass
        except ProgramError as exc:
            if len(self.frames) > 1 and exc.line is not None:
                f = self.frames[-1]
                exc.message += (f" (in subroutine {_olabel(f.name)} called from line "
                                f"{f.call_line + 1})")
            raise
        units = self.units or "mm"
        return Program(tuple(self.blocks), file=self.file, dialect="gcode", units=units,
                       start=self.start, meta=self.meta)

    # -- O-words -------------------------------------------------------------
    def _o_args(self, lx: _Lexed, what: str) -> list[float]:
        """Evaluate the bracketed arguments after an O-word keyword."""
        code = lx.code
        ow = lx.oword
        p = self._skip(code, ow.rest)
        args: list[float] = []
        while p < len(code):
            if code[p] != "[":
                raise ExprError(f"unexpected {code[p]!r} after {_olabel(ow.label)} {ow.keyword}: "
                                f"{what}", p)
            value, p = parse_bracketed(code, p, self.grammar)
            if not math.isfinite(value):
                raise ExprError("value is not a finite number", p)
            args.append(value)
            p = self._skip(code, p)
        return args

    def _condition(self, i: int) -> float:
        lx = self.lex(i)
        saved = self.line_no
        self.line_no = i
        try:
            args = self._o_args(lx, "write one condition in brackets, e.g. [#1 LT 3]")
        except ExprError as exc:
            raise self.error(exc.message, exc.col, i) from None
        self.line_no = saved
        if len(args) != 1:
            raise self.error(f"{_olabel(lx.oword.label)} {lx.oword.keyword} needs exactly one "
                             "condition in brackets, e.g. [#1 LT 3]", lx.oword.col, i)
        return args[0]

    def _no_args(self, lx: _Lexed, line: int | None = None) -> None:
        p = self._skip(lx.code, lx.oword.rest)
        if p < len(lx.code):
            raise self.error(f"unexpected text after {_olabel(lx.oword.label)} "
                             f"{lx.oword.keyword}: it takes no argument", p, line)

    def _structure(self, i: int) -> tuple:
        """Match the structure opened at line ``i``: ``(end_line, branches)``.

        ``branches`` lists the ``elseif``/``else`` lines of an ``if``. Nesting
        must be proper and every closer must carry its opener's label.
        """
        cached = self._match.get(i)
        if cached is not None:
            return cached
        ow = self.lex(i).oword
        kind, label = ow.keyword, ow.label
        stack: list[tuple[str, str, int]] = []
        branches: list[int] = []
        seen_else = False
        for j in range(i + 1, self.end_line):
            if not self.lines[j] or ("o" not in self.lines[j] and "O" not in self.lines[j]):
                continue
            o = self.lex(j).oword
            if o is None or o.keyword is None:
                continue
            kw, lab = o.keyword, o.label
            where = f"{_olabel(lab)} {kw} at line {j + 1}"
            if kw == "sub":
                if kind == "sub" or any(s[0] == "sub" for s in stack):
                    raise self.error(f"{where}: subroutine definitions cannot be nested; close "
                                     f"the enclosing sub first", o.col, j)
                stack.append((kw, lab, j))
            elif kw == "while" and stack and stack[-1][0] == "do" and stack[-1][1] == lab:
                stack.pop()
            elif kw == "while" and not stack and kind == "do" and lab == label:
                result = (j, ())
                self._match[i] = result
                return result
            elif kw in _OPENERS:
                stack.append((kw, lab, j))
            elif kw in _CLOSERS:
                want = _CLOSERS[kw]
                if stack:
                    top = stack[-1]
                    if top[0] != want or top[1] != lab:
                        raise self.error(f"{where} does not close {_olabel(top[1])} {top[0]} "
                                         f"at line {top[2] + 1}: close it with "
                                         f"{_olabel(top[1])} {_OPENERS[top[0]]} first",
                                         o.col, j)
                    stack.pop()
                elif want == kind and lab == label:
                    result = (j, tuple(branches))
                    self._match[i] = result
                    return result
                else:
                    raise self.error(f"{where} does not close {_olabel(label)} {kind} at line "
                                     f"{i + 1}: expected {_olabel(label)} {_OPENERS[kind]}",
                                     o.col, j)
            elif kw in ("elseif", "else"):
                if stack:
                    top = stack[-1]
                    if top[0] != "if" or top[1] != lab:
                        raise self.error(f"{where} is not inside an if with label "
                                         f"{_olabel(lab)}", o.col, j)
                elif kind == "if" and lab == label:
                    if seen_else:
                        raise self.error(f"{where} comes after the else of {_olabel(label)} if",
                                         o.col, j)
                    seen_else = kw == "else"
                    branches.append(j)
                else:
                    raise self.error(f"{where} is not inside an if with label {_olabel(lab)}",
                                     o.col, j)
        raise self.error(f"{_olabel(label)} {kind} has no matching {_olabel(label)} "
                         f"{_OPENERS[kind]}", ow.col, i)

    def _exec_oword(self, pc: int, lx: _Lexed) -> int:
        ow = lx.oword
        kw, label = ow.keyword, ow.label
        frame = self.frames[-1]
        if kw is None:
            self.meta.setdefault("program_number", int(label))
            return pc + 1
        if kw == "sub":
            if len(self.frames) > 1:
                raise self.error(f"{_olabel(label)} sub inside a running subroutine: "
                                 "subroutine definitions cannot be nested", ow.col)
            end, _ = self._structure(pc)
            self._define(label, pc, end, ow.col)
            return end + 1
        if kw == "call":
            args = self._o_args(lx, "write the arguments in brackets, e.g. [1] [2.5]")
            return self._call(pc, label, args, ow.col)
        if kw in ("endsub", "return"):
            args = self._o_args(lx, "write an optional return value in brackets")
            if len(args) > 1:
                raise self.error(f"{_olabel(label)} {kw} takes at most one value", ow.col)
            if len(self.frames) == 1:
                raise self.error(f"{_olabel(label)} {kw} outside a subroutine: there is no "
                                 f"matching {_olabel(label)} sub being called", ow.col)
            if frame.name != label:
                raise self.error(f"{_olabel(label)} {kw} inside subroutine {_olabel(frame.name)}: "
                                 "use the label of the subroutine", ow.col)
            return self._return(args[0] if args else None)
        if kw == "if":
            end, branches = self._structure(pc)
            if self._condition(pc) != 0.0:
                frame.ctrl.append(_Ctrl("if", label, pc, end))
                return pc + 1
            for b in branches:
                blx = self.lex(b)
                if blx.oword.keyword == "else":
                    self._no_args(blx, b)
                    frame.ctrl.append(_Ctrl("if", label, pc, end))
                    return b + 1
                if self._condition(b) != 0.0:
                    frame.ctrl.append(_Ctrl("if", label, pc, end))
                    return b + 1
            return end + 1
        if kw in ("elseif", "else", "endif"):
            if kw == "endif":
                self._no_args(lx)
            top = frame.ctrl[-1] if frame.ctrl else None
            if top is None or top.kind != "if" or top.label != label:
                raise self.error(f"{_olabel(label)} {kw} without a matching {_olabel(label)} if",
                                 ow.col)
            frame.ctrl.pop()
            return top.end + 1 if kw != "endif" else pc + 1
        if kw == "do":
            self._no_args(lx)
            end, _ = self._structure(pc)
            frame.ctrl.append(_Ctrl("do", label, pc, end))
            return pc + 1
        if kw == "while":
            top = frame.ctrl[-1] if frame.ctrl else None
            if top is not None and top.kind == "do" and top.end == pc:
                if self._condition(pc) != 0.0:
                    return top.start + 1
                frame.ctrl.pop()
                return pc + 1
            end, _ = self._structure(pc)
            if self._condition(pc) != 0.0:
                frame.ctrl.append(_Ctrl("while", label, pc, end))
                return pc + 1
            return end + 1
        if kw == "endwhile":
            self._no_args(lx)
            top = frame.ctrl[-1] if frame.ctrl else None
            if top is None or top.kind != "while" or top.end != pc:
                raise self.error(f"{_olabel(label)} endwhile without a matching "
                                 f"{_olabel(label)} while", ow.col)
            frame.ctrl.pop()
            return top.start
        if kw == "repeat":
            end, _ = self._structure(pc)
            count = self._condition(pc)
            times = int(round(count)) if abs(count) < 2**62 else (2**62 if count > 0 else 0)
            if times <= 0:
                return end + 1
            frame.ctrl.append(_Ctrl("repeat", label, pc, end, times - 1))
            return pc + 1
        if kw == "endrepeat":
            self._no_args(lx)
            top = frame.ctrl[-1] if frame.ctrl else None
            if top is None or top.kind != "repeat" or top.end != pc:
                raise self.error(f"{_olabel(label)} endrepeat without a matching "
                                 f"{_olabel(label)} repeat", ow.col)
            if top.remaining > 0:
                top.remaining -= 1
                return top.start + 1
            frame.ctrl.pop()
            return pc + 1
        if kw in ("break", "continue"):
            self._no_args(lx)
            k = len(frame.ctrl) - 1
            while k >= 0 and not (frame.ctrl[k].kind in ("do", "while", "repeat")
                                  and frame.ctrl[k].label == label):
                k -= 1
            if k < 0:
                raise self.error(f"{_olabel(label)} {kw} outside a loop labelled {_olabel(label)}: "
                                 f"use the label of the enclosing do, while or repeat", ow.col)
            loop = frame.ctrl[k]
            del frame.ctrl[k + 1:]
            if kw == "break":
                frame.ctrl.pop()
                return loop.end + 1
            if loop.kind == "while":
                frame.ctrl.pop()
                return loop.start
            return loop.end  # do: test the while condition; repeat: count down
        raise self.error(f"unknown O-word keyword {kw!r}", ow.col)  # pragma: no cover

    def _define(self, label: str, line: int, end: int, col: int) -> None:
        known = self.subs.get(label)
        if known is not None and known[0] != line:
            raise self.error(f"subroutine {_olabel(label)} is defined twice (lines {known[0] + 1} "
                             f"and {line + 1}): rename one of them", col, line)
        self.subs[label] = (line, end)

    def _call(self, pc: int, label: str, args: list[float], col: int) -> int:
        if len(args) > SUB_PARAMS:
            raise self.error(f"{_olabel(label)} call with {len(args)} arguments: at most "
                             f"{SUB_PARAMS} (#1 to #{SUB_PARAMS})", col)
        sub = self.subs.get(label)
        if sub is None:
            # LinuxCNC skips forward to a sub it has not seen yet.
            for j in range(pc + 1, self.end_line):
                if "o" not in self.lines[j] and "O" not in self.lines[j]:
                    continue
                o = self.lex(j).oword
                if o is not None and o.keyword == "sub" and o.label == label:
                    end, _ = self._structure(j)
                    self._define(label, j, end, o.col)
                    sub = self.subs[label]
                    break
            else:
                raise self.error(f"{_olabel(label)} call: no subroutine {_olabel(label)} is "
                                 f"defined; define it with {_olabel(label)} sub ... "
                                 f"{_olabel(label)} endsub", col)
        if len(self.frames) > MAX_CALL_DEPTH:
            raise self.error(f"subroutine calls nested deeper than {MAX_CALL_DEPTH}: "
                             "runaway recursion? check the condition that ends it", col)
        saved = {k: self.params[k] for k in range(1, SUB_PARAMS + 1) if k in self.params}
        for k in range(1, SUB_PARAMS + 1):
            self.params.pop(k, None)
        for k, v in enumerate(args, start=1):
            self.params[k] = v
        self.globals["_value"] = 0.0
        self.globals["_value_returned"] = 0.0
        self.frames.append(_Frame(name=label, return_pc=pc + 1, call_line=pc, saved=saved))
        return sub[0] + 1

    def _return(self, value: float | None) -> int:
        frame = self.frames.pop()
        for k in range(1, SUB_PARAMS + 1):
            self.params.pop(k, None)
        self.params.update(frame.saved)
        if value is not None:
            self.globals["_value"] = value
            self.globals["_value_returned"] = 1.0
        return frame.return_pc

    # -- ordinary lines --------------------------------------------------------
    def _exec_line(self, lx: _Lexed) -> None:
        words = self._constant.get(self.line_no)
        if words is None:
            words, settings = self._parse_words(lx)
            for kind, key, value in settings:
                self._set(kind, key, value)
            if not settings and "#" not in lx.code and "[" not in lx.code:
                # No parameter or expression: the words are the same every time.
                self._constant[self.line_no] = words
        if words.letters or words.g or words.m:
            self._execute(words, lx)

    def _parse_words(self, lx: _Lexed):
        code = lx.code
        n = len(code)
        p = lx.start
        words = _Words()
        settings: list[tuple[str, object, float]] = []
        while True:
            p = self._skip(code, p)
            if p >= n:
                break
            ch = code[p]
            up = ch.upper()
            if ch == "#":
                kind, key, q = self._parameter_target(code, p)
                q = self._skip(code, q)
                if q >= n or code[q] != "=":
                    raise ExprError("parameter setting needs '=' and a value, e.g. #1 = 2.5",
                                    p)
                value, p = self._read_value(code, q + 1, "=", q)
                settings.append((kind, key, value))
            elif up in _WORD_LETTERS:
                value, q = self._read_value(code, p + 1, up, p)
                if up == "G":
                    words.g.append((value, p))
                elif up == "M":
                    words.m.append((value, p))
                else:
                    if up in words.letters:
                        raise ExprError(f"two {up} words on one line: keep one", p)
                    words.letters[up] = (value, p)
                p = q
            elif up == "N":
                raise ExprError("N (line number) must be the first word on the line", p)
            elif up == "O":
                raise ExprError("an O-word must be the first word on its line", p)
            elif up in _UNSUPPORTED_AXES:
                raise ExprError(f"axis {up} is not supported: ccopt reads X, Y and Z only", p)
            elif up == "/":
                raise ExprError("block delete '/' is not supported: ccopt cannot know the "
                                "switch; remove the '/' or the line", p)
            elif "A" <= up <= "Z":
                raise ExprError(f"unknown word {up}: ccopt reads G M X Y Z I J K R F P D H T S "
                                "N Q words, #parameters and O-words", p)
            else:
                raise ExprError(f"unexpected character {ch!r}: expected a word such as G1 or X10",
                                p)
        words.first = lx.first
        return words, settings

    def _classify(self, words: "_Words") -> None:
        """Check G/M codes and word usage; fills ``words.gcodes``/``mcodes``."""
        for value, col in words.g:
            tenths = round(value * 10) if abs(value) < 1e6 else -1
            if tenths < 0 or abs(value * 10 - tenths) > 1e-3 or tenths not in _G_GROUPS:
                name = f"G{_fmt(value)}"
                hint = _G_UNSUPPORTED_HINT.get(tenths) if tenths >= 0 and \
                    abs(value * 10 - tenths) <= 1e-3 else None
                raise self.error(f"unknown G-code {name}: "
                                 + (hint if hint else f"ccopt reads {_KNOWN_G}"), col)
            group = _G_GROUPS[tenths]
            if group in words.gcodes:
                other = words.gcodes[group][0]
                raise self.error(f"{_gname(other)} and {_gname(tenths)} on one line belong to the "
                                 f"same modal group ({group}): keep one", col)
            words.gcodes[group] = (tenths, col)
        mgroups: dict[str, int] = {}
        for value, col in words.m:
            if abs(value - round(value)) > 1e-4 or not 0 <= value < 1000:
                raise self.error(f"M-code M{_fmt(value)} is not a whole number from 0 to 999", col)
            m = int(round(value))
            if m in (98, 99):
                raise self.error(f"M{m} (Fanuc subprogram call/return) is not supported: use "
                                 "O-word subroutines (o100 sub / o100 call)", col)
            g = _M_GROUPS.get(m)
            if g is not None:
                if g in mgroups:
                    raise self.error(f"M{mgroups[g]} and M{m} on one line belong to the same "
                                     f"modal group ({g}): keep one", col)
                mgroups[g] = m
            words.mcodes.append(m)

    def _execute(self, words: "_Words", lx: _Lexed) -> None:
        if not words.classified:
            self._classify(words)
            words.classified = True
        gc = words.gcodes
        L = words.letters
        axis = any(a in L for a in _AXES)
        ijk = "I" in L or "J" in L or "K" in L
        motion_g = gc.get("motion")
        # What motion this line performs (LinuxCNC enhance_block).
        if motion_g is not None:
            if motion_g[0] == 800:
                if axis:
                    a = next(a for a in _AXES if a in L)
                    raise self.error(f"{a} word with G80: G80 cancels motion, so it cannot use "
                                     "axis words", L[a][1])
                motion = None
            else:
                motion = motion_g[0]
        elif axis:
            if self.motion_mode is None:
                a = next(a for a in _AXES if a in L)
                raise self.error(f"{a} word with no motion mode in force: add G0, G1, G2 or G3",
                                 L[a][1])
            motion = self.motion_mode
        elif ijk and self.motion_mode in (20, 30):
            motion = self.motion_mode
        else:
            motion = None
        is_arc = motion in (20, 30)
        comp = gc.get("comp")
        # Word usage checks (LinuxCNC check_other_codes).
        if "D" in L and (comp is None or comp[0] == 400):
            raise self.error("D word with no G41, G42, G41.1 or G42.1 to use it", L["D"][1])
        if "H" in L and (gc.get("length") is None or gc["length"][0] != 430):
            raise self.error("H word with no G43 to use it", L["H"][1])
        for w in "IJK":
            if w in L and not is_arc:
                raise self.error(f"{w} word with no G2 or G3 to use it", L[w][1])
        if "R" in L and not is_arc:
            raise self.error("R word with no G2 or G3 to use it", L["R"][1])
        dwell = gc.get("dwell")
        path = gc.get("path")
        if "P" in L and not (is_arc or dwell or (path and path[0] == 640)):
            raise self.error("P word with no G2, G3, G4 or G64 to use it", L["P"][1])
        if "Q" in L and not (path and path[0] == 640):
            raise self.error("Q word with no G64 to use it", L["Q"][1])
        if dwell and is_arc:
            raise self.error("G4 and G2/G3 on one line would share the P word: put the dwell on "
                             "its own line", dwell[1])
        mcodes = tuple(words.mcodes)
        first_col = words.first if words.first is not None else 0

        # -- execution in RS274NGC order ---------------------------------
        fm = gc.get("feed_mode")
        if fm is not None:
            mode = "inverse" if fm[0] == 930 else "per_minute"
            if mode != self.feed_mode:
                self.feed = None
            self.feed_mode = mode
        if "F" in L:
            f, col = L["F"]
            if f < 0:
                raise self.error(f"negative feed rate F{_fmt(f)}: F must be >= 0", col)
            if self.feed_mode == "per_minute":
                self.feed = f
        if "T" in L:
            t, col = L["T"]
            if t < 0 or abs(t - round(t)) > 1e-4 or t > 2**31:
                raise self.error(f"T{_fmt(t)}: the tool number must be a non-negative integer", col)
            self.selected_tool = int(round(t))
        if 6 in mcodes:
            self.loaded_tool = self.selected_tool
        if dwell is not None:
            if "P" not in L:
                raise self.error("G4 needs the dwell time in seconds as P, e.g. G4 P0.5",
                                 dwell[1])
            secs = L["P"][0]
            if secs < 0:
                raise self.error(f"negative dwell time P{_fmt(secs)}", L["P"][1])
            self._emit(Block(Source(self.file, self.line_no + 1, first_col + 1), Motion.DWELL,
                             self.pos, self.pos, self.modal(), dwell=secs, mcodes=mcodes))
        plane = gc.get("plane")
        if plane is not None:
            self.plane = {170: "XY", 180: "ZX", 190: "YZ"}[plane[0]]
            self._modal = None
        units = gc.get("units")
        if units is not None:
            new = "inch" if units[0] == 200 else "mm"
            if self.moved and new != (self.units or "mm"):
                raise self.error(f"{_gname(units[0])} changes units after the first move: ccopt "
                                 "keeps one unit per program; put G20/G21 before any motion",
                                 units[1])
            self.units = new
            self._modal = None
        if comp is not None:
            self._compensation(comp, L)
        length = gc.get("length")
        if length is not None:
            h = L["H"][0] if "H" in L else None
            self.meta["tool_length"].append((self.line_no + 1, _gname(length[0]), h))
        dist = gc.get("distance")
        if dist is not None:
            self.incremental = dist[0] == 910
        adist = gc.get("arc_distance")
        if adist is not None:
            self.arc_incremental = adist[0] == 911
        corner = gc.get("corner")
        if corner is not None:
            self.corner = "circular" if corner[0] == 1360 else "linear"
            self._modal = None
        se = gc.get("start_end")
        if se is not None:
            self.start_end = "direct" if se[0] == 1380 else "contour"
            self._modal = None
        if motion_g is not None:
            self.motion_mode = None if motion_g[0] == 800 else motion_g[0]
        if motion is not None and (axis or is_arc):
            self._move(motion, L, mcodes, first_col, motion_g[1] if motion_g else first_col)
        if any(m in (2, 30) for m in mcodes):
            raise _Stop()

    def _compensation(self, comp: tuple[int, int], L: dict) -> None:
        code, col = comp
        self._modal = None
        if code == 400:
            self.side = 0
            return
        side = 1 if code in (410, 411) else -1
        if code in (411, 421):
            if "D" not in L:
                raise self.error(f"{_gname(code)} needs the tool diameter as D, e.g. "
                                 f"{_gname(code)} D6", col)
            d = L["D"][0]
            self.side = -side if d < 0 else side
            self.radius = abs(d) / 2.0
            self.tool = None
            return
        if "D" in L:
            d, dcol = L["D"]
            if d < 0 or abs(d - round(d)) > 1e-4 or d > 2**31:
                raise self.error(f"D{_fmt(d)} with {_gname(code)} is a tool number: it must be a "
                                 "non-negative integer (use G41.1/G42.1 D<diameter> for a "
                                 "diameter)", dcol)
            tool = int(round(d))
        else:
            tool = self.loaded_tool
        self.tool = tool
        self.side = side
        diameter = None
        if tool is not None and self.tool_table is not None:
            diameter = self.tool_table.get(tool)
        if diameter is None:
            self.radius = None
        else:
            self.radius = abs(diameter) / 2.0
            if diameter < 0:
                self.side = -side

    def modal(self) -> Modal:
        if self._modal is None:
            self._modal = Modal(plane=self.plane, units=self.units or "mm", side=self.side,
                                radius=self.radius, tool=self.tool, corner=self.corner,
                                start_end=self.start_end)
        return self._modal

    def _emit(self, block: Block) -> None:
        values = list(block.start) + list(block.end) + list(block.center or ())
        if block.feed is not None:
            values.append(block.feed)
        if not all(math.isfinite(v) for v in values):
            raise self.error("coordinates or feed overflow (not finite numbers): check the "
                             "values on this line", block.source.col - 1)
        self.blocks.append(block)

    # -- motion --------------------------------------------------------------
    def _move(self, motion: int, L: dict, mcodes: tuple, first_col: int, gcol: int) -> None:
        cur = self.pos
        end = list(cur)
        for k, a in enumerate(_AXES):
            if a in L:
                v = L[a][0]
                end[k] = cur[k] + v if self.incremental else v
        end_t = (end[0], end[1], end[2])
        src = Source(self.file, self.line_no + 1, first_col + 1)
        if motion == 0:
            block = Block(src, Motion.RAPID, cur, end_t, self.modal(), mcodes=mcodes)
        elif motion == 10 or self._modal_arc_without_plane_motion(L, cur, end_t):
            length = math.dist(cur, end_t)
            feed = self._feed(L, length, gcol)
            block = Block(src, Motion.LINE, cur, end_t, self.modal(), feed=feed, mcodes=mcodes)
        else:
            block = self._arc(motion, L, cur, end_t, src, mcodes, gcol)
        self._emit(block)
        self.moved = True
        self.pos = end_t

    def _modal_arc_without_plane_motion(self, L: dict, cur, end) -> bool:
        """G2/G3 still modal, no centre word and no in-plane displacement (the
        Fagor 8070 manual's ``G91 G40 Y0`` after a G03): no arc is asked for,
        so it is a straight move (of zero length in the plane). With a centre
        word or in-plane motion an arc needs its centre, and its absence stays
        an error."""
        iu, iv, _ = PLANE_AXES[self.plane]
        wu, wv = _CENTRE_WORDS[self.plane]
        return (not any(w in L for w in (wu, wv, "R", "P"))
                and cur[iu] == end[iu] and cur[iv] == end[iv])

    def _feed(self, L: dict, length: float, col: int) -> float:
        if self.feed_mode == "inverse":
            if "F" not in L:
                raise self.error("G93 inverse time: every G1/G2/G3 move needs its own F word "
                                 "(1/minutes for this move)", col)
            f = L["F"][0]
            if f <= 0:
                raise self.error("inverse-time F must be > 0", L["F"][1])
            return length * f / 60.0
        if self.feed is None:
            raise self.error("feed move with no feed rate F: add F<units per minute> on this "
                             "or an earlier line", col)
        if self.feed <= 0:
            raise self.error("feed move with feed rate F0: set F > 0 before this move", col)
        return self.feed / 60.0

    def _tolerance(self) -> float:
        tol = tolerances.ARC_RADIUS_ABS_TOL_MM
        return tol / MM_PER_INCH if self.units == "inch" else tol

    def _arc(self, motion: int, L: dict, cur, end, src: Source, mcodes, gcol: int) -> Block:
        plane = self.plane
        iu, iv, iw = PLANE_AXES[plane]
        wu, wv = _CENTRE_WORDS[plane]
        bad = _FORBIDDEN_CENTRE[plane]
        gname = "G2" if motion == 20 else "G3"
        if bad in L:
            raise self.error(f"{bad} word with a {gname} arc in the {plane} plane "
                             f"({_PLANE_G[plane]}): give the centre with {wu} and {wv}",
                             L[bad][1])
        has_r = "R" in L
        has_c = wu in L or wv in L
        if has_r and has_c:
            raise self.error(f"{gname} with both R and {wu}/{wv}: give either the radius R or "
                             "the centre offsets", L["R"][1])
        if not has_r and not has_c:
            raise self.error(f"{gname} arc with no centre: give the centre offsets {wu} and {wv} "
                             f"({_PLANE_G[plane]} plane) or a radius R", gcol)
        turns = 0
        if "P" in L:
            p, pcol = L["P"]
            if abs(p - round(p)) > 1e-3 or round(p) < 1 or p > MAX_ARC_TURNS:
                raise self.error(f"{gname} P{_fmt(p)}: P is the number of turns, a whole number "
                                 "from 1", pcol)
            turns = int(round(p)) - 1
        u0, v0 = cur[iu], cur[iv]
        u1, v1 = end[iu], end[iv]
        tol = self._tolerance()
        if has_r:
            r, rcol = L["R"]
            if u1 == u0 and v1 == v0:
                raise self.error(f"{gname} R arc ends where it starts: the centre is undefined; "
                                 f"use {wu}/{wv} centre offsets for a full circle", rcol)
            if r == 0:
                raise self.error(f"{gname} with R0: the radius must not be zero", rcol)
            cu, cv = self._r_centre(motion, u0, v0, u1, v1, r, tol, rcol)
        else:
            if self.arc_incremental:
                cu = u0 + (L[wu][0] if wu in L else 0.0)
                cv = v0 + (L[wv][0] if wv in L else 0.0)
            else:
                if wu not in L or wv not in L:
                    missing = wu if wu not in L else wv
                    raise self.error(f"G90.1 absolute arc centre needs both {wu} and {wv} "
                                     f"({missing} is missing)", gcol)
                cu, cv = L[wu][0], L[wv][0]
            r0 = math.hypot(u0 - cu, v0 - cv)
            r1 = math.hypot(u1 - cu, v1 - cv)
            if r0 < 0.1 * tol or r1 < 0.1 * tol:
                raise self.error(f"{gname} zero-radius arc: the centre lies on the "
                                 f"{'start' if r0 < 0.1 * tol else 'end'} point; check "
                                 f"{wu}/{wv}", gcol)
            err = abs(r0 - r1)
            if err > tol and err > tolerances.ARC_RADIUS_REL_TOL * max(r0, r1):
                raise self.error(f"inconsistent arc radii: start r={r0:.6g}, end r={r1:.6g} "
                                 f"(differ by {err:.3g}, more than {tol:.3g} and "
                                 f"{tolerances.ARC_RADIUS_REL_TOL:.3%}): correct the end point "
                                 f"or the centre offsets {wu}/{wv}", gcol)
        center = [cur[0], cur[1], cur[2]]
        center[iu] = cu
        center[iv] = cv
        ccw = motion == 30
        if not (math.isfinite(cu) and math.isfinite(cv)):
            raise self.error("arc centre overflows (not a finite number)", gcol)
        r0 = math.hypot(u0 - cu, v0 - cv)
        r1 = math.hypot(u1 - cu, v1 - cv)
        sweep = _sweep(u0 - cu, v0 - cv, u1 - cu, v1 - cv, ccw) + _TWO_PI * turns
        length = math.hypot(0.5 * (r0 + r1) * sweep, end[iw] - cur[iw])
        block_feed = self._feed(L, length, gcol)
        return Block(src, Motion.ARC_CCW if ccw else Motion.ARC_CW, cur, end, self.modal(),
                     center=(center[0], center[1], center[2]), turns=turns, feed=block_feed,
                     mcodes=mcodes)

    def _r_centre(self, motion, u0, v0, u1, v1, r, tol, rcol) -> tuple[float, float]:
        """Centre of an R-format arc (LinuxCNC arc_data_r)."""
        ar = abs(r)
        mu, mv = (u0 + u1) / 2.0, (v0 + v1) / 2.0
        half = math.hypot(u1 - mu, v1 - mv)
        if half - ar > tol:
            raise self.error(f"arc radius R{_fmt(r)} too small to reach the end point: the "
                             f"chord needs R >= {half:.6g}", rcol)
        if half / ar > 1.0 - 1e-12:
            half = ar  # a semicircle within tolerance
        chord = math.atan2(v1 - v0, u1 - u0)
        if (motion == 20) == (r > 0):
            theta = chord - math.pi / 2.0
        else:
            theta = chord + math.pi / 2.0
        offset = ar * math.cos(math.asin(half / ar))
        return mu + offset * math.cos(theta), mv + offset * math.sin(theta)


def _sweep(du0: float, dv0: float, du1: float, dv1: float, ccw: bool) -> float:
    """Swept angle (radians, > 0) from start to end direction; equal directions: a full turn."""
    a0 = math.atan2(dv0, du0)
    a1 = math.atan2(dv1, du1)
    d = (a1 - a0) if ccw else (a0 - a1)
    d = math.fmod(d, _TWO_PI)
    if d <= 0.0:
        d += _TWO_PI
    return d


@dataclass(slots=True)
class _Ctrl:
    kind: str      # "if" | "do" | "while" | "repeat"
    label: str
    start: int     # line of the opener
    end: int       # line of the closer
    remaining: int = 0


@dataclass(slots=True)
class _Frame:
    name: str | None
    return_pc: int
    call_line: int
    saved: dict = field(default_factory=dict)
    named: dict = field(default_factory=dict)
    ctrl: list = field(default_factory=list)


@dataclass(slots=True)
class _Words:
    g: list = field(default_factory=list)
    m: list = field(default_factory=list)
    letters: dict = field(default_factory=dict)
    gcodes: dict = field(default_factory=dict)
    mcodes: list = field(default_factory=list)
    first: int | None = None
    classified: bool = False


def _check_inputs(file, tool_table, start):
    if not isinstance(file, str):
        file = str(file)
    try:
        s = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ProgramError(f"start must be three numbers (x, y, z), got {start!r}", file) from None
    if len(s) != 3 or not all(math.isfinite(v) for v in s):
        raise ProgramError(f"start must be three finite numbers (x, y, z), got {start!r}", file)
    table = None
    if tool_table is not None:
        table = {}
        try:
            for k, v in dict(tool_table).items():
                table[int(k)] = float(v)
        except (TypeError, ValueError):
            raise ProgramError("tool_table must map tool numbers to diameters", file) from None
    return file, table, s


def read_gcode(text: str, file: str = "<string>", *, tool_table: dict[int, float] | None = None,
               start=(0.0, 0.0, 0.0)) -> Program:
    """Read RS274NGC/LinuxCNC G-code into a :class:`Program` (dialect ``"gcode"``).

    Parameters
    ----------
    text:
        The program text.
    file:
        Name used in :class:`~ccopt.program.model.Source` and in errors.
    tool_table:
        Tool number -> DIAMETER (program units), e.g. from
        :func:`ccopt.program.tooltable.read_tool_table`; used by ``G41``/``G42``
        with ``D<tool>`` or a loaded tool (``T<n> M6``).
    start:
        Machine position ``(x, y, z)`` before the first block, program units.

    Raises
    ------
    ProgramError
        For anything wrong with the text, located by file, line and column.
    """
    file, table, s = _check_inputs(file, tool_table, start)
    if not isinstance(text, str):
        raise ProgramError(f"program text must be a string, not {type(text).__name__}", file)
    reader = None
    try:
        reader = _Reader(text, file, table, s)
        return reader.run()
    except ProgramError:
        raise
    except RecursionError:
        line = reader.line_no + 1 if reader is not None else None
        raise ProgramError("program nested too deeply to read", file, line) from None
    except Exception as exc:  # a bug in this reader must still reach users located
        line = reader.line_no + 1 if reader is not None else None
        raise ProgramError(f"internal error of the G-code reader ({type(exc).__name__}: {exc}); "
                           "please report it with this program", file, line) from exc
