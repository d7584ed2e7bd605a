"""The MIMO controller as a left matrix fraction D(z)^-1 K_0 and its proof by multiplication."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from helpers import examples, random_plant
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    DiscreteTF,
    augment,
    controller_tf,
    lqr_gains,
    prove_controller_tf,
    z,
)
from symctl.design.controller import ifp_state_space
from symctl.design.fraction import MatrixFractionTF
from symctl.errors import DimensionError, ParameterError, ParseError, SymctlTypeError
from symctl.symbols import gain_matrix_symbols


def _chain(T: int, m: int, n: int) -> tuple[sp.Matrix, sp.Matrix]:
    """D(z) = z^T I - sum_k K_k z^(T-k) and K_0, written out here (not by controller_tf)."""
    blocks = gain_matrix_symbols(T, m, n)
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        D = D - blocks[k] * z ** (T - k)
    return D, blocks[0]


def _fraction(aug) -> MatrixFractionTF:
    D, K0 = _chain(aug.T, aug.m, aug.n)
    return MatrixFractionTF(D, K0, aug.plant.dt)


def _aug(n: int, m: int, ds: int, da: int, seed: int = 0):
    return augment(random_plant(np.random.default_rng(seed), n, m), ds, da)


SMALL = [(2, 2, 1, 1), (1, 3, 0, 1), (2, 3, 1, 0), (3, 2, 2, 1), (1, 2, 0, 0), (1, 3, 1, 1)]


# ---------------------------------------------------------------- the representation
@pytest.mark.parametrize("n, m, ds, da", SMALL)
def test_fraction_expands_to_the_expanded_controller_exactly(n, m, ds, da):
    aug = _aug(n, m, ds, da)
    F, G = _fraction(aug), controller_tf(aug)
    assert type(G) is DiscreteTF  # small: controller_tf still expands, as it always did
    assert F.expanded() == G  # structurally: the same num and den expressions
    D, K0 = _chain(aug.T, m, n)
    assert sp.expand(G.den - D.det()) == 0
    assert all(sp.expand(a - b) == 0 for a, b in zip(G.num_matrix, D.adjugate() * K0, strict=True))
    assert (F.shape, F.order, F.relative_degree) == (G.shape, G.order, G.relative_degree)
    assert F.free_symbols == G.free_symbols and F.equals(G) and G.equals(F)


@pytest.mark.parametrize("n, m, ds, da", SMALL)
def test_fraction_markov_parameters_equal_the_expanded_ones(n, m, ds, da):
    aug = _aug(n, m, ds, da)
    F, G = _fraction(aug), controller_tf(aug)
    for a, b in zip(F.markov(aug.T + 4), G.markov(aug.T + 4), strict=True):
        assert (a - b).applyfunc(sp.expand) == sp.zeros(*G.shape)


@pytest.mark.slow
def test_terms_bound_is_the_exact_size_for_symbolic_gains():
    aug = _aug(3, 4, 1, 1)
    F, G = _fraction(aug), controller_tf(aug)
    size = sum(len(sp.Add.make_args(sp.expand(e))) for e in (*G.num_matrix, G.den))
    assert F.terms_bound() == size == 633 + 3324


@pytest.mark.slow
def test_substituted_numbers_expand_to_the_numeric_controller():
    aug = _aug(3, 6, 1, 2, seed=5)
    gains = lqr_gains(aug)
    G = controller_tf(aug)
    assert isinstance(G, MatrixFractionTF) and not isinstance(
        controller_tf(gains), MatrixFractionTF
    )
    numeric = G.subs(gains.substitutions())
    assert isinstance(numeric, MatrixFractionTF) and not numeric.free_symbols
    assert numeric.expanded() == controller_tf(gains)  # both exact from the floats, rounded once
    assert G.subs(gains.substitutions()).expanded(max_terms=1) == numeric.expanded()  # numbers


def test_exact_substitution_commutes_with_expansion():
    aug = _aug(2, 2, 1, 1, seed=3)
    F, G = _fraction(aug), controller_tf(aug)
    rng = np.random.default_rng(0)
    values = {s: sp.Rational(int(rng.integers(-9, 10)), 7) for s in sorted(F.free_symbols, key=str)}
    assert F.subs(values).expanded().equals(G.subs(values))


def test_past_the_limit_controller_tf_returns_the_fraction_of_the_same_controller(monkeypatch):
    import symctl.design.controller as controller

    aug = _aug(2, 3, 1, 1)
    G = controller_tf(aug)
    monkeypatch.setattr(controller, "MAX_EXPANDED_TERMS", G.order)
    F = controller_tf(aug)
    assert isinstance(F, MatrixFractionTF) and F == _fraction(aug)
    assert F.expanded() == G and prove_controller_tf(aug, F) and prove_controller_tf(aug, G)


def test_a_large_fraction_refuses_to_expand_and_names_the_limit():
    aug = _aug(1, 6, 1, 2)
    G = controller_tf(aug)
    assert isinstance(G, MatrixFractionTF) and G.terms_bound() > 2 * 10**6
    assert (G.shape, G.order, G.relative_degree) == ((6, 1), 18, 3)
    assert G.D == _chain(3, 6, 1)[0] and G.N == gain_matrix_symbols(3, 6, 1)[0]
    with pytest.raises(ParameterError, match=r"max_terms.*G\.D and G\.N"):
        G.num  # noqa: B018
    with pytest.raises(ParameterError, match="max_terms"):
        G.expanded(max_terms=10**6)
    assert "^{-1}" in G.latex() and str(G).startswith("([[z**3")
    assert G.markov(4)[3] == G.N  # D^-1 K_0 = K_0 z^-3 + ...


def test_fractions_compare_by_value_and_never_equal_an_expanded_form():
    aug = _aug(2, 2, 1, 1)
    a, b = _fraction(aug), _fraction(aug)
    assert a == b and hash(a) == hash(b) and a != 2 * a
    assert a != a.expanded() and a.expanded() != a and a.equals(a.expanded())
    assert (2 * a).N == 2 * a.N and (a * 2) == (2 * a)


def test_fraction_arguments_are_checked_by_name():
    D, K0 = _chain(1, 2, 1)
    with pytest.raises(SymctlTypeError, match="D:"):
        MatrixFractionTF([[z]], K0)
    with pytest.raises(DimensionError, match="D:"):
        MatrixFractionTF(sp.Matrix([[z, 1]]), K0)
    with pytest.raises(DimensionError, match="N:"):
        MatrixFractionTF(D, sp.Matrix([[1]]))
    with pytest.raises(ParameterError, match="monic"):
        MatrixFractionTF(2 * D, K0)
    with pytest.raises(ParameterError, match="polynomial in z"):
        MatrixFractionTF(D, K0 / z)
    with pytest.raises(ParseError):
        MatrixFractionTF(D, K0).subs({"K_{0,11}": "__import__('os')"})


# ---------------------------------------------------------------- the proof
def test_the_six_input_controller_at_T3_is_proved_without_expanding():
    aug = _aug(3, 6, 1, 2)
    G = controller_tf(aug)
    proof = prove_controller_tf(aug, G)
    assert proof and "D_G = D, N_G = K_0" in proof.method and "Q[z, K]" in proof.method
    refuted = prove_controller_tf(aug, 2 * G)
    assert not refuted and refuted.evidence == "K_{0,11}"


def test_a_fraction_with_another_D_is_checked_after_expansion():
    aug = _aug(2, 2, 1, 1)
    F = _fraction(aug)
    assert prove_controller_tf(aug, F)
    U = sp.Matrix([[z, 1], [0, z]])  # the same G written as (U D)^-1 (U K_0), U D monic
    same = MatrixFractionTF(U * F.D, U * F.N)
    assert same.D != F.D and prove_controller_tf(aug, same)
    wrong = MatrixFractionTF(F.D.subs(z, z + 1), F.N)
    assert not prove_controller_tf(aug, wrong)


def test_a_controller_of_the_wrong_shape_is_refuted_by_name():
    aug = _aug(2, 3, 1, 1)
    proof = prove_controller_tf(aug, DiscreteTF(sp.eye(2), z**2))
    assert not proof and "shape" in proof.evidence


@settings(max_examples=examples(20))
@given(
    n=st.integers(1, 3),
    m=st.integers(1, 3),
    T=st.integers(0, 3),
    seed=st.integers(0, 2**32 - 1),
    where=st.integers(0, 10**6),
    bump=st.sampled_from([1, -1, 2]),
)
def test_random_plants_are_proved_and_a_perturbed_controller_is_not(n, m, T, seed, where, bump):
    aug = _aug(n, m, T // 2, T - T // 2, seed)
    G = controller_tf(aug)
    assert prove_controller_tf(aug, G)
    # one numerator entry changed by a constant: no longer the controller
    i, j = divmod(where % (m * n), n)
    num = sp.Matrix(G.num_matrix)
    num[i, j] += bump
    assert not prove_controller_tf(aug, DiscreteTF(num, G.den))
    if m > 1 and T > 0:  # and the fraction form: proved, and refuted when N or D moves
        F = _fraction(aug)
        assert prove_controller_tf(aug, F)
        N = sp.Matrix(F.N)
        N[i, j] += bump
        assert not prove_controller_tf(aug, MatrixFractionTF(F.D, N))
        D = sp.Matrix(F.D)
        D[i, (i + 1 + where) % m] += bump
        assert not prove_controller_tf(aug, MatrixFractionTF(D, F.N))


# ---------------------------------------------------------------- against python-control
@pytest.mark.slow
@pytest.mark.parametrize("n, m, ds, da", [(3, 4, 1, 1), (3, 6, 1, 2), (2, 3, 0, 3)])
def test_numeric_fraction_matches_the_lqr_controller_of_python_control(n, m, ds, da):
    """D^-1 K_0 of the symbolic fraction with LQR gains, solved numerically at a few points,
    equals the frequency response of the IFP state space of python-control, and so does the
    expanded numeric controller (its ss2tf)."""
    aug = _aug(n, m, ds, da, seed=11)
    gains = lqr_gains(aug)
    F = _fraction(aug).subs(gains.substitutions())
    A, B = np.array(aug.A, float), np.array(aug.B, float)
    ss = control.ss(*ifp_state_space(A, B, gains.K, n, m, aug.T), True)
    tf = control.ss2tf(ss)
    G = controller_tf(gains)
    for zk in (1.3 + 0.4j, -0.7 + 1.1j, 2.0):
        want = ss(zk)
        D = np.array(F.D.subs(z, zk).evalf(), dtype=complex)
        got = np.linalg.solve(D, np.array(F.N.evalf(), dtype=complex))
        assert np.allclose(got, want, rtol=1e-8, atol=1e-10)
        assert np.allclose(tf(zk), want, rtol=1e-6, atol=1e-8)
        num = np.array(G.num_matrix.subs(z, zk).evalf(), dtype=complex)
        assert np.allclose(num / complex(G.den.subs(z, zk)), want, rtol=1e-8, atol=1e-10)
