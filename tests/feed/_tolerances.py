"""The limits each planner states it keeps, as the largest ratio
``|value| / limit`` a test's samples may show (shared by the feed tests).

- ``stop`` and ``junction`` (without jerk limits): a trapezoid per block whose
  budgets keep the limits "everywhere along it" (:mod:`ccopt.feed.baselines`),
  so rounding only: :data:`BASELINE_OVER` (measured: at most 1 + 2.3e-16 on
  the bundled cases and 120 random contours).
- ``toppra``: "the axis limits hold all along the path, not only at the
  gridpoints" (:mod:`ccopt.feed.toppra.planner`), up to toppra's feasibility
  tolerance, ``1e-8`` (:func:`ccopt.feed.toppra.planner.build_constraints`):
  :data:`TOPPRA_OVER` (measured at 1 kHz: acceleration at most 1 + 2.3e-10 on
  the bundled cases (freeform-hsm), 1 + 6.8e-10 on random contours,
  tangential acceleration 1 + 3.7e-10).
- ``jerk`` (and the jerk-limited baselines): checked at gridpoints, with a
  second-order margin between them (:mod:`ccopt.feed.jerk.planner`), and
  certified by ``run`` with the verifier's tolerance:
  :data:`JERK_OVER` = 1 + :data:`ccopt.verify.limits.LIMITS_TOL` (measured at
  10 kHz on the bundled cases: jerk at most 1 + 1.9e-4, feed 1 + 2.8e-4).
"""
from ccopt.verify.limits import LIMITS_TOL

BASELINE_OVER = 1 + 1e-12
TOPPRA_OVER = 1 + 1e-8
JERK_OVER = 1 + LIMITS_TOL
OVER = {"toppra": TOPPRA_OVER, "stop": BASELINE_OVER, "junction": BASELINE_OVER}
