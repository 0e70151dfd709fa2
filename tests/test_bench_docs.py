"""A benchmark's ``--docs`` writes what it printed into its own marked section
of the benchmarks page (bench/docs_section.printed_section, issue 34: the
benches write the figures page): the printed lines verbatim in a code block,
under a heading, with the command, the date, the commit and the machine; a
second run replaces the section; without a page nothing is written and the
figures are still printed."""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

_BENCH = Path(__file__).resolve().parents[1] / "bench"
_spec = importlib.util.spec_from_file_location("bench_docs_section", _BENCH / "docs_section.py")
docs_section = importlib.util.module_from_spec(_spec)
sys.modules["bench_docs_section"] = docs_section
_spec.loader.exec_module(docs_section)


def test_printed_figures_go_into_their_section(tmp_path, capsys):
    page = tmp_path / "benchmarks.md"
    page.write_text("# Benchmarks\n\nSome text.\n")
    with docs_section.printed_section(page, "bench/x.py", "python bench/x.py --n 3", "X bench"):
        print("first line: 1.50 s")
        print("ratio       :      2.00")
    assert "first line: 1.50 s" in capsys.readouterr().out      # still printed
    text = page.read_text()
    begin, end = docs_section.markers("bench/x.py")
    assert text.startswith("# Benchmarks\n\nSome text.\n")
    body = text.split(begin)[1].split(end)[0]
    assert "### X bench" in body
    assert "`python bench/x.py --n 3` on " in body
    assert f"commit {docs_section.commit()}" in body and "cores" in body
    assert "```\nfirst line: 1.50 s\nratio       :      2.00\n```" in body
    with docs_section.printed_section(page, "bench/x.py", "python bench/x.py", "X bench"):
        print("second run")
    text = page.read_text()
    assert text.count(begin) == 1 and "second run" in text and "first line" not in text


def test_without_a_page_nothing_is_written(tmp_path, capsys):
    page = tmp_path / "benchmarks.md"
    with docs_section.printed_section(None, "bench/x.py", "python bench/x.py", "X"):
        print("only printed")
    assert capsys.readouterr().out == "only printed\n"
    assert not page.exists()


def test_a_section_names_the_machine_speed_before_and_after(tmp_path):
    """The host's speed drifts with the load average unchanged: each section
    carries the CPU time of a fixed Python loop before and after its run."""
    import re

    page = tmp_path / "benchmarks.md"
    with docs_section.printed_section(page, "bench/y.py", "python bench/y.py", "Y bench"):
        print("figure")
    m = re.search(r"speed reference \(bench/docs_section\.py: a fixed Python loop, larger is "
                  r"slower\) ([0-9.]+) ms before, ([0-9.]+) ms after", page.read_text())
    assert m is not None
    assert float(m.group(1)) > 0.0 and float(m.group(2)) > 0.0
