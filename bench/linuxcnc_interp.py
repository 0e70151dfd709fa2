"""Measure: LinuxCNC's interpreter tests, move for move (issue 31).

Every folder of LinuxCNC's ``tests/interp`` and ``tests/ccomp`` that has an
``expected`` canon file is run as its ``test.sh`` runs ``rs274``: when the
script is made of ``rs274`` runs alone (``-t TABLE``, ``-i INI``, ``-v VARS``,
``-g``, ``-n 0``/``2``; ``exec``, ``!``, ``if ! ...; then`` and ``2>&1``
allowed; no plug-in, no loop; several runs' outputs one after the other),
each program is read with those files (the tool table in
inches without an INI, as ``rs274`` takes it; ``--ini`` otherwise),
compensated in the ``linuxcnc`` style and its tool path compared with the
STRAIGHT_TRAVERSE, STRAIGHT_FEED (X Y Z A B C) and ARC_FEED calls of
``expected``, every coordinate within half a printed unit (``expected``
prints 4 decimals) plus a point's rounding, in program (work) coordinates as
the canon prints them. Each test is then one of

* ``match``: the same moves, in the same order;
* ``differs``: read and compensated, but not the same moves (the first
  difference is printed), or read where the script wants rs274 to fail;
* ``refuses where LinuxCNC stops``: ccopt stops with a located error where
  the script wants rs274 to fail (``! rs274``), or where ``expected`` (with
  rs274's messages, ``2>&1``) holds an error message;
* ``refused``: ccopt stops with a located error (printed), LinuxCNC not;
* ``needs a plug-in or script``: ``test.sh`` does more than rs274 runs, or
  loads a Python plug-in (``-p``, an INI with ``[PYTHON]``);
* a test whose ``test.sh`` keeps only the MESSAGE lines of the canon (``awk
  '/MESSAGE/ ...'``: ``(debug, ...)`` parameter values, no moves) is compared
  on its messages (``Program.meta["messages"]``): ``match`` or ``differs``.

    python bench/linuxcnc_interp.py LINUXCNC_SOURCE_TREE [--verbose]

LINUXCNC_SOURCE_TREE is a checkout (or ``git archive``) of LinuxCNC/linuxcnc
holding ``tests/interp`` and ``tests/ccomp``. Nothing is copied from it.
"""
from __future__ import annotations

import argparse
import os
import re
import shlex
from dataclasses import dataclass
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from docs_section import commit, now, write_section  # noqa: E402

from ccopt.compensate import compensate  # noqa: E402
from ccopt.errors import ProgramError  # noqa: E402
from ccopt.program import read_program  # noqa: E402
from ccopt.program.model import MESSAGES  # noqa: E402
from linuxcnc_data import TOL, canonical_moves, parse_canon  # noqa: E402

#: The units of the tool table of an ``rs274`` run without an INI file.
RS274_TABLE_UNITS = "inch"

#: Script lines around the runs that change nothing compared here: comments,
#: exits, exports, ``if``/``fi``, ``echo``, ``rm -f``, a ``trim`` filter's
#: definition, and the parts of a run-under-a-timeout idiom (``rs274 ... >
#: result &`` then a ``while kill -0 $pid`` loop that kills it after N s).
_NEUTRAL = re.compile(r"^\s*(#|exit\b|export\s|fi\s*$|then\s*$|echo\b|rm\s+-f\s|set\s+-"
                      r"|\w+\(\)\s*\{\s*sed\s[^|]*\}\s*$|pid=\$!|count=(\d+|\$\(\(count - 1\)\))\s*$"
                      r"|while\s+\[[^]]*\]\s*&&\s*kill\s+-0\s|sleep\s+\d+\s*$|done\s*$"
                      r"|if\s+kill\s+-0\s|kill\s+-9\s)")
#: ``cp FROM TO``: a file the runs read under another name.
_COPY = re.compile(r"^\s*cp\s+(\S+)\s+(\S+)\s*$")
#: The filters an rs274 run's output may pass through (none changes a move).
_FILTERS = ("awk", "sed", "trim")


@dataclass
class Run:
    """One ``rs274`` run of a ``test.sh``: its program, tool table, INI and
    parameter files; whether the script wants it to fail (``! rs274``), and
    whether its error messages go into ``expected`` (``2>&1``)."""

    program: str
    table: str | None = None
    ini: str | None = None
    var: str | None = None
    fails: bool = False
    errors_shown: bool = False
    first_field_dropped: bool = False     # awk '{$1=""; print}' on its output
    keep_going: bool = False              # -n 0: rs274 goes on after an error
    zero_sign_dropped: bool = False       # sed 's/-0\.0000/0.0000/g' on its output


