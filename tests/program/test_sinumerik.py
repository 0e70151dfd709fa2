"""The SINUMERIK 840D reader: the language around the moves, the circle
forms, the tool radius compensation words, and located refusals.

Expected positions are worked out by hand from the programs (never copied
from ccopt's output).
"""
from __future__ import annotations

import math
import random
from dataclasses import replace

import pytest

from ccopt import cli
from ccopt.errors import ProgramError
from ccopt.program import dialect_of, read_program, read_text
from ccopt.program.model import Motion
from ccopt.program.sinumerik import read_sinumerik

TOL = 1e-9


def ends(prog):
    return [tuple(round(c, 9) for c in b.end) for b in prog.blocks]


def read(text: str, **kw):
    return read_sinumerik(text, "p.mpf", **kw)


def test_suffixes_pick_the_dialect(tmp_path):
    assert dialect_of("part.mpf") == "sinumerik"
    assert dialect_of("SUB.SPF") == "sinumerik"
    f = tmp_path / "part.mpf"
    f.write_text("G1 X10 F100\n")
    prog = read_program(f)
    assert prog.dialect == "sinumerik" and prog.blocks[0].end == (10.0, 0.0, 0.0)
    assert read_text("G1 X3 F100", "x", "sinumerik").blocks[0].end == (3.0, 0.0, 0.0)


def test_block_numbers_comments_and_r_parameters():
    prog = read("N10 G90 G1 F600 ; feed\nR1=10 R2=R1*2+1 ; R2 = 21\n"
                "N20 X=R2 Y=R1/4 Z=-R1 MOD 3\nN30 X=(R1+R2)*2 Y=SIN(30)*10 Z=POT(3)\n")
    assert ends(prog) == [(21.0, 2.5, -1.0), (62.0, 5.0, 9.0)]
    # the feed is per minute: 600 mm/min = 10 mm/s
    assert prog.blocks[0].feed == pytest.approx(10.0)


def test_def_variables_and_atan2():
    prog = read("DEF REAL AA=3, BB\nDEF INT NN=2.7\nBB=AA*NN\nG1 F100 X=BB Y=ATAN2(1,1)\n")
    assert ends(prog) == [(6.0, 45.0, 0.0)]


def test_gotof_gotob_loop_counts():
    # three passes of the backward jump: X 10, 20, 30
    prog = read("R1=0\nG1 F100\nTOP: R1=R1+1\nX=R1*10\nIF R1<3 GOTOB TOP\nGOTOF DONE\n"
                "X999\nDONE: Y5\n")
    assert ends(prog) == [(10, 0, 0), (20, 0, 0), (30, 0, 0), (30, 5, 0)]


def test_if_else_while_repeat_loop_for():
    prog = read("G1 F100\nR1=2\nIF R1==2\nX1\nELSE\nX2\nENDIF\nIF R1<>2\nY7\nELSE\nY1\nENDIF\n"
                "R2=0\nWHILE R2<2\nR2=R2+1\nZ=R2\nENDWHILE\n"
                "REPEAT\nR2=R2-1\nUNTIL R2<=0\nX=10+R2\n"
                "LOOP\nR3=R3+1\nIF R3>1 GOTOF OUT\nENDLOOP\nOUT: Y=R3*10\n"
                "FOR R4=1 TO 3\nX=R4\nENDFOR\n")
    assert ends(prog) == [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 1, 2), (10, 1, 2), (10, 20, 2),
                          (1, 20, 2), (2, 20, 2), (3, 20, 2)]


def test_cr_arcs_short_and_long():
    # (0,0) -> (10,0), CR=5: a half circle centred (5,0); CR=-6.25 with G2: the
    # centre right of the chord for the long arc... G2 CR=+: shorter arc, centre
    # to the right of (0,0)->(10,0): (5,-d), d = sqrt(6.25^2 - 25) = 3.75.
    prog = read("G1 F100\nG2 X10 Y0 CR=6.25\nG0 X0\nG2 X10 Y0 CR=-6.25\n")
    assert prog.blocks[0].center[:2] == pytest.approx((5.0, -3.75))
    assert prog.blocks[2].center[:2] == pytest.approx((5.0, 3.75))


