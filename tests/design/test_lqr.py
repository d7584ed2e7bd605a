"""Delayed LQR: paper's gains, cross-checks with SciPy and python-control, errors."""

from __future__ import annotations

import control
import numpy as np
import pytest
import scipy.linalg
import sympy as sp
from helpers import random_plant
from hypothesis import given
from hypothesis import strategies as st

from symctl import (
    MuscleModel,
    NotStabilizableError,
    ParameterError,
    SymctlTypeError,
    augment,
    lqr_gains,
)
from symctl.symbols import gain_symbols


def test_paper_reference_gains_and_poles():
    g = lqr_gains(augment(MuscleModel(), 1, 1))
    np.testing.assert_allclose(g.K[0], [-0.0459719, -0.580041, -0.351813], atol=5e-7)
    assert abs(g.poles[0] - 0.0265) < 1e-4
    assert np.all(np.abs(g.poles[1:]) < 1e-6)
    assert g.substitutions() == dict(zip(gain_symbols(2), g.K[0], strict=True))


def _paper_formulation_gain(aug):
    """Independent solve: the paper's cost diag(Q, 0.., R) with zero penalty on mu."""
    A, B = np.array(aug.A, float), np.array(aug.B, float)
    Q = np.array(aug.Q, float)
    R0 = np.zeros((aug.m, aug.m)) if aug.T else np.array(aug.R, float)
    X = scipy.linalg.solve_discrete_are(A, B, Q, R0)
    return -np.linalg.solve(R0 + B.T @ X @ B, B.T @ X @ A)


@pytest.mark.parametrize("ds, da", [(0, 0), (1, 0), (1, 1), (2, 1), (3, 3)])
def test_gains_equal_scipy_solve_of_the_papers_cost(ds, da):
    aug = augment(MuscleModel(), ds, da)
    np.testing.assert_allclose(
        lqr_gains(aug).K, _paper_formulation_gain(aug), rtol=1e-8, atol=1e-10
    )


@given(
    n=st.integers(1, 3),
    m=st.integers(1, 2),
    ds=st.integers(0, 4),
    da=st.integers(0, 4),
    seed=st.integers(0, 2**32 - 1),
)
def test_random_plants_closed_loop_stable_and_equal_to_control_dlqr(n, m, ds, da, seed):
    rng = np.random.default_rng(seed)
    A, B = random_plant(rng, n, m)
    A = A * 1.3  # some unstable plants too
    aug = augment((A, B), ds, da)
    g = lqr_gains(aug)
    At, Bt = np.array(aug.A, float), np.array(aug.B, float)
    assert np.max(np.abs(np.linalg.eigvals(At + Bt @ g.K))) < 1
    # python-control on the equivalent problem (penalty R on mu)
    Qeq = np.zeros_like(At)
    Qeq[:n, :n] = np.eye(n)
    K_ctrl, _, _ = control.dlqr(At, Bt, Qeq, np.eye(m))
    np.testing.assert_allclose(g.K, -K_ctrl, rtol=1e-6, atol=1e-8)


def test_unstabilizable_plant_is_reported():
    aug = augment(([[2, 0], [0, 0.5]], [[0], [1]]), 1, 1)
    with pytest.raises(NotStabilizableError, match="not stabilizable"):
        lqr_gains(aug)


def test_undetectable_cost_is_reported():
    aug = augment(([[1.5, 0], [0, 0.5]], [[1], [1]]), 1, 1, Q=[[0, 0], [0, 1]])
    with pytest.raises(NotStabilizableError, match="detectable"):
        lqr_gains(aug)


def test_symbolic_system_needs_numbers():
    with pytest.raises(ParameterError, match="free symbols"):
        lqr_gains(augment(MuscleModel().discrete_symbolic()))


def test_wrong_type_is_refused():
    with pytest.raises(SymctlTypeError, match="system"):
        lqr_gains((1, 2))


def test_override_penalties_are_checked():
    aug = augment(MuscleModel())
    with pytest.raises(ParameterError, match="R"):
        lqr_gains(aug, R=-1)
    heavier = lqr_gains(aug, R=100)
    assert abs(heavier.K[0, 0]) < abs(lqr_gains(aug).K[0, 0])


def test_gains_render_latex():
    assert "K =" in lqr_gains(augment(MuscleModel()))._repr_latex_()
    assert isinstance(sp.Matrix(lqr_gains(augment(MuscleModel())).K), sp.Matrix)
