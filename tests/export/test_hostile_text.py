"""Exports carry only motion: a case whose title and source hold commands,
comment delimiters, markup and spreadsheet formulas is exported in every
format, and each file's commands are exactly the path's.

The reference is the same path exported with a plain title: the hostile
file's lines outside comments must equal the plain file's, ccopt's own
readers must read the same moves back from both, and those moves must end
where the computed path's segments end. Words of the hostile text must not
appear anywhere outside comments.
"""
from __future__ import annotations

import csv
import json
import re
import shutil
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

import ccopt
from ccopt.cli import main
from ccopt.export.text import csv_cell, gcode_comment, one_line, plot_text, pmac_comment
from ccopt.program import read_program
from ccopt.report.plots import path_plot
from ccopt.sweep.results import write_table
from ccopt.sweep.summary import write_summary

CASES = Path(__file__).resolve().parents[2] / "cases"

#: A title that tries every way out of a comment: line breaks of every kind
#: followed by PMAC and G-code commands, closing and reopening a G-code
#: comment, LinuxCNC's active comments, markup, a formula and ccopt's own marker.
HOSTILE_TITLE = ("x\nI130=0\nUNDEFINE ALL\r\nCLOSE\rDELETE GATHER\x85G0 X999\u2028M30"
                 "\u2029)(M30)(MSG, pwned)\x0bI131=0\x0c; OPEN PROG 9\\\n#define X "
                 "</svg><script>alert(1)</script>\x01{macro}")
#: A source that starts with a spreadsheet formula and carries markup.
HOSTILE_SOURCE = "=cmd|' /C calc'!A0\n<script>alert(2)</script>"
#: Words that may appear only inside comments (upper case: both readers are
#: case-insensitive, so the check is too).
HOSTILE_WORDS = ("I130", "I131", "UNDEFINE", "DELETE", "GATHER", "X999", "M30", "MSG",
                 "PWNED", "SCRIPT", "ALERT", "CMD", "CALC", "PROG 9", "DEFINE", "MACRO")


def _case(tmp_path: Path, name: str, title: str, source: str,
          base: str = "leadin-outside-arc") -> Path:
    """A copy of a bundled case (it has a spiral lead-in) with ``title`` and
    ``source`` (written as TOML basic strings, so every character survives)."""
    folder = tmp_path / name
    folder.mkdir()
    shutil.copy(CASES / base / "part.pmc", folder / "part.pmc")
    (folder / "case.toml").write_text(
        f"title = {json.dumps(title)}\nsource = {json.dumps(source)}\nprogram = \"part.pmc\"\n"
        "style = \"pmac\"\n[limits]\nv = [50.0, 50.0, 20.0]\na = [500.0, 500.0, 200.0]\n",
        encoding="utf-8")
    return folder


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("hostile")
    return (_case(tmp, "hostile", HOSTILE_TITLE, HOSTILE_SOURCE),
            _case(tmp, "plain", "plain title", "plain source"))


def _export(capsys, case: Path, out: Path) -> None:
    code = main(["export", str(case), "-o", str(out)])
    _, err = capsys.readouterr()
    assert code == 0, err


def _code(line: str, dialect: str) -> str:
    """A program line without its comments, upper case."""
    if dialect == "gcode":
        line = re.sub(r"\([^)]*\)", "", line)
    return line.split(";", 1)[0].strip().upper()


def _lines(text: str) -> list[str]:
    # Only "\n" may end a line: any other line boundary Python knows (\r,
    # \x0b, \x0c, \x1c-\x1e, \x85, U+2028, U+2029) would be a way out of a comment.
    assert len(text.splitlines()) == text.count("\n")
    return text.split("\n")


