"""``Certificate``: what was checked, with which figure, and what failed.

JSON (DESIGN.md)::

    {"ok": bool, "geometry_ok": bool, "limits_ok": bool, "limits_tol": float|null,
     "min_clearance": float|null, "radius": float,
     "checks": [Check...], "violations": [Violation...], ...}

Every figure says how it was obtained (``basis``):

- ``"exact"``: closed form (line/arc distances), exact up to rounding;
- ``"certified-bound"``: a certified bound for spirals and curves (a lower
  bound of a distance, an upper bound of a contact gap), within the stated
  gap of the true value;
- ``"sampled"``: from feed-profile samples (limits);
- ``"not-run"``: the check did not apply (e.g. no feed profile given).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field, fields
from itertools import repeat
from typing import Any

EXACT, CERTIFIED, SAMPLED, NOT_RUN = "exact", "certified-bound", "sampled", "not-run"

#: The check of the feed limits; every other check is about the geometry.
LIMITS_CHECK = "limits"


def _num(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _pt(p):
    return None if p is None else [float(p[0]), float(p[1])]


@dataclass(frozen=True, slots=True)
class Violation:
    """One failure.

    ``kind``: ``gouge | contact | side | gap | velocity | acceleration | feed``.
    ``depth``: how far past the requirement, in the check's unit (gouge: how
    far the tool centre is inside the clearance; contact: how far beyond
    ``r``; side: how far on the wrong side; gap: the jump; limits: the excess
    ratio ``value / limit - 1``). Tool segment and contour element are indices
    into the tool path and the contour; ``*_block`` are source lines.
    """

    kind: str
    depth: float
    tool_segment: int | None = None
    tool_block: int | None = None
    tool_role: str | None = None
    element: int | None = None
    element_block: int | None = None
    witness_tool: tuple[float, float] | None = None
    witness_contour: tuple[float, float] | None = None
    basis: str = EXACT
    detail: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        out: dict[str, Any] = {
            "kind": self.kind, "depth": _num(self.depth), "basis": self.basis,
            "tool_segment": self.tool_segment, "tool_block": self.tool_block,
            "tool_role": self.tool_role,
            "element": self.element, "element_block": self.element_block,
            "witness_tool": _pt(self.witness_tool), "witness_contour": _pt(self.witness_contour),
        }
        out.update({k: v for k, v in self.detail.items()})
        return out

    @classmethod
    def many(cls, *columns) -> list["Violation"]:
        """Violations from columns of their fields (every field, in order, one
        value per violation): the objects ``map(Violation, *columns)`` makes,
        each field set through its slot without the per-object ``__init__`` (a
        long path has hundreds of thousands of gouges)."""
        columns = [list(c) for c in columns]
        n = len(columns[0]) if columns else 0
        if len(columns) != len(_VIOLATION_SLOTS) or any(len(c) != n for c in columns):
            raise ValueError(f"Violation.many takes {len(_VIOLATION_SLOTS)} columns of one length")
        out = list(map(object.__new__, repeat(cls, n)))
        for put, column in zip(_VIOLATION_SLOTS, columns):
            deque(map(put, out, column), maxlen=0)
        return out


#: Each field's slot setter, in field order (:meth:`Violation.many`).
_VIOLATION_SLOTS = tuple(Violation.__dict__[f.name].__set__ for f in fields(Violation))


@dataclass(frozen=True)
class Check:
    """One check: ``figure`` against ``tolerance`` (``unit``), how it was
    obtained (``basis``), how many items it covered (``count``)."""

    name: str
    ok: bool
    figure: float | None
    tolerance: float
    basis: str
    unit: str
    requirement: str
    count: int = 0
    violations: int = 0
    detail: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        out = {"name": self.name, "ok": self.ok, "figure": _num(self.figure),
               "tolerance": self.tolerance, "basis": self.basis, "unit": self.unit,
               "requirement": self.requirement, "count": self.count,
               "violations": self.violations}
        if self.detail:
            out["detail"] = self.detail
        return out


@dataclass(frozen=True, eq=False)
class Certificate:
    """The verifier's answer. ``ok`` is True when every check holds:
    ``geometry_ok`` (gouge, contact, side, continuity and any other check of
    the path) and ``limits_ok`` (the feed profile's axis velocity,
    acceleration and feed within ``limits_tol``, relative) are the two
    verdicts it joins, so a path that is right but fed too fast is told from
    a wrong path.

    ``min_clearance``: the smallest distance from the tool centre to the
    contour (program units; ``None`` when the program has no contour or the
    tool never comes within reach), ``min_clearance_basis`` how it was
    obtained; ``radius``: the largest cutter radius of the contour; ``eps``:
    the tolerance used. ``context`` holds the arrays behind the figures (for
    cross-checks; not part of the JSON). ``surface``: which fully compensated
    moves were taken as part surface and which as air, and why
    (:meth:`ccopt.verify.surface.Surface.report`: ``rule``, ``part_lines``,
    ``air_lines`` as ``[first, last]`` program line ranges, ``moves`` runs).
    """

    ok: bool
    min_clearance: float | None
    min_clearance_basis: str
    radius: float
    eps: float
    checks: tuple[Check, ...]
    violations: tuple[Violation, ...]
    units: str = "mm"
    notes: tuple[str, ...] = ()
    context: Any = field(default=None, repr=False)
    surface: dict = field(default_factory=dict)
    warnings: tuple[Violation, ...] = ()
    tolerance: float | None = None

    @property
    def verdict(self) -> str:
        """``"ok"``, ``"ok within tolerance"`` (every check holds, with shallow
        violations listed as :attr:`warnings`) or ``"failed"``."""
        if not self.ok:
            return "failed"
        return "ok within tolerance" if self.warnings else "ok"

    def check(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(name)

    @property
    def limits_ok(self) -> bool:
        """The feed limits check holds (within its stated relative tolerance);
        True when no profile was given (the check did not run)."""
        return all(c.ok for c in self.checks if c.name == LIMITS_CHECK)

    @property
    def geometry_ok(self) -> bool:
        """Every check but the feed limits holds: the path itself is right,
        whatever a feed profile does along it."""
        return all(c.ok for c in self.checks if c.name != LIMITS_CHECK)

    @property
    def limits_tol(self) -> float | None:
        """The relative tolerance the limits check allowed (``None`` without one)."""
        for c in self.checks:
            if c.name == LIMITS_CHECK:
                return c.tolerance
        return None

    def violations_of(self, kind: str) -> list[Violation]:
        return [v for v in self.violations if v.kind == kind]

    def to_json(self) -> dict:
        return {
            "ok": self.ok,
            "verdict": self.verdict,
            "tolerance": self.tolerance,
            "geometry_ok": self.geometry_ok,
            "limits_ok": self.limits_ok,
            "limits_tol": self.limits_tol,
            "min_clearance": _num(self.min_clearance),
            "min_clearance_basis": self.min_clearance_basis,
            "radius": self.radius,
            "eps": self.eps,
            "units": self.units,
            "checks": [c.to_json() for c in self.checks],
            "violations": [v.to_json() for v in self.violations],
            "warnings": [v.to_json() for v in self.warnings],
            "notes": list(self.notes),
            "surface": self.surface,
        }

    def summary(self) -> str:
        """A few human lines: one per check, then the violations (first 20)."""
        lines = [f"verification {self._headline()} ({self._verdicts()}): "
                 f"cutter radius {self.radius:g} "
                 f"{self.units}, eps {self.eps:g}{self._tolerance_text()}, min clearance "
                 + ("n/a" if self.min_clearance is None else
                    f"{self.min_clearance:.9g} ({self.min_clearance_basis})")]
        for c in self.checks:
            fig = "n/a" if c.figure is None else f"{c.figure:.9g}"
            lines.append(f"  {c.name:11s} {'ok ' if c.ok else 'FAIL'}  {fig:>16s} {c.unit:5s} "
                         f"[{c.basis}] {c.requirement} ({c.count} checked, {c.violations} violations)")
        for v in self.violations[:20]:
            lines.append(f"  - {v.kind}: depth {v.depth:.9g}, {_place(v)}".rstrip())
        if len(self.violations) > 20:
            lines.append(f"  ... {len(self.violations) - 20} more")
        for v in self.warnings[:20]:
            lines.append(f"  ~ warning, {v.kind} within tolerance: depth {v.depth:.3g} "
                         f"{self.units}, {_place(v)}: {v.detail.get('cause', '')}".rstrip())
        if len(self.warnings) > 20:
            lines.append(f"  ... {len(self.warnings) - 20} more warnings")
        for n in self.notes:
            lines.append(f"  note: {n}")
        lines.extend(_surface_lines(self.surface))
        return "\n".join(lines)

    def __str__(self) -> str:
        """A short summary for ``print(certificate)``: the verdict, the cutter
        radius and smallest clearance and, when something failed, each failed
        check with its number of violations (:meth:`summary` lists every check
        and violation, :meth:`to_json` everything)."""
        clear = "n/a" if self.min_clearance is None else \
            f"{self.min_clearance:.6g} {self.units} ({self.min_clearance_basis})"
        head = (f"Certificate {self._headline().replace('PASSED', 'OK')} ({self._verdicts()}): cutter "
                f"radius {self.radius:g} {self.units}, min clearance {clear}")
        failed = [c for c in self.checks if not c.ok]
        if not failed:
            return f"{head}; {len(self.checks)} checks passed"
        return head + "\n  failed: " + ", ".join(
            f"{c.name} ({c.violations} violation{'s' if c.violations != 1 else ''})"
            for c in failed)

    def _headline(self) -> str:
        if not self.ok:
            return "FAILED"
        if self.warnings:
            n = len(self.warnings)
            return f"PASSED within tolerance ({n} warning{'s' if n != 1 else ''})"
        return "PASSED"

    def _tolerance_text(self) -> str:
        return "" if self.tolerance is None else f", tolerance {self.tolerance:g} {self.units}"

    def _verdicts(self) -> str:
        """``geometry ok, limits FAIL`` and the like: the two verdicts ``ok`` joins."""
        lim = "ok" if self.limits_ok else "FAIL"
        if any(c.name == LIMITS_CHECK and c.basis == NOT_RUN for c in self.checks):
            lim = "not run"
        elif self.limits_tol is not None:
            lim += f" at tolerance {self.limits_tol:g}"
        return f"geometry {'ok' if self.geometry_ok else 'FAIL'}, limits {lim}"

def _place(v: Violation) -> str:
    """Where a violation is: its tool segment, element and witness point."""
    where = f"tool segment {v.tool_segment} (line {v.tool_block}, {v.tool_role})" \
        if v.tool_segment is not None else ""
    elem = f" vs element {v.element} (line {v.element_block})" if v.element is not None else ""
    wit = ""
    if v.witness_tool is not None:
        wit = f" at ({v.witness_tool[0]:.6g}, {v.witness_tool[1]:.6g})"
    return f"{where}{elem}{wit}"


def _lines_text(ranges) -> str:
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in ranges) or "none"


def _surface_lines(surface: dict) -> list[str]:
    """The part/air decision in words: each run of part moves and of air
    moves with its reason (runs on the same lines for the same reason, e.g.
    the passes of one subroutine, once with their count)."""
    if not surface or not surface.get("air_lines"):
        return []
    runs: dict[tuple, int] = {}
    for run in surface["moves"]:
        key = (run["surface"], tuple(run["lines"]), run["why"])
        runs[key] = runs.get(key, 0) + 1
    out = [f"  part and air by rule {surface['rule']}:"]
    for (surf, lines, why), count in runs.items():
        label = "part surface" if surf == "part" else "air"
        times = f" (x{count})" if count > 1 else ""
        out.append(f"  {label}: lines {_lines_text([lines])}{times} ({why})")
    return out
