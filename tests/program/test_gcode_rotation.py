"""Rotated coordinate systems (``G10 L2 R``), G28/G30 stored positions and
``G10 L1/L10/L11`` tool data, as LinuxCNC's ``interp_convert.cc`` runs them
(``convert_setup``, ``convert_axis_offsets``, ``convert_home``,
``convert_savehome``, ``convert_setup_tool``) and its canon applies them
(``emccanon.cc`` ``rotate_and_offset_pos``: machine = R (work + G92) + origin).

LinuxCNC's own ``tests/interp/g10`` tests are kept in
tests/conformance/linuxcnc/frames (GPL-2.0 data, see its README) and matched
move for move; the rest is geometry derived by hand, and a seeded property:
the compensated contour of a rotated system is the rotation of the
compensated contour.
"""
from __future__ import annotations

import math
import random
import re

import pytest

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.tooltable import read_tool_table
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

FRAMES = CONFORMANCE / "frames"
G10_TESTS = ["g10-l1-l10", "g10-l11", "g10-l2-while-active", "g10-l20-while-active",
             "g10-with-g92"]


def _close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


@pytest.mark.parametrize("name", G10_TESTS)
def test_linuxcnc_g10_tests_match_move_for_move(name):
    folder = FRAMES / name
    script = (folder / "test.sh").read_text()
    table = re.search(r"-t\s+(\S+)", script)
    path = folder / "test.ngc"
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    tools = read_tool_table(folder / table.group(1)) if table else None
    prog = read_gcode(path.read_text(), str(path), tool_table=tools)
    got = canonical_moves(compensate(prog, style="linuxcnc"))
    want = expected_moves(f"frames/{name}")
    assert [k for k, _ in got] == [k for k, _ in want]
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        assert all(abs(a[q] - b[q]) <= TOL for q in range(3)), (i, kind, a, b[:3])


def _ends(text, **kw):
    return [b.end for b in read_gcode(text, "t.ngc", **kw).blocks]


def test_rotated_system_moves_along_its_turned_axes():
    # G55 at (10, 5), turned 90 deg: work +X is machine +Y
    ends = _ends("G21 G10 L2 P2 X10 Y5 R90\nG55\nG0 X2 Y0 Z1\nG91 G1 X1 F100\n"
                 "G90 G1 Y3\n")
    assert _close(ends[0], (10.0, 7.0, 1.0))
    assert _close(ends[1], (10.0, 8.0, 1.0))      # G91 X1: one along the turned X
    assert _close(ends[2], (7.0, 8.0, 1.0))       # G90 Y3 keeps work X = 3


def test_rotated_arc_centre_words_turn_with_the_system():
    prog = read_gcode("G21 G10 L2 P1 X0 Y0 R90\nG54\nG0 X10 Y0\nG3 X0 Y10 I-10 J0 F100\n",
                      "t.ngc")
    arc = prog.blocks[1]
    assert _close(arc.start, (0.0, 10.0, 0.0)) and _close(arc.end, (-10.0, 0.0, 0.0))
    assert _close(arc.center[:2], (0.0, 0.0))


def test_g92_in_a_rotated_system_is_added_before_the_rotation():
    # LinuxCNC g10-with-g92: G92 X.1 Y.2 Z.3 at work (0, 0, -10) gives
    # G92_OFFSET(-0.1, -0.2, -10.3) whatever the rotation
    prog = read_gcode("G21 G10 L2 P1 X1 Y2 Z3 R10\nG54\nG0 X0 Y0 Z-10\nG92 X.1 Y.2 Z.3\n"
                      "G0 X.1 Y.2\n", "t.ngc")
    assert _close(prog.blocks[-1].end, prog.blocks[0].end)
    assert _close(prog.blocks[-1].frame.axis_offset, (-0.1, -0.2, -10.3))


def test_arc_in_g18_of_a_rotated_system_is_refused_located():
    with pytest.raises(ProgramError) as err:
        read_gcode("G21 G10 L2 P1 R30\nG54 G18\nG0 X0 Z0\nG2 X2 Z0 I1 K0 F100\n", "t.ngc")
    assert (err.value.line, err.value.col) == (4, 1)
    assert "rotated coordinate system" in str(err.value)


def test_r_with_g10_l20_is_refused_as_linuxcnc_does():
    with pytest.raises(ProgramError) as err:
        read_gcode("G21\nG10 L20 P1 X0 R30\n", "t.ngc")
    assert err.value.line == 2 and "R not allowed in G10 L20" in str(err.value)


def test_g28_goes_through_the_waypoint_to_the_stored_position():
    ends = _ends("G21 G0 X5 Y5 Z5\nG28.1\nG0 X20 Y0 Z0\nG28 Z3\nG30\n",
                 parameters={5181: 1.0, 5182: 2.0, 5183: 3.0})
    # G28 Z3: waypoint Z3 in work coordinates, then only Z to its stored 5
    assert ends[2:4] == [(20.0, 0.0, 3.0), (20.0, 0.0, 5.0)]
    # G30 with no axis word: a traverse where it stands, then all axes
    assert ends[4:6] == [(20.0, 0.0, 5.0), (1.0, 2.0, 3.0)]


