"""Never lose the user's files; bounded and located (issue 29, items 5 and 6).

* No command writes over an input: an output that *is* an input program (the
  same path, ``./p.pmc``, ``sub/../p.pmc``, an absolute path, a symlink, a
  hard link, a path through a symlinked folder) is exit 2 with one line
  ``OUTPUT: not written: ...`` and nothing written at all; ``ccopt run p.pmc
  -o DIR`` with DIR holding ``p.pmc`` refuses before its first file. A
  generated sweep: every writing command x every output form x both dialects.
* The arc of 2^31 turns, the line to a far-away coordinate and an empty
  program, through every command, in a fresh process each: a located exit 2
  (``file:line:col: message``) or, for the empty program, "nothing to ..." and
  exit 0, in at most 200 MB (measured by ``os.wait4`` on that process alone).
  No wall-clock time is asserted here (bench/ measures time).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import ccopt
from ccopt.errors import ProgramError
from ccopt.program import read_program

from cli_run import run_cli

ROOT = Path(__file__).resolve().parents[1]
PMAC = (ROOT / "cases" / "leadin-inside-line" / "part.pmc").read_text()
GCODE = ("G21 G17 G90\nG0 X0 Y-20\nG1 F1200\nG41.1 D4\nG1 X0 Y0\nG1 X-20 Y0\nG1 X-20 Y20\n"
         "G40\nG1 X-40 Y20\nM2\n")
PROGRAMS = {"pmac": ("p.pmc", PMAC), "gcode": ("p.nc", GCODE)}

#: the message every refusal carries
REFUSED = "ccopt never writes over its inputs"


def tree(folder: Path) -> dict[str, tuple]:
    """Every entry under ``folder`` with what would show a write: kind, inode,
    size, modification time and (for files) the bytes."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in dirnames + filenames:
            p = Path(dirpath) / name
            st = os.lstat(p)
            data = p.read_bytes() if p.is_file() and not p.is_symlink() else None
            out[str(p.relative_to(folder))] = (st.st_mode, st.st_ino, st.st_size,
                                               st.st_mtime_ns, data)
    return out


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """``tmp_path`` as the working folder, holding both programs, a subfolder,
    a symlink and a hard link to each program and a symlink to the folder."""
    for name, text in PROGRAMS.values():
        (tmp_path / name).write_text(text)
        os.symlink(name, tmp_path / f"link-{name}")
        os.link(tmp_path / name, tmp_path / f"hard-{name}")
    (tmp_path / "sub").mkdir()
    os.symlink(tmp_path, tmp_path / "sub" / "up")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def output_forms(name: str, root: Path) -> dict[str, str]:
    """Ways to name the input file ``name`` (in ``root``) as an output."""
    return {"same": name, "dot": f"./{name}", "dotdot": f"sub/../{name}",
            "absolute": str(root / name), "symlink": f"link-{name}", "hardlink": f"hard-{name}",
            "via-folder-link": f"sub/up/{name}"}


FORMS = ("same", "dot", "dotdot", "absolute", "symlink", "hardlink", "via-folder-link")

#: the commands that write one file with -o, as argv before the output
FILE_COMMANDS = {
    "export": ["export", "{p}"],
    "feed": ["feed", "{p}"],
    "feed-two-planners": ["feed", "{p}", "--planner", "toppra,stop"],
    "compare": ["compare", "{p}", "--workers", "1"],
    "smooth": ["smooth", "{p}"],
}


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize("command", sorted(FILE_COMMANDS))
def test_no_command_writes_over_its_program(capsys, workdir, command, form, dialect):
    name, _ = PROGRAMS[dialect]
    out = output_forms(name, workdir)[form]
    argv = [a.format(p=name) for a in FILE_COMMANDS[command]] + ["-o", out]
    before = tree(workdir)
    code, _, err = run_cli(capsys, *argv)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "Traceback" not in err, (argv, err)
    assert lines[0].startswith(f"{out}: not written: the output is ") and REFUSED in lines[0]
    assert tree(workdir) == before, argv          # nothing written, not even a temporary file


RUN_FORMS = {"dot": ".", "dotdot": "sub/..", "absolute": "{root}", "via-folder-link": "sub/up"}


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
@pytest.mark.parametrize("form", sorted(RUN_FORMS))
def test_run_into_the_programs_folder_writes_nothing(capsys, workdir, form, dialect):
    # the reproducer: ccopt run part.pmc -o . wrote part.pmc over the program
    name, _ = PROGRAMS[dialect]
    out = RUN_FORMS[form].format(root=workdir)
    before = tree(workdir)
    code, _, err = run_cli(capsys, "run", name, "-o", out, "--workers", "1", "--no-compare")
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith(f"{Path(out) / name}: not written") and REFUSED in lines[0]
    assert tree(workdir) == before


