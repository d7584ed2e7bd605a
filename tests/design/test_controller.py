"""The optimal delayed controller G(z): the paper's formula, its proof, the IFP state space."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from helpers import random_plant
from hypothesis import given
from hypothesis import strategies as st

from symctl import (
    DiscreteTF,
    MuscleModel,
    Realization,
    augment,
    controller_tf,
    ifp_realization,
    lqr_gains,
    prove_controller_tf,
    z,
)
from symctl.design.controller import ifp_state_space
from symctl.symbols import gain_symbols


def test_T2_controller_is_the_papers_transfer_function():
    K0, K1, K2 = gain_symbols(2)
    G = controller_tf(2)
    assert sp.cancel(G.expr - K0 / (z**2 - K1 * z - K2)) == 0
    assert G.num == K0 and sp.expand(G.den - (z**2 - K1 * z - K2)) == 0
    assert G.relative_degree == 2
    assert G.latex() == r"\frac{K_{0}}{z^{2} - K_{1} z - K_{2}}"


@pytest.mark.parametrize("T", [0, 1, 3, 8, 20])
def test_general_T_controller_formula_and_relative_degree(T):
    K = gain_symbols(T)
    G = controller_tf(T)
    expected = K[0] / (z**T - sum(K[k] * z ** (T - k) for k in range(1, T + 1)))
    assert sp.cancel(G.expr - expected) == 0
    assert G.relative_degree == T
    assert [str(s) for s in G.free_symbols_sorted()] == [f"K_{k}" for k in range(T + 1)]


@pytest.mark.parametrize("ds, da", [(0, 0), (1, 1), (0, 3), (4, 2)])
def test_derivation_is_proved_against_the_augmented_matrices(ds, da):
    assert prove_controller_tf(augment(MuscleModel(), ds, da))


def test_mimo_controller_is_proved_and_has_relative_degree_T():
    aug = augment(([[1, 1], [0, 1]], [[0, 1], [1, 0]]), 1, 2)
    G = controller_tf(aug)
    assert G.shape == (2, 2)
    assert G.relative_degree == 3
    assert prove_controller_tf(aug)


def test_a_wrong_controller_is_not_proved():
    aug = augment(MuscleModel(), 1, 1)
    K0, K1, K2 = gain_symbols(2)
    wrong = DiscreteTF(K0, z**2 - K1 * z + K2)
    assert not prove_controller_tf(aug, wrong)


def _controller_impulse_by_simulation(aug, K, steps):
    """Drive the controller part of the augmented loop (mu = K chi) with x = impulse."""
    n, m, T = aug.n, aug.m, aug.T
    At, Bt = np.array(aug.A, float), np.array(aug.B, float)
    out = np.zeros((steps, m, n))
    for j in range(n):
        chain = np.zeros(T * m)
        for t in range(steps):
            x = np.zeros(n)
            x[j] = 1.0 if t == 0 else 0.0
            chi = np.concatenate([x, chain])
            mu = K @ chi
            out[t, :, j] = mu if T == 0 else chain[-m:]
            chain = (At @ chi + Bt @ mu)[n:]
    return out


@given(
    n=st.integers(1, 2),
    m=st.integers(1, 2),
    ds=st.integers(0, 4),
    da=st.integers(0, 4),
    seed=st.integers(0, 2**32 - 1),
)
def test_random_plants_G_impulse_response_equals_augmented_loop(n, m, ds, da, seed):
    rng = np.random.default_rng(seed)
    aug = augment(random_plant(rng, n, m), ds, da)
    g = lqr_gains(aug)
    G = controller_tf(g)
    T = ds + da
    assert G.relative_degree == T
    steps = T + 8
    np.testing.assert_allclose(
        G.impulse_response(steps), _controller_impulse_by_simulation(aug, g.K, steps), atol=1e-10
    )


@pytest.mark.parametrize("ds, da", [(1, 1), (0, 2), (3, 2)])
def test_closed_loop_with_G_equals_augmented_closed_loop(ds, da):
    aug = augment(MuscleModel(), ds, da)
    g = lqr_gains(aug)
    G = controller_tf(g)
    A, B = (float(v) for v in (aug.plant.A[0, 0], aug.plant.B[0, 0]))
    steps = 30
    h = G.impulse_response(steps)[:, 0, 0]
    # plant + convolution with G's impulse response, from delta_f(0) = 1
    x = np.zeros(steps + 1)
    x[0] = 1.0
    for t in range(steps):
        u = sum(h[k] * x[t - k] for k in range(t + 1))
        x[t + 1] = A * x[t] + B * u
    # augmented closed loop from chi(0) = e_1
    Acl = np.array(aug.A, float) + np.array(aug.B, float) @ g.K
    chi = np.zeros(aug.A.shape[0])
    chi[0] = 1.0
    traj = [chi[0]]
    for _ in range(steps):
        chi = Acl @ chi
        traj.append(chi[0])
    np.testing.assert_allclose(x, traj, atol=1e-12)
    # python-control: positive feedback of plant and G has the augmented characteristic
    # polynomial (compared by coefficients: the repeated poles at 0 are ill-conditioned)
    loop = control.ss(control.feedback(aug.plant.to_control(), G.to_control(), sign=1))
    np.testing.assert_allclose(np.poly(loop.A), np.poly(Acl), atol=1e-9)


def test_controller_tf_equal_by_value():
    assert controller_tf(2) == controller_tf(2)
    assert hash(controller_tf(3)) == hash(controller_tf(3))
    assert controller_tf(2) != controller_tf(3)


@pytest.mark.parametrize("ds, da", [(0, 0), (1, 1), (0, 2), (2, 1)])
def test_ifp_realization_realizes_the_numeric_controller(ds, da):
    gains = lqr_gains(augment(MuscleModel(), ds, da))
    R = ifp_realization(gains)
    assert isinstance(R, Realization) and R.n == ds + da
    G = controller_tf(gains)
    np.testing.assert_allclose(
        np.array([np.array(h, dtype=float) for h in R.markov(8)]),
        G.impulse_response(8),
        atol=1e-12,
    )


def test_proof_of_the_controller_is_a_result_with_its_evidence():
    aug = augment(MuscleModel(), 1, 1)
    proof = prove_controller_tf(aug)
    assert proof and proof == True and "polynomial identities" in proof.method  # noqa: E712
    refuted = prove_controller_tf(aug, 2 * controller_tf(aug))
    assert not refuted and refuted == False  # noqa: E712
    assert refuted.evidence and refuted.evidence != "0"


# ---------------------------------------------------------------- MIMO
def _generic_inverse_controller(T, m, n):
    """The earlier MIMO controller: SymPy's adjugate of D(z), expanded."""
    from symctl.symbols import gain_matrix_symbols

    blocks = gain_matrix_symbols(T, m, n)
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        D = D - blocks[k] * z ** (T - k)
    return (D.adjugate() * blocks[0]).applyfunc(sp.expand), sp.expand(D.det())


