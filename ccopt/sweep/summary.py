"""``summary.html``: cycle time against each swept axis, and the failures.

One panel per swept axis (and per program when there are several): the
cycle time of each task that ran, divided by its program's mean over the
sweep (so programs of different lengths share a scale), averaged per axis
value, one line per style or variant (against the program itself: seconds).
A last panel counts, per style or variant, the tasks that failed
(``error``) and those that ran but were not certified (``ok`` false: a
gouge, a side or limits violation). The page
lists the failed tasks with their errors. The figure is also written as
``summary.png``. Texts from the spec and the tasks (title, program names,
errors) are escaped for the page (:func:`ccopt.export.text.html_text`) and
for the figure (:func:`~ccopt.export.text.plot_text`); both files are
written atomically (:mod:`ccopt.atomic`).
"""
from __future__ import annotations

import base64
import io
import math
from pathlib import Path

from ccopt.atomic import write_text_atomic, write_with_atomic
from ccopt.export.text import html_text, plot_text
from ccopt.sweep.spec import AXES

#: At most this many failed tasks are listed on the page.
MAX_LISTED = 200

NUMERIC = ("radius", "delta")


def _group_key(table) -> str | None:
    for key in ("variant", "style"):
        if key in table and table[key].nunique(dropna=False) > 1:
            return key
    return None


def _axes_to_plot(table) -> list[str]:
    swept = [a for a in AXES if a in table and table[a].nunique(dropna=True) > 1]
    if table["program"].nunique() > 1:
        swept.append("program")
    return swept


def _normalised(table):
    ran = table[table["error"].isna() & table["cycle_time"].notna()].copy()
    ran["cycle_time"] = ran["cycle_time"].astype(float)
    ran["relative"] = ran["cycle_time"] / ran.groupby("program")["cycle_time"].transform("mean")
    return ran


def _axis_panel(ax, ran, axis: str, group: str | None) -> None:
    values = list(dict.fromkeys(ran[axis].dropna().tolist()))
    numeric = axis in NUMERIC
    if numeric:
        values = sorted(float(v) for v in values)
    x_of = {v: (float(v) if numeric else k) for k, v in enumerate(values)}
    groups = [(None, ran)] if group is None or group == axis else list(ran.groupby(group))
    column = "cycle_time" if axis == "program" else "relative"
    for name, part in groups:
        means = part.groupby(axis)[column].mean()
        xs = [x_of[v] for v in values if v in means.index]
        ys = [means[v] for v in values if v in means.index]
        # programs are not ordered: points, no line between them
        ax.plot(xs, ys, marker="o", linestyle="none" if axis == "program" else "-",
                label=plot_text(name) if name is not None else "all")
    if not numeric:
        ax.set_xticks(range(len(values)))
        ax.set_xticklabels([plot_text(v) for v in values], rotation=30, ha="right", fontsize=7)
    ax.set_xlabel(axis)
    ax.set_ylabel("cycle time, s" if axis == "program" else "cycle time / program mean")
    ax.grid(True, alpha=0.3)
    if group is not None and group != axis:
        ax.legend(fontsize=7, title=plot_text(group), title_fontsize=7)


def _failure_panel(ax, table, group: str | None) -> None:
    key = group or "program"
    names = list(dict.fromkeys(table[key].astype(str).tolist()))
    errors = table[table["error"].notna()][key].astype(str).value_counts()
    uncertified = table["error"].isna() & table["ok"].astype("boolean").eq(False)
    not_ok = table[uncertified.fillna(False)][key].astype(str).value_counts()
    xs = range(len(names))
    ax.bar([x - 0.2 for x in xs], [int(errors.get(n, 0)) for n in names], 0.4, label="error")
    ax.bar([x + 0.2 for x in xs], [int(not_ok.get(n, 0)) for n in names], 0.4,
           label="not certified")
    ax.set_xticks(list(xs))
    ax.set_xticklabels([plot_text(n) for n in names], rotation=30, ha="right", fontsize=7)
    ax.set_ylabel("tasks")
    ax.set_title(f"failures per {key} (of {len(table)} tasks)", fontsize=9)
    ax.legend(fontsize=7)


def figure(table, title: str = ""):
    """The summary figure (a matplotlib ``Figure``, no pyplot state)."""
    # Deferred: matplotlib takes a second to import; only the summary needs it.
    from matplotlib.figure import Figure
    group = _group_key(table)
    axes = _axes_to_plot(table)
    n = len(axes) + 1
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    fig = Figure(figsize=(4.6 * cols, 3.6 * rows), layout="constrained")
    ran = _normalised(table)
    for k, axis in enumerate(axes):
        ax = fig.add_subplot(rows, cols, k + 1)
        if len(ran):
            _axis_panel(ax, ran, axis, group)
        ax.set_title(f"cycle time against {axis}", fontsize=9)
    _failure_panel(fig.add_subplot(rows, cols, n), table, group)
    fig.suptitle(plot_text(title or "ccopt sweep"))
    return fig


def _failed_rows(table) -> str:
    failed = table[table["error"].notna()]
    if not len(failed):
        return "<p>No task failed.</p>"
    cols = [c for c in ("program", *AXES, "error") if c in failed]
    head = "".join(f"<th>{html_text(c)}</th>" for c in cols)
    body = "".join("<tr>" + "".join(f"<td>{html_text(r[c])}</td>" for c in cols) + "</tr>"
                   for _, r in failed.head(MAX_LISTED).iterrows())
    more = f"<p>... and {len(failed) - MAX_LISTED} more.</p>" if len(failed) > MAX_LISTED else ""
    return f"<table><tr>{head}</tr>{body}</table>{more}"


def write_summary(out: Path, table, title: str = "") -> Path:
    """``out/summary.html`` and ``out/summary.png``; returns the HTML file."""
    fig = figure(table, title)
    # the temporary file's suffix is not .png: name the format
    write_with_atomic(out / "summary.png", lambda p: fig.savefig(p, format="png", dpi=110))
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    img = base64.b64encode(buf.getvalue()).decode("ascii")
    n_err = int(table["error"].notna().sum())
    page = (f"<!doctype html><html><head><meta charset='utf-8'><title>{html_text(title)}"
            "</title><style>body{font-family:sans-serif;margin:2em}table{border-collapse:"
            "collapse;font-size:small}td,th{border:1px solid #ccc;padding:2px 6px}</style>"
            f"</head><body><h1>{html_text(title or 'ccopt sweep')}</h1>"
            f"<p>{len(table)} tasks, {n_err} failed. Table: results.parquet, results.csv.</p>"
            f"<img alt='summary plots' src='data:image/png;base64,{img}'>"
            f"<h2>Failed tasks</h2>{_failed_rows(table)}</body></html>\n")
    path = out / "summary.html"
    write_text_atomic(path, page)
    return path
