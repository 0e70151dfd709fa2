"""Distances between a tool path's segments and the contour's elements: the
verifier's one entry to its distance machinery.

- :func:`candidate_pairs` (:mod:`.broadphase`): the (tool segment, element)
  pairs whose boxes, grown by a reach, overlap (a uniform grid, no pair loop);
- :func:`min_distance` (:mod:`.certified`) and :func:`min_distances`
  (:mod:`.certified_batch`, the same bounds for many pairs at once): certified
  lower and upper bounds of the distance where a spiral or a curve is
  involved, by branch and bound, tight to a stated gap;
- :func:`max_distance` and :func:`max_distance_to_point` (:mod:`.maxdist`):
  the exact largest distance from a line or arc to a line, arc or point (the
  contact check), and :func:`max_distance_bound` (:mod:`.certified`) its
  certified upper bound where a spiral or curve is involved;
- :mod:`.concentric`: the bounds of arcs and spirals about one centre that
  the branch and bound uses, and :mod:`.mid_arc`: the bound of a spiral piece
  by the arc at its middle radius.

Exact line and arc distances are geometry's (:mod:`ccopt.geometry.distance`).
"""
from __future__ import annotations

from ccopt.verify.distance.broadphase import candidate_pairs
from ccopt.verify.distance.certified import Bound, is_exact, min_distance
from ccopt.verify.distance.certified import max_distance as max_distance_bound
from ccopt.verify.distance.certified_batch import batchable, min_distances
from ccopt.verify.distance.maxdist import max_distance, max_distance_to_point

__all__ = ["Bound", "batchable", "candidate_pairs", "is_exact", "max_distance",
           "max_distance_bound", "max_distance_to_point", "min_distance", "min_distances"]
