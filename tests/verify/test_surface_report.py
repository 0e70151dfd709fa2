"""The certificate's ``surface`` entry (:meth:`ccopt.verify.surface.Surface.report`)
against its definition, a move-by-move merge written here: runs of
consecutive moves (the compensated ones and the approaches) with the same
verdict and reason, each with its first and last program line."""
from __future__ import annotations

import random
from types import SimpleNamespace

import numpy as np
import pytest

from ccopt.verify import surface as S

WHYS = (S.WHY_LOOP, S.WHY_NO_LOOP, S.WHY_LEAD_BEFORE, S.WHY_MARK_AIR, "")
APPROACH_WHYS = (S.WHY_LEAD_IN, S.WHY_LEAD_OUT, S.WHY_SIDE_CHANGE)


def merged_by_hand(moves, part, why, compensated, approaches) -> list[dict]:
    runs: list[dict] = []
    nxt = None
    for k in sorted(set(np.flatnonzero(compensated).tolist()) | set(approaches)):
        surf = S.SURFACE_PART if compensated[k] and part[k] else S.SURFACE_AIR
        reason = approaches.get(k, why[k])
        if runs and runs[-1]["surface"] == surf and runs[-1]["why"] == reason and nxt == k:
            runs[-1]["lines"][1] = moves[k].source.line
        else:
            runs.append({"lines": [moves[k].source.line] * 2, "surface": surf, "why": reason})
        nxt = k + 1
    return runs


@pytest.mark.parametrize("seed", range(300))
def test_report_is_the_move_by_move_merge(seed):
    rng = random.Random(seed)
    n = rng.randint(0, 60)
    line, moves = 1, []
    for _ in range(n):
        line += rng.choice((0, 1, 1, 2))
        moves.append(SimpleNamespace(source=SimpleNamespace(line=line)))
    # long runs of one kind, as programs have them
    comp = np.array([rng.random() < 0.8 for _ in range(n)], bool)
    part = np.array([rng.random() < 0.7 for _ in range(n)], bool)
    why = tuple(rng.choice(WHYS[:2]) if rng.random() < 0.9 else rng.choice(WHYS)
                for _ in range(n))
    approaches = {k: rng.choice(APPROACH_WHYS) for k in range(n) if rng.random() < 0.1}
    got = S.Surface(part, why, "closed-loop").report(moves, comp, approaches)
    want = merged_by_hand(moves, part, why, comp, approaches)
    assert got["moves"] == want
    assert got["part_lines"] == [r["lines"] for r in want if r["surface"] == S.SURFACE_PART]
    assert got["air_lines"] == [r["lines"] for r in want if r["surface"] == S.SURFACE_AIR]
    assert got["rule"] == "closed-loop"


def test_a_loop_encloses_by_its_polygon_area_as_shapely_measures_it():
    # seeded random polygons (star-shaped, a few to 20,000 vertices, far from
    # and near the origin) and degenerate ones (a move and its retrace, a
    # sliver): a loop of lines encloses when its area exceeds eps times its
    # perimeter, area and perimeter as shapely measures them (GEOS)
    import importlib

    import numpy as np
    import shapely

    surface = importlib.import_module("ccopt.verify.surface")
    rng = np.random.default_rng(7)
    no_arcs = np.zeros(0, bool)
    decided = 0
    for k in range(200):
        n = int(rng.choice([3, 5, 40, 20_000]))
        theta = np.sort(rng.uniform(0.0, 2 * np.pi, n))
        rad = rng.uniform(0.5, 1.5, n) * 10.0 ** rng.uniform(-3, 3)
        verts = np.c_[rad * np.cos(theta), rad * np.sin(theta)] + rng.uniform(-1e4, 1e4, 2)
        if k % 4 == 0:                          # squashed toward a line: a retrace, a sliver
            verts[:, 1] = verts[0, 1] + (verts[:, 1] - verts[0, 1]) * 10.0 ** -rng.uniform(6, 14)
        ring = shapely.Polygon(verts)
        eps = 10.0 ** rng.uniform(-9, -1)
        area, perimeter = ring.area, ring.length
        if abs(area - eps * perimeter) <= 1e-9 * (area + eps * perimeter):
            continue                            # a tie within rounding: either answer
        assert surface._encloses(verts, no_arcs, eps) == (area > eps * perimeter), k
        decided += 1
    assert decided >= 190
    # any arc makes a loop a contour
    assert surface._encloses(np.zeros((3, 2)), np.array([False, True, False]), 1.0)
