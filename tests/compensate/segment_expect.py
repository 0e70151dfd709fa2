"""Expected tool-path segments for the compensation tests, and the check.

An expectation is ``(kind, role, start, end, centre, sweep)``; build them with
:func:`L` (line), :func:`A` (arc) and :func:`SP` (spiral). :func:`check`
compares a ToolPath segment by segment (kinds and roles in order, then end
points, centres and signed sweeps) to ``TOL``.
"""
from __future__ import annotations

import numpy as np
import pytest

TOL = 1e-9


def L(role, s, e):
    return ("line", role, tuple(s), tuple(e), None, None)


def A(role, c, s, e, sweep):
    return ("arc", role, tuple(s), tuple(e), tuple(c), sweep)


def SP(role, c, s, e, sweep):
    return ("spiral", role, tuple(s), tuple(e), tuple(c), sweep)


def check(path, expected, skip_roles=("rapid",), tol: float = TOL):
    segs = [s for s in path.segments if s.role.value not in skip_roles]
    got = [(s.kind, s.role.value) for s in segs]
    want = [(e[0], e[1]) for e in expected]
    assert got == want, f"segment kinds/roles differ:\n got  {got}\n want {want}"
    for i, (seg, exp) in enumerate(zip(segs, expected)):
        kind, role, s, e, c, sweep = exp
        d = seg.to_json()
        assert np.allclose(d["start"], s, atol=tol, rtol=0), f"seg {i} start {d['start']} != {s}"
        assert np.allclose(d["end"], e, atol=tol, rtol=0), f"seg {i} end {d['end']} != {e}"
        if c is not None:
            assert np.allclose(d["center"], c, atol=tol, rtol=0), f"seg {i} centre {d['center']} != {c}"
            assert d["sweep"] == pytest.approx(sweep, abs=tol), f"seg {i} sweep {d['sweep']} != {sweep}"