def test_g28_with_compensation_on_is_refused():
    with pytest.raises(ProgramError) as err:
        read_gcode("G21 G0 X0 Y0\nG41.1 D2 G1 X5 F100\nG28\n", "t.ngc")
    assert err.value.line == 3 and "G28" in str(err.value)


def test_g10_l1_radius_is_the_radius_later_g41_compensates_with():
    prog = read_gcode("G21\nG10 L1 P3 R2.5 Z-10\nT3 M6\nG0 X0 Y-10\nG41 G1 X0 Y0 F100\n"
                      "G1 X20\nG40 G1 X20 Y-10\n", "t.ngc", tool_table={3: 1.0})
    assert prog.blocks[1].modal.radius == 2.5


def test_g10_l1_of_a_tool_not_in_the_table_is_refused_naming_it():
    with pytest.raises(ProgramError) as err:
        read_gcode("G21\nG10 L1 P7 R2\n", "t.ngc", tool_table={3: 1.0})
    assert (err.value.line, err.value.col) == (2, 8)
    assert "tool 7 not found in the tool table" in str(err.value)


def _contour(rng: random.Random) -> list[str]:
    """A random open contour of lines and R arcs about the origin, G17."""
    n = rng.randint(3, 7)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
    pts = [(rng.uniform(20, 40) * math.cos(a), rng.uniform(20, 40) * math.sin(a))
           for a in angles]
    out = [f"G1 X{pts[0][0]:.4f} Y{pts[0][1]:.4f}"]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        chord = math.hypot(x1 - x0, y1 - y0)
        if rng.random() < 0.4 and chord > 1:
            r = chord * rng.uniform(0.6, 2.0)
            out.append(f"G{rng.choice((2, 3))} X{x1:.4f} Y{y1:.4f} R{r:.4f}")
        else:
            out.append(f"G1 X{x1:.4f} Y{y1:.4f}")
    return out


def _program(rng: random.Random, turn: float, origin) -> str:
    side = rng.choice(("G41", "G42"))
    body = _contour(rng)
    return "\n".join([
        "G21 G17 G90 G94 F600",
        f"G10 L2 P2 X{origin[0]:.4f} Y{origin[1]:.4f} Z0 R{turn:.6f}",
        "G55", "G0 X0 Y0 Z5", "G1 Z-1",
        f"{side} D1 {body[0]}", *body[1:],
        "G40 G1 X0 Y0", "G0 Z5", "M2"]) + "\n"


def _check_rotated_equals_rotation(seed: int) -> bool:
    """The compensated path in a system turned ``turn`` about its origin is
    the unturned system's path turned about that origin; False when both
    refuse alike (a random contour the cutter cannot follow)."""
    rng = random.Random(seed)
    turn = round(rng.uniform(-180, 180), 6)
    origin = (round(rng.uniform(-50, 50), 4), round(rng.uniform(-50, 50), 4))
    text = _program(random.Random(seed + 1), turn, origin)
    plain = text.replace(f"R{turn:.6f}", "R0")
    table = {1: rng.uniform(0.5, 4.0)}
    results = []
    for t in (text, plain):
        try:
            results.append(compensate(read_gcode(t, "g.ngc", tool_table=table),
                                      style="linuxcnc"))
        except ProgramError as exc:
            results.append(str(exc))
    if isinstance(results[0], str) or isinstance(results[1], str):
        assert results[0] == results[1], seed
        return False
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))

    def rot(p):
        x, y = p[0] - origin[0], p[1] - origin[1]
        return (x * c - y * s + origin[0], x * s + y * c + origin[1])
    turned, flat = results[0].segments, results[1].segments
    assert len(turned) == len(flat), seed
    for i, (a, b) in enumerate(zip(turned, flat)):
        assert a.kind == b.kind and a.role == b.role, seed
        # the program starts at machine zero, in no system: its first move's start
        assert i == 0 or _close(a.start, rot(b.start), 1e-7), seed
        assert _close(a.end, rot(b.end), 1e-7), seed
        if a.kind == "arc":
            assert _close(a.geom.center, rot(b.geom.center), 1e-7), seed
            assert abs(a.geom.sweep - b.geom.sweep) <= 1e-9, seed
    return True


@pytest.mark.parametrize("seed", range(5))
def test_rotated_compensation_is_the_rotated_compensation_quick(seed):
    _check_rotated_equals_rotation(seed)


@pytest.mark.slow
def test_rotated_compensation_is_the_rotated_compensation_generated():
    compared = sum(_check_rotated_equals_rotation(seed) for seed in range(100, 400))
    assert compared >= 150
