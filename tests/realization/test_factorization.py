"""G = G3 G2 G1: the paper's factors for T = 2, general delays, refusals."""

from __future__ import annotations

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from symctl import ParameterError, controller_tf, factor, z
from symctl.realization.factorization import section_symbols
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols

K0, K1, K2 = gain_symbols(2)


def zero(expr) -> bool:
    return sp.cancel(sp.together(expr)) == 0


def test_paper_factors_for_one_step_each_way():
    f = factor(controller_tf(2), sensor_delay=1, actuator_delay=1)
    assert zero(f.G1.expr - C_1 / (z - epsilon_1))
    assert zero(f.G3.expr - C_3 / (z - epsilon_3))
    paper_G2 = K0 / (C_1 * C_3) * (z**2 - (epsilon_1 + epsilon_3) * z + epsilon_1 * epsilon_3)
    assert zero(f.G2.expr - paper_G2 / (z**2 - K1 * z - K2))
    assert f.G2.relative_degree == 0
    assert f.verify()


def test_paper_split_of_G2_into_feedthrough_and_remainder():
    f = factor(controller_tf(2))
    assert f.N == K0 / (C_1 * C_3)
    assert f.remainder_coeffs == [K1 - epsilon_1 - epsilon_3, K2 + epsilon_1 * epsilon_3]
    paper = (
        f.N * ((K1 - epsilon_1 - epsilon_3) * z + K2 + epsilon_1 * epsilon_3) / (z**2 - K1 * z - K2)
    )
    assert zero(f.strictly_proper.expr - paper)
    assert zero(f.N + f.strictly_proper.expr - f.G2.expr)


def test_latex_reads_like_the_paper():
    text = factor(controller_tf(2)).latex()
    assert (
        r"\frac{K_{0}}{C_{1} C_{3}} \frac{z^{2} - \left(\epsilon_{1} + \epsilon_{3}\right) z"
        in text
    )
    assert r"G_1 = \frac{C_{1}}{z - \epsilon_{1}}" in text


@pytest.mark.slow
@given(ds=st.integers(0, 4), da=st.integers(0, 4), extra=st.integers(0, 2))
def test_any_delays_factor_exactly(ds, da, extra):
    G = controller_tf(ds + da + extra)
    f = factor(G, ds, da)
    assert f.verify()
    assert f.G1.relative_degree == ds and f.G3.relative_degree == da
    assert f.G2.relative_degree == extra
    assert len(f.sensor_eps) == ds and len(f.actuator_C) == da
    assert (f.N == 0) == (extra > 0)


def test_larger_delays_get_their_own_symbols():
    f = factor(controller_tf(5), 2, 3)
    assert f.sensor_eps == section_symbols(1, 2)[0]
    assert [str(s) for s in f.actuator_C] == ["C_{3,1}", "C_{3,2}", "C_{3,3}"]
    assert f.verify()


def test_factor_accepts_a_sympy_expression():
    f = factor(K0 / (z**2 - K1 * z - K2))
    assert f.verify() and f.N == K0 / (C_1 * C_3)


def test_refusals():
    with pytest.raises(ParameterError, match="relative degree 2"):
        factor(controller_tf(2), 2, 1)
    with pytest.raises(ParameterError, match="improper"):
        factor(z**2 / (z - 1), 0, 0)
    with pytest.raises(ParameterError, match="C"):
        factor(controller_tf(2)).subs({C_1: 0})
    with pytest.raises(ParameterError, match="C"):
        factor(controller_tf(2)).subs({C_3: 0})
    with pytest.raises(ParameterError, match="relative degree 1"):  # MIMO: the same rule
        factor(sp.Matrix([[1 / z, 1 / z]]))
    with pytest.raises(ParameterError, match="sensor_delay"):
        factor(controller_tf(2), -1, 1)


def test_numeric_values_substitute_through_all_factors():
    f = factor(controller_tf(2)).subs({epsilon_1: sp.Rational(1, 2), C_1: 2, C_3: 1})
    assert f.sensor_eps == (sp.Rational(1, 2),) and f.sensor_C == (2,)
    assert f.verify()
