"""Every command the README and docs/ show runs, and prints what they show
(tests/doc_tour.py: exact, except timing figures)."""
from __future__ import annotations

import pytest

from doc_tour import ROOT, mismatch, run_transcript, transcripts

#: commands that take seconds each (the comparison's optimised variants, a run, a sweep)
_SLOW_WORDS = ("compare", "smooth", " run", "sweep")


def _params():
    out = []
    for t in transcripts():
        slow = any(w in s.command for s in t.steps for w in _SLOW_WORDS if s.command)
        out.append(pytest.param(t, id=t.name, marks=[pytest.mark.slow] if slow else []))
    return out


def test_the_readme_has_a_tour():
    shown = [t for t in transcripts() if t.document.name == "README.md"]
    commands = " ".join(s.command for t in shown for s in t.steps)
    for command in ("show", "verify", "feed", "compare", "export"):
        assert f"ccopt {command} cases/" in commands, command
    programs = {w for s in (s for t in shown for s in t.steps) for w in s.command.split()
                if w.startswith("cases/")}
    assert any(p.endswith(".nc") for p in programs) and \
        any(not p.endswith(".nc") for p in programs), programs


@pytest.mark.parametrize("transcript", _params())
def test_shown_output_is_what_the_command_prints(transcript, tmp_path):
    outputs = run_transcript(transcript, tmp_path)
    for step, out in zip(transcript.steps, outputs):
        problem = mismatch(step.expected, out)
        assert problem is None, f"{transcript.name}: $ {step.command}\n{problem}"


def test_the_readme_and_ci_run_the_same_test_command():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    verbatim = ci[ci.index(next(x for x in ci if "test command, verbatim" in x)) + 1]
    readme = (ROOT / "README.md").read_text()
    assert f"\n{verbatim}\n" in readme
    main_job = "python3 -m venv .venv && .venv/bin/pip install -q -e . && .venv/bin/ccopt run"
    assert f"\n{main_job}\n" in readme


def test_the_readme_is_short():
    assert len((ROOT / "README.md").read_text().splitlines()) <= 220


def test_the_cli_reference_is_the_parsers_help():
    import importlib.util
    spec = importlib.util.spec_from_file_location("cli_reference", ROOT / "docs" / "cli_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert (ROOT / "docs" / "cli.md").read_text() == module.reference(), \
        "docs/cli.md is out of date: run python docs/cli_reference.py"
