"""``G76``, LinuxCNC's multi-pass lathe threading cycle (``interp_convert.cc``:
``convert_threading_cycle`` and ``threading_pass``).

The cycle starts at the current point (the *drive line*'s start, X the
radius, Z along the spindle) and cuts towards the line's ``Z`` end:

* ``P`` thread pitch (program units per revolution), ``I`` offset of the
  thread crests from the drive line (negative for an outside thread, positive
  for a bore: ``boring``), ``J`` first cut depth (> 0), ``K`` full thread
  depth (> ``J``), ``R`` depth degression (>= 1; pass ``n`` cuts to
  ``|I| + J * n**(1/R)``), ``Q`` compound angle (degrees; the infeed follows
  the thread flank), ``H`` spring passes at full depth, ``E`` taper length
  along the drive line, ``L`` which ends taper (1 start, 2 end, 3 both).
  Lengths are program units; under ``G7`` I, J and K are diameters, halved.
* Each pass: a rapid back to the retract depth, in to the cut depth (fed
  along the taper when the start tapers), the cut along Z (fed; then out
  along the end taper), a rapid out; finally a rapid to the line's end point.

Feeds are synchronised to the spindle: ``pitch * rpm / 60`` units per
second along a straight cut (rpm: S, or under ``G96`` the speed at the
cut's radius, spindle.py), and along a taper the pitch scaled by its length
per unit of Z (LinuxCNC's ``taper_pitch``), so Z always advances one pitch
per revolution. Every block is marked ``"G76"`` (``Block.cycle``).

Refused, located, as LinuxCNC refuses them: compensation on, I 0, J <= 0,
K <= J, P or I J K missing, the spindle not turning, rotary or U V W words;
and (ccopt) S0, with which no cut can be timed.
"""
from __future__ import annotations

import math

from ccopt.program.gcode.coordinates import to_machine, to_work
from ccopt.program.gcode.spindle import per_revolution
from ccopt.program.gcode.state import GCodeState
from ccopt.program.gcode.words import fmt
from ccopt.program.model import Block, Motion, Source

#: ``G76`` in tenths.
THREADING = 760
#: Most passes a ``G76`` may cut below its full depth before ccopt refuses it
#: (LinuxCNC has no bound; reading stays bounded in time and memory).
MAX_PASSES = 10_000
#: Words of a rotary or parallel axis, which ``G76`` may not move.
_OTHER_AXES = "ABCUVW"


def threading_cycle(state: GCodeState, L: dict, mcodes: tuple, src: Source, gcol: int,
                    end, emit) -> None:
    """Run ``G76`` from the current point to ``end`` (machine coordinates of the
    line's end point); ``L`` the line's words in output units (X already
    halved under ``G7``); ``emit(state, block)`` records a block."""
    _check(state, L, gcol)
    i, j, k = (L[w][0] for w in "IJK")
    if state.diameter_mode:
        i, j, k = i / 2.0, j / 2.0, k / 2.0
    x0, y0, z0 = to_work(state, state.pos)
    end_w = to_work(state, end)
    boring = i > 0.0
    full_dia_depth = abs(i)
    cut_increment = abs(j)
    full_height = abs(k)
    end_depth = full_height + full_dia_depth
    pitch = L["P"][0]
    angle = L["Q"][0] if "Q" in L else 0.0
    angle = math.radians(0.0 if angle == -1 else angle)
    if end_w[2] > z0:
        angle = -angle
    springs = int(L["H"][0]) if "H" in L else 0
    degression = L["R"][0] if "R" in L else 1.0
    degression = max(degression, 1.0)
    taper = max(L["E"][0], 0.0) if "E" in L else 0.0
    taper_pitch = pitch * math.hypot(taper, full_height) / taper if taper > 0.0 else pitch
    if end_w[2] > z0:
        taper = -taper
    flags = max(int(L["L"][0]), 0) if "L" in L else 0
    target_z = end_w[2] + full_height * math.tan(angle)
    out = _Passes(state, src, mcodes, emit, boring, x0, y0, z0, end_depth, full_height,
                  target_z, taper, bool(flags & 1), bool(flags & 2), pitch, taper_pitch, gcol)
    # passes below full depth: n >= 1 with J * n**(1/R) < K, n < (K/J)**R
    passes = (full_height / cut_increment) ** degression
    if passes > MAX_PASSES:
        raise state.error(f"G76 would cut about {passes:.3g} passes (J {fmt(cut_increment)}, "
                          f"K {fmt(full_height)}, R {fmt(degression)}: (K/J)**R), more than "
                          f"{MAX_PASSES}, ccopt's bound (LinuxCNC has none)", gcol)
    depth, n = full_dia_depth + cut_increment, 1
    while depth < end_depth:
        out.cut(depth, (depth - full_dia_depth) * math.tan(angle))
        n += 1
        depth = full_dia_depth + cut_increment * n ** (1.0 / degression)
    zoff = (end_depth - full_dia_depth) * math.tan(angle)
    for _ in range(springs + 1):         # at full depth at least once, then the spring cuts
        out.cut(end_depth, zoff)
    out.rapid(*end_w)
    state.moved = True


