"""Each option's ``--help`` states its real default: the parser's own, or, for
an option whose parser default is "not given", the value the code applies
then (named below by where it is applied, and for the axis limits and the
gouge tolerance checked on a command's output)."""
from __future__ import annotations

import argparse
import math
import re

import pytest

from pathlib import Path

from cli_run import run_cli
from ccopt.cases import DEFAULT_LIMITS
from ccopt.cli import build_parser
from ccopt.export.arcfit import DEFAULT_TOL
from ccopt.feed.planners import DEFAULT_TS
from ccopt.program.gcode import MAX_LOOP_ITERATIONS
from ccopt.tolerances import GOUGE_TOLERANCE, PMAC_BREAK_COS
from ccopt_formulations.lead_timing import SEARCH_EVALUATIONS

POCKET = str(Path(__file__).resolve().parents[1] / "cases" / "pocket" / "pocket.nc")

#: the value applied when the option is not given (parser default None), for
#: options whose help states a number
APPLIED = {"max_loop_iterations": MAX_LOOP_ITERATIONS, "break_cos": PMAC_BREAK_COS,
           "ts": DEFAULT_TS, "tolerance": GOUGE_TOLERANCE["mm"], "tol": DEFAULT_TOL["mm"],
           "vmax": DEFAULT_LIMITS["v"][0], "amax": DEFAULT_LIMITS["a"][0],
           "search": SEARCH_EVALUATIONS}

# "default 0.001", "default: 0, ...", "default: the case's ..., else 100 per axis";
# not "default: 1% of the cutter radius" (a share, not a value)
_DOCUMENTED = re.compile(r"default:? (?:[^()]*?\belse )?(-?\d[\d.]*(?:e[+-]?\d+)?)(?![\d%])")


def _options() -> list:
    return list(_each_option())


def _each_option():
    parser, _ = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for command, p in sub.choices.items():
        for a in p._actions:
            if a.option_strings and a.help and a.help is not argparse.SUPPRESS \
                    and not isinstance(a, (argparse._HelpAction, argparse._VersionAction)):
                yield pytest.param(a, id=f"{command} {a.option_strings[-1]}")


@pytest.mark.parametrize("action", _options())
def test_documented_default_is_the_real_one(action):
    help_text = action.help.replace("%%", "%")
    m = _DOCUMENTED.search(help_text)
    given = action.default not in (None, False)
    if given:
        assert m, f"{action.option_strings}: the parser's default {action.default!r} " \
                  f"is not in its help {help_text!r}"
        assert math.isclose(float(m.group(1)), action.default), help_text
    elif m:
        assert action.dest in APPLIED, \
            f"{action.option_strings}: help states default {m.group(1)}; name what applies it"
        assert math.isclose(float(m.group(1)), APPLIED[action.dest]), help_text


def test_limits_applied_to_a_bare_program_are_the_documented_ones(capsys):
    # a bare G-code file (no case.toml): the limits the help names, said as default
    code, out, _ = run_cli(capsys, "feed", POCKET)
    assert code == 0
    assert "limits v=[100.0, 100.0, 100.0] a=[1000.0, 1000.0, 1000.0] (default:" in out


def test_gouge_tolerance_applied_is_the_documented_one(capsys):
    code, out, _ = run_cli(capsys, "verify", POCKET)
    assert code == 0 and "tolerance 0.001 mm" in out
