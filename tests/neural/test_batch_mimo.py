"""simulate_batch with MIMO controllers: random G3 G2 G1 of a 2-input plant, the same loop each."""

from __future__ import annotations

import numpy as np
import pytest

from symctl import (
    augment,
    closed_loop_response,
    controllable_canonical,
    controller_tf,
    lqr_gains,
    simulate_batch,
    simulate_realization,
)
from symctl.realization.factorization import factor
from symctl.realization.realization import controller_realization

A = [[1, 0.01, 0, 0], [-0.4, 0.96, 0.005, -0.005], [0, 0, 0.6, 0], [0, 0, 0, 0.6]]
B = [[0, 0], [0.01, -0.01], [4.6, 0], [0, 4.6]]


@pytest.mark.slow
def test_a_batch_of_mimo_realizations_gives_each_ones_loop_and_the_optimal_behaviour():
    system = augment((A, B), 1, 1)
    gains = lqr_gains(system)
    G = controller_tf(gains)
    rng = np.random.default_rng(5)
    Rs = []
    for _ in range(3):
        f = factor(G, 1, 1, eps=list(rng.uniform(-0.9, 0.9, 6).round(4)), C=1)
        Rs.append(controller_realization(f, controllable_canonical(f.G2)))
    mats = [np.stack([np.asarray(R.numeric()[k], dtype=float) for R in Rs]) for k in range(4)]
    out = simulate_batch(system.plant, *mats, 1.0, steps=40)
    ref = closed_loop_response(gains, steps=40)
    for i, R in enumerate(Rs):
        one = simulate_realization(system.plant, R, 1.0, steps=40)
        np.testing.assert_allclose(out.delta_f[i], one.delta_f, atol=1e-12)
        np.testing.assert_allclose(out.delta_r[i], ref.delta_r, atol=1e-12)
    assert out.delta_r.shape == (3, 40, 2)
