"""LinuxCNC lathe compensation: the imaginary tool tip (interp_queue.cc,
latheorigin_x/latheorigin_z), G41.1/G42.1 L<orientation>, and the plane rule
of convert_cutter_compensation_on."""
from __future__ import annotations

import pytest

from ccopt.compensate import compensate
from ccopt.compensate.lathe import tip_offset
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.tooltable import read_tool_table
from ccopt.toolpath import Role, tool_centre_path

# LinuxCNC: x -= r for Q 2, 6, 1; x += r for Q 3, 8, 4;
#           z -= r for Q 2, 7, 3; z += r for Q 1, 5, 4; nothing for 0 and 9.
LATHEORIGIN = {0: (0, 0), 1: (-1, 1), 2: (-1, -1), 3: (1, -1), 4: (1, 1), 5: (0, 1),
               6: (-1, 0), 7: (0, -1), 8: (1, 0), 9: (0, 0)}


@pytest.mark.parametrize("q", range(10))
def test_tip_offset_is_linuxcncs(q):
    dx, dz = tip_offset(q, 0.25)
    assert (dx, dz) == (0.25 * LATHEORIGIN[q][0], 0.25 * LATHEORIGIN[q][1])


def test_g41_1_l_orientation_moves_the_compensated_moves():
    # G18, a face cut along -X at Z0 with a Q7 tool of r 0.5 on the left:
    # in G18's plane (u, v) = (Z, X) travel (0, -1) has its left at (1, 0),
    # +Z, so the nose centre runs at Z+0.5 and Q7 moves Z by -r: the tip runs
    # on the face, Z0
    prog = read_gcode("G18 G21 F600\nG0 X10 Z2\nG1 Z0\nG41.1 D1 L7 G1 X8\nG1 X0\n"
                      "G40 G1 Z2\n")
    path = compensate(prog, style="linuxcnc")
    along = [s for s in path.segments if s.role is Role.COMPENSATED]
    assert along and all(s.geom.start[0] == pytest.approx(0.0) for s in along)
    assert along[-1].geom.end == pytest.approx((0.0, 0.0))   # (Z, X)
    centre = tool_centre_path(path)
    back = [s for s in centre.segments if s.role is Role.COMPENSATED]
    assert all(s.geom.start[0] == pytest.approx(0.5) for s in back)


def test_a_lathe_tool_compensates_in_g18_only():
    table = read_tool_table("T2 P2 D0.1 Q2\n")
    with pytest.raises(ProgramError, match="lathe tool .*not G18"):
        read_gcode("G17 G20 F30\nT2 M6\nG41 G1 X1\n", tool_table=table)
    with pytest.raises(ProgramError, match="not G18"):
        read_gcode("G17 G21 F600\nG41.1 D1 L2 G1 X1\n")
    block = read_gcode("G18 G20 F30\nT2 M6\nG41 G1 X1\n", tool_table=table).blocks[0]
    assert block.modal.orientation == 2