def plain_runs(script: str) -> list[Run] | None:
    """The :class:`Run` of each ``rs274`` line of a ``test.sh`` made of such runs
    alone (``-t``, ``-i``, ``-v``, ``-g`` and ``-n 0``/``-n 2`` taken; ``exec``,
    ``export``, ``echo``, ``cp``, ``if ! ...; then ... fi``, ``{ ! ...; }`` and
    ``... || exit 1`` around them, ``2>&1``, output filters and a timeout
    allowed), else None (a plug-in, a loop, other commands)."""
    script = script.replace("\\\n", " ")                 # continued lines, joined
    copies: dict[str, str] = {}
    runs = []
    for ln in script.splitlines():
        if not ln.strip() or _NEUTRAL.match(ln):
            continue
        m = _COPY.match(ln)
        if m:
            copies[m.group(2)] = m.group(1)
            continue
        run = _run(ln)
        if run is None:
            return None
        runs.append(run)
    for run in runs:
        for attr in ("program", "table", "ini", "var"):
            name = getattr(run, attr)
            if name in copies:
                setattr(run, attr, copies[name])
    return runs or None


def _run(line: str) -> Run | None:
    """The run of one script line, or None when it is not a plain rs274 run."""
    try:
        lex = shlex.shlex(line.replace("2>&1", " __ERR__ "), posix=True,
                          punctuation_chars=";&|<>{}")
        lex.whitespace_split = True
        tokens = list(lex)
    except ValueError:                                    # not a plain word list
        return None
    neg = False
    while tokens and tokens[0] in ("{", "if", "!", "exec"):
        neg = neg or tokens[0] == "!"
        tokens.pop(0)
    if not tokens or tokens[0] != "rs274":
        return None
    i = 1
    args = []
    while i < len(tokens) and tokens[i] not in ("|", "||", ";", "&", ">", ";}"):
        args.append(tokens[i])
        i += 1
    if not _plain_tail(tokens[i:]):
        return None
    run = Run("", fails=neg, errors_shown="__ERR__" in args,
              zero_sign_dropped=any(a == "sed" and b == r"s/-0\.0000/0.0000/g"
                                    for a, b in zip(tokens[i:], tokens[i + 1:])),
              first_field_dropped=any(a == "awk" and b.replace(" ", "") == '{$1="";print}'
                                      for a, b in zip(tokens[i:], tokens[i + 1:])))
    it = iter(a for a in args if a != "__ERR__")
    for a in it:
        if a in ("-t", "-i", "-v"):
            setattr(run, {"-t": "table", "-i": "ini", "-v": "var"}[a], next(it, None))
        elif a == "-g":
            continue
        elif a == "-n":
            # 2 stops at an error; 0 goes on after it (read_program's keep_going);
            # 1 is interactive
            mode = next(it, None)
            if mode not in ("0", "2"):
                return None
            run.keep_going = mode == "0"
        elif a.startswith("-"):
            return None          # -p plug-in: not a plain run
        else:
            run.program = a
    return run if run.program else None


def _plain_tail(tokens: list[str]) -> bool:
    """Whether what follows a run's arguments only filters its output (``|
    awk ...``, ``| sed ...``, ``| trim``), ends a group (``; }``, ``; then``),
    writes the output to a file (``> result``), runs it in the background
    (``&``) or exits on failure (``|| exit 1``)."""
    i = 0
    while i < len(tokens):
        t = tokens[i]
        if t == "|" and i + 1 < len(tokens) and tokens[i + 1] in _FILTERS:
            i += 3 if tokens[i + 1] in ("awk", "sed") else 2
        elif t in (";", ";}") and i + 1 < len(tokens) and tokens[i + 1] in ("}", "then"):
            i += 2
        elif t == ";}" or t == "&" or t == "}":
            i += 1
        elif t == ">" and i + 1 < len(tokens):
            i += 2
        elif t == "||" and tokens[i + 1:i + 3] == ["exit", "1"]:
            i += 3
        else:
            return False
    return True


