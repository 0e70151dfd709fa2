"""The plain-line path of the G-code reader reads what line-by-line reading
reads (issue 34: ``ccopt export`` reads its 20,000-line G-code back).

A run of plain straight move lines (``[N..] [G0|G1] [X..] [Y..] [Z..] [F..]``,
literal numbers) is executed by ``ccopt.program.gcode.plain.run_plain`` in
one loop, its blocks made field by field; any other line, and any line of a
state that changes what such a line does, goes through the reader's line
loop. Switching the plain path off (``run_plain`` returning the line it is
given) must leave the Program unchanged: every block field (compared by
``repr`` and by ``pickle``, which also keeps which tuples are shared), the
meta, and every error with its file:line:col and the blocks read before it.
"""
from __future__ import annotations

import math
import pickle
import random
from dataclasses import fields
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ccopt.program.gcode as gcode
from ccopt.errors import ProgramError
from ccopt.program.gcode import plain, read_gcode, reader
from ccopt.program.model import Block, Motion, Source

ROOT = Path(__file__).resolve().parents[2]


def _outcome(text: str, **kw):
    """Everything a read gives: the Program's repr and pickle, or the error
    with the blocks read before it."""
    try:
        prog = read_gcode(text, "e.ngc", **kw)
    except ProgramError as err:
        before = err.read_before
        return ("error", str(err), repr(before.blocks) if before else None,
                pickle.dumps(before) if before else None)
    return ("program", repr(prog.blocks), repr(prog.meta), pickle.dumps(prog))


def _both(text: str, **kw):
    """The outcome with the plain path, and line by line."""
    fast = _outcome(text, **kw)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(reader, "run_plain", lambda state, pc: pc)
        slow = _outcome(text, **kw)
    return fast, slow


def _taken(text: str, **kw) -> int:
    """Lines the plain path executed while reading ``text``."""
    count = 0
    run = plain.run_plain

    def counting(state, pc):
        nonlocal count
        after = run(state, pc)
        count += after - pc
        return after
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(reader, "run_plain", counting)
        try:
            read_gcode(text, "e.ngc", **kw)
        except ProgramError:
            pass
    return count


NUMBERS = st.one_of(
    st.decimals(min_value=-2000, max_value=2000, places=4, allow_nan=False,
                allow_infinity=False).map(lambda d: f"{d:f}"),
    st.integers(-10**7, 10**7).map(str),
    st.sampled_from(["0", "-0", "+0", ".5", "-.25", "7.", "00012.50", "999999.9999",
                     "1000000", "-1000000", "1000000.0001", "9" * 400, "1 0", "1.2.3"]))
SPACE = st.sampled_from([" ", " ", "", "\t", "  "])


@st.composite
def plain_line(draw) -> str:
    """A line the plain path takes when its values are in range (and some it
    must refuse: blanks inside numbers, lower case, a leading blank)."""
    head = draw(st.sampled_from(["", "G1", "G1", "G0", "G01", "G00", "N10 G1", "N7", "g1",
                                 " G1"]))
    words = [head] if head else []
    for letter in "XYZF":
        if draw(st.booleans()):
            words.append(letter + draw(NUMBERS))
    text = ""
    for word in words:
        text += word + draw(SPACE)
    return text.rstrip(" ") if draw(st.booleans()) else text


ARC_NUMBERS = st.one_of(NUMBERS, st.floats(-60, 60, allow_nan=False).map(lambda v: f"{v:.4f}"))


@st.composite
def arc_line(draw) -> str:
    """An arc line the plain path takes when its centre checks pass (and
    lines it must leave to the line loop: no centre word, K or R, lower
    case, words out of order, a centre off the arc)."""
    head = draw(st.sampled_from(["G2", "G3", "G02", "G03", "N20 G3", "", "", "g2", "G2 G91",
                                 "G1", "G0"]))
    words = [head] if head else []
    for letter in draw(st.sampled_from(["XYIJ", "XYIJ", "XYZIJF", "XI", "YJ", "XYJ", "XYI",
                                        "XY", "IJ", "XYKJ", "XYR", "XYJI", "XYIJF"])):
        words.append(letter + draw(ARC_NUMBERS))
    text = ""
    for word in words:
        text += word + draw(SPACE)
    return text.rstrip(" ") if draw(st.booleans()) else text


