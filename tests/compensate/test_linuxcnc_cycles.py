"""LinuxCNC's own canned-cycle tests (``tests/interp/g81``, ``g84`` and ``g76``,
kept in tests/conformance/linuxcnc/cycles with their licence): each program
read as its ``test.sh`` runs ``rs274`` and compensated in the ``linuxcnc``
style gives the STRAIGHT_TRAVERSE and STRAIGHT_FEED calls of LinuxCNC's
``expected`` canon, move for move within 5e-5, and its DWELL calls. G84
outside G17 included: LinuxCNC feeds to a permuted point there (its
``expected`` records that feed off the hole), and so does ccopt, with a note.
"""
from __future__ import annotations

import re

import pytest

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

CYCLES = CONFORMANCE / "cycles"
RUNS = [f"{cycle}/{plane}/{mode}" for cycle in ("g81", "g84")
        for plane in ("g17", "g18", "g19") for mode in ("g98", "g99")]
RUNS.append("g76")


def _program(run: str):
    folder = CYCLES / run
    script = (folder / "test.sh").read_text()
    name = re.search(r"-g\s+(\S+\.ngc)", script).group(1)
    path = folder / name
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    return path


@pytest.mark.parametrize("run", RUNS)
def test_cycle_program_matches_linuxcnc_move_for_move(run):
    path = _program(run)
    prog = read_gcode(path.read_text(), str(path))
    got = canonical_moves(compensate(prog, style="linuxcnc"))
    want = expected_moves(f"cycles/{run}")
    assert [k for k, _ in got] == [k for k, _ in want]
    for i, ((kind, a), (_, b)) in enumerate(zip(got, want)):
        assert all(abs(a[q] - b[q]) <= TOL for q in range(3)), (i, kind, a, b[:3])
    dwells = [float(m) for m in re.findall(r"DWELL\(([-\d.]+)\)",
                                           (CYCLES / run / "expected").read_text())]
    assert [b.dwell for b in prog.blocks if b.motion.value == "dwell"] == dwells
