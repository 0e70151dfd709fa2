"""Execute every notebook and store it in place with its outputs.

The notebooks are stored executed, figures inline, so they read on a
repository browser; the test suite (tests/test_notebooks.py) executes them
again at small size. Run from the repository root after changing a notebook::

    .venv/bin/python notebooks/store_outputs.py [NAME.ipynb ...]
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

HERE = Path(__file__).resolve().parent

#: seconds a cell may take (the comparison of every variant is the longest)
CELL_TIMEOUT = 1800

# A log record of the Dask cluster (its shutdown warnings): timestamped,
# machine-specific noise, not the notebook's output.
_CLUSTER_LOG = re.compile(r"\d{4}-\d\d-\d\d [\d:,]+ - distributed\.")


def _without_cluster_logs(book) -> None:
    """Drop the stderr outputs that are nothing but Dask's log records."""
    for cell in book.cells:
        if cell.cell_type == "code":
            cell.outputs = [o for o in cell.outputs if not (
                o.output_type == "stream" and o.name == "stderr"
                and all(_CLUSTER_LOG.match(x) for x in o.text.splitlines() if x.strip()))]


def store(path: Path) -> Path:
    """Execute ``path`` (from the repository root, at full size) and write it
    back with its outputs; returns ``path``."""
    book = nbformat.read(path, as_version=4)
    NotebookClient(book, timeout=CELL_TIMEOUT, kernel_name="python3",
                   resources={"metadata": {"path": str(HERE.parent)}}).execute()
    _without_cluster_logs(book)
    nbformat.write(book, path)
    return path


def main(names: list[str]) -> None:
    paths = [HERE / n for n in names] if names else sorted(HERE.glob("*.ipynb"))
    for path in paths:
        print(f"{path.name} -> {store(path).relative_to(HERE.parent)}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
