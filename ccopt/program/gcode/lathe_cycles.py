"""Lathe roughing and finishing cycles G70, G71, G71.1, G71.2, G72, G72.1 and
G72.2, as LinuxCNC runs them (``interp_g7x.cc``: ``convert_g7x`` and
``motion_machine``; the geometry in :mod:`.g7x_contour` and :mod:`.g7x_path`).

``G71 Q<sub> X Z [D] [I] [R] [U] [W]`` (turning) and ``G72`` (facing, the
same with the profile turned by 90 degrees): a rapid to X Z (the start
point, absolute or under ``G91`` incremental), then the contour is read by
running ``o<sub>`` without moving, then the stock between the start point and
the contour is roughed in passes ``I`` deep (default 1) along Z (``G72``:
along X), each retracting by ``R`` (default 0.5) along both axes, leaving
``D`` (default 0) off the contour, the whole shifted by ``U`` (X) and ``W``
(Z). Under ``G91`` the contour's X Z are increments (its U W refused, as
LinuxCNC refuses them) and the cycle's line may not hold X or Z. ``G7x.1`` cuts no pockets (a contour that dips back is followed, not
cut); ``G7x.2`` cuts only the pockets. ``G70 Q<sub> X Z [D] [E] [P]``
(finishing): ``P`` passes (default 1) along the contour from ``D`` off it to
``E`` off it, each from a rapid to X Z made with cutter compensation off.

The contour's sub is read as LinuxCNC reads it: only its O-words, parameter
settings and moves act (``G0``-``G3`` with ``X Z`` absolute, ``U W``
incremental, ``I K`` or ``R`` for arcs, ``A`` a fillet and ``C`` a chamfer
of the corner at the end of the move); the distance modes are those of the
cycle's line; other words are ignored. Lengths are program units; X and U
(of the contour) are diameters in ``G7`` (halved as read), the cycle's own
``U`` is a radius as in LinuxCNC. Every move of a cycle is a block located
at the cycle's line and marked with it (``Block.cycle``, e.g. ``"G71.1"``),
timed and verified like any move. After the cycle the motion mode is that of
its last move (LinuxCNC's).

Refused, located: no ``Q``, a ``Q`` with no sub, ``G71``/``G72`` with cutter
compensation on, a plane other than ``G18``, ``I`` <= 0, ``G93``, no feed
rate, the contour errors LinuxCNC stops at (``U`` with ``X``, ``W`` with
``Z``, ``U``/``W`` under ``G91``, arcs without centre or with both ``R``
and ``I``/``K``, ``A`` with ``C``, a contour that is not monotonic), and,
where LinuxCNC would do something odd or loop for ever: Y, A, B, C, V on the
cycle's line (LinuxCNC's first rapid would move those axes), a contour move
that is not ``G0``-``G3``, a ``G10``/``G28``/``G30``/``G52``/``G53``/``G92``
in the contour, a ``G70`` ``P`` that is not a whole number from 1, a cycle
that makes no progress or needs more than
:data:`~.g7x_path.MAX_STEPS` steps.
"""
from __future__ import annotations

import math
from dataclasses import replace

from ccopt import tolerances
from ccopt.errors import ProgramError
from ccopt.program.gcode.arcs import arc_tolerance
from ccopt.program.gcode.codes import classify, read_words
from ccopt.program.gcode.coordinates import check_unrotated_plane, to_machine, to_work
from ccopt.program.gcode.g7x_contour import Chamfer, Fillet, G7xError, Round, Segment, Straight
from ccopt.program.gcode.g7x_path import Budget, Profile
from ccopt.program.gcode.oword import count_line, enter_sub, exec_oword, innermost_loop
from ccopt.program.gcode.parameters import set_parameter
from ccopt.program.gcode.spindle import per_revolution
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.units import input_factor
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, gname, lex
from ccopt.program.model import Block, Motion, Source

