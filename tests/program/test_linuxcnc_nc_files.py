"""LinuxCNC's shipped example programs (nc_files, kept in
tests/conformance/linuxcnc/nc_files with the simulator configurations they
are written for; licence: that folder's README) read, compensate and time
with the sim config's INI: the drilling samples (polar bolt circles), the
threading sample (G33), the lathe samples (G18 compensation with lathe.tbl's
tools, G70/G71). Figures are worked out from the programs' own text."""
from __future__ import annotations

import math

import pytest

import ccopt
from ccopt.compensate import compensate
from ccopt.errors import ProgramError
from ccopt.feed import AxisLimits, plan_feed
from ccopt.program import read_program
from ccopt.program.model import Motion
from linuxcnc_data import CONFORMANCE

NC = CONFORMANCE / "nc_files"
LIMITS = AxisLimits((100.0, 100.0, 100.0), (1000.0, 1000.0, 1000.0))


def _read(name: str, ini: str):
    return read_program(NC / name, ini=NC / "sim" / ini)


def _holes(prog):
    """The (x, y) of each drilling feed (a canned cycle's feed down)."""
    return [b.end[:2] for b in prog.blocks if b.motion is Motion.LINE and b.cycle == "G81"]


def _timed(prog) -> float:
    seconds = plan_feed(compensate(prog, style="linuxcnc"), LIMITS).duration
    assert math.isfinite(seconds) and seconds > 0
    return seconds


def test_hole_circle_drills_six_holes_sixty_degrees_apart():
    # G0 X1.5 Y0, then G91 G81 ... ^60 L6: the point turned 60 degrees six times
    prog = _read("hole-circle.ngc", "axis.ini")
    want = [(1.5 * math.cos(math.radians(60 * k)), 1.5 * math.sin(math.radians(60 * k)))
            for k in range(1, 7)]
    assert _holes(prog) == [pytest.approx(w, abs=1e-12) for w in want]
    _timed(prog)


def test_polar_bolt_circles_and_row():
    # three holes on a 5" diameter (X2.5, ^120, ^240); "G90 @1 ^33" with G81
    # still in force drills there too, then five 1" apart along 33 degrees;
    # then 17 on a 4" diameter from X2 turning 360/17
    prog = _read("polar.ngc", "axis.ini")
    pol = lambda r, deg: (r * math.cos(math.radians(deg)), r * math.sin(math.radians(deg)))  # noqa: E731
    want = [pol(2.5, 0), pol(2.5, 120), pol(2.5, 240)]
    want += [pol(1 + k, 33) for k in range(0, 6)]
    want += [pol(2, 360 / 17 * k) for k in range(1, 18)]
    assert _holes(prog) == [pytest.approx(w, abs=1e-9) for w in want]
    _timed(prog)


def test_threading_sample_cuts_at_twenty_inches_per_minute():
    # "s400 m3 (=20ipm cutting at .05tpi)": G33 K0.05 at 400 rev/min, and the
    # 45-degree exit at K0.05*sqrt 2 along its longer path
    prog = _read("threading.ngc", "lathe.ini")
    cuts = [b for b in prog.blocks if b.motion is Motion.LINE and b.start[0] == b.end[0]
            and b.feed == pytest.approx(20 / 60)]
    exits = [b for b in prog.blocks if b.motion is Motion.LINE
             and b.feed == pytest.approx(20 / 60 * math.sqrt(2))]
    assert len(cuts) >= 70 and len(exits) == len(cuts)
    _timed(prog)


@pytest.mark.parametrize("name, radius", [("lathecomp.ngc", 0.05),
                                          ("lathe_g70_71_demo.ngc", 0.15)])
def test_lathe_samples_compensate_with_the_lathe_tool_table(name, radius):
    # lathecomp: G42/G41 with T2 and T7 of lathe.tbl, each D0.1 on the inch
    # machine (radius 0.05 in); the G70/G71 demo: G42.1 D0.3 L2 (radius 0.15)
    prog = _read(name, "lathe.ini")
    path = compensate(prog, style="linuxcnc")
    assert path.radius == pytest.approx(radius) and {s.plane for s in path.segments} == {"ZX"}
    _timed(prog)


def test_g70_finishing_passes_verify_against_the_last_pass_only():
    # G70 ... D0.5 P2: the first pass runs 0.25 off the contour, the last on it;
    # only the last is the part's surface, the first is marked air (what the
    # last removes), so the compensated finish verifies
    prog = _read("lathe_g70_71_demo.ngc", "lathe.ini")
    g70 = [b for b in prog.blocks if b.cycle == "G70"]
    assert {b.surface for b in g70} == {"air", None}
    assert g70[-1].surface is None
    cert = ccopt.verify(compensate(prog, style="linuxcnc"), prog)
    assert cert.ok


def test_g76_sample_is_refused_where_its_compensated_facing_enters():
    # its o100 sub: "g0z1x-1", "g41", "g0z1": the entry move has length 0,
    # not more than the tool radius (LinuxCNC's convert_straight_comp1 refuses it)
    prog = _read("g76.ngc", "lathe.ini")
    with pytest.raises(ProgramError) as err:
        compensate(prog, style="linuxcnc")
    assert (err.value.line, "entry move is 0 long" in err.value.message) == (26, True)
