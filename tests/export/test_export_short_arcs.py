"""An arc shorter than the written resolution is written as a straight move.

A corner arc of 1.77e-7 rad on a 1.501 mm cutter (the SINUMERIK style's,
at a contour step of 1e-6 left by a CAM program written with 6 decimals)
has its end on its start once written with 6 decimals: read back, a G2/G3
or CIRCLE with the end on the start is a full circle (LinuxCNC's and PMAC's
rule), 9.4 mm of motion the path does not have. Found by the generated
SINUMERIK plates (tests/verify/test_family_generated.py, seed 36).

The figures here come from the geometry written in the test: the read-back
path's length is the lines' lengths plus the arc's (1.501 * 1.77e-7 mm), to
the written resolution, and every read-back move stays within that resolution
plus the arc's length of the path.
"""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.export import export
from ccopt.geometry import Arc, Line, Spiral
from ccopt.program import read_program
from ccopt.toolpath import PathSegment, Role, ToolPath

R = 1.501
SWEEP = 1.77e-7
CENTRE = (41.832444, 100.900278)


def _path() -> ToolPath:
    arc = Arc(CENTRE, R, math.pi - SWEEP, SWEEP)          # ends at angle pi
    above = (40.331444, 100.900277)                     # a 1e-6 step before the arc
    segs = (PathSegment(Line((40.331444, 120.0), above), Role.COMPENSATED, None, 0.0, 0.0, 10.0),
            PathSegment(arc, Role.CORNER, None, 0.0, 0.0, 10.0),
            PathSegment(Line(arc.end, (40.331444, 28.990563)), Role.COMPENSATED, None, 0.0, 0.0,
                        10.0))
    return ToolPath(segs, style="siemens", radius=R, units="mm")


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_an_arc_whose_written_end_is_its_start_reads_back_as_no_circle(tmp_path, suffix):
    path = _path()
    out = tmp_path / f"short{suffix}"
    res = export(path, out)
    assert res.roundtrip_error <= res.tolerance
    back = ccopt.programmed_path(read_program(out))
    moving = [s for s in back.segments if s.role is not Role.RAPID]
    expected = (120.0 - 100.900277) + R * SWEEP + (100.900278 - 28.990563)
    # a full circle would add 2 pi R = 9.43 mm; the step of 1e-6 is written as it is
    assert sum(s.length for s in moving) == pytest.approx(expected, abs=5e-6)
    assert not any(isinstance(s.geom, (Arc, Spiral)) for s in moving)


@pytest.mark.parametrize("suffix", [".nc", ".pmc"])
def test_a_short_arc_above_the_resolution_stays_an_arc(tmp_path, suffix):
    # 0.01 rad on 1.501 mm: a 15 um chord, far above the 1 um of 6 decimals
    arc = Arc(CENTRE, R, math.pi - 0.01, 0.01)
    segs = (PathSegment(Line((arc.start[0], 120.0), arc.start), Role.COMPENSATED, None, 0.0,
                        0.0, 10.0),
            PathSegment(arc, Role.CORNER, None, 0.0, 0.0, 10.0))
    out = tmp_path / f"arc{suffix}"
    export(ToolPath(segs, style="siemens", radius=R, units="mm"), out)
    back = ccopt.programmed_path(read_program(out))
    # an arc, or the spiral its rounded centre and ends make (radii 5e-8 apart)
    arcs = [s.geom for s in back.segments if isinstance(s.geom, (Arc, Spiral))]
    assert len(arcs) == 1 and arcs[0].sweep == pytest.approx(0.01, rel=1e-3)
