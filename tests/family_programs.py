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
    if cp.at_corner:
        return 0.0
    if at_entry:
        last = -2 if cp.overlap else -1           # the loop's last move, before any overlap
        kind, p, _, _ = moves[last]
        prev = moves[last - 1][1]
        return math.dist(prev, cp.entry) if kind == "line" else 0.0
    kind, p, _, _ = moves[0]
    return math.dist(cp.exit, p) if kind == "line" else 0.0


def family_program(seed: int, dialect: str, arc_forms: bool = False) -> FamilyProgram:
    """The plate of ``seed`` in ``dialect``, with the leads drawn from the seed;
    ``arc_forms``: each arc in a form drawn from :data:`ARC_FORMS` (else as
    CAM posts write them: ``I= J=``, ``CC`` + ``C``), and on SINUMERIK the
    smooth approach's direction word (none, ``G140``, ``G143``, the side's
    ``G141``/``G142``) and infeed (``G340`` in the plane at depth; ``G340``
    or ``G341`` with ``DISCL`` from above, ``G341`` with ``FAD``, the
    retraction back up) drawn as well."""
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
    forms = random.Random(seed * 104729 + 7) if arc_forms else None
    text, first, last = writer(cp, start, end, lead_in, lead_out, r, rho, ell, dec, forms)
    desc = (f"{cp.description}; {dialect} leads {lead_in} / {lead_out}, rho {rho:.3g}, "
            f"ell {ell:.3g}")
    return FamilyProgram(seed, dialect, text, r, dec, (first, last), lead_in, lead_out, desc)


def _contour_lines(cp, f, out: list[str], dialect: str, forms=None) -> tuple[int, int]:
    """Append the contour moves (the entry is the current point) and the
    overlap past the entry if any; the first and last lines of the closed
    contour (the overlap cuts the first edge again: not part of it).
    ``forms``: a random source drawing each arc's form (:data:`ARC_FORMS`),
    else every arc in the first."""
    cur = np.asarray(cp.entry, float)
    first = None
    loop_end = len(cp.contour_moves) - (1 if cp.overlap else 0)
    last = None
    for i, (kind, p, c, ccw) in enumerate(cp.contour_moves):
        if i == loop_end:
            last = len(out)
        if kind == "line":
            out.append(f"{'G1' if dialect == 'sinumerik' else 'L'} X{f(p[0])} Y{f(p[1])}")
        else:
            form = forms.choice(ARC_FORMS[dialect]) if forms else ARC_FORMS[dialect][0]
            out.extend(_arc(dialect, form, f, cur, np.asarray(p, float),
                            np.asarray(c, float), ccw))
        first = len(out) if first is None else first
        cur = np.asarray(p, float)
    return first, len(out) if last is None else last


#: The ways each dialect's programs write an arc (the first: as CAM posts do).
ARC_FORMS = {"sinumerik": ("IJ", "CR", "CIP", "AC"), "heidenhain": ("CC+C", "CR", "CP")}


def _arc(dialect: str, form: str, f, a, b, c, ccw: bool) -> list[str]:
    """The lines of the arc from ``a`` to ``b`` about ``c`` (counter-clockwise
    if ``ccw``) in ``form``: SINUMERIK ``I= J=`` (incremental centre), ``CR=``
    (radius, negative over half a turn), ``CIP`` through its middle point
    (``I1= J1=``, absolute), ``I=AC() J=AC()`` (absolute centre); HEIDENHAIN
    ``CC`` + ``C``, ``CR ... R DR`` and ``CC`` + ``CP IPA DR`` (the polar
    sweep in degrees, 4 decimals)."""
    r = float(np.hypot(*(a - c)))
    t0, t1 = math.atan2(*(a - c)[::-1]), math.atan2(*(b - c)[::-1])
    sweep = (t1 - t0) % (2 * math.pi) if ccw else -((t0 - t1) % (2 * math.pi))
    xy = f"X{f(b[0])} Y{f(b[1])}"
    big = abs(sweep) > math.pi
    if dialect == "sinumerik":
        g = "G3" if ccw else "G2"
        if form == "IJ":
            return [f"{g} {xy} I={f(c[0] - a[0])} J={f(c[1] - a[1])}"]
        if form == "CR":
            return [f"{g} {xy} CR={'-' if big else ''}{f(r).lstrip('+')}"]
        if form == "AC":
            return [f"{g} {xy} I=AC({f(c[0])}) J=AC({f(c[1])})"]
        m = c + r * np.array([math.cos(t0 + sweep / 2), math.sin(t0 + sweep / 2)])
        return [f"CIP {xy} I1={f(m[0])} J1={f(m[1])}"]
    dr = "DR+" if ccw else "DR-"
    if form == "CR":
        return [f"CR {xy} R{'-' if big else '+'}{f(r).lstrip('+')} {dr}"]
    centre = f"CC X{f(c[0])} Y{f(c[1])}"
    if form == "CP":
        deg = f"{math.degrees(sweep):+.4f}"
        return [centre, f"CP IPA{deg} {dr}"]
    return [centre, f"C {xy} {dr}"]


def _sinumerik(cp, start, end, lead_in, lead_out, r, rho, ell, dec, forms=None):
    f = lambda x: _fmt(x, dec)              # noqa: E731
    g4x = "G41" if cp.side > 0 else "G42"
    E = cp.entry
    # with forms: the approach's direction word and infeed drawn too (the
    # tool then stays up and the smooth approach and retraction move in Z)
    side_word = "G141" if cp.side > 0 else "G142"     # the tool's side, as G140 takes it
    way = forms.choice(("", "G140", "G143", side_word)) if forms else ""
    infeed = forms.choice(("plane", "space", "G341")) if forms else "plane"
    smooth = lead_in != "none" or lead_out != "none"
    up = infeed != "plane" and smooth
    disc = f" DISCL={f(rho / 2)}" if up else ""
    words = {"plane": "G340", "space": "G340", "G341": "G341"}[infeed] + disc
    fad = " FAD=300" if infeed == "G341" and smooth else ""
    out = [f"; seed {cp.seed}", f"$TC_DP6[1,1]={f(r)}", "G17 G71 G90 T1 D1 M6", "S8000 M3",
           f"G0 X{f(start[0])} Y{f(start[1])} Z5"]
    out += [] if up else ["G1 Z-2 F1000"]
    z = " Z-2" if up else ""
    if lead_in == "none":
        out += ["G1 Z-2 F1000"] if up else []
        out.append(f"{g4x} G1 X{f(E[0])} Y{f(E[1])} F600")
    else:
        out.append(f"{g4x} {lead_in} {way + ' ' if way else ''}{words} DISR={f(rho)}{fad} "
                   f"X{f(E[0])} Y{f(E[1])}{z} F600")
    first, last = _contour_lines(cp, f, out, "sinumerik", forms)
    if lead_out == "none":
        out.append(f"G40 G1 X{f(end[0])} Y{f(end[1])}")
    else:
        out.append(f"G40 {lead_out} {words} DISR={f(rho)} X{f(end[0])} Y{f(end[1])}"
                   f"{' Z5' if up else ''}")
    out += ["G0 Z5", "M30"]
    return "\n".join(out) + "\n", first, last


def _heidenhain(cp, start, end, lead_in, lead_out, r, rho, ell, dec, forms=None):
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
    first, last = _contour_lines(cp, f, out, "heidenhain", forms)
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
