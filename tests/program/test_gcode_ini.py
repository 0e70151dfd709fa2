"""``--ini``: a LinuxCNC machine's INI file gives the G-code reader its tool
table and the table's units, the subroutine folders, the parameter file and
``#<_ini[SECTION]NAME>`` values (ccopt.program.gcode.ini).

LinuxCNC's own ``tests/interp/iniparam`` is kept in
tests/conformance/linuxcnc/ini (licence: that folder's README)."""
from __future__ import annotations

import pytest
from hypothesis import given, settings, strategies as st

from ccopt.cli import main
from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.program import read_program
from ccopt.program.gcode.ini import read_ini
from ccopt.toolpath import Role
from linuxcnc_data import CONFORMANCE, TOL, canonical_moves, expected_moves

#: A G21 profile: a 20 mm square cut right of the path with tool 1's radius.
SQUARE = """G21 G17 G90 G94
G0 X-10 Y0
G42 D1 G1 X0 Y0 F600
G1 X0 Y20
G1 X20 Y20
G1 X20 Y0
G1 X0 Y0
G40 G1 X-10 Y0
M2
"""


def _machine(tmp_path, ini: str, table: str = "T1 P1 D0.25\n"):
    (tmp_path / "cfg").mkdir()
    (tmp_path / "cfg" / "tools.tbl").write_text(table)
    (tmp_path / "cfg" / "machine.ini").write_text(ini)
    (tmp_path / "part.ngc").write_text(SQUARE)
    return tmp_path / "part.ngc", tmp_path / "cfg" / "machine.ini"


def test_iniparam_reads_the_values_and_stops_where_linuxcnc_stops():
    """LinuxCNC's iniparam: `G53 G0 X#<_ini[vars]toolchange_x> ...` goes to
    [VARS] TOOLCHANGE_X/Y/Z = 10, 20, 30 (any case in the name), and line 7
    reads an entry the file does not have: LinuxCNC stops there ("Named
    parameter #<_ini[nosuchsection]nosuchname> not defined")."""
    d = CONFORMANCE / "ini" / "iniparam"
    want = expected_moves("ini/iniparam")
    assert want == [("STRAIGHT_TRAVERSE", [10.0, 20.0, 30.0, 0.0, 0.0, 0.0])]
    with pytest.raises(ProgramError) as err:
        read_program(d / "test.ngc", ini=d / "test.ini")
    assert (err.value.line, err.value.col) == (7, 10)
    assert "#<_ini[nosuchsection]nosuchname> not defined" in str(err.value)
    # the program up to there: LinuxCNC's one move
    text = (d / "test.ngc").read_text().split("; now fail")[0]
    cut = d.parent / "iniparam-head.ngc"
    try:
        cut.write_text(text)
        got = canonical_moves(compensate(read_program(cut, ini=d / "test.ini"), style="linuxcnc"))
    finally:
        cut.unlink()
    assert [k for k, _ in got] == ["STRAIGHT_TRAVERSE"]
    assert got[0][1][:3] == pytest.approx(want[0][1][:3], abs=TOL)


def test_without_the_ini_file_the_value_is_an_error_that_says_so():
    d = CONFORMANCE / "ini" / "iniparam"
    with pytest.raises(ProgramError, match=r"none was given \(--ini FILE\)") as err:
        read_program(d / "test.ngc")
    assert (err.value.line, err.value.col) == (1, 9)


@pytest.mark.parametrize("units, radius", [("", 0.25 * 25.4 / 2),           # rs274: inches
                                           ("[TRAJ]\nLINEAR_UNITS = mm\n", 0.25 / 2),
                                           ("[TRAJ]\nLINEAR_UNITS = inch\n", 0.25 * 25.4 / 2)])