def test_ar_with_centre_and_with_end_point():
    # centre (0,0) from start (10,0): I-10; AR=90 counter-clockwise -> (0,10)
    prog = read("G0 X10 Y0\nG3 I-10 J0 AR=90 F100\n")
    assert prog.blocks[1].end[:2] == pytest.approx((0.0, 10.0), abs=TOL)
    # end point (0,10) from (10,0), AR=90 clockwise: chord midpoint (5,5), half
    # chord 5*sqrt2, distance to the centre 5*sqrt2/tan45 = 5*sqrt2 to the right
    # of the chord (direction (-1,1)/sqrt2, right normal (1,1)/sqrt2): (10,10)
    prog = read("G0 X10 Y0\nG2 X0 Y10 AR=90 F100\n")
    assert prog.blocks[1].center[:2] == pytest.approx((10.0, 10.0))
    assert prog.blocks[1].motion is Motion.ARC_CW


def test_cip_and_ct():
    # through (0,0), (5,5), (10,0): centre (5,0), clockwise
    prog = read("G1 F100 X0 Y0\nCIP X10 Y0 I1=5 J1=5\n")
    b = prog.blocks[1]
    assert b.motion is Motion.ARC_CW and b.center[:2] == pytest.approx((5.0, 0.0))
    # after a move along +X ending at (10,0), CT to (20,10): the centre on the
    # left normal at distance rho = |d|^2 / (2 n.d) = 200 / 20 = 10: (10,10)
    prog = read("G1 F100 X10 Y0\nCT X20 Y10\n")
    b = prog.blocks[1]
    assert b.motion is Motion.ARC_CCW and b.center[:2] == pytest.approx((10.0, 10.0))


def test_turn_helix_ac_ic_and_incremental():
    prog = read("G1 F100 X10 Y0 Z0\nG3 X10 Y0 Z-4 I-10 J0 TURN=1\n"
                "G1 G91 X=AC(3) Y5\nG90 X=IC(2) Y=IC(-1)\n")
    assert prog.blocks[1].turns == 1
    assert ends(prog)[2:] == [(3.0, 5.0, -4.0), (5.0, 4.0, -4.0)]


def test_units_and_dwell():
    prog = read("G70 G1 F10 X1\nG4 F2.5\n")
    assert prog.units == "inch" and prog.blocks[0].end[0] == 1.0
    assert prog.blocks[1].motion is Motion.DWELL and prog.blocks[1].dwell == 2.5


def test_tool_radius_from_tc_dp6_table_d0_and_offn():
    prog = read("$TC_DP6[3,1]=4\nT3 D1\nG41 G1 X10 F100\nOFFN=0.5\nX20\nD0\nX30\n")
    radii = [b.modal.radius for b in prog.blocks]
    assert radii == [4.0, 4.5, 0.0]
    assert prog.blocks[0].modal.side == 1
    # from the tool table (diameters): tool 2 of diameter 6 -> radius 3
    prog = read("T2 D1\nG42 G1 X10 F100\n", tool_table={2: 6.0})
    assert prog.blocks[0].modal.radius == 3.0 and prog.blocks[0].modal.side == -1
    # nothing gives a radius: None (--radius must)
    assert read("T5 D1\nG41 G1 X10 F100\n").blocks[0].modal.radius is None


def test_compensation_modes_travel_on_the_blocks():
    prog = read("G1 F100\nG451 DISC=30 KONT CDON X1\nG450 NORM X2\n"
                "G41 G247 G143 G341 DISR=4 DISCL=AC(2) FAD=60 X3\nX4\n")
    m = [b.modal.siemens for b in prog.blocks]
    assert (m[0].corner, m[0].disc, m[0].approach, m[0].bottleneck) == ("G451", 30, "KONT", "CDON")
    assert (m[1].corner, m[1].approach) == ("G450", "NORM")
    sar = m[2].sar
    assert (sar.kind, sar.direction, sar.infeed, sar.disr, sar.discl, sar.discl_abs) == \
        ("G247", "G143", "G341", 4.0, None, 2.0)
    assert sar.fad == pytest.approx(1.0)     # 60 mm/min
    assert m[3].sar is None                  # non-modal: its own block only


def test_continuous_path_modes_are_read_and_noted():
    prog = read("G64 G642 G1 X1 F100\nSTOPRE\nG60 X2\n")
    assert len(prog.blocks) == 2
    assert set(prog.meta["sinumerik_ignored"]) >= {"G64", "G642", "STOPRE", "G60"}


