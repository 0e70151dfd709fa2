"""The commands shown in the README and in docs/, run as shown.

A fenced block whose first line starts with ``$ `` is a transcript: each
``$ command`` line is followed by the output it prints. :func:`transcripts`
finds them, :func:`run_transcript` runs their commands (``ccopt ...`` in this
process, in a scratch folder where ``cases/`` and ``sweeps/`` are the
repository's) and :func:`mismatch` says where the output no longer reads as
shown: exactly, except timing figures (the ``solve_s`` column of a table and
figures written ``N.N s`` after ``in``/``took``), and a line ``...`` stands
for any number of lines.

``python tests/doc_tour.py --write [DOCUMENT.md ...]`` runs every transcript
(of those documents) again and writes the outputs into them, so no output in them is typed by hand.
"""
from __future__ import annotations

import contextlib
import io
import os
import re
import shlex
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")))
#: table columns whose figures are timings, which vary run to run
TIMING_COLUMNS = ("solve_s",)
#: a timing figure in running text: "in 1.2 s", "took 0.31 s"
_TIMING_TEXT = re.compile(r"\b(in|took) \d+(\.\d+)? s\b")
_FENCE = re.compile(r"^```[a-z]*\n(\$ .*?)^```", re.S | re.M)
ELLIPSIS = "..."
#: the width --help is formatted for in the documents
HELP_WIDTH = 100


@dataclass(frozen=True)
class Step:
    command: str
    expected: tuple[str, ...]


@dataclass(frozen=True)
class Transcript:
    document: Path
    line: int          # the block's first line in the document (1-based)
    text: str          # the block's text, between the fences
    steps: tuple[Step, ...]

    @property
    def name(self) -> str:
        return f"{self.document.relative_to(ROOT)}:{self.line}"


def _steps(text: str) -> tuple[Step, ...]:
    steps: list[Step] = []
    command, out = None, []
    for line in text.splitlines():
        if line.startswith("$ "):
            if command is not None:
                steps.append(Step(command, tuple(out)))
            command, out = line[2:].split("  #")[0].strip(), []
        else:
            out.append(line)
    steps.append(Step(command, tuple(out)))
    return tuple(steps)


def transcripts(documents=DOCUMENTS) -> list[Transcript]:
    """Every transcript block of ``documents``, in order."""
    found = []
    for doc in documents:
        text = doc.read_text()
        for m in _FENCE.finditer(text):
            line = text.count("\n", 0, m.start(1)) + 1
            found.append(Transcript(doc, line, m.group(1), _steps(m.group(1))))
    return found


def run_command(command: str, folder: Path) -> str:
    """What ``command`` prints (stdout), run in ``folder``: ``ccopt ...``
    (``> FILE`` redirects it, ``| head -N`` keeps its first N lines),
    ``head -N FILE`` or ``cat FILE``."""
    words = shlex.split(command)
    target, keep = None, None
    if "|" in words:
        i = words.index("|")
        if words[i + 1:i + 2] != ["head"] or len(words) != i + 3:
            raise ValueError(f"the tour pipes into head -N only: {command!r}")
        words, keep = words[:i], int(words[i + 2].lstrip("-n"))
    if ">" in words:
        i = words.index(">")
        words, target = words[:i], words[i + 1]
    if words[0] == "ccopt":
        from ccopt.cli import main
        out = io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
            try:
                main(words[1:])
            except SystemExit:      # argparse's own exit (--help)
                pass
        text = out.getvalue()
    elif words[0] == "head":
        n = int(words[1].lstrip("-n"))
        text = "".join((folder / words[2]).read_text().splitlines(True)[:n])
    elif words[0] == "cat":
        text = (folder / words[1]).read_text()
    else:
        raise ValueError(f"the tour runs ccopt, head and cat only: {command!r}")
    if target:
        (folder / target).write_text(text)
        return ""
    if keep is not None:
        text = "".join(text.splitlines(True)[:keep])
    return text


@contextlib.contextmanager
def scratch(folder: Path):
    """``folder`` as the working directory, with the repository's ``cases/``
    and ``sweeps/`` in it (so the commands' outputs name ``cases/...``)."""
    for name in ("cases", "sweeps"):
        if not (folder / name).exists():
            (folder / name).symlink_to(ROOT / name)
    before, columns = os.getcwd(), os.environ.get("COLUMNS")
    os.chdir(folder)
    os.environ["COLUMNS"] = str(HELP_WIDTH)     # --help wraps at the terminal's width
    try:
        yield folder
    finally:
        os.chdir(before)
        if columns is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = columns


def run_transcript(t: Transcript, folder: Path) -> list[list[str]]:
    """Each step's output lines, its commands run in ``folder`` one after the other."""
    with scratch(folder):
        return [run_command(s.command, folder).rstrip("\n").splitlines() if s.command else []
                for s in t.steps]


def _timing_free(lines: list[str]) -> list[str]:
    """``lines`` with timing figures replaced by ``<t>``."""
    out, columns = [], []
    for line in lines:
        words = line.split()
        hit = [i for i, w in enumerate(words) if w in TIMING_COLUMNS]
        if hit:
            columns = hit
        elif columns and len(words) > max(columns) and not line.startswith(" "):
            words = [("<t>" if i in columns else w) for i, w in enumerate(words)]
            line = " ".join(words)
        elif not line.strip():
            columns = []
        out.append(_TIMING_TEXT.sub(r"\1 <t> s", " ".join(line.split())))
    return out


def mismatch(expected: tuple[str, ...], actual: list[str]) -> str | None:
    """``None`` when ``actual`` reads as ``expected`` shows it; else the first
    difference, said."""
    want, got = _timing_free(list(expected)), _timing_free(actual)
    i = j = 0
    while i < len(want):
        if want[i] == ELLIPSIS:
            if i + 1 == len(want):
                return None
            while j < len(got) and got[j] != want[i + 1]:
                j += 1
            if j == len(got):
                return f"after '...': {want[i + 1]!r} never printed"
            i += 1
            continue
        if j >= len(got):
            return f"line {i + 1}: expected {want[i]!r}, the output ended"
        if want[i] != got[j]:
            return f"line {i + 1}: expected\n  {want[i]!r}\nprinted\n  {got[j]!r}"
        i, j = i + 1, j + 1
    if j < len(got):
        return f"printed more than shown, from {got[j]!r}"
    return None


def _rewritten(t: Transcript, outputs: list[list[str]]) -> str:
    """The block's text with each step's output replaced by what it printed now."""
    lines = []
    for step, out in zip(t.steps, outputs):
        lines.append(f"$ {step.command}")
        lines.extend(out if step.command else step.expected)
    return "\n".join(lines) + "\n"


def write_all(folder: Path, documents=DOCUMENTS) -> None:
    """Run every transcript of ``documents`` and write what it printed into it."""
    for doc in documents:
        text = doc.read_text()
        for t in reversed(transcripts([doc])):
            outputs = run_transcript(t, folder)
            start = text.index(t.text, sum(len(x) for x in text.splitlines(True)[:t.line - 1]))
            text = text[:start] + _rewritten(t, outputs) + text[start + len(t.text):]
            print(f"{t.name}: {len(t.steps)} commands run")
        doc.write_text(text)


if __name__ == "__main__":
    import tempfile
    if sys.argv[1:2] != ["--write"]:
        sys.exit("usage: python tests/doc_tour.py --write [DOCUMENT.md ...]")
    with tempfile.TemporaryDirectory() as tmp:
        write_all(Path(tmp), [Path(d).resolve() for d in sys.argv[2:]] or DOCUMENTS)
