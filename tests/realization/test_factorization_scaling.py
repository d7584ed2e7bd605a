"""Factors built at given section values, the abbreviated G2 and the cancelling proof."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    DimensionError,
    ParameterError,
    ParseError,
    controllable_canonical,
    controller_tf,
    factor,
    observable_canonical,
    z,
)
from symctl.realization.check import check_realization
from symctl.realization.factorization import (
    Factorization,
    _products_equal,
    section_symbols,
    sigma_symbols,
)
from symctl.realization.realizers import random_full_rank

rationals = st.fractions(min_value=-2, max_value=2, max_denominator=50).map(sp.Rational)


@given(st.integers(0, 3), st.integers(0, 3), st.data())
@settings(max_examples=examples(30), deadline=None)
def test_factor_at_values_equals_substituting_the_symbols(ds, da, data):
    T = ds + da
    G = controller_tf(max(T, 1))
    eps = data.draw(st.lists(rationals, min_size=T, max_size=T))
    C = data.draw(st.lists(rationals.filter(bool), min_size=T, max_size=T))
    built = factor(G, ds, da, eps=eps, C=C)
    sym = factor(G, ds, da)
    symbols = (*sym.sensor_eps, *sym.actuator_eps, *sym.sensor_C, *sym.actuator_C)
    substituted = sym.subs(dict(zip(symbols, [*eps, *C], strict=True)))
    for a, b in zip(
        (built.G1, built.G2, built.G3),
        (substituted.G1, substituted.G2, substituted.G3),
        strict=True,
    ):
        assert a.equals(b)
    assert built.poles == tuple(eps)
    assert built.verify()


def test_factor_values_checked():
    G = controller_tf(2)
    with pytest.raises(DimensionError, match="eps: expected 2 values"):
        factor(G, eps=[1, 2, 3])
    with pytest.raises(ParameterError, match="C: the section gains"):
        factor(G, C=[1, 0])
    with pytest.raises(ParameterError, match=r"eps\[0\]: a section value cannot depend on z"):
        factor(G, eps=[z, 1])
    with pytest.raises(ParseError, match=r"eps\[0\]: function '__import__' is not allowed"):
        factor(G, eps="__import__('os')")
    assert factor(G, eps="1/2").poles == (sp.Rational(1, 2),) * 2


@pytest.mark.parametrize("ds, da", [(1, 1), (2, 1), (0, 3), (2, 3)])
def test_abbreviated_G2_at_sigma_values_is_G2(ds, da):
    f = factor(controller_tf(ds + da), ds, da)
    assert f.sigma == sigma_symbols(ds + da)
    G2a = f.abbreviated()
    assert not G2a.free_symbols & set(f.poles)
    assert G2a.subs(f.sigma_values()).equals(f.G2)  # Vieta: symbolic and exact
    # a realization of the abbreviated form realizes G2 at sigma = e(eps)
    R = controllable_canonical(G2a)
    assert check_realization(R, G2a)
    assert check_realization(R.subs(f.sigma_values()), f.G2)


def test_sigma_values_numeric_are_the_polynomial_coefficients():
    f = factor(controller_tf(4), 2, 2)
    values = dict(zip(f.poles, map(sp.Rational, ["1/2", "-1/3", "2/7", "0"]), strict=True))
    sig = f.sigma_values(values)
    coeffs = sp.Poly(sp.Mul(*(z - v for v in values.values())), z).all_coeffs()
    assert [sig[s] * (-1) ** k for k, s in enumerate(f.sigma, start=1)] == coeffs[1:]
    # floats fall back to SymPy and agree with numpy's polynomial
    fl = f.sigma_values({p: 0.25 * (i + 1) for i, p in enumerate(f.poles)})
    np.testing.assert_allclose(
        [float(fl[s]) * (-1) ** k for k, s in enumerate(f.sigma, start=1)],
        np.poly([0.25, 0.5, 0.75, 1.0])[1:],
    )


@pytest.mark.slow
def test_abbreviated_realizations_stay_small_at_T_20():
    f = factor(controller_tf(20), 10, 10)
    G2a = f.abbreviated()
    for R in (controllable_canonical(G2a), observable_canonical(G2a)):
        assert max(len(sp.Add.make_args(sp.expand(e))) for e in R.M) <= 3
    assert f.verify()


def test_products_equal_cancels_and_still_refuses_a_wrong_identity():
    a, b, c = sp.symbols("a b c")
    assert _products_equal([(z - a) * (z - b), c], [c, z**2 - (a + b) * z + a * b])
    assert not _products_equal([(z - a) * (z - b), c], [c, z**2 - (a + b) * z - a * b])
    assert _products_equal([a / c, c**2], [a * c])
    assert not _products_equal([a / c], [a * c])
    f = factor(controller_tf(6), 3, 3)
    wrong = Factorization(f.G, f.G1, f.G2, f.G1, *(f.sensor_eps, f.sensor_C) * 2)
    assert not wrong.verify()
    eps1 = section_symbols(1, 3)[0]
    assert f.sensor_eps == eps1


@pytest.mark.parametrize("n", [1, 2, 3, 8, 20])
def test_random_full_rank_is_conditioned_at_any_order(n):
    P = np.array(random_full_rank(n, rng=n), dtype=float)
    assert np.linalg.cond(P) < max(10, 5 * n)
