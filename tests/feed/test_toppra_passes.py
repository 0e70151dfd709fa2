"""TOPPRA's two passes as StoppingTOPPRA runs them (ccopt.feed.toppra.planner)
against toppra's own step methods, on generated programs: the backward pass
(toppra's compute_controllable_sets over its _one_step, with the guard of
_uncrossed) and the forward pass without margin (over toppra's _forward_step)
give the same profile to the last bit."""
from __future__ import annotations

import numpy as np
import pytest

import ccopt
from ccopt.feed import ExactPath
from ccopt.feed.toppra import planner
from ccopt.feed.toppra.library import TOPPRA
from ccopt.feed.toppra.planner import FORWARD_RETRY, StoppingTOPPRA, _uncrossed, plan_toppra
from tests.cam_programs import cam_program

LIMITS = ccopt.AxisLimits((200.0, 200.0, 100.0), (2000.0, 2000.0, 1000.0))


def _one_step(self, i, K_next):
    """toppra's step and the guard, as StoppingTOPPRA stepped before."""
    res = TOPPRA._one_step(self, i, K_next)
    res[0], res[1] = _uncrossed(res[0], res[1], float(K_next[1]))
    return res


def _forward(self, x_start, K):
    """The forward pass without margin over toppra's _forward_step."""
    N = self.solver_wrapper.get_no_stages()
    deltas = self.solver_wrapper.get_deltas()
    xs = np.empty(N + 1)
    xs[0] = x_start
    for i in range(N):
        for shrink in FORWARD_RETRY:
            u = self._forward_step(i, xs[i] * (1.0 - shrink), K[i + 1])[0]
            if not np.isnan(u):
                xs[i] *= 1.0 - shrink
                break
        else:
            return None
        xs[i + 1] = min(K[i + 1, 1], max(K[i + 1, 0], xs[i] + 2.0 * deltas[i] * u))
    return xs


def _profile(path):
    prof = plan_toppra(ExactPath(path), LIMITS)
    return prof.t, prof.s, prof.sd, prof.sdd


@pytest.mark.parametrize("seed", [2, 9, 31])
@pytest.mark.parametrize("style", ["pmac", "linuxcnc"])
def test_the_passes_are_toppras_steps(seed, style, monkeypatch):
    cp = cam_program(seed)
    prog = ccopt.read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    path = ccopt.compensate(prog, style)
    new = _profile(path)
    with monkeypatch.context() as m:
        m.setattr(StoppingTOPPRA, "compute_controllable_sets", TOPPRA.compute_controllable_sets)
        m.setattr(StoppingTOPPRA, "_one_step", _one_step, raising=False)
        m.setattr(StoppingTOPPRA, "forward_without_margin", _forward)
        old = _profile(path)
    for a, b in zip(new, old):
        assert a.tobytes() == b.tobytes()


def test_a_backward_step_that_fails_stops_the_pass_as_toppras_does(monkeypatch):
    cp = cam_program(2)
    prog = ccopt.read_text(cp.text, cp.file, cp.dialect, tool_table=cp.tool_table)
    path = ccopt.compensate(prog, "pmac")
    calls = []

    def failing(self, *args):
        calls.append(args[0])
        return [np.nan, np.nan]

    # the wrapper's class is an extension type: the pass's LPs replaced through a stand-in
    class Wrapper:
        def __init__(self, inner):
            self.inner = inner

        def __getattr__(self, name):
            return getattr(self.inner, name)

        def solve_stagewise_optim(self, *args):
            return failing(self, *args)

    got = {}
    made = StoppingTOPPRA.compute_controllable_sets

    def spy(self, sdmin, sdmax):
        self.solver_wrapper = Wrapper(self.solver_wrapper)
        got["K"] = made(self, sdmin, sdmax)
        got["N"] = self._N
        raise planner.FeedError("stop here")

    monkeypatch.setattr(StoppingTOPPRA, "compute_controllable_sets", spy)
    with pytest.raises(planner.FeedError):
        plan_toppra(ExactPath(path), LIMITS)
    K, N = got["K"], got["N"]
    assert calls == [N - 1, N - 1]          # both LPs of the last stage, then no more
    assert np.isnan(K[N - 1]).all() and not np.isnan(K[N]).any() and (K[:N - 1] == 0).all()
