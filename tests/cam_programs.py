"""A generator of the profile programs CAM systems write (issue 29).

One outside profile of a plate per program, drawn from a seed:

- the part: a rectangle or a star-shaped polygon (3-9 vertices), its convex
  corners each sharp or filleted by a tangent arc, its concave ones sharp;
- the entry: in the middle of a straight edge, or on a sharp convex corner;
- the lead-in: a straight approach plus a quarter tangent arc, a line
  perpendicular to the contour, or (from a corner) a line along the first
  edge's extension; compensation comes on over the straight approach;
- the lead-out, independently: a tangent arc plus a straight retreat (from a
  corner, the arc may end exactly where the arc in began: the leads *meet*),
  a perpendicular line, or (at a corner) a line along the last edge's
  extension; compensation goes off over the retreat;
- optionally a run-past overlap along the first edge after the loop closes;
- cutter radius 0.5-5 mm, kept below a third of the part's shortest feature
  (edges, fillets): a program a CAM system would write for that tool;
- written with 3, 4 or 6 decimals (arcs by their centre offsets I, J, as
  CAM posts write them), in G-code (G41/G42 with a tool table) or PMAC
  (CCR, CC1/CC2), cut clockwise or counter-clockwise; on request
  (``dialect=``) also for a SINUMERIK 840D (``$TC_DP6``, G41/G42, ``I=``
  ``J=``) or a HEIDENHAIN TNC (``TOOL DEF``, ``RL``/``RR``, ``CC`` + ``C``),
  the leads written as moves (the controllers' own lead moves:
  :mod:`family_programs`).

:func:`cam_program` returns a :class:`CamProgram` with the text and what
the test needs to know: which program lines are the part contour (worked
out here from the construction, not by the verifier), and a copy of the
program with one contour edge pushed into the part by a given depth.

:func:`multipass_program` writes the G-code of one profile called as a
subroutine with several diameters (0, negative, and changing between passes).
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

import numpy as np

LEAD_IN_KINDS = ("arc", "perpendicular", "extension")
LEAD_OUT_KINDS = ("arc", "meet", "perpendicular", "extension")
DECIMALS = (3, 4, 6)
DIALECTS = ("gcode", "pmac")


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _left(t):
    return np.array([-t[1], t[0]])


def _unit(v):
    v = np.asarray(v, float)
    return v / math.hypot(*v)


@dataclass
class _El:
    """One element of the contour: a line, or an arc with its centre and turn."""

    kind: str                    # "line" | "arc"
    p0: np.ndarray
    p1: np.ndarray
    centre: np.ndarray | None = None
    ccw: bool = False

    def reversed(self) -> "_El":
        return _El(self.kind, self.p1, self.p0, self.centre, not self.ccw)

    def tangent(self, at_end: bool) -> np.ndarray:
        if self.kind == "line":
            return _unit(self.p1 - self.p0)
        p = self.p1 if at_end else self.p0
        radial = _unit(p - self.centre)
        return _left(radial) if self.ccw else -_left(radial)

    @property
    def length(self) -> float:
        if self.kind == "line":
            return float(math.hypot(*(self.p1 - self.p0)))
        r = math.hypot(*(self.p0 - self.centre))
        a0 = math.atan2(*(self.p0 - self.centre)[::-1])
        a1 = math.atan2(*(self.p1 - self.centre)[::-1])
        sw = (a1 - a0) % (2 * math.pi) if self.ccw else (a0 - a1) % (2 * math.pi)
        return r * sw


def _polygon(rng: random.Random) -> np.ndarray:
    """Counter-clockwise vertices: a rectangle or a star-shaped polygon."""
    if rng.random() < 0.4:
        w, h = rng.uniform(30, 120), rng.uniform(20, 80)
        x0, y0 = rng.uniform(-50, 50), rng.uniform(-50, 50)
        return np.array([(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)])
    n = rng.randint(3, 9)
    # angles spread out enough that no edge is tiny
    while True:
        ang = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
        gaps = np.diff(ang + [ang[0] + 2 * math.pi])
        if gaps.min() > 0.35 and gaps.max() < math.pi - 0.2:
            break
    while True:
        rad = [rng.uniform(25, 60) for _ in range(n)]
        cx, cy = rng.uniform(-50, 50), rng.uniform(-50, 50)
        pts = np.array([(cx + r * math.cos(a), cy + r * math.sin(a)) for a, r in zip(ang, rad)])
        if min(abs(_turn(pts, i)) for i in range(n)) >= MIN_TURN:
            return pts


#: Every vertex of a star polygon turns by at least this (radians). LinuxCNC
#: takes a turn under 0.05 rad as straight on and its join then gouges by
#: r (1 - cos turn), more than the 1e-3 mm tolerance from 0.02 rad at r = 5:
#: such vertices are drawn by :func:`slight_turn_program`, whose figure is
#: known, not here.
MIN_TURN = 0.06


def _turn(pts: np.ndarray, i: int) -> float:
    a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
    d1, d2 = _unit(b - a), _unit(c - b)
    return math.atan2(_cross(d1, d2), float(np.dot(d1, d2)))


def _convex(pts: np.ndarray, i: int) -> bool:
    a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
    return _cross(b - a, c - b) > 0.0


def _elements(pts: np.ndarray, fillets: list[float]) -> list[_El]:
    """The CCW contour as lines and tangent fillet arcs (fillet radius 0: sharp)."""
    n = len(pts)
    ends = []                    # per vertex: (arrive, leave, arc or None)
    for i in range(n):
        a, b, c = pts[i - 1], pts[i], pts[(i + 1) % n]
        f = fillets[i]
        if f <= 0.0:
            ends.append((b, b, None))
            continue
        d1, d2 = _unit(b - a), _unit(c - b)
        turn = math.atan2(_cross(d1, d2), float(np.dot(d1, d2)))
        t = f * math.tan(abs(turn) / 2)
        t1, t2 = b - d1 * t, b + d2 * t
        ends.append((t1, t2, _El("arc", t1, t2, t1 + f * _left(d1), True)))
    els: list[_El] = []
    for i in range(n):
        _, leave, arc = ends[i]
        if arc is not None:
            els.append(arc)
        arrive = ends[(i + 1) % n][0]
        els.append(_El("line", leave, arrive))
    return els


def _fillet_fits(pts: np.ndarray, fillets: list[float]) -> bool:
    n = len(pts)
    for i in range(n):
        b, c = pts[i], pts[(i + 1) % n]
        used = 0.0
        for j, nb in ((i, pts[i - 1]), ((i + 1) % n, pts[(i + 2) % n])):
            f = fillets[j]
            if f > 0:
                v = pts[j]
                d1 = _unit(v - (pts[j - 1]))
                d2 = _unit(pts[(j + 1) % n] - v)
                turn = math.atan2(_cross(d1, d2), float(np.dot(d1, d2)))
                used += f * math.tan(abs(turn) / 2)
        if used > 0.6 * math.hypot(*(c - b)):
            return False
    return True


@dataclass
class CamProgram:
    """A generated program: ``text`` in ``dialect`` with cutter radius ``radius``
    (program units, mm), ``contour_lines`` the program lines of the part
    contour (first, last), ``pushed(depth)`` the same program with one straight
    contour edge's middle third moved ``depth`` into the part, ``notched(width,
    depth)`` with a rectangular slot cut into the part at the middle of the
    longest straight contour move but the first and the last (away from the
    leads): ``(text, slot_lines)``, the program lines of its walls and bottom."""

    seed: int
    dialect: str
    text: str
    radius: float
    decimals: int
    contour_lines: tuple[int, int]
    description: str
    tool_table: dict = field(default_factory=dict)
    _pusher: object = field(default=None, repr=False)
    _notcher: object = field(default=None, repr=False)

    def pushed(self, depth: float) -> str:
        return self._pusher(depth)

    def notched(self, width: float, depth: float) -> tuple[str, tuple[int, int]]:
        return self._notcher(width, depth)

    @property
    def file(self) -> str:
        return f"cam-{self.seed}.{SUFFIXES[self.dialect]}"


def _draw_part(rng: random.Random):
    while True:
        pts = _polygon(rng)
        n = len(pts)
        convex = [_convex(pts, i) for i in range(n)]
        fillets = [rng.choice((0.0, rng.uniform(2, 12))) if convex[i] else 0.0
                   for i in range(n)]
        if _fillet_fits(pts, fillets):
            return pts, fillets, convex


def cam_program(seed: int, dialect: str | None = None,
                lead_ins: tuple[str, ...] = ("arc", "perpendicular"),
                lead_outs: tuple[str, ...] = ("arc", "meet", "perpendicular")) -> CamProgram:
    """The program of ``seed`` (every choice drawn from it; ``dialect`` fixed
    if given; the lead kinds drawn from ``lead_ins`` and ``lead_outs``: an
    extension lead gouges the corner it starts or ends at, by
    ``r - r l / sqrt(l^2 + r^2)`` for a lead of length ``l``, so the programs
    that must verify leave it out)."""
    rng = random.Random(seed)
    dialect = dialect or rng.choice(DIALECTS)
    pts, fillets, convex = _draw_part(rng)
    els = _elements(pts, fillets)
    shortest = min(e.length for e in els)
    radius = round(rng.uniform(0.5, min(5.0, shortest / 3)), 3)
    decimals = rng.choice(DECIMALS)
    # entry: a sharp convex corner (vertex i starts element k) or mid-edge
    corners = [k for k, e in enumerate(els)
               if e.kind == "line" and any(np.allclose(e.p0, pts[i]) and convex[i]
                                          and fillets[i] == 0.0 for i in range(len(pts)))]
    lines = [k for k, e in enumerate(els) if e.kind == "line"]
    at_corner = bool(corners) and rng.random() < 0.5
    if at_corner:
        k = rng.choice(corners)
        loop = els[k:] + els[:k]
    else:
        k = rng.choice(lines)
        e = els[k]
        u = rng.uniform(0.3, 0.7)
        m = e.p0 + u * (e.p1 - e.p0)
        loop = [_El("line", m, e.p1)] + els[k + 1:] + els[:k] + [_El("line", e.p0, m)]
    clockwise = rng.random() < 0.5
    if clockwise:
        loop = [e.reversed() for e in reversed(loop)]
    # tool outside the part: left of a clockwise cut (G41/CC1), right of a
    # counter-clockwise one (G42/CC2); n: unit normal toward the tool
    side = 1 if clockwise else -1
    E = loop[0].p0
    t_in, t_out = loop[0].tangent(False), loop[-1].tangent(True)
    n_in, n_out = side * _left(t_in), side * _left(t_out)
    overlap = 0.0
    if not at_corner and rng.random() < 0.3:
        overlap = rng.uniform(0.3, 0.45) * loop[0].length
    lead_in = rng.choice(tuple(k for k in lead_ins if at_corner or k != "extension")
                         or ("perpendicular",))
    out_kinds = tuple(k for k in lead_outs if at_corner or k in ("arc", "perpendicular"))
    lead_out = rng.choice(tuple(k for k in out_kinds if lead_in == "arc" or k != "meet")
                          or ("perpendicular",))
    rho = rng.uniform(1.5, 3.0) * radius + 1.0          # lead arc radius, tool fits inside
    ell = rng.uniform(1.5, 3.0) * radius + 2.0          # straight lead length
    moves: list[tuple] = []                             # (kind, end, centre, ccw, role)
    # lead-in
    if lead_in == "arc":
        A = E + rho * n_in - rho * t_in
        start = A + ell * n_in
        moves.append(("on", A, None, None))
        moves.append(("arc", E, E + rho * n_in, side > 0))
    elif lead_in == "perpendicular":
        start = E + ell * n_in
        moves.append(("on", E, None, None))
    else:
        start = E - ell * t_in
        moves.append(("on", E, None, None))
    first_contour = len(moves)
    for e in loop:
        moves.append((e.kind, e.p1, e.centre, e.ccw))
    last_contour = len(moves) - 1
    X = E
    t_x, n_x = t_out, n_out
    if overlap:
        X = E + overlap * t_in
        moves.append(("line", X, None, None))
        t_x, n_x = t_in, n_in
    if lead_out == "arc":
        B = X + rho * n_x + rho * t_x
        moves.append(("arc", B, X + rho * n_x, side > 0))
        moves.append(("off", B + ell * n_x, None, None))
    elif lead_out == "meet":
        # the arc tangent to the contour at E that ends where the arc in began
        d = A - X
        s = float(d @ d) / (2.0 * float(d @ n_x))
        if not (s > 1.2 * radius):
            lead_out = "arc"
            B = X + rho * n_x + rho * t_x
            moves.append(("arc", B, X + rho * n_x, side > 0))
            moves.append(("off", B + ell * n_x, None, None))
        else:
            moves.append(("arc", A, X + s * n_x, side > 0))
            moves.append(("off", start, None, None))
    elif lead_out == "perpendicular":
        moves.append(("off", X + ell * n_x, None, None))
    else:
        moves.append(("off", X + ell * t_x, None, None))
    desc = (f"seed {seed}: {dialect}, {len(pts)}-gon{' rectangle' if len(pts) == 4 else ''}, "
            f"{'corner' if at_corner else 'mid-edge'} entry, lead-in {lead_in}, lead-out "
            f"{lead_out}, overlap {overlap:.3g}, r {radius}, {decimals} decimals, "
            f"{'CW' if clockwise else 'CCW'}")
    writer = WRITERS[dialect]

    def text_with(ms):
        return writer(start, ms, side, radius, decimals, desc)

    text, line_of = text_with(moves)
    # push: the longest straight contour move's middle third, depth into the part
    straight = [q for q in range(first_contour, last_contour + 1) if moves[q][0] == "line"]

    def pusher(depth: float) -> str:
        q = max(straight, key=lambda q: math.dist(moves[q - 1][1], moves[q][1]))
        a, b = np.asarray(moves[q - 1][1]), np.asarray(moves[q][1])
        inward = -(side * _left(_unit(b - a)))         # away from the tool: into the part
        m1 = a + (b - a) / 3 + depth * inward
        m2 = a + 2 * (b - a) / 3 + depth * inward
        dented = moves[:q] + [("line", m1, None, None), ("line", m2, None, None)] + moves[q:]
        return text_with(dented)[0]

    def notcher(width: float, depth: float) -> tuple[str, tuple[int, int]]:
        inner = [q for q in straight if first_contour < q < last_contour] or straight
        q = max(inner, key=lambda q: math.dist(moves[q - 1][1], moves[q][1]))
        a, b = np.asarray(moves[q - 1][1]), np.asarray(moves[q][1])
        t = _unit(b - a)
        inward = -(side * _left(t))
        m = 0.5 * (a + b)
        p1, p2 = m - 0.5 * width * t, m + 0.5 * width * t
        slot = [p1, p1 + depth * inward, p2 + depth * inward, p2]
        cut = moves[:q] + [("line", p, None, None) for p in slot] + moves[q:]
        cut_text, cut_lines = text_with(cut)
        return cut_text, (cut_lines[q + 1], cut_lines[q + 3])

    out = CamProgram(seed, dialect, text, radius, decimals,
                     (line_of[first_contour], line_of[last_contour]), desc,
                     {1: 2 * radius}, pusher, notcher)
    out.lead_in, out.lead_out = lead_in, lead_out
    out.entry, out.start, out.exit, out.end = E, start, X, moves[-1][1]
    # what a writer of the controllers' own leads needs (family_programs.py):
    # the contour moves from the entry to the exit (the overlap included), the
    # unit tangents and tool-side normals there, the lead sizes drawn, the side
    out.contour_moves = moves[first_contour:last_contour + 1 + (1 if overlap else 0)]
    out.t_in, out.n_in, out.t_x, out.n_x = t_in, n_in, t_x, n_x
    out.rho, out.ell, out.side = rho, ell, side
    out.overlap, out.at_corner = overlap, at_corner
    return out


def _fmt(x: float, decimals: int) -> str:
    s = f"{x:.{decimals}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _ISO(start, moves, side, radius, dec, desc, siemens: bool = False):
    """G-code (``G41 D1`` with a tool table, arcs by ``I J``) or, with
    ``siemens``, a SINUMERIK 840D part program as CAM posts write it: the
    radius in the tool offset ``$TC_DP6``, ``G41``/``G42`` with ``T1 D1``,
    arcs by their centre offsets ``I=`` ``J=`` (incremental, the 840D's
    default)."""
    f = lambda x: _fmt(x, dec)              # noqa: E731
    eq = "=" if siemens else ""
    head = ([f"; {desc}", f"$TC_DP6[1,1]={f(radius)}", "G17 G71 G90 T1 D1 M6"] if siemens
            else [f"({desc})", "G21 G17 G90 G94", "T1 M6"])
    out = head + [f"G0 X{f(start[0])} Y{f(start[1])}"]
    line_of = []                            # each move's line
    cur = np.asarray(start, float)
    g4x = ("G41" if side > 0 else "G42") + ("" if siemens else " D1")
    for kind, p, c, ccw in moves:
        xy = f"X{f(p[0])} Y{f(p[1])}"
        if kind == "on":
            out.append(f"{g4x} G1 {xy} F600")
        elif kind == "off":
            out.append(f"G40 G1 {xy}")
        elif kind == "line":
            out.append(f"G1 {xy}")
        else:
            out.append(f"{'G3' if ccw else 'G2'} {xy} I{eq}{f(c[0] - cur[0])} "
                       f"J{eq}{f(c[1] - cur[1])}")
        cur = np.asarray(p, float)
        line_of.append(len(out))
    out.append("M30")
    return "\n".join(out) + "\n", line_of


def _GCODE(*args):
    return _ISO(*args)


def _SINUMERIK(*args):
    return _ISO(*args, siemens=True)


def _PMAC(start, moves, side, radius, dec, desc):
    f = lambda x: _fmt(x, dec)              # noqa: E731
    out = [f"; {desc}", "OPEN PROG 1 CLEAR", f"RAPID X{f(start[0])} Y{f(start[1])}",
           "LINEAR ABS F10", f"CCR{f(radius)}"]
    line_of = []                            # each move's line
    cur = np.asarray(start, float)
    for kind, p, c, ccw in moves:
        xy = f"X{f(p[0])} Y{f(p[1])}"
        if kind == "on":
            out[-1] += f" CC{1 if side > 0 else 2}"
            out.append(f"LINEAR {xy}")
        elif kind == "off":
            out.append("CC0")
            out.append(f"LINEAR {xy}")
        elif kind == "line":
            out.append(f"LINEAR {xy}")
        else:
            out.append(f"CIRCLE{2 if ccw else 1} {xy} I{f(c[0] - cur[0])} J{f(c[1] - cur[1])}")
        cur = np.asarray(p, float)
        line_of.append(len(out))
    out.append("CLOSE")
    return "\n".join(out) + "\n", line_of



def _signed(x: float, dec: int) -> str:
    """A Klartext coordinate: its sign always written (``X+12.5``)."""
    s = _fmt(x, dec)
    return s if s.startswith("-") else "+" + s


def _HEIDENHAIN(start, moves, side, radius, dec, desc):
    """A HEIDENHAIN Klartext program as CAM posts write it: ``TOOL DEF`` with
    the radius, ``L ... RL``/``RR`` to come on, every arc as its centre ``CC``
    (absolute, a line of its own) and ``C ... DR+``/``DR-``, ``R0`` to go off."""
    f = lambda x: _signed(x, dec)           # noqa: E731
    out = ["BEGIN PGM CAM MM", f"; {desc}", f"TOOL DEF 1 L+0 R{f(radius)}",
           "TOOL CALL 1 Z S5000", f"L X{f(start[0])} Y{f(start[1])} R0 FMAX"]
    line_of = []                            # each move's line
    for kind, p, c, ccw in moves:
        xy = f"X{f(p[0])} Y{f(p[1])}"
        if kind == "on":
            out.append(f"L {xy} {'RL' if side > 0 else 'RR'} F600")
        elif kind == "off":
            out.append(f"L {xy} R0")
        elif kind == "line":
            out.append(f"L {xy}")
        else:
            out.append(f"CC X{f(c[0])} Y{f(c[1])}")
            out.append(f"C {xy} {'DR+' if ccw else 'DR-'}")
        line_of.append(len(out))
    out.append("END PGM CAM MM")
    return "\n".join(out) + "\n", line_of


#: The writer of each dialect, and its file suffix.
WRITERS = {"gcode": _GCODE, "pmac": _PMAC, "sinumerik": _SINUMERIK, "heidenhain": _HEIDENHAIN}
SUFFIXES = {"gcode": "nc", "pmac": "pmc", "sinumerik": "mpf", "heidenhain": "h"}

def multipass_program(seed: int) -> tuple[str, tuple[float, ...]]:
    """G-code: one rectangle's outside profile (cut counter-clockwise with
    ``G42.1``, entered mid-edge by a perpendicular lead) as ``o100`` called
    with the cutter diameters drawn from ``seed``: a zero one (the tool centre
    on the contour) and two or three different ones in any order (a roughing
    pass that leaves stock, a finishing pass); returns ``(text, diameters)``."""
    rng = random.Random(seed)
    w, h = rng.uniform(30, 80), rng.uniform(20, 60)
    ds = [0.0] + [round(rng.uniform(1, 10), 3) for _ in range(rng.randint(2, 3))]
    rng.shuffle(ds)
    x = round(rng.uniform(0.3, 0.7) * w, 3)
    lead = round(max(ds) + rng.uniform(2, 6), 3)
    sub = ["o100 sub", f"G0 X{x} Y{-lead}", f"G42.1 D#1 G1 X{x} Y0 F600", f"G1 X{w:.3f} Y0",
           f"G1 X{w:.3f} Y{h:.3f}", f"G1 X0 Y{h:.3f}", "G1 X0 Y0", f"G1 X{x} Y0",
           f"G40 G1 X{x} Y{-lead}", "o100 endsub"]
    body = ["G21 G17 G90 G94", *sub] + [f"o100 call [{d}]" for d in ds] + ["M30"]
    return "\n".join(body) + "\n", tuple(ds)


def slight_turn_program(seed: int) -> tuple[str, float, float]:
    """G-code (6 decimals): the outside profile of a rectangle cut clockwise
    with ``G41``, entered mid-edge by a perpendicular lead, whose top edge is
    two lines meeting at its middle, lifted or lowered so that they turn by a
    slight angle there (1e-3 to 0.05 rad, outward or inward); returns
    ``(text, r, turn)``, the turn worked out from the written coordinates
    (> 0 turning away from the tool: an outside corner)."""
    rng = random.Random(seed)
    w, h = round(rng.uniform(40, 120), 3), round(rng.uniform(20, 60), 3)
    r = round(rng.uniform(0.5, 5.0), 3)
    beta = rng.uniform(1e-3, 0.05) * rng.choice((1, -1))
    lift = round(math.tan(beta / 2) * w / 2, 6)        # > 0: the middle lifted (outside)
    x = round(rng.uniform(0.3, 0.7) * w, 3)
    lead = round(r + rng.uniform(2, 6), 3)
    top = (w / 2, h + lift)
    body = ["G21 G17 G90 G94", "T1 M6", f"G0 X{x} Y{-lead}", f"G41 D1 G1 X{x} Y0 F600",
            "G1 X0 Y0", f"G1 X0 Y{h}", f"G1 X{top[0]:.6f} Y{top[1]:.6f}", f"G1 X{w} Y{h}",
            f"G1 X{w} Y0", f"G1 X{x} Y0", f"G40 G1 X{x} Y{-lead}", "M30"]
    # written points (0, h) -> top -> (w, h), clockwise: turning right is away
    # from the tool (on the left, outside)
    d1 = _unit(np.array(top) - (0.0, h))
    d2 = _unit(np.array((w, h)) - top)
    turn = -math.atan2(_cross(d1, d2), float(np.dot(d1, d2)))
    return "\n".join(body) + "\n", r, turn


#: The stadium of issue 30: two straights of 200 joined by half circles of
#: radius 30, cut clockwise with CC1 (r 2), entered mid-straight by a
#: perpendicular lead from outside (PMAC).
STADIUM = """; stadium, clockwise with CC1 (tool outside), r 2
OPEN PROG 1 CLEAR
RAPID X50 Y60
LINEAR ABS F100
CCR2 CC1
X50 Y30
X200 Y30
CIRCLE1 X200 Y-30 I0 J-30
LINEAR X0 Y-30
CIRCLE1 X0 Y30 I0 J30
LINEAR X50 Y30
CC0
LINEAR X50 Y60
CLOSE
"""