def test_g460_the_default_retraction_strategy_is_read_and_compensates_as_without_it():
    """G460 (PM 8.11.2 / W1 2.4: approach and retraction "as before") changes
    nothing ccopt computes: the tool path is the same as without it, corner
    by corner, and G460 is noted."""
    from ccopt.compensate import compensate
    body = ("$TC_DP6[1,1]=5\nN10 G17 G90 T1 D1\nN20 G0 X0 Y0\n{g}N30 G1 G41 X10 Y0 F500\n"
            "N40 X50\nN50 Y30\nN60 G40 X60 Y40\nM30\n")
    with_g460, plain = read(body.format(g="N25 G460\n")), read(body.format(g=""))
    assert "G460" in with_g460.meta["sinumerik_ignored"]
    a, b = (compensate(p, style="siemens").segments for p in (with_g460, plain))
    assert [(s.kind, s.start, s.end) for s in a] == [(s.kind, s.start, s.end) for s in b]
    # G41 at radius 5 along +X, then +Y: the offset corner at (45, 5) (an inside turn)
    assert any(s.end == pytest.approx((45.0, 5.0)) for s in a)


def _g460_same_path(seed: int) -> None:
    """A generated plate (tests/sinumerik_plates.py) with G460 on its approach
    (G41/G42) and retraction (G40) blocks compensates, in the siemens and
    pmac styles, to the tool path of the plate without it."""
    from ccopt.compensate import compensate
    from sinumerik_plates import generated_plate
    text = generated_plate(seed)[0]
    marked = "\n".join(line + " G460" if line.startswith(("G41", "G42", "G40")) else line
                        for line in text.splitlines()) + "\n"
    assert marked.count("G460") == 2
    a, b = read(marked), read(text)
    for style in ("siemens", "pmac"):
        pa, pb = (compensate(p, style=style).segments for p in (a, b))
        assert [(s.kind, s.start, s.end) for s in pa] == [(s.kind, s.start, s.end) for s in pb], \
            (seed, style)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_g460_on_generated_plates_is_the_path_without_it(seed):
    _g460_same_path(seed)


@pytest.mark.slow
def test_g460_on_generated_plates_is_the_path_without_it_many():
    for seed in range(3, 60):
        _g460_same_path(seed)


@pytest.mark.parametrize("g", [461, 462])
def test_g461_g462_are_refused_where_they_stand(g):
    with pytest.raises(ProgramError) as e:
        read(f"$TC_DP6[1,1]=10\nN30 G0 X0 Y0 T1 D1\nN40 Y20\nN50 G42 X50 Y5 G{g}\n")
    assert (e.value.line, e.value.col) == (4, 16)          # the G of G46x
    assert f"G{g} is not read" in e.value.message and "G460" in e.value.message


