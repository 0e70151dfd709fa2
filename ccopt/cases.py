"""Bundled and user cases: a folder with a program and a ``case.toml``.

``case.toml`` keys (all optional except ``program``)::

    title   = "Lead-out, inside corner, line to line"
    source  = "PMAC User Manual p.189, figure 47 (a)"
    program = "leadout_line_line.pmc"   # relative to the case folder
    style   = "pmac"                    # controller style to compensate with
    radius  = 2.0                       # cutter radius override, program units
    expect  = "ok"                      # ok | gouge | error  (verification verdict)

    [limits]                            # axis limits for feed planning
    v = [100.0, 100.0]                  # units/s per axis (X, Y[, Z])
    a = [1000.0, 1000.0]                # units/s^2 per axis

A case folder is found either by path or by name among the bundled cases in
the repository's ``cases/`` folder.
"""
from __future__ import annotations

import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ccopt.errors import ProgramError

EXPECTS = ("ok", "gouge", "error")


@dataclass(frozen=True)
class Case:
    """A loaded ``case.toml`` (paths resolved, values checked)."""

    name: str
    folder: Path
    program: Path
    title: str = ""
    source: str = ""
    style: str = "pmac"
    radius: float | None = None
    expect: str = "ok"
    vmax: tuple[float, ...] | None = None
    amax: tuple[float, ...] | None = None
    extra: dict = field(default_factory=dict, compare=False)


def bundled_cases_dir() -> Path:
    """The bundled ``cases/`` folder: the repository's own in a source tree or an
    editable install, else the copy the wheel ships as ``ccopt.bundled_cases``."""
    package = Path(__file__).resolve().parent
    source_tree = package.parent / "cases"
    if source_tree.is_dir():
        return source_tree
    return package / "bundled_cases"


def bundled_cases() -> list[Case]:
    """Every bundled case, sorted by name."""
    root = bundled_cases_dir()
    if not root.is_dir():
        return []
    return [load_case(p.parent) for p in sorted(root.glob("*/case.toml"))]


def _toml_error(path: Path, exc: tomllib.TOMLDecodeError) -> ProgramError:
    m = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
    msg = re.sub(r"\s*\(at line \d+, column \d+\)", "", str(exc))
    if m:
        return ProgramError(f"invalid TOML: {msg}", str(path), int(m.group(1)), int(m.group(2)))
    return ProgramError(f"invalid TOML: {msg}", str(path))


def _key_line(text: str, key: str) -> int | None:
    for i, line in enumerate(text.splitlines(), 1):
        if re.match(rf"\s*{re.escape(key)}\s*=", line):
            return i
    return None


def load_case(folder: str | os.PathLike) -> Case:
    """Load ``folder/case.toml``; every problem is a located ProgramError."""
    folder = Path(folder)
    toml_path = folder / "case.toml"
    try:
        text = toml_path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ProgramError(f"cannot read case: {exc.strerror or exc}", str(toml_path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _toml_error(toml_path, exc) from None

    def bad(key: str, msg: str) -> ProgramError:
        return ProgramError(f"{key}: {msg}", str(toml_path), _key_line(text, key.split(".")[-1]))

    prog = data.get("program")
    if not isinstance(prog, str) or not prog:
        raise bad("program", "a program file name is required")
    program = folder / prog
    if not program.is_file():
        raise bad("program", f"no such file {program}")
    radius = data.get("radius")
    if radius is not None and (not isinstance(radius, (int, float)) or radius < 0):
        raise bad("radius", "must be a number >= 0")
    expect = data.get("expect", "ok")
    if expect not in EXPECTS:
        raise bad("expect", f"must be one of {', '.join(EXPECTS)}")
    limits = data.get("limits", {})
    vmax = amax = None
    if limits:
        for key in ("v", "a"):
            vals = limits.get(key)
            if not (isinstance(vals, list) and 2 <= len(vals) <= 3
                    and all(isinstance(x, (int, float)) and x > 0 for x in vals)):
                raise bad(f"limits.{key}", "must be a list of 2 or 3 positive numbers (X, Y[, Z])")
        vmax = tuple(float(x) for x in limits["v"])
        amax = tuple(float(x) for x in limits["a"])
    known = {"program", "title", "source", "style", "radius", "expect", "limits"}
    return Case(
        name=folder.resolve().name, folder=folder, program=program,
        title=str(data.get("title", "")), source=str(data.get("source", "")),
        style=str(data.get("style", "pmac")), radius=None if radius is None else float(radius),
        expect=expect, vmax=vmax, amax=amax,
        extra={k: v for k, v in data.items() if k not in known},
    )


def find_case(name_or_path: str) -> Case | None:
    """A case by folder path or bundled name; ``None`` when it is not a case."""
    p = Path(name_or_path)
    if (p / "case.toml").is_file():
        return load_case(p)
    bundled = bundled_cases_dir() / name_or_path
    if (bundled / "case.toml").is_file():
        return load_case(bundled)
    return None
