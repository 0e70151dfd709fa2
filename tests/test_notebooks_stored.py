"""The notebooks are stored executed (by notebooks/store_outputs.py), run to
the end in order with their figures inline, so they read on a repository
browser."""
from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
SOURCES = sorted(NOTEBOOKS.glob("*.ipynb"))


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.stem)
def test_executed_copy_matches_and_shows_its_figures(path):
    book = nbformat.read(path, as_version=4)
    code = [c for c in book.cells if c.cell_type == "code"]
    # executed top to bottom in one run (a cell edited or run again after the
    # store breaks the 1, 2, 3, ... sequence: run notebooks/store_outputs.py)
    assert [c.execution_count for c in code] == list(range(1, len(code) + 1))
    outputs = [o for c in code for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # every cell that draws shows its figure inline (no forced non-interactive backend)
    drawing = [c for c in code if "plt.subplots" in c.source]
    assert drawing
    for c in drawing:
        assert any("image/png" in o.get("data", {}) for o in c.outputs), c.source[:60]
    assert not any('matplotlib.use("Agg")' in c.source for c in book.cells)
