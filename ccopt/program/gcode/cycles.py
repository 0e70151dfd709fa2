"""Canned cycles G73, G74, G81-G87 and G89 with G98/G99, as LinuxCNC runs them
(``interp_cycles.cc``: ``convert_cycle``, ``convert_cycle_xy/_zx/_yz``,
``CYCLE_MACRO`` in ``interp_internal.hh`` and the ``convert_cycle_g8x``
bodies; ``convert_retract_mode`` in ``interp_convert.cc``).

A cycle line becomes the rapid, feed and dwell blocks LinuxCNC's canon
calls make, in order, each located at the cycle's line and marked with the
cycle (``Block.cycle``, e.g. ``"G81"``), so they are timed, verified and
exported like any move. Lengths are program units, P dwells seconds.

In the selected plane's axes ``(u, v, w)`` (:data:`~ccopt.program.model.PLANE_AXES`:
G17 X Y Z, G18 Z X Y, G19 Y Z X), with ``w`` the drilling axis:

* The **initial level** is ``w`` where a series of cycles starts; it holds
  until a motion that is not a cycle (``G0``-``G3``, ``G80``) ends the series.
* ``G98`` retracts to the initial level (or R when the initial level is below
  R), ``G99`` (the default) to R.
* Sticky: R, the ``w`` word, P (``G82 G84 G86 G89``; ``G74``/``G84`` take
  the last P, 0 at the start, when none is given), Q (``G73 G83``), I J K
  (``G87``) and F (the feed). A cycle code that is not the motion mode in
  force needs R and the ``w`` word again. L is **not** sticky: each line
  repeats ``L`` times (1 without L).
* Under ``G91`` the in-plane words are increments added at every repeat,
  R is measured from the initial level and the ``w`` word from R.

Refused, located, as LinuxCNC refuses them (its words): a cycle with cutter
compensation on, with ``G93``, with feed rate 0, without R or the ``w``
word, with R below the bottom, ``L0``, a negative L, ``G82``/``G86``/``G89``
without P, ``G73``/``G83`` without Q or with Q <= 0, ``G87`` without I, J,
K, ``G74``/``G84``/``G86``/``G87`` with the spindle not turning (the right
way for tapping), ``G98``/``G99`` with compensation on.
Not supported, said so: ``G88`` (the operator retracts the tool by hand at
its program stop: there is no path out of the hole to time).
``G74``/``G84`` outside G17 run as LinuxCNC runs them: its
``convert_cycle_g74_g84`` passes the axes permuted to ``cycle_feed`` in the
XZ and YZ planes (``interp_cycles.cc:324`` and ``:342``), so the feed goes to
a point off the hole (:func:`_tapping_point`); the reader notes it in
``Program.meta[NOTES]``, which the command line prints.

``G33.1`` rigid tapping (``convert_straight`` and canon ``RIGID_TAP``): a feed
to the end point and back to the start along the same line, synchronised to
the spindle at K (program units per revolution) times S (revolutions per
minute), both blocks marked ``"G33.1"``; refused with compensation on,
without K > 0, and with the spindle stopped or at S0 (nothing to time).
"""
from __future__ import annotations

from ccopt.program.gcode.coordinates import to_machine, to_work
from ccopt.program.gcode.polar import has_polar, turn
from ccopt.program.gcode.spindle import per_revolution
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import WHOLE_NUMBER_TOL, fmt, gname
from ccopt.program.model import NOTES, PLANE_AXES, Block, Motion, Source

