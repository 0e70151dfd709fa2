"""The blend contract: what a plug-in blend gets, gives back, and how it is found.

A blend is a callable ``blend(problem: BlendProblem) -> ToolPath | BlendOutcome``
(:data:`Blend`). It receives the program, PMAC's compensated path (the
*reference*), the contour the verifier checks against, the machine limits and
the options; it returns the whole tool path of its variant. Optimised blends
call :meth:`BlendProblem.accept` on their result: a blend is accepted only when
the verifier certifies the segments it made (clearance between samples too),
else :class:`BlendRejected` is raised.

Registration: any package adds a blend with one entry point in the group
:data:`ENTRY_POINT_GROUP`::

    [project.entry-points."ccopt.blends"]
    my-blend = "my_package.my_module:my_blend"

An entry point may not take a built-in name (:data:`BUILTIN_NAMES`);
:func:`blend_entry_points` discovers them. The catalogue of every variant,
built-in ones included, is :mod:`ccopt.compare.registry`. The Bezier
mathematics optimised blends share (G2 end conditions, energies, time models)
is in :mod:`ccopt.geometry.bezier`.
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field, replace
from functools import cached_property
from importlib.metadata import EntryPoint, entry_points
from typing import Any, Callable, Mapping

import numpy as np

from ccopt.compare.leads import Lead, find_leads
from ccopt.feed.limits import AxisLimits
from ccopt.program.model import Program
from ccopt.sides import side_sign
from ccopt.toolpath import ToolPath
from ccopt.verify import Certificate, contour_of, verify
from ccopt.verify.planes import plane_runs


class BlendRejected(RuntimeError):
    """A blend could not be made or was not certified (the message says why)."""


@dataclass(frozen=True)
class BlendOutcome:
    """A blend's tool path and what it wants reported (solver, iterations, ...)."""

    toolpath: ToolPath
    info: dict = field(default_factory=dict)
    #: ``stretch key -> (seconds, max_acc_ratio)`` of every stretch of
    #: ``toolpath`` as the blend timed it, starting from the problem's
    #: :attr:`BlendProblem.stretch_times` (:mod:`.timing`): the row's cycle time
    #: is read off them, the figure the blend chose by, not planned again.
    #: ``None``: the comparison times the path.
    stretch_times: dict | None = None


