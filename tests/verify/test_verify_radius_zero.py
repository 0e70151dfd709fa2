"""A pass compensated with radius 0 (G41.1 D0, or LinuxCNC's G41 D0: tool 0
is no tool) runs on the contour itself and verifies; a path that leaves the
contour by d fails contact by d."""
from __future__ import annotations

import pytest

import ccopt
from ccopt.geometry import translated
from ccopt.program.gcode import read_gcode
from ccopt.toolpath import PathSegment, ToolPath

SQUARE = "G21 F600\nG0 X0 Y0\nG41.1 D0 G1 X10\nG1 Y10\nG1 X0\nG1 Y0\nG40 G1 X-5\n"


@pytest.mark.parametrize("style", ["linuxcnc", "pmac", "fagor"])
def test_radius_zero_pass_verifies(style):
    prog = read_gcode(SQUARE, "square.ngc")
    path = ccopt.compensate(prog, style=style)
    cert = ccopt.verify(path, prog)
    assert cert.ok, cert.summary()
    contact = cert.check("contact")
    # the edges after the entry move (line 3, a lead-in) run along the part
    assert contact.count == 3 and contact.violations == 0


def test_radius_zero_path_off_the_contour_fails_contact_by_its_distance():
    prog = read_gcode(SQUARE, "square.ngc")
    path = ccopt.compensate(prog, style="linuxcnc")
    # the top edge (line 5, (10, 10) to (0, 10)) lifted by 0.01
    segments = [PathSegment(translated(s.geom, 0.0, 0.01), s.role, s.block, s.w0, s.w1, s.feed)
                if s.block is not None and s.block.source.line == 5 else s
                for s in path.segments]
    lifted = ToolPath(tuple(segments), plane=path.plane, style=path.style, radius=path.radius,
                      units=path.units)
    cert = ccopt.verify(lifted, prog)
    assert not cert.ok
    contact = [v for v in cert.violations if v.kind == "contact"]
    assert contact and max(v.depth for v in contact) == pytest.approx(0.01, abs=1e-9)
