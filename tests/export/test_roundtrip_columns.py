"""An export's round-trip error measured from the read-back's columns (issue 34)
is :func:`ccopt.export.roundtrip.displacement` move by move, bit for bit.

:func:`~ccopt.export.roundtrip.move_displacements` measures a read-back made
as columns without making its segments; the one-at-a-time reference is
:func:`~ccopt.export.roundtrip.displacement` of each read-back segment from
the geometry the writer meant, plus its bound. Over generated programs
(:mod:`cam_programs`' plates in every dialect, compensated in their own style
and in the PMAC style; bench/io.py's noisy ring, whose corner arcs read back
as spirals), each exported to G-code and to a PMAC program, and over the
same moves with the meant geometries moved by seeded amounts (so that every
displacement is non-zero, some arcs turn the other way and some meant
geometries are of another kind than the read-back's):

- every move's figure equals the reference's to the bit (NaN for a move not
  measured: a rapid of the writer's own);
- :func:`~ccopt.export.roundtrip.roundtrip_error` is the largest of them, as
  the reference loop's ``max`` finds it.
"""
from __future__ import annotations

import importlib.util
import math
import random
from pathlib import Path

import pytest

from cam_programs import cam_program
from ccopt.compensate import compensate
from ccopt.export import _ProgramExport
from ccopt.export.readback import readback_path
from ccopt.export.roundtrip import displacement, move_displacements, roundtrip_error
from ccopt.geometry import Arc, Line, Spiral
from ccopt.program import read_text

OWN_STYLE = {"gcode": "linuxcnc", "pmac": "pmac", "sinumerik": "siemens",
             "heidenhain": "heidenhain"}
ROOT = Path(__file__).resolve().parents[2]


def _reference(back, moves) -> list[float]:
    """Each move's displacement plus bound, one at a time (NaN: not measured)."""
    return [math.nan if src < 0 or meant is None else displacement(meant, seg.geom) + bound
            for seg, (src, meant, bound) in zip(back.segments, moves)]


def _moved(geom, rng: random.Random):
    """``geom`` with its numbers moved by seeded amounts (a few by far, a few
    an arc turned the other way, a few a line for an arc)."""
    e = 10.0 ** rng.uniform(-9, -2)
    nudge = lambda p: (p[0] + rng.uniform(-e, e), p[1] + rng.uniform(-e, e))  # noqa: E731
    pick = rng.random()
    if isinstance(geom, Line):
        return Line(nudge(geom.p0), nudge(geom.p1))
    if isinstance(geom, Arc):
        if pick < 0.05:
            return Line(geom.start, geom.end)
        sweep = -geom.sweep if pick < 0.1 else geom.sweep * (1 + rng.uniform(-e, e))
        if pick < 0.3:
            return Spiral(nudge(geom.center), geom.radius, geom.radius * (1 + e), geom.theta0,
                          sweep)
        return Arc(nudge(geom.center), geom.radius * (1 + rng.uniform(-e, e)),
                   geom.theta0 + rng.uniform(-e, e), sweep)
    return geom


def _same(back, moves) -> None:
    assert back.columns is not None
    got = move_displacements(back.columns, moves).tolist()
    ref = _reference(back, moves)
    assert len(got) == len(ref)
    bad = [(q, g, r) for q, (g, r) in enumerate(zip(got, ref))
           if not (g == r or (math.isnan(g) and math.isnan(r)))]
    assert not bad, bad[:5]
    worst = 0.0
    for r in ref:
        worst = max(worst, r)
    assert roundtrip_error(back, moves) == worst


def _exported_alike(path, prog, seed: int) -> None:
    for fmt, suffix in (("gcode", ".nc"), ("pmac", ".pmc")):
        job = _ProgramExport(path, fmt, 0.001, Path(f"out{suffix}"), prog, ["test"])
        text, moves = job.write(["test"], {})
        back = readback_path(text, fmt, path, moves, f"out{suffix}")
        _same(back, moves)
        rng = random.Random(seed)
        _same(back, [(src, _moved(meant, rng) if meant is not None else None, bound)
                     for src, meant, bound in moves])


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("dialect", sorted(OWN_STYLE))
def test_plates_measure_alike(seed, dialect):
    cp = cam_program(seed, dialect=dialect)
    prog = read_text(cp.text, cp.file, dialect, tool_table=cp.tool_table)
    for style in dict.fromkeys((OWN_STYLE[dialect], "pmac")):
        _exported_alike(compensate(prog, style), prog, seed)


def test_ring_measures_alike():
    spec = importlib.util.spec_from_file_location("bench_io", ROOT / "bench" / "io.py")
    bio = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bio)
    prog = read_text(bio.ring_program(600), "ring.pmc", "pmac")
    _exported_alike(compensate(prog, "pmac"), prog, 7)
