"""Design objects are values: equal by content, hashable, their insides read-only."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symctl import (
    DiscretePlant,
    MuscleModel,
    augment,
    controller_tf,
    factor,
    linearize,
    lqr_gains,
    random_realization,
)


def test_plants_systems_and_gains_equal_and_hash_by_value():
    a, b = MuscleModel(), MuscleModel()
    assert a == b and hash(a) == hash(b)
    assert a.plant() == b.plant() and hash(a.plant()) == hash(b.plant())
    sa, sb = augment(a.plant(), 1, 1), augment(b.plant(), 1, 1)
    assert sa == sb and hash(sa) == hash(sb)
    ga, gb = lqr_gains(sa), lqr_gains(sb)
    assert ga == gb and hash(ga) == hash(gb)
    assert ga != lqr_gains(augment(a.plant(), 1, 2))


def test_gain_arrays_are_read_only():
    g = lqr_gains(augment(MuscleModel(), 1, 1))
    for array in (g.K, g.X, g.poles):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0


def test_params_read_only():
    plant = DiscretePlant([[1]], [[1]], params={"tau": 0.02})
    with pytest.raises(TypeError):
        plant.params["tau"] = 1
    R = random_realization(factor(controller_tf(2)).G2, rng=0)
    with pytest.raises(TypeError):
        R.params["P"] = sp.eye(2)


def test_linearization_and_factorization_are_values():
    x, u = sp.symbols("x u")
    first = linearize([-(x**3) + u], [x], [u], [1], [1])
    second = linearize([-(x**3) + u], [x], [u], [1], [1])
    assert first == second and hash(first) == hash(second)
    assert factor(controller_tf(2)) == factor(controller_tf(2))
    assert hash(factor(controller_tf(2))) == hash(factor(controller_tf(2)))


def test_realizations_compare_by_matrices_not_by_their_records():
    G2 = factor(controller_tf(2)).G2
    R = random_realization(G2, rng=1)
    same = type(R)(R.F, R.H, R.M, R.N, R.dt)
    assert R == same and hash(R) == hash(same)
    assert R != random_realization(G2, rng=2)
    assert np.array_equal(np.array(R.F.shape), [2, 2])
