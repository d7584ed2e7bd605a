"""Circuit.as_linear_system(numeric=True) computes in floats what the exact system gives."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symctl import Circuit, ParameterError, Structure, controller_tf, factor
from symctl.realization.realizers import REALIZERS


@pytest.mark.parametrize("kind", ["controllable", "observable", "general"])
@pytest.mark.parametrize("ds, da", [(1, 1), (2, 1), (2, 3)])
def test_numeric_system_equals_the_exact_one_in_floats(kind, ds, da):
    T = ds + da
    G = controller_tf(T).subs({f"K_{k}": sp.Rational(k + 1, 7 * (k + 2)) for k in range(T + 1)})
    eps = [sp.Rational(i + 1, 3 * T) - sp.Rational(1, 2) for i in range(T)]
    f = factor(G, ds, da, eps=eps, C=1)
    R2 = REALIZERS[kind](f.G2, rng=T).realization
    c = Circuit.from_structure(Structure.from_factorization(f, R2))
    exact, fast = c.as_linear_system(), c.as_linear_system(numeric=True)
    assert fast.states == exact.states and fast.outputs == exact.outputs
    for a, b in zip(fast[:4], exact[:4], strict=True):
        np.testing.assert_allclose(
            a, np.array(b.tolist(), dtype=float).reshape(b.shape), atol=1e-12
        )


def test_numeric_system_refuses_symbols():
    f = factor(controller_tf(2))
    c = Circuit.from_structure(
        Structure.from_factorization(f, REALIZERS["controllable"](f.G2).realization)
    )
    with pytest.raises(ParameterError, match="numeric: the weights still contain"):
        c.as_linear_system(numeric=True)
