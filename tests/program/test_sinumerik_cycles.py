"""SINUMERIK drilling cycles CYCLE81/CYCLE82, once and modally (MCALL).

Expected moves follow the cycles guide's sequence, written out here: rapid
along the tool axis to RFP + SDIS, feed to DP (or RFP - DPR), dwell DTB
(CYCLE82), rapid to RTP, at the position reached before the call. Generated
hole patterns called by MCALL read to the same moves as the same holes
drilled with G0/G1/G4 blocks written by the test.
"""
from __future__ import annotations

import random

import pytest

from ccopt import compensate, verify
from ccopt.program.model import Motion
from ccopt.program.sinumerik import read_sinumerik
from located import assert_refused_at


def read(text: str, **kw):
    return read_sinumerik(text, "d.mpf", **kw)


def moves(prog):
    return [(b.motion, tuple(round(c, 9) for c in b.end), b.feed, b.dwell, b.cycle)
            for b in prog.blocks]


R, L, D = Motion.RAPID, Motion.LINE, Motion.DWELL


def test_cycle81_at_the_position_reached_before():
    m = moves(read("G17 G90 G0 X10 Y10 Z20\nG1 F120\nCYCLE81(15, 0, 2, -5)\nX20\n"))
    assert m == [(R, (10, 10, 20), None, 0.0, None),
                 (R, (10, 10, 2), None, 0.0, "CYCLE81"),
                 (L, (10, 10, -5), 2.0, 0.0, "CYCLE81"),      # F120 = 2 mm/s
                 (R, (10, 10, 15), None, 0.0, "CYCLE81"),
                 # the calling program's G1 is in force again after the cycle
                 (L, (20, 10, 15), 2.0, 0.0, None)]


def test_dpr_wins_and_cycle82_dwells():
    m = moves(read("G0 X0 Y0 Z20\nG1 F60\nCYCLE82(10, 1, 1, -50, 4, 0.5)\n"))
    # RFP 1, DPR 4: depth -3 (not DP -50); the dwell at the depth
    assert [x[:2] for x in m[1:]] == [(R, (0, 0, 2)), (L, (0, 0, -3)), (D, (0, 0, -3)),
                                      (R, (0, 0, 10))]
    assert m[3][3] == 0.5


def test_mcall_runs_after_every_move_until_mcall_alone():
    text = ("G0 X10 Y10 Z20\nG1 F120\nMCALL CYCLE81(15, 0, 2, -5)\nG0 X20\nY20\nMCALL\n"
            "X0\n")
    m = moves(read(text))
    holes = [x[1][:2] for x in m if x[0] is L]
    assert holes == [(20, 10), (20, 20)]
    assert m[-1] == (R, (0, 20, 15), None, 0.0, None)


def test_other_planes_and_incremental_mode():
    # G18: the tool axis is Y; G91 in force: the cycle's values stay absolute
    m = moves(read("G18 G0 X5 Z5 Y30\nG91 G1 F60\nCYCLE81(20, 10, 1, 0)\nX1\n"))
    assert [x[1] for x in m[1:4]] == [(5, 11, 5), (5, 0, 5), (5, 20, 5)]
    assert m[4][1] == (6, 20, 5)


