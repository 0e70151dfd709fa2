"""Trust that generalises (issue 29): generated CAM-style profile programs
(:mod:`cam_programs`) verify, in PMAC and LinuxCNC styles, from G-code and
PMAC text, with 3, 4 and 6 decimals.

Properties, each figure derived from the construction, not from the verifier:

- every program verifies ok, or ok within the tolerance; the part surface the
  verifier takes is exactly the contour the generator wrote (its program
  lines), the leads are air;
- a warning is a LinuxCNC straight join (at 6 decimals nothing else), and at
  3 or 4 decimals no deeper than the written resolution ``10**-decimals``;
- the same program with one contour edge dented 0.01 into the part, made into
  a tool path and verified against the original, fails by at least 0.01 (less
  the written resolution);
- an extension lead at a sharp corner (a lead along the edge's line, straight
  to or from the offset point) gouges that corner by ``r - r l / sqrt(l^2 + r^2)``
  (the distance from the corner to the tool's diagonal): real, in both styles;
- multi-pass programs (one subroutine called with several diameters, zero
  among them) verify, each pass against its own radius.

The quick tier runs 20 fixed programs; the slow tier 500 of each kind.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from cam_programs import cam_program, multipass_program, slight_turn_program
from ccopt.compensate import compensate
from ccopt.program import read_text
from ccopt.verify import verify

STYLES = ("pmac", "linuxcnc")
QUICK = range(20)
SLOW = range(20, 520)
TOL = 1e-3                   # the default tolerance, mm (ccopt.tolerances.GOUGE_TOLERANCE)
DENT = 0.01


def _read(cp, text=None):
    return read_text(text or cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)


def _check_program(seed: int) -> int:
    """Check one generated program in both styles; returns how many style runs
    exercised the part/air property (a closed loop found as the contour)."""
    cp = cam_program(seed)
    prog = _read(cp)
    dented = _read(cp, cp.pushed(DENT))
    resolution = 10.0 ** -cp.decimals
    exercised = 0
    for style in STYLES:
        path = compensate(prog, style)
        cert = verify(path, prog)
        assert cert.ok, (cp.description, style, cert.summary())
        s = cert.surface
        assert s["part_lines"] == [list(cp.contour_lines)], (cp.description, style, s)
        exercised += 1
        for w in cert.warnings:
            straight_join = w.detail["cause"].startswith("LinuxCNC straight join")
            assert straight_join or cp.decimals < 6, (cp.description, style, w)
            assert straight_join or w.depth <= resolution, (cp.description, style, w)
        bad = verify(compensate(dented, style), prog)
        assert not bad.ok, (cp.description, style, "a 0.01 dent passed")
        depth = max(v.depth for v in bad.violations if v.kind == "gouge")
        assert depth >= DENT - resolution, (cp.description, style, bad.summary())
    return exercised


def test_generated_cam_programs_quick():
    runs = sum(_check_program(seed) for seed in QUICK)
    assert runs == len(QUICK) * len(STYLES)


def _features(seed: int) -> set[str]:
    cp = cam_program(seed)
    return {"corner entry" if "corner entry" in cp.description else "mid-edge entry",
            "lead-in " + cp.lead_in, "lead-out " + cp.lead_out, cp.dialect,
            f"{cp.decimals} decimals", "rectangle" if "rectangle" in cp.description else "star",
            "overlap" if "overlap 0," not in cp.description else "no overlap"}


@pytest.mark.slow
def test_generated_cam_programs_500():
    runs = sum(_check_program(seed) for seed in SLOW)
    assert runs == len(SLOW) * len(STYLES)
    # every kind of program was drawn, each at least 5 % of the time (leads
    # that meet, the rarest, need a corner entry and arcs both ways)
    seen: dict[str, int] = {}
    for seed in SLOW:
        for f in _features(seed):
            seen[f] = seen.get(f, 0) + 1
    kinds = {"corner entry", "mid-edge entry", "lead-in arc", "lead-in perpendicular",
             "lead-out arc", "lead-out meet", "lead-out perpendicular", "gcode", "pmac",
             "3 decimals", "4 decimals", "6 decimals", "rectangle", "star", "overlap"}
    assert {k: seen.get(k, 0) for k in kinds if seen.get(k, 0) < 0.05 * len(SLOW)} == {}


def _dist_point_segment(p, a, b) -> float:
    p, a, b = (np.asarray(x, float) for x in (p, a, b))
    d = b - a
    u = min(max(float((p - a) @ d) / float(d @ d), 0.0), 1.0)
    return float(np.hypot(*(a + u * d - p)))


def _extension_gouge(seed: int) -> bool:
    """One program with an extension lead at a corner; False when the seed drew none."""
    cp = cam_program(seed, lead_ins=("arc", "perpendicular", "extension"),
                     lead_outs=("extension",))
    if cp.lead_in != "extension" and cp.lead_out != "extension":
        return False
    prog = _read(cp)
    r, E = cp.radius, np.asarray(cp.entry, float)
    resolution = 10.0 ** -cp.decimals
    for style in STYLES:
        path = compensate(prog, style)
        cert = verify(path, prog)
        expected = 0.0
        for s in path.segments:
            if s.role.value in ("lead-in", "lead-out") and s.kind == "line":
                # the corner lies r from the lead's offset end: the lead's
                # diagonal passes nearer, at its distance from the corner
                expected = max(expected, r - _dist_point_segment(E, s.start, s.end))
        assert expected > 0.0
        got = max([v.depth for v in cert.violations + cert.warnings if v.kind == "gouge"],
                  default=0.0)
        assert got >= expected - resolution - 1e-9, (cp.description, style, cert.summary())
        assert cert.ok is (got <= TOL), (cp.description, style, cert.summary())
        # and the analytic depth from the construction: l = the lead's length
        far = cp.start if cp.lead_in == "extension" else cp.end
        ell = math.dist(far, E)
        analytic = r - r * ell / math.hypot(ell, r)
        assert expected == pytest.approx(analytic, abs=2 * resolution + 1e-9)
    return True


def test_extension_leads_gouge_their_corner_quick():
    assert sum(_extension_gouge(seed) for seed in range(40)) >= 5


@pytest.mark.slow
def test_extension_leads_gouge_their_corner_500():
    seen = sum(_extension_gouge(seed) for seed in range(40, 540))
    assert seen >= 100


def _check_multipass(seed: int) -> None:
    text, diameters = multipass_program(seed)
    prog = read_text(text, f"multipass-{seed}.ngc", "gcode")
    for style in STYLES:
        path = compensate(prog, style)
        cert = verify(path, prog)
        assert cert.ok, (seed, diameters, style, cert.summary())
        radii = sorted(set(cert.context.contour.radius.tolist()))
        assert radii == sorted({d / 2 for d in diameters}), (seed, radii, diameters)


def test_multipass_programs_quick():
    for seed in range(5):
        _check_multipass(seed)


@pytest.mark.slow
def test_multipass_programs_200():
    for seed in range(5, 205):
        _check_multipass(seed)


def _check_slight_turn(seed: int) -> str:
    """LinuxCNC takes a turn under 0.05 rad as straight on: the next move
    starts at the last offset point, r cos(turn) from the new element's line,
    a gouge of up to r (1 - cos turn) whichever way it turns (shapely gives
    the exact figure); PMAC extends or trims the offsets and keeps r. Returns
    the LinuxCNC verdict."""
    from shapely.geometry import LineString, Polygon

    text, r, turn = slight_turn_program(seed)
    prog = read_text(text, f"slight-{seed}.ngc", "gcode", tool_table={1: 2 * r})
    assert abs(turn) < 0.05
    cert = verify(compensate(prog, "pmac"), prog, tolerance=0.0)
    assert cert.ok and not cert.warnings, (seed, r, turn, cert.summary())
    path = compensate(prog, "linuxcnc")
    cert = verify(path, prog)
    # the depth by shapely: the plate's outline against the tool's straight
    # pieces made with compensation in force (its corner arcs run at r)
    ring = Polygon([b.end[:2] for b in prog.blocks
                    if b.modal.side != 0 and b.motion.is_move][1:]).exterior
    depth = max(r - ring.distance(LineString([s.start, s.end])) for s in path.segments
                if s.kind == "line" and s.role.value == "compensated")
    # at most r (1 - cos turn): the join starts r cos(turn) from the new edge's line
    assert 0.0 < depth <= r * (1 - math.cos(turn)) * (1 + 1e-9)
    found = max([v.depth for v in cert.violations + cert.warnings if v.kind == "gouge"],
                default=0.0)
    if depth <= cert.eps:                 # within the arithmetic's eps: no violation
        assert found == 0.0 and cert.verdict == "ok", (seed, r, turn, cert.summary())
        return cert.verdict
    assert found == pytest.approx(depth, rel=1e-6, abs=1e-12), (seed, r, turn, cert.summary())
    assert cert.ok is (depth <= TOL)
    if cert.ok:
        which = "outside" if turn > 0 else "inside"
        for v in cert.warnings:
            assert v.detail["cause"].startswith(
                f"LinuxCNC straight join at a {math.degrees(abs(turn)):.3g}-degree {which}"), v
    return cert.verdict


def test_linuxcnc_slight_turns_gouge_by_r_one_minus_cos_quick():
    verdicts = {_check_slight_turn(seed) for seed in range(12)}
    assert verdicts == {"failed", "ok within tolerance"}


@pytest.mark.slow
def test_linuxcnc_slight_turns_gouge_by_r_one_minus_cos_300():
    verdicts = [_check_slight_turn(seed) for seed in range(12, 312)]
    assert verdicts.count("ok within tolerance") >= 60 and verdicts.count("failed") >= 60
