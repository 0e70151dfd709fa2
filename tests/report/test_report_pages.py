"""The report's pages answer "which variant is best" and write figures for a
reader: checked on rows made here, with figures worked out by hand, and on
the plots of a long thin bundled part."""
from __future__ import annotations

import html
import re
import struct

import pytest

from ccopt.cases import Overrides, resolve_input
from ccopt.report.figures import detail, gain, number
from ccopt.report.html import fastest_certified, render, render_case, render_index
from ccopt.report.plots import path_plot, zoom_windows

#: three variants: PMAC 10 s, LinuxCNC 9 s, an optimised blend 8 s that is
#: not certified and a lead 8.5 s that is
VARIANTS = [
    {"name": "pmac", "status": "ok", "certified": True, "duration": 10.0,
     "min_clearance": 2.0 - 4.44089e-16, "continuity": "G0"},
    {"name": "linuxcnc", "status": "ok", "certified": True, "duration": 9.0,
     "min_clearance": 2.0, "continuity": "G0"},
    {"name": "opt-casadi", "status": "uncertified", "certified": False, "duration": 8.0,
     "message": "not certified: gouge failed"},
    {"name": "line-arc", "status": "ok", "certified": True, "duration": 8.5,
     "min_clearance": 2.0, "continuity": "G1"},
]
for v in VARIANTS:   # the gains as the comparison defines them: 1 - t / t_ref
    v["gain_vs_pmac"] = 1 - v["duration"] / 10.0
    v["gain_vs_fastest_controller"] = 1 - v["duration"] / 9.0
    v["fastest_controller"] = "linuxcnc"

ROW = {"name": "part", "status": "ok", "style": "pmac", "radius": 2.0, "units": "mm",
       "program": "part.pmc", "duration": 10.0, "min_clearance": 2.0, "compare": VARIANTS,
       "feed": {"toppra": {"duration": 10.0, "max_axis_vel_ratio": 1.0,
                           "max_axis_acc_ratio": 0.999999, "max_axis_jerk_ratio": 0.5,
                           "max_feed_ratio": 1.0}},
       "limits": {"v": [100, 100], "a": [1000, 1000]},
       "certificate": {"ok": True, "min_clearance": 2.0, "radius": 2.0, "checks": [
           {"name": "continuity", "ok": True, "figure": 8.881784197001252e-16, "unit": "length",
            "detail": {"tangent_breaks": 2, "tangent_breaks_listed": [
                {"tool_segment": 1, "angle_deg": 90.0}, {"tool_segment": 4, "angle_deg": 45.0}]}}]},
       "certificate_text": "verification PASSED\n  gouge  ok  " + "x" * 400}


def _text(fragment: str) -> str:
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", fragment)).split())


def test_the_fastest_certified_variant_is_marked_with_its_gains():
    # line-arc (8.5 s) is the fastest certified: opt-casadi is faster but uncertified
    assert fastest_certified(VARIANTS)["name"] == "line-arc"
    page = render_case(ROW)
    winner = re.findall(r'<tr class="winner">(.*?)</tr>', page)
    assert len(winner) == 1
    cells = _text(winner[0]).split()
    # 1 - 8.5/10 = +15.00 %, 1 - 8.5/9 = +5.56 %
    assert cells[:6] == ["line-arc", "fastest", "certified", "ok", "8.500", "s"]
    assert "+15.00 %" in _text(winner[0]) and "+5.56 %" in _text(winner[0])
    index = render_index([ROW])
    row = _text(re.findall(r"<tr>(.*?)</tr>", index)[1])
    assert row == "part ok pmac 2 10.000 s 2.0000 line-arc 8.500 s +15.00 % +5.56 % linuxcnc"
    assert 'href="part.report.html"' in index