def test_the_tool_table_and_its_units_come_from_the_ini_file(tmp_path, units, radius):
    """[EMCIO] TOOL_TABLE, relative to the INI file's folder, in the units of
    [TRAJ] LINEAR_UNITS (inches without it, as LinuxCNC's rs274): T1 D0.25 is
    a 6.35 mm cutter in a G21 program unless the machine is metric."""
    part, ini = _machine(tmp_path, "[EMCIO]\nTOOL_TABLE = tools.tbl\n" + units)
    path = compensate(read_program(part, ini=ini), style="linuxcnc")
    assert path.radius == pytest.approx(radius, rel=1e-12)
    # clockwise round the square with the tool on the right: inside, `radius` from each edge
    up, top = [s.geom.bbox() for s in path.segments if s.role is Role.COMPENSATED][:2]
    assert up[0] == up[2] == pytest.approx(radius)                 # x = r going +Y
    assert top[1] == top[3] == pytest.approx(20.0 - radius)        # y = 20 - r going +X


def test_options_given_come_before_the_ini_file(tmp_path):
    part, ini = _machine(tmp_path, "[EMCIO]\nTOOL_TABLE = tools.tbl\n[TRAJ]\nLINEAR_UNITS = mm\n")
    other = tmp_path / "other.tbl"
    other.write_text("T1 P1 D2\n")
    prog = read_program(part, ini=ini, tool_table=other, table_units="mm")
    assert compensate(prog, style="linuxcnc").radius == pytest.approx(1.0)


def test_subroutine_path_and_parameter_file(tmp_path):
    """SUBROUTINE_PATH's folders (``:``-separated, relative to the INI file)
    are searched for o<name> call; PARAMETER_FILE's G54 origin is in force."""
    cfg = tmp_path / "cfg"
    (cfg / "subs").mkdir(parents=True)
    (cfg / "subs" / "hop.ngc").write_text("o<hop> sub\nG0 X#1 Y0\no<hop> endsub\nM2\n")
    (cfg / "m.var").write_text("5221\t5.000000\n5222\t7.000000\n5220\t1.000000\n")
    (cfg / "m.ini").write_text("[RS274NGC]\nSUBROUTINE_PATH = nothing-here:subs\n"
                               "PARAMETER_FILE = m.var\n[TRAJ]\nLINEAR_UNITS = mm\n")
    part = tmp_path / "p.ngc"
    part.write_text("G21 G90\no<hop> call [3]\nM2\n")
    prog = read_program(part, ini=cfg / "m.ini")
    assert prog.blocks[-1].end[:2] == pytest.approx((3.0 + 5.0, 7.0))


@pytest.mark.parametrize("setting, x", [("", 2.0 + 1.5), ("DISABLE_G92_PERSISTENCE = 0\n", 3.5),
                                         ("DISABLE_G92_PERSISTENCE = yes\n", 1.5)])
def test_the_g92_offset_of_the_parameter_file_unless_persistence_is_disabled(tmp_path, setting,
                                                                             x):
    """LinuxCNC's init restores the G92 offset #5211.. when #5210 is non-zero
    (2 counts, as in its g92-offset-persistence test) unless the INI says
    DISABLE_G92_PERSISTENCE: the work X0 is then at machine X = G54's 1.5."""
    cfg = tmp_path / "cfg"
    cfg.mkdir()
    (cfg / "m.var").write_text("5210\t2.0\n5211\t2.0\n5221\t1.5\n5220\t1.0\n")
    (cfg / "m.ini").write_text(f"[RS274NGC]\nPARAMETER_FILE = m.var\n{setting}"
                               "[TRAJ]\nLINEAR_UNITS = mm\n")
    part = tmp_path / "p.ngc"
    part.write_text("G21 G90\nG0 X0 Y0\n(print,#5210 #5211)\nM2\n")
    prog = read_program(part, ini=cfg / "m.ini")
    assert prog.blocks[-1].end[0] == pytest.approx(x)
    on = x > 2.0
    assert prog.meta["messages"][0]["text"] == ("2.000000 2.000000" if on
                                                else "0.000000 0.000000")