def _check(state: GCodeState, L: dict, gcol: int) -> None:
    """LinuxCNC's refusals of a ``G76`` line (``check_other_codes``,
    ``convert_straight``, ``convert_threading_cycle``)."""
    if "P" not in L:
        raise state.error("P word missing with G76: P is the thread pitch (units per "
                          "revolution)", gcol)
    if not all(w in L for w in "IJK"):
        raise state.error("I J or K words missing with G76", gcol)
    other = next((a for a in _OTHER_AXES if a in L), None)
    if other is not None:
        raise state.error("Cannot move rotary axes with G76", L[other][1])
    if state.spindle == "stopped":
        raise state.error("Chosen spindle (0) not turning in G76: start it with S and M3 "
                          "(or M4) first", gcol)
    if not state.spindle_speed > 0:
        raise state.error("G76 with spindle speed S0: the cut is synchronised to the "
                          "spindle, so give S > 0 first", gcol)
    if state.side != 0:
        raise state.error("Cannot use G76 threading cycle with cutter radius compensation on",
                          gcol)
    if L["I"][0] == 0:
        raise state.error("In G76, I must not be 0", L["I"][1])
    if not L["J"][0] > 0:
        raise state.error("In G76, J must be greater than 0", L["J"][1])
    if not L["K"][0] > L["J"][0]:
        raise state.error("In G76, K must be greater than J", L["K"][1])


class _Passes:
    """The moves of the threading passes (``threading_pass``), in work
    coordinates; X measured from the drive line's ``safe_x`` inwards (outside
    threads) or outwards (``boring``)."""

    def __init__(self, state: GCodeState, src: Source, mcodes: tuple, emit, boring: bool,
                 safe_x: float, y: float, start_z: float, end_depth: float,
                 full_height: float, target_z: float, taper: float, entry_taper: bool,
                 exit_taper: bool, pitch: float, taper_pitch: float, gcol: int):
        self.state, self.src, self.mcodes, self.emit = state, src, mcodes, emit
        self.sign = 1.0 if boring else -1.0
        self.safe_x, self.y, self.start_z = safe_x, y, start_z
        self.end_depth, self.full_height, self.target_z = end_depth, full_height, target_z
        self.taper, self.entry_taper, self.exit_taper = taper, entry_taper, exit_taper
        self.pitch, self.taper_pitch, self.gcol = pitch, taper_pitch, gcol

    def _x(self, depth: float) -> float:
        return self.safe_x + self.sign * depth

    def _block(self, motion: Motion, x: float, y: float, z: float, feed=None,
               per_rev=None) -> None:
        end = to_machine(self.state, (x, y, z))
        self.emit(self.state, Block(self.src, motion, self.state.pos, end, self.state.modal(),
                                    feed=feed, mcodes=self.mcodes, cycle="G76",
                                    per_revolution=per_rev))
        self.mcodes = ()
        self.state.pos = end

    def rapid(self, x: float, y: float, z: float) -> None:
        self._block(Motion.RAPID, x, y, z)

    def _fed(self, x: float, z: float, per_rev: float) -> None:
        """A cut to ``(x, z)`` at ``per_rev`` units per spindle revolution."""
        end = to_machine(self.state, (x, self.y, z))
        feed = per_revolution(self.state, per_rev, self.state.pos, end, self.gcol)
        self._block(Motion.LINE, x, self.y, z, feed, per_rev)

    def cut(self, depth: float, zoff: float) -> None:
        """One pass at ``depth`` (from the drive line), the start shifted by
        ``zoff`` along Z (the compound angle)."""
        z_in, z_out = self.start_z - zoff, self.target_z - zoff
        back = self._x(depth - self.end_depth)
        self.rapid(back, self.y, z_in)
        if self.taper and self.entry_taper:
            self._fed(self._x(depth - self.full_height), z_in, self.taper_pitch)
            self._fed(self._x(depth), z_in - self.taper, self.taper_pitch)
        else:
            self.rapid(self._x(depth), self.y, z_in)
        if self.taper and self.exit_taper:
            self._fed(self._x(depth), z_out + self.taper, self.pitch)
            self._fed(self._x(depth - self.full_height), z_out, self.taper_pitch)
        else:
            self._fed(self._x(depth), z_out, self.pitch)
        self.rapid(back, self.y, z_out)
