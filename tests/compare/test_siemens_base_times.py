"""The SINUMERIK families share one plan of the ``siemens`` path per process
(ccopt.compare.siemens_leads._base_times).

Each family's members differ from the ``siemens`` path as the program asks
only at their leads (and NORM/KONT at their corners), so that path is
planned once and each member plans only the stretches it changes. Checked:
the five families plan it once in a process; a family's figures are the
same whether it runs first, after the others, or in a worker process; and
each member's figure is its own path's cycle time planned whole, within the
tolerance with which a stretch planned alone may differ from the same
stretch inside the whole path (ccopt.compare.timing).
"""
from __future__ import annotations

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import compare, siemens_leads
from ccopt.compare.contract import SIEMENS_NAMES
from ccopt.compare.timing import StretchTimes, plan_whole
from ccopt.compensate import compensate

FAMILIES = SIEMENS_NAMES[1:]
CASE = "sinumerik-sar-plate"


def _program_and_limits():
    c = find_case(CASE)
    return ccopt.read_program(c.program), ccopt.AxisLimits(c.vmax, c.amax)


def _members(rows) -> dict:
    return {r.name: (r.info.get("chosen"), r.info.get("members"), r.figures.get("duration"))
            for r in rows if r.name in FAMILIES}


def test_the_siemens_path_is_planned_once_for_all_families(monkeypatch):
    prog, lim = _program_and_limits()
    whole, timed = [], []
    real_whole = StretchTimes.from_reference.__func__
    real_time = StretchTimes.time_partial

    def counted_whole(cls, *args, **kwargs):
        whole.append(args[0])
        return real_whole(cls, *args, **kwargs)

    def counted_time(self, path, *args, **kwargs):
        timed.append(path)
        return real_time(self, path, *args, **kwargs)

    monkeypatch.setattr(siemens_leads, "_BASES", {})
    monkeypatch.setattr(StretchTimes, "from_reference", classmethod(counted_whole))
    monkeypatch.setattr(StretchTimes, "time_partial", counted_time)
    compare(prog, ["pmac", *FAMILIES], limits=lim, workers=1)
    siemens = compensate(prog, "siemens")
    # the comparison's reference (PMAC's path) planned whole, once; the siemens
    # path as the program asks timed from its stretches once, for all five families
    assert len(whole) == 1
    assert [p for p in timed if p.segments == siemens.segments] != []
    assert len([p for p in timed if p.segments == siemens.segments]) == 1


def test_with_the_siemens_row_the_families_take_its_stretches(monkeypatch):
    """With the ``siemens`` row in the comparison its stretches are planned
    once, for the row, and the families read them from it (no plan of that
    path more than without the row): the same figures as when they plan that
    path themselves."""
    prog, lim = _program_and_limits()
    siemens = compensate(prog, "siemens")
    planned = []
    real_run = StretchTimes._plan_run

    def counted_run(self, exact, run):
        planned.append(exact.toolpath.segments == siemens.segments)
        return real_run(self, exact, run)

    monkeypatch.setattr(StretchTimes, "_plan_run", counted_run)
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    alone = _members(compare(prog, ["pmac", *FAMILIES], limits=lim, workers=1))
    n_alone, planned[:] = sum(planned), []
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    with_row = _members(compare(prog, ["pmac", "siemens", *FAMILIES], limits=lim, workers=1))
    assert n_alone > 0
    assert sum(planned) == n_alone
    assert with_row == alone


@pytest.mark.parametrize("case, alike", [(CASE, 0), ("pocket", 2)])
def test_a_family_row_shows_the_figure_its_member_was_chosen_by(case, alike):
    """The row's cycle time is the chosen member's figure (read off the stretch
    times it was timed with, not planned again), and a member that leaves the
    siemens path as the program asks has the siemens row's cycle time (on
    ``pocket``, NORM and KONT with G450: the style's own default)."""
    c = find_case(case)
    prog, lim = ccopt.read_program(c.program), ccopt.AxisLimits(c.vmax, c.amax)
    rows = {r.name: r for r in compare(prog, ["pmac", "siemens", *FAMILIES], limits=lim,
                                       workers=1)}
    siemens = compensate(prog, "siemens")
    same_path = 0
    for name in FAMILIES:
        row = rows[name]
        assert row.status == "ok", (name, row.message)
        assert row.figures["duration"] == row.info["members"][row.info["chosen"]]
        if row.toolpath.segments == siemens.segments:
            assert row.figures["duration"] == rows["siemens"].figures["duration"]
            same_path += 1
    assert same_path == alike


def test_family_figures_do_not_depend_on_the_order_or_the_process(monkeypatch):
    prog, lim = _program_and_limits()
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    alone = _members(compare(prog, ["pmac", "siemens-g247"], limits=lim, workers=1))
    after = _members(compare(prog, ["pmac", *FAMILIES], limits=lim, workers=1))
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    parallel = _members(compare(prog, ["pmac", *reversed(FAMILIES)], limits=lim, workers=2))
    assert alone["siemens-g247"] == after["siemens-g247"]
    assert after == parallel


def test_each_member_figure_is_its_path_planned_whole(monkeypatch):
    prog, lim = _program_and_limits()
    monkeypatch.setattr(siemens_leads, "_BASES", {})
    rows = {r.name: r for r in compare(prog, ["pmac", "siemens-g247", "siemens-norm"],
                                       limits=lim, workers=1)}
    checked = 0
    for name, options in (("siemens-g247", lambda k: {"sar": "G247",
                                                      "disr": float(k.split("=")[1])}),
                          ("siemens-norm", lambda k: {"approach": "NORM", "corner": k})):
        for key, figure in rows[name].info["members"].items():
            if not isinstance(figure, float):
                continue
            path = compensate(prog, "siemens", **options(key))
            whole = plan_whole(path, lim)[0].duration
            assert figure == pytest.approx(whole, rel=1e-9), (name, key)
            checked += 1
    assert checked >= 3
