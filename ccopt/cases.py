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
    j = [20000.0, 20000.0]              # optional: units/s^3 per axis (jerk)

A case folder is found either by path or by name among the bundled cases in
the repository's ``cases/`` folder.

:func:`resolve_input` is the one place where an input (program file, case
folder or bundled case name) gets its settings: what the command line says
(:class:`Overrides`), else what its ``case.toml`` says, else the defaults. It
returns a :class:`Job`, which every command and :mod:`ccopt.run` work from.
"""
from __future__ import annotations

import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.feed import AxisLimits
from ccopt.program import read_program
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath

EXPECTS = ("ok", "gouge", "error")

#: The controller style of a program that is not a case and gets none on the
#: command line: the reference.
DEFAULT_STYLE = "pmac"


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
    jmax: tuple[float, ...] | None = None
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
    vmax = amax = jmax = None
    if limits:
        for key in ("v", "a"):
            vals = limits.get(key)
            if not (isinstance(vals, list) and 2 <= len(vals) <= 3
                    and all(isinstance(x, (int, float)) and x > 0 for x in vals)):
                raise bad(f"limits.{key}", "must be a list of 2 or 3 positive numbers (X, Y[, Z])")
        vmax = tuple(float(x) for x in limits["v"])
        amax = tuple(float(x) for x in limits["a"])
        jmax = _case_jerk(limits, bad)
    known = {"program", "title", "source", "style", "radius", "expect", "limits"}
    return Case(
        name=folder.resolve().name, folder=folder, program=program,
        title=str(data.get("title", "")), source=str(data.get("source", "")),
        style=str(data.get("style", "pmac")), radius=None if radius is None else float(radius),
        expect=expect, vmax=vmax, amax=amax, jmax=jmax,
        extra={k: v for k, v in data.items() if k not in known},
    )


def _case_jerk(limits: dict, bad) -> tuple[float, ...] | None:
    """``[limits] j`` (optional): 2 or 3 positive numbers (X, Y[, Z]), units/s^3."""
    vals = limits.get("j")
    if vals is None:
        return None
    if not (isinstance(vals, list) and 2 <= len(vals) <= 3
            and all(isinstance(x, (int, float)) and x > 0 for x in vals)):
        raise bad("limits.j", "must be a list of 2 or 3 positive numbers (X, Y[, Z])")
    return tuple(float(x) for x in vals)


def find_case(name_or_path: str) -> Case | None:
    """A case by folder path or bundled name; ``None`` when it is not a case."""
    p = Path(name_or_path)
    if (p / "case.toml").is_file():
        return load_case(p)
    bundled = bundled_cases_dir() / name_or_path
    if (bundled / "case.toml").is_file():
        return load_case(bundled)
    return None


@dataclass(frozen=True)
class Overrides:
    """What the command line says for every input; ``None`` where it says nothing.

    style: controller style; radius: cutter radius, program units (>= 0);
    side: ``"left"``/``"right"``; vmax, amax, jmax: axis limits ``(X, Y[, Z])`` in
    units/s, units/s^2 and units/s^3; delta: the smoother's tolerance band, program units;
    dialect, tool_table: how to read the program; style_options: the style's
    own options (``break_cos``, ``ccbuf``), passed to compensation as given.
    """

    style: str | None = None
    radius: float | None = None
    side: str | None = None
    vmax: tuple[float, ...] | None = None
    amax: tuple[float, ...] | None = None
    delta: float | None = None
    dialect: str | None = None
    tool_table: str | os.PathLike | None = None
    style_options: dict = field(default_factory=dict)
    jmax: tuple[float, ...] | None = None


@dataclass(frozen=True)
class Job:
    """One input with its settings resolved (see :func:`resolve_input`).

    ``radius``/``side`` ``None``: the program's own. ``vmax``/``amax``
    ``None``: no limits known (:meth:`limits` says so). ``delta`` ``None``:
    the smoother's default band.
    """

    label: str
    program: Path
    case: Case | None
    style: str
    radius: float | None
    side: str | None
    vmax: tuple[float, ...] | None
    amax: tuple[float, ...] | None
    delta: float | None = None
    dialect: str | None = None
    tool_table: str | os.PathLike | None = None
    style_options: dict = field(default_factory=dict)
    jmax: tuple[float, ...] | None = None

    @property
    def title(self) -> str:
        return self.case.title if self.case else ""

    @property
    def source(self) -> str:
        return self.case.source if self.case else ""

    @property
    def expect(self) -> str:
        """The verdict the input should get: a case's ``expect``, else ``"ok"``."""
        return self.case.expect if self.case else "ok"

    def read(self) -> Program:
        """The program, read with the job's dialect and tool table."""
        return read_program(self.program, self.dialect, tool_table=self.tool_table)

    def compensate(self, prog: Program) -> ToolPath:
        """``prog`` compensated with the job's style, radius, side and style options."""
        return compensate(prog, style=self.style, radius=self.radius, side=self.side,
                          **self.style_options)

    def limits(self, tangential_acc: float | None = None,
               centripetal_acc: float | None = None) -> AxisLimits:
        """The job's axis limits (plus the optional path limits, units/s^2);
        a ProgramError located at the program when they are missing or bad."""
        if self.vmax is None or self.amax is None:
            raise ProgramError("no axis limits: give --vmax and --amax (X,Y[,Z]) or use a case "
                               "whose case.toml has [limits]", str(self.program))
        try:
            return AxisLimits(self.vmax, self.amax, tangential_acc=tangential_acc,
                              centripetal_acc=centripetal_acc, j=self.jmax)
        except ValueError as exc:
            raise ProgramError(f"bad limits: {exc}", str(self.program)) from None


def _locate(what: str | Case) -> tuple[str, Path, Case | None]:
    """Label, program file and case of a case, case folder, bundled case name or program file."""
    case = what if isinstance(what, Case) else find_case(what)
    if case is not None:
        return case.name, case.program, case
    p = Path(what)
    if not p.exists():
        raise ProgramError("no such program, case folder or bundled case name", what)
    if p.is_dir():
        raise ProgramError("a folder without case.toml is not a case", what)
    return p.name, p, None


def resolve_input(what: str | Case, overrides: Overrides = Overrides(),
                  default_limits: dict | None = None) -> Job:
    """The job for ``what`` (a program file, case folder, bundled case name or
    loaded :class:`Case`) with every setting resolved once: the command line's
    ``overrides``, else the case's, else :data:`DEFAULT_STYLE` for the style
    and ``default_limits`` (``{"v": (X, Y[, Z]), "a": (...)}``, units/s and
    units/s^2; ``None``: no default) for the axis limits.

    A ProgramError located at ``what`` when it is none of those.
    """
    label, program, case = _locate(what)
    default_limits = default_limits or {}
    return Job(
        label=label, program=program, case=case,
        style=overrides.style or (case.style if case else DEFAULT_STYLE),
        radius=overrides.radius if overrides.radius is not None else (
            case.radius if case else None),
        side=overrides.side,
        vmax=overrides.vmax or (case.vmax if case else None) or default_limits.get("v"),
        amax=overrides.amax or (case.amax if case else None) or default_limits.get("a"),
        delta=overrides.delta, dialect=overrides.dialect, tool_table=overrides.tool_table,
        style_options=dict(overrides.style_options),
        jmax=overrides.jmax or (case.jmax if case else None) or default_limits.get("j"))