def test_run_with_several_inputs_refuses_before_the_first_file(capsys, workdir):
    # the first input's files are harmless; the second's .pmc is that input itself
    (workdir / "a").mkdir()
    (workdir / "a" / "q.nc").write_text(GCODE)
    before = tree(workdir)
    code, _, err = run_cli(capsys, "run", "a/q.nc", "p.pmc", "-o", ".", "--workers", "1",
                           "--no-compare")
    assert code == 2 and REFUSED in err
    assert tree(workdir) == before


def test_run_does_not_replace_a_program_it_did_not_write(capsys, workdir):
    # ccopt run g.ngc -o . would write g.nc and g.pmc: the user's PMAC program
    # g.pmc beside it (not an input of this run) is left alone too
    (workdir / "g.ngc").write_text(GCODE)
    (workdir / "g.pmc").write_text(PMAC)
    before = tree(workdir)
    code, _, err = run_cli(capsys, "run", "g.ngc", "-o", "sub/up", "--workers", "1",
                           "--no-compare")
    assert code == 2 and "Traceback" not in err
    assert err.startswith("sub/up/g.pmc: not written: a file ccopt did not write is there")
    assert tree(workdir) == before


def test_run_does_not_replace_an_index_html_it_did_not_write(capsys, workdir):
    (workdir / "out").mkdir()
    (workdir / "out" / "index.html").write_text("<html><title>my site</title></html>\n")
    before = tree(workdir)
    code, _, err = run_cli(capsys, "run", "p.pmc", "-o", "out", "--workers", "1",
                           "--no-compare")
    assert code == 2 and err.startswith("out/index.html: not written: a file ccopt did not")
    assert tree(workdir) == before


def test_run_writes_over_its_own_outputs(capsys, workdir):
    for _ in range(2):
        code, _, err = run_cli(capsys, "run", "p.pmc", "-o", "out", "--workers", "1",
                               "--no-compare")
        assert code == 0, err
    assert (workdir / "p.pmc").read_text() == PMAC and (workdir / "out" / "p.pmc").is_file()


def test_export_does_not_write_over_a_tool_table(capsys, workdir):
    (workdir / "t.tbl").write_text("T1 P1 D4\n")
    (workdir / "t.ngc").write_text(GCODE.replace("G41.1 D4", "T1 M6\nG41 D1"))
    before = tree(workdir)
    code, _, err = run_cli(capsys, "export", "t.ngc", "--tool-table", "t.tbl", "-o", "t.tbl")
    assert code == 2 and err.startswith("t.tbl: not written") and REFUSED in err
    assert tree(workdir) == before


def test_sweep_into_the_specs_folder_writes_nothing(capsys, workdir):
    # the sweep copies its spec into DIR as spec.toml: over the spec itself here
    (workdir / "spec.toml").write_text('programs = ["p.pmc"]\n')
    before = tree(workdir)
    code, _, err = run_cli(capsys, "sweep", "spec.toml", "-o", ".")
    assert code == 2 and err.startswith("spec.toml: not written") and REFUSED in err
    assert tree(workdir) == before


def test_a_derived_output_name_is_guarded_too(capsys, workdir):
    # feed with two planners writes FILE.<planner>.csv: the name -o gives is not
    # the file written, so the writer itself refuses (ccopt.atomic's backstop)
    os.symlink("p.pmc", workdir / "x.toppra.csv")
    before = tree(workdir)
    code, _, err = run_cli(capsys, "feed", "p.pmc", "--planner", "toppra,stop", "-o", "x.csv")
    assert code == 2 and err.startswith("x.toppra.csv: not written: the output is a link to "
                                        "the input p.pmc") and REFUSED in err
    assert tree(workdir) == before


def test_writing_beside_the_program_still_works(capsys, workdir):
    code, out, err = run_cli(capsys, "export", "p.pmc", "-o", "p.nc")
    assert code == 0 and "verified OK" in out, err
    assert (workdir / "p.pmc").read_text() == PMAC and (workdir / "p.nc").is_file()
    # and once more over its own output (not an input)
    code, _, err = run_cli(capsys, "export", "p.pmc", "-o", "p.nc")
    assert code == 0, err


@pytest.mark.parametrize("form", FORMS)
def test_api_export_refuses_the_programs_own_file(workdir, form):
    prog = read_program("p.pmc")
    path = ccopt.compensate(prog)
    before = tree(workdir)
    out = output_forms("p.pmc", workdir)[form]
    with pytest.raises(ProgramError) as exc:
        ccopt.export(path, out, program=prog)
    assert str(exc.value).startswith(f"{out}: not written") and REFUSED in str(exc.value)
    assert tree(workdir) == before


