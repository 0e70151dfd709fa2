"""The command line's input and its settings, resolved once.

:func:`job` is how every command gets what it works on: the command line's
options become :class:`ccopt.cases.Overrides` and
:func:`ccopt.cases.resolve_input` applies them over the case's settings and
the defaults (the same resolution ``ccopt run`` and :mod:`ccopt.run` use).
"""
from __future__ import annotations

import argparse
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from ccopt.atomic import job_inputs, refuse_overwriting_inputs
from ccopt.cases import DEFAULT_LIMITS, LIMITS_FROM, Case, Job, Overrides, ReadOptions, resolve_input
from ccopt.cli.options import chosen_variants
from ccopt.cli.progress import stage_progress

if TYPE_CHECKING:  # annotations only
    from ccopt.feed.limits import AxisLimits
    from ccopt.program.model import Program

#: the command-line options (argparse dests) that are compensation style options of the same name
STYLE_OPTIONS = ("break_cos", "ccbuf")


def overrides(args: argparse.Namespace, **command) -> Overrides:
    """What ``args`` says about every input; a command without an option says
    nothing. ``command``: the :class:`Overrides` a command sets itself, not
    from an option (``ccopt run``'s planners)."""
    given = {name: getattr(args, name, None) for name in STYLE_OPTIONS}
    blend_options = {name: getattr(args, name) for name in ("lead_radius", "search")
                     if getattr(args, name, None) is not None}
    planners = [n for group in getattr(args, "planner", None) or () for n in group]
    variants = chosen_variants(args) if hasattr(args, "variants") else None
    settings = dict(
        style=getattr(args, "style", None), radius=getattr(args, "radius", None),
        side=getattr(args, "side", None), vmax=getattr(args, "vmax", None),
        amax=getattr(args, "amax", None), jmax=getattr(args, "jmax", None),
        delta=getattr(args, "delta", None), ts=getattr(args, "ts", None),
        tangential_acc=getattr(args, "tangential_acc", None),
        centripetal_acc=getattr(args, "centripetal_acc", None),
        junction_deviation=getattr(args, "junction_deviation", None),
        planners=tuple(planners) or None,
        tolerance=getattr(args, "tolerance", None), eps=getattr(args, "eps", None),
        limits_tol=getattr(args, "limits_tol", None),
        part_lines=getattr(args, "part_lines", None),
        toolpath=getattr(args, "toolpath", None),
        variants=tuple(variants) if variants else None,
        blend_options=blend_options,
        reading=ReadOptions(
            dialect=getattr(args, "dialect", None), tool_table=getattr(args, "tool_table", None),
            var_file=getattr(args, "var_file", None), units=getattr(args, "units", None),
            table_units=getattr(args, "table_units", None),
            sub_path=tuple(getattr(args, "sub_path", None) or ()),
            max_loop_iterations=getattr(args, "max_loop_iterations", None),
            ini=getattr(args, "ini", None)),
        style_options={k: v for k, v in given.items() if v is not None})
    settings.update(command)
    return Overrides(**settings)


def job(what: str | Case, args: argparse.Namespace, **command) -> Job:
    """The job for ``what`` (program file, case folder, bundled case name or
    case) with ``args``' overrides (and the ``command``'s own, see
    :func:`overrides`): every command resolves its settings by one rule
    (:func:`ccopt.cases.resolve_input`: the axis limits ``--vmax/--amax``, else
    the case's ``[limits]``, else :data:`ccopt.cases.DEFAULT_LIMITS`, which the
    output names)."""
    return resolve_input(what, overrides(args, **command), DEFAULT_LIMITS)


@contextmanager
def reading(args: argparse.Namespace, command: str,
            **settings) -> Iterator[tuple[Job, Program, object]]:
    """The preamble every command that works on one program shares: its
    stage progress (:func:`ccopt.cli.progress.stage_progress`), its :class:`Job`
    (:func:`job`) and the program read; yields ``(job, program, say)``, ``say``
    naming the next stage on the progress line, which closes on the way out
    (an error included). ``settings``: the command's own (:func:`overrides`)."""
    say = stage_progress(args, command)
    try:
        work = job(args.program, args, **settings)
        # -o must not name an input (the program, a link to it...): exit 2 before any work
        refuse_overwriting_inputs([getattr(args, "output", None)], job_inputs(work))
        say("read")
        yield work, work.read(), say
    finally:
        say.close()


def limits_text(limits: AxisLimits, work: Job) -> str:
    """``limits v=[...] a=[...] j=[...] (where they come from)``, as every
    command prints the limits it used (units of the program, per second)."""
    return limits_words(limits.to_json(), work.limits_from)


def limits_words(limits: dict, limits_from: str | None) -> str:
    """:func:`limits_text` of ``AxisLimits.to_json()`` and a ``Job.limits_from``."""
    jerk = f" j={list(limits['j'])}" if limits.get("j") is not None else ""
    note = LIMITS_FROM.get(limits_from or "", limits_from or "")
    return f"limits v={list(limits['v'])} a={list(limits['a'])}{jerk} ({note})"
