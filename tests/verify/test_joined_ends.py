"""Open ends of the contour that are joints after all
(:func:`ccopt.verify.contour._close_joined_ends`, issue 34): a run's first
start met within ``eps`` by the end of another element of the same run, or
its last end met by another's start, is no open end; an element of another
run meeting it there does not count.

The function compares each run's two ends with the run's elements at once;
here it is held to the rule written out pair by pair, over generated runs of
chained elements: closed loops, loops that close just inside and just
outside ``eps`` (the boundary, ``dx**2 + dy**2 <= eps**2``, where scipy's
``cKDTree.query_ball_point``, the earlier code, puts it), open chains,
one-element runs, and other runs (passes) passing through the same points.
"""
from __future__ import annotations

import random
from types import SimpleNamespace

import numpy as np
import pytest

from ccopt.verify.contour import _close_joined_ends

EPS = 1e-6


def _reference(p0, p1, open_start, open_end, episode, eps):
    """The rule, one pair at a time."""
    n = len(episode)
    out_start, out_end = open_start.copy(), open_end.copy()
    for opened, here, there in ((out_start, p0, p1), (out_end, p1, p0)):
        for j in np.flatnonzero(opened):
            for o in range(n):
                gap = there[o] - here[j]
                if (o != j and episode[o] == episode[j]
                        and gap[0] * gap[0] + gap[1] * gap[1] <= eps * eps):
                    opened[j] = False
    return out_start, out_end


def _runs(seed: int):
    """``(p0, p1, episode)`` of a few generated runs of chained elements."""
    rng = random.Random(seed)
    p0, p1, episode = [], [], []
    anchors = [np.array([rng.uniform(-50, 50), rng.uniform(-50, 50)]) for _ in range(3)]
    for run in range(rng.randint(1, 6)):
        m = rng.choice((1, 2, 3, rng.randint(4, 40)))
        start = rng.choice(anchors) if rng.random() < 0.5 else \
            np.array([rng.uniform(-50, 50), rng.uniform(-50, 50)])
        pts = [start]
        for _ in range(m):
            pts.append(pts[-1] + np.array([rng.uniform(-5, 5), rng.uniform(-5, 5)]))
        how = rng.choice(("open", "closed", "inside", "outside", "start-met", "end-met"))
        if how == "closed":
            pts[-1] = pts[0].copy()
        elif how in ("inside", "outside"):
            # back to the start within eps, or just beyond it
            ang = rng.uniform(0, 2 * np.pi)
            d = EPS * (1 - 1e-9 if how == "inside" else 1 + 1e-9)
            pts[-1] = pts[0] + d * np.array([np.cos(ang), np.sin(ang)])
        elif how == "start-met" and m >= 3:
            pts[2] = pts[0].copy()      # an element inside the run ends at its start
        elif how == "end-met" and m >= 3:
            pts[1] = pts[-1].copy()     # one starts where the run ends
        for a, b in zip(pts[:-1], pts[1:]):
            p0.append(a)
            p1.append(b)
            episode.append(run)
    return np.array(p0), np.array(p1), np.array(episode)


@pytest.mark.parametrize("seed", [*range(20),
                                  *(pytest.param(k, marks=pytest.mark.slow) for k in range(20, 300))])
def test_joined_ends_follow_the_rule_pair_by_pair(seed):
    p0, p1, episode = _runs(seed)
    n = len(episode)
    first = np.r_[True, episode[1:] != episode[:-1]]
    last = np.r_[episode[1:] != episode[:-1], True]
    open_start, open_end = first.copy(), last.copy()
    want = _reference(p0, p1, open_start, open_end, episode, EPS)
    elements = SimpleNamespace(arr=SimpleNamespace(p0=p0, p1=p1))
    _close_joined_ends(elements, open_start, open_end, episode, EPS)
    assert open_start.tolist() == want[0].tolist()
    assert open_end.tolist() == want[1].tolist()
    assert n == len(open_start)


def test_a_closed_loop_has_no_open_end_and_another_pass_does_not_close_one():
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]], float)
    # run 0: the closed square; run 1: an open chain from the square's corner
    # to its opposite corner, passing the first corner again
    chain = np.array([[0, 0], [5, 5], [10, 10]], float)
    p0 = np.r_[square[:-1], chain[:-1]]
    p1 = np.r_[square[1:], chain[1:]]
    episode = np.array([0, 0, 0, 0, 1, 1])
    open_start = np.array([1, 0, 0, 0, 1, 0], bool)
    open_end = np.array([0, 0, 0, 1, 0, 1], bool)
    _close_joined_ends(SimpleNamespace(arr=SimpleNamespace(p0=p0, p1=p1)), open_start,
                       open_end, episode, EPS)
    assert open_start.tolist() == [False, False, False, False, True, False]
    assert open_end.tolist() == [False, False, False, False, False, True]