@dataclass(frozen=True, eq=False)
class BlendProblem:
    """Everything a blend may use.

    Attributes
    ----------
    program: the part program.
    reference: PMAC's compensated path of it (the comparison's reference;
        ``None`` only for controller styles run when PMAC refused the program).
    limits: machine limits (``None`` when none were given; blends that
        optimise time then assume :data:`DEFAULT_ACC` and the programmed feed).
    delta: tolerance band of the smoother (program units); ``None`` means 1 %
        of the cutter radius.
    options: blend options by name (e.g. ``lead_radius``).
    radius, side: the compensation overrides the reference was made with.
    progress: called with a short line as a blend goes (:meth:`report`);
        ``None`` (the default, and in worker processes): silent.
    tolerance: the verifier's gouge tolerance, program units (``None``: its
        default), as the job that asked for the comparison has it.
    ts: the jerk planner's interpolation period (s; ``None``: its default), as
        the comparison times the variants with it.
    deviation_from: the path every row's deviation is measured from when the
        blend starts from another controller's path (``reference`` is then
        that path); ``None``: ``reference`` itself.
    reference_certificate: the verifier's certificate of ``reference`` when the
        comparison has it already (its row's); ``None``: made when asked
        (:meth:`reference_verdict`).
    stretch_times: the stretch times the comparison has planned by now (a
        :class:`~ccopt.compare.timing.StretchTimes`, not to be changed: copy
        it): the reference's, with those its controller rows planned for their
        own paths as it times them (so far the ``siemens`` row's), for a blend
        that times its candidates by stretches as the comparison times its
        rows; ``None``: not planned.
    alternatives: the other certified controller variants a blend may start
        from instead of ``reference``: ``(name, path, certificate)`` each, of
        the paths the planners do not time alike with ``reference`` (the
        smoother starts from LinuxCNC's too, :mod:`ccopt_formulations.smoother`);
        a blend that does says so (``info["started_from"]``).
    """

    program: Program
    reference: ToolPath
    limits: AxisLimits | None = None
    delta: float | None = None
    options: Mapping[str, Any] = field(default_factory=dict)
    radius: float | None = None
    side: Any = None
    progress: Callable[[str], None] | None = None
    tolerance: float | None = None
    ts: float | None = None
    deviation_from: ToolPath | None = None
    reference_certificate: Certificate | None = None
    stretch_times: Any = None
    alternatives: tuple = ()

    def report(self, line: str) -> None:
        """Pass ``line`` (e.g. "blend 2/6") to :attr:`progress`, if any."""
        if self.progress is not None:
            self.progress(line)

    @property
    def cutter_radius(self) -> float:
        return float(self.reference.radius)

    @property
    def measured_from(self) -> ToolPath:
        """The path the deviation figures are measured from (:attr:`deviation_from`)."""
        return self.deviation_from if self.deviation_from is not None else self.reference

    @property
    def band(self) -> float:
        """The smoother's tolerance band: ``delta`` or 1 % of the cutter radius."""
        return float(self.delta) if self.delta is not None else 0.01 * self.cutter_radius

    @cached_property
    def contour(self):
        """The verifier's contour of the program (:func:`ccopt.verify.contour_of`)."""
        return contour_of(self.program, radius=self.radius, side=side_sign(self.side),
                          toolpath_radius=self.reference.radius if self.radius is None else None)

    def acc(self) -> np.ndarray:
        """In-plane axis acceleration limits ``(a_u, a_v)`` used by the time models."""
        if self.limits is None:
            return np.array([DEFAULT_ACC, DEFAULT_ACC])
        _, a = self.limits.in_plane(self.reference.plane, 2)
        return np.asarray(a, float)

    def leads(self) -> list[Lead]:
        """The reference's lead-ins and lead-outs (:func:`ccopt.compare.leads.find_leads`)."""
        return find_leads(self.reference)

    def certify(self, toolpath: ToolPath) -> Certificate:
        """The verifier's certificate of ``toolpath`` against the program (with
        the job's ``tolerance`` when it names one)."""
        given = {} if self.tolerance is None else {"tolerance": self.tolerance}
        return verify(toolpath, self.program, radius=self.radius, side=self.side, **given)

    @cached_property
    def reference_verdict(self) -> Certificate:
        """The certificate of :attr:`reference`: the one the comparison gave
        (:attr:`reference_certificate`), else made here once."""
        if self.reference_certificate is not None:
            return self.reference_certificate
        return self.certify(self.reference)

    def accept(self, toolpath: ToolPath, segments) -> Certificate:
        """Certify ``toolpath``; :class:`BlendRejected` when a gouge, gap or side
        violation lies on one of ``segments`` (indices of the segments the blend
        made or trimmed). Returns the certificate."""
        cert = self.certify(toolpath)
        _reject_on(cert, set(int(i) for i in segments), 0)
        return cert

    def check(self, toolpath: ToolPath, segments) -> None:
        """:meth:`accept`'s verdict without the certificate of the whole path:
        only the segments from the one before the first of ``segments`` to the
        one after the last are certified (each against the whole contour), so
        every pair of tool segment and contour element, every segment's side
        and every joint that involves ``segments`` is checked as :meth:`accept`
        checks it, at a few segments' cost instead of the whole path's (a lead
        blend changes one or two segments; the optimised leads certified the
        whole path once per lead: 2.4 s of each Fagor case's comparison). A
        program in several planes is certified whole (:meth:`accept`).
        Raises :class:`BlendRejected`; returns nothing."""
        mine = sorted(set(int(i) for i in segments))
        if not mine or plane_runs(toolpath, self.program) is not None:
            self.accept(toolpath, mine)
            return
        lo, hi = max(mine[0] - 1, 0), min(mine[-1] + 2, len(toolpath.segments))
        part = replace(toolpath, segments=toolpath.segments[lo:hi], dwells=())
        _reject_on(self.certify(part), set(mine), lo)


def deepest(violations) -> str:
    """The deepest of ``violations`` in words: ``"gouge 0.25 at line 10"``
    (its kind, depth in program units, and program line when known)."""
    v = max(violations, key=lambda v: v.depth)
    at = f" at line {v.tool_block}" if v.tool_block is not None else ""
    return f"{v.kind} {v.depth:.3g}{at}"


