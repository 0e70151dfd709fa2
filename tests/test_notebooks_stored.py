"""The notebooks' executed copies (notebooks/with-outputs/, what a repository
browser shows, made by notebooks/store_outputs.py) are the notebooks as they
are, run to the end with their figures inline."""
from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
SOURCES = sorted(NOTEBOOKS.glob("*.ipynb"))


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.stem)
def test_executed_copy_matches_and_shows_its_figures(path):
    book = nbformat.read(path, as_version=4)
    copy = nbformat.read(NOTEBOOKS / "with-outputs" / path.name, as_version=4)
    # the same cells: the copy is not stale (run notebooks/store_outputs.py after a change)
    assert [(c.cell_type, c.source) for c in copy.cells] == \
        [(c.cell_type, c.source) for c in book.cells]
    code = [c for c in copy.cells if c.cell_type == "code"]
    assert all(c.execution_count is not None for c in code)
    outputs = [o for c in code for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # every cell that draws shows its figure inline (no forced non-interactive backend)
    drawing = [c for c in code if "plt.subplots" in c.source]
    assert drawing
    for c in drawing:
        assert any("image/png" in o.get("data", {}) for o in c.outputs), c.source[:60]
    assert not any('matplotlib.use("Agg")' in c.source for c in book.cells)