#: ``G33.1`` (rigid tapping), in tenths.
RIGID_TAP = 331
#: Canned-cycle motion codes, in tenths.
CYCLE_CODES = frozenset({730, 740, 810, 820, 830, 840, 850, 860, 870, 880, 890})
#: Cycles whose P (dwell, seconds) is required when the cycle is not in force.
_P_REQUIRED = frozenset({820, 860, 880, 890})
#: Cycles taking P at all (G74/G84 dwell at the bottom when given).
P_CYCLES = frozenset({740, 820, 840, 860, 880, 890})
#: Peck cycles, taking Q (peck depth) and D (retract clearance).
PECK_CYCLES = frozenset({730, 830})
#: Cycles that need the spindle turning.
_SPINDLE = frozenset({740, 840, 860, 870, 880})
#: Retract distance of a G73 chip-break or above the last peck of G83 when no
#: D is given, per output unit: LinuxCNC's defaults (``rs274ngc_pre.cc``,
#: ``parameter_g73_peck_clearance``/``g83``: 0.050 on an inch machine, 1 on
#: a metric one).
PECK_CLEARANCE = {"mm": 1.0, "inch": 0.05}
_PLANE_NAME = {"XY": "xy", "ZX": "xz", "YZ": "yz"}
_LETTERS = "XYZ"


def set_retract_mode(state: GCodeState, code: tuple[int, int]) -> None:
    """``G98``/``G99`` (LinuxCNC ``convert_retract_mode``)."""
    if state.side != 0:
        raise state.error("Cannot change retract mode with cutter radius compensation on "
                          "(LinuxCNC refuses it): program G40 first", code[1])
    state.cycle.retract = "initial" if code[0] == 980 else "r"


def end_series(state: GCodeState) -> None:
    """A motion that is not a cycle ends a series: the next cycle takes a new
    initial level (LinuxCNC ``convert_motion`` clears ``cycle_il_flag``)."""
    state.cycle.level = None


class _Emitter:
    """Writes the cycle's canon moves as blocks, in work coordinates ``(u, v, w)``."""

    def __init__(self, state: GCodeState, code: int, src: Source, mcodes: tuple,
                 emit, feed: float, gcol: int):
        self.state = state
        self.gcol = gcol
        self.code = gname(code)
        self.src = src
        self.mcodes = mcodes
        self.emit = emit
        self.feed = feed
        self.axes = PLANE_AXES[state.plane]

    def machine(self, u: float, v: float, w: float) -> tuple[float, float, float]:
        """Machine coordinates of the plane point ``(u, v, w)`` (work coordinates)."""
        p = [0.0, 0.0, 0.0]
        for k, value in zip(self.axes, (u, v, w)):
            p[k] = value
        return to_machine(self.state, p)

    def _block(self, motion: Motion, end, **kw) -> None:
        cur = self.state.pos
        block = Block(self.src, motion, cur, end, self.state.modal(), mcodes=self.mcodes,
                      cycle=self.code, **kw)
        self.mcodes = ()
        self.emit(self.state, block)
        self.state.pos = end
        self.state.moved = True

    def traverse(self, u: float, v: float, w: float) -> None:
        self._block(Motion.RAPID, self.machine(u, v, w))

    def feed_to(self, u: float, v: float, w: float) -> None:
        end = self.machine(u, v, w)
        feed = self.feed
        if self.state.feed_mode == "per_revolution":
            feed = per_revolution(self.state, self.state.feed, self.state.pos, end, self.gcol)
        self._block(Motion.LINE, end, feed=feed)

    def dwell(self, seconds: float) -> None:
        self._block(Motion.DWELL, self.state.pos, dwell=seconds)


