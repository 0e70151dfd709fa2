"""Axes A B C U V W read and carried (``ccopt/program/gcode/axes.py``): their
positions through G90/G91, origins, G92/G52, G53 and G28, as LinuxCNC's
interpreter computes them, kept on each block and written back by exports.

LinuxCNC's ``rotation/g28``, ``rotation/g53``, ``unit-conversion`` and
``exists`` tests (tests/conformance/linuxcnc, GPL-2.0 data) match move for
move with their A B C; the rest is derived by hand, and a seeded property:
an export reads back to the same A B C U V W on every block.
"""
from __future__ import annotations

import random

import pytest

import ccopt
from ccopt.compensate import compensate
from ccopt.program.gcode import read_gcode
from ccopt.program.model import AXES_USED
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

TESTS = [("frames/g28", "g28.ngc"), ("frames/g53", "g53.ngc"),
         ("frames/unit-conversion", "test.ngc"), ("oword/exists", "test.ngc")]


@pytest.mark.parametrize("folder, name", TESTS)
def test_linuxcnc_tests_with_a_match_move_for_move_with_abc(folder, name):
    path = CONFORMANCE / folder / name
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    got = canonical_moves(compensate(read_gcode(path.read_text(), str(path)),
                                     style="linuxcnc"))
    want = expected_moves(folder)
    assert [k for k, _ in got] == [k for k, _ in want]
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        assert all(abs(a[q] - b[q]) <= TOL for q in range(6)), (i, kind, a, b[:6])


def _axes(text: str) -> list[tuple[float, ...]]:
    return [b.axes for b in read_gcode(text, "t.ngc").blocks]


def test_extra_axes_through_modes_origins_offsets_and_g53():
    axes = _axes("G21 G10 L2 P1 A10 U1\nG54\nG0 X1 A5 U2\nG91 G0 A5 U-1\nG90 G92 A0\n"
                 "G0 A1\nG53 G0 A0\nG92.1\nG0 A0\n")
    assert [a[0] for a in axes] == [15.0, 20.0, 21.0, 0.0, 10.0]
    assert [a[3] for a in axes] == [3.0, 2.0, 2.0, 2.0, 2.0]


def test_u_v_w_are_lengths_a_b_c_angles():
    # G20: U1 is 25.4 mm in an mm output; A1 stays one degree
    axes = _axes("G21 G0 X0\nG20 G0 U1 A1\n")
    assert axes[-1][0] == 1.0 and axes[-1][3] == pytest.approx(25.4)


def test_g28_sends_only_the_written_extra_axes_home():
    axes = _axes("G21 G0 A30 B40\nG28.1\nG0 A1 B2\nG28 A5\n")
    # waypoint A5 then A home (30); B stays where the waypoint left it
    assert axes[-2][:2] == (5.0, 2.0) and axes[-1][:2] == (30.0, 2.0)


def test_no_extra_axis_no_axes():
    prog = read_gcode("G21 G0 X1 Y2\n", "t.ngc")
    assert prog.blocks[0].axes is None and AXES_USED not in prog.meta


def _program(rng: random.Random) -> str:
    lines = ["G21 G17 G90 G94 F600", f"G10 L2 P1 X0 Y0 Z0 A{rng.uniform(-90, 90):.3f}", "G54"]
    for _ in range(rng.randint(3, 12)):
        r = rng.random()
        words = f"X{rng.uniform(-50, 50):.3f} Y{rng.uniform(-50, 50):.3f}"
        for a in rng.sample("ABCUVW", rng.randint(0, 2)):
            words += f" {a}{rng.uniform(-100, 100):.3f}"
        if r < 0.15:
            lines.append(f"G92 A{rng.uniform(-10, 10):.3f}")
        elif r < 0.25:
            lines.append(f"G91 G1 A{rng.uniform(-10, 10):.3f}\nG90")
        lines.append(f"G{rng.choice((0, 1))} {words}")
    return "\n".join(lines + ["M30"]) + "\n"


def _check_export_keeps_the_axes(seed: int, tmp_path) -> None:
    rng = random.Random(seed)
    src = tmp_path / f"p{seed}.ngc"
    src.write_text(_program(rng))
    prog = ccopt.read_program(src)
    path = ccopt.compensate(prog, style="linuxcnc")
    out = tmp_path / f"o{seed}.nc"
    ccopt.export(path, out, program=prog)
    back = ccopt.read_program(out)
    want = [b.axes for b in prog.blocks]
    got = [b.axes for b in back.blocks if b.motion.is_move]
    # the export may add a positioning move first
    got = got[len(got) - len(want):]
    for a, b in zip(want, got):
        if a is None:
            continue
        assert b is not None and all(abs(x - y) <= 1e-6 for x, y in zip(a, b)), seed


@pytest.mark.parametrize("seed", range(5))
def test_export_keeps_the_extra_axes_quick(seed, tmp_path):
    _check_export_keeps_the_axes(seed, tmp_path)


@pytest.mark.slow
def test_export_keeps_the_extra_axes_generated(tmp_path):
    for seed in range(100, 400):
        _check_export_keeps_the_axes(seed, tmp_path)
