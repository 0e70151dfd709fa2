"""LinuxCNC tool table reader."""
from __future__ import annotations

import pytest

from ccopt.errors import ProgramError
from ccopt.program.gcode import read_gcode
from ccopt.program.tooltable import read_tool_table

TABLE = """; a LinuxCNC tool table
T1 P1 D6.0 Z+0.0 ;6 mm end mill
t2 p2 x0 z-12.5 d10 i0 j0 q0

T3 P3 Z1.5   ;no diameter
T17 P4 D-8 ; negative diameter flips the side
"""


def test_reads_text():
    assert read_tool_table(TABLE) == {1: 6.0, 2: 10.0, 3: 0.0, 17: -8.0}


def test_reads_a_file_by_path_and_by_str(tmp_path):
    path = tmp_path / "tool.tbl"
    path.write_text(TABLE)
    assert read_tool_table(path) == read_tool_table(str(path)) == read_tool_table(TABLE)


def test_missing_file_is_a_program_error(tmp_path):
    with pytest.raises(ProgramError, match="not found"):
        read_tool_table(str(tmp_path / "nope.tbl"))


def test_table_feeds_g41(tmp_path):
    table = read_tool_table(TABLE)
    b = read_gcode("G41 D2 G1 X1 F60\nT17 M6\nG42 X2\n", tool_table=table).blocks
    assert (b[0].modal.side, b[0].modal.radius, b[0].modal.tool) == (1, 5.0, 2)
    assert (b[1].modal.side, b[1].modal.radius, b[1].modal.tool) == (1, 4.0, 17)  # -8 flips G42


@pytest.mark.parametrize("text, line, col, words", [
    ("T1 P1 D6\nT1 P2 D8", 2, 1, "listed twice"),
    ("T1 P1 E6", 1, 7, "unknown word 'E6'"),
    ("T1 P1 D6.0.1", 1, 7, "D needs a number"),
    ("T1 P1 Dinf", 1, 7, "D needs a number"),
    ("T1 P1 D1e999", 1, 7, "not a finite number"),
    ("T1.5 P1 D6", 1, 1, "whole number"),
    ("T-1 P1 D6", 1, 1, "must not be negative"),
    ("\n  P1 D6", 2, 3, "without T"),
    ("T1 T2", 1, 4, "two T words"),
    ("1 1 0.0 6.0", 1, 1, "old-style"),
])
def test_bad_lines_are_located(text, line, col, words):
    with pytest.raises(ProgramError) as info:
        read_tool_table(text, file="tool.tbl")
    e = info.value
    assert words in e.message and (e.file, e.line, e.col) == ("tool.tbl", line, col), str(e)


def test_whole_words_written_with_decimals_and_every_word():
    # every word LinuxCNC's tool table has; Q0.0 and P2.0 as other tools write them
    text = "T5 P2.0 X0.1 Y0 Z-1 A0 B0 C0 U0 V0 W0 D3.0 I95.0 J155.0 Q0.0 ; all words\n"
    assert read_tool_table(text) == {5: 3.0}
    with pytest.raises(ProgramError, match="Q needs a whole number"):
        read_tool_table("T5 P2 D3 Q0.5")
