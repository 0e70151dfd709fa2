"""Read, compensate and verify every Klartext program of a corpus folder.

Issue 32 asks that a public corpus of HEIDENHAIN programs (the GitHub project
polymech-info/heidenhain-simulator keeps 2,686 ``.h`` files under
``samples/``, most of them CAM output) reads without a traceback: each
program gives a path or a located refusal, none runs over 20 s. Clone it
and point this script at its ``samples`` folder:

    git clone https://github.com/polymech-info/heidenhain-simulator /tmp/hs
    .venv/bin/python bench/klartext_corpus.py /tmp/hs/samples [--radius 3] [--jobs 2]

Per program: ``read`` (read fully), ``refused`` (a located ProgramError; the
reason is the message without its numbers), ``traceback`` (any other
exception: a bug), ``timeout`` (over ``--timeout`` seconds); of the programs
read, ``compensated`` (the ``heidenhain`` style made a path, with
``--radius`` where the program gives none) and ``verified`` (the certificate
passed). Prints the shares and the most frequent refusal reasons; exits 1
when any program gave a traceback or a timeout.

``--docs docs/heidenhain.md`` also writes the figures (date, number of
programs, shares, refusal reasons) into that file, between the markers
``<!-- klartext-corpus: begin -->`` and ``<!-- klartext-corpus: end -->``
(appended as a new section when the file has none); ``--note`` adds a
sentence on where the programs came from.
"""
from __future__ import annotations

import argparse
import datetime
import re
import signal
import sys
import textwrap
import time
import traceback
from collections import Counter
from multiprocessing import Pool
from pathlib import Path

# the bench folder's own modules, also when a test loads this file by its path
sys.path.insert(0, str(Path(__file__).resolve().parent))
from docs_section import markers, write_section  # noqa: E402

from ccopt import verify  # noqa: E402
from ccopt.compensate import compensate  # noqa: E402
from ccopt.errors import ProgramError  # noqa: E402
from ccopt.program import read_program  # noqa: E402

_NUMBERS = re.compile(r"[-+]?\d+(\.\d+)?")


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def classify(path: str, radius: float = 3.0, timeout: float = 20.0) -> dict:
    """What reading, compensating and verifying ``path`` gave (see the module
    docstring); ``seconds`` is the wall time."""
    out = {"file": path, "status": None, "reason": None, "compensated": False,
           "verified": False}
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    t0 = time.perf_counter()
    try:
        prog = read_program(path, "heidenhain")
        out["status"] = "read"
        try:
            tp = compensate(prog, style="heidenhain",
                            radius=None if _has_radius(prog) else radius)
            out["compensated"] = True
            out["verified"] = bool(verify(tp, prog).ok)
        except ProgramError as exc:
            out["reason"] = "compensate: " + _NUMBERS.sub("#", exc.message)
    except ProgramError as exc:
        out["status"] = "refused" if exc.line is not None else "refused-unlocated"
        out["reason"] = _NUMBERS.sub("#", exc.message)
    except _Timeout:
        out["status"] = "timeout"
    except Exception:   # noqa: BLE001 - a bug: counted and shown, never hidden
        out["status"] = "traceback"
        out["reason"] = traceback.format_exc(limit=3)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    out["seconds"] = time.perf_counter() - t0
    return out


def _has_radius(prog) -> bool:
    return all(b.modal.radius is not None for b in prog.blocks if b.modal.side != 0)


def run(folder: Path, radius: float = 3.0, jobs: int = 2, timeout: float = 20.0) -> list[dict]:
    files = sorted(str(p) for p in folder.rglob("*.h"))
    args = [(f, radius, timeout) for f in files]
    if jobs <= 1:
        return [classify(*a) for a in args]
    with Pool(jobs) as pool:
        return pool.starmap(classify, args, chunksize=8)