REFUSALS = {
    "deep hole": ("G0 X0 Y0 Z9\nCYCLE83(10, 0, 1, -20, , -5, , 2, 0, 0, 1, 0)\n", 2, 1,
                  "CYCLE81 and CYCLE82"),
    "pocket": ("POCKET3(10, 0, 1, -5, 20, 10)\n", 1, 1, "POCKET3"),
    "too many values": ("CYCLE81(1, 0, 1, -5, 0, 0, 0, 0, 0)\n", 1, 1, "at most 8"),
    "later parameter set": ("CYCLE81(10, 0, 1, -5, , 1)\n", 1, 1, "GMODE=1"),
    "depth above": ("G0 Z20\nCYCLE81(10, 0, 1, 5)\n", 2, 1, "below RFP + SDIS"),
    "with compensation on": ("T1 D1\nG41 G1 X1 F100\nCYCLE81(10, 0, 1, -5)\n", 3, 1,
                             "G40"),
    "with a move": ("G0 X1 CYCLE81(10, 0, 1, -5)\n", 1, 1, "block of its own"),
    "no parentheses": ("CYCLE81\n", 1, 8, "parentheses"),
    "negative dwell": ("G0 Z20\nG1 F100\nCYCLE82(10, 0, 1, -5, , -1)\n", 3, 1, "DTB"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    text, line, col, words = REFUSALS[name]
    assert_refused_at(read, text, ("d.mpf", line, col), words, tool_table={1: 2.0})


def test_drilling_then_a_contour_compensates_and_verifies():
    text = ("$TC_DP6[1,1]=2\nT1 D1\nG0 X50 Y20 Z10\nG1 F300\nMCALL CYCLE81(5, 0, 1, -4)\n"
            "G0 X20\nX30\nMCALL\nG0 X-10 Y-10\nG1 Z-2\nG42 X0 Y0\nX60\nY40\nX0\nY0\n"
            "G40 X-10 Y-10\nG0 Z10\nM30\n")
    prog = read(text)
    assert sum(b.cycle == "CYCLE81" for b in prog.blocks) == 6
    for style in ("siemens", "pmac"):
        path = compensate(prog, style=style)
        assert verify(path, prog).ok, style


# -- generated: hole patterns by MCALL against the same holes written out ----------
def hole_pair(seed: int):
    rng = random.Random(seed)
    rfp = round(rng.uniform(-5, 5), 3)
    sdis = round(rng.uniform(0.5, 3), 3)
    rtp = round(rfp + sdis + rng.uniform(0, 20), 3)
    dp = round(rfp - rng.uniform(1, 30), 3)
    dpr = rng.choice((None, round(rng.uniform(1, 20), 3)))
    dtb = rng.choice((None, round(rng.uniform(0.1, 2), 2)))
    depth = rfp - dpr if dpr else dp
    name = "CYCLE82" if dtb else "CYCLE81"
    args = [rtp, rfp, sdis, dp, "" if dpr is None else dpr] + ([dtb] if dtb else [])
    holes = [(round(rng.uniform(-80, 80), 3), round(rng.uniform(-80, 80), 3))
             for _ in range(rng.randint(1, 6))]
    head = [f"G0 X0 Y0 Z{rtp + 5}", f"G1 F{rng.choice((60, 150, 900))}"]
    called = head + [f"MCALL {name}({', '.join(str(a) for a in args)})"]
    called += [f"G0 X{x} Y{y}" for x, y in holes] + ["MCALL", "G0 X0 Y0"]
    written, tags = list(head), [None]
    for x, y in holes:
        written += [f"G0 X{x} Y{y}", f"Z{rfp + sdis}", f"G1 Z{depth}"]
        written += [f"G4 F{dtb}"] if dtb else []
        written += [f"G0 Z{rtp}"]
        tags += [None] + [name] * (4 if dtb else 3)
    written += ["G0 X0 Y0"]
    tags += [None]
    return "\n".join(called) + "\n", "\n".join(written) + "\n", tags


def _check_holes(seed: int) -> None:
    called, written, tags = hole_pair(seed)
    a, b = read(called), read(written)
    assert len(a.blocks) == len(b.blocks) == len(tags), (called, written)
    for x, y, tag in zip(a.blocks, b.blocks, tags):
        assert (x.motion, x.feed, x.dwell, x.cycle) == (y.motion, y.feed, y.dwell, tag)
        assert x.end == pytest.approx(y.end, abs=1e-9)


@pytest.mark.parametrize("seed", range(5))
def test_generated_hole_patterns(seed):
    _check_holes(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(5, 205))
def test_generated_hole_patterns_slow(seed):
    _check_holes(seed)