def run_cycle(state: GCodeState, code: int, gcol: int, L: dict, mcodes: tuple,
              first_col: int, previous_mode: int | None, emit) -> None:
    """Execute cycle ``code`` (tenths) of the line with words ``L`` (lengths in
    output units); ``previous_mode`` is the motion mode in force before the
    line; ``emit(state, block)`` records a block. ``gcol`` (0-based) locates
    the cycle's errors."""
    cs = state.cycle
    in_force = previous_mode == code
    r_word = _check_cycle(state, code, gcol, L, in_force)
    repeats = _repeats(state, L)
    iu, iv, iw = PLANE_AXES[state.plane]
    wl = _LETTERS[iw]
    plane = _PLANE_NAME[state.plane]
    if not in_force and wl not in L:
        raise state.error(f"{wl} value unspecified in {plane} plane canned cycle: "
                          f"{gname(code)} needs {wl} (the bottom)", gcol)
    w_word = L[wl][0] if wl in L else cs.w
    here = to_work(state, state.pos)
    cur_u, cur_v, cur_w = here[iu], here[iv], here[iw]
    if cs.level is None:
        cs.level = cur_w
    old = cs.level
    du = dv = 0.0
    if state.incremental:
        du = L[_LETTERS[iu]][0] if _LETTERS[iu] in L else 0.0
        dv = L[_LETTERS[iv]][0] if _LETTERS[iv] in L else 0.0
        r = r_word + old
        bottom = r + w_word
        u, v = cur_u, cur_v
    else:
        r = r_word
        bottom = w_word
        u = L[_LETTERS[iu]][0] if _LETTERS[iu] in L else cur_u
        v = L[_LETTERS[iv]][0] if _LETTERS[iv] in L else cur_v
    if r < bottom:
        raise state.error(f"R less than {wl.lower()} in cycle in {plane} plane: R "
                          f"{fmt(r)} is below the bottom {fmt(bottom)}", gcol)
    params = _parameters(state, code, L, in_force, gcol)
    src = Source(*state.where(state.line_no), first_col + 1)
    out = _Emitter(state, code, src, mcodes, emit, state.feed / 60.0, gcol)
    current = cur_w
    if old < r:
        # below the R plane: straight up to it first
        out.traverse(cur_u, cur_v, r)
        old = current = r
    clear = r if cs.retract == "r" else old
    polar = state.incremental and has_polar(L)
    for n in range(repeats):
        u, v = u + du, v + dv
        if polar:                        # G91 @ and ^ at every repeat (CYCLE_MACRO)
            u, v = turn(state, u, v, L, gcol)
        if n == 0 and current > r:
            out.traverse(u, v, current)
            out.traverse(u, v, r)
        else:
            out.traverse(u, v, clear)
            if clear > r:
                out.traverse(u, v, r)
        _body(out, code, u, v, r, clear, bottom, params)
        if code in (740, 840) and state.plane != "XY":
            # LinuxCNC's current point is the hole at the clear level; the
            # tool is at the permuted point its feed went to
            cs.tool_at = state.pos
            state.pos = out.machine(u, v, clear)
    cs.r = r_word
    cs.w = w_word
    if code in P_CYCLES:
        cs.p = params["p"]
    if code in PECK_CYCLES:
        cs.q = params["q"]


def _check_cycle(state: GCodeState, code: int, gcol: int, L: dict, in_force: bool) -> float:
    """LinuxCNC's checks before a cycle moves (``convert_cycle``); the R word
    (sticky when the cycle is in force)."""
    if code == 880:
        raise state.error("G88 is not supported: the operator retracts the tool by hand at "
                          "its program stop, so there is no path out of the hole to time; "
                          "write the moves out", gcol)
    if state.feed_mode == "inverse":
        raise state.error("Cannot use inverse time feed with canned cycles (LinuxCNC "
                          "refuses it): program G94 first", gcol)
    if not state.feed:
        raise state.error("Cannot feed with zero feed rate: give the cycle's F (units per "
                          "minute) on this or an earlier line", gcol)
    if state.side != 0:
        raise state.error("Cannot use canned cycles with cutter compensation on (LinuxCNC "
                          "refuses it, interp_cycles.cc:721): program G40 before the cycle",
                          gcol)
    if "R" in L:
        r_word = L["R"][0]
    elif in_force:
        r_word = state.cycle.r
    else:
        raise state.error(f"R clearance plane unspecified in cycle: {gname(code)} needs R "
                          "where it is not already the motion mode", gcol)
    if code in (740, 840) and state.plane != "XY":
        src = state.where(state.line_no)
        state.meta.setdefault(NOTES, []).append(
            f"{src[0]}:{src[1]}:{gcol + 1}: {gname(code)} in the "
            f"{_PLANE_NAME[state.plane].upper()} plane feeds off the hole, as LinuxCNC does: "
            "it passes the axes permuted to its feed there (interp_cycles.cc:324, :342); "
            "use G17 to tap along Z")
    return r_word