def test_api_may_export_again_over_a_file_it_read(workdir):
    # outside a command only the program's own files are guarded: a session
    # may read back what it exported and export it again
    prog = read_program("p.pmc")
    path = ccopt.compensate(prog)
    assert ccopt.export(path, "out.pmc", program=prog).verified
    read_program("out.pmc")
    assert ccopt.export(path, "out.pmc", program=prog).verified


# -- bounded and located, in a fresh process per command ---------------------------------
#: the fuzzing finds of issue 29, with where their message must point
# (an empty program has no place: "nothing to ..." and exit 0)
BAD = {
    "turns.ngc": ("G21 G17 G90\nG0 X0 Y0\nG1 X10 Y0 F100\nG2 X10 Y0 I-10 J0 P2147483647\nM2\n",
                  (4, 19), "at most 100 turns"),
    "far.ngc": ("G21 G17 G90\nG0 X0 Y0\nG1 X1000000000 Y0 F100\nM2\n", (3, 4), "out of range"),
    "far.pmc": ("LINEAR ABS F10\nX0 Y0\nX1000000000 Y0\n", (3, 1), "out of range"),
    "empty.ngc": ("", None, "nothing to"),
    "empty.pmc": ("", None, "nothing to"),
    "no-moves.ngc": ("G21 G90\nG4 P1\nM2\n", None, "nothing to"),
}

#: every command that reads a program, with the options that make it do everything
COMMANDS = {
    "show": ["show"],
    "verify": ["verify"],
    "verify --feed": ["verify", "--feed"],
    "feed": ["feed", "--planner", "all"],
    "export": ["export", "-o", "{out}/x.nc"],
    "compare": ["compare", "--workers", "1"],
    "run": ["run", "-o", "{out}/run", "--workers", "1"],
}

#: at most this much memory for any of them (bytes)
MEMORY_CAP = 200e6

#: measures one ccopt command in its own process: exit code, peak memory (its own
#: rusage from os.wait4, not every child this test process ever had), stderr, stdout
MEASURE = """\
import os, subprocess, sys, tempfile
with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
    p = subprocess.Popen([sys.executable, "-m", "ccopt.cli", *sys.argv[1:]], stdout=out,
                         stderr=err)
    _, status, usage = os.wait4(p.pid, 0)
    out.seek(0); err.seek(0)
    sys.stdout.write(repr((os.waitstatus_to_exitcode(status), usage.ru_maxrss * 1024,
                           err.read().decode(), out.read().decode())))
"""


def measured(argv: list[str], cwd: Path) -> tuple[int, float, str, str]:
    res = subprocess.run([sys.executable, "-c", MEASURE, *argv], cwd=cwd, capture_output=True,
                         text=True, check=True)
    return eval(res.stdout)  # noqa: S307 - our own repr of a tuple of an int, a float and text


#: the issue's three in the quick tier, the others in the slow one
QUICK = ("turns.ngc", "far.ngc", "empty.ngc")


@pytest.mark.parametrize("command", list(COMMANDS))
@pytest.mark.parametrize("name", [n if n in QUICK else pytest.param(n, marks=pytest.mark.slow)
                                  for n in BAD])
def test_bad_programs_are_located_and_bounded(tmp_path, name, command):
    text, where, says = BAD[name]
    prog = tmp_path / name
    prog.write_text(text)
    argv = [a.format(out=tmp_path) for a in COMMANDS[command]]
    argv.insert(1, str(prog))
    code, peak, err, out = measured(argv, tmp_path)
    assert "Traceback" not in err and "internal error" not in err, err
    assert peak <= MEMORY_CAP, f"{command} {name}: {peak / 1e6:.0f} MB"
    if where is None:
        if command == "show":          # nothing to say but that
            assert code == 0 and "programmed path 0.0000 mm" in out
        elif command == "export":      # the written file's line says it
            assert code == 0 and "nothing to verify: the program has no moves" in out
        elif command == "feed":        # says so, and plans what there is: a dwell's time
            assert code == 0 and f"{prog}: nothing to verify" in out and "toppra" in out
        else:
            assert code == 0 and f"{prog}: {says}" in out + err, (out, err)
        return
    line, col = where
    located = [ln for ln in err.splitlines() if ln.startswith(f"{prog}:{line}:{col}: ")]
    assert code == 2 and located and says in located[0], err


