"""The time-optimal planner, TOPPRA (Pham and Pham's reachability analysis).

- :mod:`.planner`: :func:`~ccopt.feed.toppra.planner.plan_toppra`, the
  planner itself, on the gridpoints of :mod:`ccopt.feed.grid`;
- :mod:`.constraints`: the axis and path limits as small toppra constraint
  objects;
- :mod:`.library`: toppra's names ccopt uses, imported without its plotting
  and spline dependencies (every ccopt module takes them from there).

Nothing is imported here: :mod:`ccopt.feed.path` (shared by every planner)
takes toppra's ``AbstractGeometricPath`` from :mod:`.library` alone.
"""
