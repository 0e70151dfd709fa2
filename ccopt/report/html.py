"""The HTML report of a ``ccopt run``: an index and one page per case (plots
embedded as PNG).

The index has one row per case: its verdict, cycle time and minimum
clearance, and the answer to "which variant is best": the fastest certified
variant with its gain against PMAC's path and against the fastest certified
controller variant. A case's page has the programmed vs tool path (tool
circles along it, violations marked), the feed along the path, speed against
time per planner, the feed figures (jerk too when jerk limits are given),
the variants with the fastest certified one marked, the certificate and
links to the exported files. Figures are written by
:mod:`ccopt.report.figures` (units, sensible digits, yes/no, ok/failed).

Every text on the page (titles, sources, messages, names) is escaped by
:func:`ccopt.export.text.html_text` and every link made by
:func:`~ccopt.export.text.html_href`: a case's text stays text. The pages
carry no script.
"""
from __future__ import annotations

import base64
from typing import Any

from ccopt.export.text import html_href, html_text
from ccopt.report.figures import detail, gain, number, status, verdict

#: The title of every page (the index's alone: ccopt.export recognises the
#: index it wrote by it; a case page's title adds the case's name).
TITLE = "ccopt run"

#: A case's page beside the index: ``<label>.report.html`` (never
#: ``index.html``, whatever the label).
PAGE_SUFFIX = ".report.html"

CSS = """
body{font-family:system-ui,Segoe UI,Helvetica,Arial,sans-serif;margin:1.5em auto;max-width:1200px;
padding:0 1em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0;font-size:.88em;max-width:100%}
td,th{border:1px solid #ddd;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f3f3f3}td.num{text-align:right;white-space:nowrap}
td.text{overflow-wrap:anywhere;min-width:12em}
tr.winner td{background:#e8f5e9}.badge{background:#1b7f3b;color:#fff;border-radius:3px;
padding:0 .35em;font-size:.8em;margin-left:.3em;white-space:nowrap}
.ok{color:#1b7f3b;font-weight:600}.fail{color:#b3261e;font-weight:600}.muted{color:#666}
img.plot{max-width:100%;height:auto;border:1px solid #eee;margin:.3em 0}
.grid{display:grid;grid-template-columns:repeat(auto-fit,minmax(480px,1fr));gap:1em}
pre{white-space:pre-wrap;overflow-wrap:anywhere;background:#f8f8f8;padding:.6em;font-size:.85em}
code{background:#f6f6f6;padding:0 .2em;overflow-wrap:anywhere}
details summary{cursor:pointer;color:#1d3557}
"""

#: The variant table's columns: (heading, key, kind of figure); ``gain`` for
#: gains, ``text`` for words.
VARIANT_COLUMNS = [
    ("variant", "variant", "html"), ("status", "status", "status"),
    ("cycle time", "duration", "time"), ("gain vs PMAC", "gain_vs_pmac", "gain"),
    ("gain vs fastest controller", "gain_vs_fastest_controller", "gain"),
    ("length", "length", "length"), ("max curvature", "max_curvature", "curvature"),
    ("curvature jump", "max_curvature_jump", "curvature"), ("joins", "continuity", "text"),
    ("min clearance", "min_clearance", "clearance"),
    ("max deviation", "max_deviation", "clearance"), ("certified", "certified", "plain"),
    ("solve time", "solve_time", "solve_time"),
]

#: The feed table's columns (the jerk ratio only when jerk limits are given).
FEED_COLUMNS = [("planner", "planner", "text"), ("cycle time", "duration", "time"),
                ("max velocity / limit", "max_axis_vel_ratio", "ratio"),
                ("max acceleration / limit", "max_axis_acc_ratio", "ratio"),
                ("max jerk / limit", "max_axis_jerk_ratio", "ratio"),
                ("max feed / F", "max_feed_ratio", "ratio")]

#: The certificate's checks: (heading, key, kind).
CHECK_COLUMNS = [("check", "name", "text"), ("ok", "ok", "verdict"),
                 ("figure", "figure", "plain"), ("unit", "unit", "text"),
                 ("basis", "basis", "text"), ("requirement", "requirement", "long"),
                 ("checked", "count", "plain"), ("violations", "violations", "plain"),
                 ("detail", "detail", "detail")]


