"""A program's blocks as columns (:func:`ccopt.program.columns.columns_of`,
issue 34): read once, kept with the program, and equal, field by field, to
what each block says.

Over generated CAM plates in every dialect the plates are written in
(G-code, PMAC, SINUMERIK, HEIDENHAIN Klartext), with dwells, Z moves and arcs,
and over hand-written programs with PMAC move times and several modal states.
The quick tier reads 8 plates, the slow tier 200.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cam_programs import cam_program
from family_programs import family_program
from ccopt.program import read_text
from ccopt.program.columns import MOTIONS, BlockColumns, columns_of
from ccopt.program.model import Motion

QUICK = range(8)
SLOW = range(8, 208)


def _generated(seed: int):
    """Plate ``seed`` in G-code or PMAC (even seeds, :func:`cam_program`) or
    SINUMERIK or Klartext (odd seeds, :func:`family_program`)."""
    if seed % 2 == 0:
        cp = cam_program(seed)
        return read_text(cp.text, cp.file, cp.dialect)
    fp = family_program(seed, "sinumerik" if seed % 4 == 1 else "heidenhain")
    return read_text(fp.text, fp.file, fp.dialect)


def _check(prog) -> BlockColumns:
    """The columns equal the blocks' own fields, read one block at a time."""
    blocks = prog.blocks
    cols = columns_of(prog)
    assert columns_of(prog) is cols                       # read once, kept
    assert len(cols) == len(blocks)
    assert cols.motions == tuple(b.motion for b in blocks)
    assert [MOTIONS[c] for c in cols.motion_code.tolist()] == [b.motion for b in blocks]
    assert cols.is_arc.tolist() == [b.motion in (Motion.ARC_CW, Motion.ARC_CCW)
                                    for b in blocks]
    assert all(m is b.modal for m, b in zip(cols.modals, blocks))
    want_start = np.array([b.start for b in blocks], float).reshape(-1, 3)
    want_end = np.array([b.end for b in blocks], float).reshape(-1, 3)
    assert np.array_equal(cols.start, want_start) and np.array_equal(cols.end, want_end)
    # a new run wherever the modal object changes
    firsts = [q for q in range(len(blocks)) if q == 0 or blocks[q].modal is not blocks[q - 1].modal]
    assert cols.modal_first.tolist() == firsts
    assert cols.modal_runs().sum() == len(blocks)
    assert cols.timed == any(b.move_time is not None for b in blocks)
    for arr in (cols.motion_code, cols.start, cols.end, cols.modal_first):
        assert not arr.flags.writeable
    return cols


@pytest.mark.parametrize("seed", QUICK)
def test_columns_equal_the_blocks(seed):
    _check(_generated(seed))


@pytest.mark.slow
@pytest.mark.parametrize("seed", SLOW)
def test_columns_equal_the_blocks_generated(seed):
    _check(_generated(seed))


def test_columns_of_a_program_with_move_times_dwells_and_several_modal_states():
    text = "\n".join([
        "CCR2", "LINEAR", "F10", "X0 Y0", "CC1", "X10", "DWELL 100", "Z-1",
        "CIRCLE1 X20 Y10 I0 J10", "LINEAR", "CCR3", "X20 Y30", "CC0", "TM 500", "X0 Y30"])
    prog = read_text(text, "t.pmc", "pmac")
    cols = _check(prog)
    assert cols.timed
    assert Motion.DWELL in cols.motions and cols.is_arc.any()
    assert len(cols.modal_first) >= 3                 # CC1, CCR3, CC0 each start a run


def test_a_replaced_program_reads_its_own_columns():
    prog = read_text("G1 X1 Y0 F100\nG1 X1 Y1\n", "a.nc", "gcode")
    first = columns_of(prog)
    other = dataclasses.replace(prog, blocks=prog.blocks[:1])
    assert columns_of(other) is not first and len(columns_of(other)) == 1
    assert prog == dataclasses.replace(prog)           # the kept columns are no field


def test_an_empty_program_has_empty_columns():
    cols = _check(read_text("(nothing)\n", "e.nc", "gcode"))
    assert len(cols) == 0 and cols.start.shape == (0, 3) and not cols.timed
