"""The SINUMERIK families' shared plan (ccopt.compare.siemens_leads._base_times)
over generated CAM programs (tests/cam_programs.py), not only the bundled
sinumerik-sar-plate (tests/compare/test_siemens_base_times.py).

For each program, under axis limits drawn from its seed:

* a family's row shows the cycle time its chosen member was chosen by, and
  the rows are the same in worker processes with the ``siemens`` row in the
  comparison (the families then read that path's stretches off the row);

* every member's figure (the cycle time it was chosen by) is its own path
  planned whole, within the 1e-9 relative with which a stretch planned alone
  may differ from the same stretch inside the whole path (ccopt.compare.timing);
* a family's row (member chosen, every member's figure, the row's cycle
  time) is the same when it runs alone in a fresh process state as when it
  runs after the other four families, which filled the shared plan (one
  family per program, in turn by seed: each comparison alone costs a plan
  of PMAC's path and of the ``siemens`` path).
"""
from __future__ import annotations

import random

import pytest

from cam_programs import cam_program
from ccopt.compare import compare, siemens_leads
from ccopt.compare.contract import SIEMENS_NAMES
from ccopt.compare.timing import plan_whole
from ccopt.compensate import compensate
from ccopt.feed import AxisLimits
from ccopt.program import read_text

FAMILIES = SIEMENS_NAMES[1:]


def _options(family: str, member: str) -> dict:
    """The ``siemens`` style's options of a member, from its key in ``info["members"]``
    (``G450``/``G451`` for NORM and KONT, ``DISR=<value>`` for the smooth approaches)."""
    kind = family.split("-")[1]
    if kind in ("norm", "kont"):
        return {"approach": kind.upper(), "corner": member}
    return {"sar": kind.upper(), "disr": float(member.split("=")[1])}


def _program_and_limits(seed: int):
    cp = cam_program(seed)
    prog = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    rng = random.Random(20_000 + seed)
    v, a = rng.uniform(50.0, 300.0), rng.uniform(500.0, 5000.0)
    return prog, AxisLimits((v, v), (a, a))


def _rows(prog, lim, names, workers=1):
    return {r.name: r for r in compare(prog, ["pmac", *names], limits=lim, workers=workers)
            if r.name in FAMILIES}


def _figures(row):
    return row.status, row.info.get("chosen"), row.info.get("members"), \
        row.figures.get("duration")


def _check(seed: int, monkeypatch) -> int:
    """The two properties on one program; the number of member figures checked."""
    prog, lim = _program_and_limits(seed)
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    together = _rows(prog, lim, FAMILIES)
    name = FAMILIES[seed % len(FAMILIES)]
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    alone = _rows(prog, lim, [name])[name]
    assert _figures(alone) == _figures(together[name]), (seed, name)
    # in worker processes, with the siemens row (whose stretches the families
    # then read instead of planning that path): the same rows
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    beside = _rows(prog, lim, ["siemens", *FAMILIES], workers=2)
    assert {n: _figures(r) for n, r in beside.items()} == \
        {n: _figures(r) for n, r in together.items()}, seed
    checked = 0
    for name in FAMILIES:
        row = together[name]
        if row.status == "ok":       # the row shows the figure its member was chosen by
            assert row.figures["duration"] == row.info["members"][row.info["chosen"]], \
                (seed, name)
        for member, figure in together[name].info.get("members", {}).items():
            if not isinstance(figure, float):
                continue            # refused or not certified: no figure
            path = compensate(prog, "siemens", **_options(name, member))
            whole = plan_whole(path, lim)[0].duration
            assert figure == pytest.approx(whole, rel=1e-9), (seed, name, member)
            checked += 1
    return checked


def test_siemens_base_times_on_a_generated_program_quick(monkeypatch):
    assert _check(5, monkeypatch) > 0


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(300, 315))
def test_siemens_base_times_on_generated_programs(seed, monkeypatch):
    assert _check(seed, monkeypatch) > 0
