"""Tolerance with a scale: shallow violations are warnings, deep ones fail.

The checks find every violation beyond ``eps`` (the arithmetic's tolerance,
1e-6 program units) with its exact depth. A part program has a scale of its
own: a CAM system writes 3 or 4 decimals, and a controller's own rules may
leave a few micrometres (LinuxCNC takes a turn under 0.05 rad as straight on,
:data:`ccopt.tolerances.LINUXCNC_CONCAVE_CORNER`, and its straight join then
comes ``r (1 - cos angle)`` inside the clearance at an outside turn). So a
gouge, contact excess or wrong-side offset no deeper than the certificate's
``tolerance`` (default :data:`ccopt.tolerances.GOUGE_TOLERANCE` by the
program's units) is a *warning*, listed with its depth, place and cause, and
the verdict is "ok within tolerance"; deeper ones fail. The figures stay exact.
"""
from __future__ import annotations

import math
from collections import Counter
from dataclasses import fields, replace
from itertools import compress, repeat
from operator import attrgetter

import numpy as np

from ccopt.errors import ProgramError
from ccopt.tolerances import GOUGE_TOLERANCE, LINUXCNC_CONCAVE_CORNER
from ccopt.toolpath import STRAIGHT_JOINS, ToolPath
from ccopt.verify.certificate import Certificate, Violation

#: The checks whose violations are lengths a tolerance applies to (the
#: violation kind of each check).
TOLERATED = {"gouge": "gouge", "contact": "contact", "side": "side"}

CAUSE_WITHIN = "no deeper than the tolerance"

_TOLERATED_KINDS = frozenset(TOLERATED.values())
_DEPTH, _KIND = attrgetter("depth"), attrgetter("kind")


def default_tolerance(units: str) -> float:
    """:data:`~ccopt.tolerances.GOUGE_TOLERANCE` for ``units`` (``"mm"`` or ``"inch"``)."""
    return GOUGE_TOLERANCE.get(units, GOUGE_TOLERANCE["mm"])


def resolve_tolerance(tolerance: float | None, units: str, file: str = "<string>") -> float:
    """``tolerance`` checked (a finite number >= 0), or the default for ``units``."""
    if tolerance is None:
        return default_tolerance(units)
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise ProgramError(f"tolerance must be a number, not {tolerance!r}", file) from None
    if not (0.0 <= tol < math.inf):
        raise ProgramError(f"tolerance must be a finite number >= 0 (program units), "
                           f"got {tolerance!r}", file)
    return tol


def cause_of(violation, toolpath: ToolPath) -> str:
    """Why a shallow violation is there, as far as the tool path recorded it:
    a controller's straight join at a slight turn, else the generic cause."""
    joins = toolpath.meta.get(STRAIGHT_JOINS) or {}
    i = violation.tool_segment
    # the join is the segment that starts at the last offset point, and the
    # segment before it ends there
    at = next((j for j in (i, None if i is None else i + 1) if j is not None and j in joins),
              None)
    if at is not None:
        beta = joins[at]
        which = "outside" if beta > 0 else "inside"
        who = "LinuxCNC" if toolpath.style == "linuxcnc" else toolpath.style
        return (f"{who} straight join at a {math.degrees(abs(beta)):.3g}-degree {which} corner "
                f"(turns under {LINUXCNC_CONCAVE_CORNER:g} rad are taken as straight on)")
    return CAUSE_WITHIN


#: The fields :func:`_with_causes` copies, in order (checked here: a field
#: added to :class:`Violation` must be copied there too).
_VIOLATION_FIELDS = ("kind", "depth", "tool_segment", "tool_block", "tool_role", "element",
                     "element_block", "witness_tool", "witness_contour", "basis", "detail")
if tuple(f.name for f in fields(Violation)) != _VIOLATION_FIELDS:
    raise ImportError("Violation's fields changed: update tolerance._with_causes")


def _with_causes(viol: list[Violation], toolpath: ToolPath) -> list[Violation]:
    """Each of ``viol`` with its cause (:func:`cause_of`) in its detail:
    ``dataclasses.replace`` field by field, done column by column
    (:meth:`Violation.many`: a long path has tens of thousands of warnings)."""
    if toolpath.meta.get(STRAIGHT_JOINS):
        causes = [cause_of(v, toolpath) for v in viol]
    else:
        causes = repeat(CAUSE_WITHIN)          # no straight join recorded: no other cause
    copied = [list(map(attrgetter(name), viol)) for name in _VIOLATION_FIELDS[:-1]]
    details = [{**v.detail, "cause": cause} for v, cause in zip(viol, causes)]
    return Violation.many(*copied, details)


def apply_tolerance(cert: Certificate, tolerance: float, toolpath: ToolPath) -> Certificate:
    """``cert`` with its violations no deeper than ``tolerance`` moved to
    ``warnings`` (each with its ``cause`` in ``detail``) and each check's
    verdict taken on the deeper ones only."""
    viol = cert.violations
    # the verdict of each violation in bulk (a long path has hundreds of
    # thousands of them): tolerated kind, finite depth, no deeper than the tolerance
    kinds = list(map(_KIND, viol))
    shallow = np.fromiter(map(_TOLERATED_KINDS.__contains__, kinds), bool, len(viol))
    # (the depths of the tolerated kinds only: the others' need not be numbers)
    depth = np.fromiter(map(_DEPTH, compress(viol, shallow.tolist())), float)
    shallow[shallow] = np.isfinite(depth) & (depth <= tolerance)
    deep = (~shallow).tolist()
    shallow = shallow.tolist()
    warn = _with_causes(list(compress(viol, shallow)), toolpath)
    keep = list(compress(viol, deep))
    checks = []
    warned, failed = Counter(compress(kinds, shallow)), Counter(compress(kinds, deep))
    for c in cert.checks:
        kind = TOLERATED.get(c.name)
        if kind is None:
            checks.append(c)
            continue
        n_warn, n_fail = warned[kind], failed[kind]
        # a check that failed without listing violations (none of its kind) keeps its verdict
        ok = c.ok or (n_fail == 0 and n_warn > 0)
        checks.append(replace(c, ok=ok, violations=n_fail,
                              detail={**c.detail, "warnings": n_warn, "tolerance": tolerance}))
    return replace(cert, ok=all(c.ok for c in checks), checks=tuple(checks),
                   violations=tuple(keep), warnings=tuple(warn), tolerance=tolerance)