def _reject_on(cert: Certificate, mine: set[int], offset: int) -> None:
    """:class:`BlendRejected` when ``cert`` (of a path whose segment 0 is
    segment ``offset`` of the whole) has a gouge, gap or side violation on one
    of the segments ``mine`` (whole-path indices)."""
    bad = [v for v in cert.violations
           if v.kind in ("gouge", "gap", "side") and v.tool_segment + offset in mine]
    if bad:
        v = max(bad, key=lambda v: v.depth)
        raise BlendRejected(f"verifier: {v.kind} of depth {v.depth:.3g} on blend segment "
                            f"{v.tool_segment + offset} ({len(bad)} violation(s))")


#: Acceleration assumed by time proxies when no limits are given (units/s^2).
DEFAULT_ACC = 1000.0


#: What a plug-in implements: the whole tool path of its variant, or it with a report.
#: A blend may carry an attribute ``imports``: a callable (no arguments) that
#: imports what the blend imports only when it runs (a solver library its
#: module defers, such as cvxpy, half a second). A parallel comparison calls
#: it in its own process while the controller variants run, before it forks
#: the workers that solve the blends (:func:`ccopt.compare.registry.preload`),
#: so that no worker imports the library again.
Blend = Callable[[BlendProblem], "ToolPath | BlendOutcome"]


# --------------------------------------------------------------------------- registration

#: The entry-point group plug-in blends register in.
ENTRY_POINT_GROUP = "ccopt.blends"

#: The variants built into ccopt (:mod:`ccopt.compare.registry`); an entry point
#: of one of these names is ignored.
#: The SINUMERIK 840D style as the program asks (``siemens``) and its approach
#: families (:mod:`ccopt.compare.siemens_leads`).
SIEMENS_NAMES = ("siemens", "siemens-norm", "siemens-kont", "siemens-g147", "siemens-g247",
                 "siemens-g347")
BUILTIN_NAMES = ("pmac", "linuxcnc", "fagor-g138", "fagor-g139-g136", "fagor-g139-g137",
                 "heidenhain", "tangent-arc", "line-arc", "heidenhain-lt", "heidenhain-ln",
                 "heidenhain-ct", "heidenhain-lct") + SIEMENS_NAMES
#: The lead families: each searches a parameter set (every member compensated,
#: certified and timed) for the fastest certified member. ``ccopt compare``
#: runs them by default, the main job (``ccopt run``) on demand
#: (:func:`ccopt.compare.registry.main_job_variants`).
LEAD_FAMILY_NAMES = ("heidenhain-lt", "heidenhain-ln", "heidenhain-ct", "heidenhain-lct",
                     "siemens-norm", "siemens-kont", "siemens-g147", "siemens-g247",
                     "siemens-g347")
#: The built-in variants that are a controller's own program-following path
#: (the others are geometric leads, or lead families with a chosen
#: parameter): the baselines an optimised blend must beat. ``siemens`` among
#: them: on a SINUMERIK program with a smooth approach (G247 ... G248) its
#: path is the controller's own and can be the fastest of all (0.69 % faster
#: than LinuxCNC's on a generated plate, tests/family_programs.py seed 8).
CONTROLLER_NAMES = BUILTIN_NAMES[:6] + ("siemens",)


def blend_entry_points() -> dict[str, EntryPoint]:
    """Entry points of group ``ccopt.blends`` by name (the first of a name wins).

    Found once per state of the places distributions are found in
    (:func:`_where_distributions_are`): the main job asks for every variant
    of every case, and each search reads every installed distribution's
    metadata."""
    where = _where_distributions_are()
    if _FOUND.get("where") != where:
        out: dict[str, EntryPoint] = {}
        for ep in entry_points(group=ENTRY_POINT_GROUP):
            if ep.name not in BUILTIN_NAMES:
                out.setdefault(ep.name, ep)
        _FOUND.update(where=where, eps=out)
    return dict(_FOUND["eps"])


#: The last search of :func:`blend_entry_points`: ``where`` it looked, the ``eps`` it found.
_FOUND: dict = {}


def _where_distributions_are() -> tuple:
    """What a search for entry points depends on: the finders, the current
    folder (``""`` on ``sys.path``) and each ``sys.path`` folder with its
    modification time (ns; a distribution installed or removed there changes
    it; ``None``: not a folder)."""
    def stamp(entry: str):
        try:
            return os.stat(entry or ".").st_mtime_ns
        except (OSError, TypeError, ValueError):
            return None
    return (tuple(map(id, sys.meta_path)), os.getcwd(),
            tuple((entry, stamp(entry)) for entry in sys.path))
