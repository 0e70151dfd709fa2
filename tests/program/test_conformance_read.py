"""LinuxCNC conformance: reading `crazy-paths/test.ngc` reproduces the programmed
moves LinuxCNC's own interpreter prints in `expected` (uncompensated calls), and
the compensation state of the compensated calls.

The data is kept in ``tests/conformance/linuxcnc`` (source and licence in its
README). A missing copy is a failure, not a skip.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion
from linuxcnc_data import N_CALLS, TOL, data_file, expected_calls


def _data(name: str) -> Path:
    return data_file(name)


def _expected_calls() -> list[list[tuple[str, object]]]:
    return expected_calls(comments=True)


@pytest.fixture(scope="module")
def program():
    path = _data("test.ngc")
    return read_gcode(path.read_text(), str(path))


@pytest.fixture(scope="module")
def calls(program):
    out = []
    for block in program.blocks:
        if block.motion is Motion.RAPID:
            out.append([block])
        else:
            assert out, f"line {block.source.line}: a move before the first rapid"
            out[-1].append(block)
    return out


def test_every_call_is_expanded(calls):
    expected = _expected_calls()
    assert len(expected) == N_CALLS, "expected output should hold 25 paths x 3 radii"
    assert len(calls) == N_CALLS, f"read {len(calls)} calls (split at rapids), want {N_CALLS}"


def test_uncompensated_calls_match_linuxcnc(calls):
    expected = _expected_calls()
    checked_moves = 0
    for k in range(0, N_CALLS, 3):  # #1 = 0: the first of every three calls
        got, want = calls[k], [e for e in expected[k] if e[0] != "COMMENT"]
        assert len(got) == len(want), (
            f"call {k}: {len(got)} blocks read, LinuxCNC emits {len(want)} canonical moves")
        for i, (block, (kind, nums)) in enumerate(zip(got, want)):
            where = f"call {k} move {i} (line {block.source.line})"
            if kind == "STRAIGHT_TRAVERSE":
                assert block.motion is Motion.RAPID, f"{where}: {block.motion} vs {kind}"
            elif kind == "STRAIGHT_FEED":
                assert block.motion is Motion.LINE, f"{where}: {block.motion} vs {kind}"
            else:
                assert block.motion.is_arc, f"{where}: {block.motion} vs {kind}"
                turn = int(nums[4])
                want_motion = Motion.ARC_CCW if turn > 0 else Motion.ARC_CW
                assert block.motion is want_motion, f"{where}: {block.motion} vs turn {turn}"
                assert abs(turn) == block.turns + 1, f"{where}: turns {block.turns} vs {turn}"
                cx, cy = nums[2], nums[3]
                assert math.isclose(block.center[0], cx, abs_tol=TOL) and \
                    math.isclose(block.center[1], cy, abs_tol=TOL), (
                    f"{where}: centre {block.center[:2]} vs LinuxCNC ({cx}, {cy})")
                assert block.modal.plane == "XY"
            ex, ey = nums[0], nums[1]
            assert math.isclose(block.end[0], ex, abs_tol=TOL) and \
                math.isclose(block.end[1], ey, abs_tol=TOL), (
                f"{where}: end {block.end[:2]} vs LinuxCNC ({ex}, {ey})")
            assert block.modal.side == 0, f"{where}: compensation should be off"
            if kind != "STRAIGHT_TRAVERSE":
                assert block.feed == pytest.approx(100.0 / 60.0), f"{where}: F100 -> 100/60 mm/s"
            checked_moves += 1
    assert checked_moves == sum(len([e for e in expected[k] if e[0] != "COMMENT"])
                                for k in range(0, N_CALLS, 3))


@pytest.mark.parametrize("offset, side, word", [(1, -1, "right"), (2, +1, "left")])
def test_compensated_calls_carry_side_and_radius(calls, offset, side, word):
    """#1 = -0.5 -> G41.1 D-0.5: right, r 0.25; #1 = 0.5 -> left, r 0.25."""
    expected = _expected_calls()
    for k in range(offset, N_CALLS, 3):
        comments = [e[1] for e in expected[k] if e[0] == "COMMENT"]
        assert f"interpreter: cutter radius compensation on {word}" in comments, (
            f"call {k}: LinuxCNC's expected output should switch compensation on {word}")
        blocks = calls[k]
        on = [b for b in blocks if b.modal.side != 0]
        # rapid (off), then the five path moves (on), then the G40 lead-out (off)
        assert [b.modal.side != 0 for b in blocks] == [False] + [True] * (len(blocks) - 2) + [False], (
            f"call {k}: compensation state per block "
            f"{[(b.source.line, b.modal.side) for b in blocks]}")
        for i, b in enumerate(on):
            assert b.modal.side == side, f"call {k} move {i + 1}: side {b.modal.side}, want {side}"
            assert b.modal.radius == pytest.approx(0.25), (
                f"call {k} move {i + 1}: radius {b.modal.radius}, want 0.25")
            assert b.modal.tool is None
        # The programmed path is the same as in the uncompensated call.
        base = calls[k - offset]
        assert [b.end for b in blocks] == [b.end for b in base], f"call {k}: programmed ends differ"
        assert [b.center for b in blocks] == [b.center for b in base]


def test_blocks_point_at_subroutine_lines(program):
    lines = _data("test.ngc").read_text().splitlines()
    for b in program.blocks:
        text = lines[b.source.line - 1].strip().upper()
        assert text.startswith("G"), f"block of line {b.source.line} points at {text!r}"
        assert b.source.col == 1
        if b.motion is Motion.RAPID:
            assert text.startswith("G0 ")
    # the first move of the first call is written on line 7: "g90 g1 y-102.000000"
    assert program.blocks[1].source.line == 7
    assert program.units == "mm"
