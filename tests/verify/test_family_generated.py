"""Generated SINUMERIK and HEIDENHAIN plates (issue 32): read, compensated in
every controller family's style, certified, exported and read back.

Two kinds of program, both from :mod:`cam_programs`' plates (rectangles and
star-shaped polygons with fillets, entered mid-edge or at a corner, cut
either way, radii 0.5-5 mm, 3, 4 or 6 decimals):

- as CAM posts write them for the controller (:func:`cam_programs.cam_program`
  with ``dialect="sinumerik"`` or ``"heidenhain"``: ``G41``/``G42`` or
  ``RL``/``RR`` on a straight approach, the leads written as moves);
- entered and left by the controller's own lead moves
  (:func:`family_programs.family_program`: ``G147``/``G247``/``G347`` with
  ``DISR`` and their retractions; ``APPR``/``DEP`` ``LN``, ``CT``, ``LCT``,
  ``LT``), and on odd seeds every arc in a form drawn from the dialect's
  (``CR=``, ``CIP``, ``I=AC() J=AC()``; ``CR ... R DR``, ``CC`` + ``CP IPA``)
  and the SINUMERIK approach's ``G140``-``G143`` and ``G340``/``G341`` with
  ``DISCL`` and ``FAD`` (the tool coming down in the approach).

Properties, each figure from the construction, not from the verifier:

- in each of the four styles ``pmac``, ``linuxcnc``, ``siemens`` and
  ``heidenhain`` (any style compensates any program ccopt reads) the path
  is certified: ok, its warnings no deeper than the written resolution
  ``10**-decimals`` (or a LinuxCNC straight join), and the part the verifier
  takes is exactly the contour lines the generator wrote (the leads, the
  controller's own included, are air). One exception, LinuxCNC's own rule: a
  ``DEP LN`` leaves toward the tool side, an inside corner for a style that
  keeps compensating the departure as a contour element; when the move
  before it is shorter than the radius, LinuxCNC refuses the program with
  its concave-corner error, located at the departure's line;
- a contour edge dented 0.01 into the part fails by at least 0.01 less the
  resolution, in the dialect's own style;
- the dialect's own style's path exports to G-code and to a PMAC program
  that read back within the export tolerance and certified.

Quick tier: a few fixed programs; slow tier: 60 seeds of each kind and dialect.
"""
from __future__ import annotations

import pytest

from cam_programs import cam_program
from ccopt.compensate import compensate
from ccopt.errors import CompensationError
from ccopt.export import export
from ccopt.program import read_text
from ccopt.verify import verify
from family_programs import (HEIDENHAIN_IN, HEIDENHAIN_OUT, SINUMERIK_IN, SINUMERIK_OUT,
                             family_program)

STYLES = ("pmac", "linuxcnc", "siemens", "heidenhain")
OWN_STYLE = {"sinumerik": "siemens", "heidenhain": "heidenhain"}
DENT = 0.01
QUICK = (0, 9, 23, 36, 48)
SLOW = range(100, 160)


def _program(seed: int, dialect: str, native: bool):
    """``(program, generated program, dented text or None)``."""
    if native:
        # odd seeds: each arc in a form drawn from family_programs.ARC_FORMS
        fp = family_program(seed, dialect, arc_forms=seed % 2 == 1)
        prog = read_text(fp.text, fp.file, dialect)
        return prog, fp, None
    cp = cam_program(seed, dialect=dialect)
    prog = read_text(cp.text, cp.file, dialect, tool_table=cp.tool_table)
    return prog, cp, cp.pushed(DENT)


def _linuxcnc_refuses_dep_ln(exc: CompensationError, fp, style: str) -> bool:
    """The one refusal the module docstring allows: LinuxCNC's concave corner
    at a ``DEP LN`` after a move shorter than the radius, located at the
    departure's line (the line after the contour's last)."""
    if not (style == "linuxcnc" and getattr(fp, "lead_out", None) == "LN"):
        return False
    dep = 1 + next(i for i, line in enumerate(fp.text.splitlines()) if line.startswith("DEP LN"))
    return "concave corner" in str(exc) and str(exc).startswith(f"{fp.file}:{dep}:")


def _check(seed: int, dialect: str, native: bool, export_to=None) -> None:
    prog, gp, dented = _program(seed, dialect, native)
    resolution = 10.0 ** -gp.decimals
    for style in STYLES:
        try:
            path = compensate(prog, style)
        except CompensationError as exc:
            assert _linuxcnc_refuses_dep_ln(exc, gp, style), (gp.description, style, str(exc))
            continue
        cert = verify(path, prog)
        assert cert.ok, (gp.description, style, cert.summary())
        assert cert.surface["part_lines"] == [list(gp.contour_lines)], (gp.description, style)
        for w in cert.warnings:
            straight_join = w.detail["cause"].startswith("LinuxCNC straight join")
            assert straight_join or (gp.decimals < 6 and w.depth <= resolution), \
                (gp.description, style, w)
    own = compensate(prog, OWN_STYLE[dialect])
    if dented is not None:
        bad = verify(compensate(read_text(dented, gp.file, dialect, tool_table=gp.tool_table),
                                OWN_STYLE[dialect]), prog)
        depth = max([v.depth for v in bad.violations if v.kind == "gouge"], default=0.0)
        assert not bad.ok and depth >= DENT - resolution, (gp.description, bad.summary())
    if export_to is not None:
        for suffix in (".nc", ".pmc"):
            res = export(own, export_to / f"{dialect}-{seed}{suffix}", program=prog)
            assert res.verified and res.roundtrip_error <= res.tolerance, \
                (gp.description, suffix, res.roundtrip_error)


@pytest.mark.parametrize("dialect", ["sinumerik", "heidenhain"])
@pytest.mark.parametrize("native", [False, True], ids=["cam-leads", "own-leads"])
def test_generated_family_plates_quick(dialect, native, tmp_path):
    for seed in QUICK:
        _check(seed, dialect, native, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("dialect", ["sinumerik", "heidenhain"])
@pytest.mark.parametrize("native", [False, True], ids=["cam-leads", "own-leads"])
def test_generated_family_plates_60(dialect, native, tmp_path):
    for seed in SLOW:
        _check(seed, dialect, native, tmp_path if seed % 3 == 0 else None)
    if native:
        # every lead kind was drawn, each at least 5 % of the time
        ins = SINUMERIK_IN if dialect == "sinumerik" else HEIDENHAIN_IN
        outs = SINUMERIK_OUT if dialect == "sinumerik" else HEIDENHAIN_OUT
        drawn = [family_program(seed, dialect) for seed in SLOW]
        for kinds, got in ((ins, [fp.lead_in for fp in drawn]),
                           (outs, [fp.lead_out for fp in drawn])):
            assert {k: got.count(k) for k in kinds if got.count(k) < 0.05 * len(SLOW)} == {}
