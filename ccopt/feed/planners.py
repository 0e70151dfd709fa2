"""The registry of feed planners: name -> ``"module:function"``.

Kept apart from the planners themselves so that naming one does not import
toppra (the modules load when a planner is first looked up).
"""
from __future__ import annotations

import importlib

#: The jerk planner's default interpolation period ``ts`` (s): the acceleration
#: step at a curvature break is at most ``jmax * ts`` (:mod:`ccopt.feed.jerk.planner`).
DEFAULT_TS = 1e-3

#: planner name -> "module:function"; each takes (path, limits, junction_deviation=..., grid=...);
#: ``jerk`` also takes ``ts`` and needs ``limits.j``
PLANNERS: dict[str, str] = {
    "toppra": "ccopt.feed.toppra.planner:plan_toppra",
    "stop": "ccopt.feed.baselines:plan_stop_per_block",
    "junction": "ccopt.feed.baselines:plan_junction",
    "jerk": "ccopt.feed.jerk.planner:plan_jerk",
}


def planner_function(name: str):
    """The planner function registered as ``name`` in :data:`PLANNERS`."""
    if name not in PLANNERS:
        raise ValueError(f"unknown planner {name!r}; choose one of {', '.join(PLANNERS)}")
    module, func = PLANNERS[name].split(":")
    return getattr(importlib.import_module(module), func)


__all__ = ["PLANNERS", "planner_function"]
