"""The writers' bulk road (runs of lines and arcs written from columns,
:mod:`ccopt.export.bulk`) writes what the move-by-move road writes, byte for
byte: on seeded random numbers and edge cases, on generated CAM programs,
PMAC rings and G-code programs that change frames, planes, words, axes and
feeds between their moves."""
from __future__ import annotations

import math
import random
import sys

import numpy as np
import pytest

from cam_programs import cam_program
from ccopt.cases import default_style
from ccopt.compensate import compensate
from ccopt.errors import CcoptError
from ccopt.export import write_gcode, write_pmac
from ccopt.export.bulk import fmt_many, rounded
from ccopt.export.gcode import fmt
from ccopt.program import read_text
from ccopt.toolpath import programmed_path

gcode_writer = sys.modules["ccopt.export.gcode"]
pmac_writer = sys.modules["ccopt.export.pmacprog"]

EDGES = [0.0, -0.0, 5e-7, -5e-7, 4.9999999e-7, -4.9999999e-7, 5.0000001e-7, 1e-7, -1e-7,
         0.5, -0.5, 1.5, 2.5, -2.5, 0.0000005, 1.0000005, 2.0000005, -1.0000015, 0.1, 0.7,
         123456.0000005, 1e15, 1e16 + 2.0, 1e22, -1e22, 1e300, -1e300, 1.7976931348623157e308,
         5e-324, -5e-324, 2.2250738585072014e-308, 9.9999995, 99.999999500000001,
         math.nan, math.inf, -math.inf, 100.0, -100.0, 10.0, 1e-300]


def _numbers(seed: int) -> list[float]:
    rng = np.random.default_rng(seed)
    scale = 10.0 ** rng.integers(-12, 20, 3000)
    near_ties = rng.integers(-10 ** 7, 10 ** 7, 1000) / 2e6   # halves of the 6th decimal
    ties = rng.integers(-10 ** 9, 10 ** 9, 1000) / 2.0 ** rng.integers(1, 30, 1000)  # exact
    return EDGES + (rng.standard_normal(3000) * scale).tolist() + near_ties.tolist() \
        + ties.tolist() + (ties * 1e6).tolist()


@pytest.mark.parametrize("digits", [0, 1, 2, 3, 4, 6, 9, 12, 18, 22, 30])
def test_bulk_numbers_are_fmt_and_round(digits):
    values = _numbers(digits)
    assert fmt_many(values, digits) == [fmt(x, digits) for x in values]
    assert list(map(repr, rounded(values, digits).tolist())) == \
        [repr(round(x, digits)) for x in values]


def _per_segment(monkeypatch):
    """Write every segment by itself: no segment continues a run."""
    for module in (gcode_writer, pmac_writer):
        monkeypatch.setattr(module, "run_ends", lambda joins: list(range(1, len(joins) + 1)))


def _written(path, program) -> list:
    out = []
    for write in (lambda: write_gcode(path, 1e-3, ["h"], program=program),
                  lambda: write_gcode(path, 1e-2, None, digits=3),
                  lambda: write_pmac(path, None),
                  lambda: write_pmac(path, None, digits=4, tol=1e-2)):
        try:
            out.append(repr(write()))
        except (CcoptError, ValueError) as exc:     # refused alike on both roads
            out.append(f"{type(exc).__name__}: {exc}")
    return out


def _plane_words(plane: str):
    """Axis letters and centre words of ``plane``'s (u, v)."""
    return {"G17": ("XY", "IJ"), "G18": ("ZX", "KI"), "G19": ("YZ", "JK")}[plane]