def test_figures_are_written_for_a_reader():
    assert number(4.44089e-16, "length") == "0.000"          # round-off of 0
    assert number(2.0 - 4.44089e-16, "clearance") == "2.0000"
    assert number(True) == "yes" and number(False) == "no"
    assert number(None) == "-" and number(float("inf")) == "&infin;"
    assert gain(1 - 9.0 / 10.0) == "+10.00 %" and gain(1 - 11.0 / 10.0) == "-10.00 %"
    assert gain(None) == "-"
    page = render_case(ROW)
    assert "e-16" not in page and "True" not in page and "False" not in page
    # a long list in a check's detail is folded under its length
    assert "<summary>2 listed</summary>" in detail(ROW["certificate"]["checks"][0]["detail"])


def test_the_certificate_wraps_and_the_jerk_column_needs_jerk_limits():
    css = render_case(ROW)
    assert re.search(r"pre\{[^}]*white-space:pre-wrap", css)
    assert "max jerk / limit" not in render_case(ROW)
    jerky = {**ROW, "limits": {"v": [100, 100], "a": [1000, 1000], "j": [20000, 20000]}}
    page = render_case(jerky)
    assert "max jerk / limit" in page
    feed = page[page.index("<h3>Feed</h3>"):page.index("<h3>Variants</h3>")]
    assert "0.5000" in _text(feed)


def test_every_case_has_its_page_and_no_page_has_a_script():
    pages = render([ROW, {**ROW, "name": "index"}])
    # a case named "index" does not replace the index
    assert set(pages) == {"index.html", "part.report.html", "index.report.html"}
    assert not any("<script" in p for p in pages.values())


def _png_size(png: bytes) -> tuple[int, int]:
    return struct.unpack(">II", png[16:24])


def test_a_long_thin_part_is_drawn_with_zoomed_leads():
    # fagor-g136-g138: passes along a 530 x 30 mm strip (height / width 0.056)
    job = resolve_input("fagor-g136-g138", Overrides(), {})
    prog = job.read()
    path = job.compensate(prog)
    box = (min(s.geom.bbox()[0] for s in path.segments), max(s.geom.bbox()[2] for s in path.segments),
           min(s.geom.bbox()[1] for s in path.segments), max(s.geom.bbox()[3] for s in path.segments))
    assert (box[3] - box[2]) / (box[1] - box[0]) < 0.1
    windows = zoom_windows(path, path.radius, box)
    assert [name for name, _ in windows][0] == "lead-in"
    for _, (x0, x1, y0, y1) in windows:          # squares a few radii wide
        assert x1 - x0 == pytest.approx(y1 - y0) and x1 - x0 >= 8 * path.radius
    w, h = _png_size(path_plot(path, None, path.radius))
    assert h / w > 0.4, (w, h)                     # not a thin strip
    # a part about as tall as wide (pocket, 57 x 37 mm) gets no zoom
    pocket = resolve_input("pocket", Overrides(), {})
    ppath = pocket.compensate(pocket.read())
    assert zoom_windows(ppath, ppath.radius, (0.0, 57.0, 0.0, 37.0)) == []


@pytest.mark.parametrize("case", ["fagor-g136-g138", "pocket", "leadin-inside-line"])
def test_figures_are_the_images_savefig_tight_draws(case, monkeypatch):
    """Each figure's PNG is byte for byte what ``savefig(bbox_inches="tight")``
    writes (one draw instead of two): plain and thin plan views with zooms,
    the colour bar, the legend outside the axes, speed against time."""
    import io

    import ccopt.report.plots as plots
    from ccopt.feed import AxisLimits, ExactPath, plan_feed

    drawn = []

    def both(fig):
        ours = real(fig)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", bbox_inches="tight")
        drawn.append(ours == buf.getvalue())
        return ours

    real = plots._png
    monkeypatch.setattr(plots, "_png", both)
    job = resolve_input(case, Overrides(), {})
    path = job.compensate(job.read())
    prof = plan_feed(ExactPath(path), AxisLimits(job.vmax, job.amax))
    plots.path_plot(path, None, path.radius, [], case)
    plots.feed_plot(prof, case)
    plots.speed_time_plot({"toppra": prof}, case)
    assert drawn == [True, True, True]
