"""A stretch planned alone is planned in the whole path's coordinates.

``compare`` times a variant by its stretches between stops, planning only
those the reference lacks, each run of them as a path of its own
(ccopt.compare.timing). On a path that moves ``z`` somewhere (a plunge
before the contour), a stretch that moves only ``x`` and ``y`` was planned
as a 2-axis path, its grid read from the in-plane limits alone, while the
whole path's plan grids it with the ``z`` axis's limits too: the same
stretch came out up to 0.1 % apart (freeform-hsm's ``siemens`` row 0.058 %
over its own whole-path plan). Checked: every controller style's cycle time
in ``compare``, under jerk limits, equals the jerk planner's plan of its
whole path within the planners' own tolerance (far under that gap), on
freeform-hsm and on generated CAM plates with a plunge and a retract.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

import ccopt
from ccopt.cases import find_case
from ccopt.compare import compare
from ccopt.compare.timing import plan_whole

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from cam_programs import cam_program  # noqa: E402

#: How far a row's cycle time by stretches may be from its whole path's plan:
#: the jerk planner's windows and rounds give a stretch planned alone the
#: whole plan's figure to about 1e-8 (measured), 5e-4 apart before the fix.
REL = 1e-6
STYLES = ["pmac", "linuxcnc", "siemens"]
LIMITS = ccopt.AxisLimits((200.0, 200.0, 50.0), (2000.0, 2000.0, 500.0),
                          j=(20000.0, 20000.0, 5000.0))


def _rows_match_whole_plans(prog, limits, radius=None) -> int:
    checked = 0
    for row in compare(prog, STYLES, limits=limits, radius=radius, workers=1):
        if row.toolpath is None or row.figures.get("duration") is None:
            continue
        whole = plan_whole(row.toolpath, limits)[0].duration
        assert row.figures["duration"] == pytest.approx(whole, rel=REL), row.name
        checked += 1
    return checked


def plunged(seed: int, tmp_path: Path) -> tuple[Path, float]:
    """The G-code CAM plate of ``seed`` with a plunge to Z-2 before its lead-in
    and a retract after its lead-out (its contour's fillets join tangent:
    stretches with no stop, planned in windows)."""
    cp = cam_program(seed, "gcode")
    lines = cp.text.splitlines()
    at = next(i for i, ln in enumerate(lines) if ln.startswith("G0 X"))
    lines[at + 1:at + 1] = ["G1 Z-2 F300"]
    end = next(i for i, ln in enumerate(lines) if ln.startswith("M30"))
    lines[end:end] = ["G0 Z5"]
    f = tmp_path / f"plunged-{seed}.ngc"
    f.write_text("\n".join(lines) + "\n")
    return f, cp.radius


def test_freeform_hsm_rows_are_their_whole_path_plans():
    c = find_case("freeform-hsm")
    assert _rows_match_whole_plans(ccopt.read_program(c.program),
                                   ccopt.AxisLimits(c.vmax, c.amax, j=c.jmax)) == len(STYLES)


@pytest.mark.parametrize("seed", [3, 11])
def test_plunged_cam_plates(seed, tmp_path):
    f, r = plunged(seed, tmp_path)
    assert _rows_match_whole_plans(ccopt.read_program(f), LIMITS, r) >= 2


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(20, 45))
def test_many_plunged_cam_plates(seed, tmp_path):
    f, r = plunged(seed, tmp_path)
    assert _rows_match_whole_plans(ccopt.read_program(f), LIMITS, r) >= 1
