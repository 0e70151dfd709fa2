"""The sweep spec: a TOML file naming the programs and the axes of the sweep.

::

    title = "Controller styles x cutter radii"       # optional
    programs = ["leadin-*", "cases/pocket", "parts/*.nc"]
    planners = ["toppra", "stop"]                     # planned for every task; the first is
                                                      # verified (default: the certified one,
                                                      # jerk with jerk limits, else toppra)
    tolerance = 0.001                                 # the verifier's gouge tolerance (program
                                                      # units; default 1e-3 mm / 4e-5 inch)

    [axes]                                            # the sweep is their product
    style = ["pmac", "linuxcnc", "fagor"]
    radius = [1.0, 1.5, 2.0]                          # cutter radius, program units
    side = ["left", "right"]
    limits = [{name = "slow", v = [50, 50, 20], a = [500, 500, 200]},
              {name = "fast", v = [200, 200, 50], a = [2000, 2000, 500],
               j = [20000, 20000, 5000]}]                 # j: jerk, units/s^3 (optional)
    planner = ["toppra", "junction"]                  # one planner per task instead
    variant = ["pmac", "tangent-arc", "smooth"]       # a compare variant (not with style)
    delta = [0.01, 0.03]                              # the smoother's band (with variant)

    [[combinations]]                                  # explicit combinations: one more
    style = "fagor"                                   # axis whose values are whole tables
    radius = 2.0

A value that is not a list is a fixed setting (a one-value axis); the
top-level ``tolerance`` is one too. Each task's settings are resolved as the
command line's are, over its case's (:func:`ccopt.cases.resolve_input`): a
program that is not a case gets its style by dialect, its own radius and
:data:`ccopt.cases.DEFAULT_LIMITS`; a limits table without ``j`` keeps the
case's jerk limits, if any. Programs
are bundled case names, case folders, program files, folders and globs,
relative to the spec's folder (a glob that matches no file is matched
against the bundled case names). Every problem is a
:class:`~ccopt.errors.ProgramError` located at the spec's line; values a
task alone can judge (an unknown style or variant, a radius the program
cannot take) are left to the task, whose row then carries the error.
"""
from __future__ import annotations

import math
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ccopt.errors import ProgramError
from ccopt.feed import PLANNERS
from ccopt.sides import SIDE_NAMES

#: The axes a sweep may span, in the order of the table's columns.
AXES = ("style", "radius", "side", "limits", "planner", "variant", "delta", "tolerance")
TOP_KEYS = ("title", "programs", "planners", "tolerance", "axes", "combinations")
LIMIT_KEYS = ("name", "v", "a", "j")


@dataclass(frozen=True)
class Spec:
    """A checked sweep spec.

    ``axes``: axis name -> list of values (a fixed setting is a one-value
    list); ``combinations``: explicit settings (dicts), one more axis whose
    values are whole tables (``[{}]`` when none); ``planners``: planned for
    every task unless ``planner`` is an axis, the first verified (``None``:
    each task's certified planner, :func:`ccopt.feed.certified_planner`);
    ``base``: the folder program
    entries are relative to; ``text``: the spec as written (for the copy in
    the results folder), ``file``: where it came from.
    """

    programs: tuple[str, ...]
    axes: dict
    combinations: tuple[dict, ...] = ({},)
    planners: tuple[str, ...] | None = None
    title: str = ""
    base: Path = field(default_factory=Path.cwd)
    file: str = "<spec>"
    text: str = ""

    @property
    def setting_names(self) -> list[str]:
        """Every setting a task may carry, in column order."""
        named = set(self.axes) | {k for c in self.combinations for k in c}
        return [a for a in AXES if a in named]


class _Locator:
    """Finds the line of a key in the spec text, for located errors."""

    def __init__(self, file: str, text: str):
        self.file = file
        self.lines = text.splitlines()

    def _section_start(self, section: str | None, index: int) -> int:
        if section is None:
            return 0
        pattern = re.compile(rf"\s*\[\[?\s*{re.escape(section)}\s*\]\]?")
        hits = [i for i, line in enumerate(self.lines) if pattern.match(line)]
        return hits[min(index, len(hits) - 1)] if hits else 0

    def line(self, key: str | None, section: str | None = None, index: int = 0) -> int | None:
        start = self._section_start(section, index)
        if key is None:
            return start + 1 if self.lines else None
        pattern = re.compile(rf"\s*{re.escape(key)}\s*=")
        for i in range(start, len(self.lines)):
            if pattern.match(self.lines[i]):
                return i + 1
        for i, text in enumerate(self.lines):  # e.g. an inline table written elsewhere
            if pattern.match(text):
                return i + 1
        return None

    def error(self, message: str, key: str | None = None, section: str | None = None,
              index: int = 0) -> ProgramError:
        return ProgramError(message, self.file, self.line(key, section, index))


