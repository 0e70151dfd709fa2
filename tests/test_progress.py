"""The progress line reads: one counter per level, stage text cut between
words, a bar even where the terminal does not say its width."""
from __future__ import annotations

import io
import re

import pytest

from ccopt.cli import progress
from ccopt.cli.progress import CasesProgress, clip

TEXTS = ["leadin-outside-line: compare: variants 8/10 done: opt-casadi",
         "freeform-hsm: feed: jerk planner, window 12 of 40", "pocket: export",
         "a-very-long-case-name-with-no-spaces-at-all-in-it-whatsoever-really"]


@pytest.mark.parametrize("text", TEXTS)
@pytest.mark.parametrize("width", [10, 25, 40, 60])
def test_clip_cuts_between_words(text, width):
    got = clip(text, width)
    assert len(got) <= width
    if got == text:
        return
    assert got.endswith("\u2026")
    kept = got[:-1]
    assert text.startswith(kept)
    if " " in text[:width - 1]:
        # the cut falls between words: what follows the kept part starts a separator
        assert text[len(kept)] in " :,|", (got, text)
    # else one word longer than the line: its start (the only place to cut)


def test_a_bar_is_drawn_when_the_terminal_width_is_unknown(monkeypatch):
    err = io.StringIO()
    monkeypatch.setattr(progress.sys, "stderr", err)
    monkeypatch.setattr(progress, "terminal_columns", lambda: None)
    bar = CasesProgress(["pocket", "profile"])
    bar.stage(0, "compare: variant 3/10 tangent-arc")
    bar.done(0, {})
    bar.close()
    text = err.getvalue()
    # 1 of 2 cases: a half-filled bar of the fallback width
    assert re.search(r"cases:\s+50%\|[#\u2588]+", text), text
    assert "1/2" in text
    assert any(len(line) == progress.FALLBACK_COLUMNS for line in text.split("\r")), text


def test_each_comparison_progress_line_has_one_counter():
    import ccopt
    from ccopt.cases import find_case
    from ccopt.compare.core import compare
    from ccopt.feed import AxisLimits
    case = find_case("leadin-inside-line")
    prog = ccopt.read_program(case.program)
    names = ["pmac", "linuxcnc", "tangent-arc", "line-arc"]
    for workers in (1, 2):
        lines: list[str] = []
        compare(prog, names, limits=AxisLimits(case.vmax, case.amax), workers=workers,
                      progress=lines.append)
        counted = [x for x in lines if x.startswith("variant")]
        assert counted, lines
        for line in counted:
            assert len(re.findall(r"\d+/\d+", line)) == 1, line
        if workers == 2:     # the workers' variants counted as they finish, to the last
            assert counted[-1].startswith(f"variants {len(names) - 1}/{len(names) - 1} done: ")