def page_name(label: str) -> str:
    """The file name of a case's page."""
    return f"{label}{PAGE_SUFFIX}"


def _cell(value: Any, kind: str) -> str:
    if kind == "html":          # markup made here, its text escaped already
        return f"<td>{value}</td>"
    if kind == "gain":
        return f'<td class="num">{gain(value)}</td>'
    if kind == "status":
        return f"<td>{status(str(value))}</td>" if value else "<td>-</td>"
    if kind == "verdict":
        return f"<td>{verdict(bool(value))}</td>"
    if kind == "detail":
        return f'<td class="text">{detail(value) if value else "-"}</td>'
    if kind == "long":
        return f'<td class="text">{number(value)}</td>'
    if kind == "text":
        return f"<td>{number(value)}</td>"
    return f'<td class="num">{number(value, kind)}</td>'


def _table(rows: list[dict], columns: list[tuple[str, str, str]], units: str = "",
           row_class=lambda row: "") -> str:
    """``rows`` under ``columns`` (heading, key, kind); a column no row fills is left out."""
    if not rows:
        return '<p class="muted">none</p>'
    cols = [c for c in columns if any(r.get(c[1]) is not None for r in rows)]
    unit = {"length": units, "clearance": units, "curvature": f"1/{units}" if units else ""}
    head = "".join(f"<th>{html_text(h)}" + (f" ({html_text(unit[k])})" if unit.get(k) else "")
                   + "</th>" for h, _, k in cols)
    body = []
    for r in rows:
        cls = row_class(r)
        cells = "".join(_cell(r.get(key), kind) for _, key, kind in cols)
        body.append(f'<tr{f" class={chr(34)}{cls}{chr(34)}" if cls else ""}>{cells}</tr>')
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def fastest_certified(variants: list[dict]) -> dict | None:
    """The certified variant of least cycle time (the first listed on a tie), if any."""
    certified = [v for v in variants if v.get("certified") and v.get("status") == "ok"
                 and v.get("duration") is not None]
    return min(certified, key=lambda v: v["duration"]) if certified else None


def _variants(variants: list[dict], units: str) -> str:
    """The variants, the fastest certified one marked (its row and a badge),
    then their messages."""
    best = fastest_certified(variants)
    rows = [{**v, "variant": html_text(v.get("name")) + (
        ' <span class="badge">fastest certified</span>' if v is best else ""),
        "winner": v is best} for v in variants]
    table = _table(rows, VARIANT_COLUMNS, units, lambda r: "winner" if r["winner"] else "")
    # each variant's message (why refused or rejected, what was kept) below the
    # table, full width, so the table needs no long column
    notes = "".join(f"<li><b>{html_text(v.get('name'))}</b>: {html_text(v['message'])}</li>"
                    for v in variants if v.get("message"))
    return table + (f'<ul class="notes">{notes}</ul>' if notes else "")


def _certificate(cert: dict, text: str | None) -> list[str]:
    """The verdict, the verifier's own summary (wrapped) and the checks as a table."""
    parts = ["<h3>Certificate</h3>",
             f"<p>verdict: {verdict(bool(cert.get('ok')))}, minimum clearance "
             f"{number(cert.get('min_clearance'), 'clearance')} for cutter radius "
             f"{number(cert.get('radius'))}</p>"]
    if text:
        # escaped line by line (html_text makes each text one line), indents kept
        parts.append("<pre>" + "\n".join(" " * (len(line) - len(line.lstrip(" "))) + html_text(line)
                                           for line in text.splitlines()) + "</pre>")
    parts.append(_table(cert.get("checks", []), CHECK_COLUMNS))
    return parts


def _head(title: str) -> list[str]:
    return ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>{html_text(title)}</title><style>{CSS}</style></head><body>"]


