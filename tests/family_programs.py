"""Generated plates entered and left by the controllers' own lead moves (issue 32).

The part, the entry and exit points, the cut direction, the tool radius and
the written decimals are those of :func:`cam_programs.cam_program` for the
same seed; the leads are the ones an operator or a CAM post writes for a
SINUMERIK 840D or a HEIDENHAIN TNC, drawn from the seed:

- SINUMERIK: smooth approach ``G41``/``G42`` with ``G147`` (a straight line
  along the first element's tangent, only where the part leaves room: see
  below), ``G247`` (a quarter circle) or ``G347`` (a half circle), ``DISR``
  and ``G340``; the retraction ``G40`` with ``G148``/``G248``/``G348`` to the
  start point; or none (``G41`` on a straight move, as CAM writes it);
- HEIDENHAIN: ``APPR LN`` (perpendicular), ``APPR CT`` (a tangent arc of
  ``CCA90``), ``APPR LCT`` (a straight line and a tangent arc) and ``APPR LT``
  (along the tangent, same room rule), and ``DEP LN``, ``DEP CT``, ``DEP LCT``
  to the start point and ``DEP LT``.

Placement, from the construction: the start point lies on the tool side of
the entry, beyond every lead's reach (the lead's size plus the radius plus
the straight lead length ``ell`` the generator drew). A lead along the
tangent (``G147``, ``APPR LT``, ``DEP LT``) runs over the part's own edge
when the entry is mid-edge: it is drawn only where that edge is straight
for the lead's whole length plus the radius (on the exit, likewise past the
exit along the last edge's extension, which at a sharp convex corner or
mid-edge stays in the air beside the part only when the edge before it, for
the entry, or after it, for the exit, is that straight edge itself: so
these leads are drawn at mid-edge entries only).
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass

import numpy as np

from cam_programs import _fmt, _signed, cam_program

SINUMERIK_IN = ("G147", "G247", "G347", "none")
SINUMERIK_OUT = ("G148", "G248", "G348", "none")
HEIDENHAIN_IN = ("LN", "CT", "LCT", "LT")
HEIDENHAIN_OUT = ("LN", "CT", "LCT", "LT")


@dataclass
class FamilyProgram:
    """A generated plate: ``text`` in ``dialect`` (``sinumerik`` or
    ``heidenhain``), cutter radius ``radius`` (mm), the program lines of the
    part contour ``contour_lines`` (first, last), the leads drawn."""

    seed: int
    dialect: str
    text: str
    radius: float
    decimals: int
    contour_lines: tuple[int, int]
    lead_in: str
    lead_out: str
    description: str

    @property
    def file(self) -> str:
        return f"family-{self.seed}.{'mpf' if self.dialect == 'sinumerik' else 'h'}"


def _room_along(cp, at_entry: bool) -> float:
    """How far the straight edge through the entry (behind it) or the exit
    (beyond it) runs: the length of the contour line that ends at the entry
    (mid-edge entries: the loop's last move) or begins at the exit; 0 when
    the entry is a corner or the move is an arc."""
    moves = cp.contour_moves
    if "mid-edge" not in cp.description:
        return 0.0
    if at_entry:
        kind, p, _, _ = moves[-1] if "overlap 0," in cp.description else moves[-2]
        prev = moves[-2][1] if "overlap 0," in cp.description else moves[-3][1]
        return math.dist(prev, cp.entry) if kind == "line" else 0.0
    kind, p, _, _ = moves[0]
    return math.dist(cp.exit, p) if kind == "line" else 0.0


def family_program(seed: int, dialect: str) -> FamilyProgram:
    """The plate of ``seed`` in ``dialect``, with the leads drawn from the seed."""
    cp = cam_program(seed, dialect=dialect)
    rng = random.Random(seed * 7919 + (1 if dialect == "sinumerik" else 2))
    r, rho, ell, dec = cp.radius, cp.rho, cp.ell, cp.decimals
    E, X = np.asarray(cp.entry, float), np.asarray(cp.exit, float)
    t_in, n_in, t_x, n_x = cp.t_in, cp.n_in, cp.t_x, cp.n_x
    ins = SINUMERIK_IN if dialect == "sinumerik" else HEIDENHAIN_IN
    outs = SINUMERIK_OUT if dialect == "sinumerik" else HEIDENHAIN_OUT
    straight_in = ins[0] if dialect == "sinumerik" else "LT"
    straight_out = outs[0] if dialect == "sinumerik" else "LT"
    lead_in = rng.choice(ins)
    if lead_in == straight_in and _room_along(cp, True) < 1.5 * (ell + r):
        lead_in = rng.choice([k for k in ins if k != straight_in])
    lead_out = rng.choice(outs)
    if lead_out == straight_out and _room_along(cp, False) < 1.5 * (ell + r):
        lead_out = rng.choice([k for k in outs if k != straight_out])
    # the start point: on the tool side of the entry, beyond every lead's reach
    start = E + (r + 2.0 * rho + 2.0 * ell) * n_in - rho * t_in
    end = X + (r + 2.0 * rho + 2.0 * ell) * n_x + rho * t_x
    writer = _sinumerik if dialect == "sinumerik" else _heidenhain
    text, first, last = writer(cp, start, end, lead_in, lead_out, r, rho, ell, dec)
    desc = (f"{cp.description}; {dialect} leads {lead_in} / {lead_out}, rho {rho:.3g}, "
            f"ell {ell:.3g}")
    return FamilyProgram(seed, dialect, text, r, dec, (first, last), lead_in, lead_out, desc)


def _contour_lines(cp, f, out: list[str], dialect: str) -> tuple[int, int]:
    """Append the contour moves (the entry is the current point) and the
    overlap past the entry if any; the first and last lines of the closed
    contour (the overlap cuts the first edge again: not part of it)."""
    cur = np.asarray(cp.entry, float)
    first = None
    loop_end = len(cp.contour_moves) - (0 if "overlap 0," in cp.description else 1)
    last = None
    for i, (kind, p, c, ccw) in enumerate(cp.contour_moves):
        if i == loop_end:
            last = len(out)
        xy = f"X{f(p[0])} Y{f(p[1])}"
        if dialect == "sinumerik":
            if kind == "line":
                out.append(f"G1 {xy}")
            else:
                out.append(f"{'G3' if ccw else 'G2'} {xy} I={f(c[0] - cur[0])} "
                           f"J={f(c[1] - cur[1])}")
        else:
            if kind == "line":
                out.append(f"L {xy}")
            else:
                out.append(f"CC X{f(c[0])} Y{f(c[1])}")
                out.append(f"C {xy} {'DR+' if ccw else 'DR-'}")
        first = len(out) if first is None else first
        cur = np.asarray(p, float)
    return first, len(out) if last is None else last


def _sinumerik(cp, start, end, lead_in, lead_out, r, rho, ell, dec):
    f = lambda x: _fmt(x, dec)              # noqa: E731
    g4x = "G41" if cp.side > 0 else "G42"
    E = cp.entry
    out = [f"; seed {cp.seed}", f"$TC_DP6[1,1]={f(r)}", "G17 G71 G90 T1 D1 M6", "S8000 M3",
           f"G0 X{f(start[0])} Y{f(start[1])} Z5", "G1 Z-2 F1000"]
    if lead_in == "none":
        out.append(f"{g4x} G1 X{f(E[0])} Y{f(E[1])} F600")
    else:
        out.append(f"{g4x} {lead_in} G340 DISR={f(rho)} X{f(E[0])} Y{f(E[1])} F600")
    first, last = _contour_lines(cp, f, out, "sinumerik")
    if lead_out == "none":
        out.append(f"G40 G1 X{f(end[0])} Y{f(end[1])}")
    else:
        out.append(f"G40 {lead_out} G340 DISR={f(rho)} X{f(end[0])} Y{f(end[1])}")
    out += ["G0 Z5", "M30"]
    return "\n".join(out) + "\n", first, last


def _heidenhain(cp, start, end, lead_in, lead_out, r, rho, ell, dec):
    f = lambda x: _signed(x, dec)           # noqa: E731
    rl = "RL" if cp.side > 0 else "RR"
    E = cp.entry
    out = ["BEGIN PGM PLATE MM", f"; seed {cp.seed}", f"TOOL DEF 1 L+0 R{f(r)}",
           "TOOL CALL 1 Z S5000", "L Z+5 R0 FMAX",
           f"L X{f(start[0])} Y{f(start[1])} R0 FMAX M3", "L Z-2 R0 F1000"]
    xy = f"X{f(E[0])} Y{f(E[1])}"
    if lead_in == "LN" or lead_in == "LT":
        out.append(f"APPR {lead_in} {xy} LEN{f(ell)} {rl} F600")
    elif lead_in == "CT":
        out.append(f"APPR CT {xy} CCA90 R{f(rho)} {rl} F600")
    else:
        out.append(f"APPR LCT {xy} R{f(rho)} {rl} F600")
    first, last = _contour_lines(cp, f, out, "heidenhain")
    if lead_out in ("LN", "LT"):
        out.append(f"DEP {lead_out} LEN{f(ell)} F800")
        out.append(f"L X{f(end[0])} Y{f(end[1])} R0 FMAX")
    elif lead_out == "CT":
        out.append(f"DEP CT CCA90 R{f(rho)} F800")
        out.append(f"L X{f(end[0])} Y{f(end[1])} R0 FMAX")
    else:
        out.append(f"DEP LCT X{f(end[0])} Y{f(end[1])} R{f(rho)} F800")
    out += ["L Z+5 R0 FMAX", "END PGM PLATE MM"]
    return "\n".join(out) + "\n", first, last
