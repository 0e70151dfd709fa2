"""Executing PMAC motion-program statements: modal state, moves, dwells.

:class:`Interpreter` runs the lines of the selected program buffer one by
one and appends a :class:`~ccopt.program.model.Block` per executed move or
dwell. It carries PMAC's modal state: move mode, ``ABS``/``INC`` per axis and
for the centre vector, ``NORMAL`` plane, feed or move-time mode, ``TA``/``TS``,
cutter compensation ``CC0``/``CC1``/``CC2`` and its radius ``CCR``. Lengths
are program units, times seconds (the program writes milliseconds), feeds
units per second. The rules and decisions are in ``docs/pmac.md``.
"""
from __future__ import annotations

import math
import re

from ccopt.errors import ProgramError
from ccopt.program.model import (MAX_PROGRAM_COORDINATE, Block, Modal, Motion, Source, Vec3,
                                 out_of_range)
from ccopt.program.blocks import new_block
from ccopt.program.pmac.lexer import (AXES, AXES_LINE_RE, LETTERS_RE, MOVE_MODES, OTHER_AXES,
                                      PLAIN_LINE_RE, STRAIGHT_LINE_RE, UNSUPPORTED,
                                      UNSUPPORTED_MODES, UNSUPPORTED_WHY, VECTORS, keyword_at,
                                      skip, word)
from ccopt.program.pmac.moves import CircleMode, PendingMove, circle_centre, finite_point
from ccopt.program.pmac.straight import run_straight
from ccopt.program.pmac.variables import Variables

_LABEL_RE = re.compile(r"[NO][ \t]*\d+")
_FRAX_RE = re.compile(r"FRAX([ \t]*\([ \t]*([A-Z ,\t]*)\))?")
#: Milliseconds per second: the program writes times in ms.
_MS = 1000.0
#: Axis letter -> index in (x, y, z).
_AXIS_INDEX = {a: i for i, a in enumerate(AXES)}
#: CC0/CC1/CC2 -> programmed side (+1 left, -1 right, 0 off).
_CC_SIDES = {"CC0": 0, "CC1": 1, "CC2": -1}
#: NORMAL's one negative component -> plane.
_NORMAL_PLANES = {"K": "XY", "J": "ZX", "I": "YZ"}
#: I-variable number of Isx<offset> for coordinate system s: 5000 + 100 s + offset.
_ISX_BASE, _ISX_STEP = 5000, 100
_ISX_ACCEL, _ISX_SCURVE, _ISX_FEED, _ISX_FEED_UNIT, _ISX_BREAK = 87, 88, 89, 90, 99