@pytest.mark.parametrize("suffix,dialect", [(".nc", "gcode"), (".pmc", "pmac")])
def test_hostile_title_program_exports_carry_only_the_path(cases, suffix, dialect, tmp_path,
                                                           capsys):
    hostile, plain = cases
    bad, good = tmp_path / f"bad{suffix}", tmp_path / f"good{suffix}"
    _export(capsys, hostile, bad)
    _export(capsys, plain, good)
    bad_lines, good_lines = _lines(bad.read_text()), _lines(good.read_text())
    # the title is there, as one comment line
    assert any("UNDEFINE ALL" in ln for ln in bad_lines)
    # the commands are exactly those of the plain export
    bad_code = [c for c in (_code(ln, dialect) for ln in bad_lines) if c]
    good_code = [c for c in (_code(ln, dialect) for ln in good_lines) if c]
    assert bad_code == good_code
    for c in bad_code:
        assert not any(w in c for w in HOSTILE_WORDS), c
    # ccopt's reader reads the same moves from both, ending where the
    # computed path's segments end, in order
    back = ccopt.programmed_path(read_program(bad))
    ref = ccopt.programmed_path(read_program(good))
    assert [(s.kind, s.start, s.end) for s in back] == [(s.kind, s.start, s.end) for s in ref]
    path = ccopt.compensate(read_program(hostile / "part.pmc"), "pmac")
    ends = np.array([s.end for s in back.segments])
    k = 0
    for seg in path.segments:      # every computed end point, in order, among the moves'
        hits = np.flatnonzero(np.hypot(*(ends[k:] - seg.end).T) <= 1e-6)
        assert hits.size, (seg.kind, seg.end)
        k += int(hits[0]) + 1
    assert len(back.segments) == k     # nothing after the path's end


def test_hostile_title_svg_is_one_drawing_of_the_path(cases, tmp_path, capsys):
    hostile, plain = cases
    bad, good = tmp_path / "bad.svg", tmp_path / "good.svg"
    _export(capsys, hostile, bad)
    _export(capsys, plain, good)
    root = ET.parse(bad).getroot()          # well-formed XML: no control characters
    ns = "{http://www.w3.org/2000/svg}"
    tags = {el.tag.removeprefix(ns) for el in root.iter()}
    assert tags == {"svg", "title", "g", "path"}
    assert root.find(f"{ns}title").text == one_line(HOSTILE_TITLE)
    d = [el.get("d") for el in root.iter(f"{ns}path")]
    assert d == [el.get("d") for el in ET.parse(good).getroot().iter(f"{ns}path")]


def test_hostile_title_json_holds_the_same_path(cases, tmp_path, capsys):
    hostile, plain = cases
    bad, good = tmp_path / "bad.json", tmp_path / "good.json"
    _export(capsys, hostile, bad)
    _export(capsys, plain, good)
    assert json.loads(bad.read_text()) == json.loads(good.read_text())


