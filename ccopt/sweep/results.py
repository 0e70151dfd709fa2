"""The results folder: the table (Parquet and CSV), the spec's copy, the versions.

::

    DIR/results.parquet   one row per task (pyarrow)
    DIR/results.csv       the same table as CSV
    DIR/spec.toml         the spec as written (spec.json for a spec given as a dict)
    DIR/meta.json         ccopt and Dask versions, task counts, times
    DIR/summary.html      plots (:mod:`ccopt.sweep.summary`), summary.png beside it

Resumable: :func:`load_done` reads the rows already there, and only the
tasks without a row run again. The table is rewritten whole (atomically)
every few seconds while the sweep runs, so an interrupted sweep keeps what
it finished. Rows whose task the current spec no longer has are dropped.

Every file is replaced atomically through :mod:`ccopt.atomic` (the umask's
permissions; a killed run's temporary file is removed by the next). The CSV
is for spreadsheets: its text cells are written by
:func:`ccopt.export.text.csv_cell` (one line; a cell starting with ``=``,
``+``, ``-`` or ``@`` gets a leading ``'`` so it is never run as a formula).
The Parquet table keeps the values as they are.
"""
from __future__ import annotations

import json
import os
import time
from pathlib import Path

from ccopt.atomic import write_with_atomic
from ccopt.errors import ProgramError
from ccopt.export.text import csv_cell
from ccopt.sweep.execute import FIGURES
from ccopt.sweep.spec import AXES, Spec

PARQUET, CSV, META = "results.parquet", "results.csv", "meta.json"

#: How often the table is rewritten while tasks finish (seconds).
FLUSH_SECONDS = 5.0


def make_folder(out: str | os.PathLike) -> Path:
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ProgramError(f"cannot create results folder: {exc.strerror or exc}",
                           str(out)) from None
    return out


def columns(spec: Spec, planners: list[str]) -> list[str]:
    """The table's columns: id, program, the settings, the figures (with
    ``cycle_time_<planner>`` of each of ``planners``), the run."""
    settings = [a for a in AXES if a in spec.setting_names]
    figures = list(FIGURES)
    at = figures.index("cycle_time") + 1
    figures[at:at] = [f"cycle_time_{p}" for p in planners]
    return ["task_id", "program", *settings, *figures, "run"]


def load_done(out: Path):
    """The rows already in ``out`` (a DataFrame), or ``None`` when there are none."""
    # Deferred: pandas and pyarrow take a second to import; only sweeps use them.
    import pandas as pd
    file = out / PARQUET
    if not file.is_file():
        return None
    try:
        return pd.read_parquet(file, engine="pyarrow")
    except Exception as exc:  # a truncated or foreign file: say which, do not guess
        raise ProgramError(f"cannot read previous results ({type(exc).__name__}: {exc}); "
                           "remove the file or choose another folder", str(file)) from None


def make_table(rows: list[dict], cols: list[str]):
    """A DataFrame of ``rows`` with exactly ``cols`` (missing ones empty)."""
    # Deferred: pandas takes a second to import; only sweeps use it.
    import pandas as pd
    table = pd.DataFrame.from_records(rows)
    for c in cols:
        if c not in table:
            table[c] = None
    return table[cols]


def merge(done, new, order: list[str], cols: list[str]):
    """Previous rows of current tasks plus the new ones, in task order."""
    # Deferred: pandas takes a second to import; only sweeps use it.
    import pandas as pd
    parts = []
    if done is not None and len(done):
        parts.append(make_table(done.to_dict("records"), cols))
    if new:
        parts.append(make_table(new, cols))
    if not parts:
        return make_table([], cols)
    table = pd.concat(parts, ignore_index=True) if len(parts) > 1 else parts[0]
    rank = {tid: k for k, tid in enumerate(order)}
    table = table[table["task_id"].isin(rank)].drop_duplicates("task_id", keep="last")
    table = table.iloc[table["task_id"].map(rank).argsort(kind="stable")]
    return table.reset_index(drop=True)


def _replace(path: Path, write) -> None:
    write_with_atomic(path, write)


def spreadsheet_safe(table):
    """A copy of ``table`` whose text cells (and column names) are
    :func:`~ccopt.export.text.csv_cell`: for the CSV only."""
    safe = table.copy()
    for c in safe.columns:
        if safe[c].dtype.kind not in "biufcmM":     # text (object or string) columns
            safe[c] = safe[c].map(csv_cell)
    safe.columns = [csv_cell(str(c)) for c in safe.columns]
    return safe


def write_table(out: Path, table) -> None:
    """``results.parquet`` and ``results.csv``, each replaced atomically."""
    _replace(out / PARQUET, lambda p: table.to_parquet(p, engine="pyarrow", index=False))
    _replace(out / CSV, lambda p: spreadsheet_safe(table).to_csv(p, index=False))


def write_spec_copy(out: Path, spec: Spec) -> str:
    """The spec as written, beside the results; returns the file name."""
    if spec.text:
        name, text = "spec.toml", spec.text
    else:
        name = "spec.json"
        text = json.dumps({"programs": list(spec.programs), "planners": list(spec.planners or ()),
                           "axes": spec.axes, "combinations": list(spec.combinations),
                           "title": spec.title}, indent=2) + "\n"
    _replace(out / name, lambda p: p.write_text(text, encoding="utf-8"))
    return name


def write_meta(out: Path, meta: dict) -> None:
    _replace(out / META, lambda p: p.write_text(json.dumps(meta, indent=2, default=str) + "\n",
                                               encoding="utf-8"))


class Flusher:
    """Rewrites the table at most every :data:`FLUSH_SECONDS` while rows arrive."""

    def __init__(self, out: Path | None, done, order: list[str], cols: list[str]):
        self.out, self.done, self.order, self.cols = out, done, order, cols
        self.rows: list[dict] = []
        self.last = time.monotonic()

    def add(self, row: dict) -> None:
        self.rows.append(row)
        if self.out is not None and time.monotonic() - self.last > FLUSH_SECONDS:
            self.flush()

    def flush(self):
        table = merge(self.done, self.rows, self.order, self.cols)
        if self.out is not None:
            write_table(self.out, table)
        self.last = time.monotonic()
        return table