def _machine_program(seed: int) -> str:
    """A G-code program of runs of lines and arcs with frames, planes, machine
    words, A axis moves, dwells, feeds and (odd seeds) threads changing
    between them."""
    rnd = random.Random(seed)
    out = ["G21 G17 G90 G94 F600"]
    pos = {"X": 0.0, "Y": 0.0, "Z": 0.0}
    known = True                  # pos is the current point in work coordinates
    turned = False                # in the rotated G56 (no arcs but in G17 there)
    plane = "G17"
    blocks = rnd.randint(30, 60)
    for k in range(blocks):
        r = rnd.random()
        if r < 0.06:
            out.append(rnd.choice(["S8000 M3", "M8", "M9", "M7"]))
        elif r < 0.11:
            word = rnd.choice(["G54", "G55", "G92 X1 Y-2", "G92.1", "G52 X3 Z1", "G52 X0",
                               "G10 L2 P1 X5", "G10 L2 P3 X30 Y20 Z0 R30\nG56"])
            out.append(word)
            known, turned = False, word.endswith("G56") or turned and word[:3] not in ("G54", "G55")
        elif r < 0.13:
            out.append(f"G4 P{rnd.choice([0.5, 1, 0.25])}")
        elif r < 0.17:
            plane = rnd.choice(["G17", "G18", "G19"])
            out.append(plane)
        elif r < 0.20:
            out.append(f"G53 G0 X{rnd.uniform(-9, 9):.3f} Y{rnd.uniform(-9, 9):.3f} Z10")
            known = False
        elif r < 0.23 and k > 0.8 * blocks:       # A carried on every block after
            pos["X"] = round(rnd.uniform(-20, 20), 4)
            out.append(f"G1 X{pos['X']} A{rnd.uniform(0, 90):.3f}")
        elif r < 0.25 and seed % 2:       # PMAC refuses threads: half the programs
            pos["Z"] = round(rnd.uniform(-5, 0), 3)
            out += ["S600 M3", f"G33 Z{pos['Z']} K1.5"]
        elif r < 0.55 and known and (plane == "G17" or not turned):
            out.append(_arc(rnd, plane, pos))
        else:
            word = rnd.choice(["G0", "G1", "G1", "G1"])
            for axis in "XYZ":
                pos[axis] = round(pos[axis] + rnd.uniform(-10, 10), rnd.choice([3, 6]))
            out.append(f"{word} X{pos['X']} Y{pos['Y']} Z{pos['Z']}"
                       f"{rnd.choice(['', '', ' F450'])}")
            known = True
    return "\n".join(out + ["M2"]) + "\n"


def _arc(rnd: random.Random, plane: str, pos: dict) -> str:
    """An arc from ``pos`` in ``plane`` (``pos`` moved to its end): of any
    sweep, or of a sliver (written as a line), or of extra turns."""
    (u, v), (ci, cj) = _plane_words(plane)
    radius = rnd.uniform(0.1, 8)
    sweep = rnd.choice([rnd.uniform(-6, 6), rnd.uniform(-1e-5, 1e-5), 3.5, -4])
    a0 = rnd.uniform(-math.pi, math.pi)
    cu, cv = pos[u] - radius * math.cos(a0), pos[v] - radius * math.sin(a0)
    eu, ev = cu + radius * math.cos(a0 + sweep), cv + radius * math.sin(a0 + sweep)
    turns = " P2" if rnd.random() < 0.25 else ""
    # 12 decimals: the end on the circle to well within SPIRAL_RADIUS_REL_TOL (an arc)
    text = (f"{'G3' if sweep > 0 else 'G2'} {u}{eu:.12f} {v}{ev:.12f} "
            f"{ci}{cu - pos[u]:.12f} {cj}{cv - pos[v]:.12f}{turns}"
            f"{rnd.choice(['', ' F300', ' F900'])}")
    pos[u], pos[v] = float(f"{eu:.12f}"), float(f"{ev:.12f}")
    return text


def _ring_program(seed: int) -> str:
    """A PMAC ring of short noisy LINEAR moves, a feed change half way: its
    offset folds and turns (corner arcs), and compensation makes its path
    as columns (:attr:`ToolPath.columns`)."""
    rnd = random.Random(seed)
    n = rnd.randint(80, 160)
    lines = ["OPEN PROG 1 CLEAR", f"CCR{rnd.choice([1, 2, 0.5])}", "F100", "LINEAR", "X60 Y0",
             rnd.choice(["CC1", "CC2"])]
    for k in range(n + 1):
        t = 2.0 * math.pi * (k % n) / n
        r = 50.0 + math.sin(7.0 * t) + (rnd.uniform(-0.01, 0.01) if k % n else 0.0)
        lines.append(f"X{r * math.cos(t):.4f} Y{r * math.sin(t):.4f}"
                     + (" F250" if k == n // 2 else ""))
    return "\n".join(lines + ["CC0", "X60 Y0", "CLOSE"]) + "\n"


@pytest.mark.parametrize("seed", range(12))
def test_bulk_writers_write_what_the_per_segment_road_writes(seed, monkeypatch):
    cp = cam_program(seed)
    cam = read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    made = read_text(_machine_program(seed), "made.ngc", "gcode")
    ring = read_text(_ring_program(seed), "ring.pmc", "pmac")
    paths = [(compensate(cam, default_style(cam)[0]), cam), (programmed_path(made), made),
             (compensate(ring, "pmac"), ring)]
    assert paths[2][0].columns is not None
    bulk = [_written(path, program) for path, program in paths]
    _per_segment(monkeypatch)
    assert bulk == [_written(path, program) for path, program in paths]
