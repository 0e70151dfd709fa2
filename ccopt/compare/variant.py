"""One variant's row of the comparison: its blend solved, its path certified
and measured (:class:`VariantResult`).

:func:`solve` runs a blend on a :class:`~.contract.BlendProblem` and gives
its row with every figure but the cycle time (:func:`measure_shape`); the
cycle time joins it afterwards (:func:`with_duration`), planned under the
reference's stretch times (:mod:`.timing`) by :mod:`.schedule`, which hands
both parts of every variant to this process or to worker processes.
:func:`measure` does both at once for a path made elsewhere.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

from ccopt.compare.contract import BlendOutcome, BlendProblem, BlendRejected
from ccopt.compare.deviation import max_deviation
from ccopt.compare.figures import path_figures
from ccopt.compare.leads import lead_joins
from ccopt.compare.registry import load
from ccopt.compare.timing import StretchTimes, duration_figures
from ccopt.errors import CcoptError
from ccopt.toolpath import FITTED_PIECES, STRAIGHT_JOINS, ToolPath

#: Figures every listed variant has (``None`` when it has no tool path).
FIGURES = ("length", "max_curvature", "max_curvature_jump", "continuity", "path_continuity",
           "tangent_breaks", "duration", "duration_ratio", "max_acc_ratio", "min_clearance",
           "certified", "max_deviation", "max_deviation_bound", "solve_time")


@dataclass
class VariantResult:
    """One row of the comparison."""

    name: str
    status: str                     # ok | uncertified | refused | rejected | failed
    message: str | None = None
    toolpath: ToolPath | None = None
    certificate: object | None = None
    figures: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    #: The stretch times planned for this row's cycle time and not the
    #: reference's (:mod:`.timing`), or, for a row its blend timed
    #: (:attr:`timed_by_blend`), those of every stretch of its path: the
    #: plug-in blends solved from a controller row's path take them, so its
    #: stretches are planned once. Not reported.
    stretch_times: dict = field(default_factory=dict, repr=False, compare=False)
    #: Whether :attr:`stretch_times` are its blend's figures of every stretch
    #: of its path (:attr:`~.contract.BlendOutcome.stretch_times`): its cycle
    #: time is read off them (:func:`.schedule.run_jobs`). Not reported.
    timed_by_blend: bool = field(default=False, repr=False, compare=False)

    def __getitem__(self, key):
        return self.to_json()[key]

    def to_json(self) -> dict:
        out = {"name": self.name, "status": self.status, "message": self.message}
        for k in FIGURES:
            out[k] = self.figures.get(k)
        for k, v in self.figures.items():
            out.setdefault(k, v)
        if self.info:
            out["info"] = self.info
        return out


def measure(name: str, path: ToolPath, problem: BlendProblem, solve_time: float,
            info: dict | None = None, certificate=None,
            times: StretchTimes | None = None) -> VariantResult:
    """Certify, time and measure one variant's tool path (``times``: the
    reference's stretch times, :mod:`.timing`; ``None`` plans the whole path;
    the cycle time is :func:`.timing.duration_figures`)."""
    row = measure_shape(name, path, problem, solve_time, info, certificate)
    return with_duration(row, duration_figures(path, problem.limits, times))


def measure_shape(name: str, path: ToolPath, problem: BlendProblem, solve_time: float,
                  info: dict | None = None, certificate=None) -> VariantResult:
    """:func:`measure` but the cycle time: certificate, path figures, deviation
    from the reference (what needs no feed plan)."""
    cert = certificate if certificate is not None else problem.certify(path)
    fig = path_figures(path, lead_joins(path))
    if problem.reference is not None:
        dev, dev_bound = max_deviation(path, problem.measured_from)
    else:  # no reference to measure against (PMAC refused the program)
        dev = dev_bound = None
    gouge = cert.check("gouge")
    fig.update(min_clearance=cert.min_clearance, certified=bool(cert.ok),
               verdict=cert.verdict,
               clearance_ok=bool(gouge.ok), violations=len(cert.violations),
               max_deviation=dev, max_deviation_bound=dev_bound, solve_time=solve_time)
    status, message = ("ok", _warnings_note(cert)) if cert.ok else \
        ("uncertified", uncertified_reason(cert))
    return VariantResult(name, status, message, path, cert, fig, dict(info or {}))


def _warnings_note(cert) -> str | None:
    """``ok within tolerance: ...`` for a certified path with shallow violations
    the verifier lists as warnings (program units), else ``None``."""
    if not cert.warnings:
        return None
    v = max(cert.warnings, key=lambda v: v.depth)
    line = f" at line {v.tool_block}" if v.tool_block is not None else ""
    return (f"ok within tolerance: {len(cert.warnings)} warning(s), deepest {v.kind} "
            f"{v.depth:.3g}{line}")


def uncertified_reason(cert) -> str:
    """Why a row whose path the verifier did not certify is not ``ok``: the
    checks that failed and the deepest violation (program units for a
    gouge, side or gap; a ratio over the limit for the feed limits)."""
    failed = [c.name for c in cert.checks if not c.ok]
    text = f"not certified: {', '.join(failed) or 'a check'} failed"
    if cert.violations:
        v = max(cert.violations, key=lambda v: v.depth)
        line = f" at line {v.tool_block}" if v.tool_block is not None else ""
        text += f" (deepest: {v.kind} {v.depth:.3g}{line}, {len(cert.violations)} violation(s))"
    return text


def gets_cycle_time(row: VariantResult) -> bool:
    """Whether ``row`` gets a cycle time: it has a tool path (``ok`` or
    ``uncertified``; the time of an uncertified path is still a figure)."""
    return row.status in ("ok", "uncertified") and row.toolpath is not None


def with_duration(row: VariantResult, duration) -> VariantResult:
    """``row`` with a cycle time's ``(duration, max_acc_ratio, message)``
    (:func:`.timing.duration_figures`; the planner's refusal joins the row's
    own message, if any) and, as a fourth item when there is one, the stretch
    times planned for it (:attr:`VariantResult.stretch_times`)."""
    dur, acc_ratio, feed_msg = duration[:3]
    if len(duration) > 3:
        row.stretch_times = dict(duration[3])
    row.figures.update(duration=dur, max_acc_ratio=acc_ratio)
    if feed_msg:
        row.message = feed_msg if row.message is None else f"{row.message}; {feed_msg}"
    return row


def solve(name: str, problem: BlendProblem, measured: list | None = None) -> VariantResult:
    """The blend ``name`` on ``problem``, certified and measured but for its cycle
    time (:func:`measure_shape`); a blend that is refused, rejected or fails
    gives its row with the reason.

    ``measured``: rows measured before under the same problem (the same
    settings and reference; this call appends its own): a path equal to one
    of theirs takes that row's certificate and figures (:func:`measured_as`)
    instead of being certified and measured again (controller styles often
    leave the same path)."""
    t0 = time.perf_counter()
    try:
        blend = load(name)
        out = blend(problem)
    except BlendRejected as exc:
        return VariantResult(name, "rejected", str(exc),
                             figures={"solve_time": time.perf_counter() - t0})
    except CcoptError as exc:
        return VariantResult(name, "refused", str(exc),
                             figures={"solve_time": time.perf_counter() - t0})
    except Exception as exc:  # a plug-in's bug must not hide the other variants
        return VariantResult(name, "failed", f"{type(exc).__name__}: {exc}",
                             figures={"solve_time": time.perf_counter() - t0})
    seconds = time.perf_counter() - t0
    info: dict = {}
    cert = None
    stretch_times = None
    if isinstance(out, BlendOutcome):
        info = dict(out.info)
        cert = info.pop("certificate", None)
        stretch_times = out.stretch_times
        out = out.toolpath
    if not isinstance(out, ToolPath):
        return VariantResult(name, "failed", f"blend returned {type(out).__name__}, "
                             "not a ToolPath or BlendOutcome", figures={"solve_time": seconds})
    twin = measured_as(measured, out) if measured is not None else None
    if twin is not None:
        row = VariantResult(name, twin.status, twin.message, out, twin.certificate,
                            {**twin.figures, "solve_time": seconds}, info)
    else:
        row = measure_shape(name, out, problem, seconds, info, cert)
        if measured is not None:
            measured.append(row)
    if stretch_times:
        row.stretch_times = dict(stretch_times)
        row.timed_by_blend = True
    return row


def measured_as(measured: list, path: ToolPath) -> VariantResult | None:
    """The row of ``measured`` (rows measured under one problem) whose path
    is measured as ``path`` is (:func:`measured_alike`), or None: its
    certificate and figures are this path's."""
    return next((row for row in measured if measured_alike(row.toolpath, path)), None)


#: The entries of a tool path's ``meta`` that its certificate and figures read:
#: the fitted pieces (the contact check), the straight joins (the cause of a
#: tolerated violation) and the blend joins (:func:`~.leads.lead_joins`).
MEASURED_META = (FITTED_PIECES, STRAIGHT_JOINS, "joins")


def measured_alike(a: ToolPath, b: ToolPath) -> bool:
    """Whether :func:`measure_shape` gives ``a`` and ``b`` the same certificate
    and figures: the same segments (blocks too: the certificate names their
    lines), plane, radius, dwells and units, the same
    :data:`MEASURED_META` entries, and the same style where the certificate
    names it (a tolerated violation's cause at a straight join); two
    controller styles often leave the same path."""
    if a is b:
        return True
    if (a.segments, a.plane, a.radius, a.dwells, a.units) != \
            (b.segments, b.plane, b.radius, b.dwells, b.units):
        return False
    if any(a.meta.get(k) != b.meta.get(k) for k in MEASURED_META):
        return False
    return a.style == b.style or not a.meta.get(STRAIGHT_JOINS)
