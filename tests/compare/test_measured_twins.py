"""Variants that leave the same tool path are certified and measured once in a
comparison (:func:`ccopt.compare.variant.measured_as`), with the figures the
path has when measured on its own."""
from __future__ import annotations

from ccopt.cases import make_job
from ccopt.compare import compare
from ccopt.compare.contract import BlendProblem
from ccopt.compare.variant import measure_shape, measured_alike
from ccopt.pipeline import pipeline

#: Variants that leave PMAC's path on leadin-inside-line (its entry is a line
#: to a line, and these styles put the corner arc on the same block as PMAC
#: does), and two that do not (LinuxCNC's entry, SINUMERIK's corner block).
SAME_PATH = ("pmac", "fagor-g138", "fagor-g139-g136", "heidenhain")
OTHERS = ("linuxcnc", "siemens")


def test_a_path_left_by_several_variants_is_measured_once_with_its_own_figures(monkeypatch):
    done = pipeline(make_job("leadin-inside-line"), compare=False, export=[])
    prog, limits = done.program, done.limits
    calls = []
    certify = BlendProblem.certify

    def counted(self, path, *a, **k):
        calls.append(path)
        return certify(self, path, *a, **k)

    monkeypatch.setattr(BlendProblem, "certify", counted)
    rows = {r.name: r for r in compare(prog, list(SAME_PATH + OTHERS), limits=limits)}
    monkeypatch.setattr(BlendProblem, "certify", certify)
    ref = rows["pmac"].toolpath
    # the premise: which variants leave PMAC's path here (their style names aside)
    assert all(measured_alike(rows[n].toolpath, ref) for n in SAME_PATH)
    assert not any(measured_alike(rows[n].toolpath, ref) for n in OTHERS)
    assert not measured_alike(rows["linuxcnc"].toolpath, rows["siemens"].toolpath)
    # the reference's row (measured apart), the shared path once more (the
    # first variant that leaves it), then each of the others
    assert len(calls) == 2 + len(OTHERS)
    alone = measure_shape("alone", ref, BlendProblem(prog, ref, limits), 0.0)
    for name in SAME_PATH:
        row = rows[name]
        assert row.status == alone.status and row.message == alone.message
        for key, value in alone.figures.items():
            if key != "solve_time":
                assert row.figures[key] == value, (name, key)
    # each row keeps its own path (a twin's style is its own)
    assert rows["heidenhain"].toolpath.style == "heidenhain"
    assert rows["fagor-g138"].toolpath.style == "fagor"


def test_paths_alike_only_where_every_measured_entry_agrees():
    from dataclasses import replace

    from ccopt.toolpath import FITTED_PIECES, STRAIGHT_JOINS
    done = pipeline(make_job("leadin-inside-line"), compare=False, export=[])
    path = done.path
    assert measured_alike(path, replace(path, style="other"))
    # a straight join's cause names the style: then the style must agree too
    joined = replace(path, meta={**path.meta, STRAIGHT_JOINS: {3: 0.01}})
    assert measured_alike(joined, replace(joined))
    assert not measured_alike(joined, replace(joined, style="other"))
    assert not measured_alike(path, joined)
    assert not measured_alike(path, replace(path, meta={**path.meta, FITTED_PIECES: (1,)}))
    assert not measured_alike(path, replace(path, radius=path.radius + 1e-12))
    assert not measured_alike(path, replace(path, segments=path.segments[:-1]))


def test_paths_the_planners_time_alike_are_timed_once(monkeypatch):
    """SINUMERIK's path of leadin-inside-line is PMAC's but for the block its
    entry corner is attributed to (line 8, not 7): certified apart (the
    certificate names lines), timed once (the planners read no block)."""
    from ccopt.compare import schedule
    from ccopt.compare.timing import same_timing_message, timed_alike
    done = pipeline(make_job("leadin-inside-line"), compare=False, export=[])
    prog, limits = done.program, done.limits
    planned = []
    timed = schedule._timed

    def counted(path, *a, **k):
        planned.append(path)
        return timed(path, *a, **k)

    monkeypatch.setattr(schedule, "_timed", counted)
    rows = {r.name: r for r in compare(prog, ["pmac", "fagor-g138", "siemens"], limits=limits)}
    a, b = rows["fagor-g138"].toolpath, rows["siemens"].toolpath
    assert timed_alike(a, b) and not same_timing_message(a, b)
    assert not measured_alike(a, b)
    assert len(planned) == 1          # fagor-g138's path; siemens takes its figures
    assert rows["siemens"].figures["duration"] == rows["fagor-g138"].figures["duration"]
    # and they are the figures siemens's path has when timed on its own
    from ccopt.compare.timing import duration_figures
    alone = duration_figures(b, limits, None)
    assert abs(alone[0] - rows["siemens"].figures["duration"]) <= 1e-9 * alone[0]
    assert alone[2] is None
