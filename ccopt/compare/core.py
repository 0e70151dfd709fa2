"""``compare``: every variant of one program, with the same figures.

For each variant: build its tool path (timed: ``solve_time``), certify it
with :func:`ccopt.verify.verify` against the program's contour, plan its feed
under the same limits, with TOPPRA, or with the jerk planner when the limits
carry jerk (``max_acc_ratio`` is the largest axis acceleration over its limit
in the profile sampled every 0.2 ms; the feed grid follows the turning inside
blend curves, :mod:`ccopt.feed.grid`), and measure it (:mod:`.figures`)
against the reference, PMAC's path. A row is ``ok`` only when the verifier
certifies its path; a path it does not certify is ``uncertified``, with its
figures and why. A variant that a controller refuses (``refused``), that
cannot be built or certified (``rejected``) or that fails unexpectedly
(``failed``) is still listed, with the reason and no figures.

The reference is planned once, whole; a variant's cycle time reuses the
reference's time on every stretch between two stops that it shares and
plans only the stretches it changed (:mod:`.timing`, where the rule and why
it is exact are); variants that build the same tool path are timed once.
``workers > 1`` runs the variants in that many worker
processes (:mod:`.schedule`); the rows are the same as a serial run's (each
variant starts from the reference's stretch times alone), ``solve_time``
aside. The controller styles run first; the built-in leads then run beside
the plug-in blends, which start from the fastest certified controller
variant's path (:mod:`.baseline`) and so wait for the controllers alone.
A row is made in :mod:`.variant`; blends implement :mod:`.contract`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Callable

from ccopt.compare.baseline import apply_baseline, base_row, from_base
from ccopt.compare.contract import BUILTIN_NAMES, CONTROLLER_NAMES, BlendProblem
from ccopt.compare.registry import available, load, preload
from ccopt.compare.schedule import run_jobs, say
from ccopt.compare.timing import (StretchTimes, duration_figures, reference_times, same_plan,
                                  stretch_keys, timed_alike)
from ccopt.compare.variant import VariantResult, measure
from ccopt.compensate import compensate
from ccopt.errors import CcoptError
from ccopt.feed import certified_planner
from ccopt.feed.limits import AxisLimits
from ccopt.program.model import Program
from ccopt.toolpath import ToolPath

if TYPE_CHECKING:  # pragma: no cover
    from ccopt.feed.profile import FeedProfile

REFERENCE = "pmac"


@dataclass
class Comparison:
    """Rows in variant order; iterable. ``reference`` is PMAC's path."""

    variants: list[VariantResult]
    reference: ToolPath | None
    limits: AxisLimits | None
    program: Program

    def __iter__(self):
        return iter(self.variants)

    def __len__(self):
        return len(self.variants)

    def __getitem__(self, name: str) -> VariantResult:
        for v in self.variants:
            if v.name == name:
                return v
        raise KeyError(name)

    def to_json(self) -> dict:
        return {"program": self.program.file,
                "radius": self.reference.radius if self.reference is not None else None,
                "units": self.program.units,
                "limits": self.limits.to_json() if self.limits is not None else None,
                "reference": REFERENCE,
                "planner": certified_planner(self.limits) if self.limits is not None else None,
                "variants": [v.to_json() for v in self.variants]}


@dataclass(frozen=True)
class GivenReference:
    """PMAC's path of the program as the caller made it (``ccopt run``'s
    pipeline, when the job's own path is PMAC's): ``path``, the ``seconds``
    compensating it took, and ``profile``, its whole-path feed plan under the
    comparison's limits and :func:`~ccopt.feed.certified_planner` when the
    caller has one (``None``: planned here). The comparison takes it as its
    reference instead of compensating the program again."""

    path: ToolPath
    seconds: float = 0.0
    profile: FeedProfile | None = None