@st.composite
def circle_arcs(draw) -> str:
    """Arcs whose centre checks pass: ``G2``/``G3`` about a centre at
    incremental ``I J`` from the current point, ending on the same circle
    (written with 4 decimals, as CAM writes them), from ``X0 Y0``."""
    out, x, y = ["G0 X0 Y0", "G1 F300"], 0.0, 0.0
    for _ in range(draw(st.integers(1, 6))):
        r = draw(st.floats(0.05, 50))
        a0 = draw(st.floats(-3.2, 3.2))
        sweep = draw(st.floats(-6.2, 6.2).filter(lambda v: abs(v) > 1e-3))
        cx, cy = x - r * math.cos(a0), y - r * math.sin(a0)
        ex, ey = round(cx + r * math.cos(a0 + sweep), 4), round(cy + r * math.sin(a0 + sweep), 4)
        z = draw(st.sampled_from(["", " Z-1", " Z0.5"]))
        out.append(f"G{3 if sweep > 0 else 2} X{ex:.4f} Y{ey:.4f}{z} I{cx - x:.4f} "
                   f"J{cy - y:.4f}")
        x, y = ex, ey
    return "\n".join(out)


#: Lines that change what a plain line does, or that it must leave alone.
OTHER_LINES = st.sampled_from([
    "G91", "G90", "G20", "G21", "G93", "G94", "G95 S100 M3", "G7", "G8", "G18", "G17",
    "G92 X1 Y2", "G92.1", "G52 X3", "G10 L2 P1 R30", "G10 L2 P1 X5 Y5", "G55", "G54",
    "G41 D1", "G40", "T2 M6", "M8", "#1=5", "G1 X#1", "F0", "F500", "G80", "G2 X1 Y0 I1",
    "G0 A5", "G53 G0 X0", "(msg, hi)", "G90.1", "G91.1", "G19", "G2 X1 Y0 R1", "G1 X1 (ccopt: air)", "G4 P1", "", "G81 X1 Y1 Z-1 R1",
    "G1 X1 Y1 F-1", "G1 X1 F0", "M0", "G1 X1 Y1 Z1 A1", "X1 Y1", "G1 X1e3", "G28"])


@st.composite
def programs(draw) -> str:
    head = draw(st.sampled_from(["G21 G90 G94 F100\n", "G20 F10\n", "", "G91 F10\n",
                                 "G54\nG1 F600\n", "T1 M6\nG41 D1 F100\n", "G18 F100\n"]))
    lines = draw(st.lists(st.one_of(plain_line(), plain_line(), arc_line(), circle_arcs(),
                                    OTHER_LINES), min_size=1, max_size=12))
    end = draw(st.sampled_from(["", "M2\n", "%\n"]))
    return head + "\n".join(lines) + "\n" + end


@settings(max_examples=300, deadline=None)
@given(programs(), st.sampled_from([{}, {"units": "inch"}, {"keep_going": True},
                                    {"start": (999999.0, -999999.5, 999999.5)},
                                    {"parameters": {5221: 2.5, 5222: -1.0}},
                                    {"tool_table": {1: 6.0, 2: 4.0}}]))
def test_plain_path_reads_as_line_by_line(text, kw):
    fast, slow = _both(text, **kw)
    assert fast == slow


