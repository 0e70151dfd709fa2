"""What every command shares on the way out: exit codes, JSON and tables.

Exit codes (DESIGN.md): 0 success, 1 verification failed, 2 bad input (one
line ``file:line: message`` on stderr, never a traceback), 3 an unexpected
internal failure.
"""
from __future__ import annotations

import json
import math
import sys

from ccopt.toolpath import ToolPath

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERNAL = 0, 1, 2, 3


def nothing_to_do(args, prog, what: str) -> int:
    """A program with no moves (:meth:`~ccopt.program.model.Program.nothing_to_verify`):
    ``FILE: nothing to WHAT: the program has no moves`` (or that as JSON, key
    ``nothing_to_verify``) instead of figures over nothing; exit 0 (issue 29)."""
    text = prog.nothing_to_verify().replace("nothing to verify", f"nothing to {what}")
    if getattr(args, "json", False):
        emit_json({"program": prog.file, "nothing_to_verify": text})
    elif not getattr(args, "quiet", False):
        print(f"{prog.file}: {text}")
    return EXIT_OK


def emit_json(obj) -> None:
    """One JSON document on stdout (compact: it is for programs)."""
    json.dump(obj, sys.stdout, separators=(",", ":"))
    sys.stdout.write("\n")


def _fmt(x: float) -> str:
    return f"{x:.4f}"


def path_table(path: ToolPath) -> str:
    """A readable table of a tool path's segments."""
    rows = [("#", "kind", "role", "line", "start", "end", "centre / sweep")]
    for i, seg in enumerate(path.segments):
        d = seg.to_json()
        extra = ""
        if "center" in d:
            extra = (f"({_fmt(d['center'][0])}, {_fmt(d['center'][1])}) "
                     f"{'ccw' if d['ccw'] else 'cw'} {d['sweep'] * 180 / math.pi:.3f} deg")
        rows.append((str(i), d["kind"], d["role"], str(d["block"] or ""),
                     f"({_fmt(d['start'][0])}, {_fmt(d['start'][1])})",
                     f"({_fmt(d['end'][0])}, {_fmt(d['end'][1])})", extra))
    return aligned(rows)


def aligned(rows: list) -> str:
    """Rows of cells as left-aligned columns two spaces apart, no trailing blanks."""
    widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip() for r in rows)


def figure(x, fmt: str = "{:.4f}") -> str:
    """A figure of a table cell: ``-`` for none, yes/no for a flag, ``fmt`` for a number."""
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return fmt.format(x) if isinstance(x, (int, float)) else str(x)