def compare(program: Program, variants=None, *, limits: AxisLimits | None = None,
            delta: float | None = None, radius: float | None = None, side=None,
            options: dict | None = None, workers: int = 1,
            progress: Callable[[str], None] | None = None, ts: float | None = None,
            reference: GivenReference | None = None,
            tolerance: float | None = None) -> Comparison:
    """Compare lead-in/lead-out/corner variants of ``program``.

    Parameters
    ----------
    variants: names (default: every available one, :func:`available`).
    limits: machine limits for the cycle time (``None``: no durations); with
        jerk limits (``limits.j``) cycle times are the jerk planner's.
    delta: the smoother's tolerance band (default 1 % of the cutter radius).
    radius, side: compensation overrides, as for :func:`ccopt.compensate`.
    options: blend options (e.g. ``lead_radius`` for the geometric leads).
    workers: worker processes for the variants (1: all in this process); the
        rows are the same either way, ``solve_time`` aside.
    progress: called with a short line as the work goes ("variant 3/10
        opt-casadi"; in this process also "opt-casadi: blend 2/6").
    ts: the jerk planner's interpolation period (s; None: its default, 1 ms).
    reference: PMAC's path (and its plan) when the caller has made it already
        (:class:`GivenReference`; it must be PMAC's path of ``program`` with
        ``radius`` and ``side``); its plan is used only when it is the plan
        this would make (:func:`.timing.same_plan`: these limits, their
        planner and ``ts``), else the path is planned here.
    tolerance: the verifier's gouge tolerance (program units; ``None``: its
        default), as for :func:`ccopt.verify.verify`.

    A row is ``ok`` only when its path is certified; a path the verifier does
    not certify is ``uncertified``, with its figures and why (``message``).
    """
    names = list(variants) if variants else available()
    ref = _Reference.of(program, radius, side, limits, ts, reference)
    settings = (limits, delta, dict(options or {}), radius, side, None, tolerance, ts)
    problem = BlendProblem(program, ref.path, *settings) if ref.path is not None else None
    rows, jobs, ref_index = _jobs(names, program, problem, ref.error, settings)

    def reference_row(times: StretchTimes | None):
        """The reference's row (it is the first variant that reports)."""
        if ref_index is None:
            return []
        say(progress, f"variant {ref_index + 1}/{len(names)} {REFERENCE}")
        return [(ref_index, measure(REFERENCE, ref.path, problem, ref.seconds, times=times))]

    # the controllers first; the plug-in blends then start from the fastest
    # certified controller variant's path (issue 30), beside the built-in leads
    memo: dict = {"jobs": len(jobs)}
    first = [job for job in jobs if job[1] in CONTROLLER_NAMES]
    later = [job for job in jobs if job[1] not in BUILTIN_NAMES]
    plugin_names = tuple(job[1] for job in later)
    for i, row in run_jobs(first, ref, reference_row, len(names), workers, progress,
                           memo=memo, prepare=lambda: preload(plugin_names)):
        rows[i] = row
    leads = _with_stretch_times(
        [job for job in jobs if job[1] in BUILTIN_NAMES and job[1] not in CONTROLLER_NAMES],
        ref, memo, rows)
    base = base_row(rows, REFERENCE) if limits is not None and problem is not None else None
    later, later_ref = _from_base(later, base, problem, ref,
                                  rows[ref_index] if ref_index is not None else None)
    later = _with_alternatives(later, rows, later_ref.times())
    plugins = {i for i, _, _ in later}
    for i, row in run_jobs(leads + later, ref, lambda _: [], len(names), workers, progress,
                           refs={i: later_ref for i in plugins}, memo=memo):
        started = base is not None or row.info.get("started_from") is not None
        rows[i] = from_base(row, base.name if base is not None else REFERENCE) \
            if i in plugins and started else row
    ref_duration = rows[ref_index].figures.get("duration") if ref_index is not None else None
    if ref_duration is None and problem is not None and limits is not None:
        ref_duration = duration_figures(ref.path, limits, ref.times())[0]
    for row in rows:
        d = row.figures.get("duration")
        if d is not None and ref_duration:
            row.figures["duration_ratio"] = d / ref_duration
    if limits is not None and problem is not None:
        apply_baseline(rows, REFERENCE)
    return Comparison(rows, ref.path, limits, program)


def _with_stretch_times(jobs, ref: "_Reference", memo: dict, rows):
    """``jobs`` whose problems carry the stretch times planned by now
    (:attr:`~.contract.BlendProblem.stretch_times`): the reference's, and the
    ``siemens`` row's own (the SINUMERIK families start from that path, and
    would plan the very same stretches again); a problem's measured rows
    (:func:`.schedule.run_jobs`'s ``memo``) stay its own."""
    times = ref.times()
    if times is None:
        return jobs
    siemens = next((r for r in rows if r is not None and r.name == "siemens"), None)
    if siemens is not None and siemens.stretch_times:
        times = ref.with_stretches(siemens.stretch_times).times()
    made: dict = {}
    out = []
    for i, name, problem in jobs:
        if id(problem) not in made:
            made[id(problem)] = replace(problem, stretch_times=times)
            memo[("measured", id(made[id(problem)]))] = memo.setdefault(
                ("measured", id(problem)), [])
        out.append((i, name, made[id(problem)]))
    return out


def _with_alternatives(later, rows, times: StretchTimes | None):
    """The plug-in jobs ``later`` with the other certified, timed controller
    variants their blends may start from
    (:attr:`~.contract.BlendProblem.alternatives`: one of each path the
    planners time alike, none timed alike with the job's own start) and the
    stretch times the comparison times them with (``times``)."""
    out = []
    for i, name, problem in later:
        if problem is None:
            out.append((i, name, problem))
            continue
        seen = [problem.reference]
        alternatives = []
        for row in rows:
            if row is None or row.name not in CONTROLLER_NAMES or row.status != "ok" \
                    or row.figures.get("duration") is None or row.toolpath is None \
                    or any(timed_alike(row.toolpath, p) for p in seen):
                continue
            seen.append(row.toolpath)
            alternatives.append((row.name, row.toolpath, row.certificate))
        out.append((i, name, replace(problem, alternatives=tuple(alternatives),
                                     stretch_times=times)))
    return out