@pytest.mark.parametrize("text, kw", [
    # incremental ends at and past the bound
    ("G91 G1 F10\nX600000 Y1\nX600000\n", {}),
    ("G91 F10\nG0 Y-600000\nY-600000\nG1 Y-1\n", {}),
    ("G1 F10 X1\nX1000000 Y-1000000 Z1000000\nG91 X-0 Y0\n", {}),
    ("G1 F10\nG1 X1\n", {"start": (1e7, 0.0, 0.0)}),
    # the feed: none, zero, negative, inverse time, per revolution, set on a rapid
    ("G1 X1 Y1\n", {}), ("F0\nG1 X1\n", {}), ("G1 X1 F-1\n", {}), ("G0 X1 F-1\n", {}),
    ("G0 X1 F5\nG1 X2\n", {}),
    ("G93\nG1 X1 F10\nG1 X2\n", {}), ("G95 S100 M3\nG1 X1 F.1\nX2\n", {}),
    # modes that change a plain line: units, lathe diameter, offsets, rotation
    ("G20\nG1 X1 F10\n", {"units": "mm"}), ("G7\nG18 G1 X10 Z1 F100\nX20\n", {}),
    ("G10 L2 P1 X5 Y5 Z1\nG1 X1 Y1 Z1 F100\nG92 X0 Y0\nG1 X1\nG92.1\nG1 X2\n", {}),
    ("G10 L2 P1 R30\nG1 X1 Y1 F100\nG1 X2 Y2\n", {}),
    ("G1 X1 F100\nG0 A10\nG1 X2\nG1 X3\n", {}),
    # machine words wait for the next block; an arc mode or G80 in force
    ("T1 M6\nG1 X1 F100\nX2\nM8\nX3\n", {}),
    ("G1 X1 F100\nG2 X2 Y0 I0.5 J0\nX3 Y0 I0.5 J0\nX4 Y0\nG80\nX5\n", {}),
    # loops, subroutines, the runaway guards, %
    ("o1 repeat [40]\nG1 X1 Y2 F100\nG1 X2\n\nG0 X0\no1 endrepeat\nM2\n",
     {"max_loop_iterations": 7}),
    ("o100 sub\nG1 X#1 Y1 F100\nG1 X2 Y2\nG1 X3\no100 endsub\no100 call [5]\nG1 X9\nM2\n", {}),
    ("%\nG1 X1 F100\nG1 X2\n%\nG1 X3\n", {}),
    ("N10 G1 X1 Y1 F100\nN20 X2\nN30G1X3Y3\nN40 G01 X4 Y4 Z0 F50\nG00 X0 Y0\n\n\n", {}),
    ("G1 X1 F100\n\n\nG1 X 2\nG1 X1 0\ng1 x3\n G1 X4\nG1 X5 \n", {"keep_going": True}),
])
def test_plain_path_at_its_limits(text, kw):
    fast, slow = _both(text, **kw)
    assert fast == slow


@pytest.mark.parametrize("text, kw", [
    # arcs: a centre off the arc (radii disagree past the tolerance), on an end,
    # on the bound; modal arc lines; one centre word; a helix; incremental ends
    ("G1 F100\nG2 X2 Y0 I1 J0\nG2 X4 Y0 I1.1 J0\nG1 X5\n", {}),
    ("G1 F100\nG3 X2 Y0 I0 J0\nG1 X3\n", {}),
    ("G1 F100\nG2 X2 Y0 I1\nX4 Y0 I1\nG3 X2 J0 I-1\nX6 Y2 Z-1 J2\nY0 I2 J-1\n", {}),
    ("G1 F100\nG2 X999999 Y0 I499999.5 J0\nG3 X-999999 Y0 I-999999 J0\n", {}),
    ("G91 G1 F100\nG2 X2 Y0 I1 J0\nG3 X2 Y0 I1 J0\nG0 X1\n", {}),
    ("G54\nG1 F100\nG2 X2 Y0 I1 J0\nG3 X0 Y0 I-1 J0\n", {"parameters": {5221: 2.5}}),
    # what the arc path leaves alone: other planes, absolute centres, R, P, K,
    # inverse time, inch input, a rotated system, compensation changes
    ("G18 G1 F100\nG2 X2 Z0 I1 K0\nG17\nG2 X4 Y0 I1 J0\n", {}),
    ("G90.1 G1 F100\nG2 X2 Y0 I1 J0\nG91.1\nG2 X4 Y0 I1 J0\n", {}),
    ("G1 F100\nG2 X2 Y0 R1\nG2 X4 Y0 I1 J0 P2\nG2 X6 Y0 I1 J0 K0\n", {}),
    ("G93\nG2 X2 Y0 I1 J0 F10\n", {}), ("G20\nG1 F10\nG2 X2 Y0 I1 J0\n", {"units": "mm"}),
    ("G10 L2 P1 R30\nG1 F100\nG2 X2 Y0 I1 J0\n", {}),
    ("T1 M6\nG41 D1 G1 X1 Y1 F100\nG2 X3 Y1 I1 J0\nG40 G1 X9\n", {"tool_table": {1: 1.0}}),
    ("G1 F100\nG1 X1 I1 J0\nG2 X1 Y1\nG2 I1 J0\n", {"keep_going": True}),
])
def test_arc_path_at_its_limits(text, kw):
    fast, slow = _both(text, **kw)
    assert fast == slow


