"""LinuxCNC's own cutter-compensation tests beyond crazy-paths, run through
the ``linuxcnc`` style with their own tool tables: the tool path is the
sequence of canonical moves LinuxCNC's interpreter prints in ``expected``,
move for move, every end point, centre and Z within 5e-5 (``expected``
prints 4 decimals); the programs LinuxCNC refuses are refused (exit 2) for
the same reason. Data and licence: tests/conformance/linuxcnc/README.md.
"""
from __future__ import annotations

import pytest

from ccopt.cli import main
from ccopt.compensate import compensate
from ccopt.program.gcode import read_gcode
from ccopt.program.tooltable import read_tool_table
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

# G20 programs whose tables are in inches (LinuxCNC's stand-alone
# interpreter runs in inches): two G17 mill tests and the G18 lathe test,
# whose tools Q2 and Q7 put the controlled point at the imaginary tip.
MILL_TESTS = ("mill-line-arc-entry", "mill-zchanges", "lathe-comp")


def _ours(folder: str):
    d = CONFORMANCE / folder
    table = read_tool_table(d / "test.tbl")
    prog = read_gcode((d / "test.ngc").read_text(), str(d / "test.ngc"), tool_table=table)
    return canonical_moves(compensate(prog, style="linuxcnc"))


def _differences(got, want) -> list[str]:
    """Every move whose kind, end point, centre, Z or turn differs from
    LinuxCNC's by more than TOL, in words."""
    assert [k for k, _ in got] == [k for k, _ in want]
    problems = []
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        # straight: x, y, z; arc: end, centre, turn, z (index 5)
        fields = (0, 1, 2) if kind != "ARC_FEED" else (0, 1, 2, 3, 5)
        problems += [f"move {i} ({kind}) field {q}: ccopt {a[q]:.6f}, LinuxCNC {b[q]:.4f}"
                     for q in fields if not abs(a[q] - b[q]) <= TOL]
        if kind == "ARC_FEED" and int(a[4]) != int(b[4]):
            problems.append(f"move {i} turn: ccopt {a[4]}, LinuxCNC {b[4]}")
    return problems


@pytest.mark.parametrize("folder", MILL_TESTS)
def test_program_matches_linuxcnc_move_for_move(folder):
    got, want = _ours(folder), expected_moves(folder)
    problems = _differences(got, want)
    assert not problems, "\n".join(problems)


def test_inside_corners_matches_linuxcnc_in_g17_and_then_g18():
    """LinuxCNC's inside-corners test (tests/interp/inside-corners): the same
    path of concave, convex and tangent joins with G41.1 D0, D-0.15 and
    D0.15, in G17 and then, after G40, in G18 (no tool table: the diameters
    are in the program). Every move matches LinuxCNC's, both planes'."""
    d = CONFORMANCE / "inside-corners"
    path = compensate(read_gcode((d / "test.ngc").read_text(), str(d / "test.ngc")),
                      style="linuxcnc")
    want = expected_moves("inside-corners")
    problems = _differences(canonical_moves(path), want)
    assert not problems, "\n".join(problems)
    planes = [seg.plane for seg in path.segments]
    # three passes of 39 compensated moves (and their corners) in each plane, XY first
    assert planes[0] == "XY" and planes[-1] == "ZX"
    assert planes.count("ZX") > 3 * 39 and planes.count("XY") > 3 * 39
    assert planes == sorted(planes, key=["XY", "ZX"].index)


def test_zchanges_arc_entry_with_z_move_is_linuxcncs_arc():
    """mill-zchanges, second pass: G41 G2 D2 (tool 2, D0.125, r 0.0625) from
    (0.25, 0.5) to (0.5, 0.75) about (0.5, 0.5): LinuxCNC's entry arc ends at
    the offset end (0.5, 0.75 + r) = (0.5, 0.8125) about a centre on the
    perpendicular bisector of its chord, (0.5, 0.5562)."""
    kind, a = _ours("mill-zchanges")[8]
    assert kind == "ARC_FEED"
    assert a[:2] == pytest.approx([0.5, 0.75 + 0.0625], abs=TOL)
    # the centre is equidistant from both ends
    (x0, y0), (x1, y1), (cx, cy) = (0.25, 0.5), a[:2], a[2:4]
    assert (x0 - cx) ** 2 + (y0 - cy) ** 2 == pytest.approx((x1 - cx) ** 2 + (y1 - cy) ** 2)
    assert (cx, cy) == pytest.approx((0.5, 0.5562), abs=TOL)


