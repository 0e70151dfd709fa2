"""The command line's input and its settings, resolved once.

:func:`job` is how every command gets what it works on: the command line's
options become :class:`ccopt.cases.Overrides` and
:func:`ccopt.cases.resolve_input` applies them over the case's settings and
the defaults (the same resolution ``ccopt run`` and :mod:`ccopt.run` use).
"""
from __future__ import annotations

import argparse

from ccopt.cases import DEFAULT_LIMITS, Case, Job, Overrides, ReadOptions, resolve_input

#: the command-line options (argparse dests) that are compensation style options of the same name
STYLE_OPTIONS = ("break_cos", "ccbuf")


def overrides(args: argparse.Namespace) -> Overrides:
    """What ``args`` says about every input; a command without an option says nothing."""
    given = {name: getattr(args, name, None) for name in STYLE_OPTIONS}
    return Overrides(
        style=getattr(args, "style", None), radius=getattr(args, "radius", None),
        side=getattr(args, "side", None), vmax=getattr(args, "vmax", None),
        amax=getattr(args, "amax", None), jmax=getattr(args, "jmax", None),
        delta=getattr(args, "delta", None), ts=getattr(args, "ts", None),
        reading=ReadOptions(
            dialect=getattr(args, "dialect", None), tool_table=getattr(args, "tool_table", None),
            var_file=getattr(args, "var_file", None), units=getattr(args, "units", None),
            table_units=getattr(args, "table_units", None),
            sub_path=tuple(getattr(args, "sub_path", None) or ()),
            max_loop_iterations=getattr(args, "max_loop_iterations", None)),
        style_options={k: v for k, v in given.items() if v is not None})


def job(what: str | Case, args: argparse.Namespace,
        default_limits: dict | None = DEFAULT_LIMITS) -> Job:
    """The job for ``what`` (program file, case folder, bundled case name or
    case) with ``args``' overrides; ``default_limits`` as in
    :func:`ccopt.cases.resolve_input`: every command resolves the axis limits
    by one rule (``--vmax/--amax``, else the case's ``[limits]``, else
    :data:`ccopt.cases.DEFAULT_LIMITS`, which the output names)."""
    return resolve_input(what, overrides(args), default_limits)