def test_arc_lines_are_taken():
    """Arcs as ccopt's exports and CAM write them go the plain path, with the
    line loop's centres, bit for bit."""
    text = "G21 G90 G94\nG1 X0 Y0 Z0 F600\n" + "".join(
        f"G{2 + k % 2} X{k + 1}.0000 Y0.0000 Z0.0000 I0.5000 J0.0000\n" for k in range(20))
    assert _taken(text) == 21
    assert _taken("G1 F100\nN10 G02 X2 Y0 I1 J0\nN20 X4 Y0 I1\nG03 X2 Y0 I-1 J0\n") == 3
    assert _taken("G1 F100\nG03 X2 Y0 J0 I-1\n") == 0       # words out of order
    assert _taken("G18 G1 F100\nG2 X2 Z0 I1 K0\n") == 0
    fast, slow = _both(text)
    assert fast == slow
    prog = read_gcode(text, "a.ngc")
    assert [b.motion for b in prog.blocks[1:3]] == [Motion.ARC_CW, Motion.ARC_CCW]
    assert prog.blocks[1].center == (0.5, 0.0, 0.0) and prog.blocks[2].center == (1.5, 0.0, 0.0)


def test_runaway_guard_counts_plain_lines(monkeypatch):
    text = "G1 F100\n" + "".join(f"G1 X{k} Y{k} Z0\n" for k in range(50))
    for limit in (1, 2, 10, 50, 51, 52):
        monkeypatch.setattr(gcode, "MAX_EXECUTED_LINES", limit)
        fast, slow = _both(text)
        assert fast == slow, limit


def test_plain_lines_are_taken():
    """The path is used: on an export's lines, CAM lines with N words and
    modal moves, under G91 and under a work offset."""
    text = "G21 G90 G94\nG1 F600\n" + "".join(f"G1 X{k}.5 Y-{k} Z-1\n" for k in range(20))
    assert _taken(text) == 20
    assert _taken("G91 F10\nN1 G0 X1\nN2 G1 Y2\nX3 Z-1 F20\n") == 3
    assert _taken("G54\nG1 X1 F10\nX2\n", parameters={5221: 2.5}) == 2
    assert _taken("G20\nG1 X1 F10\nX2\n", units="mm") == 0
    assert _taken("G93\nG1 X1 F10\nX2\n") == 0


def test_plain_blocks_are_the_dataclass_blocks():
    """The blocks of a run have every field set, are the blocks ``Block``
    makes of those fields, and each starts at the previous one's end tuple."""
    text = "G21 F100\nG0 X1 Y2 Z3\nG1 X-0\nN5 Y-1.5 Z.5\n\nG1 X2 F50\n"
    prog = read_gcode(text, "s.ngc")
    assert _taken(text) == 5
    assert [b.source.line for b in prog.blocks] == [2, 3, 4, 6]
    assert [b.source.col for b in prog.blocks] == [1, 1, 1, 1]
    assert [b.motion for b in prog.blocks] == [Motion.RAPID] + [Motion.LINE] * 3
    assert [b.feed for b in prog.blocks] == [None, 100 / 60, 100 / 60, 50 / 60]
    for before, block in zip(prog.blocks, prog.blocks[1:]):
        assert block.start is before.end
    for block in prog.blocks:
        expected = Block(**{f.name: getattr(block, f.name) for f in fields(Block)})
        assert type(block) is Block and type(block.source) is Source
        assert block == expected and hash(block) == hash(expected)
        assert repr(block) == repr(expected)
    # X-0 plus the work offset (0.0), as the line loop adds it: 0.0
    assert repr(prog.blocks[1].end) == "(0.0, 2.0, 3.0)"


def _inputs() -> list[Path]:
    return sorted(p for folder in ("tests", "cases") for p in (ROOT / folder).rglob("*")
                  if p.suffix in (".ngc", ".nc") and p.is_file())


def _mutants(texts: list[str], count: int, seed: int) -> list[str]:
    """Seeded mutants of ``texts``: mode and move lines inserted, lines
    dropped or doubled, one character changed."""
    rng = random.Random(seed)
    extra = ["G91", "G90", "G20", "G93", "G7", "G92 X1", "G10 L2 P1 R10", "T2 M6", "F0",
             "G1 X1 Y1 Z1", "X2 Y2", "G0 X1", "G80", "G1 X1e3", "", "G1 X9999999"]
    out = []
    for _ in range(count):
        lines = rng.choice(texts).split("\n")
        if len(lines) > 200:
            start = rng.randrange(len(lines) - 150)
            lines = lines[:8] + lines[start:start + 150]
        for _ in range(rng.randint(1, 4)):
            k = rng.randrange(len(lines))
            op = rng.random()
            if op < 0.5:
                lines.insert(k, rng.choice(extra))
            elif op < 0.7:
                del lines[k]
            elif op < 0.85:
                lines.insert(k, lines[rng.randrange(len(lines))])
            elif lines[k]:
                i = rng.randrange(len(lines[k]))
                lines[k] = lines[k][:i] + rng.choice("GXYZF0-. 1") + lines[k][i + 1:]
        out.append("\n".join(lines))
    return out


