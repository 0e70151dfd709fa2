"""One set of names and defaults on the command line: every subcommand's
help, ``-o/--output`` where a command writes (old spellings still taken),
the style by dialect, one rule for the limits, progress only on a terminal."""
from __future__ import annotations

import fcntl
import json
import os
import pty
import re
import select
import struct
import subprocess
import sys
import termios
from pathlib import Path

import pytest

from ccopt.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
COMMANDS = sorted(build_parser()[1])
WRITERS = {"run": "DIR", "smooth": "FILE", "export": "OUT", "sweep": "DIR", "feed": "FILE.csv",
           "compare": "FILE"}


def _help(capsys, command: str) -> str:
    with pytest.raises(SystemExit) as exc:
        main([command, "--help"])
    assert exc.value.code == 0
    return capsys.readouterr().out


def test_every_command_is_listed():
    assert COMMANDS == ["compare", "compensate", "export", "feed", "run", "show", "smooth",
                        "sweep", "verify"]


@pytest.mark.parametrize("command", COMMANDS)
def test_help_has_a_paragraph_and_an_example(capsys, command):
    text = _help(capsys, command)
    # usage, blank line, the description (one paragraph), blank line, the options
    blocks = text.split("\n\n")
    description = blocks[1]
    assert not description.startswith(("positional arguments", "options")), text
    words = description.split()
    assert len(words) >= 30, description          # a paragraph, not a phrase
    assert description.rstrip().endswith("."), description
    example = text.split("example:\n", 1)[1].splitlines()
    assert example and all(line.startswith(f"  ccopt {command} ") for line in example
                           if line.strip() and not line.lstrip().startswith("#")), example


@pytest.mark.parametrize("command", sorted(WRITERS))
def test_writers_take_o_and_output_and_hide_old_spellings(capsys, command):
    text = _help(capsys, command)
    metavar = WRITERS[command]
    assert f"-o {metavar}, --output {metavar}" in text
    assert "--out " not in text and "--csv" not in text and "--plot" not in text


def test_old_spellings_still_work(capsys, tmp_path):
    parser, _ = build_parser()
    for argv, value in ((["run", "--out", "d"], "d"), (["feed", "p", "--csv", "f.csv"], "f.csv"),
                        (["compare", "p", "--plot", "x.png"], "x.png"),
                        (["smooth", "p", "--out", "s.nc"], "s.nc"),
                        (["export", "p", "--out", "e.nc"], "e.nc"),
                        (["sweep", "s.toml", "--out", "d"], "d")):
        assert parser.parse_args(argv).output == value


@pytest.mark.parametrize("text, suffix, style, why", [
    ("G21 G90 F600\nG41.1 D4\nG1 X10 Y0\nG1 X10 Y10\nG40 G1 X20 Y10\n", ".nc", "linuxcnc",
     "default for G-code"),
    # Fagor's G137 (linear corner transition) in the program: the Fagor style
    ("G21 G90 F600 G137\nG41.1 D4\nG1 X10 Y0\nG1 X10 Y10\nG40 G1 X20 Y10\n", ".nc", "fagor",
     "default for G-code with Fagor's G136-G139"),
    # in a comment it is no Fagor word
    ("G21 G90 F600 (not G137)\nG41.1 D4\nG1 X10 Y0\nG1 X10 Y10\nG40 G1 X20 Y10\n", ".nc",
     "linuxcnc", "default for G-code"),
    ("LINEAR ABS F10\nCCR2 CC1\nX10 Y0\nX10 Y10\nCC0\nX20 Y10\n", ".pmc", "pmac",
     "default for a PMAC program"),
])
def test_default_style_follows_the_dialect(capsys, tmp_path, text, suffix, style, why):
    prog = tmp_path / f"p{suffix}"
    prog.write_text(text)
    code = main(["compensate", str(prog)])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert out.splitlines()[0].startswith(f"{prog}: style {style} ({why}), cutter radius 2 ")
    code = main(["compensate", str(prog), "--json"])
    assert json.loads(capsys.readouterr().out)["style"] == style
    # --style still decides
    main(["compensate", str(prog), "--style", "pmac"])
    assert capsys.readouterr().out.startswith(f"{prog}: style pmac (--style)")


def test_a_case_style_is_said(capsys):
    main(["compensate", "fagor-g136-g138"])
    assert ": style fagor (the case's)" in capsys.readouterr().out.splitlines()[0]


def _duration(capsys, *argv) -> float:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)


def test_command_line_limits_reach_the_planner(capsys, tmp_path):
    # a 100 mm line along X at F6000 (100 mm/s) under 50 mm/s and 500 mm/s^2:
    # the trapezoid accelerates over v/a = 0.1 s twice, T = L/v + v/a = 2.1 s
    prog = tmp_path / "line.nc"
    prog.write_text("G21 G90 F6000\nG1 X100 Y0\n")
    feed = _duration(capsys, "feed", str(prog), "--vmax", "50,50", "--amax", "500,500",
                     "--json")
    assert feed["duration"] == pytest.approx(2.1, rel=2e-3)
    assert feed["limits_from"] == "command line"