class _Tags(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags: set[str] = set()
        self.hrefs: list[str] = []
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.add(tag)
        self.hrefs += [v for k, v in attrs if k == "href"]

    def handle_data(self, data):
        self.text.append(data)


def test_hostile_case_through_ccopt_run(cases, tmp_path, capsys):
    hostile, _ = cases
    out = tmp_path / "run"
    code = main(["run", str(hostile), "-o", str(out), "--no-compare"])
    _, err = capsys.readouterr()
    assert code == 0, err
    page = _Tags()
    for html_file in sorted(out.glob("*.html")):      # the index and the case's page
        page.feed(html_file.read_text())
    assert {"index.html", "hostile.report.html"} <= {f.name for f in out.glob("*.html")}
    assert "script" not in page.tags
    assert one_line(HOSTILE_TITLE) in "".join(page.text)      # shown, as text
    assert one_line(HOSTILE_SOURCE) in "".join(page.text)
    assert all(not re.match(r"[a-z]+:", h) for h in page.hrefs)   # relative links only
    for suffix, dialect in ((".nc", "gcode"), (".pmc", "pmac")):
        text = (out / f"hostile{suffix}").read_text()
        for c in (_code(ln, dialect) for ln in _lines(text)):
            assert not any(w in c for w in HOSTILE_WORDS), c
    summary = json.loads((out / "summary.json").read_text())
    assert summary["cases"][0]["title"] == HOSTILE_TITLE      # JSON keeps it whole, quoted


def test_sweep_csv_cells_are_never_formulas(tmp_path):
    import pandas as pd  # a dependency of ccopt (sweeps): missing is a failure, not a skip
    rows = [{"task_id": "a", "program": "=cmd|' /C calc'!A0", "style": "+pmac",
             "error": "-1+1\nI130=0", "cycle_time": -1.5, "ok": False},
            {"task_id": "b", "program": "@SUM(A1)", "style": "\tpmac", "error": None,
             "cycle_time": 2.0, "ok": True}]
    table = pd.DataFrame.from_records(rows)
    write_table(tmp_path, table)
    with open(tmp_path / "results.csv", newline="", encoding="utf-8") as fh:
        got = list(csv.reader(fh))
    assert len(got) == 3                      # header + two rows: no cell spans lines
    assert got[1] == ["a", "'=cmd|' /C calc'!A0", "'+pmac", "'-1+1 I130=0", "-1.5", "False"]
    assert got[2] == ["b", "'@SUM(A1)", "pmac", "", "2.0", "True"]
    # the Parquet table keeps the values as they were
    back = pd.read_parquet(tmp_path / "results.parquet")
    assert back["program"].tolist() == ["=cmd|' /C calc'!A0", "@SUM(A1)"]
    assert back["error"].tolist()[0] == "-1+1\nI130=0"


def test_sweep_summary_escapes_the_spec_title_and_errors(tmp_path):
    import pandas as pd  # a dependency of ccopt (sweeps): missing is a failure, not a skip
    table = pd.DataFrame.from_records([
        {"task_id": "a", "program": "$\\frac{<b>", "style": "pmac", "error": "<script>x</script>",
         "cycle_time": None, "ok": None},
        {"task_id": "b", "program": "p2", "style": "pmac", "error": None, "cycle_time": 1.0,
         "ok": True}])
    page = write_summary(tmp_path, table, "t</title><script>alert(1)</script>$\\frac{")
    parser = _Tags()
    parser.feed(page.read_text())
    assert "script" not in parser.tags and "b" not in parser.tags
    assert (tmp_path / "summary.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_titles_are_never_mathtext():
    # an unbalanced mathtext title makes matplotlib raise when drawing
    path = ccopt.compensate(read_program(CASES / "leadin-outside-arc" / "part.pmc"), "pmac")
    png = path_plot(path, None, path.radius, [], "$\\frac{ x\ny")
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert plot_text("a $1 b\nc") == "a \\$1 b c"


@pytest.mark.parametrize("text,gcode,pmac", [
    ("x\nI130=0\nUNDEFINE ALL", "(x I130=0 UNDEFINE ALL)", "; x I130=0 UNDEFINE ALL"),
    (")(M30", "(][M30)", "; )(M30"),
    ("a b;c", "(a b,c)", "; a b,c"),
    ("a,b", "('a,b)", "; 'a,b"),        # any WORD, opening is neutralised
    ("MSG, hello", "('MSG, hello)", "; 'MSG, hello"),          # LinuxCNC would show it
    ("logopen,/tmp/x", "('logopen,/tmp/x)", "; 'logopen,/tmp/x"),  # ... or open a file
    ("ccopt: air", "('ccopt: air)", "; 'ccopt: air"),           # ccopt's own marker
    ("caf\u00e9 \u2014 x\\", "(cafe ? x\\)", "; cafe ? x/"),      # ASCII only
    ("{m}", "({m})", "; [m]"),
])
def test_comment_sanitisers(text, gcode, pmac):
    assert gcode_comment(text) == gcode
    assert pmac_comment(text) == pmac


@pytest.mark.parametrize("cell,expected", [
    ("=1+1", "'=1+1"), ("+1", "'+1"), ("-1", "'-1"), ("@A1", "'@A1"),
    ("\uff1d1", "'\uff1d1"), ("a\nb", "a b"), ("plain", "plain"), (3.5, 3.5), (None, None),
])
def test_csv_cell(cell, expected):
    assert csv_cell(cell) == expected