#: G70 and the roughing cycles, in tenths.
FINISHING = 700
LATHE_CYCLES = frozenset({700, 710, 711, 712, 720, 721, 722})
ROUGHING = LATHE_CYCLES - {FINISHING}
#: Moves one cycle may make. LinuxCNC has no bound; a roughing pass makes
#: four or five moves, so this is some 10,000 passes (1 um cuts through 10 mm),
#: which the reader makes in about 0.6 s (12 us a block).
MAX_CYCLE_MOVES = 50_000
#: LinuxCNC's ``TOLERANCE_EQUAL``: an arc ending this close to where the tool
#: is (in X and in Z) is left out, as ``motion_machine::circular_move`` does.
_SAME_POINT = 1e-6
#: Axis words a cycle's line may not carry: its moves are in X and Z.
_OTHER_AXES = "YABCV"
#: Codes that would take a contour line's axis words for themselves.
_NOT_IN_CONTOUR = ("axis_setting", "machine_coords")


def run_lathe_cycle(state: GCodeState, code: int, gcol: int, L: dict, mcodes: tuple,
                    first_col: int, emit) -> None:
    """Execute cycle ``code`` (tenths) of the current line with words ``L``
    (lengths in output units, X a radius); ``emit(state, block)`` records a
    block; ``gcol`` (0-based) locates the cycle's errors."""
    name = gname(code)
    _check_line(state, code, name, gcol, L)
    factor = input_factor(state)     # D and E are lengths the units module leaves alone
    here = to_work(state, state.pos)
    x = L["X"][0] if "X" in L else here[0]     # absolute: _check_line refuses them in G91
    z = L["Z"][0] if "Z" in L else here[2]
    src = Source(*state.where(state.line_no), first_col + 1)
    out = _Emitter(state, name, src, mcodes, emit, here[1], gcol)
    out.straight_rapid(complex(z, x), comp_off=True)
    path, out.mode, last = _capture(state, name, L["Q"], complex(z, x))
    if len(path) > 1:
        i = L["I"][0] if "I" in L else 1.0 * factor
        if i <= 0:
            raise state.error("G7X error: I must be greater than zero.", L["I"][1])
        d = L["D"][0] * factor if "D" in L else 0.0
        try:
            _run(state, code, Profile(path, Budget()), out, last, x, z, d, i, L, factor)
        except G7xError as exc:
            raise state.error(f"G7X error: {exc}", gcol) from None
    state.motion_mode = out.mode


