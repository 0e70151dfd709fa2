"""The ``smooth`` variant smooths LinuxCNC's path too and keeps the faster.

The comparison hands the smoother the fastest certified controller path;
where that is not LinuxCNC's and LinuxCNC's path is certified, the variant
also smooths LinuxCNC's (whose entry joins the contour as at a corner,
docs/compensation.md LinuxCNC rules 1 and 2) and keeps the faster certified
result (formulations/smoother_variant.py).

Checked against figures made here independently: each start smoothed on its
own (:func:`ccopt_formulations.smoother.smooth`, from that controller's
compensated path) and planned whole by the certified planner. The row's
cycle time is the smaller of the two (within the jerk planner's difference
between a whole-path plan and the comparison's stretch-by-stretch one), the
row says which path it started from, and it is certified and never slower
than the fastest controller variant (``smooth_row``).
"""
from __future__ import annotations

from smoother_checks import faster_start_holds, smooth_row


def test_linuxcncs_path_smoothed_is_kept_where_it_is_faster():
    # seed 5 (a 3-gon, arc leads): Fagor's G138 path is the fastest controller
    # variant, LinuxCNC's smoothed the faster (worked out in faster_start_holds)
    assert faster_start_holds(5, smooth_row(5)) == "linuxcnc"


def test_the_fastest_path_alone_where_it_is_linuxcncs():
    # seed 1: LinuxCNC's path is the fastest controller variant itself
    assert faster_start_holds(1, smooth_row(1)) is None


# Generated plates 0-29 (bench/blend_gains.py: 200 plates, (a) and (b)) are
# checked by tests/formulations/test_smoother_kinks.py's
# test_generated_plates_with_tiny_kinks: its plates 0-59 include them, and one
# comparison per plate serves both checks (a comparison of a plate with the
# smoother takes seconds).