REFUSALS = {
    "subprogram without its file": ("G1 X1 F100\nL123\n", 2, 1, "no subprogram file L123"),
    "frame": ("G1 X1 F100\nMIRROR X0\n", 2, 1, "scaling and mirroring"),
    "TRANS with a move": ("TRANS X10 G1 F100\n", 1, 1, "X Y Z only"),
    "TRANS while on": ("G1 F100 G41 X1\nTRANS X10\n", 2, 1, "compensation on"),
    "rounding too large": ("G1 X1 F100 RND=2\nY5\n", 1, 12, "too large"),
    "contour over two blocks": ("G1 X1 F100 ANG=30 Y3\n", 1, 12, "two or three blocks"),
    "unknown G": ("G1 X1 F100\nG333 X2\n", 2, 1, "G333"),
    "unmatched ENDIF": ("G1 X1 F100\nENDIF\n", 2, 1, "ENDIF without its IF"),
    "unclosed WHILE": ("WHILE R1<1\nG1 X1 F100\n", 1, 1, "never closed"),
    "missing label": ("GOTOF NOWHERE\n", 1, 7, "no jump label NOWHERE"),
    "unknown variable": ("G1 F100 X=FOO\n", 1, 11, "unknown variable FOO"),
    "SAR without G41": ("G1 F100 G147 DISR=2 X5\n", 1, 9, "switches compensation on"),
    "SAR with no end point": ("G41 G147 DISR=2 Z0 F100\nG1 Z5\n", 2, 4, "nothing may move"),
    "SAR never ended": ("G1 F100\nG41 G147 DISR=2 Z0\n", 2, 5, "no later block"),
    "quarter without DISR": ("G1 G41 G247 X5 F100\n", 1, 8, "DISR > 0"),
    "DEF of an address": ("DEF REAL B\n", 1, 10, "an address"),
    "endless loop": ("LOOP\nENDLOOP\n", 2, 1, "loop passes"),
    "DISC out of range": ("G450 DISC=150\n", 1, 6, "DISC runs from 0 to 100"),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_are_located(name):
    text, line, col, words = REFUSALS[name]
    with pytest.raises(ProgramError) as info:
        read(text, max_loop_iterations=100)
    exc = info.value
    assert (exc.file, exc.line, exc.col) == ("p.mpf", line, col), str(exc)
    assert words in str(exc)


def test_cli_refusal_exit_2_one_line(tmp_path, capsys):
    f = tmp_path / "bad.mpf"
    f.write_text("G1 X1 F100\nSCALE X2\n")
    rc = cli.main(["compensate", str(f), "--radius", "1"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and err.startswith(f"{f}:2:1:"), err


def test_circle_geometry_is_consistent_with_its_centre():
    prog = read("G1 F100 X0 Y0\nCIP X8 Y4 I1=2 J1=6\n")
    b = prog.blocks[1]
    c = b.center
    r0 = math.dist(c[:2], b.start[:2])
    assert math.dist(c[:2], b.end[:2]) == pytest.approx(r0)
    assert math.dist(c[:2], (2.0, 6.0)) == pytest.approx(r0)


def test_subprogram_calls_by_name_and_number_with_passes(tmp_path):
    (tmp_path / "main.mpf").write_text("G90 G1 F600 X0 Y0\nR1=0\nSTEP P2\nL12\nX100\nM30\n")
    # each pass: X += 10 at Y0, then Y10 while R1 <= 100
    (tmp_path / "STEP.SPF").write_text("PROC STEP\nR1=R1+10\nG1 X=R1 Y0\n"
                                       "IF R1>100 GOTOF OUT\nY10\nOUT: M17\n")
    (tmp_path / "L12.spf").write_text("G1 Y=R1*2\nRET\n")
    prog = read_program(tmp_path / "main.mpf")
    assert ends(prog) == [(0, 0, 0), (10, 0, 0), (10, 10, 0), (20, 0, 0), (20, 10, 0),
                          (20, 40, 0), (100, 40, 0)]
    assert prog.blocks[1].source.file == str(tmp_path / "STEP.SPF")
    assert prog.blocks[1].source.line == 3


def test_subprogram_errors_name_the_subprogram_file(tmp_path):
    (tmp_path / "main.mpf").write_text("G1 X1 F100\nSUBX\n")
    (tmp_path / "SUBX.SPF").write_text("PROC SUBX\nG1 X=NOPE\n")
    with pytest.raises(ProgramError) as info:
        read_program(tmp_path / "main.mpf")
    assert (info.value.file, info.value.line, info.value.col) == (
        str(tmp_path / "SUBX.SPF"), 2, 6)
    (tmp_path / "other.mpf").write_text("G1 X1 F100\nSUBX X5\n")
    with pytest.raises(ProgramError) as info:
        read_program(tmp_path / "other.mpf")
    assert info.value.line == 2 and "takes its block" in str(info.value)
    (tmp_path / "PARAMS.SPF").write_text("PROC PARAMS(REAL A)\nG1 X1\n")
    (tmp_path / "third.mpf").write_text("G1 X1 F100\nPARAMS\n")
    with pytest.raises(ProgramError) as info:
        read_program(tmp_path / "third.mpf")
    assert "with parameters" in str(info.value)


def test_trans_atrans_named_tools_and_noted_settings():
    prog = read('T="MILL10" D1 M6\nSOFT COMPCAD G642 ADIS=0.05\nCYCLE832(0.01,_FINISH,1)\n'
                'WORKPIECE(,"",,"BOX",112,0,-50,-80,0,0,100,100)\nTRANS X10 Y5\n'
                'G1 F100 X0 Y0\nATRANS X1\nG1 X1\nTRANS\nX2\nG41 X3\n')
    # TRANS X10 Y5: work (0,0) is machine (10,5); ATRANS X1 adds: work X1 -> 12;
    # TRANS alone: no translation, Y stays where it is
    assert ends(prog) == [(10, 5, 0), (12, 5, 0), (2, 5, 0), (3, 5, 0)]
    assert prog.blocks[-1].modal.radius is None      # a named tool: --radius gives it
    assert set(prog.meta["sinumerik_ignored"]) >= {"SOFT", "COMPCAD", "ADIS", "CYCLE832",
                                                  "WORKPIECE"}


def test_cli_dialect_option_and_units(tmp_path, capsys):
    f = tmp_path / "part.txt"
    f.write_text("G70 G1 F10 X1 Y2\n")
    assert cli.main(["show", str(f), "--dialect", "sinumerik", "--units", "mm"]) == 0
    out = capsys.readouterr().out
    assert "sinumerik" in out and "units mm" in out
    prog = read_program(f, "sinumerik", units="mm")
    assert prog.blocks[0].end[:2] == pytest.approx((25.4, 50.8))


# G group 1 at program start: its reset value (MD20150 $MC_GCODE_RESET_VALUES),
# G1 in Siemens' standard configuration (PM Fundamentals, list of G functions:
# G1 "Def."; 808D manual: "G01 *"). docs/sinumerik.md, "Moves".

def test_axis_words_before_any_motion_word_move_at_g1():
    prog = read("N10 X0 Y0 F1000\nN20 X10\n")
    # by hand: N10 goes from the start (0,0,0) to (0,0,0), N20 from there to
    # (10,0,0), both straight at F1000 mm/min = 1000/60 mm/s
    assert [b.motion for b in prog.blocks] == [Motion.LINE, Motion.LINE]
    assert [b.start for b in prog.blocks] == [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]
    assert ends(prog) == [(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)]
    assert [b.feed for b in prog.blocks] == [pytest.approx(1000 / 60)] * 2
    assert [b.source.line for b in prog.blocks] == [1, 2]


def test_a_programmed_g0_first_still_rapids():
    prog = read("N10 G0 X0 Y0 F1000\nN20 X10\n")
    assert [b.motion for b in prog.blocks] == [Motion.RAPID, Motion.RAPID]
    assert ends(prog) == [(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)]
    assert [b.feed for b in prog.blocks] == [None, None]


def test_the_reset_g1_without_a_feed_is_refused_as_g1_without_f():
    # the G-code reader's refusal of G1 with no F, located at the block's move
    with pytest.raises(ProgramError) as info:
        read("N10 X0 Y0\nN20 X10\n")
    exc = info.value
    assert (exc.file, exc.line, exc.col) == ("p.mpf", 1, 5), str(exc)
    assert "feed move with no feed rate F" in str(exc)
    with pytest.raises(ProgramError) as info:
        read_text("G1 X0 Y0\n", "p.ngc", "gcode")
    assert "feed move with no feed rate F" in str(info.value)


def test_the_gcode_dialect_still_wants_a_motion_word():
    with pytest.raises(ProgramError) as info:
        read_text("N10 X0 Y0 F1000\nN20 X10\n", "p.ngc", "gcode")
    exc = info.value
    assert (exc.file, exc.line, exc.col) == ("p.ngc", 1, 5), str(exc)
    assert "X word with no motion mode in force: add G0, G1, G2 or G3" in str(exc)


def _random_program(rng) -> list[str]:
    """A few blocks; the first moves with no G0-G3 (sometimes no F either)."""
    def axes(k=None):
        picked = rng.sample("XYZ", k or rng.randint(1, 3))
        return " ".join(f"{a}{rng.randint(-40, 40) / 4:g}" for a in sorted(picked))
    first = ["N10"] + [rng.choice(["G90", "G91"])] * (rng.random() < 0.3) + [axes()]
    if rng.random() < 0.85:
        first.append(f"F{rng.randint(1, 50) * 100}")
    blocks = [" ".join(first)]
    for n in range(rng.randint(1, 5)):
        words = [f"N{20 + 10 * n}"]
        motion = rng.choice(["", "", "", "G0", "G1", "G2", "G3"])
        if motion:
            words.append(motion)
        if rng.random() < 0.15:
            words.append(rng.choice(["G90", "G91"]))
        if motion in ("G2", "G3"):
            # X and Y within +-40 (G91: +-80 from the start): a chord under
            # 2 * 500, so CR=500 always gives a circle
            words += [axes(2) if rng.random() < 0.5 else "X5 Y-5", "CR=500"]
        elif rng.random() < 0.9:
            words.append(axes())
        if rng.random() < 0.25:
            words.append(f"F{rng.randint(1, 50) * 100}")
        blocks.append(" ".join(words))
    return blocks


def _outcome(text: str):
    """The blocks (the column aside: the inserted G1 shifts the words) or the
    error's message and line."""
    try:
        prog = read(text)
    except ProgramError as exc:
        return ("error", exc.message, exc.line)
    return [replace(b, source=replace(b.source, col=1)) for b in prog.blocks]


def test_generated_programs_read_as_with_g1_in_the_first_block():
    rng = random.Random(20150)
    kinds = set()
    for _ in range(50):
        blocks = _random_program(rng)
        with_g1 = [blocks[0].replace("N10 ", "N10 G1 ", 1)] + blocks[1:]
        got = _outcome("\n".join(blocks) + "\n")
        assert got == _outcome("\n".join(with_g1) + "\n"), blocks
        kinds.add("error" if isinstance(got, tuple) else "read")
    assert kinds == {"read", "error"}     # both cases were generated