def test_fanuc_style_subprograms_disabled_by_the_ini_file(tmp_path):
    """[RS274NGC] DISABLE_FANUC_STYLE_SUB: M98 (and a subprogram's M99) refused
    where they are met, with LinuxCNC's message (interp_read.cc read_o_word);
    the main program's M99 is read_m's and stays allowed."""
    part, ini = _machine(tmp_path, "[RS274NGC]\nDISABLE_FANUC_STYLE_SUB = 1\n")
    part.write_text("G21\nG0 X1\nM98 P1 L2\nM30\nO1\nG91 G0 X1\nM99\n")
    with pytest.raises(ProgramError, match="DISABLE_FANUC_STYLE_SUB set in INI file, but "
                                           "found m98") as err:
        read_program(part, ini=ini)
    assert (err.value.line, err.value.col) == (3, 1)
    part.write_text("G21\nG0 X1\nG0 X2 M99\n")
    assert read_program(part, ini=ini).blocks[-1].end[0] == pytest.approx(2.0)
    ini.write_text("[RS274NGC]\nDISABLE_FANUC_STYLE_SUB = 0\n")
    part.write_text("G21\nG0 X1\nM98 P1 L2\nM30\nO1\nG91 G0 X1\nM99\n")
    assert read_program(part, ini=ini).blocks[-1].end[0] == pytest.approx(3.0)
    ini.write_text("[RS274NGC]\nDISABLE_FANUC_STYLE_SUB = maybe\n")
    with pytest.raises(ProgramError, match="DISABLE_FANUC_STYLE_SUB = maybe: a yes/no"):
        read_program(part, ini=ini)


