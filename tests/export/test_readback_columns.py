"""The programmed path and an export's read-back made as columns (issue 34)
are the paths made segment by segment, bit for bit.

:func:`ccopt.toolpath.programmed_path` keeps a program's moves as rows
(:func:`ccopt.move_geometry.move_rows`) and :func:`ccopt.export.readback.readback_columns`
builds an export's read-back from them, making no segment object until one is asked
for; :func:`~ccopt.toolpath.programmed_segments` and
:func:`~ccopt.export.readback.readback_segments` are the one-at-a-time
references. Over generated programs (:mod:`cam_programs`' plates in every
dialect, compensated in their own style and in the PMAC style as columns;
drilling plates with dwells and a work offset, :mod:`test_cycle_programs`),
each exported to G-code and to a PMAC program and read back:

- every segment of both roads is the same: geometry of the same type with
  the same numbers (to the bit: compared by ``repr``), role, the same block
  object, ``w`` at both ends, feed and plane; and the paths' dwells, plane,
  meta (:data:`~ccopt.toolpath.FITTED_PIECES`) and settings are equal; also
  for a path that starts away from the origin (the writer's own rapid to it).
"""
from __future__ import annotations

from pathlib import Path

import pytest

from cam_programs import cam_program
from ccopt.compensate import compensate
from ccopt.compensate.pmac import PmacStyle, assemble
from ccopt.compensate.scan import scan_program
from ccopt.export import _ProgramExport, readback_path
from ccopt.export.readback import readback_columns, readback_segments
from ccopt.program import read_text
from ccopt.program.gcode import read_gcode
from ccopt.program.model import START_PARAMETERS
from ccopt.toolpath import ToolPath, programmed_path, programmed_segments
from test_cycle_programs import make_plate

OWN_STYLE = {"gcode": "linuxcnc", "pmac": "pmac", "sinumerik": "siemens",
             "heidenhain": "heidenhain"}
QUICK = range(4)


def _segment_key(seg) -> tuple:
    g = seg.geom
    # the numbers a geometry keeps beside its fields (length, a spiral's b) too
    return (type(g), repr(g), repr((g.length, getattr(g, "b", None))), seg.role,
            id(seg.block), repr(seg.w0), repr(seg.w1), repr(seg.feed), seg.plane)


def _same_paths(a: ToolPath, b: ToolPath) -> None:
    assert a.columns is not None and b.columns is None
    assert len(a) == len(b)
    assert [_segment_key(s) for s in a.segments] == [_segment_key(s) for s in b.segments]
    assert a.dwells == b.dwells and [id(d[2]) for d in a.dwells] == [id(d[2]) for d in b.dwells]
    assert (a.plane, a.style, a.radius, a.units) == (b.plane, b.style, b.radius, b.units)
    assert a.meta == b.meta and a.planes == b.planes


def _read_back_alike(path: ToolPath, prog) -> None:
    """``path`` exported in both formats reads back alike on both roads."""
    for fmt, suffix in (("gcode", ".nc"), ("pmac", ".pmc")):
        job = _ProgramExport(path, fmt, 0.001, Path(f"out{suffix}"), prog, ["test"])
        text, moves = job.write(["test"], {})
        params = prog.meta.get(START_PARAMETERS)
        back = read_text(text, f"out{suffix}", fmt,
                         parameters=params if fmt == "gcode" else None)
        got = readback_columns(programmed_path(back), path, moves, f"out{suffix}")
        _same_paths(got, readback_segments(programmed_segments(back), path, moves,
                                           f"out{suffix}"))
        # as the export reads it back
        assert readback_path(text, fmt, path, moves, f"out{suffix}", parameters=params) == got


@pytest.mark.parametrize("seed", QUICK)
@pytest.mark.parametrize("dialect", sorted(OWN_STYLE))
def test_plates_read_back_alike(seed, dialect):
    cp = cam_program(seed, dialect=dialect)
    prog = read_text(cp.text, cp.file, dialect, tool_table=cp.tool_table)
    _same_paths(programmed_path(prog), programmed_segments(prog))
    path = compensate(prog, OWN_STYLE[dialect])
    _read_back_alike(path, prog)
    # away from the origin (its first segment left out): the writer's positioning rapid
    _read_back_alike(ToolPath(path.segments[1:], plane=path.plane, style=path.style,
                              radius=path.radius, units=path.units), prog)
    # the PMAC style's path as columns (as compensate makes it for long programs)
    columns = assemble(PmacStyle(), scan_program(prog, bulk=True), prog, columns=True)
    assert columns.columns is not None
    _read_back_alike(columns, prog)


@pytest.mark.parametrize("seed", QUICK)
def test_drilling_plates_read_back_alike(seed):
    plate = make_plate(seed)
    ox, oy, oz = plate.origin
    prog = read_gcode(plate.text, f"plate{seed}.ngc", tool_table={1: 6.0},
                      parameters={5221: ox, 5222: oy, 5223: oz})
    assert any(b.motion.value == "dwell" for b in prog.blocks) or seed % 2
    _same_paths(programmed_path(prog), programmed_segments(prog))
    _read_back_alike(compensate(prog, "linuxcnc"), prog)
