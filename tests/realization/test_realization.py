"""Realizations: the paper's n = 2 matrices, any order, similarity, series, interop, numbers."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given
from hypothesis import strategies as st

from symctl import (
    DimensionError,
    ParameterError,
    Realization,
    check_realization,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    observable_canonical,
    random_realization,
    z,
)
from symctl.realization.realization import (
    controller_realization,
    first_order_realization,
    split_proper,
)
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols

K0, K1, K2 = gain_symbols(2)
N_PAPER = K0 / (C_1 * C_3)
G2 = factor(controller_tf(2)).G2


def same(a, b) -> bool:
    return (sp.Matrix(a) - sp.Matrix(b)).applyfunc(sp.cancel) == sp.zeros(*sp.Matrix(a).shape)


def test_controllable_canonical_is_the_papers():
    R = controllable_canonical(G2)
    assert R.F == sp.Matrix([[0, 1], [K2, K1]])
    assert R.H == sp.Matrix([0, 1])
    assert same(
        R.M, N_PAPER * sp.Matrix([[K2 + epsilon_1 * epsilon_3, K1 - epsilon_1 - epsilon_3]])
    )
    assert same(R.N, [[N_PAPER]])
    assert R.to_tf().equals(G2)


def test_observable_canonical_is_the_papers():
    R = observable_canonical(G2)
    assert R.F == sp.Matrix([[0, K2], [1, K1]])
    assert R.M == sp.Matrix([[0, 1]])
    assert same(R.H, N_PAPER * sp.Matrix([K2 + epsilon_1 * epsilon_3, K1 - epsilon_1 - epsilon_3]))
    assert R.to_tf().equals(G2)


def test_symbolic_similarity_keeps_the_transfer_function():
    P = sp.Matrix(2, 2, sp.symbols("p_11 p_12 p_21 p_22", real=True))
    R = general_realization(G2, P)
    assert R.to_tf().equals(G2)
    assert general_realization(G2, P, base="observable").to_tf().equals(G2)


def test_singular_P_is_refused():
    a = sp.Symbol("a")
    with pytest.raises(ParameterError, match="singular"):
        controllable_canonical(G2).similar([[1, 2], [2, 4]])
    with pytest.raises(ParameterError, match="singular"):
        controllable_canonical(G2).similar([[a, a], [1, 1]])
    with pytest.raises(DimensionError, match="P"):
        controllable_canonical(G2).similar([[1]])


def _random_tf(seed: int, n: int, strictly: bool = False):
    rng = np.random.default_rng(seed)
    coef = [sp.Rational(int(v), 7) for v in rng.integers(-20, 21, size=2 * n + 1)]
    den = z**n + sum(coef[i] * z**i for i in range(n))
    num = sum(coef[n + i] * z**i for i in range(n)) + (0 if strictly else coef[2 * n] * z**n)
    return num, den


@pytest.mark.slow
@given(
    n=st.integers(1, 6),
    seed=st.integers(0, 2**32 - 1),
    base=st.sampled_from(["controllable", "observable"]),
)
def test_every_constructor_realizes_random_G_of_order_1_to_6(n, seed, base):
    num, den = _random_tf(seed, n)
    assume(sp.degree(sp.gcd(num, den), z) == 0)  # a common root would lower the order
    G = num / den
    R = controllable_canonical(G) if base == "controllable" else observable_canonical(G)
    assert R.n == n and R.to_tf().equals(G)
    rng = np.random.default_rng(seed)
    P = sp.Matrix(n, n, lambda i, j: sp.Rational(int(rng.integers(-9, 10)), 4))
    P = P + 5 * sp.eye(n)  # diagonally dominant: full rank
    assert general_realization(G, P, base).to_tf().equals(G)
    # a perturbed realization realizes something else
    bad = Realization(R.F, R.H, R.M + sp.Matrix([[1] + [0] * (n - 1)]), R.N)
    assert not bad.to_tf().equals(G)


def test_random_realization_follows_the_papers_recipe_and_is_seeded():
    R = random_realization(G2, rng=7)
    assert set(R.params) == {epsilon_1, epsilon_3, "P"}
    assert all(-1 < R.params[e] < 1 for e in (epsilon_1, epsilon_3))
    assert R.params["P"].det() != 0
    chosen = {epsilon_1: R.params[epsilon_1], epsilon_3: R.params[epsilon_3]}
    assert R.to_tf().equals(G2.subs(chosen))
    again = random_realization(G2, rng=7)
    assert again.F == R.F and again.params == R.params
    assert random_realization(G2, rng=8).F != R.F


def test_minimality():
    assert controllable_canonical(G2).is_minimal()
    # a pole-zero cancellation makes the canonical realization non-minimal
    G = (z - sp.Rational(1, 2)) / ((z - sp.Rational(1, 2)) * (z + sp.Rational(1, 3)))
    R = controllable_canonical(
        sp.Mul(
            z - sp.Rational(1, 2),
            1 / sp.expand((z - sp.Rational(1, 2)) * (z + sp.Rational(1, 3))),
            evaluate=False,
        )
    )
    assert R.n == 1  # from_expr reduces to lowest terms ...
    big = Realization([[sp.Rational(1, 2), 0], [0, -sp.Rational(1, 3)]], [[1], [1]], [[0, 1]], 0)
    assert not big.is_minimal()  # ... a hand-made one is not
    assert big.to_tf().equals(DiscreteTF_from(G))


def DiscreteTF_from(expr):
    from symctl import DiscreteTF

    return DiscreteTF.from_expr(expr)


def test_split_proper():
    N, c, a = split_proper(G2)
    assert N == N_PAPER
    assert [sp.cancel(ci / N) for ci in c] == [
        K2 + epsilon_1 * epsilon_3,
        K1 - epsilon_1 - epsilon_3,
    ]
    assert a == [-K2, -K1]


def test_whole_controller_series_realizes_G():
    f = factor(controller_tf(2))
    for R2 in (controllable_canonical(f.G2), observable_canonical(f.G2)):
        R = controller_realization(f, R2)
        assert R.n == 4 and check_realization(R, f.G).ok
    f5 = factor(controller_tf(5), 2, 3)
    assert check_realization(controller_realization(f5, controllable_canonical(f5.G2)), f5.G).ok


@pytest.mark.slow
@given(
    ds=st.integers(0, 3),
    da=st.integers(0, 3),
    extra=st.integers(0, 1),
    seed=st.integers(0, 2**32 - 1),
    base=st.sampled_from(["controllable", "observable"]),
)
def test_random_delays_every_constructor_passes_the_checker_and_perturbed_fail(
    ds, da, extra, seed, base
):
    f = factor(controller_tf(ds + da + extra), ds, da)
    R2 = random_realization(f.G2, rng=seed, base=base)
    chosen = {k: v for k, v in R2.params.items() if k != "P"}
    G2 = f.G2.subs(chosen)
    assert check_realization(R2, G2).ok
    whole = controller_realization(f.subs(chosen), R2)
    assert check_realization(whole, f.G, method="randomized").ok
    bad = Realization(R2.F, R2.H, R2.M, R2.N + sp.Matrix([[1]]))
    result = check_realization(bad, G2)
    assert not result.ok and result.counterexample is not None


def test_first_order_sections():
    R = first_order_realization(epsilon_1, C_1)
    assert R.to_tf().equals(C_1 / (z - epsilon_1))
    assert (
        Realization.series(R, first_order_realization(epsilon_3, C_3))
        .to_tf()
        .equals(C_1 * C_3 / ((z - epsilon_1) * (z - epsilon_3)))
    )


def test_control_state_space_roundtrip_keeps_dt():
    f = factor(controller_tf(2)).subs({epsilon_1: 0.3, epsilon_3: -0.2, C_1: 1, C_3: 2})
    R = controllable_canonical(f.G2.subs({K0: -0.05, K1: -0.58, K2: -0.35}))
    R = Realization(R.F, R.H, R.M, R.N, dt=0.01)
    sys = R.to_control()
    assert isinstance(sys, control.StateSpace) and sys.dt == pytest.approx(0.01)
    back = Realization.from_control(sys)
    np.testing.assert_allclose(np.array(back.F, float), np.array(R.F, float))
    assert back.dt == pytest.approx(0.01)
    # python-control agrees on the transfer function
    tf = control.ss2tf(sys)
    np.testing.assert_allclose(tf.den[0][0], [float(c) for c in R.to_tf().den_coeffs()], atol=1e-12)


def test_realization_checks_shapes():
    with pytest.raises(DimensionError, match="F"):
        Realization([[1, 2]], [[1]], [[1]], 0)
    with pytest.raises(DimensionError, match="H"):
        Realization([[1]], [[1], [2]], [[1]], 0)
    with pytest.raises(DimensionError, match="M"):
        Realization([[1]], [[1]], [[1, 2]], 0)


def test_lambdify_vectorizes_over_1e5_parameter_sets_and_matches_sympy():
    R = controllable_canonical(G2.subs({K0: -0.046, K1: -0.58, K2: -0.352, C_1: 1, C_3: 1}))
    f = R.lambdify([epsilon_1, epsilon_3])
    rng = np.random.default_rng(0)
    e1, e3 = rng.uniform(-1, 1, size=(2, 100_000))
    F, _H, M, N = f(e1, e3)
    assert F.shape == (100_000, 2, 2) and M.shape == (100_000, 1, 2) and N.shape == (100_000, 1, 1)
    for k in rng.integers(0, 100_000, size=20):
        exact = R.subs({epsilon_1: e1[k], epsilon_3: e3[k]})
        np.testing.assert_allclose(M[k], np.array(exact.M.evalf(), float), rtol=1e-12)
        np.testing.assert_allclose(N[k], np.array(exact.N.evalf(), float), rtol=1e-12)
    # the transfer function too
    g = G2.lambdify([K0, K1, K2, epsilon_1, epsilon_3, C_1, C_3])
    zs = np.exp(0.3j) * np.ones(100_000)
    vals = g(zs, -0.046, -0.58, -0.352, e1, e3, 1.0, 2.0)
    k = 123
    want = complex(
        G2.expr.subs(
            {
                z: np.exp(0.3j),
                K0: -0.046,
                K1: -0.58,
                K2: -0.352,
                epsilon_1: e1[k],
                epsilon_3: e3[k],
                C_1: 1,
                C_3: 2,
            }
        )
    )
    assert abs(vals[k] - want) <= 1e-12 * abs(want)


def test_realizations_render_latex():
    assert "F =" in controllable_canonical(G2)._repr_latex_()
