"""Delay augmentation: the paper's T = 2 matrices and the general chain."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from helpers import random_plant
from hypothesis import given
from hypothesis import strategies as st

from symctl import DimensionError, MuscleModel, ParameterError, SymctlTypeError, augment


def test_T2_scalar_gives_the_papers_augmented_system():
    A, B, Q, R = sp.symbols("A B Q R")
    aug = augment(([[A]], [[B]]), sensor_delay=1, actuator_delay=1, Q=Q, R=R)
    assert aug.A == sp.Matrix([[A, 0, B], [0, 0, 0], [0, 1, 0]])
    assert aug.B == sp.Matrix([0, 1, 0])
    assert aug.Q == sp.diag(Q, 0, R)
    assert aug.state_names == ("x", "gamma", "u")
    assert aug.T == 2


def test_muscle_state_is_delta_f_gamma_delta_r():
    aug = augment(MuscleModel(), 1, 1)
    assert aug.state_names == ("delta_f", "gamma", "delta_r")


def test_T0_is_the_plant_itself():
    aug = augment(([[2, 1], [0, 1]], [[0], [1]]), 0, 0)
    assert aug.A == sp.Matrix([[2, 1], [0, 1]])
    assert aug.B == sp.Matrix([0, 1])
    assert aug.Q == sp.eye(2)
    assert aug.R_mu == sp.eye(1)


@given(
    n=st.integers(1, 3),
    m=st.integers(1, 2),
    ds=st.integers(0, 4),
    da=st.integers(0, 4),
    seed=st.integers(0, 2**32 - 1),
)
def test_chain_delays_mu_by_T_steps(n, m, ds, da, seed):
    rng = np.random.default_rng(seed)
    A, B = random_plant(rng, n, m)
    aug = augment((A, B), ds, da)
    T = ds + da
    At, Bt = np.array(aug.A, float), np.array(aug.B, float)
    assert At.shape == (n + T * m, n + T * m) and Bt.shape == (n + T * m, m)
    steps = T + 6
    mu = rng.normal(size=(steps, m))
    chi = np.zeros(n + T * m)
    chi[:n] = rng.normal(size=n)
    x = chi[:n].copy()
    for t in range(steps):
        # the plant input is mu delayed by T steps (zero before the first arrival)
        u = mu[t - T] if t >= T else np.zeros(m)
        if T:
            np.testing.assert_allclose(chi[n + (T - 1) * m :], u, atol=1e-12)
        else:
            u = mu[t]
        x = A @ x + B @ u
        chi = At @ chi + Bt @ mu[t]
        np.testing.assert_allclose(chi[:n], x, atol=1e-9)
    Qt = np.array(aug.Q, float)
    assert np.allclose(Qt[:n, :n], np.eye(n))
    if T:
        assert np.allclose(Qt[-m:, -m:], np.eye(m))
        assert np.allclose(Qt[n:-m, :], 0)


@pytest.mark.parametrize("name", ["sensor_delay", "actuator_delay"])
def test_delays_must_be_non_negative_integers(name):
    with pytest.raises(ParameterError, match=f"{name}: must be an integer >= 0"):
        augment(MuscleModel(), **{name: -1})
    for bad in (1.5, True, "1"):  # a wrong type is the type error
        with pytest.raises(SymctlTypeError, match=f"{name}: expected an integer"):
            augment(MuscleModel(), **{name: bad})


def test_penalties_are_checked():
    with pytest.raises(DimensionError, match="Q"):
        augment(MuscleModel(), Q=[[1, 0], [0, 1]])
    with pytest.raises(DimensionError, match="R"):
        augment(MuscleModel(), R=[[1, 0], [0, 1]])
    with pytest.raises(ParameterError, match="Q"):
        augment(MuscleModel(), Q=-1)
    with pytest.raises(ParameterError, match="R"):
        augment(([[1, 0], [0, 1]], [[1, 0], [0, 1]]), R=[[1, 2], [2, 1]])
    with pytest.raises(ParameterError, match="Q"):
        augment(([[1, 0], [0, 1]], [[1], [0]]), Q=[[1, 1], [0, 1]])


def test_plant_type_is_checked():
    with pytest.raises(SymctlTypeError, match="plant"):
        augment("muscle")


def test_augmented_system_renders_latex():
    text = augment(MuscleModel().discrete_symbolic())._repr_latex_()
    assert r"\tilde A" in text and r"\gamma" in text
