"""What the HTML report says: refused variants with their message, the
certificate as text, the speed axis set by the feed moves (not by rapids),
and ``print(certificate)`` as a short summary."""
from __future__ import annotations

import html
import re
from pathlib import Path

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.cli import main
from ccopt.feed import AxisLimits, ExactPath, plan_feed
from ccopt.report.plots import FEED_HEADROOM, rapid_samples, speed_axis_top


def _compensated(name: str):
    case = find_case(name)
    prog = ccopt.read_program(case.program)
    return case, prog, ccopt.compensate(prog, case.style)


@pytest.mark.slow
def test_report_lists_a_refused_variant_with_its_message_and_the_certificate_as_text(
        capsys, tmp_path):
    # Fagor refuses an arc as the move that starts compensation; the CIRCLE1
    # lead-in of leadin-outside-arc is one (line 8 of its program)
    code = main(["run", "leadin-outside-arc", "short-move-overcut", "--variants",
                 "pmac,fagor-g138", "-o", str(tmp_path), "--workers", "2"])
    capsys.readouterr()
    assert code == 0
    page = (tmp_path / "leadin-outside-arc.report.html").read_text()
    variants = page[page.index("<h3>Variants</h3>"):]
    variants = variants[:variants.index("</ul>")]
    rows = re.findall(r"<tr.*?</tr>", variants)
    fagor = html.unescape(re.sub(r"<[^>]+>", " ", next(r for r in rows if "fagor-g138" in r)))
    assert fagor.split()[:2] == ["fagor-g138", "refused"]
    # its message, in the notes under the table
    notes = [html.unescape(re.sub(r"<[^>]+>", "", n))
             for n in re.findall(r"<li>(.*?)</li>", variants)]
    message = next(n for n in notes if n.startswith("fagor-g138: "))
    assert message == "fagor-g138: " + str(find_case("leadin-outside-arc").program) + \
        ":8:1: the move that activates cutter compensation (the first move in the plane " \
        "after G41/G42) must be linear (G00/G01), not an arc: add a straight approach move"
    # short-move-overcut: the 1 mm step under a 2 mm cutter is a gouge 1 mm deep,
    # the certificate says so in words, one line per check and violation
    section = (tmp_path / "short-move-overcut.report.html").read_text()
    pre = html.unescape(section[section.index("<pre>") + 5:section.index("</pre>")])
    lines = pre.splitlines()
    assert lines[0].startswith("verification FAILED (geometry FAIL")
    assert any(re.match(r"  gouge +FAIL +-1 length \[exact\]", x) for x in lines)
    assert any(x.startswith("  - gouge: depth 1, tool segment 3 (line 9, compensated)")
               for x in lines)
    # no JSON in the certificate's table
    table = section[section.index("<h3>Certificate</h3>"):]
    table = table[:table.index("</table>")]
    assert "{&quot;" not in table and "[&quot;" not in table


def test_speed_axis_tops_at_the_feed_moves_not_the_rapids():
    # leadin-outside-line: rapids at the axis limit (50 mm/s), the cut at F20
    # (PMAC's F in units per second): the axis ends 8 % above 20 mm/s
    case, prog, path = _compensated("leadin-outside-line")
    limits = AxisLimits(case.vmax, case.amax)
    prof = plan_feed(ExactPath(path), limits)
    smp = prof.sample(1e-3)
    rapid = rapid_samples(prof, smp)
    assert rapid.any() and smp.feed[rapid].max() == pytest.approx(50.0, rel=1e-3)
    assert speed_axis_top({"toppra": prof}) == pytest.approx(FEED_HEADROOM * 20.0, rel=1e-3)


def test_print_certificate_is_a_short_summary(capsys):
    _, prog, path = _compensated("short-move-overcut")
    print(ccopt.verify(path, prog))
    assert capsys.readouterr().out.splitlines() == [
        "Certificate FAILED (geometry FAIL, limits not run): cutter radius 2 mm, "
        "min clearance 1 mm (exact)",
        "  failed: gouge (2 violations), contact (1 violation)"]
    _, prog, path = _compensated("leadin-outside-line")
    assert str(ccopt.verify(path, prog)) == (
        "Certificate OK (geometry ok, limits not run): cutter radius 2 mm, min clearance 2 mm "
        "(exact); 5 checks passed")
