"""From a spec to tasks: the programs it names, and the product of its axes.

A task is one program with one setting. Its id (:func:`task_id`) is a hash of
the program's label and the setting, so a results folder knows which tasks
it already holds whatever order they run in (resume).

A bundled or user case brings its own style, cutter radius and axis limits
(``case.toml``); they apply wherever the sweep does not set them. A bare
program gets style ``pmac``, its own radius and :data:`DEFAULT_LIMITS`.
"""
from __future__ import annotations

import fnmatch
import glob
import hashlib
import itertools
import json
from dataclasses import dataclass
from pathlib import Path

from ccopt.cases import DEFAULT_LIMITS, Case, bundled_cases, find_case, load_case
from ccopt.errors import ProgramError
from ccopt.sweep.spec import Spec, limits_label

PROGRAM_SUFFIXES = (".pmc", ".nc", ".ngc")
GLOB_CHARS = "*?["


@dataclass(frozen=True)
class ProgramInput:
    """One program of the sweep: its label in the table, file and case (if any)."""

    label: str
    file: Path
    case: Case | None = None

    def defaults(self) -> dict:
        """The settings the program brings: its case's style, radius and limits."""
        c = self.case
        # a program that is not a case (and a sweep that sets none) takes the
        # limits every command takes (ccopt.cases.DEFAULT_LIMITS)
        limits = {key: list(value) for key, value in DEFAULT_LIMITS.items()}
        if c is not None and c.vmax and c.amax:
            limits = {"v": list(c.vmax), "a": list(c.amax)}
        return {"style": c.style if c else "pmac", "radius": c.radius if c else None,
                "side": None, "limits": limits, "variant": None, "delta": None}


@dataclass(frozen=True)
class Setting:
    """Everything a task runs with (program defaults overridden by the sweep).

    ``style``: controller style; ``radius``: cutter radius override (program
    units, ``None``: the program's); ``side``: ``"left"``/``"right"``
    override or ``None``; ``limits``: ``{"v": [...], "a": [...]}`` in
    units/s and units/s^2; ``planners``: planned in order, the first is
    the one verified and reported as ``cycle_time``; ``variant``: a compare
    variant whose path replaces the style's (``None``: the style's);
    ``delta``: the smoother's band (program units, ``None``: compare's default).
    """

    style: str
    radius: float | None
    side: str | None
    limits: dict
    planners: tuple[str, ...]
    variant: str | None = None
    delta: float | None = None


@dataclass(frozen=True)
class Task:
    """One row to compute: ``settings`` are the swept values (the columns)."""

    id: str
    program: str
    settings: dict
    setting: Setting


def task_id(program: str, settings: dict) -> str:
    """A stable id of (program, swept settings): 16 hex digits of SHA-1."""
    doc = json.dumps([program, settings], sort_keys=True, separators=(",", ":"))
    return hashlib.sha1(doc.encode()).hexdigest()[:16]


def _label(path: Path, base: Path) -> str:
    try:
        return str(path.resolve().relative_to(base.resolve()))
    except ValueError:
        return str(path)


def _from_path(path: Path, base: Path) -> list[ProgramInput]:
    """A case folder, a folder of cases and programs, or a program file."""
    if (path / "case.toml").is_file():
        case = load_case(path)
        return [ProgramInput(case.name, case.program, case)]
    if path.is_dir():
        found = [q for p in sorted(path.glob("*/case.toml")) for q in _from_path(p.parent, base)]
        files = sorted(p for p in path.iterdir() if p.suffix.lower() in PROGRAM_SUFFIXES)
        return found + [ProgramInput(_label(p, base), p) for p in files]
    if path.is_file():
        return [ProgramInput(_label(path, base), path)]
    return []


def _resolve_entry(entry: str, spec: Spec) -> list[ProgramInput]:
    base = spec.base
    if any(ch in entry for ch in GLOB_CHARS):
        pattern = entry if Path(entry).is_absolute() else str(base / entry)
        found = [q for p in sorted(glob.glob(pattern)) for q in _from_path(Path(p), base)]
        if not found:
            found = [ProgramInput(c.name, c.program, c) for c in bundled_cases()
                     if fnmatch.fnmatchcase(c.name, entry)]
        return found
    path = Path(entry) if Path(entry).is_absolute() else base / entry
    found = _from_path(path, base)
    if not found:
        case = find_case(entry)
        if case is not None:
            found = [ProgramInput(case.name, case.program, case)]
    return found


def resolve_programs(spec: Spec) -> list[ProgramInput]:
    """Every program the spec names, in order, each once (by label)."""
    out: dict[str, ProgramInput] = {}
    for entry in spec.programs:
        found = _resolve_entry(entry, spec)  # a broken case.toml raises at its own line
        if not found:
            raise ProgramError(f"programs: {entry!r} is no program file, folder, case or "
                               "bundled case name, and matches none", spec.file,
                               _programs_line(spec))
        for p in found:
            out.setdefault(p.label, p)
    return list(out.values())


def _programs_line(spec: Spec) -> int | None:
    for i, line in enumerate(spec.text.splitlines(), 1):
        if line.strip().startswith("programs"):
            return i
    return None


def settings_product(spec: Spec) -> list[dict]:
    """The axes' product times the explicit combinations, as column values."""
    names = list(spec.axes)
    out = []
    for values in itertools.product(*(spec.axes[n] for n in names)):
        point = dict(zip(names, values))
        for combo in spec.combinations:
            merged = {**point, **combo}
            out.append({n: merged[n] for n in spec.setting_names if n in merged})
    return out


def make_setting(program: ProgramInput, settings: dict, spec: Spec) -> Setting:
    """The full setting of one task: the program's defaults, then the sweep's."""
    s = {**program.defaults(), **settings}
    planners = (s["planner"],) if "planner" in settings else spec.planners
    return Setting(style=s["style"], radius=s["radius"], side=s["side"],
                   limits={"v": list(s["limits"]["v"]), "a": list(s["limits"]["a"])},
                   planners=tuple(planners), variant=s["variant"], delta=s["delta"])


def expand(spec: Spec, programs: list[ProgramInput]) -> list[Task]:
    """Every task of the sweep: programs x settings, in that order."""
    product = settings_product(spec)
    tasks = []
    for prog in programs:
        for settings in product:
            columns = {k: (limits_label(v) if k == "limits" else v) for k, v in settings.items()}
            tasks.append(Task(task_id(prog.label, settings), prog.label, columns,
                              make_setting(prog, settings, spec)))
    return tasks
