"""Where a jerk profile's ``SLINEAR`` piece is at a given time
(:func:`ccopt.feed.jerk.profile._slinear_at`): the closed-form motion of
``s'' = a0 + c x`` must agree with the inverse of the piece's duration
integral (:func:`~ccopt.feed.jerk.profile.slinear_time`, whose durations the
profile's knots hold), found here independently by bisection, and with the
ODE itself (``v^2 = v0^2 + 2 a0 x + c x^2``, ``a = a0 + c x``)."""
from __future__ import annotations

import numpy as np
import pytest

from ccopt.feed.jerk.profile import _slinear_at, slinear_time


def _bisect_position(v0, a0, a1, h, tau, steps=80):
    lo, hi = np.zeros_like(h), h.copy()
    b0 = v0 * v0
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        late = slinear_time(b0, a0, a1, h, mid) > tau
        hi = np.where(late, mid, hi)
        lo = np.where(late, lo, mid)
    return 0.5 * (lo + hi)


def _pieces(seed, n=4000):
    # speeds 1-100 units/s, lengths 1e-3-5 units, accelerations within 5000
    # units/s^2 whose squared speed stays within a factor 4 of v0^2 on the piece
    # (the planner's grid keeps a piece's speeds closer: slinear_time's
    # quadrature is exact to rounding there, not where the speed grows 70-fold):
    # c = (a1 - a0) / h of both signs, from ~0 to |c| tau^2 near 1
    rng = np.random.default_rng(seed)
    v0 = rng.uniform(1.0, 100.0, n)
    h = 10.0 ** rng.uniform(-3.0, np.log10(5.0), n)
    a0 = rng.uniform(-5000.0, 5000.0, n)
    a1 = a0 + rng.choice([0.0, 1e-9, 1.0, 1e3], n) * rng.uniform(-5.0, 5.0, n)
    x = np.linspace(0.0, 1.0, 21)[:, None] * h
    b = v0 ** 2 + 2.0 * a0 * x + (a1 - a0) / h * x * x
    keep = (b.min(axis=0) > 0.25 * v0 ** 2) & (b.max(axis=0) < 4.0 * v0 ** 2)
    v0, h, a0, a1 = v0[keep], h[keep], a0[keep], a1[keep]
    dt = slinear_time(v0 * v0, a0, a1, h, h)
    tau = rng.uniform(0.0, 1.0, v0.size) * dt
    return v0, a0, a1, h, tau


@pytest.mark.parametrize("seed", range(4))
def test_position_is_the_inverse_of_the_duration_integral(seed):
    v0, a0, a1, h, tau = _pieces(seed)
    assert v0.size > 300
    c = (a1 - a0) / h
    assert (c * tau * tau).max() > 0.5 and (c * tau * tau).min() < -0.5    # both branches
    x, v, acc, jerk = _slinear_at(v0, a0, a1, h, tau)
    want = _bisect_position(v0, a0, a1, h, tau)
    assert np.max(np.abs(x - want) / h) < 1e-12
    assert np.allclose(v * v, v0 * v0 + 2.0 * a0 * x + c * x * x, rtol=1e-12, atol=0.0)
    assert np.allclose(acc, a0 + c * x, rtol=1e-12, atol=1e-9)
    assert np.allclose(jerk, v * c, rtol=1e-12, atol=0.0)
