"""Moves synchronised to the spindle (G33 threading, G76's cuts) are exported
as G33 with their pitch, never as plain G1 feeds, which would cut without the
synchronisation; rigid tapping and PMAC exports, which cannot keep it, are
refused with the place. Pitches are the programs' own (K, P, and G76's taper
pitch P*hypot(E, K)/E worked out here)."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.errors import ProgramError
from ccopt.program import read_program

THREAD = ("G18 G21\nS600 M3\nG0 X12 Z5\nG1 X10 F300\nG33 Z-20 K1.5\nG0 X12\nZ5\n"
          "G76 P2 Z-20 I-1 J0.5 K1.2 E2 L2\nM5\nM30\n")


@pytest.fixture
def thread(tmp_path):
    (tmp_path / "thread.ngc").write_text(THREAD)
    return tmp_path


def _synchronised(prog):
    return [(b.end, b.per_revolution, round(b.feed, 9)) for b in prog.blocks
            if b.per_revolution is not None]


def test_threads_export_as_g33_with_their_pitch_and_read_back_the_same(thread):
    prog = read_program(thread / "thread.ngc")
    pitches = sorted({round(b.per_revolution, 12) for b in prog.blocks
                      if b.per_revolution is not None})
    taper = 2 * math.hypot(2, 1.2) / 2                 # G76 P2 E2 K1.2
    assert pitches == pytest.approx(sorted([1.5, 2.0, taper]))
    path = ccopt.compensate(prog, style="linuxcnc")
    res = ccopt.export(path, thread / "out.ngc", program=prog)
    assert res.verified
    text = (thread / "out.ngc").read_text()
    assert "G33 Z-20 X10 Y0 K1.5" in text               # G18 writes Z X Y
    g33 = [ln for ln in text.splitlines() if ln.startswith("G33")]
    assert len(g33) == len(_synchronised(prog))
    back = read_program(thread / "out.ngc")
    assert _synchronised(back) == [(pytest.approx(e), pytest.approx(k), pytest.approx(f))
                                   for e, k, f in _synchronised(prog)]


def test_rigid_tapping_and_pmac_exports_are_refused_where_they_cannot_keep_it(thread):
    tap = thread / "tap.ngc"
    tap.write_text("G17 G21\nS500 M3\nG0 X0 Y0 Z2\nG33.1 Z-10 K1.25\nM30\n")
    prog = read_program(tap)
    with pytest.raises(ProgramError, match="rigid tapping") as err:
        ccopt.export(ccopt.compensate(prog, style="linuxcnc"), thread / "t.ngc", program=prog)
    assert (err.value.line, err.value.col) == (4, 1) and not (thread / "t.ngc").exists()
    prog = read_program(thread / "thread.ngc")
    with pytest.raises(ProgramError, match="PMAC") as err:
        ccopt.export(ccopt.compensate(prog, style="linuxcnc"), thread / "t.pmc", program=prog)
    assert err.value.line == 5 and not (thread / "t.pmc").exists()
