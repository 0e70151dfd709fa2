"""Programs that compensate in more than one plane, one plane at a time.

A program may compensate in ``G17``, turn compensation off and compensate
again in ``G18`` (LinuxCNC's own inside-corners test does). The PMAC and
Fagor engines work in the coordinates of one plane, so :func:`by_plane`
splits the program where the plane changes into *sections* of blocks in one
plane, compensates each as a program of its own that starts where the tool
stands, and joins the tool paths; every segment keeps its section's plane.
A section ends as a program ends: still on there, the style's own
program-end rule removes the offset (PMAC's automatic lead-out, Fagor's
``FAGOR_PROGRAM_END_WHILE_ON``); docs/compensation.md, section 1.2.
LinuxCNC's engine follows its interpreter instead and changes plane in
place (:func:`change_plane`).

A plane change while compensation is on is an error: where the reader has
refused those itself (:data:`~ccopt.program.model.PLANE_CHANGES_CHECKED`, the
G-code reader), every change reaching here was made with compensation off;
otherwise (PMAC programs, whose reader does not judge) a change next to a
compensated move is refused, located at the move after it.
"""
from __future__ import annotations

import math
from dataclasses import replace
from functools import wraps
from operator import attrgetter

import numpy as np

from ccopt.errors import CompensationError
from ccopt.program.columns import columns_of
from ccopt.program.model import PLANE_CHANGES_CHECKED, Block, Program
from ccopt.tolerances import POINT_EPS
from ccopt.toolpath import ToolPath, machine_point, plane_point


def check_plane_change(program: Program, on_before: bool, blk: Block, old: str) -> None:
    """Refuse the change from plane ``old`` to ``blk``'s (located at ``blk``)
    when compensation may have been on at it: ``on_before`` is whether it was
    on for the move before (module docstring)."""
    if program.meta.get(PLANE_CHANGES_CHECKED):
        return
    if on_before or blk.modal.side != 0:
        s = blk.source
        raise CompensationError(f"plane change ({old} to {blk.modal.plane}, NORMAL/G17-G19) "
                                "while cutter compensation is on: turn it off (CC0/G40) first",
                                s.file, s.line, s.col)


def change_plane(interp, blk: Block, was_on: bool) -> bool:
    """LinuxCNC's engine (``interp``, a ``linuxcnc._Interpreter``) meets
    ``blk`` in another plane; returns whether compensation is still on.

    A program whose reader judged the plane words (G-code) turned
    compensation off before the plane word: that ``G40`` happens here if the
    blocks cannot show it (``G40``, ``G18``, ``G41`` between two moves). The
    positions LinuxCNC keeps in machine coordinates (the tool's, the
    programmed point) go over to the new plane's ``(u, v)`` and ``w``; the
    next move starts where the tool stands, as LinuxCNC's canonical move does.
    """
    old, new = interp.plane, blk.modal.plane
    check_plane_change(interp.program, was_on or interp.k != 0, blk, old)
    if was_on:
        interp.compensation_off(blk)
    prog_xyz = machine_point(old, interp.prog[0], interp.prog[1], interp.cur_w)
    for pos, w in (("cur", "cur_w"), ("tip", "tip_w")):
        u, v, ww = plane_point(new, machine_point(old, *getattr(interp, pos), getattr(interp, w)))
        setattr(interp, pos, np.array([u, v]))
        setattr(interp, w, ww)
    interp.prog = np.array(plane_point(new, prog_xyz)[:2])
    interp.endpoint_valid = False
    interp.plane = new
    return False


_PLANE_OF = attrgetter("modal.plane")


def plane_sections(program: Program) -> list[list[Block]]:
    """The program's blocks cut where the plane changes (one list per run of
    blocks in one plane, in order; one list for a one-plane program)."""
    sections: list[list[Block]] = []
    plane = None
    for blk in program.blocks:
        if blk.modal.plane != plane:
            if sections:
                before = sections[-1][-1]
                check_plane_change(program, before.modal.side != 0, blk, before.modal.plane)
            sections.append([])
            plane = blk.modal.plane
        sections[-1].append(blk)
    return sections


def _starting_at(blocks: list[Block], at) -> list[Block]:
    """``blocks`` with the first one starting at machine point ``at`` when the
    tool stands elsewhere than its programmed start (a section ended on an
    offset point): the machine moves from where the tool is."""
    first = blocks[0]
    if math.dist(first.start, at) <= POINT_EPS:
        return blocks
    return [replace(first, start=tuple(at)), *blocks[1:]]


def join_paths(paths: list[ToolPath]) -> ToolPath:
    """One tool path of the sections' paths, in order (dwell indices moved)."""
    segs, dwells, meta = [], [], {}
    for p in paths:
        dwells += [(i + len(segs), t, b) for i, t, b in p.dwells]
        segs += p.segments
        meta.update(p.meta)
    first = paths[0]
    return ToolPath(tuple(segs), plane=segs[0].plane if segs else first.plane,
                    style=first.style, radius=max(p.radius for p in paths),
                    dwells=tuple(dwells), units=first.units, meta=meta)


def by_plane(compensate):
    """Decorate an engine's ``compensate(self, program, radius, side)`` so that
    a program in several planes is compensated section by section."""

    @wraps(compensate)
    def run(self, program: Program, radius: float | None = None,
            side: int | None = None) -> ToolPath:
        if len(columns_of(program).planes()) <= 1:      # read once, for the scan too
            # one plane (most programs): no sections to cut, nothing to check
            return compensate(self, program, radius=radius, side=side)
        sections = plane_sections(program)
        if len(sections) <= 1:
            return compensate(self, program, radius=radius, side=side)
        paths = []
        at = program.start
        for blocks in sections:
            sub = Program(tuple(_starting_at(blocks, at)), file=program.file,
                          dialect=program.dialect, units=program.units, start=tuple(at),
                          meta=program.meta)
            path = compensate(self, sub, radius=radius, side=side)
            paths.append(path)
            if path.segments:
                at = path.segments[-1].end_xyz
        return join_paths(paths)

    return run
