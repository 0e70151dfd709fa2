"""One self-contained HTML report for a ``ccopt run`` (plots embedded as PNG).

The page has a summary table and, per case: programmed vs tool path (tool
circles along it, violations marked), the feed along the path coloured by
speed, speed against time for each planner, the blend comparison table, the
certificate (every check with its figure and whether it is exact or a
certified bound), and links to the exported files.

Every text on the page (titles, sources, messages, names) is escaped by
:func:`ccopt.export.text.html_text` and every link made by
:func:`~ccopt.export.text.html_href`: a case's text stays text.
"""
from __future__ import annotations

import base64
from typing import Any

from ccopt.export.text import html_href, html_text

CSS = """
body{font-family:system-ui,Segoe UI,Helvetica,Arial,sans-serif;margin:2em;max-width:1200px;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0;font-size:.9em}
td,th{border:1px solid #ddd;padding:.25em .6em;text-align:left}th{background:#f3f3f3}
.ok{color:#1b7f3b;font-weight:600}.fail{color:#b3261e;font-weight:600}.muted{color:#777}
img.plot{max-width:100%;height:auto;border:1px solid #eee;margin:.3em 0}
.grid{display:grid;grid-template-columns:1fr 1fr;gap:1em}
code{background:#f6f6f6;padding:0 .2em}
"""


def _e(x: Any) -> str:
    return html_text(x)


def _img(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<img class="plot" alt="{_e(alt)}" src="data:image/png;base64,{data}">'


def _fmt(x: Any) -> str:
    if isinstance(x, bool) or x is None:
        return _e(x)
    if isinstance(x, float):
        return f"{x:.6g}"
    return _e(x)


def _table(rows: list[dict], columns: list[str] | None = None) -> str:
    if not rows:
        return '<p class="muted">none</p>'
    columns = columns or list(rows[0].keys())
    head = "".join(f"<th>{_e(c)}</th>" for c in columns)
    body = "".join("<tr>" + "".join(f"<td>{_fmt(r.get(c, ''))}</td>" for c in columns) + "</tr>"
                   for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def _status(s: str) -> str:
    cls = "ok" if s.startswith("ok") or "expected" in s else "fail"
    return f'<span class="{cls}">{_e(s)}</span>'


#: the columns of the variant table, in order (``message`` says why a variant
#: was refused or rejected, or what its feed planning met)
VARIANT_COLUMNS = ["name", "status", "duration", "length", "max_curvature", "max_curvature_jump",
                   "continuity", "min_clearance", "max_deviation", "certified", "solve_time",
                   "message"]

#: the columns of the certificate's checks (``detail`` is written out as text)
CHECK_COLUMNS = ["name", "ok", "figure", "unit", "basis", "requirement", "count", "violations",
                 "detail"]


def _variants_table(rows: list[dict]) -> str:
    """Every variant with its figures, a refused or rejected one with its message."""
    cols = [c for c in VARIANT_COLUMNS if any(row.get(c) is not None for row in rows)]
    return _table(rows, cols)


def _as_text(value: Any) -> Any:
    """A check's nested detail as ``key: value`` text, lists comma-separated."""
    if isinstance(value, dict):
        return "; ".join(f"{k}: {_as_text(v)}" for k, v in value.items())
    if isinstance(value, (list, tuple)):
        return ", ".join(str(_as_text(v)) for v in value)
    if isinstance(value, float):
        return f"{value:.6g}"
    return value


def _certificate(cert: dict, text: str | None) -> list[str]:
    """The certificate section: the verdict, the verifier's own summary
    (checks, violations, part and air in words) and the checks as a table."""
    parts = ["<h3>Certificate</h3>",
             f"<p>verdict: {_status('ok' if cert.get('ok') else 'FAILED')}, "
             f"minimum clearance {_fmt(cert.get('min_clearance'))} for radius "
             f"{_fmt(cert.get('radius'))}</p>"]
    if text:
        # escaped line by line (html_text makes each text one line, stripped),
        # each line's indent kept
        parts.append("<pre>" + "\n".join(" " * (len(line) - len(line.lstrip(" "))) + _e(line)
                                           for line in text.splitlines()) + "</pre>")
    checks = [{k: _as_text(c.get(k)) for k in CHECK_COLUMNS if k in c}
              for c in cert.get("checks", [])]
    parts.append(_table(checks))
    return parts


def render(results: list[dict], title: str = "ccopt run") -> str:
    """The HTML page for ``results``: one dict per case with keys ``name``,
    ``title``, ``source``, ``status``, ``program``, ``style``, ``radius``,
    ``units``, and optionally ``plots`` (name -> PNG bytes), ``feed``
    (planner -> summary dict), ``certificate`` (dict), ``compare`` (list of
    variant dicts), ``files`` (label -> relative path), ``message``."""
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             f"<title>{_e(title)}</title><style>{CSS}</style></head><body>",
             f"<h1>{_e(title)}</h1>"]
    summary = []
    for r in results:
        # the certified planner's time (the jerk planner's under jerk limits)
        feed = r.get("feed", {}).get(r.get("planner", "toppra"), {})
        cert = r.get("certificate") or {}
        summary.append({"case": f'<a href="#{_e(r["name"])}">{_e(r["name"])}</a>',
                        "style": r.get("style", ""), "radius": r.get("radius", ""),
                        "cycle time (s)": feed.get("duration", ""),
                        "min clearance": cert.get("min_clearance", ""),
                        "status": _status(r["status"])})
    parts.append("<h2>Summary</h2>")
    # summary cells carry their own markup
    head = "".join(f"<th>{_e(c)}</th>" for c in summary[0]) if summary else ""
    body = "".join("<tr>" + "".join(
        f"<td>{v if k in ('case', 'status') else _fmt(v)}</td>" for k, v in row.items()) + "</tr>"
        for row in summary)
    parts.append(f"<table><tr>{head}</tr>{body}</table>")
    for r in results:
        parts.append(f'<h2 id="{_e(r["name"])}">{_e(r["name"])} {_status(r["status"])}</h2>')
        if r.get("title"):
            parts.append(f"<p>{_e(r['title'])}</p>")
        meta = [f"program <code>{_e(r.get('program', ''))}</code>"]
        if r.get("source"):
            meta.append(f"source: {_e(r['source'])}")
        if r.get("style"):
            meta.append(f"style <b>{_e(r['style'])}</b>, cutter radius {_fmt(r.get('radius'))} "
                        f"{_e(r.get('units', ''))}")
        parts.append("<p class='muted'>" + " &middot; ".join(meta) + "</p>")
        if r.get("message"):
            parts.append(f"<p><code>{_e(r['message'])}</code></p>")
        plots = r.get("plots", {})
        if plots:
            parts.append('<div class="grid">')
            parts += [_img(png, name) for name, png in plots.items()]
            parts.append("</div>")
        if r.get("feed"):
            parts.append("<h3>Feed</h3>")
            rows = [{"planner": k, **{c: v.get(c) for c in (
                "duration", "max_axis_vel_ratio", "max_axis_acc_ratio", "max_feed_ratio")}}
                for k, v in r["feed"].items()]
            parts.append(_table(rows))
        if r.get("compare"):
            parts.append("<h3>Blend variants</h3>")
            parts.append(_variants_table(r["compare"]))
        if r.get("certificate"):
            parts += _certificate(r["certificate"], r.get("certificate_text"))
        if r.get("files"):
            links = " ".join(f'<a href="{html_href(path)}">{_e(label)}</a>'
                             for label, path in r["files"].items())
            parts.append(f"<p>files: {links}</p>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"