@pytest.mark.parametrize("n, m, ds, da", [(2, 2, 1, 1), (1, 3, 0, 1), (2, 3, 1, 0)])
def test_mimo_fraction_free_controller_equals_the_generic_inverse(n, m, ds, da):
    rng = np.random.default_rng(n + 10 * m)
    aug = augment(random_plant(rng, n, m), ds, da)
    G = controller_tf(aug)
    num, den = _generic_inverse_controller(aug.T, m, n)
    assert sp.expand(G.den - den) == 0
    assert all(sp.expand(a - b) == 0 for a, b in zip(G.num_matrix, num, strict=True))
    assert G.equals(num / den)
    assert G.relative_degree == aug.T
    assert prove_controller_tf(aug, G)


def test_mimo_ring_proof_rejects_a_wrong_controller():
    aug = augment(random_plant(np.random.default_rng(1), 2, 2), 1, 1)
    G = controller_tf(aug)
    wrong = DiscreteTF(G.num_matrix.subs(z, z + 1), G.den)
    proof = prove_controller_tf(aug, wrong)
    assert not proof and "Q[z, K]" in proof.method and proof.evidence
    assert not prove_controller_tf(aug, 2 * G)


@pytest.mark.parametrize("n, m, ds, da", [(3, 4, 1, 1), (2, 3, 1, 2), (3, 6, 1, 2)])
def test_mimo_numeric_controller_matches_the_state_space_of_python_control(n, m, ds, da):
    rng = np.random.default_rng(7 * m + n)
    aug = augment(random_plant(rng, n, m), ds, da)
    gains = lqr_gains(aug)
    G = controller_tf(gains)
    assert G.shape == (m, n) and G.relative_degree == aug.T
    F, H, M, N = ifp_state_space(
        np.array(aug.A, float), np.array(aug.B, float), gains.K, n, m, aug.T
    )
    ss = control.ss(F, H, M, N, True)
    for zk in (1.3 + 0.4j, -0.7 + 1.1j, 2.0):
        want = ss(zk)
        num = np.array(G.num_matrix.subs(z, zk).evalf(), dtype=complex)
        got = num / complex(G.den.subs(z, zk))
        assert np.allclose(got, want, rtol=1e-8, atol=1e-10)


def test_mimo_numeric_controller_equals_substituting_the_symbolic_one():
    aug = augment(random_plant(np.random.default_rng(3), 2, 2), 1, 1)
    gains = lqr_gains(aug)
    fast = controller_tf(gains)
    slow_num, slow_den = _generic_inverse_controller(aug.T, 2, 2)
    rule = gains.substitutions()
    slow_den = sp.Poly(slow_den.subs(rule), z).all_coeffs()
    assert np.allclose(np.array(fast.den_coeffs(), float), np.array(slow_den, float), atol=1e-12)
    for a, b in zip(fast.num_matrix, slow_num.subs(rule), strict=True):
        assert abs(float(sp.expand(a - b).subs(z, 0.9))) < 1e-12