def _img(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<img class="plot" alt="{html_text(alt)}" src="data:image/png;base64,{data}">'


def index_row(r: dict) -> dict:
    """A case's row on the index: verdict, cycle time, clearance and the
    fastest certified variant with its gains."""
    best = fastest_certified(r.get("compare") or [])
    return {"case": r["name"], "status": r["status"], "style": r.get("style"),
            "radius": r.get("radius"), "duration": r.get("duration"),
            "min_clearance": r.get("min_clearance"),
            "best": best["name"] if best else None,
            "best_duration": best["duration"] if best else None,
            "gain_vs_pmac": best.get("gain_vs_pmac") if best else None,
            "gain_vs_fastest_controller": best.get("gain_vs_fastest_controller") if best else None,
            "fastest_controller": best.get("fastest_controller") if best else None}


INDEX_COLUMNS = [("case", "link", "html"), ("verdict", "status", "status"),
                 ("style", "style", "text"), ("cutter radius", "radius", "plain"),
                 ("cycle time", "duration", "time"), ("min clearance", "min_clearance", "clearance"),
                 ("fastest certified variant", "best", "text"),
                 ("its cycle time", "best_duration", "time"),
                 ("gain vs PMAC", "gain_vs_pmac", "gain"),
                 ("gain vs fastest controller", "gain_vs_fastest_controller", "gain"),
                 ("fastest controller", "fastest_controller", "text")]


def render_index(results: list[dict], title: str = TITLE) -> str:
    """The index page: one row per case, each linking to its page."""
    parts = _head(title) + [f"<h1>{html_text(title)}</h1>",
                            f"<p class='muted'>{len(results)} case(s); each name opens its page. "
                            "Gains are in cycle time (1 - t / t<sub>ref</sub>): positive is "
                            "faster.</p>"]
    rows = [{**index_row(r), "link": f'<a href="{html_href(page_name(r["name"]))}">'
             f'{html_text(r["name"])}</a>'} for r in results]
    parts += [_table(rows, INDEX_COLUMNS), "</body></html>"]
    return "\n".join(parts) + "\n"


def render_case(r: dict, title: str = TITLE) -> str:
    """One case's page (the keys of :func:`ccopt.run.run_one`'s row)."""
    units = r.get("units", "")
    parts = _head(f"{title}: {r['name']}") + [
        '<p><a href="index.html">&larr; all cases</a></p>',
        f"<h1>{html_text(r['name'])} {status(r['status'])}</h1>"]
    if r.get("title"):
        parts.append(f"<p>{html_text(r['title'])}</p>")
    meta = [f"program <code>{html_text(r.get('program', ''))}</code>"]
    if r.get("source"):
        meta.append(f"source: {html_text(r['source'])}")
    if r.get("style"):
        meta.append(f"style <b>{html_text(r['style'])}</b>, cutter radius "
                    f"{number(r.get('radius'))} {html_text(units)}")
    parts.append("<p class='muted'>" + " &middot; ".join(meta) + "</p>")
    if r.get("message"):
        parts.append(f"<p><code>{html_text(r['message'])}</code></p>")
    if r.get("plots"):
        parts += ['<div class="grid">', *(_img(png, name) for name, png in r["plots"].items()),
                  "</div>"]
    if r.get("feed"):
        parts.append("<h3>Feed</h3>")
        if r.get("limits"):
            lim = r["limits"]
            parts.append("<p class='muted'>axis limits " + ", ".join(
                f"{k} = {html_text(lim[k])}" for k in ("v", "a", "j") if lim.get(k)) + "</p>")
        jerk = bool((r.get("limits") or {}).get("j"))
        rows = [{"planner": k, **v} for k, v in r["feed"].items()]
        cols = [c for c in FEED_COLUMNS if jerk or c[1] != "max_axis_jerk_ratio"]
        parts.append(_table(rows, cols))
    if r.get("compare"):
        parts += ["<h3>Variants</h3>", _variants(r["compare"], units)]
        if r.get("not_compared"):
            parts.append("<p class='muted'>not compared in this run: "
                         + ", ".join(html_text(n) for n in r["not_compared"])
                         + " (<code>ccopt run --variants all</code>, or "
                         "<code>ccopt compare</code>)</p>")
    if r.get("certificate"):
        parts += _certificate(r["certificate"], r.get("certificate_text"))
    if r.get("files"):
        links = " ".join(f'<a href="{html_href(path)}">{html_text(label)}</a>'
                         for label, path in r["files"].items())
        parts.append(f"<p>files: {links}</p>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def render(results: list[dict], title: str = TITLE) -> dict[str, str]:
    """Every page of the report: ``{"index.html": ..., page_name(case): ...}``."""
    pages = {"index.html": render_index(results, title)}
    for r in results:
        pages[page_name(r["name"])] = render_case(r, title)
    return pages