def differences(got, want) -> list[str]:
    """Moves of ``got`` that are not ``want``'s, in words (empty: a match)."""
    out = []
    if len(got) != len(want):
        out.append(f"{len(got)} moves, LinuxCNC {len(want)}")
    for i, ((k1, a), (k2, b)) in enumerate(zip(got, want)):
        if k1 != k2:
            out.append(f"move {i}: {k1}, LinuxCNC {k2}")
            break
        # straight moves: X Y Z A B C; arcs: end, centre, turn, axis
        fields = tuple(range(min(6, len(a), len(b)))) if k1 != "ARC_FEED" else (0, 1, 2, 3, 5)
        bad = [q for q in fields if not abs(a[q] - b[q]) <= TOL]
        if k1 == "ARC_FEED" and int(a[4]) != int(b[4]):
            bad.append(4)
        if bad:
            out.append(f"move {i} {k1}: ccopt {[round(x, 4) for x in a[:6]]}, "
                       f"LinuxCNC {b[:6]}")
            break
    return out


#: Why a test needs Python (the acceptance counts the tests without it).
PLUG_IN = "it loads an interpreter plug-in (rs274 -p)"
PYTHON_INI = "its INI loads Python ([PYTHON])"


def run_test(folder: Path) -> tuple[str, str]:
    """``(outcome, detail)`` of one test folder."""
    if (folder / "skip").exists() and not os.access(folder / "skip", os.X_OK):
        return "skipped by LinuxCNC", "its runner skips it (a `skip` file)"
    script = (folder / "test.sh").read_text()
    if re.search(r"\brs274\b[^\n]*\s-p\s", script):
        return "needs a plug-in or script", PLUG_IN
    runs = plain_runs(script)
    if runs is None:
        return "needs a plug-in or script", _why_not_plain(folder, script)
    if any(r.ini and re.search(r"^\s*\[PYTHON\]", (folder / r.ini).read_text(), re.M)
           for r in runs):
        return "needs a plug-in or script", PYTHON_INI
    if re.search(r"awk\s+'/MESSAGE/", script):
        return _messages(folder, runs)
    expected = (folder / "expected").read_text()
    segments = _segments(expected, len(runs))
    if segments is None:
        return "needs a plug-in or script", "its runs' outputs cannot be told apart"
    echoes = set(re.findall(r"^\s*echo\s+[\"']?(.*?)[\"']?\s*$", script, re.M))
    results = [_compare_run(folder, run, seg, echoes) for run, seg in zip(runs, segments)]
    bad = next(((o, d) for o, d in results
                if o not in ("match", "refuses where LinuxCNC stops")), None)
    if bad is not None:
        return bad
    notes = [d for o, d in results if o == "match" and d]
    if notes and not any(o == "refuses where LinuxCNC stops" for o, _ in results):
        return "match", notes[0]
    stops = [d for o, d in results if o == "refuses where LinuxCNC stops"]
    if len(stops) == len(results):
        return "refuses where LinuxCNC stops", stops[-1]
    if stops:
        return "match", (f"{len(results) - len(stops)} runs match, {len(stops)} refuse where "
                         f"LinuxCNC stops ({stops[0]})")
    return "match", ""


#: A canon call as rs274 prints it: its line number (``N.....`` or ``N1234``) first.
_CANON_CALL = re.compile(r"N[.\d]+\s+[A-Z][A-Za-z0-9_.]*\(")


def _why_not_plain(folder: Path, script: str) -> str:
    """What a ``test.sh`` does beyond plain rs274 runs, in words."""
    why = []
    if re.search(r"^\s*linuxcnc\s", script, re.M):
        why.append("it runs LinuxCNC itself against a motion logger")
    if re.search(r"^\s*for\s", script, re.M):
        why.append("it loops over programs and judges each run's exit status")
    if (folder / "xfail").exists():
        why.append("LinuxCNC expects it to fail (an `xfail` file)")
    return "; ".join(why)


def _segments(expected: str, n: int) -> list[str] | None:
    """``expected`` cut into the outputs of ``n`` rs274 runs (each starts with
    canon's USE_LENGTH_UNITS), or None when it does not hold ``n``."""
    if n == 1:
        return [expected]
    starts = [m.start() for m in re.finditer(r"^.*USE_LENGTH_UNITS\(", expected, re.M)]
    if len(starts) != n:
        return None
    return [expected[a:b] for a, b in zip(starts, starts[1:] + [len(expected)])]


