"""The reader's state: one object every stage reads and updates.

As LinuxCNC's interpreter passes its ``setup`` to every ``read_*``,
``convert_*`` and O-word function, the stages of this reader (lexing in
:mod:`.words`, parameters in :mod:`.parameters`, O-word flow in
:mod:`.oword`, modal execution in :mod:`.execute`, arcs in :mod:`.arcs`) all
take one :class:`GCodeState`: the program text and its caches, the modal
machine state, the parameters, the subroutine call frames and the limits.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

from ccopt.errors import ProgramError
from ccopt.program.expr import Grammar
from ccopt.program.model import Block, Modal

#: Highest numbered parameter (LinuxCNC RS274NGC_MAX_PARAMETERS - 1).
MAX_PARAMETER = 5601

#: Executed lines (loops and calls counted each time) before the reader
#: gives up on a runaway program.
MAX_EXECUTED_LINES = 1_000_000
#: Deepest subroutine call nesting accepted.
MAX_CALL_DEPTH = 100
#: Loop iterations (every pass of every ``do``/``while``/``repeat`` loop of
#: the program, together) before the reader stops a runaway loop.
#: ``read_gcode(max_loop_iterations=)`` and ``--max-loop-iterations`` raise
#: it for a program that needs more; real programs' loops (depth passes,
#: patterns) make far fewer.
MAX_LOOP_ITERATIONS = 10_000
#: Lines the loops may execute (all loops together, nested loops and the
#: subroutines they call included) per allowed iteration: a long loop body
#: stops as soon as a short one. The reader takes 20-60 us a line (a move
#: with expressions, on this project's 2-core machine under load), so the
#: default 30,000 lines stop a runaway in 0.6-2 s.
LOOP_LINES_PER_ITERATION = 3

LINE_SPLIT = re.compile(r"\r\n|\r|\n")


class ProgramEnd(Exception):
    """Program end (``M2``/``M30``) reached: nothing after it executes."""


@dataclass(slots=True)
class Ctrl:
    """An O-word structure being executed (an ``if`` branch or a loop)."""

    kind: str      # "if" | "do" | "while" | "repeat"
    label: str
    start: int     # 0-based line of the opener
    end: int       # 0-based line of the closer
    remaining: int = 0  # repeat: passes still to run after this one


@dataclass(slots=True)
class Frame:
    """The main program or one subroutine call being executed."""

    name: str | None   # subroutine label; None for the main program
    return_pc: int     # 0-based line to continue at after the return
    call_line: int     # 0-based line of the call (-1: main program)
    saved: dict = field(default_factory=dict)   # caller's #1..#30, restored on return
    named: dict = field(default_factory=dict)   # local named parameters
    ctrl: list = field(default_factory=list)    # open Ctrl structures, innermost last
    fanuc: bool = False  # an M98 call of a Fanuc subprogram (parameters not local)
    repeats: int = 0     # M98 L: passes still to run after this one
    start: int = -1      # M98: 0-based line of the subprogram's O-word head

@dataclass(slots=True)
class CycleState:
    """The sticky cycle values (LinuxCNC ``cycle_r``, ``cycle_cc``, ``cycle_p``,
    ``cycle_q``, ``cycle_i/j/k``, ``cycle_il``), program units and seconds.

    ``level`` is the initial level in work coordinates, ``None`` when no
    series of cycles is running; ``retract`` is ``"initial"`` (G98) or
    ``"r"`` (G99, LinuxCNC's start-up mode). ``tool_at``: where the tool
    really is (machine coordinates) after a ``G74``/``G84`` outside G17, whose
    last feed goes to a permuted point while LinuxCNC takes the hole at the
    clear level as its current point (the state's ``pos``); the next move
    starts from ``tool_at`` (``None``: the tool is at ``pos``).
    """

    retract: str = "r"
    r: float = 0.0
    w: float = 0.0
    p: float = 0.0
    q: float = 0.0
    ijk: tuple[float, float, float] = (0.0, 0.0, 0.0)
    level: float | None = None
    tool_at: tuple[float, float, float] | None = None


class GCodeState:
    """Everything the reader knows while it runs one program text.

    Positions are absolute ``(x, y, z)`` in program units; ``feed`` is the
    F word in units per minute (``G94``) or per revolution (``G95``); modes are stored as the reader
    exposes them in :class:`~ccopt.program.model.Modal` (``plane`` "XY",
    "ZX" or "YZ"; ``side`` +1 left, -1 right, 0 off). Line numbers held here
    (``line_no``, ``first_line``, ``end_line``, structure lines) are 0-based.
    """

    #: ``G96``: ``[radius x rpm product, maximum rpm or None]`` in output
    #: units (spindle.py); ``None`` under ``G97``, the start-up mode.
    css: list | None = None
    #: LinuxCNC's ``rs274 -n 0``: go on after an error (reader._go_on_after).
    keep_going: bool = False

    def __init__(self, text: str, file: str, tool_table: dict[int, float] | None,
                 start: tuple[float, float, float], *,
                 max_executed_lines: int = MAX_EXECUTED_LINES,
                 max_call_depth: int = MAX_CALL_DEPTH,
                 max_loop_iterations: int = MAX_LOOP_ITERATIONS):
        self.file = file
        self.lines = LINE_SPLIT.split(text)
        if self.lines and self.lines[-1] == "":
            self.lines.pop()
        # caches, per 0-based line: lexed text, matched O-word structure,
        # words of a line whose values cannot change
        self.lexed: dict = {}
        self.matched: dict[int, tuple] = {}
        self.constant: dict = {}
        self.tool_table = tool_table
        self.grammar: Grammar | None = None  # set by parameters.attach_grammar
        self.max_executed_lines = max_executed_lines
        self.max_call_depth = max_call_depth
        self.max_loop_iterations = max_loop_iterations
        self.loop_iterations = 0  # loop passes started so far, all loops together
        self.max_loop_lines = LOOP_LINES_PER_ITERATION * max_loop_iterations
        self.loop_lines = 0       # lines executed while a loop was open, all loops together
        self.in_loop = False      # a loop is open in some frame (updated after O-words)
        # machine state
        self.pos = start
        # A B C U V W in machine coordinates (axes.py); None until a word moves one
        self.extra: list[float] | None = None
        self.start = start
        self.blocks: list[Block] = []
        self.moved = False
        self.plane = "XY"
        self.units: str | None = None      # the words' units as written now (G20/G21)
        self.out_units: str | None = None  # every length is converted to this (units.py)
        self.table_units: str | None = None  # the tool table's units (None: out_units)
        self.incremental = False
        self.arc_incremental = True
        # G7 lathe diameter mode: X words are diameters (halved when read)
        self.diameter_mode = False
        # coordinate systems (see coordinates.py): active origin 1..9 (G54..G59.3)
        # and the G92/G52 axis offset, program units
        self.origin_index = 1
        self.axis_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.feed_mode = "per_minute"
        self.feed: float | None = None       # G94 F, units per minute
        self.motion_mode: int | None = None  # tenths (G1 -> 10); None = G80
        self.side = 0
        self.radius: float | None = None
        self.tool: int | None = None
        self.orientation = 0  # lathe tool orientation Q (0: mill tool)
        self.selected_tool: int | None = None
        self.loaded_tool: int | None = None
        self.corner = "circular"
        # "cw" (M3), "ccw" (M4), "stopped" (M5, at start); S in rev/min (0 until an S word)
        self.spindle, self.spindle_speed = "stopped", 0.0
        self.cycle = CycleState()  # sticky canned-cycle values (cycles.py)
        # machine words read since the last block, and the work frame (machine_words.py)
        self.pending_words: list[str] = []
        self.frame = None
        self.frame_key: tuple | None = None
        self.start_end = "contour"
        self.siemens = None   # SINUMERIK modes (ccopt.program.sinumerik), else None
        self._modal: Modal | None = None
        self.meta: dict = {"tool_length": []}
        self.fanuc_subs: dict[str, int] = {}  # Fanuc subprogram label -> its O line
        # parameters
        self.params: dict[int, float] = {}
        self.globals: dict[str, float] = {"_value": 0.0, "_value_returned": 0.0}
        # control
        self.subs: dict[str, tuple[int, int]] = {}
        self.frames: list[Frame] = [Frame(name=None, return_pc=-1, call_line=-1)]
        self.line_no = 0          # 0-based index of the line being executed
        self.executed = 0
        self.first_line = 0       # program lines are [first_line, end_line)
        self.end_line = len(self.lines)
        self.main_lines = len(self.lines)
        # subroutine files read into ``lines`` after the program: (first, end, file)
        self.sub_files: list[tuple[int, int, str]] = []
        self.sub_path: tuple[str, ...] = ()
        self.ini = None   # the machine's INI file (gcode/ini.py) for #<_ini[...]>, or None

    def where(self, ln: int) -> tuple[str, int]:
        """``(file, 1-based line)`` of 0-based line ``ln`` of ``lines``."""
        for first, end, file in self.sub_files:
            if first <= ln < end:
                return file, ln - first + 1
        return self.file, ln + 1

    def region_end(self, ln: int) -> int:
        """End of the text line ``ln`` belongs to: the program's or a sub file's."""
        for first, end, _ in self.sub_files:
            if first <= ln < end:
                return end
        return self.end_line

    def in_sub_file(self, ln: int) -> bool:
        return any(first <= ln < end for first, end, _ in self.sub_files)

    def error(self, message: str, col: int | None = None, line: int | None = None) -> ProgramError:
        """A located error; ``col`` is 0-based (None: unknown), ``line`` 0-based
        (None: the line being executed)."""
        file, line1 = self.where(self.line_no if line is None else line)
        return ProgramError(message, file, line1, None if col is None else col + 1)

    def modal(self) -> Modal:
        """The modal state blocks carry (one shared object until a mode changes)."""
        if self._modal is None:
            self._modal = Modal(plane=self.plane, units=self.out_units or self.units or "mm",
                                side=self.side,
                                radius=self.radius, tool=self.tool, corner=self.corner,
                                start_end=self.start_end, orientation=self.orientation,
                                siemens=self.siemens)
        return self._modal

    def modal_changed(self) -> None:
        """A mode carried by :class:`Modal` changed: the next block takes a new one."""
        self._modal = None
