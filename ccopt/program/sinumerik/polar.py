"""Polar coordinates of a SINUMERIK program: the pole ``G110``/``G111``/
``G112`` and moves by ``AP=`` (angle) and ``RP=`` (radius) (Programming
Manual Fundamentals 6FC5398-2EP40, "Reference point of polar coordinates
(G110, G111, G112)" and "Travel commands with polar coordinates (G0, G1,
G2, G3, AP, RP)").

In the plane of ``G17``-``G19`` (``u, v``: its first and second axis), a
polar point is ``pole + RP (cos AP, sin AP)``, ``AP`` in degrees from the
first axis, counter-clockwise; the third axis may be written as usual
(cylindrical coordinates). ``G0``/``G1`` go straight to it, ``G2``/``G3``
turn about the pole to it. Without a pole, the work zero is the pole.

The pole stands in a block of its own, written with the plane's two axes or
with ``AP``/``RP``: ``G110`` from the last programmed position, ``G111``
from the work zero (absolute), ``G112`` from the last pole. ``AP`` and
``RP`` are kept from block to block; ccopt forgets them where the pole or
the plane changes (the manual does not say they survive it), so the first
polar move after that writes both. ``AP=IC(..)``/``RP=IC(..)`` add to the
kept value, ``AC(..)`` is absolute; under ``G91`` ccopt asks for one of the
two (the manual's wording leaves plain values open there).

Everything is turned into the core's words: ``X Y Z`` (absolute, or from
the current point under ``G91``) and, for a circle, the centre offsets from
the start, all in the work frame (:mod:`.frames` may turn it).
"""
from __future__ import annotations

import math

from ccopt.program.expr import ExprError
from ccopt.program.gcode.arcs import CENTRE_WORDS
from ccopt.program.gcode.coordinates import to_work
from ccopt.program.model import PLANE_AXES
from ccopt.program.sinumerik.state import SinumerikRun
from ccopt.program.sinumerik.words import BlockWords

POLAR_WORDS = ("AP", "RP")


def pole_block(run: SinumerikRun, bw: BlockWords) -> None:
    """Execute a ``G110``/``G111``/``G112`` block: set the pole."""
    state = run.state
    n, col = bw.pole
    iu, iv, _ = PLANE_AXES[state.plane]
    au, av = "XYZ"[iu], "XYZ"[iv]
    polar = [w for w in POLAR_WORDS if w in bw.values]
    others = set(bw.axes) - {au, av}
    if others or len(bw.values) > len(polar) or bw.g or bw.m or bw.letters or bw.centre:
        raise ExprError(f"G{n} takes a block of its own with {au} {av} or AP RP only", col)
    here = to_work(state, state.pos)
    ref = {110: (here[iu], here[iv]), 111: (0.0, 0.0),
           112: run.pole if run.pole is not None else (0.0, 0.0)}[n]
    if polar:
        if bw.axes or len(polar) < 2:
            raise ExprError(f"G{n}: give the pole by {au} {av} or by AP and RP, not a mix",
                            col)
        ap, rp = (_plain(bw, w) for w in POLAR_WORDS)
        pole = _polar_point(ref, ap, rp)
    else:
        if set(bw.axes) != {au, av}:
            raise ExprError(f"G{n} needs the pole's {au} and {av} (or AP and RP)", col)
        for a in (au, av):
            if bw.axes[a][1] is not None:
                raise ExprError(f"G{n}: the pole's {a} is a value, not AC/IC(..)", bw.axes[a][2])
        u, v = bw.axes[au][0], bw.axes[av][0]
        pole = (u, v) if n == 111 else (ref[0] + u, ref[1] + v)
    run.pole, run.pole_plane = pole, state.plane
    run.ap = run.rp = None


def _plain(bw: BlockWords, name: str) -> float:
    value, mode, col = bw.values[name]
    if mode not in (None, "AC"):
        raise ExprError(f"{name} of a pole is a value", col)
    return value


def polar_move(run: SinumerikRun, bw: BlockWords, letters: dict, g: list) -> None:
    """A block with ``AP``/``RP``: its end point (and a circle's centre, the
    pole) written into ``letters`` as the core's words."""
    if not any(w in bw.values for w in POLAR_WORDS):
        return
    state = run.state
    col = bw.values["AP" if "AP" in bw.values else "RP"][2]
    if run.pole is not None and run.pole_plane != state.plane or _changes_plane(bw):
        raise ExprError("AP/RP in another plane than the pole's: set the pole again (G110-"
                        "G112) in this plane", col)
    iu, iv, _ = PLANE_AXES[state.plane]
    au, av = "XYZ"[iu], "XYZ"[iv]
    if au in bw.axes or av in bw.axes:
        raise ExprError(f"AP/RP with {au} or {av} in one block: give the end point one way",
                        col)
    incremental = _incremental(state, bw)
    ap = _value(bw, "AP", run.ap, incremental, col)
    rp = _value(bw, "RP", run.rp, incremental, col)
    if rp < 0:
        raise ExprError(f"RP={rp:g}: the polar radius is >= 0", col)
    run.ap, run.rp = ap, rp
    pole = run.pole if run.pole is not None else (0.0, 0.0)
    target = _polar_point(pole, ap, rp)
    here = to_work(state, state.pos)
    for k, a, t in ((iu, au, target[0]), (iv, av, target[1])):
        letters[a] = (t - here[k] if incremental else t, col)
    motion = _motion(run, g, col)
    if motion in (20, 30):
        wu, wv = CENTRE_WORDS[state.plane]
        if any(w in letters for w in (wu, wv, "R")) or "AR" in bw.values:
            raise ExprError("a circle by AP/RP turns about the pole: no centre, CR= or AR= "
                            "with it", col)
        letters[wu] = (pole[0] - here[iu], col)
        letters[wv] = (pole[1] - here[iv], col)


def _changes_plane(bw: BlockWords) -> bool:
    return any(t in (170, 180, 190) for t, _ in bw.g)


def _incremental(state, bw: BlockWords) -> bool:
    incremental = state.incremental
    for t, _ in bw.g:
        if t in (900, 910):
            incremental = t == 910
    return incremental


def _polar_point(centre, ap: float, rp: float) -> tuple[float, float]:
    a = math.radians(ap)
    return (centre[0] + rp * math.cos(a), centre[1] + rp * math.sin(a))


def _value(bw: BlockWords, name: str, kept: float | None, incremental: bool,
           col: int) -> float:
    """``AP``/``RP`` of a move: written (plain, ``AC``, ``IC``) or kept."""
    if name not in bw.values:
        if kept is None:
            raise ExprError(f"{name} is not known here (none since the pole or plane was "
                            f"set): write {name}= too", col)
        return kept
    value, mode, col = bw.values[name]
    if mode is None and incremental:
        raise ExprError(f"{name} under G91: write {name}=AC(..) or {name}=IC(..)", col)
    if mode == "IC":
        if kept is None:
            raise ExprError(f"{name}=IC(..) adds to the last {name}, and none is known here "
                            "(none since the pole or plane was set)", col)
        return kept + value
    if mode not in (None, "AC"):
        raise ExprError(f"{name}={mode}(..): ccopt reads {name}=value, AC(..) and IC(..)", col)
    return value


def _motion(run: SinumerikRun, g: list, col: int) -> int | None:
    """The motion (tenths) the block runs; CIP and CT do not take AP/RP."""
    written = [t for t, _ in g if t in (0, 10, 20, 30)]
    if run.motion is not None and not written:
        raise ExprError(f"AP/RP with {run.motion}: ccopt reads polar moves with G0-G3", col)
    return written[-1] if written else run.state.motion_mode