@pytest.mark.parametrize("name, reason", [
    ("ccomp-arcexit", "must be straight, not an arc"),
    ("ccomp-gouging", "cannot be reached by the tool without gouging"),
])
def test_programs_linuxcnc_refuses_are_refused(name, reason, capsys):
    program = CONFORMANCE / "bad" / f"{name}.ngc"
    theirs = (CONFORMANCE / "bad" / f"{name}.expected-error").read_text()
    assert reason in theirs  # the reason below is LinuxCNC's own
    code = main(["compensate", str(program), "--style", "linuxcnc"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith(f"{program}:") and reason in err
    assert len(err.strip().splitlines()) == 1


def test_lathe_tip_is_the_nose_centre_moved_by_the_orientation():
    """lathe-comp, tool 2 (D0.1, r 0.05, Q2): the first compensated arc, G3 to
    X0 Z0.1 about (Z0.1, X0.1) with R0.1, has its nose centre on the circle
    of radius 0.1 - 0.05 about the same point; Q2 moves X and Z by -r, so the
    controlled point's arc is about (Z0.05, X0.05) and ends at (Z0.05, X0)."""
    moves = _ours("lathe-comp")
    kind, a = moves[10]
    assert kind == "ARC_FEED"
    assert a[:4] == pytest.approx([0.1 - 0.05 - 0.0, 0.0, 0.1 - 0.05, 0.1 - 0.05], abs=TOL)


def test_lathe_path_verifies_and_exports(tmp_path, capsys):
    d = CONFORMANCE / "lathe-comp"
    args = [str(d / "test.ngc"), "--style", "linuxcnc", "--tool-table", str(d / "test.tbl")]
    assert main(["verify", *args]) == 0        # the nose centre keeps r from the part
    out = tmp_path / "lathe.nc"
    assert main(["export", *args, "-o", str(out)]) == 0
    assert "verified OK" in capsys.readouterr().out
    assert "G18" in out.read_text()


@pytest.mark.parametrize("folder", MILL_TESTS)
def test_linuxcnc_tests_verify(folder):
    """Every pass of LinuxCNC's own tests keeps the radius offset, the radius-0
    passes of mill-zchanges (G41 D0) included."""
    d = CONFORMANCE / folder
    assert main(["verify", str(d / "test.ngc"), "--style", "linuxcnc",
                 "--tool-table", str(d / "test.tbl")]) == 0


def test_a_metric_program_takes_its_tool_table_in_inches_as_rs274_does():
    """cam-nisley (tests/interp/cam-nisley): a G21 program compensated with
    `G42 D1` from `test.tbl`'s T1 D0.0625, which rs274 without an INI reads in
    inches (1.5875 mm, r 0.79375): its entry arc of radius 1.6 about
    (0, -10.475) becomes one of 1.6 - 0.79375 = 0.80625 (ends at x -0.8063,
    then (0, -9.6687)). Every one of its 317 moves matches LinuxCNC's."""
    d = CONFORMANCE / "cam-nisley"
    prog = read_gcode((d / "cam.ngc").read_text(), str(d / "cam.ngc"),
                      tool_table=read_tool_table(d / "test.tbl"), table_units="inch")
    got, want = canonical_moves(compensate(prog, style="linuxcnc")), expected_moves("cam-nisley")
    assert len(got) == len(want) == 317
    assert got[2][0] == "STRAIGHT_FEED"   # after the traverses to Z10 and to the start
    assert got[2][1][0] == pytest.approx(-(1.6 - 0.0625 * 25.4 / 2), abs=1e-12)
    problems = _differences(got, want)
    assert not problems, "\n".join(problems)