class Interpreter:
    """Modal state of a PMAC coordinate system and the blocks it has run.

    ``start`` is the position ``(x, y, z)`` before the first move; ``meta``
    the program's ``meta`` dict (see ``docs/pmac.md``).
    """

    def __init__(self, file: str, start: Vec3, meta: dict):
        self.file = file
        self.pos: Vec3 = tuple(start)         # where the last move ended
        self.meta = meta
        self.vars = Variables(file, meta)
        # modal state (power-on defaults)
        self.mode = "LINEAR"
        self.incremental = {a: False for a in AXES}
        self.vector_absolute = False
        self.plane = "XY"
        self.feed: float | None = None        # units/s, feed mode
        self.move_time: float | None = None   # s, time mode
        self.time_mode = False
        self.accel_time: float | None = None  # s
        self.scurve_time: float | None = None  # s
        self.programmed_side = 0
        self.radius_sign = 1
        self.radius: float | None = None
        self.coord_system = 1
        self.feed_unit_ms = 1000.0            # Isx90: F is units per this many ms
        # output
        self.blocks: list[Block] = []
        self.pending: PendingMove | None = None
        self.line_mcodes: list[int] = []
        self.in_body = False
        self.finished = False
        #: line -> "part"/"air": the surface markers in the comments (markers.py)
        self.markers: dict[int, str] = {}
        #: the Modal of each modal state met so far (see ``modal``)
        self._modals: dict[tuple, Modal] = {}

    def error(self, message: str, line: int | None, col: int | None = None) -> ProgramError:
        return ProgramError(message, self.file, line, col)

    def nonnegative(self, value: float, what: str, line: int | None, col: int | None) -> float:
        if value < 0:
            raise self.error(f"{what}{value:g}: must not be negative", line, col)
        return value

    # -- variables and coordinate-system set-up --------------------------------
    def bounded(self, value: float, letter: str, line: int, col: int) -> None:
        """A ProgramError at ``col`` when word ``letter``'s value is beyond
        :data:`~ccopt.program.model.MAX_PROGRAM_COORDINATE`."""
        if out_of_range(value):
            raise self.error(f"{letter}{value:g} is out of range: coordinates, I J K R and F "
                             f"must lie within +-{MAX_PROGRAM_COORDINATE:g}", line, col)

    def isx(self, offset: int) -> int:
        """Number of the I-variable Isx<offset> of the selected coordinate system."""
        return _ISX_BASE + _ISX_STEP * self.coord_system + offset

    def assignment(self, line: int, text: str, pos: int) -> int | None:
        """Execute a variable assignment at ``pos`` (with what an I-variable
        changes); the position after it, or ``None`` when there is none."""
        done = self.vars.assignment(line, text, pos)
        if done is None:
            return None
        if done.kind == "I" and self.in_body:
            number = done.number
            if self.isx(_ISX_ACCEL) <= number <= self.isx(_ISX_FEED_UNIT):
                if self.blocks:
                    raise self.error(
                        f"I{number} changed after the first move: ccopt does not model changing "
                        f"Isx87..Isx90 while the program runs; set it before OPEN PROG",
                        line, pos + 1)
                self.apply_coordinate_system_defaults()
            elif number == self.isx(_ISX_BREAK):
                self.meta["break_cos"] = self.vars.i[number]
        return done.end

    def apply_coordinate_system_defaults(self) -> None:
        """Honour Isx87/88/89/90/99 of the selected coordinate system, if the file set them."""
        i, i_line = self.vars.i, self.vars.i_line
        self.meta["coordinate_system"] = self.coord_system
        n = self.isx(_ISX_FEED_UNIT)
        if n in i:
            if not i[n] > 0:
                raise self.error(f"I{n}={i[n]:g}: the feedrate time unit must be > 0 ms",
                                 i_line[n])
            self.feed_unit_ms = i[n]
        n = self.isx(_ISX_ACCEL)
        if n in i:
            self.accel_time = self.nonnegative(i[n], f"I{n}=", i_line[n], None) / _MS
        n = self.isx(_ISX_SCURVE)
        if n in i:
            self.scurve_time = self.nonnegative(i[n], f"I{n}=", i_line[n], None) / _MS
        n = self.isx(_ISX_FEED)
        if n in i:
            if not i[n] > 0:
                raise self.error(f"I{n}={i[n]:g}: the default feedrate must be > 0", i_line[n])
            self.feed = i[n] * _MS / self.feed_unit_ms
        n = self.isx(_ISX_BREAK)
        if n in i:
            self.meta["break_cos"] = i[n]

    # -- program body -----------------------------------------------------------
    def run_lines(self, body: list[tuple[int, str]]) -> None:
        """Execute the ``(line number, text)`` lines of the program buffer
        until the end or ``RETURN``: runs of straight move lines in one loop
        (:func:`~ccopt.program.pmac.straight.run_straight`), every other line
        by :meth:`other_line`, in order."""
        k, count = 0, len(body)
        while k < count and not self.finished:
            k = run_straight(self, body, k, AXES_LINE_RE, STRAIGHT_LINE_RE)
            if k < count:
                self.other_line(*body[k])
                k += 1

    def other_line(self, line: int, text: str) -> None:
        """Execute a line that is not a straight move line (or one whose
        move raises an error): a plain one (:meth:`plain_line`), or any other
        statement by statement, each path the same in effect as the next."""
        self.pending = None
        if self.line_mcodes:
            self.line_mcodes = []
        plain = PLAIN_LINE_RE.fullmatch(text)
        if plain is not None:
            self.plain_line(line, plain)    # it runs its moves itself and writes no M-code
            return
        pos = 0
        while not self.finished:
            pos = skip(text, pos)
            if pos >= len(text):
                break
            pos = self.statement(line, text, pos)
        self.flush()
        if self.line_mcodes:
            self.meta["ignored"].append({"line": line, "text": " ".join(
                f"M{c}" for c in self.line_mcodes), "why": "M-code call without a move"})
            self.line_mcodes = []

    def straight_line(self, line: int, text: str) -> bool:
        """Execute a straight move line (:data:`~ccopt.program.pmac.lexer.STRAIGHT_LINE_RE`:
        ``[LINEAR|RAPID] [X..] [Y..] [Z..]``, most lines of a long program)
        whose move raises no error, and say ``True``; ``False``, with nothing
        done, for any other line (an empty one too), which :meth:`other_line`
        runs (:func:`~ccopt.program.pmac.straight.run_straight` on the one line)."""
        return bool(text) and run_straight(self, [(line, text)], 0, AXES_LINE_RE,
                                           STRAIGHT_LINE_RE) == 1

    def plain_line(self, line: int, plain: re.Match) -> None:
        """Execute a line of move modes, ``CC0``/``CC1``/``CC2`` and axis and
        ``F`` words with literal numbers (the CIRCLE moves of a long program)
        from its match ``plain`` of :data:`~ccopt.program.pmac.lexer.PLAIN_LINE_RE`,
        four groups per statement: the same effects and errors as
        :meth:`statement`, without its look-ups character by character, and
        with the axis words of the line's move gathered here rather than in a
        :class:`PendingMove`."""
        words: dict[str, float] = {}    # the move being written: letter -> value
        col = 0                         # its first axis word's column
        groups = iter(plain.groups())
        for k, (kw, letter, sign, number) in enumerate(zip(groups, groups, groups, groups)):
            if kw is not None:
                if words:               # a mode word runs the move written before it
                    self.move(line, col, words)
                    words = {}
                if kw in _CC_SIDES:
                    self.programmed_side = _CC_SIDES[kw]
                else:
                    self.mode = MOVE_MODES[kw]
                continue
            if letter is None:          # past the last statement
                break
            value = float(number)
            if value == math.inf:       # digits only: never -inf nor nan
                raise self.error(f"{letter}: number too large", line, plain.start(4 * k + 4) + 1)
            if sign == "-":
                value = -value
            if letter == "F":
                self.feed_word(value, line, plain.start(4 * k + 2) + 1)
                continue
            if not -MAX_PROGRAM_COORDINATE <= value <= MAX_PROGRAM_COORDINATE:
                self.bounded(value, letter, line, plain.start(4 * k + 2) + 1)
            if not words:
                col = plain.start(4 * k + 2) + 1
            elif letter in words:
                raise self.error(f"{letter} is written twice in one move", line,
                                 plain.start(4 * k + 2) + 1)
            words[letter] = value
        if words:
            self.move(line, col, words)

    def statement(self, line: int, text: str, pos: int) -> int:
        """Execute the statement at ``pos``; the position after it."""
        ch = text[pos]
        col = pos + 1
        if not ("A" <= ch <= "Z"):
            raise self.error(f"unexpected {ch!r}: expected a command", line, col)
        end = self.assignment(line, text, pos)
        if end is not None:
            return end
        kw = keyword_at(text, pos)
        if kw is not None:
            return self.keyword(kw, line, text, pos)
        if len(LETTERS_RE.match(text, pos).group(0)) > 1:
            name = word(text, pos)
            hint = ""
            if name.startswith("CIR"):
                hint = ": write CIRCLE1 (clockwise) or CIRCLE2 (counter-clockwise)"
            elif name.startswith("CC"):
                hint = ": ccopt knows CC0, CC1, CC2 and CCR"
            raise self.error(f"unknown command {name!r}{hint}", line, col)
        return self.letter(ch, line, text, pos)

    def letter(self, ch: str, line: int, text: str, pos: int) -> int:
        """Execute the single-letter word ``ch`` at ``pos`` (axis, F, label, M-code)."""
        col = pos + 1
        if ch in AXES or ch in VECTORS or ch == "R":
            return self.axis_word(ch, line, text, pos)
        if ch in OTHER_AXES:
            raise self.error(f"axis {ch} is not supported: ccopt carries X, Y and Z only",
                             line, col)
        if ch == "F":
            value, end = self.vars.data(line, text, pos + 1, "F")
            self.feed_word(value, line, col)
            return end
        if ch in "NO":
            m = _LABEL_RE.match(text, pos)
            if not m:
                raise self.error(f"label {ch} needs a number", line, col)
            return m.end()
        if ch in "PQ":
            raise self.error(f"{word(text, pos) or ch}: a {ch}-variable on its own is not a "
                             "program statement; write {var}={expression}", line, col)
        if ch == "M":
            value, end = self.vars.data(line, text, pos + 1, "M")
            if value != int(value) or value < 0:
                raise self.error(f"M{value:g}: an M-code must be a non-negative integer",
                                 line, col)
            self.line_mcodes.append(int(value))
            return end
        if ch in "GTD":
            raise self.error(f"{ch}-codes are not supported: PMAC runs them as calls into PROG "
                             f"10x0-10x3 subroutines that ccopt cannot see", line, col)
        raise self.error(f"unknown command {word(text, pos)!r}", line, col)

    def feed_word(self, value: float, line: int, col: int) -> None:
        """``F{value}`` at ``col``: the feedrate, in force from this line's move."""
        self.bounded(value, "F", line, col)
        if not value > 0:
            raise self.error(f"F{value:g}: the feedrate must be positive", line, col)
        self.feed = value * _MS / self.feed_unit_ms
        self.time_mode = False

    def keyword(self, kw: str, line: int, text: str, pos: int) -> int:
        """Execute the command word ``kw`` at ``pos``; the position after it.

        A statement that changes the modal state of moves first executes the
        move written before it on the line (``flush``)."""
        col = pos + 1
        end = pos + len(kw)
        if kw in UNSUPPORTED_MODES:
            raise self.error(f"unsupported move mode {kw}: ccopt reads LINEAR, CIRCLE1, CIRCLE2 "
                             "and RAPID moves", line, col)
        if kw in UNSUPPORTED:
            raise self.error(f"unsupported command {kw}: {UNSUPPORTED_WHY}", line, col)
        if kw in ("CC3", "CC4"):
            raise self.error(f"{kw} is not supported: ccopt does 2-D compensation with CC0, CC1 "
                             "and CC2", line, col)
        if kw in ("OPEN", "CLOSE", "CLEAR"):
            raise self.error(f"{kw} must stand alone on its line", line, col)
        if kw in ("DEFINE", "DELETE", "UNDEFINE"):
            raise self.error(f"{kw} is an on-line command: put it outside OPEN PROG ... CLOSE",
                             line, col)
        if kw in ("TA", "TS", "TM"):
            return self.timing(kw, line, text, end)
        if kw == "FRAX":
            return self.frax(line, text, pos)
        self.flush()
        if kw in MOVE_MODES:
            self.mode = MOVE_MODES[kw]
            return end
        if kw in ("ABS", "INC"):
            return self.abs_inc(kw == "INC", line, text, end)
        if kw in ("DWELL", "DWE", "DELAY", "DLY"):
            return self.dwell(kw, line, text, pos)
        if kw in _CC_SIDES:
            self.programmed_side = _CC_SIDES[kw]
            return end
        if kw == "CCR":
            value, end = self.vars.data(line, text, end, "CCR")
            self.radius = abs(value)
            self.radius_sign = -1 if value < 0 else 1
            return end
        if kw in ("NORMAL", "NRM"):
            return self.normal(line, text, end, col)
        if kw in ("RETURN", "RET"):
            self.finished = True
            return len(text)
        raise AssertionError(kw)  # pragma: no cover - every keyword is handled above

    def timing(self, kw: str, line: int, text: str, pos: int) -> int:
        """``TA``/``TS``/``TM{ms}``; ``TM`` switches to move-time mode. They
        apply to the move being written on the line (no flush)."""
        value, end = self.vars.data(line, text, pos, kw)
        value = self.nonnegative(value, kw, line, pos - len(kw) + 1) / _MS
        if kw == "TA":
            self.accel_time = value
        elif kw == "TS":
            self.scurve_time = value
        else:
            self.move_time = value
            self.time_mode = True
        return end

    def frax(self, line: int, text: str, pos: int) -> int:
        """``FRAX`` or ``FRAX(X,Y,Z)``: the default feedrate axes, the only set read."""
        m = _FRAX_RE.match(text, pos)
        axes = set(re.findall(r"[A-Z]", m.group(2) or "")) if m.group(1) else set()
        if m.group(1) and axes != set(AXES):
            raise self.error("FRAX with other feedrate axes than X, Y, Z is not supported "
                             "(ccopt's feed is the X-Y-Z vector speed)", line, pos + 1)
        return m.end()

    def dwell(self, kw: str, line: int, text: str, pos: int) -> int:
        """``DWELL{ms}``/``DELAY{ms}``: a dwell block at the current point."""
        col = pos + 1
        value, end = self.vars.data(line, text, pos + len(kw), kw)
        value = self.nonnegative(value, kw, line, col)
        p = self.pos
        if kw in ("DELAY", "DLY"):
            self.meta["delay_blocks"].append(len(self.blocks))
        self.blocks.append(self.block(Source(self.file, line, col), Motion.DWELL, p, p,
                                      dwell=value / _MS))
        return end

    def abs_inc(self, incremental: bool, line: int, text: str, pos: int) -> int:
        """``ABS``/``INC`` for all axes, or ``ABS(X,Y,R)``/``INC(...)`` for the
        listed axes and ``R`` (the centre vector)."""
        p = skip(text, pos)
        if not (p < len(text) and text[p] == "("):
            for a in AXES:
                self.incremental[a] = incremental
            return pos
        close = text.find(")", p)
        if close < 0:
            raise self.error("unterminated axis list: missing ')'", line, p + 1)
        for name in (s.strip() for s in text[p + 1:close].split(",")):
            if name == "R":
                self.vector_absolute = not incremental
            elif name in AXES:
                self.incremental[name] = incremental
            elif name in OTHER_AXES:
                pass  # other axes never move in a ccopt program
            else:
                raise self.error(f"{'INC' if incremental else 'ABS'}(...): expected axis "
                                 f"letters or R, found {name!r}", line, p + 2)
        return close + 1

    def normal(self, line: int, text: str, pos: int, col: int) -> int:
        """``NORMAL I.. J.. K..``: the plane; only one negative component is read."""
        comps = {"I": 0.0, "J": 0.0, "K": 0.0}
        seen = False
        while True:
            p = skip(text, pos)
            if not (p < len(text) and text[p] in comps and not text.startswith("INC", p)):
                break
            comps[text[p]], pos = self.vars.data(line, text, p + 1, f"NORMAL {text[p]}")
            seen = True
        if not seen:
            raise self.error("NORMAL needs a vector, e.g. NORMAL K-1", line, col)
        nonzero = [k for k, v in comps.items() if v != 0.0]
        if len(nonzero) == 1 and comps[nonzero[0]] < 0:
            self.plane = _NORMAL_PLANES[nonzero[0]]
            return pos
        vec = " ".join(f"{k}{v:g}" for k, v in comps.items())
        raise self.error(f"unsupported NORMAL {vec}: ccopt supports NORMAL K-1 (XY plane), "
                         "J-1 (ZX) and I-1 (YZ)", line, col)

    # -- moves ------------------------------------------------------------------
    def axis_word(self, letter: str, line: int, text: str, pos: int) -> int:
        """Add ``X``/``Y``/``Z``, ``I``/``J``/``K`` or ``R`` to the line's move."""
        value, end = self.vars.data(line, text, pos + 1, letter)
        self.add_axis_word(letter, value, line, pos + 1)
        return end

    def add_axis_word(self, letter: str, value: float, line: int, col: int) -> None:
        """Add the word ``letter`` (at ``col``) with ``value`` to the line's move."""
        if not -MAX_PROGRAM_COORDINATE <= value <= MAX_PROGRAM_COORDINATE:
            self.bounded(value, letter, line, col)
        if self.pending is None:
            self.pending = PendingMove(line, col)
        words = self.pending.words
        if letter in words:
            raise self.error(f"{letter} is written twice in one move", line, col)
        words[letter] = value

    def flush(self) -> None:
        """Execute the move written so far on this line, if any."""
        pend, self.pending = self.pending, None
        if pend is not None:
            self.move(pend.line, pend.col, pend.words)

    def move(self, line: int, col: int, words: dict[str, float]) -> None:
        """Execute the move whose first axis word is at ``line``:``col``:
        ``words`` maps each of ``X Y Z I J K R`` written to its value."""
        start = self.pos
        end = [start[0], start[1], start[2]]
        axes = 0
        for letter, value in words.items():
            i = _AXIS_INDEX.get(letter)
            if i is not None:
                end[i] = start[i] + value if self.incremental[letter] else value
                axes += 1
        if not axes:
            raise self.error("a centre vector or radius without an end point: write the end "
                             "point (X, Y, Z) on the same line", line, col)
        end_t = finite_point(end, self.file, line, col, "end point")
        has_centre = axes < len(words)          # I, J, K or R written
        mcodes = ()
        if self.line_mcodes:
            mcodes = tuple(self.line_mcodes)
            self.line_mcodes = []
        feed = move_time = center = None
        mode = self.mode
        if mode == "RAPID":
            if has_centre:
                raise self.error("I/J/K or R on a RAPID move: only CIRCLE moves take a centre",
                                 line, col)
            motion = Motion.RAPID
        else:
            feed, move_time = self.feed_or_time(line, col)
            if mode == "LINEAR":
                if has_centre:
                    raise self.error("I/J/K or R on a LINEAR move: put CIRCLE1 or CIRCLE2 "
                                     "before it", line, col)
                motion = Motion.LINE
            else:
                cm = CircleMode(mode, self.plane, self.vector_absolute, self.file)
                end_t, center = circle_centre(PendingMove(line, col, words), start, end_t, cm)
                motion = Motion.ARC_CW if mode == "CIRCLE1" else Motion.ARC_CCW
        self.blocks.append(new_block(
            self.file, line, col, motion, start, end_t, self.modal(), center, feed, move_time,
            mcodes, self.markers.get(line) if self.markers else None))
        self.pos = end_t

    def feed_or_time(self, line: int, col: int) -> tuple[float | None, float | None]:
        """``(feed, move_time)`` of a LINEAR/CIRCLE move: one of them is None."""
        if self.time_mode:
            return None, self.move_time
        if self.feed is None:
            raise self.error(f"{self.mode} move without a speed: give F (units per second) or "
                             "TM (move time in ms) before it", line, col)
        return self.feed, None

    def modal(self) -> Modal:
        """The modal state in force (effective side: CC1/CC2 times sign of CCR)."""
        key = (self.plane, self.programmed_side * self.radius_sign, self.radius,
               self.accel_time, self.scurve_time)
        modal = self._modals.get(key)
        if modal is None:
            # Modal is immutable: the blocks run under the same state share one
            modal = Modal(plane=key[0], units="mm", side=key[1], radius=key[2],
                          accel_time=key[3], scurve_time=key[4])
            self._modals[key] = modal
        return modal

    def block(self, source: Source, motion: Motion, start: Vec3, end: Vec3, **kw) -> Block:
        """A block with the modal state in force."""
        surface = self.markers.get(source.line) if self.markers else None
        return Block(source=source, motion=motion, start=start, end=end, modal=self.modal(),
                     surface=surface, **kw)
