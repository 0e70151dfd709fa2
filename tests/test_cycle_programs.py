"""Generated plate programs: compensated rectangles (G42 outside profiles) and
drilling patterns (G73 G81 G82 G83 G85 G89, G98 or G99, absolute hole lists
or G91 with L repeats) in random order, in a random G54 origin. Properties,
against the holes the generator asked for (worked out from the words it
wrote, not from ccopt):

* every hole is drilled where asked: the deepest feed of each hole is at the
  hole's (x, y) and the bottom, in the order written;
* a cycle feeds only along the drilling axis; it moves in the plane only at
  or above R; it retracts to R under G99 and to the initial level under G98;
* the contour verifies, and the export reads back to the same moves with the
  same machine words in the same order.

A handful of programs in the quick tier, hundreds in the slow tier.
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

import pytest

import ccopt
from ccopt.program.gcode import read_gcode
from ccopt.program.model import Motion

CYCLES = ("G73", "G81", "G82", "G83", "G85", "G89")


@dataclass
class Plate:
    text: str
    origin: tuple[float, float, float]
    # per cycle line: (retract "r"/"initial", r, initial level, [(x, y)], bottom), work mm
    drills: list = field(default_factory=list)


def _fmt(v: float) -> str:
    return f"{v:.3f}".rstrip("0").rstrip(".")


def make_plate(seed: int) -> Plate:
    rnd = random.Random(seed)
    origin = (rnd.uniform(-200, 200), rnd.uniform(-200, 200), rnd.uniform(-50, 0))
    lines = ["G21 G17 G90 G94", "G54", "T1 M6", f"S{rnd.randint(1000, 9000)} M3", "M8"]
    plate = Plate("", origin)
    z = 10.0
    lines.append(f"G0 X-20 Y-20 Z{_fmt(z)}")
    for part in rnd.sample(["contour", "drill", "drill2"], 3):
        if part == "contour":
            w, h = rnd.uniform(30, 80), rnd.uniform(20, 60)
            lines += ["G0 X-10 Y-10", "G1 Z-2 F300", f"G42 D1 G1 X0 Y0 F{rnd.randint(300, 900)}",
                      f"G1 X{_fmt(w)}", f"G1 Y{_fmt(h)}", "G1 X0", "G1 Y0", "G40 G1 X-10 Y-10",
                      "G0 Z10"]
            z = 10.0
            continue
        code = rnd.choice(CYCLES)
        retract = rnd.choice(["G98", "G99"])
        extra = {"G73": f" Q{_fmt(rnd.uniform(0.5, 3))}", "G83": f" Q{_fmt(rnd.uniform(0.5, 3))}",
                 "G82": f" P{_fmt(rnd.uniform(0, 1))}", "G89": f" P{_fmt(rnd.uniform(0, 1))}"}
        level = z
        if rnd.random() < 0.5:
            holes = [(rnd.uniform(0, 60), rnd.uniform(0, 40)) for _ in range(rnd.randint(1, 4))]
            r = rnd.uniform(-1, 12)
            bottom = r - rnd.uniform(1, 10)
            x, y = holes[0]
            lines.append(f"{retract} {code} X{_fmt(x)} Y{_fmt(y)} Z{_fmt(bottom)} R{_fmt(r)}"
                         f"{extra.get(code, '')} F{rnd.randint(100, 400)}")
            lines += [f"X{_fmt(x)} Y{_fmt(y)}" for x, y in holes[1:]]
            holes = [(float(_fmt(x)), float(_fmt(y))) for x, y in holes]
            r, bottom = float(_fmt(r)), float(_fmt(bottom))
            lines.append("G80")
        else:
            n = rnd.randint(1, 4)
            dx, dy = rnd.uniform(-10, 10), rnd.uniform(-10, 10)
            dr, dz = rnd.uniform(-8, 3), -rnd.uniform(1, 10)
            dx, dy, dr, dz = (float(_fmt(v)) for v in (dx, dy, dr, dz))
            lines += ["G0 X20 Y20",
                      f"G91 {retract} {code} X{_fmt(dx)} Y{_fmt(dy)} Z{_fmt(dz)} R{_fmt(dr)} "
                      f"L{n}{extra.get(code, '')} F{rnd.randint(100, 400)}", "G90 G80"]
            holes = [(20 + k * dx, 20 + k * dy) for k in range(1, n + 1)]
            r, bottom = level + dr, level + dr + dz
        plate.drills.append(("r" if retract == "G99" else "initial", r, level, holes, bottom))
        lines.append("G0 Z10")
        z = 10.0
    lines += ["M9", "M5", "M30"]
    plate.text = "\n".join(lines) + "\n"
    return plate


def check_plate(seed: int, tmp_path, export: bool) -> None:
    plate = make_plate(seed)
    ox, oy, oz = plate.origin
    params = {5221: ox, 5222: oy, 5223: oz}
    prog = read_gcode(plate.text, f"plate{seed}.ngc", tool_table={1: 6.0}, parameters=params)
    flat = [b for b in prog.blocks if b.cycle is not None]
    for b in flat:
        if b.motion is Motion.LINE:
            assert b.start[:2] == pytest.approx(b.end[:2], abs=1e-9), (seed, "feed in plane")
    want_holes = [(x + ox, y + oy, bottom + oz, retract, r + oz, level + oz)
                  for retract, r, level, holes, bottom in plate.drills for x, y in holes]
    # a hole's deepest feed: down to the lowest point its cycle line reaches
    deepest = {}
    for b in flat:
        if b.motion is Motion.LINE:
            deepest[b.source.line] = min(deepest.get(b.source.line, math.inf), b.end[2])
    bottoms = [k for k, b in enumerate(flat) if b.motion is Motion.LINE
               and b.end[2] < b.start[2] and math.isclose(b.end[2], deepest[b.source.line],
                                                           abs_tol=1e-9)]
    assert len(bottoms) == len(want_holes), (seed, plate.text)
    for k, (x, y, zb, retract, r, level) in zip(bottoms, want_holes):
        b = flat[k]
        assert b.end == pytest.approx((x, y, zb), abs=1e-6), (seed, plate.text)
        moving = [c for c in flat[:k] if c.motion is Motion.RAPID and c.start[:2] != c.end[:2]]
        assert moving[-1].end[2] >= r - 1e-9, (seed, "in-plane move below R")
        after = [c for c in flat[k + 1:] if c.motion is not Motion.DWELL]
        last = after[1] if b.cycle == "G85" else after[0]   # G85 feeds to R, then rapids
        top = r if retract == "r" else max(level, r)
        assert last.end[2] == pytest.approx(top, abs=1e-6), (seed, plate.text)
    if not export:
        return
    path = ccopt.compensate(prog, style="linuxcnc")
    assert ccopt.verify(path, prog).ok, (seed, plate.text)
    res = ccopt.export(path, tmp_path / f"p{seed}.nc", program=prog)
    assert res.verified and res.roundtrip_error < 1e-5
    back = read_gcode((tmp_path / f"p{seed}.nc").read_text(), "back.nc", parameters=params)
    assert [w for b in back.blocks for w in b.words] + list(back.meta["trailing_words"]) == \
        [w for b in prog.blocks for w in b.words] + list(prog.meta["trailing_words"])
    assert back.meta["program_end"] == "M30"
    moves = [b for b in back.blocks if b.motion.is_move]
    assert len(moves) == len(path.segments)
    for seg, b in zip(path.segments, moves):
        assert math.dist(seg.end_xyz, b.end) < 1e-5


@pytest.mark.parametrize("seed", range(5))
def test_generated_plates_quick(seed, tmp_path):
    check_plate(seed, tmp_path, export=True)


@pytest.mark.slow
def test_generated_plates_slow(tmp_path):
    for seed in range(5, 305):
        check_plate(seed, tmp_path, export=seed % 3 == 0)
