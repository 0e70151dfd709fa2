"""LinuxCNC's own ``tests/interp/inverse-time-with-comp`` (issue 29): one
subroutine, an open run of moves (it never returns to its start), called with
``G42.1 D#100`` for D = 0, 0.4 and -0.4 (inch; a diameter, a negative one
cutting on the other side).

Worked out from the program: no pass closes a loop, so every compensated
move is part and nothing is called a closed loop; the passes are held to
their own radii (0, 0.2, 0.2 on the left); the only gouge is the D-0.4 pass's
``G40`` move, which runs from the tool's last offset point (0, 4.8) straight
up to (0, 6) through the arc's end point (0, 5): a depth of the whole radius
0.2 (LinuxCNC's ``expected`` canon prints that move, STRAIGHT_FEED(0, 6)
after ARC_FEED(0, 4.8, ...)).
"""
from __future__ import annotations

from pathlib import Path

import pytest

import ccopt
from ccopt.compensate import compensate
from ccopt.verify import verify

PROGRAM = (Path(__file__).resolve().parents[1] / "conformance" / "linuxcnc"
           / "inverse-time-with-comp" / "inverse.ngc")
G40_LINE = 15


def test_inverse_time_with_comp_passes_and_its_one_gouge():
    prog = ccopt.read_program(PROGRAM)
    path = compensate(prog, "linuxcnc")
    cert = verify(path, prog)
    surface = cert.surface
    assert all(run["why"] != "closed loop" for run in surface["moves"])
    part = [run for run in surface["moves"] if run["surface"] == "part"]
    assert [run["lines"] for run in part] == [[6, 14]] * 3
    assert "closed loop" not in cert.summary().replace("no closed loop", "")
    # each pass with its own radius and side
    contour = cert.context.contour
    assert len(contour) == 3 * 8                 # lines 6-8 and 10-14
    assert contour.radius.tolist() == [0.0] * 8 + [0.2] * 16
    assert contour.side.tolist() == [-1] * 16 + [1] * 8
    # the one gouge: the third pass's G40 move through (0, 5)
    assert not cert.ok
    assert {v.kind for v in cert.violations} == {"gouge"}
    third = [i for i, s in enumerate(path.segments) if s.role.value == "rapid"][2]
    for v in cert.violations:
        assert v.tool_block == G40_LINE and v.tool_role == "lead-out"
        assert v.tool_segment > third
        assert v.depth == pytest.approx(0.2, abs=1e-12)
        assert v.witness_tool == pytest.approx((0.0, 5.0), abs=1e-12)
    assert cert.min_clearance == pytest.approx(0.0, abs=1e-12)