def _run(state: GCodeState, code: int, profile: Profile, out, last: complex, x: float,
         z: float, d: float, i: float, L: dict, factor: float) -> None:
    """The cycle's passes over the captured ``profile`` (``last``: the
    contour's end)."""
    path = profile.segs
    if code == FINISHING:
        e = L["E"][0] * factor if "E" in L else 0.0
        profile.do_g70(out, x, z, d, e, _passes(state, L))
        return
    u = L["U"][0] if "U" in L else 0.0
    w = L["W"][0] if "W" in L else 0.0
    r = L["R"][0] if "R" in L else 0.5 * factor
    front = path[0].end - path[0].start
    back = path[-1].end - path[-1].start
    if code // 10 == 71:
        if abs(back.real) > 0 and front.imag * (x - last.imag) < 0:
            path.append(Straight(last, complex(last.real, x)))
    elif abs(back.imag) > 0 and front.real * (z - last.real) < 0:
        path.append(Straight(last, complex(z, last.imag)))
    profile.do_g71(out, code % 10, x, z, u, w, d, i, r, do_rotate=code // 10 == 72)


def _passes(state: GCodeState, L: dict) -> int:
    """G70's ``P``: the number of finishing passes (default 1)."""
    if "P" not in L:
        return 1
    p, col = L["P"]
    if abs(p - round(p)) > WHOLE_NUMBER_TOL or round(p) < 1:
        raise state.error(f"G70 P{fmt(p)}: P is the number of finishing passes, a whole "
                          "number from 1", col)
    return int(round(p))


def _check_line(state: GCodeState, code: int, name: str, gcol: int, L: dict) -> None:
    """LinuxCNC's checks of ``convert_g7x`` before it moves, and ccopt's own."""
    if "Q" not in L:
        raise state.error(f"{name} requires a Q word: the number of the subroutine that "
                          "holds the contour", gcol)
    if state.side != 0 and code != FINISHING:
        raise state.error(f"{name} cannot be used with cutter compensation enabled "
                          "(LinuxCNC refuses it): program G40 before the cycle", gcol)
    if state.plane != "ZX":
        raise state.error(f"{name} can only be used in XZ plane (G18)", gcol)
    check_unrotated_plane(state, f"{name} (a lathe cycle)", gcol)
    if state.feed_mode == "inverse":
        raise state.error(f"{name} with inverse time feed (G93): the cycle makes its own "
                          "moves, which have no F of their own; program G94 first", gcol)
    for a in "XZ":
        if state.incremental and a in L:
            # convert_g7x sets G90 before its first rapid, which reads the words as
            # they are: the rapid and the cycle would start at different points
            raise state.error(f"{a} word with {name} under G91: LinuxCNC's first rapid "
                              f"takes {a} as an absolute coordinate while the cycle adds it "
                              "to the position; program the cycle's line under G90",
                              L[a][1])
    for a in _OTHER_AXES:
        if a in L:
            raise state.error(f"{a} word with {name}: the lathe cycles move X and Z only "
                              "(LinuxCNC's first rapid would move that axis too)", L[a][1])


# ---------------------------------------------------------------------------
# The moves
# ---------------------------------------------------------------------------
class _Emitter:
    """LinuxCNC's ``motion_machine``: the cycle's moves as blocks, from points
    ``z + x*1j`` in work coordinates of the ZX plane (Y stays at ``y``)."""

    def __init__(self, state: GCodeState, name: str, src: Source, mcodes: tuple, emit,
                 y: float, gcol: int):
        self.state = state
        self.name = name
        self.src = src
        self.mcodes = mcodes
        self.emit = emit
        self.y = y
        self.gcol = gcol
        self.at: complex | None = None   # where the tool is, z + x*1j
        self.mode: int | None = 0        # the motion mode the moves leave
        self.moves = 0
        self.surface: str | None = None   # Block.surface of the moves (G70's early passes)

    def _machine(self, p: complex) -> tuple[float, float, float]:
        return to_machine(self.state, (p.imag, self.y, p.real))

    def _block(self, motion: Motion, end: complex, comp_off: bool = False, **kw) -> None:
        state = self.state
        modal = state.modal()
        if comp_off and modal.side != 0:
            # G70's rapids to its start points: LinuxCNC makes them with compensation off
            modal = replace(modal, side=0)
        self.moves += 1
        if self.moves > MAX_CYCLE_MOVES:
            raise state.error(f"{self.name} makes more than {MAX_CYCLE_MOVES} moves (depth of "
                              "cut I too small for the contour?); ccopt stops it here",
                              self.gcol)
        target = self._machine(end)
        self.emit(state, Block(self.src, motion, state.pos, target, modal, mcodes=self.mcodes,
                               cycle=self.name, surface=self.surface, **kw))
        self.mcodes = ()
        state.pos = target
        state.moved = True
        self.at = end

    def _feed(self, end: complex, center=None) -> float:
        """The feed of a cutting move to ``end`` (about the machine point
        ``center`` for an arc), program units per second: F per minute, or
        under ``G95`` per spindle revolution (spindle.py)."""
        if not self.state.feed:
            raise self.state.error("Cannot feed with zero feed rate: give the cycle's F "
                                   "(units per minute) on this or an earlier line", self.gcol)
        if self.state.feed_mode == "per_revolution":
            return per_revolution(self.state, self.state.feed, self.state.pos,
                                  self._machine(end), self.gcol, center)
        return self.state.feed / 60.0

    def straight_rapid(self, end: complex, comp_off: bool = False) -> None:
        self._block(Motion.RAPID, end, comp_off)
        self.mode = 0

    def straight_move(self, end: complex) -> None:
        self._block(Motion.LINE, end, feed=self._feed(end))
        self.mode = 10

    def circular_move(self, ccw: bool, center: complex, end: complex) -> None:
        if (self.at is not None and abs(self.at.real - end.real) < _SAME_POINT
                and abs(self.at.imag - end.imag) < _SAME_POINT):
            return
        _check_radii(self.state, self.at, center, end, self.gcol, self.name)
        c = self._machine(center)
        self._block(Motion.ARC_CCW if ccw else Motion.ARC_CW, end, center=c, turns=0,
                    feed=self._feed(end, c))
        self.mode = 30 if ccw else 20


def _check_radii(state: GCodeState, start: complex, center: complex, end: complex, col: int,
                 name: str) -> None:
    """An arc's start and end radii agree, neither is zero (LinuxCNC's
    ``arc_data_ijk``; ccopt's arc tolerances)."""
    r0, r1 = abs(start - center), abs(end - center)
    tol = arc_tolerance(state)
    if not (r0 >= 0.1 * tol and r1 >= 0.1 * tol):
        raise state.error(f"{name}: zero-radius arc at Z{end.real:g} X{end.imag:g}", col)
    err = abs(r0 - r1)
    if err > tol and err > tolerances.ARC_RADIUS_REL_TOL * max(r0, r1):
        raise state.error(f"{name}: radius to end of arc differs from radius to start: "
                          f"start r={r0:.6g}, end r={r1:.6g} (arc to Z{end.real:g} "
                          f"X{end.imag:g})", col)


# ---------------------------------------------------------------------------
# The contour
# ---------------------------------------------------------------------------
def _capture(state: GCodeState, name: str, q: tuple[float, int],
             start: complex) -> tuple[list[Segment], int | None, complex]:
    """Run the contour's sub (LinuxCNC: ``read("O<q> CALL")`` and its loop
    over the sub's blocks) without moving: its segments from ``start``, the
    motion mode it leaves and its end point."""
    value, qcol = q
    if abs(value - round(value)) > WHOLE_NUMBER_TOL or value < 0:
        raise state.error(f"{name} Q{fmt(value)}: Q is the number of the contour's "
                          "subroutine, a whole number", qcol)
    call_line = state.line_no
    depth = len(state.frames)
    try:
        pc = enter_sub(state, str(int(round(value))), call_line, qcol, [])
    except ProgramError as exc:
        exc.message = f"{name} Q{int(round(value))}: {exc.message}"
        raise
    contour = _Contour(state, start)
    while len(state.frames) > depth:
        _count_line(state, pc)
        lx = lex(state, pc)
        if lx.oword is not None:
            pc = exec_oword(state, pc, lx)
            state.in_loop = innermost_loop(state) is not None
            continue
        if lx.fanuc is not None:
            raise state.error(f"M{lx.fanuc} in the contour of {name} (called from line "
                              f"{call_line + 1}): the contour is an O-word sub", lx.start)
        if lx.first is not None:
            words, settings = read_words(state, lx)
            for kind, key, setting in settings:
                set_parameter(state, kind, key, setting)
            classify(state, words)
            contour.line(words)
        pc += 1
    state.line_no = call_line
    state.in_loop = innermost_loop(state) is not None
    return contour.path, contour.mode, contour.at


def _count_line(state: GCodeState, pc: int) -> None:
    """The runaway guards of the reader's line loop, for line ``pc``."""
    if pc >= len(state.lines):
        raise state.error("the contour's subroutine runs past the end of the text")
    count_line(state, pc)


class _Contour:
    """The segments LinuxCNC's ``convert_g7x`` builds from the contour's lines."""

    def __init__(self, state: GCodeState, start: complex):
        self.state = state
        self.at = start
        self.mode: int | None = 0      # the cycle's first rapid set G0
        self.path: list[Segment] = []

    def _words(self, words) -> dict:
        """The line's contour words in output units (X and U halved in G7)."""
        state = self.state
        factor = input_factor(state)
        out = {}
        for letter in "XZUWIKRAC":
            if letter in words.letters:
                value, col = words.letters[letter]
                value *= factor
                if letter in "XU" and state.diameter_mode:
                    value /= 2.0
                out[letter] = (value, col)
        return out

    def line(self, words) -> None:
        """One contour line: its move (if it moves) and corner."""
        state = self.state
        for group in _NOT_IN_CONTOUR:
            if group in words.gcodes:
                tenths, col = words.gcodes[group]
                raise state.error(f"{gname(tenths)} in a lathe cycle's contour: LinuxCNC "
                                  "would read its axis words as a contour move", col)
        L = self._words(words)
        end = self._end(L)
        motion = words.gcodes.get("motion")
        if motion is not None:
            self.mode = None if motion[0] == 800 else motion[0]
        if end == self.at:
            return
        if self.mode in (0, 10):
            self.path.append(Straight(self.at, end))
        elif self.mode in (20, 30):
            col = motion[1] if motion is not None else words.first or 0
            self.path.append(Round(self.mode == 30, self.at, self._center(L, end, col), end))
        else:
            col = motion[1] if motion is not None else words.first or 0
            raise state.error("a lathe cycle's contour moves with G0, G1, G2 and G3 only",
                              col)
        if "A" in L and "C" in L:
            raise state.error("G7X error: Both A and C parameters on a corner", L["C"][1])
        if "A" in L:
            self.path.append(Fillet(L["A"][0], end))
        if "C" in L:
            self.path.append(Chamfer(L["C"][0], end))
        self.at = end

    def _end(self, L: dict) -> complex:
        """The move's end: X Z absolute (G90) or incremental (G91), U W incremental."""
        state = self.state
        incremental = state.incremental
        end = 0j if incremental else self.at
        for inc, word, along in (("U", "X", 1j), ("W", "Z", 1)):
            if inc in L:
                if incremental:
                    raise state.error(f"G7x error: Cannot use {inc} in incremental mode (G91)",
                                      L[inc][1])
                if word in L:
                    raise state.error(f"G7x error: Cannot use {inc} and {word} in the same "
                                      "block", L[inc][1])
                end += along * L[inc][0]
            elif word in L:
                v = L[word][0]
                end = complex(end.real, v) if word == "X" else complex(v, end.imag)
        if incremental:
            end += self.at
        return end

    def _center(self, L: dict, end: complex, col: int) -> complex:
        """The arc's centre from I K (offsets from the start under G91.1) or R;
        ``col`` locates the arc's errors."""
        state = self.state
        start = self.at
        if "R" in L:
            if "I" in L or "K" in L:
                raise state.error("G7X error: both R and I or K flag used for arc", L["R"][1])
            r, rcol = L["R"]
            chord2 = abs(end - start) ** 2
            q = (r * r - chord2 / 4) / chord2
            if q < 0:
                if math.sqrt(chord2) / 2 - abs(r) > arc_tolerance(state):
                    raise state.error(f"arc radius R{fmt(r)} too small to reach the end point",
                                      rcol)
                q = 0.0
            d = 1j * math.sqrt(q) * (end - start)
            mid = (start + end) / 2.0
            return mid + d if self.mode == 30 else mid - d
        if "I" not in L and "K" not in L:
            raise state.error("G7X error: either I or K must be present for arc", col)
        center = complex(L["K"][0] if "K" in L else 0.0, L["I"][0] if "I" in L else 0.0)
        if state.arc_incremental:
            center += start
        _check_radii(state, start, center, end, min(L[w][1] for w in "IK" if w in L),
                     "contour arc")
        return center