@pytest.mark.slow
def test_feed_and_run_give_the_same_cycle_time(capsys, tmp_path):
    # a program with its limits on the command line: a lead-in, a corner arc, a line
    prog = tmp_path / "lead.nc"
    prog.write_text("G21 G90 F6000\nG0 X0 Y-10\nG41.1 D4\nG1 X0 Y0\nG1 X100 Y0\n")
    limits = ["--vmax", "50,50", "--amax", "500,500"]
    feed = _duration(capsys, "feed", str(prog), *limits, "--json")
    run = _duration(capsys, "run", str(prog), *limits, "--no-compare", "-o",
                    str(tmp_path / "o"), "--json")["cases"][0]
    assert run["duration"] == feed["duration"] and run["style"] == feed["style"] == "linuxcnc"
    # no faster than the 100 mm line alone (2.1 s, above)
    assert feed["duration"] > 2.1
    # a case: its [limits] in both
    feed = _duration(capsys, "feed", "leadin-outside-line", "--json")
    run = _duration(capsys, "run", "leadin-outside-line", "--no-compare", "-o",
                    str(tmp_path / "c"), "--json")["cases"][0]
    assert run["duration"] == feed["duration"] and feed["limits_from"] == "case"
    assert feed["limits"]["v"] == [50.0, 50.0, 20.0]
    # no limits anywhere: run takes the documented default and says so; feed
    # with those limits spelled out gives the same time
    code = main(["run", str(prog), "--no-compare", "-o", str(tmp_path / "d")])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert ("limits v=[100.0, 100.0, 100.0] a=[1000.0, 1000.0, 1000.0] (default: no [limits] "
            "in a case and no --vmax/--amax) for lead") in out
    row = json.loads((tmp_path / "d" / "summary.json").read_text())["cases"][0]
    assert row["limits_from"] == "default"
    feed = _duration(capsys, "feed", str(prog), "--vmax", "100,100", "--amax", "1000,1000",
                     "--json")
    assert row["duration"] == feed["duration"]


def test_feed_prints_where_its_limits_come_from(capsys):
    code = main(["feed", "leadin-outside-line", "--planner", "stop"])
    out = capsys.readouterr().out
    assert code == 0
    assert out.splitlines()[0].endswith(
        "limits v=[50.0, 50.0, 20.0] a=[500.0, 500.0, 200.0] (the case's [limits])")
    main(["feed", "leadin-outside-line", "--planner", "stop", "--vmax", "10,10,10"])
    assert "(--vmax/--amax over the case's [limits])" in capsys.readouterr().out


def _run_on(argv: list[str], tty: bool) -> tuple[int, str, str]:
    """``ccopt argv`` in a process whose stdout and stderr are a terminal (a
    pseudo-terminal) or pipes: exit code, stdout, stderr."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), COLUMNS="120")
    cmd = [sys.executable, "-m", "ccopt.cli", *argv]
    if not tty:
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
        return p.returncode, p.stdout, p.stderr
    out_master, out_slave = pty.openpty()
    err_master, err_slave = pty.openpty()
    for fd in (out_slave, err_slave):   # a terminal 120 columns wide (a new one has 0)
        fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
    p = subprocess.Popen(cmd, stdout=out_slave, stderr=err_slave, env=env)
    os.close(out_slave)
    os.close(err_slave)
    got = {out_master: b"", err_master: b""}
    while got:
        ready, _, _ = select.select(list(got), [], [], 300)
        if not ready:
            break
        for fd in ready:
            try:
                chunk = os.read(fd, 65536)
            except OSError:         # the other side closed (EIO on Linux)
                chunk = b""
            if chunk:
                got[fd] += chunk
            else:
                os.close(fd)
                text = got.pop(fd).decode(errors="replace")
                if fd == out_master:
                    out = text
                else:
                    err = text
    return p.wait(timeout=60), out, err


@pytest.mark.slow
def test_progress_on_a_terminal_only(tmp_path):
    argv = ["run", "leadin-outside-line", "--variants", "pmac,tangent-arc", "-o",
            str(tmp_path / "o")]
    code, out, err = _run_on(argv, tty=True)
    assert code == 0, err
    # the bar counts the cases and names the stage inside the running one
    assert "cases:" in err and "leadin-outside-line: " in err
    assert re.search(r"leadin-outside-line: (read|compensate|feed|verify|compare|export)", err)
    assert "report:" in out
    for extra, tty in (([], False), (["--json"], True), (["--quiet"], True)):
        code, out, err = _run_on(argv + extra, tty=tty)
        assert code == 0 and err == "", (extra, err)
