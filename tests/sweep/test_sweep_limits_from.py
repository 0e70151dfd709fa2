"""Each sweep row says where its axis limits came from, as every command
that plans a feed does: a case's [limits], the defaults for a bare program,
the spec's own limits."""
from __future__ import annotations

from pathlib import Path

from ccopt.cases import DEFAULT_LIMITS, Overrides, resolve_input
from ccopt.sweep.execute import figures

CASES = Path(__file__).resolve().parents[2] / "cases"


def _row(what: str, **given) -> dict:
    job = resolve_input(what, Overrides(**given), DEFAULT_LIMITS)
    return figures(job.read(), job)


def test_rows_say_where_their_limits_came_from():
    assert _row(str(CASES / "leadin-outside-line"))["limits_from"] == "case"
    assert _row(str(CASES / "pocket" / "pocket.nc"))["limits_from"] == "default"
    spec = _row(str(CASES / "pocket" / "pocket.nc"), vmax=(50.0, 50.0, 20.0),
                amax=(500.0, 500.0, 200.0))
    assert spec["limits_from"] == "command line"
