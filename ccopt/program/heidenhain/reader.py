"""``read_heidenhain``: Klartext text -> :class:`Program` (dialect ``"heidenhain"``).

Reading order: cut the text into NC blocks (:mod:`.lexer`), find the labels,
then run the blocks from the first with a block counter, a call stack for
``CALL LBL`` and a repeat counter per ``CALL LBL n REP m``. Path functions go
to :mod:`.moves`, cycles to :mod:`.cycles`, Q parameters to :mod:`.values`.
Every problem is a located :class:`~ccopt.errors.ProgramError`; what ccopt
does not read (FK free contours, tilted planes, touch probes, SL and pocket
cycles, ...) is refused where it stands.
"""
from __future__ import annotations

import re

from ccopt.errors import ProgramError
from ccopt.program.heidenhain.args import read_args
from ccopt.program.heidenhain.cycles import Cycles
from ccopt.program.heidenhain.lexer import Statement, split_statements
from ccopt.program.heidenhain.machine import PLANE_OF_AXIS, Machine
from ccopt.program.heidenhain.moves import Moves
from ccopt.program.heidenhain.values import Q_RE, Parameters
from ccopt.program.model import PLANE_AXES, PROGRAM_END, Motion, Program, Source

#: Most NC blocks one run executes (loops and calls included) before it is
#: stopped as a runaway program repeat.
MAX_EXECUTED = 2_000_000
#: ``M140 MB MAX`` retracts along the tool axis to this far above the top of
#: the ``BLK FORM`` (or above the highest position so far without one),
#: program units: ccopt does not know the machine's travel limit, and any
#: height above the part serves a path that only rapids there.
M140_MAX_CLEARANCE = 50.0
_PATH = {"L", "LP", "C", "CP", "CR", "CT", "CC", "RND", "CHF"}
_REFUSED = {
    "FL": "FK free contour programming", "FLT": "FK free contour programming",
    "FC": "FK free contour programming", "FCT": "FK free contour programming",
    "FPOL": "FK free contour programming", "FSELECT": "FK free contour programming",
    "PLANE": "tilting the working plane (PLANE)", "TCH": "touch probe cycles",
    "TRANS": "coordinate transformations (TRANS)", "SEL": "program selection (SEL)",
    "FUNCTION": "FUNCTION blocks", "DECLARE": "DECLARE", "SPEC": "special functions",
    "LN": "LN (3D lines with normal vectors)", "SYSCALL": "SYSCALL",
}
_Q_ASSIGN = re.compile(r"Q[LR]?\d+(=.*)?$")


def read_heidenhain(text: str, file: str = "<string>", *,
                    tool_table: dict | None = None) -> Program:
    """Read a HEIDENHAIN Klartext (conversational) program.

    ``tool_table``: ``{tool number: diameter}`` for the radius of ``TOOL CALL
    n`` (``TOOL DEF n R..`` in the program wins); without either the radius
    comes from ``--radius``. Returns a :class:`Program` of dialect
    ``"heidenhain"``; APPR/DEP blocks are recorded in
    ``meta["heidenhain_leads"]`` for the ``heidenhain`` style.
    """
    statements = split_statements(text, file)
    run = _Run(file, statements, tool_table)
    run.execute()
    m = run.m
    if run.moves.pending is not None:
        p = run.moves.pending
        raise ProgramError(f"{p.kind} is not followed by a contour element", p.src.file,
                           p.src.line, p.src.col)
    return Program(blocks=tuple(m.blocks), file=file, dialect="heidenhain", units=m.units,
                   start=(0.0, 0.0, 0.0), meta=m.meta)