def _repeats(state: GCodeState, L: dict) -> int:
    """The L word: repeats of the cycle on this line (1 without L)."""
    if "L" not in L:
        return 1
    value, col = L["L"]
    if abs(value - round(value)) > WHOLE_NUMBER_TOL:
        raise state.error(f"L{fmt(value)}: the number of repeats must be a whole number", col)
    if value < 0:
        raise state.error("Negative l word used: L counts the repeats of the cycle", col)
    if round(value) == 0:
        raise state.error("Cannot do zero repeats of cycle (L0)", col)
    return int(round(value))


def _parameters(state: GCodeState, code: int, L: dict, in_force: bool, gcol: int) -> dict:
    """P, Q, D and I J K of the cycle, sticky values filled in, checked as
    LinuxCNC checks them before it moves."""
    cs = state.cycle
    params: dict = {}
    name = gname(code)
    if code in P_CYCLES:
        if "P" in L:
            params["p"] = L["P"][0]
            if params["p"] < 0:
                raise state.error(f"negative dwell time P{fmt(params['p'])}", L["P"][1])
        elif code in _P_REQUIRED and not in_force:
            raise state.error(f"Dwell time p word missing with {name.lower()}", gcol)
        else:
            params["p"] = cs.p
    if code in PECK_CYCLES:
        if "Q" in L:
            params["q"] = L["Q"][0]
        elif not in_force:
            raise state.error(f"Q word missing with {name.lower()}: give the peck depth", gcol)
        else:
            params["q"] = cs.q
        if params["q"] <= 0:
            raise state.error("Negative or zero q value used: the peck depth Q must be > 0",
                              L["Q"][1] if "Q" in L else gcol)
        params["d"] = L["D"][0] if "D" in L else PECK_CLEARANCE[state.out_units or "mm"]
    if code == 870:
        if not in_force:
            for w in "IJK":
                if w not in L:
                    raise state.error(f"{w} word missing with g87", gcol)
        ijk = tuple(L[w][0] if w in L else cs.ijk[k] for k, w in enumerate("IJK"))
        cs.ijk = ijk
        params["ijk"] = ijk
    if code in _SPINDLE:
        _check_spindle(state, code, gcol)
    return params


def _check_spindle(state: GCodeState, code: int, gcol: int) -> None:
    """LinuxCNC's ``check_g74_g84_spindle`` and the G86/G87 turning checks."""
    turning = state.spindle
    if code in (740, 840):
        if turning == "stopped":
            raise state.error(f"Spindle not turning in {gname(code)}: start it with "
                              f"{'M4' if code == 740 else 'M3'}", gcol)
        if code == 740 and turning == "cw":
            raise state.error("Spindle turning clockwise in G74 (left-hand tapping needs M4)",
                              gcol)
        if code == 840 and turning == "ccw":
            raise state.error("Spindle turning counterclockwise in G84 (right-hand tapping "
                              "needs M3)", gcol)
    elif turning == "stopped":
        raise state.error(f"Spindle not turning in {gname(code).lower()}: start it with M3 "
                          "or M4", gcol)