def _number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _axis_values(name: str, values: list, where) -> list:
    """Check the values of one axis; ``where(message)`` makes the located error."""
    if not values:
        raise where(f"{name}: the list is empty")
    out = []
    for v in values:
        if name in ("style", "variant", "planner") and not (isinstance(v, str) and v):
            raise where(f"{name}: {v!r} is not a name")
        if name == "planner" and v not in PLANNERS:
            raise where(f"planner: unknown planner {v!r}; choose among {', '.join(PLANNERS)}")
        if name == "radius" and not (_number(v) and v >= 0):
            raise where(f"radius: {v!r} is not a number >= 0")
        if name == "delta" and not (_number(v) and v > 0):
            raise where(f"delta: {v!r} is not a number > 0")
        if name == "tolerance" and not (_number(v) and v >= 0):
            raise where(f"tolerance: {v!r} is not a number >= 0")
        if name == "side" and v not in SIDE_NAMES:
            raise where(f"side: {v!r} is not {' or '.join(SIDE_NAMES)}")
        out.append(_limits_value(v, where) if name == "limits" else
                   float(v) if name in ("radius", "delta", "tolerance") else v)
    return out


def _limits_value(v, where) -> dict:
    """A limits table ``{name?, v, a, j?}`` as a plain dict with float lists
    (``j``: jerk limits, units/s^3, for the jerk planner)."""
    if not isinstance(v, dict):
        raise where(f"limits: {v!r} is not a table {{v = [...], a = [...]}}")
    unknown = sorted(set(v) - set(LIMIT_KEYS))
    if unknown:
        raise where(f"limits: unknown key(s) {', '.join(unknown)}; known: v, a, j, name")
    out = {}
    for key in ("v", "a", "j"):
        vals = v.get(key)
        if key == "j" and vals is None:
            continue
        if not (isinstance(vals, list) and 2 <= len(vals) <= 3
                and all(_number(x) and x > 0 for x in vals)):
            raise where(f"limits.{key}: must be a list of 2 or 3 positive numbers (X, Y[, Z])")
        out[key] = [float(x) for x in vals]
    if len({len(vals) for vals in out.values()}) != 1:
        raise where("limits: v, a and j must name the same axes (same length)")
    if "name" in v:
        if not (isinstance(v["name"], str) and v["name"]):
            raise where("limits.name: must be a non-empty string")
        out["name"] = v["name"]
    return out


def limits_label(limits: dict | None) -> str | None:
    """The column value of a limits setting: its name, else ``v=..;a=..``."""
    if limits is None:
        return None
    if "name" in limits:
        return limits["name"]
    return ";".join(f"{key}=" + ",".join(f"{x:g}" for x in limits[key])
                    for key in ("v", "a", "j") if key in limits)


def _check_axes(data: dict, loc: _Locator) -> dict:
    axes = data.get("axes", {})
    if not isinstance(axes, dict):
        raise loc.error("axes: must be a table [axes]", "axes")
    out = {}
    for name, values in axes.items():
        if name not in AXES:
            raise loc.error(f"axes: unknown axis {name!r}; known: {', '.join(AXES)}",
                            name, "axes")
        values = values if isinstance(values, list) else [values]
        out[name] = _axis_values(name, values, lambda m, n=name: loc.error(m, n, "axes"))
    return out


def _check_combinations(data: dict, axes: dict, loc: _Locator) -> tuple[dict, ...]:
    combos = data.get("combinations", [])
    if not isinstance(combos, list) or not all(isinstance(c, dict) for c in combos):
        raise loc.error("combinations: must be tables [[combinations]]", "combinations")
    out = []
    for i, combo in enumerate(combos):
        checked = {}
        for name, value in combo.items():
            def where(m, n=name, k=i):
                return loc.error(m, n, "combinations", k)
            if name not in AXES:
                raise where(f"combinations: unknown setting {name!r}; known: {', '.join(AXES)}")
            if name in axes:
                raise where(f"combinations: {name} is also an axis; give it in one place")
            checked[name] = _axis_values(name, [value], where)[0]
        out.append(checked)
    return tuple(out) or ({},)


