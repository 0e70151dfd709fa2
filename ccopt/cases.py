"""Bundled and user cases: a folder with a program and a ``case.toml``.

``case.toml`` keys (all optional except ``program``)::

    title   = "Lead-out, inside corner, line to line"
    source  = "PMAC User Manual p.189, figure 47 (a)"
    program = "leadout_line_line.pmc"   # relative to the case folder
    style   = "pmac"                    # controller style (default: by the program's dialect)
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
(:class:`Overrides`: the command line's options, a sweep spec's row or the
Python API's keywords, :func:`make_job`), else what its ``case.toml`` says,
else the defaults. It returns a :class:`Job`, which :func:`ccopt.pipeline.pipeline`
runs for every command, ``ccopt run``, the sweep and the API alike.
"""
from __future__ import annotations

import math
import os
import re
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ccopt.compensate import STYLES, compensate
from ccopt.atomic import protect_input
from ccopt.errors import ProgramError
from ccopt.feed import PLANNERS, AxisLimits, certified_planner
from ccopt.program import read_program
from ccopt.program.model import ENDLESS_MAIN, INPUT_FILES, MAX_COORDINATE, NOTES, Program
from ccopt.tolerances import LIMIT_RANGE
from ccopt.toolpath import ToolPath

EXPECTS = ("ok", "gouge", "error")

#: The controller style of a PMAC program that is not a case and gets none on
#: the command line: the reference. G-code gets :data:`GCODE_STYLE`, or
#: :data:`FAGOR_STYLE` when Fagor's G136-G139 appear (:func:`default_style`).
DEFAULT_STYLE = "pmac"
GCODE_STYLE = "linuxcnc"
FAGOR_STYLE = "fagor"
#: The style of a HEIDENHAIN Klartext program (``.h``).
HEIDENHAIN_STYLE = "heidenhain"
#: The style of a SINUMERIK program (``.mpf``, ``.spf``).
SIEMENS_STYLE = "siemens"

#: Axis limits of an input whose case has no ``[limits]`` and that gets no
#: ``--vmax``/``--amax``: 100 units/s and 1000 units/s^2 on every axis (a small
#: mill in mm); no jerk limit. Every command that plans says when it uses them.
DEFAULT_LIMITS = {"v": (100.0, 100.0, 100.0), "a": (1000.0, 1000.0, 1000.0)}

#: How the output says where the axis limits come from (:attr:`Job.limits_from`).
LIMITS_FROM = {"command line": "--vmax/--amax", "case": "the case's [limits]",
               "default": "default: no [limits] in a case and no --vmax/--amax",
               "command line and case": "--vmax/--amax over the case's [limits]",
               "command line and default": "--vmax/--amax over the default"}

# Fagor's words in G-code, outside comments: G136/G137 (corner transition),
# G138/G139 (how compensation starts and ends).
_FAGOR_WORD_RE = re.compile(r"(?i)(?<![A-Z])G\s*0*13[6-9](?![0-9.])")
_COMMENT_RE = re.compile(r"\([^)]*\)|;.*")


@dataclass(frozen=True)
class Case:
    """A loaded ``case.toml`` (paths resolved, values checked)."""

    name: str
    folder: Path
    program: Path
    title: str = ""
    source: str = ""
    style: str | None = None            # None: by the program's dialect (default_style)
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


_TABLE_RE = re.compile(r"\[\s*([^\[\]]+?)\s*\]\s*(#.*)?$")
_KEY_RE = re.compile(r"""([A-Za-z0-9_\-."' ]+?)\s*=""")


def _dotted(key: str) -> list[str]:
    return [k.strip().strip("\"'") for k in key.split(".")]


def _key_line(text: str, key: str) -> int | None:
    """The 1-based line of ``text`` (TOML) that sets ``key`` (dotted, e.g.
    ``"limits.v"``): under its table header, as a dotted key or, failing
    those, the line of its table (header or inline table). tomllib gives no
    line numbers, so errors about values find their line here."""
    want = _dotted(key)
    table: list[str] = []
    fallback = None
    for i, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        m = _TABLE_RE.match(line)
        if m:
            table = _dotted(m.group(1))
            if fallback is None and table == want[:len(table)]:
                fallback = i
            continue
        m = _KEY_RE.match(line)
        if not m:
            continue
        path = table + _dotted(m.group(1))
        if path == want:
            return i
        if fallback is None and path == want[:len(path)]:
            fallback = i
    return fallback


