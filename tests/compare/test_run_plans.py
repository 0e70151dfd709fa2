"""Plans of runs of stretches kept by their signature (ccopt.compare.timing):
on generated programs, a run's figures taken from the kept plans are those
planned afresh, and runs of other controller styles' paths share a plan
only where every number they are planned from is the same."""
from __future__ import annotations

import random
from collections import OrderedDict
from dataclasses import replace

import pytest

import ccopt
from ccopt.compare import timing
from ccopt.compare.timing import StretchTimes, run_signature, stretches
from ccopt.feed import ExactPath
from ccopt.geometry import Line
from ccopt.toolpath import PathSegment, Role, ToolPath
from tests.cam_programs import cam_program

LIMITS = ccopt.AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0))
STYLES = ("pmac", "linuxcnc", "fagor", "heidenhain")


@pytest.mark.parametrize("seed", [3, 11, 27])
def test_kept_run_plans_are_the_fresh_ones(seed, monkeypatch):
    monkeypatch.setattr(timing, "_RUN_PLANS", OrderedDict())
    cp = cam_program(seed)
    prog = ccopt.read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    rng = random.Random(seed)
    runs = []
    for style in STYLES:
        exact = ExactPath(ccopt.compensate(prog, style))
        parts = stretches(exact)
        for _ in range(3):
            i = rng.randrange(len(parts))
            runs.append((exact, parts[i:rng.randrange(i, min(len(parts), i + 4)) + 1]))
        runs.append((exact, parts[:1]))         # the lead-in, alike in several styles
    for exact, run in runs:
        fresh = StretchTimes(LIMITS)._plan_run_afresh(exact, run)
        assert StretchTimes(LIMITS)._plan_run(exact, run) == fresh
        assert StretchTimes(LIMITS)._plan_run(exact, run) == fresh      # kept, the same
    signatures = [run_signature(exact, run, LIMITS, None) for exact, run in runs]
    assert len(timing._RUN_PLANS) == len(set(signatures))
    # another ts or other limits are another plan
    exact, run = runs[0]
    assert run_signature(exact, run, LIMITS, 0.002) != signatures[0]
    assert run_signature(exact, run, replace(LIMITS, v=(150.0, 200.0, 100.0)),
                         None) != signatures[0]


def _path(x0: float, feed: float = 50.0, block=None) -> ToolPath:
    return ToolPath((PathSegment(Line((x0, 0.0), (10.0, 0.0)), Role.COMPENSATED, block,
                                 feed=feed),
                     PathSegment(Line((10.0, 0.0), (10.0, 10.0)), Role.COMPENSATED, block,
                                 feed=feed)))


def _signature(path: ToolPath):
    exact = ExactPath(path)
    return run_signature(exact, stretches(exact)[:1], LIMITS, None)


def test_signatures_tell_numbers_by_their_bits_and_leave_blocks_out():
    assert _signature(_path(0.0)) == _signature(_path(0.0))
    assert _signature(_path(0.0)) != _signature(_path(-0.0))     # equal, not the same bits
    assert _signature(_path(0.0)) != _signature(_path(0.0, feed=50.000000001))
    prog = ccopt.read_text("G1 X10 F600\n", "a.ngc", "gcode")
    assert _signature(_path(0.0, block=prog.blocks[0])) == _signature(_path(0.0))
