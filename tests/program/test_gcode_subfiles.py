"""Subroutine files (LinuxCNC's SUBROUTINE_PATH): ``o<name> call`` of a sub the
program does not define reads ``name.ngc`` from the sub path's folders, in
order, and from nowhere else; a name holding a path is refused."""
from __future__ import annotations

import json

import pytest

from ccopt.cli import main
from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode

SQUARE = "o<square> sub\n  G1 X#1\n  G1 Y#1\no<square> endsub\nM2\n"


@pytest.fixture
def folders(tmp_path):
    first, second = tmp_path / "first", tmp_path / "second"
    first.mkdir()
    second.mkdir()
    (second / "square.ngc").write_text(SQUARE)
    (second / "broken.ngc").write_text("o<broken> sub\n  G1 X[1/0]\no<broken> endsub\n")
    (second / "other.ngc").write_text("o<not-other> sub\no<not-other> endsub\n")
    return first, second


def test_sub_from_the_path_runs_with_its_arguments(folders):
    prog = read_gcode("G21 F600\no<square> call [5]\nG1 X0\no<square> call [2]\n", "main.ngc",
                      sub_path=folders)
    assert [b.end[:2] for b in prog.blocks] == [(5, 0), (5, 5), (0, 5), (2, 5), (2, 2)]
    # each move is located in the file that holds it
    square = str(folders[1] / "square.ngc")
    assert [(b.source.file, b.source.line) for b in prog.blocks] == [
        (square, 2), (square, 3), ("main.ngc", 3), (square, 2), (square, 3)]


def test_the_first_folder_that_has_the_file_wins(folders):
    (folders[0] / "square.ngc").write_text("o<square> sub\n  G1 Y#1\no<square> endsub\n")
    prog = read_gcode("G21 F600\no<square> call [3]\n", sub_path=folders)
    assert [b.end[:2] for b in prog.blocks] == [(0, 3)]


def test_a_sub_defined_in_the_program_wins_over_the_path(folders):
    text = "G21 F600\no<square> call [1]\nM2\no<square> sub\n  G1 Y7\no<square> endsub\n"
    assert [b.end[:2] for b in read_gcode(text, sub_path=folders).blocks] == [(0, 7)]


@pytest.mark.parametrize("call, sub_path, where, message", [
    ("o<broken> call", True, "broken.ngc:2:", "division by zero"),
    ("o<other> call", True, "main.ngc:2:", "does not define o<other> sub"),
    ("o<nope> call", True, "main.ngc:2:", "no nope.ngc in the sub path"),
    ("o<nope> call", False, "main.ngc:2:", "--sub-path"),
    ("o<../second/square> call", True, "main.ngc:2:", "cannot hold a path"),
])
def test_located_errors(folders, call, sub_path, where, message):
    with pytest.raises(ProgramError) as err:
        read_gcode(f"G21 F600\n{call}\n", "main.ngc", sub_path=folders if sub_path else ())
    assert where in str(err.value) and message in str(err.value)


def test_sub_path_on_the_command_line(folders, tmp_path, capsys):
    program = tmp_path / "main.ngc"
    program.write_text("G21 F600\no<square> call [4]\n")
    path = f"{folders[0]}:{folders[1]}"
    assert main(["show", str(program), "--sub-path", path, "--json"]) == 0
    assert [s["end"] for s in json.loads(capsys.readouterr().out)["segments"]] == [[4, 0], [4, 4]]
    assert main(["show", str(program)]) == 2
    assert "--sub-path" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exit_:
        main(["show", str(program), "--sub-path", str(tmp_path / "missing")])
    assert exit_.value.code == 2


def test_a_sub_file_is_read_no_further_than_its_subs_endsub(tmp_path):
    """LinuxCNC's nested-sub-in-file-error: sequential.ngc defines o<sequential>,
    which calls o200, written after o<sequential> endsub in the same file.
    LinuxCNC reads the file no further than that endsub, so o200 is not
    defined and the call is an error (its expected output stops there)."""
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "sequential.ngc").write_text(
        "o<sequential> sub\n(DEBUG, main: #1)\no200 call [4]\no<sequential> endsub\n\n"
        "o200 sub\n(DEBUG, helper: #1)\no200 endsub\nM2\n")
    with pytest.raises(ProgramError, match="o200") as err:
        read_gcode("o<sequential> call [7]\nM2\n", "main.ngc", sub_path=[subs])
    assert err.value.file.endswith("sequential.ngc") and err.value.line == 3
    # o200 defined in the program the file's sub is called from is found
    (subs / "sequential.ngc").write_text(
        "o<sequential> sub\no200 call [4]\no<sequential> endsub\nM2\n")
    inline = ("o200 sub\nG0 X#1\no200 endsub\no<sequential> call [7]\nM2\n")
    assert read_gcode(inline, "main.ngc", sub_path=[subs]).blocks[-1].end[0] == 4.0