class _Run:
    def __init__(self, file: str, statements: list[Statement], tool_table):
        self.file = file
        self.sts = statements
        self.q = Parameters(file)
        self.m = Machine(file, self.q, tool_table)
        self.moves = Moves(self.m)
        self.cycles = Cycles(self.m)
        self.labels: dict[str, int] = {}
        for i, st in enumerate(statements):
            if st.head == "LBL" and len(st.words) > 1:
                self.labels.setdefault(st.words[1].text.strip('"'), i)
        self.stack: list[int] = []
        self.repeats: dict[int, int] = {}
        self.top_w: float | None = None
        self.ended = False

    def err(self, msg: str, st: Statement, col: int | None = None) -> ProgramError:
        return ProgramError(msg, self.file, st.line, col or st.words[0].col)

    def execute(self) -> None:
        pc, count = 0, 0
        while pc < len(self.sts) and not self.ended:
            count += 1
            if count > MAX_EXECUTED:
                raise self.err(f"more than {MAX_EXECUTED} blocks executed: a runaway "
                               "program repeat or jump?", self.sts[pc])
            nxt = self.statement(pc, self.sts[pc])
            pc = pc + 1 if nxt is None else nxt

    # -- one block ---------------------------------------------------------------------
    def statement(self, pc: int, st: Statement) -> int | None:
        head = st.head
        src = Source(self.file, st.line, st.words[0].col)
        if head in _PATH:
            if head == "CHF":
                self._chf(src, st)
            else:
                self._path(src, head, st)
            return None
        if head in ("APPR", "DEP"):
            if len(st.words) < 2:
                raise self.err(f"{head}: give its kind (LT, LN, CT, LCT)", st)
            a = read_args(st, list(st.words[2:]), self.q, self.file)
            kind = st.words[1].text
            (self.moves.appr if head == "APPR" else self.moves.dep)(src, kind, a)
            self._after_move(src, a.mcodes)
            return None
        if head == "LBL":
            if len(st.words) > 1 and st.words[1].text == "0" and self.stack:
                return self.stack.pop()
            return None
        if head == "CALL":
            return self._call(pc, st)
        if head == "FN":
            jump = self.q.fn(st)
            if jump is not None and jump[1]:
                return self._label(jump[2].strip('"'), st)
            return None
        if _Q_ASSIGN.match(head) and Q_RE.match(head):
            self.q.assignment(st)
            return None
        if head == "CYCL":
            self._cycle(src, st)
            return None
        return self._other(src, head, st)

    def _other(self, src: Source, head: str, st: Statement) -> int | None:
        if head in ("BEGIN", "END"):
            if len(st.words) >= 4 and st.words[1].text == "PGM":
                unit = st.words[-1].text
                if unit not in ("MM", "INCH"):
                    raise self.err(f"{head} PGM: the unit must be MM or INCH, not {unit}", st,
                                   st.words[-1].col)
                self.m.units = "mm" if unit == "MM" else "inch"
            self.ended = head == "END"
            return None
        if head == "BLK":
            self._blk_form(st)
            return None
        if head == "TOOL":
            self._tool(src, st)
            return None
        if head == "STOP" or head.startswith("M"):
            words = st.words[1:] if head == "STOP" else st.words
            a = read_args(st, list(words), self.q, self.file)
            a.allow({"M"}, "a block of M functions", self.file)
            self._after_move(src, a.mcodes, moved=False)
            return None
        why = _REFUSED.get(head)
        if why is None:
            raise self.err(f"{head}: this block is not read by ccopt", st)
        raise self.err(f"{head}: {why} is not read by ccopt", st)

    def _path(self, src: Source, head: str, st: Statement) -> None:
        a = read_args(st, list(st.words[1:]), self.q, self.file)
        if 140 in a.mcodes:
            self._m140(src, st, a)
            return
        if head in ("L", "LP"):
            self.moves.line(src, a, head == "LP")
        elif head in ("CC", "RND"):
            if head == "CC":
                self.moves.pole(src, a)
            else:
                self.moves.corner(src, head, a, None)
            return
        else:
            self.moves.arc(src, head, a)
        self._after_move(src, a.mcodes)

    def _chf(self, src: Source, st: Statement) -> None:
        if len(st.words) < 2:
            raise self.err("CHF: give the chamfer length (CHF 1)", st)
        w = st.words[1]
        value = self.q.number(w.text, st.line, w.col, "CHF ")
        a = read_args(st, list(st.words[2:]), self.q, self.file)
        self.moves.corner(src, "CHF", a, value)

    def _after_move(self, src: Source, mcodes: tuple, moved: bool = True) -> None:
        """What the M functions of a block do after its move: ``M99`` calls
        the cycle, ``M89`` calls it after this and every later positioning
        block (until ``M99`` or a new ``CYCL DEF``), ``M2``/``M30`` end."""
        if 89 in mcodes:
            self.cycles.modal_call = True
        if 99 in mcodes:
            self.cycles.modal_call = False
            self.cycles.call(src)
        elif self.cycles.modal_call and moved:
            self.cycles.call(src)
        if any(c in (2, 30) for c in mcodes) and not self.stack:
            self.m.meta[PROGRAM_END] = next(f"M{c}" for c in mcodes if c in (2, 30))
            self.ended = True

    def _m140(self, src: Source, st: Statement, a) -> None:
        """``L M140 MB MAX`` / ``MB <distance>``: retract along the tool axis."""
        m = self.m
        iw = PLANE_AXES[m.plane][2]
        texts = [w.text for w in a.extra]
        if a.coords:
            raise self.err("M140 with coordinates: program the retract in a block of its own",
                           st, a.col("X"))
        target = list(m.pos)
        if "MAX" in texts or "MBMAX" in texts:
            top = self.top_w if self.top_w is not None else m.pos[iw]
            target[iw] = max(m.pos[iw], top + M140_MAX_CLEARANCE)
        else:
            dist = next((w for w in a.extra if w.text.startswith("MB") and len(w.text) > 2), None)
            if dist is None:
                raise self.err("M140: give MB MAX or MB <distance>", st)
            target[iw] += abs(self.q.number(dist.text[2:], st.line, dist.col, "MB"))
        if target != m.pos:
            m.emit(src, Motion.LINE, target, rapid=True, side=0)

    def _blk_form(self, st: Statement) -> None:
        texts = st.texts()
        self.m.meta.setdefault("blk_form", []).append(" ".join(texts))
        if len(texts) > 2 and texts[1] == "FORM" and texts[2] in ("0.2",):
            axis = "XYZ"[PLANE_AXES[self.m.plane][2]]
            for w in st.words[3:]:
                if w.text.startswith(axis) and len(w.text) > 1:
                    self.top_w = self.q.number(w.text[1:], st.line, w.col, axis)

    def _tool(self, src: Source, st: Statement) -> None:
        words = st.words
        if len(words) < 3 or words[1].text not in ("CALL", "DEF"):
            raise self.err("expected TOOL CALL or TOOL DEF", st)
        ident = words[2].text
        tool = None
        rest = list(words[3:])
        if words[1].text == "CALL" and ident in PLANE_OF_AXIS:
            # TOOL CALL without a tool number (``TOOL CALL Z``, as the Autodesk
            # posts write it before ``L M140 MB MAX``): the tool axis, S, F and
            # DR change, the tool in the spindle stays
            self._tool_axis_call(src, st, list(words[2:]))
            return
        if not ident.startswith('"'):
            tool = int(self.q.number(ident, st.line, words[2].col, "TOOL "))
        if words[1].text == "DEF":
            a = read_args(st, [w for w in rest if not w.text.startswith("L")], self.q,
                          self.file)
            if tool is not None and a.radius is not None:
                self.m.tool_radii[tool] = a.radius
            return
        a = self._tool_call_args(st, rest)
        self.m.set_tool_radius(tool, a.dr_value or 0.0, src)

    def _tool_call_args(self, st: Statement, rest: list):
        """The words of ``TOOL CALL`` after its tool number: the tool axis (it
        sets the working plane), then S, F, DL, DR (DR2 is read past), M;
        sets the spindle speed and the feed, returns the arguments."""
        if rest and rest[0].text in PLANE_OF_AXIS:
            if self.m.rot != 0.0 and PLANE_OF_AXIS[rest[0].text] != self.m.plane:
                raise ProgramError("TOOL CALL with another tool axis while the working plane "
                                   "is turned (CYCL DEF 10): end the rotation (ROT+0) first",
                                   self.file, st.line, rest[0].col)
            self.m.plane = PLANE_OF_AXIS[rest[0].text]
            rest = rest[1:]
        a = read_args(st, [w for w in rest if not w.text.startswith("DR2")], self.q, self.file)
        a.allow({"S", "F", "DL", "DR", "M"}, "TOOL CALL", self.file)
        if a.feed is not None:
            self.m.tool_feed = a.feed
        if a.speed is not None:
            self.m.speed = a.speed
        return a

    def _tool_axis_call(self, src: Source, st: Statement, rest: list) -> None:
        """``TOOL CALL`` with a tool axis and no tool number: the axis, S and F
        as any ``TOOL CALL``; the tool stays, with this call's DR when it gives one."""
        a = self._tool_call_args(st, rest)
        if a.dr_value is not None:
            self.m.set_tool_radius(self.m.tool, a.dr_value, src)

    def _cycle(self, src: Source, st: Statement) -> None:
        if len(st.words) > 1 and st.words[1].text == "CALL":
            rest = list(st.words[2:])
            if rest and rest[0].text == "PAT":
                raise self.err("CYCL CALL PAT is not read by ccopt: position with L, then "
                               "CYCL CALL or M99", st, rest[0].col)
            pos = bool(rest) and rest[0].text == "POS"
            a = read_args(st, rest[1:] if pos else rest, self.q, self.file)
            a.allow({"M", "F"} | (set("XYZ") if pos else set()), "CYCL CALL", self.file)
            surface = self._call_position(src, a) if pos else None
            self.cycles.call(src, surface)
            self._after_move(src, tuple(c for c in a.mcodes if c != 99), moved=False)
            return
        self.cycles.define(st)

    def _call_position(self, src: Source, a) -> float | None:
        """``CYCL CALL POS X Y Z``: move in the working plane to ``X Y`` (at
        ``F``, else rapid), and the tool-axis coordinate is the surface the
        cycle starts from (it replaces ``Q203``); ``None`` when not given."""
        m = self.m
        iw = PLANE_AXES[m.plane][2]
        axis = "XYZ"[iw]
        target = m.target({k: v for k, v in a.coords.items() if k != axis})
        m.feed_from(a.feed, a.st.line, a.col("F"), a.fauto)
        if target != m.pos:
            m.emit(src, Motion.LINE, target, rapid=a.feed is None, side=0)
        if axis not in a.coords:
            return None
        return m.target({axis: a.coords[axis]})[iw] - m.datum[iw]

    # -- labels and calls ------------------------------------------------------------------
    def _label(self, name: str, st: Statement) -> int:
        if name not in self.labels:
            raise self.err(f"label {name} is not defined (LBL {name})", st)
        return self.labels[name] + 1

    def _call(self, pc: int, st: Statement) -> int | None:
        words = st.words
        if len(words) < 3 or words[1].text != "LBL":
            raise self.err("CALL: only CALL LBL is read by ccopt (CALL PGM is not)", st)
        name = words[2].text.strip('"')
        rep = None
        for i, w in enumerate(words[3:], start=3):
            if w.text.startswith("REP"):
                text = w.text[3:] or (words[i + 1].text if i + 1 < len(words) else "")
                text = text.split("/")[0]
                rep = int(self.q.number(text, st.line, w.col, "REP "))
        target = self._label(name, st)
        if rep is None:
            if len(self.stack) > 100:
                raise self.err("CALL LBL nested more than 100 deep", st)
            self.stack.append(pc + 1)
            return target
        left = self.repeats.get(pc, rep)
        if left > 0:
            self.repeats[pc] = left - 1
            return target
        self.repeats.pop(pc, None)
        return None