def _check_programs(data: dict, loc: _Locator) -> tuple[str, ...]:
    progs = data.get("programs")
    if isinstance(progs, str):
        progs = [progs]
    if not (isinstance(progs, list) and progs and all(isinstance(p, str) and p for p in progs)):
        raise loc.error("programs: a list of programs, folders, globs or bundled case names "
                        "is required", "programs")
    return tuple(progs)


def _check_planners(data: dict, loc: _Locator) -> tuple[str, ...] | None:
    if "planners" not in data:
        return None
    planners = data["planners"]
    planners = planners if isinstance(planners, list) else [planners]
    planners = _axis_values("planner", planners, lambda m: loc.error(m, "planners"))
    if len(set(planners)) != len(planners):
        raise loc.error("planners: a planner is listed twice", "planners")
    return tuple(planners)


def _check_together(axes: dict, combos: tuple[dict, ...], data: dict, loc: _Locator) -> None:
    """Settings that only make sense together (or apart)."""
    named = set(axes) | {k for c in combos for k in c}
    if "style" in named and "variant" in named:
        raise loc.error("style and variant cannot both be set: a variant is a controller "
                        "style or a blend on PMAC's path (see ccopt compare --list)",
                        "variant", "axes" if "variant" in axes else "combinations")
    if "delta" in named and "variant" not in named:
        raise loc.error("delta is the smoother's band: it needs a variant axis "
                        "(e.g. variant = [\"smooth\"])", "delta",
                        "axes" if "delta" in axes else "combinations")
    if "planner" in named and "planners" in data:
        raise loc.error("planners and a planner axis cannot both be given", "planners")


def parse_spec(data: dict, file: str = "<spec>", text: str = "",
               base: str | os.PathLike | None = None) -> Spec:
    """Check a spec already read as a dict (``text`` locates the errors)."""
    loc = _Locator(file, text)
    unknown = [k for k in data if k not in TOP_KEYS]
    if unknown:
        raise loc.error(f"unknown key {unknown[0]!r}; known: {', '.join(TOP_KEYS)}", unknown[0])
    title = data.get("title", "")
    if not isinstance(title, str):
        raise loc.error("title: must be a string", "title")
    axes = _check_axes(data, loc)
    if "tolerance" in data:
        if "tolerance" in axes:
            raise loc.error("tolerance: given both at the top and in [axes]; give it in one "
                            "place", "tolerance")
        axes["tolerance"] = _axis_values("tolerance", [data["tolerance"]],
                                         lambda m: loc.error(m, "tolerance"))
    combos = _check_combinations(data, axes, loc)
    _check_together(axes, combos, data, loc)
    return Spec(programs=_check_programs(data, loc), axes=axes, combinations=combos,
                planners=_check_planners(data, loc), title=title,
                base=Path(base) if base is not None else Path.cwd(), file=file, text=text)


def bundled_sweeps_dir() -> Path:
    """The bundled example specs: the repository's ``sweeps/`` in a source tree
    or an editable install, else the copy the wheel ships as ``ccopt.bundled_sweeps``."""
    package = Path(__file__).resolve().parents[1]
    source_tree = package.parent / "sweeps"
    return source_tree if source_tree.is_dir() else package / "bundled_sweeps"


def find_spec_file(name: str | os.PathLike) -> Path:
    """``name`` as a path, else a bundled spec of that name (``styles-radii``)."""
    path = Path(name)
    if path.is_file():
        return path
    for candidate in (bundled_sweeps_dir() / path.name, bundled_sweeps_dir() / f"{path.name}.toml"):
        if candidate.is_file():
            return candidate
    return path


def load_spec(source) -> Spec:
    """A :class:`Spec` from a TOML file path (or a bundled spec's name), or
    from a dict written like one (then programs are relative to the current
    folder)."""
    if isinstance(source, Spec):
        return source
    if isinstance(source, dict):
        return parse_spec(source)
    path = find_spec_file(source)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ProgramError(f"cannot read sweep spec: {exc.strerror or exc}", str(path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        msg = re.sub(r"\s*\(at line \d+, column \d+\)", "", str(exc))
        line = int(m.group(1)) if m else None
        if line is None and "end of document" in str(exc):
            line = max(1, len(text.splitlines()))
        raise ProgramError(f"invalid TOML: {msg}", str(path), line) from None
    return parse_spec(data, str(path), text, path.resolve().parent)
