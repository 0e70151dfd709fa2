"""The SINUMERIK drilling cycles ``CYCLE81`` and ``CYCLE82``, called once or
modally with ``MCALL`` (Programming Guide Cycles 6FC5298-6AB40, 2.1.2
"Drilling, centering - CYCLE81" and 2.1.3 "Drilling, counterboring -
CYCLE82"; Programming Manual Fundamentals, "Modal subprogram call (MCALL)").

``CYCLE81(RTP, RFP, SDIS, DP, DPR)`` at the position reached before the
call, along the plane's normal (``G17``: Z): rapid to the reference plane
brought forward by the safety clearance, ``RFP + SDIS``; feed (the ``F`` in
force) to the final depth, ``DP``, or ``RFP - DPR`` when ``DPR`` is written
(the guide: "If a value is entered both for DP and DPR, the final drilling
depth is derived from DPR"); rapid to the retraction plane ``RTP``.
``CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB)`` dwells ``DTB`` seconds at the
depth before retracting. Every value is absolute in the work frame
(``SDIS``, ``DPR`` without sign), program units (a cycle after a change of
``G70``/``G71`` is refused, like the circle forms); an argument left empty
is 0. The later parameters of newer controls (``GMODE``, ``_DMODE``,
``_AMODE``) are read when empty or 0 (their default) and refused otherwise.
The cycle keeps the calling program's modes: its motion mode is the one in
force before it.

``MCALL CYCLE8x(..)`` runs the cycle after every later block that moves,
until ``MCALL`` alone. The moves are tagged with the cycle's name
(:attr:`~ccopt.program.model.Block.cycle`). Other cycles (``CYCLE83``
deep-hole drilling, ``CYCLE84`` tapping, pockets, ...) are refused where
they are called, as is a cycle with compensation on.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from ccopt.program.expr import ExprError
from ccopt.program.gcode.codes import Words
from ccopt.program.gcode.coordinates import to_work
from ccopt.program.gcode.execute import execute_words
from ccopt.program.gcode.units import input_factor
from ccopt.program.model import PLANE_AXES
from ccopt.program.sinumerik.lexer import skip_blanks

#: The cycles read: name -> its parameters (after which only empty or 0 may follow).
DRILLING = {"CYCLE81": ("RTP", "RFP", "SDIS", "DP", "DPR"),
            "CYCLE82": ("RTP", "RFP", "SDIS", "DP", "DPR", "DTB")}
#: Parameters newer controls append, read at their default (empty or 0) only.
LATER = ("GMODE", "_DMODE", "_AMODE")


@dataclass(frozen=True)
class DrillingCall:
    """A drilling cycle as called: ``name``, its values by parameter name
    (``None``: left empty), ``col`` where the name stands."""

    name: str
    values: dict
    col: int


def is_cycle(name: str) -> bool:
    """A name of the standard cycles (``CYCLE`` and digits)."""
    return name.startswith("CYCLE") and name[5:].isdigit()


def read_call(run, name: str, code: str, p: int, col: int) -> tuple[DrillingCall, int]:
    """The call ``name(args)`` at ``p`` (at the ``(``): its values and the
    position after it. Cycles ccopt does not read are refused here."""
    if name not in DRILLING:
        raise ExprError(f"{name}: ccopt reads the drilling cycles CYCLE81 and CYCLE82 (as "
                        "moves); other cycles are not read: program their moves", col)
    args, end = _arguments(run, code, p)
    params = DRILLING[name]
    if len(args) > len(params) + len(LATER):
        raise ExprError(f"{name} takes at most {len(params) + len(LATER)} values", col)
    for extra, value in zip(LATER, args[len(params):]):
        if value not in (None, 0.0):
            raise ExprError(f"{name}: {extra}={value:g} is not read by ccopt (only its "
                            "default, empty or 0)", col)
    values = dict(zip(params, args + [None] * (len(params) - len(args))))
    return DrillingCall(name, values, col), end


def _arguments(run, code: str, p: int) -> tuple[list, int]:
    """``(a, , b)``: the values (``None`` where empty) and the position after ``)``."""
    p = skip_blanks(code, p)
    if p >= len(code) or code[p] != "(":
        raise ExprError("a cycle is called with its values in parentheses: CYCLE81(10, 0, "
                        "2, -5)", p)
    p, args = p + 1, []
    while True:
        p = skip_blanks(code, p)
        if p < len(code) and code[p] in ",)":
            args.append(None)
        else:
            value, p = run.variables.evaluate(code, p)
            args.append(value)
            p = skip_blanks(code, p)
        if p >= len(code) or code[p] not in ",)":
            raise ExprError("expected ',' or ')' in the cycle's values", p)
        if code[p] == ")":
            if args == [None]:
                args = []
            return args, p + 1
        p += 1


def run_cycle(run, call: DrillingCall) -> None:
    """The moves of ``call`` at the current position, tagged with its name;
    the motion mode in force before is kept."""
    state = run.state
    if state.side != 0:
        raise ExprError(f"{call.name} with tool radius compensation on: program G40 before "
                        "the drilling cycle", call.col)
    if input_factor(state) != 1.0:
        raise ExprError(f"{call.name} in other units than the program's first (G70/G71 "
                        "changed): not read by ccopt", call.col)
    v = {k: (0.0 if x is None else x) for k, x in call.values.items()}
    rtp, rfp, sdis = v["RTP"], v["RFP"], abs(v["SDIS"])
    dpr = call.values["DPR"]
    depth = rfp - abs(dpr) if dpr not in (None, 0.0) else v["DP"]
    start = rfp + sdis
    if not depth < start or rtp < start:
        raise ExprError(f"{call.name}: the depth {depth:g} must lie below RFP + SDIS = "
                        f"{start:g}, and the retraction plane RTP {rtp:g} not below it",
                        call.col)
    first = len(state.blocks)
    motion, col = state.motion_mode, call.col
    _move(state, 0, start, col)
    _move(state, 10, depth, col)
    if call.name == "CYCLE82" and v["DTB"] > 0.0:
        execute_words(state, Words(g=[(4.0, col)], m=[], letters={"P": (v["DTB"], col)},
                                   first=col))
    elif call.name == "CYCLE82" and v["DTB"] < 0.0:
        raise ExprError(f"{call.name}: DTB is a dwell in seconds (>= 0)", col)
    _move(state, 0, rtp, col)
    state.motion_mode = motion
    state.blocks[first:] = [replace(b, cycle=call.name) for b in state.blocks[first:]]


def _move(state, motion: int, w_value: float, col: int) -> None:
    """``G0``/``G1`` (``motion`` in tenths) along the plane's normal to the
    work coordinate ``w_value``, in the distance mode in force."""
    k = PLANE_AXES[state.plane][2]
    value = w_value - to_work(state, state.pos)[k] if state.incremental else w_value
    execute_words(state, Words(g=[(motion / 10.0, col)], m=[],
                               letters={"XYZ"[k]: (value, col)}, first=col))