def _from_base(later, base, problem: BlendProblem | None, ref: "_Reference", ref_row):
    """``(jobs, timing reference)`` of the plug-in blends ``later``: solved from
    the fastest certified controller variant's path (``base``'s row, when it is
    not PMAC's) and timed with its stretch times (each of its stretches is
    planned once, not once per plug-in); else from PMAC's path, with its row's
    certificate (``ref_row``), which says whether anything outside their reach
    keeps them from being certified."""
    if base is not None:
        return ([(i, name, replace(problem, reference=base.toolpath,
                                   deviation_from=problem.reference,
                                   reference_certificate=base.certificate))
                 for i, name, _ in later], ref.with_stretches(base.stretch_times))
    if ref_row is not None:
        later = [(i, name, replace(problem, reference_certificate=ref_row.certificate))
                 for i, name, _ in later]
    return later, ref


@dataclass
class _Reference:
    """PMAC's path of the program (``None`` with the ``error`` when PMAC refuses
    it), the seconds its compensation took, and its stretch times, planned
    when first asked (:meth:`times`): in a parallel comparison while the
    workers solve the blends (freeform-hsm's reference takes about 2 s)."""

    path: ToolPath | None
    error: str | None
    seconds: float
    limits: AxisLimits | None
    ts: float | None
    profile: FeedProfile | None           # the caller's plan of it, if any
    _times: list = field(default_factory=list)
    _keys: list = field(default_factory=list)   # [its stretch keys], once asked

    @classmethod
    def of(cls, program: Program, radius, side, limits, ts,
           given: GivenReference | None = None) -> "_Reference":
        """PMAC's path of ``program``: the caller's (``given``) or compensated here."""
        if given is not None:
            return cls(given.path, None, given.seconds, limits, ts, given.profile)
        t0 = time.perf_counter()
        try:
            path, error = compensate(program, REFERENCE, radius=radius, side=side), None
        except CcoptError as exc:
            path, error = None, str(exc)
        return cls(path, error, time.perf_counter() - t0, limits, ts, None)

    def times(self) -> StretchTimes | None:
        """:func:`.timing.reference_times`, once; with no reference (refused) an empty
        :class:`StretchTimes`, so each path is planned whole with ``ts``."""
        if not self._times:
            if self.path is None:
                self._times.append(None if self.limits is None
                                   else StretchTimes(self.limits, ts=self.ts))
            else:
                planned = self.profile if same_plan(self.profile, self.path, self.limits,
                                                    self.ts) else None
                self._times.append(reference_times(self.path, self.limits, self.ts, planned))
        return self._times[0]

    def planned(self) -> bool:
        """Whether :meth:`times` has been computed (it then returns at once)."""
        return bool(self._times)

    def with_stretches(self, extra: dict) -> "_Reference":
        """This reference whose stretch times (:meth:`times`) also hold ``extra``
        (key -> ``(seconds, max_acc_ratio)``, e.g. another row's,
        :attr:`.variant.VariantResult.stretch_times`)."""
        times = self.times()
        if times is None or not extra:
            return self
        merged = StretchTimes(times.limits, {**times.known, **extra}, times.ts)
        return replace(self, _times=[merged], _keys=list(self._keys))

    def keys(self) -> frozenset:
        """The reference's stretch keys (:func:`.timing.stretch_keys`; none
        without a reference or limits): a cycle time planned before the
        reference leaves these stretches to its plan."""
        if not self._keys:
            self._keys.append(frozenset() if self.path is None or self.limits is None
                              else frozenset(stretch_keys(self.path)) - {None})
        return self._keys[0]


def _jobs(names: list[str], program: Program, problem: BlendProblem | None,
          ref_error: str | None, settings: tuple):
    """``(rows, jobs, ref_index)``: the rows known without work (unknown names,
    refusals for want of a reference), the jobs ``(index, name, problem)`` and
    the reference's index in ``names`` (None when absent or refused).
    ``settings``: ``(limits, delta, options, radius, side, progress, tolerance)``
    of a problem without reference."""
    known = set(available())
    rows: list[VariantResult | None] = [None] * len(names)
    jobs: list[tuple[int, str, BlendProblem]] = []
    ref_index = None
    for i, name in enumerate(names):
        if name not in known:
            rows[i] = VariantResult(name, "failed", f"unknown variant {name!r}; known: "
                                    f"{', '.join(sorted(known))}")
        elif problem is None:
            if name == REFERENCE:
                rows[i] = VariantResult(name, "refused", ref_error)
            elif getattr(load(name), "compensates", False):
                # another controller style needs no reference: it may accept the program
                jobs.append((i, name, BlendProblem(program, None, *settings)))
            else:
                rows[i] = VariantResult(name, "failed", f"no reference path: {ref_error}")
        elif name == REFERENCE:
            ref_index = i
        else:
            jobs.append((i, name, problem))
    return rows, jobs, ref_index
