"""Files as users expect: the umask's permissions, a failing export never
over an existing file, and no temporary file that a killed run left behind
outlives the next write."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

import ccopt
from ccopt import atomic
from ccopt.cli import main
from ccopt.export import export
from ccopt.program import read_program

CASES = Path(__file__).resolve().parents[2] / "cases"
ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def umask():
    """Set a umask for one test, restored afterwards."""
    old = os.umask(0o022)
    yield os.umask
    os.umask(old)


def _path(name: str):
    prog = read_program(CASES / name / "part.pmc")
    return prog, ccopt.compensate(prog, "pmac")


@pytest.mark.parametrize("mask", [0o022, 0o077, 0o002, 0o027], ids=lambda m: f"umask{m:03o}")
def test_outputs_get_the_umask_permissions(umask, mask, tmp_path):
    umask(mask)
    want = 0o666 & ~mask          # what open(..., "w") would give
    prog, path = _path("leadin-outside-arc")
    for suffix in (".nc", ".pmc", ".svg", ".json"):
        out = tmp_path / f"part{suffix}"
        export(path, out, program=prog)
        assert out.stat().st_mode & 0o777 == want, (suffix, oct(out.stat().st_mode))
    atomic.write_text_atomic(tmp_path / "plain.txt", "x\n")
    assert (tmp_path / "plain.txt").stat().st_mode & 0o777 == want
    atomic.write_with_atomic(tmp_path / "lib.txt", lambda p: Path(p).write_text("y\n"))
    assert (tmp_path / "lib.txt").stat().st_mode & 0o777 == want
    # the same as a file the user creates with the same umask
    (tmp_path / "reference").write_text("z")
    assert (tmp_path / "reference").stat().st_mode & 0o777 == want


def test_ccopt_run_outputs_get_the_umask_permissions(umask, tmp_path, capsys):
    umask(0o027)
    out = tmp_path / "run"
    code = main(["run", "leadin-outside-arc", "-o", str(out), "--no-compare"])
    assert code == 0, capsys.readouterr().err
    files = [f for f in out.iterdir() if f.is_file()]
    assert len(files) >= 8          # nc pmc svg feed.csv certificate toolpath index summary
    assert {f.stat().st_mode & 0o777 for f in files} == {0o640}


def test_failing_export_is_not_written_over_a_good_file(tmp_path, capsys):
    good = tmp_path / "part.nc"
    # a good, verified export of another program sits at the target
    assert main(["export", "leadin-outside-arc", "-o", str(good)]) == 0
    before = good.read_bytes()
    assert b"verified against the programmed contour: OK" in before
    capsys.readouterr()
    # short-move-overcut gouges (PMAC's documented overcut): exit 1
    code = main(["export", "short-move-overcut", "-o", str(good)])
    out = capsys.readouterr().out
    assert code == 1
    assert good.read_bytes() == before                     # byte-identical
    failed = tmp_path / "part.failed.nc"
    assert failed.is_file()
    assert "verified against the programmed contour: FAILED" in failed.read_text()
    assert out.startswith(f"{failed}: gcode")
    assert "verification FAILED" in out
    assert f"written as {failed}, not over the existing {good}" in out
    # the failed file is the failing program: it reads back as short-move-overcut's path
    back = ccopt.programmed_path(read_program(failed))
    prog = read_program(CASES / "short-move-overcut" / "part.pmc")
    path = ccopt.compensate(prog, "pmac")
    assert back.segments[-1].end == pytest.approx(path.segments[-1].end, abs=1e-6)


@pytest.mark.parametrize("suffix", [".pmc", ".json"])
def test_failing_export_in_other_formats(tmp_path, suffix, capsys):
    target = tmp_path / f"part{suffix}"
    target.write_bytes(b"GOOD OLD FILE\n")
    code = main(["export", "short-move-overcut", "-o", str(target), "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 1
    assert target.read_bytes() == b"GOOD OLD FILE\n"
    assert doc["verified"] is False
    assert doc["file"] == str(tmp_path / f"part.failed{suffix}")
    assert doc["kept_existing"] == str(target)
    assert (tmp_path / f"part.failed{suffix}").stat().st_size > 0


def test_failing_export_with_no_file_there_takes_the_name(tmp_path, capsys):
    # nothing to protect: the file is written under its name, its header says FAILED
    target = tmp_path / "part.nc"
    assert main(["export", "short-move-overcut", "-o", str(target)]) == 1
    assert "verified against the programmed contour: FAILED" in target.read_text()
    assert not (tmp_path / "part.failed.nc").exists()
    assert "not over the existing" not in capsys.readouterr().out


def _dead_pid() -> int:
    """The pid of a process that has exited (and been reaped)."""
    proc = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    return int(proc.stdout)


def test_a_killed_write_leaves_a_temp_file_the_next_export_removes(tmp_path):
    target = tmp_path / "part.nc"
    target.write_text("GOOD OLD FILE\n")
    # a writer killed (SIGKILL) between writing its temporary file and renaming it
    child = ("import os, signal, sys\n"
             "from ccopt import atomic\n"
             "atomic.os.replace = lambda a, b: os.kill(os.getpid(), signal.SIGKILL)\n"
             "atomic.write_text_atomic(sys.argv[1], 'PARTIAL')\n")
    proc = subprocess.run([sys.executable, "-c", child, str(target)], cwd=ROOT)
    assert proc.returncode == -signal.SIGKILL
    left = [p for p in tmp_path.iterdir() if p.name.startswith(".part.nc.ccopt-")]
    assert len(left) == 1 and left[0].read_text() == "PARTIAL"
    assert target.read_text() == "GOOD OLD FILE\n"
    # a temp file of a live process (a concurrent writer) and of another target stay
    live = tmp_path / f".part.nc.ccopt-{os.getppid()}-0.tmp"
    other = tmp_path / f".other.nc.ccopt-{_dead_pid()}-0.tmp"
    stale = tmp_path / f".part.nc.ccopt-{_dead_pid()}-3.tmp"
    for f in (live, other, stale):
        f.write_text("x")
    prog, path = _path("leadin-outside-arc")
    export(path, target, program=prog)
    assert "read back with ccopt" in target.read_text()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted([target.name, live.name, other.name])


def test_temp_names_carry_the_pid(tmp_path, monkeypatch):
    seen = []
    real = atomic.os.replace

    def spy(a, b):
        seen.append(Path(a).name)
        real(a, b)

    monkeypatch.setattr(atomic.os, "replace", spy)
    atomic.write_text_atomic(tmp_path / "x.csv", "1\n")
    assert len(seen) == 1
    assert seen[0].startswith(f".x.csv.ccopt-{os.getpid()}-") and seen[0].endswith(".tmp")