def _text_lines(segment: str, echoes: set[str]) -> list[str]:
    """The lines of one run's output that are no canon call, ``executing`` or a
    line the script echoes: what the program printed (``(print, ...)``) and
    rs274's error messages (``2>&1``)."""
    out = []
    for ln in segment.splitlines():
        text = re.sub(r"^\s*\d+\s+(?=N[.\d])", "", ln).strip()
        if text and not _CANON_CALL.match(text) and text != "executing" \
                and text not in echoes:
            out.append(text)
    return out


def _compare_run(folder: Path, run: Run, segment: str, echoes: set[str]) -> tuple[str, str]:
    """One run against its output ``segment``: its moves, what it prints, or,
    where LinuxCNC stops with an error, ccopt's refusal at the same block."""
    try:
        prog = _program(folder, run)
    except ProgramError as exc:
        if run.fails or (run.errors_shown and _stops_with_an_error(segment)):
            problems = _moves_before(exc, segment)
            if problems:
                return "differs", f"before the error ({exc}): {problems[0]}"
            return "refuses where LinuxCNC stops", str(exc)
        return "refused", str(exc)
    if run.fails:
        return "differs", f"ccopt reads {run.program}; LinuxCNC stops with an error"
    try:
        got = canonical_moves(compensate(prog, style="linuxcnc"))
    except ProgramError as exc:
        return "refused", str(exc)
    problems = differences(got, parse_canon(segment))
    if problems:
        return "differs", problems[0]
    prints = [m["text"] for m in prog.meta.get(MESSAGES, ()) if m.get("kind") == "print"]
    if run.first_field_dropped:             # what the script's awk leaves of each line
        prints = [" ".join(p.split()[1:]) for p in prints]
    prints = [p.strip() for p in prints if p.strip()]
    want = _text_lines(segment, echoes)
    if prints != want and (prints or not run.errors_shown):
        return "differs", f"it prints {prints}, LinuxCNC {want}"
    return "match", _message_difference(prog, segment, run)


def _message_difference(prog, segment: str, run: Run) -> str:
    """Where the program's ``(debug, ...)``/``(msg, ...)`` messages differ from
    the MESSAGE calls of LinuxCNC's output (after the script's ``sed`` of
    -0.0000 to 0.0000, when it has one), in words; empty when they agree.
    Moves decide the outcome; this is reported beside it."""
    shown = [m["text"] for m in prog.meta.get(MESSAGES, ()) if m.get("kind") != "print"]
    if run.zero_sign_dropped:
        shown = [re.sub(r"-0\.0000", "0.0000", m) for m in shown]
    if run.first_field_dropped:              # awk rebuilds each line with single blanks
        shown = [re.sub(r"\s+", " ", m) for m in shown]
    wanted = re.findall(r'MESSAGE\("(.*)"\)', segment)
    if shown == wanted:
        return ""
    i = next((k for k, (a, b) in enumerate(zip(shown, wanted)) if a != b),
             min(len(shown), len(wanted)))
    return (f"{MESSAGES_DIFFER}: message {i}: ccopt {shown[i] if i < len(shown) else None!r}, "
            f"LinuxCNC {wanted[i] if i < len(wanted) else None!r}")


#: How a detail says that a test matches move for move but not in its messages.
MESSAGES_DIFFER = "its debug messages differ"


def _moves_before(exc: ProgramError, segment: str) -> list[str]:
    """How the moves ccopt read before its error differ from those LinuxCNC
    made before it stopped (empty: the same; nothing read, as for a read
    error before the program runs, compares as no moves)."""
    before = exc.read_before
    got = canonical_moves(compensate(before, style="linuxcnc")) if before else []
    return differences(got, parse_canon(segment))


def _messages(folder: Path, runs: list[Run]) -> tuple[str, str]:
    """A test that keeps only the canon's MESSAGE lines (``awk '/MESSAGE/'``, and
    the script's ``sed`` of -0.0000 to 0.0000): ccopt's ``(debug, ...)`` and
    ``(msg, ...)`` messages against them."""
    want = re.findall(r'MESSAGE\("(.*)"\)', (folder / "expected").read_text())
    got = []
    for run in runs:
        try:
            prog = _program(folder, run)
        except ProgramError as exc:
            return "refused", str(exc)
        got += [re.sub(r"-0\.0000", "0.0000", m["text"]) for m in prog.meta.get(MESSAGES, ())]
    if got == want:
        return "match", "its messages"
    bad = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
    return "differs", (f"message {bad}: ccopt {got[bad] if bad < len(got) else None!r}, "
                       f"LinuxCNC {want[bad] if bad < len(want) else None!r}")