def _body(out: _Emitter, code: int, u: float, v: float, r: float, clear: float,
          bottom: float, params: dict) -> None:
    """The moves of one hole, from ``(u, v, r)`` (``convert_cycle_g8x``)."""
    if code == 810:
        out.feed_to(u, v, bottom)
        out.traverse(u, v, clear)
    elif code == 820:
        out.feed_to(u, v, bottom)
        out.dwell(params["p"])
        out.traverse(u, v, clear)
    elif code in PECK_CYCLES:
        delta, back = params["q"], params["d"]
        depth = r - delta
        while depth > bottom:
            out.feed_to(u, v, depth)
            if code == 830:
                out.traverse(u, v, r)
            out.traverse(u, v, depth + back)
            depth = depth - delta
        out.feed_to(u, v, bottom)
        out.traverse(u, v, clear)
    elif code in (740, 840):
        out.feed_to(*_tapping_point(out.state.plane, u, v, bottom))
        out.dwell(params["p"])
        out.feed_to(*_tapping_point(out.state.plane, u, v, clear))
    elif code == 850:
        out.feed_to(u, v, bottom)
        out.feed_to(u, v, r)
        out.traverse(u, v, clear)
    elif code == 860:
        out.feed_to(u, v, bottom)
        out.dwell(params["p"])
        out.traverse(u, v, clear)
    elif code == 870:
        i, j, k = params["ijk"]
        _back_bore(out, u, v, r, clear, bottom, i, j, k)
    elif code == 890:
        out.feed_to(u, v, bottom)
        out.dwell(params["p"])
        out.feed_to(u, v, clear)


def _tapping_point(plane: str, u: float, v: float, w: float) -> tuple[float, float, float]:
    """Where LinuxCNC's ``convert_cycle_g74_g84`` feeds for the hole ``(u, v)``
    at level ``w`` (plane coordinates ``(u, v, w)``): the point itself in G17;
    in G19 ``(w, u, v)`` and in G18 ``(v, w, u)``, its arguments to
    ``cycle_feed`` being permuted there (interp_cycles.cc:324, :342). So a
    G18/G19 tap feeds off the hole; the reader notes it
    (``Program.meta[NOTES]``)."""
    if plane == "YZ":
        return w, u, v
    if plane == "ZX":
        return v, w, u
    return u, v, w


def _back_bore(out: _Emitter, u: float, v: float, r: float, clear: float, bottom: float,
               i: float, j: float, k: float) -> None:
    """G87: in through the hole off-centre by the in-plane pair of I J K, bore
    up to the third (``convert_cycle_g87``; under G91 it is measured from the
    bottom)."""
    plane_ij = {(0, 1, 2): (i, j, k), (2, 0, 1): (k, i, j), (1, 2, 0): (j, k, i)}
    du, dv, top = plane_ij[out.axes]
    if out.state.incremental:
        top = bottom + top
    ou, ov = u + du, v + dv
    out.traverse(ou, ov, r)
    out.traverse(ou, ov, bottom)
    out.traverse(u, v, bottom)
    out.feed_to(u, v, top)
    out.feed_to(u, v, bottom)
    out.traverse(ou, ov, bottom)
    out.traverse(ou, ov, clear)
    out.traverse(u, v, clear)


def rigid_tap(state: GCodeState, L: dict, mcodes: tuple, src: Source, gcol: int, end,
              emit) -> None:
    """``G33.1 ... K``: the feed to ``end`` (machine coordinates) and back to where
    it started, at ``K * S`` per minute (the module docstring)."""
    if state.side != 0:
        raise state.error("G33.1 with cutter radius compensation on: turn it off with G40 "
                          "first", gcol)
    if "K" not in L or not L["K"][0] > 0:
        raise state.error("G33.1 needs the thread pitch K > 0 (units per revolution)",
                          L["K"][1] if "K" in L else gcol)
    if state.spindle == "stopped" or not state.spindle_speed > 0:
        raise state.error("G33.1 with the spindle not turning: start it with S and M3 (or "
                          "M4) first", gcol)
    feed = per_revolution(state, L["K"][0], state.pos, end, gcol)
    start = state.pos
    for a, b in ((start, end), (end, start)):
        emit(state, Block(src, Motion.LINE, a, b, state.modal(), feed=feed, mcodes=mcodes,
                          cycle="G33.1", per_revolution=L["K"][0]))
        mcodes = ()
    state.moved = True
