"""Measure: LinuxCNC's interpreter tests, move for move (issue 31).

Every folder of LinuxCNC's ``tests/interp`` and ``tests/ccomp`` that has an
``expected`` canon file is run as its ``test.sh`` runs ``rs274``: when the
script is one plain ``rs274 [-t TABLE] -g PROGRAM`` (no INI, no plug-in, no
shell around it), the program is read with that tool table, compensated in
the ``linuxcnc`` style and its tool path compared with the STRAIGHT_TRAVERSE,
STRAIGHT_FEED (X Y Z A B C) and ARC_FEED calls of ``expected``, every coordinate within
5e-5 (``expected`` prints 4 decimals), in program (work) coordinates as the
canon prints them. Each test is then one of

* ``match``: the same moves, in the same order;
* ``differs``: read and compensated, but not the same moves (the first
  difference is printed);
* ``refused``: ccopt stops with a located error (printed);
* ``needs INI, plug-in or script``: ``test.sh`` runs more than a plain rs274;
* ``messages only``: ``test.sh`` keeps only the MESSAGE lines of the canon
  (``awk '/MESSAGE/ ...'``), which hold ``(debug, ...)`` parameter values,
  not moves: nothing to compare move for move.

    python bench/linuxcnc_interp.py LINUXCNC_SOURCE_TREE [--verbose]

LINUXCNC_SOURCE_TREE is a checkout (or ``git archive``) of LinuxCNC/linuxcnc
holding ``tests/interp`` and ``tests/ccomp``. Nothing is copied from it.
"""
from __future__ import annotations

import argparse
import re
import shlex
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from ccopt.compensate import compensate  # noqa: E402
from ccopt.errors import ProgramError  # noqa: E402
from ccopt.program.gcode import read_gcode  # noqa: E402
from ccopt.program.tooltable import read_tool_table  # noqa: E402
from linuxcnc_data import TOL, canonical_moves, parse_canon  # noqa: E402

#: The units of the tool table of an ``rs274`` run without an INI file.
RS274_TABLE_UNITS = "inch"

_PLAIN = re.compile(r"^\s*rs274\s+(?P<args>[^|&;]*?)\s*(\|\s*awk[^|]*)?(\|\s*sed[^|]*)?$")


def plain_run(script: str) -> tuple[str, str | None] | None:
    """``(program, table)`` of a ``test.sh`` that is one plain rs274 run, else None."""
    lines = [ln for ln in script.splitlines()
             if ln.strip() and not ln.lstrip().startswith("#") and not ln.startswith("exit")]
    if len(lines) != 1:
        return None
    m = _PLAIN.match(lines[0])
    if not m:
        return None
    args = shlex.split(m.group("args"))
    program = table = None
    it = iter(args)
    for a in it:
        if a == "-t":
            table = next(it, None)
        elif a == "-g":
            continue
        elif a.startswith("-"):
            return None          # -i INI, -p plug-in, -n, -v: not a plain run
        else:
            program = a
    return (program, table) if program else None


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


def run_test(folder: Path) -> tuple[str, str]:
    """``(outcome, detail)`` of one test folder."""
    plain = plain_run((folder / "test.sh").read_text())
    if plain is None:
        return "needs INI, plug-in or script", ""
    program, table = plain
    if re.search(r"awk\s+'/MESSAGE/", (folder / "test.sh").read_text()):
        return "messages only", ""
    want = parse_canon((folder / "expected").read_text())
    try:
        tools = read_tool_table(folder / table) if table else None
        # rs274 without an INI takes its tool table in inches, whatever G20/G21
        # say (src/emc/sai/driver.cc: external length units 1/25.4 per mm unless
        # the INI's [TRAJ] LINEAR_UNITS is mm)
        prog = read_gcode((folder / program).read_text(), str(folder / program),
                          tool_table=tools, table_units=RS274_TABLE_UNITS if tools else None)
        got = canonical_moves(compensate(prog, style="linuxcnc"))
    except ProgramError as exc:
        return "refused", str(exc)
    problems = differences(got, want)
    return ("differs", problems[0]) if problems else ("match", "")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tree", type=Path)
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args(argv)
    folders = sorted(p.parent for base in ("tests/interp", "tests/ccomp")
                     for p in (args.tree / base).rglob("expected"))
    counts = Counter()
    for folder in folders:
        outcome, detail = run_test(folder)
        counts[outcome] += 1
        if args.verbose or outcome in ("differs", "refused"):
            print(f"{folder.relative_to(args.tree)}: {outcome}"
                  + (f": {detail}" if detail else ""))
    print(f"{len(folders)} tests with an expected file: "
          + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
