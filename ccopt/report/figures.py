"""How the report writes figures: numbers with sensible digits, round-off
noise as 0, gains as signed percentages, booleans and verdicts as words.

Every function returns escaped HTML text (a cell's content).
"""
from __future__ import annotations

import math
from typing import Any

from ccopt.export.text import html_text

#: A figure smaller than this (in its own unit) is round-off of an exact zero
#: (4.44e-16 from a difference of two equal coordinates), written 0.
ROUND_OFF = 1e-9

#: How each kind of figure is written: (format, unit shown after it).
FORMATS = {
    "time": ("{:.3f}", " s"),
    "solve_time": ("{:.2f}", " s"),
    "length": ("{:.3f}", ""),
    "clearance": ("{:.4f}", ""),
    "curvature": ("{:.3g}", ""),
    "ratio": ("{:.4f}", ""),
    "plain": ("{:.6g}", ""),
}


def number(x: Any, kind: str = "plain") -> str:
    """``x`` as a figure of ``kind`` (:data:`FORMATS`); words for the rest:
    ``-`` for none, yes/no for booleans, text escaped."""
    if x is None or x == "":
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int, float)):
        x = float(x)
        if math.isnan(x):
            return "n/a"
        if math.isinf(x):
            return "&infin;" if x > 0 else "-&infin;"
        if abs(x) < ROUND_OFF:
            x = 0.0
        spec, unit = FORMATS[kind]
        return spec.format(x) + unit
    return html_text(x)


def gain(x: float | None) -> str:
    """A gain in cycle time (``1 - t / t_ref``) as a signed percentage; ``-``
    when there is no reference."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if abs(x) < ROUND_OFF:
        x = 0.0
    return f"{100 * x:+.2f} %"


def verdict(ok: bool | None, text: str | None = None) -> str:
    """ok/failed as a word in colour (``text`` instead of the word when given)."""
    word = text if text is not None else ("ok" if ok else "failed")
    return f'<span class="{"ok" if ok else "fail"}">{html_text(word)}</span>'


def status(s: str) -> str:
    """A case's or variant's status in colour: green when it is what was asked
    (ok, or the expected verdict), red otherwise."""
    good = s.startswith("ok") or "expected" in s
    return verdict(good, s)


def detail(value: Any, depth: int = 0) -> str:
    """A check's detail: one ``key: value`` per line, a long list folded
    under its length (``<details>``), numbers written as :func:`number`."""
    if isinstance(value, dict):
        lines = [f"<b>{html_text(k.replace('_', ' '))}</b>: {detail(v, depth + 1)}"
                 for k, v in value.items()]
        return "<br>".join(lines) if depth == 0 else "; ".join(lines)
    if isinstance(value, (list, tuple)):
        if not value:
            return "none"
        items = [detail(v, depth + 1) for v in value]
        if len(items) <= 3 and all(not isinstance(v, (dict, list)) for v in value):
            return ", ".join(items)
        body = "".join(f"<li>{i}</li>" for i in items)
        return f"<details><summary>{len(items)} listed</summary><ul>{body}</ul></details>"
    if isinstance(value, float):
        return number(value)
    return number(value) if isinstance(value, bool) else html_text(value)