def report(results: list[dict]) -> str:
    n = len(results) or 1
    status = Counter(r["status"] for r in results)
    lines = [f"{len(results)} programs"]
    for key in ("read", "refused", "refused-unlocated", "traceback", "timeout"):
        lines.append(f"  {key:18s} {status[key]:6d}  {100.0 * status[key] / n:6.2f} %")
    comp = sum(r["compensated"] for r in results)
    ver = sum(r["verified"] for r in results)
    lines.append(f"  {'compensated':18s} {comp:6d}  {100.0 * comp / n:6.2f} %")
    lines.append(f"  {'verified':18s} {ver:6d}  {100.0 * ver / n:6.2f} %")
    slowest = max(results, key=lambda r: r["seconds"], default=None)
    if slowest:
        lines.append(f"  slowest {slowest['seconds']:.2f} s: {slowest['file']}")
    reasons = Counter(r["reason"] for r in results if r["status"] == "refused")
    lines.append("top refusal reasons:")
    lines += [f"  {c:5d}  {why}" for why, c in reasons.most_common(12)]
    bad = [r for r in results if r["status"] in ("traceback", "timeout", "refused-unlocated")]
    for r in bad[:10]:
        lines.append(f"{r['status']}: {r['file']}\n{r['reason'] or ''}")
    return "\n".join(lines)


#: The docs section this script writes (:mod:`docs_section`) and its markers.
SECTION = "klartext-corpus"
BEGIN, END = markers(SECTION)


def figures_markdown(results: list[dict], folder: str, radius: float, note: str = "",
                     today: str | None = None) -> str:
    """The figures of one run as a Markdown section (between the markers)."""
    n = len(results) or 1
    status = Counter(r["status"] for r in results)
    comp = sum(r["compensated"] for r in results)
    ver = sum(r["verified"] for r in results)
    today = today or datetime.datetime.now(datetime.timezone.utc).date().isoformat()
    rows = [(k, status[k]) for k in ("read", "refused", "refused-unlocated", "traceback",
                                     "timeout")] + [("compensated", comp), ("verified", ver)]
    intro = (f"Measured {today} with `bench/klartext_corpus.py` on {len(results)} programs "
             f"(`{folder}`, `--radius {radius:g}` where a program gives none)."
             + (f" {note}" if note else ""))
    out = [BEGIN, "## Corpus figures", "", textwrap.fill(intro, 78, break_on_hyphens=False,
                                                          break_long_words=False), "",
           "| programs | count | share |", "| --- | ---: | ---: |"]
    out += [f"| {k} | {c} | {100.0 * c / n:.1f} % |" for k, c in rows]
    reasons = Counter(r["reason"] for r in results if r["status"] == "refused")
    comp_reasons = Counter(r["reason"] for r in results
                           if r["status"] == "read" and r["reason"])
    if reasons or comp_reasons:
        out += ["", "| refusal reason | programs |", "| --- | ---: |"]
        out += [f"| {why} | {c} |" for why, c in (reasons + comp_reasons).most_common(12)]
    slowest = max(results, key=lambda r: r["seconds"], default=None)
    if slowest:
        out += ["", f"Slowest program: {slowest['seconds']:.2f} s."]
    out.append(END)
    return "\n".join(out)


def write_docs(path: Path, section: str) -> None:
    """Replace the marked section of ``path`` by ``section`` (:func:`figures_markdown`,
    markers included); append it when the file has no markers."""
    write_section(path, SECTION, section.removeprefix(BEGIN).removesuffix(END))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", type=Path)
    ap.add_argument("--radius", type=float, default=3.0,
                    help="cutter radius where a program gives none (default 3)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per program")
    ap.add_argument("--docs", type=Path, help="write the figures into this Markdown file")
    ap.add_argument("--note", default="", help="a sentence on where the programs came from")
    args = ap.parse_args(argv)
    results = run(args.folder, args.radius, args.jobs, args.timeout)
    print(report(results))
    if args.docs:
        write_docs(args.docs, figures_markdown(results, args.folder.name, args.radius,
                                               args.note))
    bad = any(r["status"] in ("traceback", "timeout", "refused-unlocated") for r in results)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
