"""The jerk-limited time-optimal planner and the jerk-limited motion it shares
with the baselines.

- :mod:`.planner`: :func:`~ccopt.feed.jerk.planner.plan_jerk` (the formulation
  is in its docstring);
- :mod:`.lp`: the linear program of one window of gridpoints (HiGHS);
- :mod:`.windows`: the gridpoints cut into windows, the pseudo-jerk rounds on
  each, in worker processes on long programs (:mod:`ccopt.workers`);
- :mod:`.speed_bound`: the speed bound the rounds start from (TOPPRA's
  acceleration-limited speed);
- :mod:`.profile`: :class:`~ccopt.feed.jerk.profile.JerkProfile`, a profile
  of pieces with bounded jerk;
- :mod:`.scurve`: the 7-phase S-curve in closed form (also the jerk-limited
  baselines', :mod:`ccopt.feed.baselines`).

Nothing is imported here, so that a worker process importing
:mod:`.windows` loads only what it needs.
"""