def test_files_and_their_mutants_read_alike():
    texts = []
    for path in _inputs():
        try:
            texts.append(path.read_text(encoding="utf-8"))
        except UnicodeDecodeError:
            continue
    assert texts
    for text in texts + _mutants(texts, 150, seed=34):
        fast, slow = _both(text, tool_table={1: 6.0, 2: 4.0})
        assert fast == slow


def _arc_run(seed: int, count: int) -> str:
    """``count`` seeded lines after ``X0 Y0``: mostly arcs (either way, with
    ``I`` and ``J`` or the one that is not zero, modal, a helix's ``Z``,
    tiny radii), some straight lines and feeds, and now and then an arc the
    line loop may refuse, which the plain path must then leave to it: its
    end off the circle (at the radius tolerances, absolute and relative,
    either way), its centre on an end or at the zero-radius limit, a centre
    word or the centre past the bound (a straight line back to where it
    started follows)."""
    rng = random.Random(seed)
    out, x, y, mode = ["G21 G90 G94", "G1 X0 Y0 Z0 F600"], 0.0, 0.0, 1
    for _ in range(count):
        if rng.random() < 0.2:
            x, y, mode = round(x + rng.uniform(-5, 5), 4), round(y + rng.uniform(-5, 5), 4), 1
            feed = f" F{rng.randint(1, 900)}" if rng.random() < 0.2 else ""
            out.append(f"G1 X{x:.4f} Y{y:.4f} Z0{feed}")
            continue
        r = rng.choice((rng.uniform(0.0005, 0.01), rng.uniform(0.05, 50.0)))
        a0, sweep = rng.uniform(-math.pi, math.pi), rng.uniform(-6.3, 6.3)
        if rng.random() < 0.1:
            a0 = rng.choice((0.0, 0.5, 1.0, -0.5)) * math.pi    # a centre word of zero
        r1, bad = r, rng.random()
        if bad < 0.04:      # at a radius tolerance: 0.002 absolute, 0.1 % relative
            off = max(0.002, 0.001 * r) * (1.0 + rng.choice((-1, 1)) * rng.choice((5e-4, 2e-3)))
            r1 = r + rng.choice((-1, 1)) * off
        cx, cy = x - r * math.cos(a0), y - r * math.sin(a0)
        ex, ey = cx + r1 * math.cos(a0 + sweep), cy + r1 * math.sin(a0 + sweep)
        i, j = cx - x, cy - y
        if 0.04 <= bad < 0.06:
            i, j = ex - x, ey - y                           # the centre on the end
        elif 0.06 <= bad < 0.07:
            i, j, ex, ey = rng.choice((1e-4, 2e-4, 3e-4)), 0.0, x, y    # a full circle
        elif 0.07 <= bad < 0.08:
            i = rng.choice((1000000.0001, 999999, -2000000))     # past the bound
        g = 3 if sweep > 0 else 2
        head = "" if g == mode and rng.random() < 0.3 else f"G{g} "
        words = f"{'' if i == 0 else f' I{i:.7f}'}{'' if j == 0 else f' J{j:.7f}'}"
        z = rng.choice(("", " Z0", " Z-1"))
        out.append(f"{head}X{ex:.7f} Y{ey:.7f}{z}{words or ' I0'}")
        if bad < 0.08:
            out.append(f"G1 X{x:.4f} Y{y:.4f}")
            mode = 1
        else:
            x, y, mode = round(ex, 7), round(ey, 7), g
    return "\n".join(out) + "\nM2\n"


@pytest.mark.parametrize("seed", range(4))
def test_arc_runs_read_as_line_by_line(seed):
    """Long runs of arcs, their centres worked out together: the blocks, the
    refused arcs (exactly those left to the line loop, which says why) and
    the run after each, as line by line."""
    text = _arc_run(seed, 400)
    # the plain path leaves the line loop just the header, M2 and the lines it refuses
    refused = read_gcode(text, "e.ngc", keep_going=True).meta["errors_passed"]
    assert len(refused) > 5
    assert _taken(text, keep_going=True) == len(text.splitlines()) - 2 - len(refused)
    for kw in ({"keep_going": True}, {}, {"start": (999990.0, 0.0, 0.0), "keep_going": True}):
        fast, slow = _both(text, **kw)
        assert fast == slow
