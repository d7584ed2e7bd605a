"""MIMO factorization: one chain of sections per channel, G3 G2 G1 = G proved entry by entry."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import DimensionError, augment, controller_tf, lqr_gains
from symctl.realization.factorization import factor
from symctl.symbols import z


def _antagonist_like(ds: int = 1, da: int = 1):
    A = [[1, 0.01, 0, 0], [-0.4, 0.96, 0.005, -0.005], [0, 0, 0.6, 0], [0, 0, 0, 0.6]]
    B = [[0, 0], [0.01, -0.01], [4.6, 0], [0, 4.6]]
    return augment((A, B), ds, da)


def test_a_two_input_controller_factors_channel_by_channel():
    system = _antagonist_like()
    G = controller_tf(system)
    f = factor(G, 1, 1)
    assert f.channels == (4, 2) and not f.is_siso
    assert f.G2.shape == (2, 4) and f.G1.shape == (4, 4) and f.G3.shape == (2, 2)
    assert len(f.sensor_eps) == 4 and len(f.actuator_eps) == 2
    assert f.sensor_eps[2] == sp.Symbol("epsilon_{1,3,1}", real=True)
    assert bool(f.verify())
    # G1 and G3 are diagonal; their diagonals are the channels' sections
    for M, sections in ((f.G1, f.sensor_sections), (f.G3, f.actuator_sections)):
        k = M.shape[0]
        for i in range(k):
            for j in range(k):
                entry = sp.cancel(M.num_matrix[i, j] / M.den)
                want = sections[i].expr if i == j else 0
                assert sp.cancel(entry - want) == 0


def test_the_symbolic_factorization_proves_and_a_wrong_g2_is_refused():
    G = controller_tf(_antagonist_like())
    f = factor(G, 1, 1)
    assert f.verify().method.startswith("entry by entry")
    wrong = type(f)(
        f.G,
        f.G1,
        f.G2.subs({f.sensor_C[0]: 2 * f.sensor_C[0]}),
        f.G3,
        f.sensor_eps,
        f.sensor_C,
        f.actuator_eps,
        f.actuator_C,
        f.channels,
    )
    assert not wrong.verify()


def test_numbers_for_the_sections_agree_with_g_at_random_points():
    system = _antagonist_like()
    G = controller_tf(lqr_gains(system))
    rng = np.random.default_rng(3)
    f = factor(G, 1, 1, eps=list(rng.uniform(-0.9, 0.9, 6).round(3)), C=1)
    for point in (1.7 + 0.3j, -0.4 + 1.1j, 2.5):
        g1 = [complex(s.expr.subs(z, point)) for s in f.sensor_sections]
        g3 = [complex(s.expr.subs(z, point)) for s in f.actuator_sections]
        G2 = np.array(sp.Matrix(f.G2.expr).subs(z, point).evalf(), dtype=complex)
        Gz = np.array(sp.Matrix(G.expr).subs(z, point).evalf(), dtype=complex)
        np.testing.assert_allclose(np.diag(g3) @ G2 @ np.diag(g1), Gz, rtol=1e-9, atol=1e-12)


def test_the_siso_factorization_is_unchanged():
    f = factor(controller_tf(2))
    assert f.channels == (1, 1) and f.is_siso
    assert f.N == sp.Symbol("K_0", real=True) / (f.sensor_C[0] * f.actuator_C[0])
    assert f.remainder_coeffs[0] == sp.Symbol("K_1", real=True) - sum(f.poles)


def test_siso_only_forms_are_refused_for_mimo():
    f = factor(controller_tf(_antagonist_like()), 1, 1)
    with pytest.raises(DimensionError, match="SISO"):
        f.remainder_coeffs  # noqa: B018
    assert f.N.shape == (2, 4)


def test_eps_of_the_wrong_length_for_the_channels_is_refused():
    G = controller_tf(_antagonist_like())
    with pytest.raises(DimensionError, match="expected 6 values"):
        factor(G, 1, 1, eps=[0.1, 0.2])


@settings(max_examples=examples(25), deadline=None)
@given(st.integers(1, 3), st.integers(1, 3), st.integers(0, 2), st.integers(0, 2), st.data())
def test_random_mimo_controllers_factor_exactly(p, m, ds, da, data):
    order = ds + da + data.draw(st.integers(0, 2))
    if order == 0:
        order = 1
    ints = st.integers(-5, 5)
    den = z**order + sum(data.draw(ints) * z**k for k in range(order))
    top = order - ds - da  # numerator degree at most this
    num = sp.Matrix(p, m, lambda i, j: sum(data.draw(ints) * z**k for k in range(top + 1)))
    G = num / den
    f = factor(G, ds, da)
    assert f.channels == (m, p)
    assert bool(f.verify())


@pytest.mark.slow
@pytest.mark.parametrize("form", ["controllable", "observable"])
def test_block_canonical_forms_realize_a_mimo_g2_exactly(form):
    from symctl import check_realization, controllable_canonical, observable_canonical

    f = factor(controller_tf(_antagonist_like()), 1, 1)
    realize = controllable_canonical if form == "controllable" else observable_canonical
    R = realize(f.G2)
    p, m = f.G2.shape
    n = f.G2.order
    assert R.F.shape == ((n * m, n * m) if form == "controllable" else (n * p, n * p))
    assert R.H.shape[1] == m and R.M.shape[0] == p
    check = check_realization(R, f.G2)
    assert check.ok and check.method == "exact"
    assert sp.Matrix(R.N) == f.N
    # a wrong entry is caught
    wrong = R.subs({f.sensor_C[0]: 3})
    assert not check_realization(wrong, f.G2).ok


@pytest.mark.slow
@settings(max_examples=examples(20), deadline=None)
@given(st.integers(1, 3), st.integers(1, 3), st.integers(1, 3), st.data())
def test_block_forms_match_python_control_numerically(p, m, n, data):
    import control

    from symctl import controllable_canonical, observable_canonical

    rng = np.random.default_rng(data.draw(st.integers(0, 2**16)))
    den = np.poly(rng.uniform(-0.9, 0.9, n))
    num = rng.integers(-3, 4, size=(p, m, n + 1)).astype(float)
    G = sp.Matrix(
        p, m, lambda i, j: sum(sp.Rational(int(num[i, j, k])) * z ** (n - k) for k in range(n + 1))
    )
    G = G / sum(sp.Rational(c).limit_denominator(10**12) * z ** (n - k) for k, c in enumerate(den))
    for realize in (controllable_canonical, observable_canonical):
        R = realize(G)
        F, H, M, N = R.numeric()
        sys = control.ss(F, H, M, N, True)
        for point in (1.3 + 0.2j, -2.0):
            want = np.array(sp.Matrix(G).subs(z, point).evalf(), dtype=complex)
            got = sys(point)
            np.testing.assert_allclose(np.atleast_2d(got).reshape(p, m), want, rtol=1e-8, atol=1e-9)


def test_mimo_zeros_are_abbreviated_entry_by_entry_and_equal_G2_at_sigma():
    f = factor(controller_tf(_antagonist_like(2, 1)), 2, 1)
    a = f.abbreviated()
    assert len(f.sigma) == 2 * 4 * 3  # p * m entries, 3 sections each
    assert f.sigma_poles[sp.Symbol("sigma_{2,3,1}", real=True)] == (
        1,
        (*f.sensor_eps[4:6], f.actuator_eps[1]),
    )
    assert not a.free_symbols & set(f.poles)  # the zeros enter as sigma only
    assert a.subs(f.sigma_values()).equals(f.G2)
    assert f.G2_symbolic == f.G2  # 3 sections per entry: expanded


def test_beyond_expanded_zeros_max_G2_symbolic_is_abbreviated_with_few_terms():
    f = factor(controller_tf(augment(([[0.9, 0.1], [0, 0.8]], [[0], [0.1]]), 4, 4)), 4, 4)
    G2 = f.G2_symbolic
    assert G2 == f.abbreviated()
    # expanded, each entry's zeros have 2^8 monomials; abbreviated, 9 terms
    assert all(len(sp.Add.make_args(sp.expand(e))) == 9 for e in G2.num_matrix)
    assert all(len(sp.Add.make_args(sp.expand(e))) == 2**8 for e in f.G2.num_matrix)
