"""From a spec to tasks: the programs it names, and the product of its axes.

A task is one program with one setting. Its id (:func:`task_id`) is a hash of
the program's label and the setting, so a results folder knows which tasks
it already holds whatever order they run in (resume).

A task's settings are resolved as every command's are
(:func:`ccopt.cases.resolve_input`): a bundled or user case brings its own
style, cutter radius and axis limits (``case.toml``), which apply wherever the
sweep does not set them; a bare program gets its style by dialect (as every
command picks it), its own radius and :data:`DEFAULT_LIMITS`.
"""
from __future__ import annotations

import fnmatch
import glob
import hashlib
import itertools
import json
from dataclasses import dataclass
from pathlib import Path

from ccopt.cases import (DEFAULT_LIMITS, Case, Job, Overrides, bundled_cases, find_case,
                         load_case, resolve_input)
from ccopt.errors import CcoptError, ProgramError
from ccopt.feed import PLANNERS
from ccopt.sweep.spec import Spec, limits_label

PROGRAM_SUFFIXES = (".pmc", ".nc", ".ngc")
GLOB_CHARS = "*?["


@dataclass(frozen=True)
class ProgramInput:
    """One program of the sweep: its label in the table, file and case (if any)."""

    label: str
    file: Path
    case: Case | None = None


@dataclass(frozen=True)
class Task:
    """One row to compute: ``settings`` are the swept values (the columns),
    ``job`` the task's whole job, resolved as every entry point's is
    (:func:`make_job`)."""

    id: str
    program: str
    settings: dict
    job: Job


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


def make_job(program: ProgramInput, settings: dict, spec: Spec) -> Job:
    """The job of one task: the sweep's ``settings`` over the program's case
    and the defaults, by :func:`ccopt.cases.resolve_input` (the rule every
    command follows: a style by the program's dialect where neither sets
    one, :data:`DEFAULT_LIMITS` where neither gives limits, the certified
    planner where the spec names none). A ``limits`` table sets ``v`` and
    ``a`` (and ``j`` when it has one); the spec's ``planners`` are planned for
    every task, the first verified, unless ``planner`` is swept."""
    limits = settings.get("limits")
    planners = (settings["planner"],) if "planner" in settings else spec.planners
    overrides = Overrides(
        style=settings.get("style"), radius=settings.get("radius"), side=settings.get("side"),
        vmax=tuple(limits["v"]) if limits else None, amax=tuple(limits["a"]) if limits else None,
        # a limits row is a whole set: without j, no jerk limit (not the case's)
        jmax=(tuple(limits["j"]) if "j" in limits else ()) if limits else None,
        planner=planners[0] if planners else None, planners=planners,
        variant=settings.get("variant"), delta=settings.get("delta"),
        tolerance=settings.get("tolerance"))
    return resolve_input(program.case or str(program.file), overrides, DEFAULT_LIMITS,
                         label=program.label)


def planned(spec: Spec, tasks: list[Task]) -> list[str]:
    """The planners of the table's ``cycle_time_<planner>`` columns: the spec's
    (its ``planner`` axis, else ``planners``) in its order, else every planner
    some task plans (its certified one), in the registry's order; a task whose
    limits are bad plans none (its row says why)."""
    named = list(spec.axes.get("planner", [])) or list(spec.planners or ())
    if named:
        return named
    names: set[str] = set()
    for t in tasks:
        try:
            names.update(t.job.planners_for(t.job.limits()))
        except CcoptError:
            continue
    return [p for p in PLANNERS if p in names]


def expand(spec: Spec, programs: list[ProgramInput]) -> list[Task]:
    """Every task of the sweep: programs x settings, in that order."""
    product = settings_product(spec)
    tasks = []
    for prog in programs:
        for settings in product:
            columns = {k: (limits_label(v) if k == "limits" else v) for k, v in settings.items()}
            tasks.append(Task(task_id(prog.label, settings), prog.label, columns,
                              make_job(prog, settings, spec)))
    return tasks