def _shown(value) -> str:
    """``value`` as TOML writes it, for a message (short)."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = '"' + value.replace('"', '\\"') + '"'
    elif isinstance(value, list):
        text = "[" + ", ".join(_shown(v) for v in value) + "]"
    elif isinstance(value, dict):
        text = "{" + ", ".join(f"{k} = {_shown(v)}" for k, v in value.items()) + "}"
    else:
        text = str(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _number_in(value, lowest: float, strict: bool) -> bool:
    """``value`` is a TOML number (not a boolean), finite, above ``lowest``
    (or equal, unless ``strict``) and at most :data:`MAX_COORDINATE`."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    if not math.isfinite(value) or value > MAX_COORDINATE:
        return False
    return value > lowest if strict else value >= lowest


def _limits(data: dict, bad) -> tuple[tuple[float, ...] | None, tuple[float, ...] | None]:
    """``[limits] v, a`` checked: ``(vmax, amax)``, ``(None, None)`` when absent."""
    limits = data.get("limits", {})
    if not isinstance(limits, dict):
        raise bad("limits", limits, "must be a table with v and a, e.g. [limits] "
                  "v = [100.0, 100.0] a = [1000.0, 1000.0]")
    if not limits:
        return None, None
    for key in ("v", "a"):
        vals = limits.get(key)
        if vals is None:
            raise bad("limits", None, f"[limits] needs {key} = [X, Y[, Z]]")
        lo, hi = LIMIT_RANGE
        if not (isinstance(vals, list) and 2 <= len(vals) <= 3
                and all(_number_in(x, lo, strict=False) and x <= hi for x in vals)):
            raise bad(f"limits.{key}", vals, f"must be a list of 2 or 3 numbers between {lo:g} "
                      f"and {hi:g} (X, Y[, Z])")
    return tuple(float(x) for x in limits["v"]), tuple(float(x) for x in limits["a"])


