"""``ccopt compare`` and ``ccopt smooth`` on the command line."""
from __future__ import annotations

import json
import math

import pytest

from ccopt.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_compare_json_and_plot(capsys, tmp_path):
    png = tmp_path / "v.png"
    code, out, err = run(capsys, "compare", "leadin-inside-line", "--variants",
                         "pmac,tangent-arc", "--variants", "line-arc", "--json", "--plot", str(png))
    assert code == 0, err
    doc = json.loads(out)
    assert [v["name"] for v in doc["variants"]] == ["pmac", "tangent-arc", "line-arc"]
    for v in doc["variants"]:
        for k in ("name", "duration", "min_clearance", "max_curvature", "continuity", "certified"):
            assert k in v
    # limits from the case
    assert doc["limits"] == {"v": [50.0, 50.0, 20.0], "a": [500.0, 500.0, 200.0]}
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_compare_refuses_a_plot_name_it_cannot_write_before_comparing(capsys, tmp_path,
                                                                       monkeypatch):
    # -o names a plot; a .json there was an internal error (matplotlib's), after
    # the whole comparison had run
    import ccopt.cli.compare as cli_compare

    def never(*_a, **_k):
        raise AssertionError("the comparison ran")

    monkeypatch.setattr(cli_compare, "pipeline", never)
    out = tmp_path / "v.json"
    code, _, err = run(capsys, "compare", "leadin-inside-line", "-o", str(out))
    assert code == 2
    assert err.startswith(f"{out}: compare -o writes a plot") and "--json" in err
    assert "Traceback" not in err and not out.exists()


def test_compare_text_and_limits_override(capsys):
    code, out, _ = run(capsys, "compare", "leadin-inside-line", "--variants", "pmac",
                       "--vmax", "10,10,10", "--amax", "100,100,100")
    assert code == 0
    assert "limits v=[10.0, 10.0, 10.0]" in out and out.splitlines()[1].startswith("variant")


def test_compare_without_limits_takes_the_printed_default(capsys, tmp_path):
    # issue 17: the same limit rule as feed and run (DEFAULT_LIMITS, printed)
    prog = tmp_path / "p.nc"
    prog.write_text("G21 G90 F600\nG41.1 D2\nG1 X10 Y0\nG1 X10 Y10\nG40\nG1 X20 Y10\n")
    code, out, err = run(capsys, "compare", str(prog), "--variants", "pmac")
    assert code == 0, err
    assert "default" in out and "a=[1000.0, 1000.0, 1000.0]" in out


def test_smooth_json(capsys):
    code, out, err = run(capsys, "smooth", "leadin-inside-line", "--json")
    assert code == 0, err
    doc = json.loads(out)
    # default band: 1 % of the cutter radius 2
    assert doc["delta"] == pytest.approx(0.02)
    assert doc["certified"] is True and doc["certificate"]["ok"] is True
    assert doc["max_deviation_bound"] <= doc["delta"]
    assert doc["path_continuity"] == "G2"
    assert doc["duration"] < doc["pmac_duration"]
    assert all(j["status"] == "blended" for j in doc["joins"])
    # the feed-limited floor of PMAC's path: the rapid from the origin to (0, -20) at
    # Y's 50 mm/s, then at F20 the lead-in to (0, -2), the first move to (-20, -2),
    # the R2 quarter arc round the outside corner, (-22, 0) to (-22, 20) and the
    # lead-out to (-40, 20)
    assert doc["pmac_feed_floor"] == pytest.approx(20 / 50 + (18 + 20 + math.pi + 20 + 18) / 20,
                                                   rel=1e-12)
    # blends cut corners: the smoothed path is shorter, and neither beats its floor
    assert doc["feed_floor"] < doc["pmac_feed_floor"] < doc["pmac_duration"]
    assert doc["feed_floor"] < doc["duration"]


def test_smooth_export_verdict_sets_the_exit_code(capsys, tmp_path, monkeypatch):
    # The exported file is what runs on the machine: its read-back verdict
    # counts. The smoothed path of leadin-inside-line in G-code (its blends as
    # arcs, tangent at the blends' ends, within the tolerance) reads back clean:
    # exit 0, and the file says so.
    ok_file = tmp_path / "lead.nc"
    code, out, err = run(capsys, "smooth", "leadin-inside-line", "-o", str(ok_file))
    assert code == 0, err
    assert f"exported {ok_file}: read back within" in out and "verified OK" in out
    assert "verified against the programmed contour: OK" in ok_file.read_text()
    # A file whose read-back failed (the exporter's verdict, stubbed here) is
    # exit 1 even though the computed path itself is certified.
    import ccopt.cli.compare as export_module  # smooth calls the exporter it imported
    real = export_module.export

    def failing(*args, **kw):
        res = real(*args, **kw)
        res.verified = False
        return res

    monkeypatch.setattr(export_module, "export", failing)
    code, out, err = run(capsys, "smooth", "leadin-inside-line", "-o", str(tmp_path / "x.nc"),
                         "--json")
    doc = json.loads(out)
    assert doc["certified"] is True and doc["export"]["verified"] is False
    assert code == 1
