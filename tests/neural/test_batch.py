"""Batch simulation: many loops at once equal the single runs, in chunks, with Schur-Cohn stability."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from helpers import rel_err

import symctl.neural.batch as batch_module
from symctl import (
    MuscleModel,
    ParameterError,
    SymctlTypeError,
    augment,
    closed_loop_response,
    controllable_canonical,
    controller_tf,
    factor,
    lqr_gains,
    pulse,
    simulate_realization,
)
from symctl.neural.batch import _schur_stable, simulate_batch
from symctl.realization.realization import controller_realization
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3

MODEL = MuscleModel()
GAINS = lqr_gains(augment(MODEL, 1, 1))
REF = closed_loop_response(GAINS)
FACT = factor(controller_tf(2))
K_VALUES = GAINS.substitutions()


def test_batch_equals_single_runs_for_lambdified_realizations():
    a, b = sp.symbols("a b")
    P = sp.Matrix([[1, a], [b, 2]])
    f = FACT.subs({**K_VALUES, epsilon_1: sp.Rational(1, 3), epsilon_3: -sp.Rational(1, 2)})
    f = f.subs({C_1: 1, C_3: 2})
    R = controller_realization(f, controllable_canonical(f.G2).similar(P))
    gen = np.random.default_rng(3)
    av, bv = gen.uniform(-1, 1, 40), gen.uniform(3, 4, 40)  # det P = 2 - a b != 0
    F, H, M, N = R.lambdify([a, b])(av, bv)
    out = simulate_batch(MODEL, F, H, M, N, states=True)
    assert out.delta_f.shape == (40, 50, 1) and out.states.shape == (40, 50, 4)
    for i in (0, 17, 39):
        one = simulate_realization(MODEL, R.subs({a: av[i], b: bv[i]}))
        np.testing.assert_allclose(out.states[i], one.states, rtol=1e-9, atol=1e-12)
        assert rel_err(out.delta_r[i], REF.delta_r) < 1e-9
    assert np.max(np.abs(out.states[0] - out.states[1])) > 1e-4


def test_batch_accepts_one_disturbance_per_realization():
    F, H, M, N = (
        np.zeros((2, 1, 1)),
        np.full((2, 1, 1), -0.05),
        np.ones((2, 1, 1)),
        np.zeros((2, 1, 1)),
    )
    w = np.stack([pulse(30, 1.0), pulse(30, 2.0)])
    out = simulate_batch(MODEL, F, H, M, N, w)
    np.testing.assert_allclose(out.delta_f[1], 2 * out.delta_f[0], rtol=1e-12)


def test_batch_across_chunk_boundaries_equals_single_loops(monkeypatch):
    monkeypatch.setattr(batch_module, "_CHUNK", 64)  # the same code at a tenth of the cost
    monkeypatch.setattr(batch_module, "_MIN_CHUNK", 16)
    count = 2 * 64 + 3
    gain = np.linspace(-0.02, -0.08, count).reshape(count, 1, 1)
    F, H, M, N = np.zeros((count, 1, 1)), gain, np.ones((count, 1, 1)), np.zeros((count, 1, 1))
    scale = np.linspace(0.5, 2.0, count)
    w = scale[:, None, None] * pulse(12, 1.0)[None]
    out = simulate_batch(MODEL, F, H, M, N, w, states=True)
    parts = batch_module._chunks(count)
    assert len(parts) == 4
    for i in sorted({p.start for p in parts} | {p.stop - 1 for p in parts}):
        one = simulate_batch(
            MODEL, F[i : i + 1], H[i : i + 1], M[i : i + 1], N[i : i + 1], w[i][None]
        )
        np.testing.assert_allclose(out.delta_f[i], one.delta_f[0], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(out.delta_r[i], one.delta_r[0], rtol=1e-12, atol=1e-15)


def test_schur_cohn_agrees_with_eigenvalues():
    gen = np.random.default_rng(7)
    A = gen.normal(size=(3000, 5, 5)) * gen.uniform(0.1, 0.8, size=(3000, 1, 1))
    radii = np.max(np.abs(np.linalg.eigvals(A)), axis=-1)
    clear = np.abs(radii - 1) > 1e-6
    assert 100 < np.sum(radii < 1) < 2900
    stable = _schur_stable(np.moveaxis(A, 0, -1))  # stacks are realization-last
    np.testing.assert_array_equal(stable[clear], (radii < 1)[clear])


def test_schur_cohn_has_the_eigenvalue_paths_margin():
    # a marginal mode that rounds inside the unit circle is unstable on both paths
    A = np.array([[[1 - 1e-11]], [[1 - 1e-6]]])
    np.testing.assert_array_equal(_schur_stable(np.moveaxis(A, 0, -1)), [False, True])


def test_batch_refuses_an_unstable_loop_among_many():
    F = np.zeros((3000, 1, 1))
    H = np.full((3000, 1, 1), -0.05)
    H[1234] = -1.0
    with pytest.raises(ParameterError, match=r"unstable.*realization 1234 of 3000"):
        simulate_batch(MODEL, F, H, np.ones((3000, 1, 1)), np.zeros((3000, 1, 1)), steps=5)


def test_a_rate_that_overflows_while_the_state_stays_finite_is_refused(monkeypatch):
    monkeypatch.setattr(batch_module, "_CHUNK", 64)
    monkeypatch.setattr(batch_module, "_MIN_CHUNK", 16)
    # delta_r = -1e10 delta_f overflows during the pulse; the stable loop (pole -0.5)
    # has decayed to finite rates again by the last step.
    plant = (np.array([[0.5]]), np.array([[1e-10]]))
    zero = np.zeros((1, 1, 1))
    with pytest.raises(ParameterError, match="blew up at step 6"):
        simulate_batch(plant, zero, zero, zero, np.full((1, 1, 1), -1e10), 1e300)
    N = np.zeros((64 + 1, 1, 1))
    N[-1] = -1e10  # only the last loop, in the second chunk
    assert len(batch_module._chunks(65)) == 2
    zeros = np.zeros_like(N)
    with pytest.raises(ParameterError, match="blew up at step 6"):
        simulate_batch(plant, zeros, zeros, zeros, N, 1e300)


def test_a_run_whose_returned_values_are_finite_is_not_refused():
    # only the state after the horizon, which nobody sees, overflows
    plant = (np.array([[1e200]]), np.array([[1.0]]))
    zero = np.zeros((1, 1, 1))
    out = simulate_batch(plant, zero, zero, zero, zero, [1.0, 0.0, 0.0], check_stability=False)
    np.testing.assert_array_equal(out.delta_f[0, :, 0], [0.0, 1.0, 1e200])


def test_a_ragged_batch_disturbance_is_refused_by_name():
    with pytest.raises(SymctlTypeError, match="disturbance"):
        simulate_batch(MODEL, *(np.zeros((2, 1, 1)),) * 4, [[1.0], [1.0, 2.0]])


def test_batch_response_arrays_read_only():
    F, H, M, N = (
        np.zeros((2, 1, 1)),
        np.full((2, 1, 1), -0.05),
        np.ones((2, 1, 1)),
        np.zeros((2, 1, 1)),
    )
    out = simulate_batch(MODEL, F, H, M, N, states=True)
    for arr in (out.t, out.delta_f, out.delta_r, out.states):
        assert not arr.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        out.delta_r[0, 0, 0] = 1.0
    assert F.flags.writeable
