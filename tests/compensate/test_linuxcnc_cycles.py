"""LinuxCNC's own canned-cycle tests (``tests/interp/g81`` and ``g84``, kept in
tests/conformance/linuxcnc/cycles with their licence): each program read as
its ``test.sh`` runs ``rs274`` and compensated in the ``linuxcnc`` style gives
the STRAIGHT_TRAVERSE and STRAIGHT_FEED calls of LinuxCNC's ``expected``
canon, move for move within 5e-5, and its DWELL calls. G84 outside G17 is
refused, located, for the reason docs/gcode.md gives (LinuxCNC feeds to a
permuted point there: its ``expected`` records that feed off the hole).
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
REFUSED = {r for r in RUNS if r.startswith("g84") and "g17" not in r}


def _program(run: str):
    folder = CYCLES / run
    script = (folder / "test.sh").read_text()
    name = re.search(r"-g\s+(\S+\.ngc)", script).group(1)
    path = folder / name
    if not path.is_file():
        pytest.fail(f"LinuxCNC conformance data missing: {path}")
    return path


@pytest.mark.parametrize("run", [r for r in RUNS if r not in REFUSED])
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


@pytest.mark.parametrize("run", sorted(REFUSED))
def test_g84_outside_g17_is_refused_at_its_first_cycle(run):
    path = _program(run)
    lines = path.read_text().splitlines()
    first = next(n for n, ln in enumerate(lines, 1) if ln.lower().startswith("g84"))
    with pytest.raises(ProgramError) as err:
        read_gcode(path.read_text(), str(path))
    assert err.value.line == first and err.value.col == 1
    assert "plane is not supported" in str(err.value)