def test_the_arc_fit_limit_is_located(capsys, tmp_path, monkeypatch):
    # a spiral the G-code export fits with ~2000 arcs, against a limit lowered to
    # 64 (the real one, 65536, is the same code): exit 2 at the spiral's line,
    # nothing written (it was a ValueError, exit 3)
    from ccopt.export import arcfit
    monkeypatch.setattr(arcfit.fit_arcs, "__defaults__", (64,))
    prog = tmp_path / "spiral.pmc"
    prog.write_text("LINEAR ABS F10\nX1 Y0\nCIRCLE1 X-900000 Y0 I-1 J0\n")
    code, _, err = run_cli(capsys, "export", str(prog), "-o", str(tmp_path / "spiral.nc"))
    assert code == 2 and err.startswith(f"{prog}:3:9: cannot fit the spiral within "), err
    assert not (tmp_path / "spiral.nc").exists()


def test_the_feed_sampling_limit_names_the_line(capsys, tmp_path):
    # 100 m at F100 (1.67 mm/s): 60000 s, 6e7 samples at 1 ms, past the 2e7
    # the samples may take; the message names the line that takes the time
    prog = tmp_path / "long.ngc"
    prog.write_text("G21 G17 G90\nG0 X0 Y0\nG1 X1 Y0 F6000\nG1 X100000 Y0 F100\nM2\n")
    code, _, err = run_cli(capsys, "feed", str(prog))
    assert code == 2 and "Traceback" not in err
    assert err.startswith(f"{prog}:4:1: sampling 59999") and "(line 4 alone takes 5999" in err


def test_api_export_refuses_the_paths_own_program_without_program(workdir):
    # no program= given: the tool path's moves still say which file they came from
    path = ccopt.compensate(read_program("p.pmc"))
    before = tree(workdir)
    with pytest.raises(ProgramError, match="not written: the output is a link to the input"):
        ccopt.export(path, "link-p.pmc")
    assert tree(workdir) == before


def test_a_subroutine_file_is_an_input_too(capsys, workdir):
    # known only once the program is read: export refuses it before writing
    (workdir / "side.ngc").write_text("o<side> sub\nG1 X-20 Y0\nG1 X-20 Y20\no<side> endsub\n")
    (workdir / "main.ngc").write_text("G21 G17 G90\nG0 X0 Y-20\nG1 F1200\nG41.1 D4\nG1 X0 Y0\n"
                                      "o<side> call\nG40\nG1 X-40 Y20\nM2\n")
    before = tree(workdir)
    code, _, err = run_cli(capsys, "export", "main.ngc", "--sub-path", ".", "-o", "side.ngc")
    assert code == 2 and err.startswith("side.ngc: not written: the output is the input")
    assert tree(workdir) == before


def test_inputs_are_guarded_only_within_a_command(workdir):
    from ccopt import atomic
    from ccopt.cases import ReadOptions
    with atomic.inputs_guarded():
        ReadOptions().read("p.pmc")         # as every command reads its program
        with pytest.raises(ProgramError, match="never writes over its inputs"):
            atomic.write_text_atomic("link-p.pmc", "x")
    # outside, the writer remembers nothing (the API's explicit checks apply):
    # here it replaces the link itself, the program stays as it was
    ReadOptions().read("p.pmc")
    atomic.write_text_atomic("link-p.pmc", "x")
    assert not (workdir / "link-p.pmc").is_symlink() and (workdir / "p.pmc").read_text() == PMAC


def test_run_gives_inputs_that_share_a_name_their_own_files(capsys, workdir):
    # p.pmc and p.nc (and p.nc again, by another path): each output file named
    # LABEL.* once per input, none written over by another input's
    code, out, err = run_cli(capsys, "run", "p.pmc", "p.nc", "sub/up/p.nc", "-o", "out",
                             "--workers", "1", "--no-compare", "--json")
    assert code == 0, err
    rows = json.loads((workdir / "out" / "summary.json").read_text())["cases"]
    assert [(r["name"], Path(r["program"]).name) for r in rows] == [
        ("p-pmc", "p.pmc"), ("p-nc", "p.nc"), ("p-nc-2", "p.nc")]
    for r in rows:
        for name in r["files"].values():
            assert (workdir / "out" / name).is_file(), name
    # each export is its own program's tool path: the PMAC case's lead-in
    # line against the G-code program's corner moves
    def moves(label):
        text = (workdir / "out" / f"{label}.nc").read_text()
        return [line for line in text.splitlines() if line.startswith("G")]

    assert moves("p-pmc") != moves("p-nc") and moves("p-nc") == moves("p-nc-2")


def test_run_all_refuses_two_jobs_with_one_label(workdir):
    from ccopt.cases import make_job
    from ccopt.run import RunOptions, distinct_labels, run_all

    jobs = [make_job("p.pmc"), make_job("p.nc")]
    with pytest.raises(ProgramError, match="share the label 'p'"):
        run_all(jobs, workdir / "out", RunOptions(compare=False))
    assert not (workdir / "out").exists()
    assert [j.label for j in distinct_labels(jobs)] == ["p-pmc", "p-nc"]