def load_case(folder: str | os.PathLike) -> Case:
    """Load ``folder/case.toml``; every problem is a ProgramError located at
    the key's line (``case.toml:LINE: key = value: what it must be``)."""
    folder = Path(folder)
    toml_path = folder / "case.toml"
    try:
        text = toml_path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ProgramError(f"cannot read case: {exc.strerror or exc}", str(toml_path)) from None
    except UnicodeDecodeError:
        raise ProgramError("not UTF-8 text", str(toml_path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _toml_error(toml_path, exc) from None

    def bad(key: str, value, msg: str) -> ProgramError:
        shown = f"{key} = {_shown(value)}: " if value is not None else f"{key}: "
        return ProgramError(shown + msg, str(toml_path), _key_line(text, key))

    prog = data.get("program")
    if not isinstance(prog, str) or not prog:
        raise bad("program", prog, "a program file name is required")
    program = folder / prog
    if not program.is_file():
        raise bad("program", prog, f"no such file {program}")
    radius = data.get("radius")
    if radius is not None and not _number_in(radius, 0.0, strict=False):
        raise bad("radius", radius, f"must be a finite number >= 0 and at most "
                  f"{MAX_COORDINATE:g} (program units)")
    expect = data.get("expect", "ok")
    if expect not in EXPECTS:
        raise bad("expect", expect, f"must be one of {', '.join(EXPECTS)}")
    style = data.get("style")
    if style is not None and style not in STYLES:
        raise bad("style", style, f"must be one of {', '.join(sorted(STYLES))}")
    vmax, amax = _limits(data, bad)
    jmax = _case_jerk(data.get("limits", {}), bad) if vmax is not None else None
    known = {"program", "title", "source", "style", "radius", "expect", "limits"}
    return Case(
        name=folder.resolve().name, folder=folder, program=program,
        title=str(data.get("title", "")), source=str(data.get("source", "")),
        style=style, radius=None if radius is None else float(radius),
        expect=expect, vmax=vmax, amax=amax, jmax=jmax,
        extra={k: v for k, v in data.items() if k not in known},
    )


def _case_jerk(limits: dict, bad) -> tuple[float, ...] | None:
    """``[limits] j`` (optional): 2 or 3 positive numbers (X, Y[, Z]), units/s^3."""
    vals = limits.get("j")
    if vals is None:
        return None
    lo, hi = LIMIT_RANGE
    if not (isinstance(vals, list) and 2 <= len(vals) <= 3
            and all(_number_in(x, lo, strict=False) and x <= hi for x in vals)):
        raise bad("limits.j", vals, f"must be a list of 2 or 3 numbers between {lo:g} and "
                  f"{hi:g} (X, Y[, Z])")
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


def default_style(prog: Program) -> tuple[str, str]:
    """The style of ``prog`` when neither a case nor the command line names
    one, and why: ``pmac`` for a PMAC program, ``heidenhain`` for a Klartext
    program, ``siemens`` for a SINUMERIK one, ``fagor`` for G-code where
    Fagor's G136-G139 appear (outside comments), else ``linuxcnc``."""
    if prog.dialect == "pmac":
        return DEFAULT_STYLE, "default for a PMAC program"
    if prog.dialect == "heidenhain":
        return HEIDENHAIN_STYLE, "default for a HEIDENHAIN Klartext program"
    if prog.dialect == "sinumerik":
        return SIEMENS_STYLE, "default for a SINUMERIK program"
    for name in dict.fromkeys(b.source.file for b in prog.blocks):
        try:
            text = Path(name).read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue        # a program read from a string: no file to look in
        if any(_FAGOR_WORD_RE.search(_COMMENT_RE.sub(" ", line)) for line in text.splitlines()):
            return FAGOR_STYLE, "default for G-code with Fagor's G136-G139"
    return GCODE_STYLE, "default for G-code"


@dataclass(frozen=True)
class ReadOptions:
    """How to read a program (see :func:`ccopt.program.read_program`): the
    dialect (``None``: from the suffix) and a tool table, and for G-code a
    LinuxCNC parameter file, the unit every length is converted to, the tool
    table's units, the folders of subroutine files (LinuxCNC's
    SUBROUTINE_PATH), the O-word loop limit and the machine's LinuxCNC INI
    file, which gives those it names that are not given (``None``: the
    defaults)."""

    dialect: str | None = None
    tool_table: str | os.PathLike | None = None
    var_file: str | os.PathLike | None = None
    units: str | None = None
    table_units: str | None = None
    sub_path: tuple[str, ...] = ()
    max_loop_iterations: int | None = None
    ini: str | os.PathLike | None = None

    def read(self, program: str | os.PathLike) -> Program:
        """``program`` read with these options; the files it was read from
        remembered as inputs within a command (:func:`ccopt.atomic.protect_input`)."""
        prog = read_program(program, self.dialect, tool_table=self.tool_table,
                            var_file=self.var_file, units=self.units,
                            table_units=self.table_units, sub_path=self.sub_path,
                            max_loop_iterations=self.max_loop_iterations, ini=self.ini)
        for f in prog.meta.get(INPUT_FILES, ()):
            protect_input(f)
        if ENDLESS_MAIN in prog.meta:
            # the program is read, but a machine would not stop where ccopt did
            print(f"{prog.meta[ENDLESS_MAIN]} (note)", file=sys.stderr)
        for note in prog.meta.get(NOTES, ()):
            print(f"{note} (note)", file=sys.stderr)
        return prog


@dataclass(frozen=True)
class Overrides:
    """What the command line, a sweep spec's row or the Python API says for an
    input; ``None`` (or empty) where it says nothing. Units are the program's.

    style: controller style; radius: cutter radius (>= 0); side: ``"left"``/``"right"``;
    vmax, amax, jmax: axis limits ``(X, Y[, Z])`` in units/s, units/s^2 and units/s^3
    (``jmax=()``: no jerk limit, whatever the case says: a sweep's limits row without j);
    tangential_acc, centripetal_acc: path acceleration limits, units/s^2;
    ts: the jerk-limited planners' interpolation period, s; planner: the planner whose
    profile is certified and timed (``None``: :func:`ccopt.feed.certified_planner`);
    planners: the planners planned (``"all"``: every one the limits allow);
    junction_deviation: grbl's corner deviation for the planners that take it;
    tolerance: the verifier's gouge tolerance (``None``: 1e-3 mm or 4e-5 inch,
    the verifier's default); eps, limits_tol, part_lines: the verifier's other
    settings (``None``: its defaults); toolpath: a tool path file (JSON) to
    verify instead of compensating; variants: the blend variants compared
    (``None``: every available one); variant: a compare variant whose path is
    the job's instead of the style's; delta: the smoother's band; blend_options:
    the blends' options (``lead_radius``); reading: how to read the program
    (:class:`ReadOptions`); style_options: the style's own options
    (``break_cos``, ``ccbuf``), passed to compensation as given.
    """

    style: str | None = None
    radius: float | None = None
    side: str | None = None
    vmax: tuple[float, ...] | None = None
    amax: tuple[float, ...] | None = None
    jmax: tuple[float, ...] | None = None
    delta: float | None = None
    reading: ReadOptions = ReadOptions()
    style_options: dict = field(default_factory=dict)
    ts: float | None = None
    tangential_acc: float | None = None
    centripetal_acc: float | None = None
    planner: str | None = None
    planners: tuple[str, ...] | None = None
    junction_deviation: float | None = None
    tolerance: float | None = None
    eps: float | None = None
    limits_tol: float | None = None
    part_lines: object = None
    toolpath: str | os.PathLike | None = None
    variants: tuple[str, ...] | None = None
    variant: str | None = None
    blend_options: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Job:
    """One input with every setting resolved (see :func:`resolve_input`): what
    :func:`ccopt.pipeline.pipeline` runs.

    ``style`` ``None``: by the program's dialect (:func:`default_style`).
    ``radius``/``side`` ``None``: the program's own. ``vmax``/``amax``
    ``None``: no limits known (:meth:`limits` says so); ``limits_from`` says
    where they came from (``"command line"``, ``"case"``, ``"default"``).
    The other fields are :class:`Overrides`' (the same names and units),
    resolved over the case's settings.
    """

    label: str
    program: Path
    case: Case | None
    style: str | None
    radius: float | None
    side: str | None
    vmax: tuple[float, ...] | None
    amax: tuple[float, ...] | None
    jmax: tuple[float, ...] | None = None
    delta: float | None = None
    reading: ReadOptions = ReadOptions()
    style_options: dict = field(default_factory=dict)
    ts: float | None = None
    limits_from: str | None = None
    style_from: str | None = None
    tangential_acc: float | None = None
    centripetal_acc: float | None = None
    planner: str | None = None
    planners: tuple[str, ...] | None = None
    junction_deviation: float | None = None
    tolerance: float | None = None
    eps: float | None = None
    limits_tol: float | None = None
    part_lines: object = None
    toolpath: Path | None = None
    variants: tuple[str, ...] | None = None
    variant: str | None = None
    blend_options: dict = field(default_factory=dict)

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
        """The program, read with the job's reading options."""
        return self.reading.read(self.program)

    def style_for(self, prog: Program) -> tuple[str, str]:
        """The style ``prog`` is compensated with, and where it comes from
        (``"--style"``, ``"the case's"`` or the default's reason)."""
        if self.style is not None:
            return self.style, self.style_from or "given"
        return default_style(prog)

    def compensate(self, prog: Program) -> ToolPath:
        """``prog`` compensated with the job's style (:meth:`style_for`), radius,
        side and style options."""
        return compensate(prog, style=self.style_for(prog)[0], radius=self.radius,
                          side=self.side, **self.style_options)

    def limits_note(self) -> str:
        """Where the axis limits come from, for the output (``""`` when unknown)."""
        return LIMITS_FROM.get(self.limits_from or "", self.limits_from or "")

    def limits(self) -> AxisLimits:
        """The job's axis limits (with its path acceleration limits, units/s^2);
        a ProgramError located at the program when they are missing or bad."""
        if self.vmax is None or self.amax is None:
            raise ProgramError("no axis limits: give --vmax and --amax (X,Y[,Z]) or use a case "
                               "whose case.toml has [limits]", str(self.program))
        try:
            return AxisLimits(self.vmax, self.amax, tangential_acc=self.tangential_acc,
                              centripetal_acc=self.centripetal_acc, j=self.jmax)
        except ValueError as exc:
            raise ProgramError(f"bad limits: {exc}", str(self.program)) from None

    def planner_for(self, limits: AxisLimits) -> str:
        """The planner whose profile is certified and whose duration is the cycle
        time: the job's ``planner``, else :func:`ccopt.feed.certified_planner`."""
        return self.planner or certified_planner(limits)

    def planners_for(self, limits: AxisLimits) -> list[str]:
        """The planners the job plans, in order (``"all"``: every registered one,
        ``jerk`` only when ``limits`` carry jerk), the certified one
        (:meth:`planner_for`) among them; none asked: that one alone."""
        names: list[str] = []
        for name in self.planners or ():
            names.extend((p for p in PLANNERS if p != "jerk" or limits.j is not None)
                         if name == "all" else (name,))
        certified = self.planner_for(limits)
        return list(dict.fromkeys(names if certified in names else [certified, *names]))

    def verify_options(self) -> dict:
        """The keywords of :func:`ccopt.verify.verify` the job sets: its overrides
        (``radius``, ``side``) and the verifier settings it names (``tolerance``,
        ``eps``, ``limits_tol``, ``part_lines``; left out where ``None``, the
        verifier's defaults then)."""
        given = {"tolerance": self.tolerance, "eps": self.eps, "limits_tol": self.limits_tol,
                 "part_lines": self.part_lines}
        return {"radius": self.radius, "side": self.side,
                **{k: v for k, v in given.items() if v is not None}}


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
    return p.stem, p, None  # outputs are <stem>.nc, <stem>.pmc, ... (no doubled suffix)


#: the :class:`Overrides` fields a :class:`Job` takes as they are (no case setting under them)
_AS_GIVEN = ("side", "delta", "reading", "ts", "tangential_acc", "centripetal_acc", "planner",
             "planners", "junction_deviation", "tolerance", "eps", "limits_tol", "part_lines",
             "variants", "variant")


def resolve_input(what: str | Case, overrides: Overrides = Overrides(),
                  default_limits: dict | None = None, label: str | None = None) -> Job:
    """The job for ``what`` (a program file, case folder, bundled case name or
    loaded :class:`Case`) with every setting resolved once: the ``overrides``
    (command line, sweep row or API), else the case's, else the defaults: the
    style by the program's dialect (:func:`default_style`, once it is read) and
    ``default_limits`` (``{"v": (X, Y[, Z]), "a": (...)}``, units/s and
    units/s^2, e.g. :data:`DEFAULT_LIMITS`; ``None``: no default) for the axis
    limits. The velocity and acceleration limits come as a pair from one
    place: both given, else the case's, else the default (one of
    ``vmax``/``amax`` replaces that one of the pair); the jerk limits are the
    overrides', else the case's. ``label``: the job's name in tables and file
    names (default: the case's name or the program's stem).

    This is the one place settings are resolved. A ProgramError located at
    ``what`` when it is none of those.
    """
    found, program, case = _locate(what)
    default_limits = default_limits or {}
    vmax, amax, limits_from = _resolved_limits(overrides, case, default_limits)
    case_style = case.style if case else None
    return Job(
        label=label or found, program=program, case=case,
        style=overrides.style or case_style,
        style_from="--style" if overrides.style else ("the case's" if case_style else None),
        radius=overrides.radius if overrides.radius is not None else (
            case.radius if case else None),
        vmax=vmax, amax=amax, limits_from=limits_from,
        jmax=(overrides.jmax or None) if overrides.jmax is not None else (
            (case.jmax if case else None) or default_limits.get("j")),
        style_options=dict(overrides.style_options),
        blend_options=dict(overrides.blend_options),
        toolpath=Path(overrides.toolpath) if overrides.toolpath is not None else None,
        **{name: getattr(overrides, name) for name in _AS_GIVEN})


def make_job(what: str | Case, **settings) -> Job:
    """The Python API's job: ``what`` with ``settings`` (the :class:`Overrides`
    fields: ``style=``, ``radius=``, ``vmax=``, ``tolerance=``, ...) resolved
    as the command line's are, over the case's settings and
    :data:`DEFAULT_LIMITS` (what every command takes)::

        job = ccopt.make_job("cases/pocket", style="linuxcnc", vmax=(50, 50))
        outcome = ccopt.pipeline(job)
    """
    return resolve_input(what, Overrides(**settings), DEFAULT_LIMITS)


def _resolved_limits(overrides: Overrides, case: Case | None, default_limits: dict):
    """``(vmax, amax, where from)`` by the rule of :func:`resolve_input`."""
    base, source = (None, None), None
    if case is not None and case.vmax is not None:
        base, source = (case.vmax, case.amax), "case"
    elif default_limits.get("v") is not None:
        base, source = (default_limits.get("v"), default_limits.get("a")), "default"
    vmax, amax = overrides.vmax or base[0], overrides.amax or base[1]
    if overrides.vmax or overrides.amax:
        source = "command line" if (overrides.vmax and overrides.amax) or source is None \
            else f"command line and {source}"
    return vmax, amax, source