def _program(folder: Path, run: Run):
    """``run``'s program as ccopt reads it. rs274 without an INI takes its tool
    table in inches, whatever G20/G21 say (src/emc/sai/driver.cc: external
    length units 1/25.4 per mm unless the INI's [TRAJ] LINEAR_UNITS is mm);
    with one, read_program takes the INI's."""
    return read_program(folder / run.program, "gcode",
                        tool_table=folder / run.table if run.table else None,
                        var_file=folder / run.var if run.var else None,
                        table_units=RS274_TABLE_UNITS if run.table and not run.ini else None,
                        ini=folder / run.ini if run.ini else None,
                        keep_going=run.keep_going)


def _moves(folder: Path, run: Run) -> list:
    """The canonical moves of ``run``'s program as ccopt reads (:func:`_program`)
    and compensates it."""
    return canonical_moves(compensate(_program(folder, run), style="linuxcnc"))


def _stops_with_an_error(expected: str) -> bool:
    """Whether rs274's output (with its error messages, ``2>&1``) has a line that
    is neither a canon call nor ``executing``: its error message."""
    return any(ln.strip() and not re.match(r"^\s*(\d+\s+)?N\.\.\.\.\.", ln)
               and ln.strip() != "executing" for ln in expected.splitlines())


#: The page and section ``--docs`` writes.
DOCS = ROOT / "docs" / "gcode.md"
SECTION = "bench/linuxcnc_interp.py"
#: The outcomes, in the order the page lists them.
OUTCOMES = ("match", "refuses where LinuxCNC stops", "differs", "refused",
            "needs a plug-in or script", "skipped by LinuxCNC")


def docs_body(results: list[tuple[str, str, str]], linuxcnc: str) -> str:
    """The figures of one run (``(test, outcome, detail)`` each) as Markdown."""
    counts = Counter(outcome for _, outcome, _ in results)
    lines = [f"`python bench/linuxcnc_interp.py TREE --docs` on {now()}, ccopt commit "
             f"{commit()}, LinuxCNC {linuxcnc}: {len(results)} tests with an `expected` "
             "file.", "", "| outcome | tests |", "| --- | ---: |"]
    lines += [f"| {k} | {counts[k]} |" for k in OUTCOMES if counts[k]]
    run = [(o, d) for _, o, d in results
           if o != "skipped by LinuxCNC" and d not in (PLUG_IN, PYTHON_INI)]
    right = sum(o in OUTCOMES[:2] for o, _ in run)
    lines += ["", f"Of the {len(run)} tests LinuxCNC runs without Python (no plug-in, no "
              f"`[PYTHON]` INI), {right} ({100 * right / len(run):.0f} %) match or refuse "
              "where LinuxCNC stops."]
    differ = [(t, d) for t, o, d in results if o == "match" and MESSAGES_DIFFER in d]
    if differ:
        lines += ["", f"{len(differ)} of the matching tests match move for move but not in "
                  "the text of their `(debug, ...)` messages:", ""]
        lines += [f"- `{t}`: {d}" for t, d in differ]
    lines += ["", "Every test that does not match:", ""]
    for k in OUTCOMES[1:]:
        for test, outcome, detail in results:
            if outcome == k:
                why = detail.split(": ", 1)[-1] if detail.startswith("/") else detail
                why = why.split(": ccopt reads G0")[0]      # the G-code list, left out
                lines.append(f"- `{test}`: {k}" + (f" ({why})" if why else ""))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tree", type=Path)
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--docs", action="store_true",
                    help=f"write the figures into {DOCS.relative_to(ROOT)}")
    ap.add_argument("--linuxcnc-commit", default="(commit not given)",
                    help="the LinuxCNC commit of TREE, named on the page")
    args = ap.parse_args(argv)
    folders = sorted(p.parent for base in ("tests/interp", "tests/ccomp")
                     for p in (args.tree / base).rglob("expected"))
    counts = Counter()
    results = []
    for folder in folders:
        outcome, detail = run_test(folder)
        counts[outcome] += 1
        test = str(folder.relative_to(args.tree))
        results.append((test, outcome, detail.replace(str(folder) + "/", "")))
        if args.verbose or outcome in ("differs", "refused"):
            print(f"{test}: {outcome}" + (f": {detail}" if detail else ""))
    print(f"{len(folders)} tests with an expected file: "
          + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))
    if args.docs:
        write_section(DOCS, SECTION, docs_body(results, args.linuxcnc_commit))
        print(f"written: {DOCS}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