@pytest.mark.parametrize("text, line, message", [
    ("[RS274NGC]\nthis line has no equals sign\n", 2, "not a [SECTION]"),
    ("NAME = 1\n", 1, "before any [SECTION]"),
    ("[TRAJ]\nLINEAR_UNITS = furlong\n", 2, "LINEAR_UNITS = furlong"),
])
def test_a_bad_ini_file_is_a_located_error(tmp_path, capsys, text, line, message):
    part, ini = _machine(tmp_path, text)
    code = main(["show", str(part), "--ini", str(ini)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith(f"{ini}:{line}:") and message in err and "Traceback" not in err


def test_ini_vars_off_and_a_value_that_is_not_a_number(tmp_path):
    part, ini = _machine(tmp_path, "[RS274NGC]\nINI_VARS = 0\n[VARS]\nX = 1\n")
    part.write_text("G21\nG0 X#<_ini[vars]x>\nM2\n")
    with pytest.raises(ProgramError, match="INI_VARS = 0"):
        read_program(part, ini=ini)
    ini.write_text("[VARS]\nX = left\n")
    with pytest.raises(ProgramError, match=r"\[VARS\] X = left .* is not a number"):
        read_program(part, ini=ini)
    ini.write_text("[VARS]\nX = 4\nX = 9\n")          # the first counts, as LinuxCNC's
    assert read_program(part, ini=ini).blocks[-1].end[0] == pytest.approx(4.0)


def test_an_ini_file_is_for_g_code_only(tmp_path):
    part, ini = _machine(tmp_path, "[TRAJ]\nLINEAR_UNITS = mm\n")
    pmc = tmp_path / "p.pmc"
    pmc.write_text("OPEN PROG 1 CLEAR\nLINEAR F10 X1\nCLOSE\n")
    with pytest.raises(ProgramError, match="G-code programs only"):
        read_program(pmc, ini=ini)


def test_an_ini_entry_is_read_only():
    """LinuxCNC's iniparam-failassign: `#<_ini[vars]toolchange_x> = 3.1415` is an
    error at its line ("Cannot assign to read-only parameter")."""
    d = CONFORMANCE / "ini" / "iniparam-failassign"
    assert "Cannot assign to read-only parameter #<_ini[vars]toolchange_x>" in \
        (d / "expected").read_text()
    with pytest.raises(ProgramError, match=r"read-only parameter #<_ini\[vars\]toolchange_x>") \
            as err:
        read_program(d / "test.ngc", ini=d / "test.ini")
    assert (err.value.line, err.value.col) == (1, 1)


def test_an_abort_comment_stops_the_program_with_its_message():
    """LinuxCNC's abort-hot-comment: `(abort, ... #42 ... #<named> ...
    #<_ini[a]value>)` inside a loop stops the program when #42 is 20, with
    the parameters' values in the message as LinuxCNC prints them (%f)."""
    d = CONFORMANCE / "ini" / "abort-hot-comment"
    message = "MixedCase param42=20.000000 named=4711.000000 INI=3.140000"
    assert message in (d / "expected").read_text()
    with pytest.raises(ProgramError) as err:
        read_program(d / "test.ngc", ini=d / "test.ini")
    assert message in str(err.value) and (err.value.line, err.value.col) == (5, 6)


@pytest.mark.parametrize("ini", ["axis.ini", "axis_mm.ini"])
def test_a_shipped_example_with_the_sim_config_it_is_written_for(ini):
    """LinuxCNC's nc_files/comp.ngc (G20, `g42 d1`) with the axis simulator's
    INI: tool 1 is sim.tbl's D0.125 on the inch machine ([TRAJ] LINEAR_UNITS
    = inch), sim_mm.tbl's D3 (mm) on the mm one: radius 0.0625 in, or
    3 / 25.4 / 2 in, in this inch program."""
    d = CONFORMANCE / "nc_files"
    inch = ini == "axis.ini"
    table = (d / "sim" / ("sim.tbl" if inch else "sim_mm.tbl")).read_text()
    assert ("T1 P1 Z0.511 D0.125" if inch else "T1 P1 Z0.511 D3 ") in table
    path = compensate(read_program(d / "comp.ngc", ini=d / "sim" / ini), style="linuxcnc")
    assert path.radius == pytest.approx(0.0625 if inch else 3.0 / 25.4 / 2, rel=1e-12)
    assert {s.plane for s in path.segments} == {"XY", "ZX"}


# -- by generation ---------------------------------------------------------------------

_NAMES = st.text("ABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789abcxyz", min_size=1, max_size=8).filter(
    lambda n: n.strip() == n and "=" not in n and not n.startswith(("#", ";", "[")))
_VALUES = st.one_of(st.floats(-1e6, 1e6, allow_nan=False).map(repr),
                    st.text("abc xyz/.-_", max_size=10).map(str.strip))


@st.composite
def _ini_files(draw):
    """INI text with its entries in order: sections in any case, names in any
    case, blank and comment lines, repeated names; and the model of what
    LinuxCNC finds (upper-case keys, the first of equal names)."""
    lines, model = [], {}
    for _ in range(draw(st.integers(1, 4))):
        section = draw(_NAMES)
        lines.append(f"[{draw(st.sampled_from(['', ' ']))}{section}]")
        for _ in range(draw(st.integers(0, 5))):
            if draw(st.booleans()):
                lines.append(draw(st.sampled_from(["", "# a comment", "; another", "   "])))
            name, value = draw(_NAMES), draw(_VALUES)
            lines.append(f"{name}{draw(st.sampled_from(['=', ' = ', '  =  ']))}{value}")
            model.setdefault((section.upper(), name.upper()), value)
    return "\n".join(lines) + "\n", model


@settings(max_examples=300, deadline=None, derandomize=True)
@given(_ini_files())
def test_read_ini_finds_what_linuxcnc_finds_over_generated_files(tmp_path_factory, case):
    text, model = case
    path = tmp_path_factory.mktemp("ini") / "m.ini"
    path.write_text(text)
    ini = read_ini(path)
    assert ini.values == model
    for (section, name), value in model.items():
        # any case reads it, as the G-code reader lowercases #<_ini[...]...> names
        assert ini.get(section.lower(), name.lower()) == value
        try:
            number = float(value)
        except ValueError:
            with pytest.raises(ValueError, match="is not a number"):
                ini.number(section, name)
        else:
            assert ini.number(section, name) == number


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.lists(st.text(st.characters(blacklist_categories=("Cs",)), max_size=30), max_size=8))
def test_any_text_reads_or_is_a_located_error(tmp_path_factory, lines):
    """Whatever the file holds: its entries, or an error at one of its lines."""
    path = tmp_path_factory.mktemp("ini") / "x.ini"
    path.write_text("\n".join(lines), encoding="utf-8", errors="replace")
    try:
        read_ini(path)
    except ProgramError as exc:
        assert exc.file == str(path)
        assert 1 <= exc.line <= max(1, len(path.read_text(errors="replace").splitlines()))
